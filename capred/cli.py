"""Command-line interface: thin commands over capred.pipelines.

Only typer is imported at start-up; each command imports its pipeline when it
runs, so `capred --help` stays fast.
"""

import json
from pathlib import Path
from typing import Annotated, Optional

import typer

from .errors import CapredError

app = typer.Typer(
    name="capred",
    help="Capillary effective stress and strength from unsaturated-soil lab tests.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    # plain help text: rendering help through rich would double `capred --help` start-up time
    rich_markup_mode=None,
)


def _version(value: bool):
    if value:
        from . import __version__

        typer.echo(f"capred {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[bool, typer.Option("--version", callback=_version, is_eager=True,
                                          help="Show the version and exit.")] = False,
):
    """capred turns raw unsaturated-soil lab readings into effective stresses,
    strength parameters, model comparisons and report figures."""


# While `capred batch` reads a manifest, commands hand their jobs here instead of running them.
_COLLECTING: Optional[list] = None


def fail(exc: CapredError) -> None:
    """Print a clean one-message error to stderr and exit 1 (re-raised while collecting a manifest)."""
    if _COLLECTING is not None:
        raise exc
    typer.echo(f"Error: {exc}", err=True)
    raise typer.Exit(1)


def _quantity(text: Optional[str], unit: str, kind: str, option: str,
              notes: Optional[list] = None) -> Optional[float]:
    from .errors import OptionError
    from .units import parse_quantity

    if text is None:
        return None
    try:
        return parse_quantity(text, unit, kind, notes)
    except CapredError as exc:
        raise OptionError(f"{option}: {exc}") from None


def _default_out(command: str, data: Path) -> Path:
    return Path.cwd() / "capred_out" / f"{command}_{data.stem}"


def _console():
    from rich.console import Console

    return Console()


OutOpt = Annotated[Optional[Path], typer.Option("--out", "-o", help="Output folder [default: ./capred_out/<command>_<input name>].")]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON document on stdout instead of tables.")]
PlotOpt = Annotated[bool, typer.Option("--plots/--no-plots", help="Write the PNG report figures.")]
SampleOpt = Annotated[bool, typer.Option("--sample", help="Run on the bundled (synthetic) sample data.")]
WorkersOpt = Annotated[int, typer.Option(min=1, help="Worker processes for a batch of files.")]


