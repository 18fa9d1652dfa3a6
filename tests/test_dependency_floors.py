"""The floors of capred's direct dependencies (issue 32, item 8): constraints-floors.txt pins exactly the lowest
version pyproject.toml allows for each, so that .ci/run's second venv tests what a user may really have."""

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _floors_in_pyproject() -> dict[str, str]:
    deps = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    out = {}
    for d in deps:
        m = re.fullmatch(r"([A-Za-z0-9_.\-]+)\s*>=\s*([0-9][0-9.]*)", d.strip())
        assert m, f"dependency '{d}' has no plain '>=' floor: .ci/run cannot test its lowest version"
        out[m.group(1).lower()] = m.group(2)
    return out


def _pins() -> dict[str, str]:
    out = {}
    for line in (ROOT / "constraints-floors.txt").read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            name, _, version = line.partition("==")
            out[name.strip().lower()] = version.strip()
    return out


def test_every_dependency_is_pinned_at_its_floor():
    from packaging.version import Version  # a dependency of matplotlib

    floors, pins = _floors_in_pyproject(), _pins()
    assert set(pins) == set(floors)
    assert {k: Version(v) for k, v in pins.items()} == {k: Version(v) for k, v in floors.items()}


def test_ci_installs_the_floors_and_runs_the_suite_against_them():
    ci = (ROOT / ".ci" / "run").read_text()
    assert "constraints-floors.txt" in ci
    assert ci.count("-m pytest") >= 3  # newest: everyday + slow; floors: everyday
