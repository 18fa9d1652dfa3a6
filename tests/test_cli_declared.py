"""Each CLI option declared once (issue 28 items 5 and 6): by its Options field and the glossary.

The hand-written commands name the Options field of each option (capred.cli.declare.option); help text, unit,
range and default come from the field and the glossary, the lists of models and laws from the registries, read at
run time from their numpy-free declarations in capred.spec (nothing generated, nothing cached on disk).
"""

import ast
import dataclasses
import importlib.util
import re
from importlib import import_module
from pathlib import Path

import pytest
import typer.main
from typer.testing import CliRunner

from capred.cli import _subcommand, app
from capred.cli.common import BUILDERS
from capred.cli.declare import class_facts, si_values
from capred.nomenclature import QUANTITIES
from capred.reductions import REDUCTIONS
from capred.units import parse_quantity

runner = CliRunner()
CLI = Path(__file__).resolve().parents[1] / "capred" / "cli"


def _help(*args) -> str:
    res = runner.invoke(app, [*args, "--help"], terminal_width=200)
    assert res.exit_code == 0, res.output
    return " ".join(res.stdout.split())  # wrapped lines joined


def _options_class(path: str):
    module, name = path.split(":")
    return getattr(import_module(module), name)


#: every Options class a command declares its options with (and shear's model parameters)
OPTIONS_PATHS = sorted({r.options_path for r in REDUCTIONS.values()} | {"capred.spec.shear:ModelParams"})
#: what each declares about its options, read now
DECLARED = {path: class_facts(_options_class(path)) for path in OPTIONS_PATHS}


def _registry(path: str):
    module, name = path.split(":")
    return getattr(import_module(module), name)


@pytest.mark.parametrize(
    "registry,command",
    [
        ("capred.physics.effective_stress_models:REGISTRY", ("shear",)),
        ("capred.fitting.retention_models:MODELS", ("retention",)),
        ("capred.fitting.retention_models:MODELS", ("retention-convert",)),
        ("capred.physics.bridge_laws:LAWS", ("bridge", "laws")),
    ],
)
def test_every_registry_entry_is_listed_in_its_help(registry, command):
    """The live registry (not the snapshot): an entry added there and missing from --help fails here."""
    text = _help(*command)
    missing = [name for name in _registry(registry) if not re.search(rf"(?<![\w-]){name}(?![\w-])", text)]
    assert not missing, f"capred {' '.join(command)} --help does not list {missing}"


def test_models_help_lists_the_wet_area_model_and_the_registry_sets():
    # the hand-typed list of before missed it; the thesis's four and the fitted laws are registry flags
    text = _help("shear")
    assert "pedrotti_tarantino_wet_area" in text
    assert "'thesis' for the thesis's no_suction, bishop, own1, own2" in text
    assert "Fitted per material: chi_power, khalili_fit." in text


def test_no_registry_name_alone_in_the_cli():
    """A registered name lives in its registry's module: the CLI's help lists and the snapshot join the names
    (no string constant of capred/cli/*.py is one name), so a grep for special-cased names finds none here."""
    registries = (
        "capred.physics.effective_stress_models:REGISTRY",
        "capred.fitting.retention_models:MODELS",
        "capred.fitting.chi_laws:LAWS",
        "capred.physics.bridge_laws:LAWS",
    )
    names = {n for path in registries for n in _registry(path)}
    for path in sorted(CLI.glob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        constants = {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)}
        assert not constants & names, f"{path.name}: {sorted(constants & names)}"


def test_glossary_options_show_the_glossary_unit_range_and_the_options_default():
    """Every option of a dimensional field: '[unit; range]' of its glossary entry in --help, and the default
    shown is the Options default in that unit (gamma_w 9810 N/m^3 -> 9.81 kN/m^3)."""
    shear = _help("shear")
    assert "Unit weight of water γ_w [kN/m^3; > 0]; the thesis uses 10. [default: 9.81]" in shear
    assert "Shear box area A [cm^2; > 0]" in shear and "[default: 101.325]" in shear
    assert "Contact angle θ_c [deg; 0 to 90, 90 excluded]" in _help("bridge", "curve")
    assert "Mean total stress p0 [kPa; >= 0]. [default: 100]" in _help("skempton-b")
    checked = 0
    for path, fields in DECLARED.items():
        cls = _options_class(path)
        for f in dataclasses.fields(cls):
            entry = fields.get(f.name)
            if entry is None or entry["quantity"] is None or f.default is dataclasses.MISSING or f.default is None:
                continue
            q = QUANTITIES[cls.QUANTITIES[f.name]]
            assert entry["unit"] == ("" if q.unit == "-" else q.unit)
            shown = float(re.fullmatch(r"\[default: (.*)\]", entry["default"]).group(1))
            assert shown == pytest.approx(f.default * q.factor, rel=1e-12)  # 12 digits shown
            checked += 1
    assert checked >= 20


