"""Lab data in, as labs have it (issue 14): spreadsheets, exports, locale, units, unused columns, one round of
problems, checked options, physical limits, raw shear and triaxial curves, sample state."""

import io
import json

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.errors import CapredError, InputError
from capred.io.grid import TableSource
from capred.pipelines.shear_curves import corrected_area

runner = CliRunner()
HEADER = "test_id,material,condition,sigma_N [kPa],tau_max [kPa],suction [kPa],S_R,R [mm]\n"
DRY = (
    "d1,m,dry,1,1.0452,,,1\nd2,m,dry,2,1.7598,,,1\nd3,m,dry,3,2.4744,,,1\nd4,m,dry,4,3.189,,,1\nd5,m,dry,5,3.9036,,,1\n"
)
WET = "w1,m,wet,1,1.5,2,0.3,1\nw2,m,wet,2,2.2,2,0.3,1\n"


def _xlsx(path, rows, title="Tests"):
    from openpyxl import Workbook

    wb = Workbook()
    ws = wb.active
    ws.title = title
    for r in rows:
        ws.append(r)
    wb.save(path)
    return path


def _materials(source, **kw):
    return capred.run_shear(source, capred.ShearOptions(bootstrap=0, **kw)).to_json()["materials"]


# --- spreadsheets --------------------------------------------------------------------------------
def test_xlsx_export_gives_the_same_fits_as_the_csv():
    a = _materials(capred.sample_path("shear-export"))
    b = _materials(capred.sample_path("shear"))
    assert a == b
    doc = capred.run_shear(capred.sample_path("shear-export"), capred.ShearOptions(bootstrap=0)).to_json()
    assert doc["inputs"][0]["sheet"] == "Direct shear"
    assert doc["inputs"][0]["metadata"]["Apparatus"] == "60 mm shear box"


def test_xlsx_problems_name_sheet_row_and_column(tmp_path):
    rows = [
        ["Lab", "x"],
        [],
        ["test_id", "condition", "sigma_N [kPa]", "tau_max [kPa]"],
        ["a", "dry", 1, 1.0],
        ["b", "dry", "two", 1.7],
        ["c", "dry", 3, 2.4],
    ]
    path = _xlsx(tmp_path / "t.xlsx", rows, "Run 2")
    with pytest.raises(InputError) as info:
        capred.run_shear(path)
    p = info.value.problems[0]
    # the spreadsheet's own row number (5), the sheet named
    assert (p.sheet, p.line, p.column, p.value) == ("Run 2", 5, "sigma_N [kPa]", "two")
    assert "sheet 'Run 2', line 5, column 'sigma_N [kPa]'" in str(info.value)


def test_sheet_by_name_and_number(tmp_path):
    from openpyxl import Workbook

    wb = Workbook()
    wb.active.title = "notes"
    wb.active.append(["nothing here"])
    ws = wb.create_sheet("data")
    for r in [
        ["test_id", "condition", "sigma_N [kPa]", "tau_max [kPa]"],
        ["a", "dry", 1, 1.0452],
        ["b", "dry", 2, 1.7598],
        ["c", "dry", 3, 2.4744],
    ]:
        ws.append(r)
    wb.save(tmp_path / "w.xlsx")
    for sheet in ("data", 2, "2"):
        m = _materials(TableSource(tmp_path / "w.xlsx", sheet=sheet))
        assert m["(all)"]["tan_phi"] == pytest.approx(0.7146, rel=1e-9)
    res = runner.invoke(app, ["shear", str(tmp_path / "w.xlsx"), "--sheet", "nope", "--no-plots"])
    assert res.exit_code == 1 and "no sheet named 'nope'" in res.stderr and "data" in res.stderr
    res = runner.invoke(
        app, ["shear", str(tmp_path / "w.xlsx"), "--sheet", "data", "--no-plots", "--bootstrap", "0", "--json"]
    )
    assert res.exit_code == 0, res.output


def test_ods_with_metadata_block(tmp_path):
    frame = pd.DataFrame(
        [
            ["Operator", "me", None, None],
            [None, None, None, None],
            ["test_id", "condition", "sigma_N [kPa]", "tau_max [kPa]"],
            ["a", "dry", 1.0, 1.0452],
            ["b", "dry", 2.0, 1.7598],
            ["c", "dry", 3.0, 2.4744],
        ]
    )
    frame.to_excel(tmp_path / "t.ods", engine="odf", header=False, index=False)
    doc = capred.run_shear(tmp_path / "t.ods", capred.ShearOptions(bootstrap=0)).to_json()
    assert doc["materials"]["(all)"]["tan_phi"] == pytest.approx(0.7146, rel=1e-9)
    assert doc["inputs"][0]["metadata"] == {"Operator": "me"}
    assert [t["line"] for t in doc["tests"]] == [4, 5, 6]  # the spreadsheet's row numbers