@app.command()
def shear(
    data: Annotated[Optional[list[Path]], typer.Argument(help="CSV files of direct-shear tests (one row per test); "
                                                         "several files or globs run as a batch.",
                                                         show_default=False)] = None,
    out: OutOpt = None,
    json_out: JsonOpt = False,
    plots: PlotOpt = True,
    sample: SampleOpt = False,
    workers: WorkersOpt = 1,
    gamma_w: Annotated[str, typer.Option(help="Unit weight of water [kN/m^3]; the thesis uses 10.")] = "9.81",
    surface_tension: Annotated[str, typer.Option(help="Surface tension of water [N/m].")] = "0.0728",
    gravity: Annotated[str, typer.Option("--g", help="Gravitational acceleration [m/s^2].")] = "9.81",
    pendular_limit: Annotated[float, typer.Option(help="S_R above which a wet test is flagged outside the pendular regime.")] = 0.05,
    box_area: Annotated[Optional[str], typer.Option(help="Shear box area [cm^2] for rows without 'box_area'.")] = None,
    cap_mass: Annotated[Optional[str], typer.Option(help="Top-cap mass [g] for rows without 'cap_mass'.")] = None,
    radius: Annotated[Optional[str], typer.Option(help="Particle radius R [mm] for rows without 'R'.")] = None,
    void_volume: Annotated[Optional[str], typer.Option(help="Void volume V_v [cm^3] for rows without 'V_v'.")] = None,
    models: Annotated[str, typer.Option(help="Models to compare, comma separated: no_suction, bishop, own1, own2 "
                                        "(= 'thesis', the default), vanapalli, khalili, lu_likos, fredlund, "
                                        "pedrotti_tarantino; 'all' for every one.")] = "thesis",
    retention: Annotated[Optional[Path], typer.Option(help="fits.json from capred retention: S_res, s_e and van "
                                                      "Genuchten parameters for the extra models.")] = None,
    s_res: Annotated[Optional[float], typer.Option(help="Residual S_R (Vanapalli).")] = None,
    vanapalli_kappa: Annotated[float, typer.Option(help="Fitting exponent kappa of Vanapalli et al.")] = 1.0,
    air_entry: Annotated[Optional[str], typer.Option(help="Air-entry suction s_e [kPa] (Khalili-Khabbaz).")] = None,
    vg_alpha: Annotated[Optional[str], typer.Option(help="van Genuchten alpha [1/kPa] (Lu-Likos).")] = None,
    vg_n: Annotated[Optional[float], typer.Option(help="van Genuchten n (Lu-Likos); m = 1 - 1/n unless --vg-m.")] = None,
    vg_m: Annotated[Optional[float], typer.Option(help="van Genuchten m (Lu-Likos).")] = None,
    water_envelope: Annotated[Optional[str], typer.Option(help="'c,phi' [kPa, deg] of the water-saturated soil "
                                                          "(Pedrotti-Tarantino); default: the dry envelope.")] = None,
):
    """Direct-shear tests with hanging-column suction: dry envelope per material,
    the four effective-stress models (No suction, Bishop, Own 1, Own 2) on every
    wet test, their scores and a PNG report sheet per material.

    Values in the file win over the options; options fill absent columns and
    blank cells. Any option may carry a unit: --box-area "36 cm^2".

    Example: capred shear tests.csv --out report --gamma-w 10
    """
    try:
        from .pipelines.shear import ShearOptions

        opts = ShearOptions(
            gamma_w=_quantity(gamma_w, "kN/m^3", "unit_weight", "--gamma-w"),
            surface_tension=_quantity(surface_tension, "N/m", "surface_tension", "--surface-tension"),
            g=_quantity(gravity, "m/s^2", "acceleration", "--g"),
            pendular_limit=pendular_limit,
            box_area=_quantity(box_area, "cm^2", "area", "--box-area"),
            cap_mass=_quantity(cap_mass, "g", "mass", "--cap-mass"),
            radius=_quantity(radius, "mm", "length", "--radius"),
            void_volume=_quantity(void_volume, "cm^3", "volume", "--void-volume"),
            models=_model_list(models),
            model_params=_model_params(retention, s_res=s_res, vanapalli_kappa=vanapalli_kappa,
                                       air_entry=_quantity(air_entry, "kPa", "pressure", "--air-entry"),
                                       vg_alpha=_quantity(vg_alpha, "1/kPa", "per_pressure", "--vg-alpha"),
                                       vg_n=vg_n, vg_m=vg_m, water_envelope=_envelope_pair(water_envelope)),
        )
        _dispatch("shear", data, sample, out, json_out, plots, workers,
                  {"options": opts, "command_options": {"plots": plots}})
    except CapredError as exc:
        fail(exc)


@app.command("triaxial-bounds")
def triaxial_bounds(
    data: Annotated[Optional[list[Path]], typer.Argument(help="CSV files of triaxial tests (one row per test); "
                                                         "several files or globs run as a batch.",
                                                         show_default=False)] = None,
    out: OutOpt = None,
    json_out: JsonOpt = False,
    plots: PlotOpt = True,
    sample: SampleOpt = False,
    workers: WorkersOpt = 1,
    curves: Annotated[Optional[Path], typer.Option(help="Long CSV of raw curves (test_id, axial_strain, q): "
                                                   "failure = peak of q, for tests without q_f or sigma1.")] = None,
    c_eff: Annotated[Optional[str], typer.Option(help="Effective cohesion c' [kPa], instead of fitting saturated tests.")] = None,
    phi_eff: Annotated[Optional[float], typer.Option(help="Effective friction angle phi' [deg], with --c-eff.")] = None,
):
    """Bounds of the capillary stress tensor at failure from triaxial tests
    (Prunier et al. 2024): effective envelope from saturated drained tests, then
    for every unsaturated test the spherical upper bound (q = q'), the lower
    bound (sigma1_cap = 0) and the EDTP upper bound (needs s0), with the
    strength gain q'/q'_sat; groups sharing one tensor get the Appendix 1 analysis.

    Example: capred triaxial-bounds tests.csv --out bounds
    """
    try:
        from .pipelines.triaxial import TriaxialOptions

        opts = TriaxialOptions(c_eff=_quantity(c_eff, "kPa", "pressure", "--c-eff"), phi_eff=phi_eff)
        _dispatch("triaxial-bounds", data, sample, out, json_out, plots, workers,
                  {"options": opts, "curves": curves,
                   "command_options": {"plots": plots, "curves": str(curves) if curves else None}})
    except CapredError as exc:
        fail(exc)


