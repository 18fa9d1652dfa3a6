"""Console tables (issue 21, item 3): folded tables keep their row labels, headers wrap before a table folds,
numbers that are 0 within the computation's rounding print 0."""

import pytest
from rich.cells import cell_len
from rich.console import Console

import capred
from capred.report import render
from capred.report.presenters import console_tables
from capred.result import TableSpec


@pytest.fixture(scope="module")
def shear_specs():
    result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=100))
    return {spec.title.split(" (")[0].split(":")[0]: spec for spec in console_tables(result)}


@pytest.fixture(scope="module")
def triaxial_specs():
    return console_tables(capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds")))


def _pieces(spec, width):
    """Each folded piece of a table as the text rich prints at ``width`` columns."""
    out = []
    for table in render.rich_tables(spec, width):
        con = Console(width=width, record=True, force_terminal=True, color_system=None)
        con.print(table)
        out.append(con.export_text())
    return out


def test_fmt_zero_within_the_computations_rounding():
    # 7.276e-15 kPa among stresses of ~150 kPa: 0.26 ulp of 150 (2.8e-14), printed as 0
    assert render.fmt(7.276e-15, scale=150.2) == "0"
    assert render.fmt(-5.821e-14, scale=396.7) == "0"
    # above ZERO_RTOL x scale a small value stays: 1e-6 kPa beside 150 kPa is 6.7e-9 relative
    assert render.fmt(1e-6, scale=150.0) == "1e-06"
    assert render.fmt(7.276e-15) == "7.276e-15"  # no scale, no rule
    assert render.magnitude([1.0, None, -3.5, float("nan"), "x"]) == 3.5


def test_row_table_prints_zero_relative_to_its_column():
    spec = render.row_table("t", [{"case": "a", "q": 150.2}, {"case": "b", "q": 7.276e-15}], ["case", "q"])
    assert [r[1] for r in spec.rows] == ["150.2", "0"]


def test_triaxial_spherical_bound_has_no_deviator(triaxial_specs):
    # q_cap of the spherical bound is 0 by construction (σ1,cap = σ3,cap, Prunier et al. 2024, eq. 30)
    tensor = next(s for s in triaxial_specs if s.title.startswith("Capillary stress tensor"))
    heads = [h for h, _ in tensor.columns]
    q_cap = [r[heads.index("q_cap")] for r in tensor.rows if r[heads.index("bound")] == "UB q=q'"]
    assert q_cap and set(q_cap) == {"0"}
    assert not any("e-1" in cell for row in tensor.rows for cell in row)


def test_model_comparison_stacks_each_row_with_its_material_and_model(shear_specs):
    spec = shear_specs["Wet tests"]
    text = "".join(_pieces(spec, 60))
    models = ("No suction", "Bishop", "Own 1", "Own 2")
    for material in ("steel_2mm", "sand_208-417um", "(all)"):
        for m in models:  # a blank material cell carries the material above it
            assert f"{material} · {m}" in text.splitlines()
    assert "lowest RMSE: best" in text  # the mark stays in its own row's block
    assert all(cell_len(line) <= 60 for line in text.splitlines())


def test_bootstrap_table_stacks_at_60_columns(shear_specs):
    spec = shear_specs["How sure is the ranking?"]
    text = "".join(_pieces(spec, 60))
    assert "steel_2mm" in text.splitlines() and "sand_208-417um" in text.splitlines()
    assert "replicates: 2000" in text or "replicates: 100" in text
    assert all(cell_len(line) <= 60 for line in text.splitlines())


def test_triaxial_tensor_table_names_test_and_bound(triaxial_specs):
    tensor = next(s for s in triaxial_specs if s.title.startswith("Capillary stress tensor"))
    text = "".join(_pieces(tensor, 60))
    assert "UNSAT-0 · UB EDTP" in text.splitlines()
    assert all(cell_len(line) <= 60 for line in text.splitlines())


def test_a_table_that_fits_prints_as_one_table():
    spec = TableSpec("t", [("material", "left"), ("c [kPa]", "right")], [["sand", "0.1234"]])
    assert len(render.rich_tables(spec, 80)) == 1 and "│ sand     │  0.1234 │" in _pieces(spec, 80)[0]
    assert "c [kPa]" in _pieces(spec, 80)[0]  # room enough: the header on one line


def test_a_long_value_breaks_between_parameters_never_inside_a_number():
    value = "; ".join(f"p{k} 0.123456 ± 0.0042" for k in range(8))
    spec = TableSpec("fits", [("model", "left"), ("parameters", "left"), ("R²", "right")], [["vg", value, "0.99"]])
    lines = _pieces(spec, 50)[0].splitlines()
    assert lines[1].strip() == "vg"  # the long text column is a value, not a row label
    assert all(cell_len(x) <= 50 for x in lines)
    assert all("± 0.0042" in x for x in lines[2:-1])  # each piece ends with its error: broken after '; '


def test_headers_wrap_before_a_table_folds():
    spec = TableSpec("t", [("material", "left"), ("RMSE difference [kPa]", "right")], [["sand", "0.1234"]])
    assert render.column_groups(spec, 30) == [[0, 1]]  # 'difference' (10) fits beside 'material' in 30 columns
    assert render.wrap_header("RMSE difference [kPa]", 10) == "RMSE\ndifference\n[kPa]"
    # a table folded into groups: every column once, the labels in each
    wide = TableSpec(
        "t",
        [("test", "left"), ("bound", "left")] + [(f"c{k}", "right") for k in range(12)],
        [["T", "LB", *("-123.4" for _ in range(12))]],
    )
    groups = render.column_groups(wide, 40)
    assert all(g[:2] == [0, 1] for g in groups)
    assert sorted(j for g in groups for j in g[2:]) == list(range(2, 14))