@pytest.mark.parametrize(
    "magic,what",
    [
        (b"PK\x03\x04rest", "zip archive"),
        (b"\xd0\xcf\x11\xe0rest", ".xls"),
        (b"%PDF-1.4", "PDF"),
        (b"ab\x00cd" * 10, "binary"),
    ],
)
def test_binary_named_csv_is_named(tmp_path, magic, what):
    (tmp_path / "t.csv").write_bytes(magic)
    res = runner.invoke(app, ["shear", str(tmp_path / "t.csv"), "--no-plots"])
    assert res.exit_code == 1 and what in res.stderr and "Traceback" not in res.output


# --- exports: metadata block and units row ----------------------------------------------------------
def test_metadata_block_and_units_row(tmp_path):
    text = (
        "Instrument: ShearBox 3000\nOperator,Jane\n\n"
        "test_id,condition,sigma_N,tau_max\n,,kPa,(Pa)\n"
        "a,dry,1,1045.2\nb,dry,2,1759.8\nc,dry,3,2474.4\n"
    )
    (tmp_path / "e.csv").write_text(text)
    doc = capred.run_shear(tmp_path / "e.csv", capred.ShearOptions(bootstrap=0)).to_json()
    assert doc["materials"]["(all)"]["tan_phi"] == pytest.approx(0.7146, rel=1e-9)
    assert doc["inputs"][0]["metadata"] == {"Instrument": "ShearBox 3000", "Operator": "Jane"}
    assert [t["line"] for t in doc["tests"]] == [6, 7, 8]


def test_european_sample_runs_as_the_csv():
    assert _materials(capred.sample_path("shear-eu")) == _materials(capred.sample_path("shear"))


# --- locale and plain numbers -----------------------------------------------------------------------
def test_thousands_separator_is_an_error_unless_told(tmp_path):
    text = (
        "test_id;condition;added_mass [g];cap_mass [g];box_area [cm^2];tau_max [kPa]\n"
        "a;dry;1.000;120;36;0,5\nb;dry;0;120;36;0,35\nc;dry;2.000;120;36;0,9\n"
    )
    (tmp_path / "eu.csv").write_text(text)
    with pytest.raises(InputError) as info:
        capred.run_shear(tmp_path / "eu.csv")
    msgs = [(p.line, p.column) for p in info.value.problems]
    assert (2, "added_mass [g]") in msgs and (4, "added_mass [g]") in msgs
    assert "--thousands ." in str(info.value)
    res = capred.run_shear(TableSource(tmp_path / "eu.csv", thousands="."), capred.ShearOptions(bootstrap=0))
    sig = [t["sigma_N_kPa"] for t in res.to_json()["tests"]]
    # (1000 + 120) g * 9.81 / 36 cm^2 = 3.052 kPa: the dots were thousands separators
    assert sig[0] == pytest.approx(1.120 * 9.81 / 36e-4 / 1e3, rel=1e-12)


@pytest.mark.parametrize("cell", ["1_000", "١٢", "1e5x", "0x1F", "inf", "½"])
def test_only_plain_decimal_numbers(tmp_path, cell):
    (tmp_path / "t.csv").write_text(f"test_id,condition,sigma_N,tau_max\na,dry,{cell},1\nb,dry,2,1\nc,dry,3,2\n")
    with pytest.raises(InputError) as info:
        capred.run_shear(tmp_path / "t.csv")
    assert any(p.line == 2 and p.column == "sigma_N" and p.value == cell for p in info.value.problems)


def test_quoted_field_over_two_lines(tmp_path):
    text = (
        "test_id,condition,sigma_N [kPa],tau_max [kPa],notes\n"
        'a,dry,1,1.0452,"first line\nsecond line"\nb,dry,2,x,ok\nc,dry,3,2.4744,\n'
    )
    (tmp_path / "t.csv").write_text(text)
    with pytest.raises(InputError) as info:
        capred.run_shear(tmp_path / "t.csv")
    # b starts on line 4 of the file (the quoted field of a spans lines 2-3)
    assert [(p.line, p.column) for p in info.value.problems] == [(4, "tau_max [kPa]")]


# --- units, safely ---------------------------------------------------------------------------------
@pytest.mark.parametrize("unit", ["1/0", "((((kPa", "kPa # x", "$kPa", "{kPa}", "m" + "*m" * 3000, "k" * 100_000])
def test_bad_unit_strings_are_named_problems(tmp_path, unit):
    (tmp_path / "t.csv").write_text(f"test_id,condition,sigma_N [{unit}],tau_max\na,dry,1,1\nb,dry,2,2\nc,dry,3,3\n")
    with pytest.raises(InputError) as info:
        capred.run_shear(tmp_path / "t.csv")
    # a header of 100,000 characters is longer than any cell (max_cell_chars): refused before its unit is read
    assert any(p.line == 1 and ("unit" in p.message or "(max_cell_chars)" in p.message) for p in info.value.problems)