def _quick_options(command):
    """The options the CLI builds for a command's quick run (its sample and example options)."""
    red = REDUCTIONS[command]
    cmd = _subcommand(typer.main.get_command(app), command)
    ctx = cmd.make_context(command, red.example_args()[len(command.split()) :])
    return BUILDERS[command](**ctx.params).options


@pytest.mark.parametrize("command", sorted(c for c in REDUCTIONS if c in BUILDERS))
def test_an_option_not_given_is_the_options_default(command):
    """The CLI's defaults are the Options' (declared once): no option but the example's gives the options
    object the API builds from the same example."""
    red = REDUCTIONS[command]
    cli = _quick_options(command)
    api = red.options(**dict(red.example))
    if command == "pt-volume":  # --sample alone runs the bundled path with EXAMPLE_KAOLIN (its header says so)
        api = dataclasses.replace(api, example_kaolin=True)
    for f in dataclasses.fields(api):
        if f.name not in ("curves",):
            assert getattr(cli, f.name) == getattr(api, f.name), f.name


def test_a_bare_number_is_read_once_in_the_unit_help_shows():
    """Values stay numbers: '10' of --gamma-w is 10 kN/m^3 = 10000.0 N/m^3, a float (10 * 1000 exactly), never
    text again; a value with its own unit goes to the Options as typed (they read it, and note how)."""
    v = si_values("capred.pipelines.shear:ShearOptions", gamma_w="10", box_area="36", radius="0.5", seed=3)
    # the same bits as the reading of "36 cm^2" (36 * 1e-4): one multiplication by the unit's SI value
    assert v == {"gamma_w": 10 * 1e3, "box_area": 36 * 1e-4, "radius": 0.5 * 1e-3, "seed": 3}
    assert v["box_area"] == parse_quantity("36 cm^2", "m^2", "area")
    assert all(type(x) is float for k, x in v.items() if k != "seed")
    assert si_values("capred.pipelines.shear:ShearOptions", box_area="36 cm^2") == {"box_area": "36 cm^2"}
    assert si_values("capred.pipelines.shear:ShearOptions", gamma_w=None) == {}  # the Options' default applies
    res = runner.invoke(app, ["shear", "--sample", "--json", "--gamma-w", "10", "--box-area", "3600 mm^2"])
    assert res.exit_code == 0, res.output
    import json

    options = json.loads(res.stdout)["options"]
    assert options["gamma_w"] == 10000.0 and options["box_area"] == pytest.approx(0.0036, rel=1e-15)


@pytest.mark.parametrize(
    "args,message",
    [
        (["shear", "--sample", "--box-area", "-3"], "box_area (--box-area): shear box area must be > 0 cm^2"),
        (["rumpf", "--S-R", "1.5"], "S_R (--S-R): degree of saturation must lie between 0 and 1"),
        (["bridge", "curve", "--contact-angle", "95"], "contact_angle (--contact-angle): contact angle must lie"),
    ],
)
def test_a_bare_number_out_of_range_names_the_option_in_the_glossary_wording(args, message):
    res = runner.invoke(app, args)
    assert res.exit_code == 1 and message in res.stderr, res.output
    assert "Traceback" not in res.output and "plain number read in" not in res.stderr


def _module_constants(tree) -> dict:
    return {
        t.id: node.value.value
        for node in tree.body
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant)
        for t in node.targets
        if isinstance(t, ast.Name)
    }


def _strings(node) -> list[str]:
    return [n.value for n in ast.walk(node) if isinstance(n, ast.Constant) and isinstance(n.value, str)]