@app.command()
def retention(
    data: Annotated[Optional[list[Path]], typer.Argument(help="CSV files of retention readings: suction or head, "
                                                         "and S_R, theta or z2 + V_v.", show_default=False)] = None,
    out: OutOpt = None,
    json_out: JsonOpt = False,
    plots: PlotOpt = True,
    sample: SampleOpt = False,
    workers: WorkersOpt = 1,
    model: Annotated[str, typer.Option(help="vg (m = 1 - 1/n, and m free), bc, or all.")] = "all",
    fix: Annotated[Optional[list[str]], typer.Option(help="Fix a parameter, e.g. --fix theta_s=0.25 "
                                                     "(alpha in 1/kPa, s_e in kPa); repeatable.")] = None,
    gamma_w: Annotated[str, typer.Option(help="Unit weight of water [kN/m^3], to turn heads into suction.")] = "9.81",
):
    """Fit water retention curves: van Genuchten (m = 1 - 1/n and m free) and
    Brooks-Corey (air-entry suction s_e, index lambda) for every branch (drying,
    wetting), with standard errors, R^2 and AIC. Branches come from a 'branch'
    column or, without one, from the order of readings (rising suction = drying).

    Example: capred retention column.csv --model vg --fix theta_r=0
    """
    try:
        from .pipelines.retention import RetentionOptions, parse_fixed

        models = {"all": ("vg", "vg_m_free", "bc"), "vg": ("vg", "vg_m_free"), "bc": ("bc",)}
        if model not in models:
            from .errors import OptionError

            raise OptionError(f"--model must be vg, bc or all (got '{model}')")
        opts = RetentionOptions(models=models[model], fixed=parse_fixed(fix or []),
                                gamma_w=_quantity(gamma_w, "kN/m^3", "unit_weight", "--gamma-w"))
        _dispatch("retention", data, sample, out, json_out, plots, workers,
                  {"options": opts, "command_options": {"plots": plots}})
    except CapredError as exc:
        fail(exc)


def _dispatch(command, data, sample, out, json_out, plots, workers, kwargs) -> None:
    """One file: run it and show its tables (or JSON). Several: a batch with progress and an index."""
    from .pipelines import jobs

    sources = _sources(data, sample, command)
    if _COLLECTING is not None:
        _COLLECTING.append((command, sources, kwargs, plots, out))
        return
    if len(sources) == 1:
        job = jobs.Job(command, sources[0], out or _default_out(command.split("-")[0], sources[0]), kwargs, plots)
        result, written = jobs.run(job)
        if json_out:
            typer.echo(json.dumps(result.to_json(), indent=2, ensure_ascii=False))
            return
        from .report import console

        tables = {"shear": console.shear_tables, "triaxial-bounds": console.triaxial_tables,
                  "retention": console.retention_tables}[command](result)
        _print(tables, result.notes, written, job.out_dir)
        return
    root = out or Path.cwd() / "capred_out"
    batch = [jobs.Job(command, src, d, kwargs, plots, keep_json=json_out)
             for src, d in zip(sources, jobs.output_dirs([command] * len(sources), sources, root))]
    _run_batch(batch, root, json_out, workers)


def _run_batch(batch, root: Path, json_out: bool, workers: int) -> None:
    """Run jobs with a progress bar (on a terminal, not with --json), print a summary, write index.csv."""
    from rich.console import Console
    from rich.markup import escape
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn
    from rich.table import Table

    from .pipelines import jobs

    err = Console(stderr=True)
    show = err.is_terminal and not json_out
    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                  console=err, disable=not show, transient=True) as progress:
        task = progress.add_task(f"capred: {len(batch)} files", total=len(batch))
        outcomes = jobs.run_all(batch, workers, on_done=lambda o: progress.advance(task))
    index = jobs.write_index(root, outcomes)
    failed = [o for o in outcomes if not o.ok]
    if json_out:
        typer.echo(json.dumps({"files": [{"input": o.source, "command": o.command, "ok": o.ok,
                                          "error": o.message or None, "out_dir": o.out_dir,
                                          "result": o.result_json} for o in outcomes],
                               "index": str(index), "failed": len(failed)}, indent=2, ensure_ascii=False))
    else:
        t = Table(title=f"{len(outcomes) - len(failed)} of {len(outcomes)} files reduced", title_justify="left")
        for col in ("input", "command", "status", "output / error"):
            t.add_column(col)
        for o in outcomes:
            t.add_row(escape(o.source), o.command, "[green]ok[/]" if o.ok else "[red]failed[/]",
                      escape(o.out_dir if o.ok else o.message))
        Console().print(t)
        Console().print(f"Index of all outputs: [bold]{escape(str(index))}[/]")
    for o in failed:
        typer.echo(f"Error: {o.message}", err=True)
    if failed:
        raise typer.Exit(1)