@pytest.mark.parametrize(
    "header,value,si",
    [
        ("suction [cmH2O]", "10", 980.665),
        ("suction [cm H2O]", "10", 980.665),
        ("suction [cm water]", "10", 980.665),
        ("suction [mH2O]", "1", 9806.65),
        ("suction [kgf/cm^2]", "0.01", 980.665),
        ("suction [psi]", "1", 6894.757293),
    ],
)
def test_lab_spellings_of_units(tmp_path, header, value, si):
    (tmp_path / "t.csv").write_text(
        HEADER.replace("suction [kPa]", header) + DRY + WET.replace(",2,0.3", f",{value},0.3")
    )
    doc = capred.run_shear(tmp_path / "t.csv", capred.ShearOptions(bootstrap=0)).to_json()
    wet = [t for t in doc["tests"] if t["condition"] == "wet"]
    assert wet[0]["suction_kPa"] == pytest.approx(si / 1e3, rel=1e-9)


def test_head_in_cm_of_water_and_percent_and_micrometres(tmp_path):
    text = (
        "test_id,condition,sigma_N [kPa],tau_max [kPa],z1 [cm H2O],S_R [%],R [um]\n"
        "d1,dry,1,1.0452,,,\nd2,dry,2,1.7598,,,\nd3,dry,3,2.4744,,,\nw1,wet,1,1.5,20,30,156\n"
    )
    (tmp_path / "t.csv").write_text(text)
    w = capred.run_shear(tmp_path / "t.csv", capred.ShearOptions(bootstrap=0)).to_json()["tests"][3]
    assert w["suction_kPa"] == pytest.approx(0.2 * 9.81, rel=1e-12) and w["S_R"] == pytest.approx(0.3)


@pytest.mark.parametrize(
    "header,cell,name,si",
    [
        ("V_v [cm³]", "27", "V_v", 27e-6),
        ("V_v [m³]", "2.7e-5", "V_v", 2.7e-5),
        ("V_v_mm³", "27000", "V_v", 27e-6),
        ("box_area [cm²]", "36", "box_area", 36e-4),
        ("box_area [mm²]", "3600", "box_area", 36e-4),
        ("box_area (m²)", "0.0036", "box_area", 36e-4),
        ("rho_d [g/cm³]", "1.65", "rho_d", 1650.0),
    ],
)
def test_superscript_units_in_headers(tmp_path, header, cell, name, si):
    """Units as Excel users type them (issue 23): cm³ = 1e-6 m³, cm² = 1e-4 m², g/cm³ = 1000 kg/m³."""
    from capred.io.table import read_table
    from capred.pipelines.shear import SCHEMA

    (tmp_path / "t.csv").write_text(f"test_id,condition,tau_max,{header}\na,dry,1,{cell}\n", encoding="utf-8")
    t = read_table(tmp_path / "t.csv", SCHEMA)
    assert not t.problems
    assert_allclose(t.columns[name], [si], rtol=1e-12)  # one decimal scaling: exact to rounding


def test_superscript_units_row_is_a_units_row(tmp_path):
    """A units row with cm³ and cm² is read as units, not as a data row (it gave 10 misleading errors)."""
    from capred.io.table import read_table
    from capred.pipelines.shear import SCHEMA

    text = (
        "test_id,condition,z1,z2,V_v,added_mass,cap_mass,box_area,R,tau_max\n"
        "-,-,cm,cm³,cm³,g,g,cm²,mm,kPa\n"
        "w1,wet,20,5,27,1000,120,36,0.5,2.2\n"
    )
    (tmp_path / "t.csv").write_text(text, encoding="utf-8")
    t = read_table(tmp_path / "t.csv", SCHEMA)
    assert not t.problems and list(t.lines) == [3]
    assert t.units["z2"] == "cm³" and t.units["box_area"] == "cm²"
    assert_allclose([t.columns["V_v"][0], t.columns["box_area"][0]], [27e-6, 36e-4], rtol=1e-12)
    # one unit nobody knows is named, on the units row, and the row is still a units row
    (tmp_path / "u.csv").write_text(text.replace("cm²", "blorp²"), encoding="utf-8")
    t = read_table(tmp_path / "u.csv", SCHEMA)
    assert [(p.line, p.column) for p in t.problems] == [(2, "box_area")] and list(t.lines) == [3]


@pytest.mark.parametrize("kind", ["csv", "xlsx"])
def test_text_under_the_data_is_a_note(tmp_path, kind):
    """'Remarks: ...' under the data (first cell only) is reported as a note, not read as a test (issue 23)."""
    rows = [
        ["test_id", "condition", "sigma_N [kPa]", "tau_max [kPa]"],
        ["a", "dry", 1, 1.0452],
        ["b", "dry", 2, 1.7598],
        ["c", "dry", 3, 2.4744],
        ["Remarks: sample b disturbed", None, None, None],
        ["checked by the operator", None, None, None],
    ]
    if kind == "xlsx":
        path = _xlsx(tmp_path / "t.xlsx", rows)
    else:
        path = tmp_path / "t.csv"  # as Excel saves it: the empty cells kept as trailing commas
        path.write_text("\n".join(",".join("" if c is None else str(c) for c in r) for r in rows) + "\n")
    doc = capred.run_shear(path, capred.ShearOptions(bootstrap=0)).to_json()
    assert [t["line"] for t in doc["tests"]] == [2, 3, 4]
    assert "note under the data (line 5): Remarks: sample b disturbed" in doc["notes"]
    assert "note under the data (line 6): checked by the operator" in doc["notes"]
    assert doc["materials"]["(all)"]["tan_phi"] == pytest.approx(0.7146, rel=1e-9)  # the sample's 3 tests