def test_no_hand_typed_unit_or_range_of_a_glossary_quantity_in_the_cli():
    """grep of capred/cli/*.py: an option of a field with a glossary entry is declared by option() (not a
    typer.Option of its own), and its help and note add no unit ('[kPa]', 'kN/m^3') or range: those are the
    glossary's. No quantity() call site is left."""
    glossary_fields = {name for fields in DECLARED.values() for name, e in fields.items() if e["quantity"] is not None}
    problems = []
    for path in sorted(CLI.glob("*.py")):
        source = path.read_text(encoding="utf-8")
        tree = ast.parse(source)
        if re.search(r"\bquantity\(", source):
            problems.append(f"{path.name}: a quantity() call site")
        consts = _module_constants(tree)
        for fn in (n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)):
            for arg in fn.args.args + fn.args.kwonlyargs:
                ann = arg.annotation
                if ann is None:
                    continue
                call = ann if isinstance(ann, ast.Call) and getattr(ann.func, "id", "") == "option" else None
                if call is None:
                    if "typer.Option" in ast.unparse(ann) and arg.arg in glossary_fields:
                        problems.append(f"{path.name}: {fn.name}({arg.arg}) declares a glossary quantity by hand")
                    continue
                options = consts.get(getattr(call.args[0], "id", ""), "")
                field = call.args[1].value
                entry = DECLARED[options][field]
                if entry["quantity"] is None:
                    continue
                q = QUANTITIES[entry["quantity"]]
                units = {q.unit, q.unit.replace("^", "")} - {"-", ""}
                for text in (s for kw in call.keywords if kw.arg in ("help", "note") for s in _strings(kw.value)):
                    for unit in units:
                        u = rf"(?<![\w/^]){re.escape(unit)}(?![\w/^])"
                        if re.search(rf"\[[^\]]*{u}[^\]]*\]|\bin {u}", text):  # '[kPa]', '[kPa, deg]', 'in kPa'
                            problems.append(f"{path.name}: {fn.name}({arg.arg}) types the unit {unit!r}: {text!r}")
                    if re.search(r"\[-\]|\[\s*[<>]=?\s*\d", text):
                        problems.append(f"{path.name}: {fn.name}({arg.arg}) types a unit or range: {text!r}")
    assert not problems, "\n".join(problems)


def test_the_grep_above_finds_a_hand_typed_unit(tmp_path, monkeypatch):
    """The check can fail: a help that types '[kPa]' for a glossary quantity is reported."""
    bad = tmp_path / "bad_command.py"
    bad.write_text(
        'X = "capred.spec.shear:ShearOptions"\n\n\n'
        'def f(ambient_pressure: option(X, "ambient_pressure", help="Air pressure [kPa]") = None):\n    pass\n',
        encoding="utf-8",
    )
    monkeypatch.setattr(__import__(__name__), "CLI", tmp_path)
    with pytest.raises(AssertionError, match="types the unit 'kPa'"):
        test_no_hand_typed_unit_or_range_of_a_glossary_quantity_in_the_cli()


def test_every_commands_options_are_declared_in_the_numpy_free_spec():
    """The Options of every command live in capred.spec (so that its --help imports no numerical library) and
    keep their old import path (the pipeline module re-exports the same class)."""
    for name, red in REDUCTIONS.items():
        module, cls = red.options_path.split(":")
        assert module.startswith("capred.spec."), name
        pipeline = import_module(red.run_path.split(":")[0])
        assert getattr(pipeline, cls, None) is _options_class(red.options_path), name


