"""The Rust fix assembler against the shared fix vectors and against Python on gpsd's logs, through
the `fixes` verb of the nmea-rs tool (one JSON object per epoch, the members of Fix.to_dict).

The tool is NMEA_TOOLS's (make test-tools: build/test-bin), else `make build/test-bin/nmea-rs`
builds it here (and nmea-py beside it). On the logs the two tools print the same bytes: the same
epochs, each fact the same value (doubles the same bits: both sides convert the wire text to the
nearest double and scale it by the same factor), written alike.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any

import pytest

from . import gpsd_oracle
from .gpsd_oracle import CORPUS, ROOT
from .test_vectors import VECTORS, same
from nmeaspec.fixes import fixes


@pytest.fixture(scope="module")
def nmea_rs() -> Path:
    tools = os.environ.get("NMEA_TOOLS")
    if tools:
        return Path(tools) / "nmea-rs"
    subprocess.run(["make", "--no-print-directory", "-s", "build/test-bin/nmea-rs", "build/test-bin/nmea-py"],
                   cwd=ROOT, check=True)
    return ROOT / "build" / "test-bin" / "nmea-rs"


def rust_fixes(tool: Path, data: bytes) -> list[dict[str, Any]]:
    out = subprocess.run([str(tool), "fixes"], input=data, capture_output=True, check=True).stdout
    return [json.loads(line) for line in out.decode("ascii").splitlines()]


def neutral(fix: dict[str, Any]) -> dict[str, Any]:
    """A fix of the tool in the vectors' form: with the two satellite counts (Fix.used_count and
    Fix.in_view_count)."""
    in_view = {(s["system"], s["id"]) for s in fix["in_view"]}
    return {**fix, "used_count": sum(len(ids) for ids in fix["used"].values()), "in_view_count": len(in_view)}


@pytest.mark.parametrize("vector", VECTORS, ids=[v["where"][:40] for v in VECTORS])
def test_fix_vector(nmea_rs: Path, vector: dict[str, Any]) -> None:
    got = [neutral(fix) for fix in rust_fixes(nmea_rs, "".join(f"{line}\r\n" for line in vector["lines"]).encode())]
    assert len(got) == len(vector["fixes"])
    for number, (fix, want) in enumerate(zip(got, vector["fixes"]), 1):
        for fact, value in want.items():
            assert same(fix[fact], value), f"fix {number}, {fact}: {fix[fact]!r}, the vector says {value!r}"


@pytest.mark.parametrize("log", gpsd_oracle.logs())
def test_rust_agrees_with_python(nmea_rs: Path, log: str) -> None:
    """The two tools' `fixes` output on the log, byte for byte."""
    data = (CORPUS / f"{log}.nmea").read_bytes()
    rust = subprocess.run([str(nmea_rs), "fixes"], input=data, capture_output=True, check=True).stdout
    python = subprocess.run([str(nmea_rs.parent / "nmea-py"), "fixes"], input=data, capture_output=True,
                            check=True).stdout
    assert rust.count(b"\n") == python.count(b"\n")
    for number, (got, want) in enumerate(zip(rust.splitlines(), python.splitlines()), 1):
        assert got == want, f"fix {number}:\n  Rust {got!r}\nPython {want!r}"