def test_a_test_id_alone_is_still_a_row(tmp_path):
    (tmp_path / "t.csv").write_text("test_id,condition,sigma_N,tau_max\na,dry,1,1\nb,dry,2,2\nd4,,,\n")
    with pytest.raises(InputError) as info:
        capred.run_shear(tmp_path / "t.csv")
    assert any(p.line == 4 for p in info.value.problems)  # an incomplete test, not a note


# --- unused columns --------------------------------------------------------------------------------
def test_unused_columns_are_warned_with_a_suggestion(tmp_path):
    text = (
        "test_id,Materiaal,condition,sigma_N [kPa],tau_max [kPa],,remarks\n"
        "a,m1,dry,1,1.0452,7,x\nb,m1,dry,2,1.7598,,\nc,m2,dry,3,2.4744,,\n"
    )
    (tmp_path / "t.csv").write_text(text)
    # 'Materiaal' is a near miss of 'material', which groups the tests: an error (issue 23), not a warning
    with pytest.raises(InputError) as info:
        capred.run_shear(tmp_path / "t.csv", capred.ShearOptions(bootstrap=0))
    (p,) = info.value.problems
    assert (p.line, p.column) == (1, "Materiaal") and "'material'" in p.message and "--ignore-column" in p.message
    # ignored as asked, the others are warnings as before
    source = TableSource(tmp_path / "t.csv", ignore_columns=("Materiaal",))
    doc = capred.run_shear(source, capred.ShearOptions(bootstrap=0)).to_json()
    assert any("column 6 has data but no header" in w for w in doc["warnings"])
    assert any("'remarks' is not used" in w for w in doc["warnings"])
    assert not any("Materiaal" in w for w in doc["warnings"])
    (tmp_path / "t.csv").write_text(text.replace("Materiaal", "Mat. type"))  # three edits from 'material'
    doc = capred.run_shear(tmp_path / "t.csv", capred.ShearOptions(bootstrap=0)).to_json()
    assert any("'Mat. type' is not used" in w for w in doc["warnings"])  # a warning, as before


def _decisive_near_misses() -> list[tuple[str, str, str]]:
    """(command, header, column) for every decisive column of 5 characters or more of every command of the registry
    that reads a table (capred.reductions.REDUCTIONS, through the schema its --help shows: a new command is tested
    without editing this file): the name with its 2nd and 3rd letters swapped, one transposition away."""
    from capred.cli.help import schema_of
    from capred.reductions import REDUCTIONS

    return [
        (command, c.name[0] + c.name[2] + c.name[1] + c.name[3:], c.name)
        for command in REDUCTIONS
        for c in schema_of(command)
        if c.is_decisive and len(c.name) >= 5 and c.name[1] != c.name[2]
    ]


@pytest.mark.parametrize(
    "command,header,column",
    [
        ("shear", "Conditon", "condition"),
        ("shear", "tset_id", "test_id"),
        ("shear", "Materials", "material"),
        ("shear", "Radious [mm]", "R"),
        ("triaxial-bounds", "grup", "group"),
        ("retention", "Brnach", "branch"),
        ("retention", "weigth", "weight"),
        ("bridge solve", "Radios", "R"),
        *_decisive_near_misses(),
    ],
)
def test_near_miss_of_a_decisive_column_is_an_error_in_every_schema(tmp_path, command, header, column):
    from capred.cli.help import schema_of
    from capred.io.table import read_table

    schema = schema_of(command)
    (tmp_path / "t.csv").write_text(f"x,{header}\n1,2\n")
    (p,) = read_table(tmp_path / "t.csv", schema).problems
    assert (p.line, p.column) == (1, header) and f"close to '{column}'" in p.message
    t = read_table(TableSource(tmp_path / "t.csv", ignore_columns=(header,)), schema)
    assert not t.problems and f"column '{header}' ignored, as asked" in t.notes


def test_every_command_reading_a_table_has_its_decisive_columns_checked():
    """The registry's commands that read a table with a decisive column of 5 characters or more are all in the
    test above (shear, triaxial-bounds and retention today), so that the derivation cannot silently yield none."""
    assert {"shear", "triaxial-bounds", "retention"} <= {command for command, _, _ in _decisive_near_misses()}