@app.command()
def batch(
    manifest: Annotated[Path, typer.Argument(help="CSV (command,input,options) or TOML ([[run]] command, input, "
                                             "options) listing the runs.", show_default=False)],
    out: Annotated[Optional[Path], typer.Option("--out", "-o", help="Root output folder [default: ./capred_out].")] = None,
    json_out: JsonOpt = False,
    workers: WorkersOpt = 1,
):
    """Run a season's worth of reductions listed in a manifest: one line per run,
    with the command (shear, triaxial-bounds, retention), the input file or glob,
    and that command's options as on the command line. Every file gets its own
    folder under --out; bad files are reported and the others still complete;
    index.csv lists every output; the exit code is 1 if anything failed.

    Example: capred batch season.csv --workers 2   (season.csv: command,input,options /
    shear,runs/*.csv,--gamma-w 10 --no-plots)
    """
    global _COLLECTING
    import shlex

    import typer.main

    from .errors import InputError, Problem
    from .pipelines import jobs

    try:
        entries = _read_manifest(manifest)
    except CapredError as exc:
        fail(exc)
    group = typer.main.get_command(app)
    root = out or Path.cwd() / "capred_out"
    collected: list = []
    problems: list = []
    base = manifest.parent
    for line, command, pattern, options in entries:
        cmd = group.commands.get(command) if command in jobs.RUNNERS else None
        if cmd is None:
            problems.append(Problem(str(manifest), line, "command", f"'{command}' is not one of {', '.join(jobs.RUNNERS)}"))
            continue
        target = pattern if Path(pattern).is_absolute() else str(base / pattern)
        try:
            argv = [target, *shlex.split(options)]
        except ValueError as exc:  # unbalanced quotes in the options
            problems.append(Problem(str(manifest), line, "options", str(exc)))
            continue
        try:
            ctx = cmd.make_context(command, argv)
            _COLLECTING = collected
            ctx.invoke(cmd.callback, **ctx.params)
        except CapredError as exc:
            problems.append(Problem(str(manifest), line, None, str(exc)))
        except Exception as exc:  # click usage errors: bad option names or values in the manifest
            if type(exc).__module__.split(".")[0] not in ("click", "typer"):
                raise
            message = exc.format_message() if hasattr(exc, "format_message") else str(exc)
            problems.append(Problem(str(manifest), line, "options", message))
        finally:
            _COLLECTING = None
    if problems:
        fail(InputError(problems))
    all_jobs = []
    for command, sources, kwargs, plots, _ in collected:
        all_jobs += [(command, src, kwargs, plots) for src in sources]
    dirs = jobs.output_dirs([c for c, _, _, _ in all_jobs], [src for _, src, _, _ in all_jobs], root)
    batch_jobs = [jobs.Job(c, src, d, kw, pl, keep_json=json_out) for (c, src, kw, pl), d in zip(all_jobs, dirs)]
    _run_batch(batch_jobs, root, json_out, workers)


