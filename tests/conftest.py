import hashlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
# public retention datasets with published fits (sources and licences: tests/data/retention/README.md)
RETENTION_DATA = ROOT / "tests" / "data" / "retention"


def file_hash(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


@pytest.fixture
def write_csv(tmp_path):
    """Write a CSV text into tmp_path and return its path."""

    def _write(text: str, name: str = "data.csv") -> Path:
        p = tmp_path / name
        p.write_text(text)
        return p

    return _write