@pytest.mark.parametrize(
    "command,header",
    [
        ("triaxial-bounds", "Stage"),
        ("shear", "soils"),
        ("shear", "Remark"),
        ("shear", "test"),
        ("retention", "weights_old_2"),
    ],
)
def test_far_or_short_names_stay_warnings(tmp_path, command, header):
    """'Stage' is one edit from the alias 'state' (of condition), but short aliases are too near everyday words."""
    from capred.cli.help import schema_of
    from capred.io.table import read_table

    (tmp_path / "t.csv").write_text(f"x,{header}\n1,2\n")
    t = read_table(tmp_path / "t.csv", schema_of(command))
    assert not [p for p in t.problems if "close to" in p.message]


def test_ignore_columns_drops_a_known_column_and_names_absent_ones(tmp_path):
    from capred.io.table import read_table
    from capred.pipelines.shear import SCHEMA

    (tmp_path / "t.csv").write_text("test_id,material,condition,sigma_N,tau_max\na,m,dry,1,1\n")
    t = read_table(tmp_path / "t.csv", SCHEMA, ignore_columns=("Material", "nope"))
    assert "material" not in t.columns and "column 'material' ignored, as asked" in t.notes
    assert "ignore_columns: the header has no column 'nope'" in t.warnings


def test_header_with_unbalanced_brackets_is_a_problem(tmp_path):
    (tmp_path / "t.csv").write_text("test_id,condition,sigma_N [kPa)],tau_max\na,dry,1,1\nb,dry,2,2\nc,dry,3,3\n")
    with pytest.raises(InputError) as info:
        capred.run_shear(tmp_path / "t.csv")
    assert any("brackets do not match" in p.message for p in info.value.problems)


# --- one round of problems ---------------------------------------------------------------------------
def test_all_problems_in_one_round(tmp_path):
    """60 bad cells in one pass: every one in the JSON; the console shows the same problem in many cells of a
    column as one line (issue 29, item 6)."""
    rows = "".join(f"t{k},dry,x{k},-1\n" for k in range(30))
    (tmp_path / "t.csv").write_text("test_id,condition,sigma_N [kPa],tau_max [kPa]\n" + rows)
    res = runner.invoke(app, ["shear", str(tmp_path / "t.csv"), "--no-plots"])
    assert res.exit_code == 1
    assert "60 problems" in res.stderr and res.stderr.count("  - ") == 2
    assert "30 cells are not numbers (lines 2, 3, 4, 5, 6, ...: 'x0', 'x1', 'x2', 'x3', 'x4')" in res.stderr
    assert "must not be negative (got -1 kPa) (in 30 lines: 2, 3, 4, 5, 6, ...)" in res.stderr
    res = runner.invoke(app, ["shear", str(tmp_path / "t.csv"), "--no-plots", "--json"])
    assert res.exit_code == 1
    errors = json.loads(res.stdout)["errors"]
    assert len(errors) == 60
    assert errors[0] == {
        "file": str(tmp_path / "t.csv"),
        "sheet": None,
        "line": 2,
        "column": "sigma_N [kPa]",
        "value": "x0",
        "message": "'x0' is not a number",
    }


def test_missing_column_and_bad_cells_reported_together(tmp_path):
    (tmp_path / "t.csv").write_text("test_id,condition,sigma_N [kPa]\na,dry,1\nb,dry,zwei\nc,dry,3\n")
    with pytest.raises(InputError) as info:
        capred.run_shear(tmp_path / "t.csv")
    texts = [p.message for p in info.value.problems]
    assert any("missing column 'tau_max'" in t for t in texts) and any("'zwei' is not a number" in t for t in texts)
    assert len(texts) == 2  # no per-row echo of the missing column


# --- options checked like columns --------------------------------------------------------------------
@pytest.mark.parametrize(
    "args,message",
    [
        (["shear", "--sample", "--box-area", "-36"], "box area must be > 0"),
        (["shear", "--sample", "--gamma-w", "0"], "unit weight of water must be > 0"),
        (["shear", "--sample", "--radius", "0"], "particle radius must be > 0"),
        (["skempton-b", "--sr", "1.5"], "degree of saturation must lie between 0 and 1"),
        (
            ["rumpf", "--shape-factor", "1", "--void-ratio", "0.5", "--sr", "2", "--diameter", "0.2"],
            "degree of saturation must lie between 0 and 1",
        ),
        (["prism", "--break-tension", "-5", "--friction-angle", "30"], "break tension of a sand prism must be > 0"),
        (["shear", "--sample", "--box-area", "36 kPa"], "not a unit of area"),
    ],
)
def test_options_are_checked_like_columns(args, message, tmp_path):
    res = runner.invoke(app, [*args, "--out", str(tmp_path / "o")])
    assert res.exit_code == 1 and message in res.stderr, res.output
    assert not (tmp_path / "o").exists()


