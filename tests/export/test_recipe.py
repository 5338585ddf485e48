"""docs/export.md's recipe for archives, run as written: the Python block of the page, as a
script in a directory with an archive of real logs, with Dask in local mode."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pyarrow as pa
import pyarrow.parquet as pq

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec.apps.nmea_cli import main  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "real"
PAGE = ROOT / "docs" / "export.md"


def recipe() -> str:
    (block,) = [b for b in re.findall(r"```python\n(.*?)```", PAGE.read_text(encoding="utf-8"), re.S)
                if "dask" in b]
    return block


def test_the_recipe_gives_the_tables_of_one_export(tmp_path: Path) -> None:
    archive = tmp_path / "archive"
    logs = sorted((CORPUS / "gpsd").glob("*.nmea"))[:12] + sorted((CORPUS / "pynmeagps").glob("*.nmea"))[:4]
    for n, log in enumerate(logs):  # in subdirectories, as archives are
        target = archive / f"day-{n % 3}" / log.name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(log, target)
    (tmp_path / "recipe.py").write_text(recipe(), encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=str(ROOT / "generated" / "python"))
    done = subprocess.run([sys.executable, "recipe.py"], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    parts = sorted((tmp_path / "tables").glob("part-*"))
    assert len(parts) == 8

    ordered = sorted(str(p.relative_to(tmp_path)) for p in archive.rglob("*.nmea"))
    whole = tmp_path / "whole"
    assert main(["export", "-q", *(str(tmp_path / p) for p in ordered), "-o", str(whole)]) == 0
    for table in ("fixes", "GGA", "GSV", "errors"):
        together = pq.read_table(whole / f"{table}.parquet")
        pieces = [pq.read_table(p) for p in sorted(tmp_path.glob(f"tables/part-*/{table}.parquet"))]
        spread = pa.concat_tables(pieces)
        key = ["log", "first_line"] if table == "fixes" else ["log", "line"]
        assert spread.sort_by([(k, "ascending") for k in key]).to_pylist() == \
            together.sort_by([(k, "ascending") for k in key]).to_pylist(), table
    fixes = pq.read_table(whole / "fixes.parquet").num_rows
    assert done.stdout == f"{fixes} fixes from {len(logs)} logs\n"