def _read_manifest(path: Path) -> list[tuple[int, str, str, str]]:
    """(line, command, input, options) per run, from a CSV or TOML manifest."""
    from .errors import InputError, Problem

    if not path.is_file():
        raise InputError(Problem(str(path), None, None, "file not found"))
    text = path.read_text(encoding="utf-8-sig")
    if path.suffix.lower() == ".toml":
        import tomllib

        try:
            runs = tomllib.loads(text).get("run", [])
        except tomllib.TOMLDecodeError as exc:
            raise InputError(Problem(str(path), None, None, f"not valid TOML: {exc}")) from None
        out = []
        for k, r in enumerate(runs, start=1):
            if not isinstance(r, dict) or "command" not in r or "input" not in r:
                raise InputError(Problem(str(path), None, None, f"[[run]] number {k} needs 'command' and 'input'"))
            opts = r.get("options", "")
            out.append((k, str(r["command"]), str(r["input"]), " ".join(opts) if isinstance(opts, list) else str(opts)))
        return out
    import csv

    rows = [(n, row) for n, row in enumerate(csv.reader(text.splitlines()), start=1)
            if row and not row[0].lstrip().startswith("#") and any(c.strip() for c in row)]
    if not rows:
        raise InputError(Problem(str(path), None, None, "the manifest is empty"))
    header = [h.strip().lower() for h in rows[0][1]]
    if "command" not in header or "input" not in header:
        raise InputError(Problem(str(path), rows[0][0], None, "the header needs 'command' and 'input' (and 'options')"))
    ci, ii = header.index("command"), header.index("input")
    oi = header.index("options") if "options" in header else None
    return [(n, r[ci].strip(), r[ii].strip(), r[oi].strip() if oi is not None and oi < len(r) else "")
            for n, r in rows[1:]]


bridge_app = typer.Typer(help="Exact capillary bridges between two equal spheres (Young-Laplace), the "
                              "thesis's analytical comparison and checks against microscopic tests.",
                         no_args_is_help=True)
app.add_typer(bridge_app, name="bridge")


@bridge_app.command("curve")
def bridge_curve_cmd(
    radius: Annotated[str, typer.Option(help="Particle radius R [mm] (2 mm steel spheres: 1).")] = "1",
    surface_tension: Annotated[str, typer.Option(help="Surface tension gamma [N/m].")] = "0.0728",
    contact_angle: Annotated[float, typer.Option(help="Contact angle theta [deg].")] = 0.0,
    points: Annotated[int, typer.Option(help="Number of S_R values.")] = 2000,
    sr_max: Annotated[float, typer.Option(help="Largest S_R of the sweep (bridges stop where suction reaches 0).")] = 0.3,
    pendular_limit: Annotated[float, typer.Option(help="S_R bound of the pendular regime panel.")] = 0.05,
    out: OutOpt = None,
    json_out: JsonOpt = False,
    plots: PlotOpt = True,
):
    """The thesis's analytical comparison: sigma' = F_cap/(pi R^2) against
    S_R = 3 V_w/(2 pi R^3) for two spheres in contact, from exact bridges,
    beside Israelachvili, Bishop, Own 1 and Own 2; one panel inside the
    pendular regime and one over the whole concave range.

    Example: capred bridge curve --radius 1 --contact-angle 0 --points 2000
    """
    try:
        from .pipelines.bridge import bridge_curve, write_bridge_outputs
        from .report.bridge_figures import figure_curve

        curve = bridge_curve(_quantity(radius, "mm", "length", "--radius"),
                             _quantity(surface_tension, "N/m", "surface_tension", "--surface-tension"),
                             contact_angle, points, pendular_limit, sr_max)
        js = curve.to_json()
        out_dir = out or Path.cwd() / "capred_out" / "bridge_curve"
        written = write_bridge_outputs("bridge curve", curve.rows(), js, out_dir,
                                       figure_curve(curve) if plots else None,
                                       options={"radius": radius, "surface_tension": surface_tension,
                                                "contact_angle": contact_angle, "points": points})
    except CapredError as exc:
        fail(exc)
    if json_out:
        typer.echo(json.dumps(js, indent=2, ensure_ascii=False))
        return
    from rich.table import Table

    t = Table(title="RMS relative error of sigma' against the exact bridge", title_justify="left")
    for col in ("model", f"S_R < {pendular_limit:g}", f"S_R >= {pendular_limit:g}"):
        t.add_column(col, justify="right" if col != "model" else "left")
    err = js["rms_relative_error_vs_exact"]
    for m in ("israelachvili", "bishop", "own1", "own2"):
        t.add_row(m, *(f"{err[r][m]:.1%}" if err[r][m] is not None else "—" for r in ("inside", "outside")))
    _print([t], [], written, out_dir)