# --- physics limits and plausibility -----------------------------------------------------------------
def test_hanging_column_above_cavitation_is_an_error(tmp_path):
    text = (
        "test_id,condition,sigma_N [kPa],tau_max [kPa],z1 [m],S_R,R [mm]\n"
        "d1,dry,1,1.0452,,,\nd2,dry,2,1.7598,,,\nd3,dry,3,2.4744,,,\nw1,wet,1,1.5,50,0.3,1\nw2,wet,1,1.5,9,0.3,1\n"
    )
    (tmp_path / "t.csv").write_text(text)
    with pytest.raises(InputError) as info:
        capred.run_shear(tmp_path / "t.csv")
    (p,) = info.value.problems
    # (101325 - 2339) Pa / 9810 N/m^3 = 10.09 m
    assert p.line == 5 and "cavitate" in p.message and "10.1 m" in p.message and "'suction'" in p.message


def test_implausible_dry_fit_warns(tmp_path):
    text = "test_id,condition,sigma_N [kPa],tau_max [kPa]\na,dry,1,0.2\nb,dry,2,0.25\nc,dry,3,0.35\n"
    (tmp_path / "t.csv").write_text(text)
    w = capred.run_shear(tmp_path / "t.csv", capred.ShearOptions(bootstrap=0)).to_json()["warnings"]
    assert any("outside the usual 15-60°" in x for x in w) and any("fewer than 5" in x for x in w)


# --- raw direct-shear curves -------------------------------------------------------------------------
def test_area_corrections_by_hand():
    A = 36e-4  # 60 mm square box
    assert corrected_area(A, 6e-3, "square") == pytest.approx(0.06 * 0.054, rel=1e-12)
    # circular box: the overlap of two discs of radius r offset by d (lens area), computed independently
    D = np.sqrt(4 * A / np.pi)
    r, d = D / 2, 5e-3
    lens = 2 * r**2 * np.arccos(d / (2 * r)) - d / 2 * np.sqrt(4 * r**2 - d**2)
    assert corrected_area(A, d, "circular") == pytest.approx(lens, rel=1e-12)
    assert corrected_area(A, 0.0, "circular") == pytest.approx(A, rel=1e-12)
    assert corrected_area(A, 1e-3, "none") == A


def test_curves_give_the_peaks_residual_and_dilatancy():
    doc = capred.run_shear(
        capred.sample_path("shear"), capred.ShearOptions(bootstrap=0, curves=capred.sample_path("shear-curves"))
    ).to_json()
    plain = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0)).to_json()
    by_id = {t["test_id"]: t for t in plain["tests"]}
    steel = [t for t in doc["tests"] if t["material"] == "steel_2mm"]
    for t in steel:
        assert t["tau_max_kPa"] == pytest.approx(by_id[t["test_id"]]["tau_max_kPa"], rel=1e-5)  # 6 digits in file
        assert t["displacement_at_peak_mm"] == 1.5
        # last 10 % of 0-6 mm: 5.5, 5.75, 6.0 mm, all at 85 % of the peak
        assert t["tau_residual_kPa"] == pytest.approx(0.85 * t["tau_max_kPa"], rel=1e-5)
        # v = -0.02 d + 0.012 d^2 -> dv/dh at 1.5 mm = -0.02 + 0.036 = 0.016 (central difference is exact)
        assert t["dilatancy_angle_deg"] == pytest.approx(np.degrees(np.arctan(0.016)), rel=1e-6)
    assert all(t.get("displacement_at_peak_mm") is None for t in doc["tests"] if t["material"] != "steel_2mm")
    assert not any("differs by more than 1 %" in w for w in doc["warnings"])


def test_curves_replace_a_missing_tau_and_warn_on_a_difference(tmp_path):
    (tmp_path / "t.csv").write_text(
        "test_id,condition,sigma_N [kPa],box_area [cm^2],tau_max [kPa]\n"
        "a,dry,1,36,\nb,dry,2,36,1.7598\nc,dry,3,36,2.6\n"
    )
    lines = ["test_id,displacement [mm],F [N]"]
    for tid, tau in (("a", 1.0452), ("b", 1.7598), ("c", 2.4744)):
        for d, s in ((0, 0), (1, 0.8), (2, 1.0), (3, 0.9)):
            lines.append(f"{tid},{d},{tau * 1e3 * 36e-4 * s!r}")
    (tmp_path / "c.csv").write_text("\n".join(lines) + "\n")
    res = runner.invoke(
        app, ["shear", str(tmp_path / "t.csv"), "--curves", str(tmp_path / "c.csv"), "--json", "--bootstrap", "0"]
    )
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["materials"]["(all)"]["tan_phi"] == pytest.approx(0.7146, rel=1e-9)
    assert any("test 'c'" in w and "differs by more than 1 %" in w for w in doc["warnings"])
    res = runner.invoke(
        app,
        [
            "shear",
            str(tmp_path / "t.csv"),
            "--curves",
            str(tmp_path / "c.csv"),
            "--json",
            "--bootstrap",
            "0",
            "--area-correction",
            "square",
        ],
    )
    doc2 = json.loads(res.stdout)
    # at the peak (2 mm of 60 mm) the square area is 60 x 58 mm^2: tau higher by 60/58
    assert doc2["tests"][1]["tau_max_kPa"] == pytest.approx(1.7598 * 60 / 58, rel=1e-9)