def test_the_cli_holds_no_generated_source_and_declare_does_not_import_generated():
    """No snapshot in the package (issue 42), and no import circle cli.declare <-> cli.generated."""
    assert not (CLI / "declared.py").exists() and not (CLI / "help_columns.py").exists()
    tree = ast.parse((CLI / "declare.py").read_text(encoding="utf-8"))
    imported = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    imported |= {a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
    assert not {m for m in imported if m and m.endswith("generated")}, imported


def test_a_model_registered_at_run_time_shows_in_shear_help(monkeypatch):
    """A model added to the registry after the CLI was built (a lab script's own model) is listed by
    `capred shear --help`: the --models help is rendered when the help is shown."""
    import capred.spec.effective_stress as es

    _help("shear")  # the command built (and its help shown) before the model exists
    entry = dataclasses.replace(es.REGISTRY["bishop"], name="half_bishop_rt", label="half Bishop")
    monkeypatch.setitem(es.REGISTRY, "half_bishop_rt", entry)
    assert re.search(r"(?<![\w-])half_bishop_rt(?![\w-])", _help("shear"))
    monkeypatch.delitem(es.REGISTRY, "half_bishop_rt")
    assert "half_bishop_rt" not in _help("shear")


# --- the help as a new user reads it (one vocabulary of metavars, no option split at its hyphen) ---------------

#: every command `capred --help` lists, and those of its groups (bridge)
EVERY_COMMAND = sorted({*REDUCTIONS, "batch"})


def _raw_help(command: str, width: int) -> str:
    """`capred COMMAND --help` as printed in a terminal ``width`` columns wide (lines as wrapped)."""
    res = runner.invoke(app, [*command.split(), "--help"], terminal_width=width)
    assert res.exit_code == 0, res.output
    return res.stdout


@pytest.mark.parametrize("width", [80, 120])
@pytest.mark.parametrize("command", EVERY_COMMAND)
def test_help_shows_values_in_one_vocabulary_without_python_types(command, width):
    """No Python type repr (``<list[Path]>``, ``<str>``, ``<int range>``, ``<float>``) and no range in click's
    words (``[x>=1]``) beside the one the text states: a value shows as NUMBER, INTEGER, FILE, PATH, TEXT or
    NAME[,NAME...] (capred.cli.declare.METAVARS), or as the words it may be."""
    text = _raw_help(command, width)
    for typer_words in ("<list[", "<str>", "<int range>", "<int>", "<float>", "<path>", "[x>=", "[x<=", "<=x<="):
        assert typer_words not in text, f"capred {command} --help shows {typer_words!r}"


@pytest.mark.parametrize("width", [80, 120])
@pytest.mark.parametrize("command", [*EVERY_COMMAND, "bridge", ""])
def test_help_never_splits_an_option_name_at_its_hyphen(command, width):
    """An option named in prose (``--reference-stress``, ``--model bounding-surface``) stays on one line, so it
    can be copied: no line ends in a hyphenated word cut after its hyphen."""
    text = _raw_help(command, width) if command else runner.invoke(app, ["--help"], terminal_width=width).stdout
    cut = [line for line in text.splitlines() if re.search(r"\w-$", line.rstrip())]
    assert not cut, f"capred {command} --help breaks at a hyphen: {cut}"


def test_the_reviewed_options_show_their_kind():
    """The options the review found (issue: help polish): a file as PATH (as --out and --store), a number as
    NUMBER, a whole number as INTEGER, the data files argument as FILE... (not ``data... <list[Path]>``)."""
    skempton = _raw_help("skempton-b", 200)
    assert re.search(r"^  --retention PATH ", skempton, re.M) and re.search(r"^  --compression PATH ", skempton, re.M)
    assert re.search(r"^  --interpolation-h NUMBER ", skempton, re.M)
    assert re.search(r"^  FILE\.\.\.", skempton, re.M)  # the data files argument, in the Arguments section
    if importlib.util.find_spec("typer._click") is not None:  # typer >= 0.2x; its floor 0.16 (on the click
        # package) prints an argument's usage as its metavar alone and its help only in rich mode
        assert re.search(r"^  FILE\.\.\. ", skempton, re.M) and "[OPTIONS] [FILE]..." in skempton
    band = _raw_help("shear-band", 200)
    assert re.search(r"^  --triaxial PATH ", band, re.M) and re.search(r"^  --dilatancy-rate NUMBER ", band, re.M)
    assert re.search(r"^  --compression-w PATH ", _raw_help("pt-volume", 200), re.M)
    assert re.search(r"^  --S-R-max, --sr-max NUMBER ", _raw_help("bridge curve", 200), re.M)
    shear = _raw_help("shear", 200)
    assert re.search(r"^  --bootstrap INTEGER ", shear, re.M) and re.search(r"^  --ignore-column TEXT ", shear, re.M)
    assert re.search(r"^  --max-megabytes INTEGER .*\[>= 1\]$", shear, re.M)  # the range once, in capred's words


@pytest.mark.parametrize(
    "args,message",
    [
        (["shear", "--sample", "--bootstrap", "1.5"], "bootstrap (--bootstrap) must be a whole number >= 0 (got 1.5)"),
        (["shear", "--sample", "--seed", "-1"], "seed (--seed) must be a whole number >= 0 (got -1)"),
        (
            ["triaxial", "--sample", "--bootstrap", "many"],
            "bootstrap (--bootstrap) must be a whole number >= 0 (got 'many')",
        ),
        (
            ["bridge", "solve", "--sample", "--workers", "2.5"],
            "workers (--workers) must be a whole number >= 1 (got 2.5)",
        ),
    ],
)
def test_a_non_integer_for_an_integer_option_reads_as_its_declared_constraint(args, message, tmp_path):
    """``--bootstrap 1.5`` is refused in the words of the field's Whole constraint, exit 1, as ``--seed -1`` is
    (not typer's "Input should be a valid integer", exit 2), and nothing is written."""
    out = tmp_path / "out"
    res = runner.invoke(app, [*args, "--out", str(out)])
    assert res.exit_code == 1, res.output
    assert message in " ".join(res.output.split())
    assert "valid integer" not in res.output and not out.exists()
