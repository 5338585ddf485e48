"""The C assembler (nmea_fix_feed, through `nmea-c fixes`, built here from generated/c) against
the fix vectors (generated/vectors/fixes.jsonl, as test_vectors.py holds Python to them) and
against the Python assembler on every gpsd log of tests/fixes: per epoch, the same JSON text as
the Python tool's `fixes` verb prints (Fix.to_dict), so doubles compared exactly (the same bits:
both compute them with the same double operations from the same digits, and print the shortest
text that reads back to them)."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any

import pytest

from .gpsd_oracle import CORPUS, ROOT, logs
from .test_vectors import VECTORS, same
from nmeaspec.fixes import fixes


@pytest.fixture(scope="module")
def c_tool(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The nmea-c of $NMEA_TOOLS (make test-tools), else one built here unoptimized (the tests
    need answers, not speed)."""
    if os.environ.get("NMEA_TOOLS"):
        return Path(os.environ["NMEA_TOOLS"]) / "nmea-c"
    tool = tmp_path_factory.mktemp("fixes-c") / "nmea-c"
    cc = os.environ.get("CC", "cc")
    subprocess.run([cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O0", "-o", str(tool),
                    *(str(ROOT / "generated" / "c" / name) for name in ("nmea.c", "nmea_ais.c", "nmea_ubx.c", "nmea_rtcm3.c",
                                                                     "nmea_tool.c"))],
                   check=True)
    return tool


def c_fixes(tool: Path, data: bytes) -> list[str]:
    out = subprocess.run([str(tool), "fixes"], input=data, capture_output=True, check=True).stdout
    return out.decode("latin-1").splitlines()


def with_counts(fix: dict[str, Any]) -> dict[str, Any]:
    """A fix's JSON in the vectors' form: Fix.used_count and Fix.in_view_count added."""
    in_view = {(s["system"], s["id"]) for s in fix["in_view"]}
    return {**fix, "used_count": sum(len(ids) for ids in fix["used"].values()), "in_view_count": len(in_view)}


@pytest.mark.parametrize("vector", VECTORS, ids=[v["where"][:40] for v in VECTORS])
def test_c_fix_vector(c_tool: Path, vector: dict[str, Any]) -> None:
    got = [with_counts(json.loads(fix)) for fix in c_fixes(c_tool, "\n".join(vector["lines"]).encode("latin-1") + b"\n")]
    assert len(got) == len(vector["fixes"])
    for number, (fix, want) in enumerate(zip(got, vector["fixes"]), 1):
        for fact, value in want.items():
            assert same(fix[fact], value), f"fix {number}, {fact}: {fix[fact]!r}, the vector says {value!r}"


@pytest.mark.parametrize("log", logs())
def test_c_fixes_agree_with_python(c_tool: Path, log: str) -> None:
    path = CORPUS / f"{log}.nmea"
    with open(path, encoding="latin-1", newline="") as lines:
        want = [json.dumps(fix.to_dict(), separators=(",", ":")) for fix in fixes(lines)]
    got = c_fixes(c_tool, path.read_bytes())
    assert len(got) == len(want)
    for number, (fix, expected) in enumerate(zip(got, want), 1):
        assert fix == expected, f"{log}, epoch {number}"