# --- triaxial instrument exports -------------------------------------------------------------------
def test_triaxial_exports_from_a_folder_equal_the_long_curves(tmp_path):
    tests = pd.read_csv(capred.sample_path("triaxial-bounds"), comment="#")
    tests.loc[tests["condition"] == "unsaturated", "q_f [kPa]"] = np.nan  # the curves must supply the peaks
    long = capred.run_triaxial_bounds(tests, curves=capred.sample_path("triaxial-curves")).to_json()
    folder = capred.run_triaxial_bounds(tests, curves=capred.sample_path("triaxial-export")).to_json()
    qa = {t["test_id"]: t["q_kPa"] for t in long["tests"]}
    qb = {t["test_id"]: t["q_kPa"] for t in folder["tests"]}
    for tid in qa:
        # UNSAT-0 comes from the axial force through A = A0 (1 - eps_v)/(1 - eps_a): 9 digits in the file
        assert qb[tid] == pytest.approx(qa[tid], rel=1e-8)
    assert any("A0 (1 - eps_v)/(1 - eps_a)" in n for n in folder["notes"])
    glob_ = capred.run_triaxial_bounds(tests, curves=str(capred.sample_path("triaxial-export") / "UNSAT-*.csv"))
    assert {t["test_id"]: t["q_kPa"] for t in glob_.to_json()["tests"]} == qb


def test_triaxial_force_without_diameter_is_an_error(tmp_path):
    src = capred.sample_path("triaxial-export") / "UNSAT-0.csv"
    text = "\n".join(ln for ln in src.read_text().splitlines() if not ln.startswith("Initial diameter"))
    (tmp_path / "UNSAT-0.csv").write_text(text + "\n")
    tests = pd.read_csv(capred.sample_path("triaxial-bounds"), comment="#")
    tests.loc[tests["test_id"] == "UNSAT-0", "q_f [kPa]"] = np.nan
    with pytest.raises(InputError, match="initial diameter"):
        capred.run_triaxial_bounds(tests, curves=tmp_path / "UNSAT-0.csv")
    tests["D0 [mm]"] = 38.0  # the tests table may give it
    assert capred.run_triaxial_bounds(tests, curves=tmp_path / "UNSAT-0.csv").to_json()["tests"][4]["q_kPa"] > 0


# --- sample state ------------------------------------------------------------------------------------
def test_void_volume_from_void_ratio_or_dry_density(tmp_path):
    base = (
        "test_id,condition,sigma_N [kPa],tau_max [kPa],suction [kPa],z2 [cm^3],R [mm],box_area [cm^2],"
        "height [mm],{extra}\nd1,dry,1,1.0452,,,1,36,20,{v}\nd2,dry,2,1.7598,,,1,36,20,{v}\n"
        "d3,dry,3,2.4744,,,1,36,20,{v}\nw1,wet,1,1.5,2,10,1,36,20,{v}\n"
    )
    (tmp_path / "e.csv").write_text(base.format(extra="e", v="0.6"))
    w = capred.run_shear(tmp_path / "e.csv", capred.ShearOptions(bootstrap=0)).to_json()["tests"][3]
    v_v = 36 * 2.0 * 0.6 / 1.6  # cm^3 = A h e / (1 + e) = 27 cm^3
    assert w["S_R"] == pytest.approx((v_v - 10) / v_v, rel=1e-12)
    # rho_d = G_s rho_w/(1 + e) = 2.65 * 1000 / 1.6 gives the same e = 0.6
    (tmp_path / "r.csv").write_text(base.format(extra="rho_d [kg/m^3],G_s", v=f"{2650 / 1.6!r},2.65"))
    w2 = capred.run_shear(tmp_path / "r.csv", capred.ShearOptions(bootstrap=0)).to_json()["tests"][3]
    assert w2["S_R"] == pytest.approx(w["S_R"], rel=1e-12)


# --- fuzzing the new paths ---------------------------------------------------------------------------
CELL = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(-(10**9), 10**9),
    st.none(),
    st.text(max_size=6),
    st.sampled_from(["1.000", "0,5", "kPa", "(g)", "-", "[cm]", "1_0"]),
)
HEAD = st.sampled_from(
    [
        "test_id",
        "condition",
        "sigma_N",
        "tau_max [kPa]",
        "z1 [cm]",
        "S_R",
        "Materiaal",
        "",
        "suction [1/0]",
        "R [um]",
        "tau [kPa # x]",
        "Key: value",
    ]
)
SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