@bridge_app.command("solve")
def bridge_solve_cmd(
    data: Annotated[Optional[Path], typer.Argument(help="CSV, one bridge per row: R, gamma, theta, gap, and "
                                                   "suction or V_w.", show_default=False)] = None,
    out: OutOpt = None,
    json_out: JsonOpt = False,
    sample: SampleOpt = False,
):
    """Exact bridge per row: neck radius r0, F_cap = F_L + F_T, V_w, half-filling
    angle, S_R = 3V_w/(2 pi R^3) and sigma' = F_cap/(pi R^2); a row without a
    bridge (beyond rupture, too much water) gets a status, not an error.

    Example: capred bridge solve cases.csv --json
    """
    try:
        from .pipelines.bridge import solve_bridges, write_bridge_outputs

        src = _source(data, sample, "bridge-solve")
        res = solve_bridges(src)
        out_dir = out or _default_out("bridge", src)
        written = write_bridge_outputs("bridge solve", res.rows(), res.to_json(), out_dir, inputs=[src])
    except CapredError as exc:
        fail(exc)
    if json_out:
        typer.echo(json.dumps({"bridges": res.rows()}, indent=2, ensure_ascii=False))
        return
    keep = ("case", "r0_mm", "F_cap_mN", "V_w_mm3", "filling_angle_deg", "suction_kPa", "S_R", "sigma_prime_kPa",
            "status")
    _print([_rows_table("Exact capillary bridges", [{k: r[k] for k in keep if k in r} for r in res.rows()])],
           res.notes, written, out_dir)


@bridge_app.command("compare")
def bridge_compare_cmd(
    data: Annotated[Optional[Path], typer.Argument(help="CSV of microscopic tests: R, theta, gap, V_w, measured "
                                                   "F_cap (and filling_angle).", show_default=False)] = None,
    out: OutOpt = None,
    json_out: JsonOpt = False,
    plots: PlotOpt = True,
    sample: SampleOpt = False,
):
    """Microscopic tests against theory: the measured force of each sphere pair
    beside the exact bridge of the same R, gap, theta and V_w, the toroidal
    approximation, Willett et al. (2000) and Israelachvili, with residuals.

    Example: capred bridge compare micro_tests.csv --out micro
    """
    try:
        from .pipelines.bridge import compare_measured, comparison_rows, write_bridge_outputs
        from .report.bridge_figures import figure_compare

        src = _source(data, sample, "bridge-compare")
        rows = comparison_rows(compare_measured(src))
        js = {"source": str(src), "comparison": rows}
        out_dir = out or _default_out("bridge", src)
        written = write_bridge_outputs("bridge compare", rows, js, out_dir,
                                       figure_compare(rows) if plots else None, inputs=[src])
    except CapredError as exc:
        fail(exc)
    if json_out:
        typer.echo(json.dumps(js, indent=2, ensure_ascii=False))
        return
    keep = ("case", "F_measured_mN", "F_exact_mN", "F_toroidal_mN", "F_willett_mN", "F_israelachvili_mN", "status")
    _print([_rows_table("Measured against predicted capillary force [mN]",
                        [{k: r[k] for k in keep if k in r} for r in rows])], [], written, out_dir)


def _rows_table(title: str, rows: list[dict]):
    from rich.markup import escape
    from rich.table import Table

    from .report.console import _f

    t = Table(title=title, title_justify="left")
    keys = [k for k in rows[0] if k != "note"] if rows else []
    for k in keys:
        t.add_column(escape(k), justify="left" if k in ("case", "status") else "right")
    for r in rows:
        t.add_row(*(escape(str(r.get(k))) if isinstance(r.get(k), str) else _f(r.get(k)) for k in keys))
    return t


def _calc_done(result, out, json_out, plots, figure_fn=None, options=None):
    """Shared ending of the calculator commands: write outputs, print JSON or a table."""
    from .pipelines.calculators import write_calc_outputs

    out_dir = out or _default_out(result.command, Path(result.source) if result.source else Path("options"))
    fig = figure_fn() if (plots and figure_fn) else None
    written = write_calc_outputs(result, out_dir, fig, options)
    if json_out:
        typer.echo(json.dumps(result.to_json(), indent=2, ensure_ascii=False))
        return
    from .report.console import calc_table

    _print([calc_table(result)], result.notes, written, out_dir)


