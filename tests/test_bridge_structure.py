"""The bridge modules' structure (issue 28): no import circle, no private name across modules, CSV headers."""

import ast
import re
from pathlib import Path

import numpy as np

from capred.pipelines import bridge_solve as bs

PKG = Path(__file__).resolve().parents[1] / "capred"


def _imports(path: Path) -> set[str]:
    """Modules a file imports (relative imports resolved inside capred.pipelines)."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            mod = node.module or ""
            if node.level == 1:  # from . import x / from .x import y
                out |= {f"pipelines.{mod}"} if mod else {f"pipelines.{a.name}" for a in node.names}
            else:
                out.add(mod)
    return out


def test_no_import_circle_between_the_bridge_pipelines():
    solve = _imports(PKG / "pipelines" / "bridge_solve.py")
    blocks = _imports(PKG / "pipelines" / "bridge_blocks.py")
    assert "pipelines.bridge" not in solve and "pipelines.bridge_blocks" not in solve
    assert "pipelines.bridge" not in blocks  # bridge -> bridge_blocks -> bridge_solve, never back


def test_yade_files_uses_only_public_root_finders():
    text = (PKG / "pipelines" / "yade_files.py").read_text()
    assert re.findall(r"\bbr\._\w+", text) == []


def test_csv_headers_name_their_unit():
    assert bs.csv_header("r0_mm") == "r0 [mm]"
    assert bs.csv_header("V_w_mm3") == "V_w [mm^3]"
    assert bs.csv_header("area_mm2") == "area [mm^2]"
    assert bs.csv_header("S_R") == "S_R [-]"
    assert bs.csv_header("case") == "case"
    cols = {"F_cap_mN": np.array([1.0]), "status": np.array(["ok"], dtype=object)}
    assert list(bs.with_csv_headers(cols)) == ["F_cap [mN]", "status"]


def test_solve_columns_and_headers_come_from_the_typed_record():
    import dataclasses

    from capred.pipelines import bridge as pb
    from capred.pipelines.bridge_records import BridgeRecord
    from capred.samples import sample_path

    res = pb.solve_bridges(sample_path("bridge-solve"))
    rec = res.record()
    assert isinstance(rec, BridgeRecord)
    keys = [f.metadata["output"].json for f in dataclasses.fields(BridgeRecord)]
    assert list(res.columns()) == keys  # the JSON keys, in the record's order
    np.testing.assert_array_equal(res.columns()["F_cap_mN"], rec.F_cap)
    assert [h for h in res.csv_tables()["solve"] if h not in ("case", "status", "note")] == [
        BridgeRecord.csv_headers()[k] for k in keys
    ]
    assert "V_w [mm^3]" in res.csv_tables()["solve"] and "S_R [-]" in res.csv_tables()["solve"]


def _absolute(path: Path, node: ast.ImportFrom) -> str:
    """The module an ``from X import ...`` of ``path`` names, relative imports resolved."""
    if node.level == 0:
        return node.module or ""
    package = ["capred", *path.relative_to(PKG).parent.parts]
    return ".".join(package[: len(package) - node.level + 1] + ([node.module] if node.module else []))


def test_no_module_reads_a_private_name_of_the_bridge_physics():
    # issue 28 item 7: the root finders and solvers other modules need are public in capred.physics.bridge
    # (golden, illinois, suction_at_neck, solve_for_suction, ...); nothing outside it reads a `_name` of it
    import capred.physics.bridge as br

    private = {name for name in vars(br) if name.startswith("_") and not name.startswith("__")}
    found = []
    for path in PKG.rglob("*.py"):
        if path == PKG / "physics" / "bridge.py":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        aliases = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                module = _absolute(path, node)
                if module == "capred.physics.bridge":
                    found += [f"{path.name}: {a.name}" for a in node.names if a.name in private]
                elif module == "capred.physics":
                    aliases |= {a.asname or a.name for a in node.names if a.name == "bridge"}
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases:
                if node.attr in private:
                    found.append(f"{path.name}: {node.value.id}.{node.attr}")
    assert found == []
    assert {"golden", "illinois", "suction_at_neck"} <= set(vars(br))  # what yade_files used privately before


def test_absolute_resolves_relative_imports():
    # the detector above: yade_files' `from ..physics import bridge as br` names capred.physics
    node = ast.parse("from ..physics import bridge as br").body[0]
    assert _absolute(PKG / "pipelines" / "yade_files.py", node) == "capred.physics"
    node = ast.parse("from .bridge import _quad").body[0]
    assert _absolute(PKG / "physics" / "shear.py", node) == "capred.physics.bridge"