@pytest.mark.slow
@SETTINGS
@given(
    meta=st.lists(st.lists(CELL, max_size=3), max_size=3),
    header=st.lists(HEAD, min_size=1, max_size=6),
    units=st.booleans(),
    rows=st.lists(st.lists(CELL, max_size=7), max_size=5),
    kind=st.sampled_from(["xlsx", "ods", "csv"]),
)
def test_fuzzed_workbooks_read_or_explain(tmp_path, meta, header, units, rows, kind):
    grid = [*meta, header] + ([["kPa", "(g)", "-", "cm", "%", "um"][: len(header)]] if units else []) + rows
    if kind == "xlsx":
        from openpyxl import Workbook

        wb = Workbook()
        path = tmp_path / "f.xlsx"
        try:
            for r in grid:
                wb.active.append(r)
            wb.save(path)
        except Exception:  # openpyxl refuses some characters: not a capred input
            return
    elif kind == "ods":
        width = max((len(r) for r in grid), default=1) or 1
        frame = pd.DataFrame([list(r) + [None] * (width - len(r)) for r in grid] or [[None]])
        path = tmp_path / "f.ods"
        try:
            frame.to_excel(path, engine="odf", header=False, index=False)
        except Exception:
            return
    else:
        buf = io.StringIO()
        for r in grid:
            buf.write(
                ",".join(
                    '"' + str(c).replace('"', '""') + '"'
                    if isinstance(c, str) and ("," in c or "\n" in c)
                    else ("" if c is None else str(c))
                    for c in r
                )
                + "\n"
            )
        path = tmp_path / "f.csv"
        path.write_text(buf.getvalue())
    for run in (capred.run_shear, capred.run_triaxial_bounds, capred.run_retention):
        try:
            run(path)
        except CapredError as exc:
            assert str(exc)


@SETTINGS
@given(data=st.binary(min_size=0, max_size=400))
def test_random_bytes_as_a_workbook_read_or_explain(tmp_path, data):
    for name in ("r.xlsx", "r.ods"):
        (tmp_path / name).write_bytes(b"PK\x03\x04" + data)
        try:
            capred.run_shear(tmp_path / name)
        except CapredError as exc:
            assert str(exc)


@SETTINGS
@given(unit=st.text(max_size=80))
def test_fuzzed_unit_strings_never_crash(unit):
    import math

    from capred.errors import UnitError
    from capred.units import conversion

    for kind in ("pressure", "length", "dimensionless"):
        try:
            factor = conversion(unit, kind)[0]
        except UnitError as exc:
            assert str(exc)  # a message, not a traceback
        else:  # a unit that is read converts by a finite, positive factor
            assert math.isfinite(factor) and factor > 0, (unit, kind, factor)


def test_long_plain_csv_names_the_line_of_a_bad_cell_past_the_first_rows(tmp_path):
    """Rows after the first 200 lines are split as whole columns (issue 13's speed); their messages still name
    the spreadsheet line, and a ragged or blank line falls back to row-by-row reading."""
    from capred.io.table import read_table
    from capred.pipelines.bridge import SOLVE_SCHEMA

    rows = [f"{1 + k % 7},{k % 30},0.{k % 9},1.5" for k in range(5000)]
    good = "R,contact_angle,gap,suction\n" + "\n".join(rows) + "\n"
    (tmp_path / "ok.csv").write_text(good)
    t = read_table(tmp_path / "ok.csv", SOLVE_SCHEMA)
    assert t.lines[0] == 2 and t.lines[-1] == 5001 and len(t.lines) == 5000
    assert t.columns["R"][4999] == pytest.approx((1 + 4999 % 7) * 1e-3)  # mm -> m
    bad = rows.copy()
    bad[3998] = "1,0,abc,1.5"  # spreadsheet line 4000
    (tmp_path / "bad.csv").write_text("R,contact_angle,gap,suction\n" + "\n".join(bad) + "\n")
    t = read_table(tmp_path / "bad.csv", SOLVE_SCHEMA)
    assert any(p.line == 4000 and "'abc' is not a number" in p.message for p in t.problems)
    ragged = rows.copy()
    ragged[2998] = "1,0,0.1,1.5,7"  # line 3000: one field too many
    (tmp_path / "ragged.csv").write_text("R,contact_angle,gap,suction\n" + "\n".join(ragged) + "\n")
    t = read_table(tmp_path / "ragged.csv", SOLVE_SCHEMA)
    assert any(p.line == 3000 and "5 fields" in p.message for p in t.problems)
    assert len(t.lines) == 5000 and t.lines[-1] == 5001
    assert t.columns["gap"][4999] == pytest.approx(float(f"0.{4999 % 9}") * 1e-3)
    ragged.insert(4000, "")  # and a blank line too
    (tmp_path / "blank.csv").write_text("R,contact_angle,gap,suction\n" + "\n".join(ragged) + "\n")
    t = read_table(tmp_path / "blank.csv", SOLVE_SCHEMA)
    assert any(p.line == 3000 and "5 fields" in p.message for p in t.problems)
    assert len(t.lines) == 5000 and t.lines[-1] == 5002