@app.command()
def prism(
    data: Annotated[Optional[Path], typer.Argument(help="Optional CSV of cases: break_tension, friction_angle.",
                                                   show_default=False)] = None,
    break_tension: Annotated[Optional[str], typer.Option(help="Break tension sigma_b of the prism [kPa]; "
                                                         "any pressure unit, g/cm^2 read as gram-force.")] = None,
    friction_angle: Annotated[Optional[float], typer.Option(help="Friction angle rho of the sand [deg].")] = None,
    gamma_w: Annotated[str, typer.Option(help="Unit weight of water [kN/m^3].")] = "9.81",
    out: OutOpt = None,
    json_out: JsonOpt = False,
    sample: SampleOpt = False,
):
    """Bernatzik's prism test: maximal capillary pressure
    P_kmax = sigma_b (1 - sin rho)/(2 sin rho) and capillary rise h_c = P_kmax/gamma_w.

    Example: capred prism --break-tension "115 g/cm^2" --friction-angle 36
    """
    try:
        from .pipelines.calculators import run_prism

        notes: list[str] = []
        src = _source(data, sample, "prism") if (data or sample) else None
        result = run_prism(src, _quantity(break_tension, "kPa", "pressure", "--break-tension", notes), friction_angle,
                           _quantity(gamma_w, "kN/m^3", "unit_weight", "--gamma-w"))
        result.notes[:0] = notes
        _calc_done(result, out, json_out, False, options={"break_tension": break_tension,
                                                          "friction_angle": friction_angle, "gamma_w": gamma_w})
    except CapredError as exc:
        fail(exc)


@app.command("skempton-b")
def skempton_b(
    data: Annotated[Optional[Path], typer.Argument(help="Optional CSV of cases: S_r (or B), and any of kappa, e0, "
                                                   "p0, u0, pa0.", show_default=False)] = None,
    sr: Annotated[Optional[float], typer.Option("--sr", help="Degree of saturation S_r [-]: compute B.")] = None,
    b: Annotated[Optional[float], typer.Option("--b", help="Measured B [-]: compute S_r.")] = None,
    kappa: Annotated[float, typer.Option(help="Slope of the elastic line in e-ln p'.")] = 0.006,
    e0: Annotated[float, typer.Option(help="Initial void ratio.")] = 0.8,
    p0: Annotated[str, typer.Option(help="Mean total stress [kPa].")] = "100",
    u0: Annotated[str, typer.Option(help="Initial pore pressure [kPa].")] = "30",
    pa0: Annotated[str, typer.Option(help="Absolute initial air pressure [kPa].")] = "130",
    se: Annotated[Optional[str], typer.Option("--se", help="Air-entry suction s_e [kPa] (Brooks-Corey): "
                                              "simulation with suction equilibrium.")] = None,
    bc_alpha: Annotated[Optional[float], typer.Option(help="Brooks-Corey index alpha, with --se.")] = None,
    out: OutOpt = None,
    json_out: JsonOpt = False,
    plots: PlotOpt = True,
    sample: SampleOpt = False,
):
    """Skempton's B against degree of saturation (Morvan et al., eq. 10):
    B = 1/(1 + p'0 e0 (1 - S_r)/(kappa P_a0)) with p'0 = p0 - u0, or its inverse
    S_r from a measured B; with --se and --bc-alpha, the simulation with suction
    equilibrium (p'0 = p0 - u_a0 + s S_r). Defaults are the seed's Table 1.

    Example: capred skempton-b --sr 0.9 --kappa 0.06
    """
    try:
        from .pipelines.calculators import run_skempton_b
        from .report.calculator_figures import figure_skempton

        src = _source(data, sample, "skempton-b") if (data or sample) else None
        kw = dict(kappa=kappa, e0=e0, p0=_quantity(p0, "kPa", "pressure", "--p0"),
                  u0=_quantity(u0, "kPa", "pressure", "--u0"), pa0=_quantity(pa0, "kPa", "pressure", "--pa0"))
        s_e = _quantity(se, "kPa", "pressure", "--se")
        result = run_skempton_b(src, sr=sr, b=b, s_e=s_e, bc_alpha=bc_alpha, **kw)
        pts = (result.inputs.get("S_r", result.outputs.get("S_r")), result.inputs.get("B", result.outputs.get("B")))
        _calc_done(result, out, json_out, plots,
                   lambda: figure_skempton(s_e=s_e, bc_alpha=bc_alpha, points=pts, **kw),
                   options={**kw, "sr": sr, "b": b, "se": s_e, "bc_alpha": bc_alpha})
    except CapredError as exc:
        fail(exc)


@app.command()
def rumpf(
    data: Annotated[Optional[Path], typer.Argument(help="Optional CSV of cases (shape_factor, void_ratio, S_r, "
                                                   "diameter, surface_tension, contact_angle).",
                                                   show_default=False)] = None,
    shape_factor: Annotated[Optional[float], typer.Option(help="Particle shape factor phi [-].")] = None,
    void_ratio: Annotated[Optional[float], typer.Option(help="Void ratio e [-].")] = None,
    sr: Annotated[Optional[float], typer.Option("--sr", help="Degree of saturation S_r [-].")] = None,
    diameter: Annotated[Optional[str], typer.Option(help="Apparent particle diameter d_p [mm].")] = None,
    surface_tension: Annotated[str, typer.Option(help="Surface tension gamma [N/m].")] = "0.0728",
    contact_angle: Annotated[float, typer.Option(help="Wetting angle theta [deg].")] = 0.0,
    out: OutOpt = None,
    json_out: JsonOpt = False,
    sample: SampleOpt = False,
):
    """Rumpf's capillary pressure p_cap = -(6/phi)(S_r/e)(gamma/d_p) cos(theta)
    (Prunier et al. 2024, eq. 19); negative means tension.

    Example: capred rumpf --shape-factor 1 --void-ratio 0.5 --sr 0.3 --diameter 0.2
    """
    try:
        from .pipelines.calculators import run_rumpf

        src = _source(data, sample, "rumpf") if (data or sample) else None
        result = run_rumpf(src, shape_factor, void_ratio, sr, _quantity(diameter, "mm", "length", "--diameter"),
                           _quantity(surface_tension, "N/m", "surface_tension", "--surface-tension"), contact_angle)
        _calc_done(result, out, json_out, False, options={"shape_factor": shape_factor, "void_ratio": void_ratio,
                                                          "sr": sr, "diameter": diameter,
                                                          "surface_tension": surface_tension,
                                                          "contact_angle": contact_angle})
    except CapredError as exc:
        fail(exc)


def _print(tables, notes, written, out_dir) -> None:
    con = _console()
    for t in tables:
        con.print(t)
    from rich.markup import escape

    for note in notes:
        con.print(f"[yellow]note:[/] {escape(note)}")
    con.print(f"Wrote {len(written)} files to [bold]{out_dir}[/]")


def _model_list(text: str) -> tuple[str, ...]:
    from .errors import OptionError
    from .physics.shear import EXTRA_MODELS, MODELS

    out: list[str] = []
    for name in (t.strip().lower().replace("-", "_") for t in text.split(",") if t.strip()):
        expand = {"thesis": MODELS, "all": MODELS + EXTRA_MODELS}.get(name, (name,))
        for m in expand:
            if m not in MODELS + EXTRA_MODELS:
                raise OptionError(f"--models: unknown model '{m}'; choose from {', '.join(MODELS + EXTRA_MODELS)}")
            if m not in out:
                out.append(m)
    if not out:
        raise OptionError("--models: no model named")
    return tuple(out)


def _model_params(retention: Optional[Path], **kw):
    from .pipelines.shear import ModelParams, model_params_from_retention

    if retention is not None:
        return model_params_from_retention(retention, **kw)
    return ModelParams(**{k: v for k, v in kw.items() if v is not None})


def _envelope_pair(text: Optional[str]):
    from .errors import OptionError

    if text is None:
        return None
    try:
        c, phi = (float(x) for x in text.split(","))
    except ValueError:
        raise OptionError(f"--water-envelope '{text}': expected 'c,phi' in kPa and degrees") from None
    return c * 1e3, phi


def _sources(data: Optional[list[Path]], sample: bool, command: str) -> list[Path]:
    """Input files: the arguments with globs expanded (sorted), or the bundled sample."""
    import glob

    from .errors import InputError, Problem

    if sample or not data:
        return [_source(data[0] if data else None, sample, command)]
    out: list[Path] = []
    for p in data:
        text = str(p)
        if any(ch in text for ch in "*?[") and not p.exists():
            hits = sorted(glob.glob(text, recursive=True))
            if not hits:
                raise InputError(Problem(text, None, None, "no file matches this pattern"))
            out += [Path(h) for h in hits]
        else:
            out.append(p)
    return out


def _source(data: Optional[Path], sample: bool, command: str) -> Path:
    from .errors import OptionError
    from .samples import sample_path

    if sample and data is not None:
        raise OptionError("give a data file or --sample, not both")
    if sample:
        return sample_path(command)
    if data is None:
        raise OptionError(f"no data file given (try: capred {command} --sample)")
    return data


def main() -> None:
    app(prog_name="capred")


if __name__ == "__main__":
    main()
