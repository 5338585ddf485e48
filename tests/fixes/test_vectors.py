"""The fix vectors every language's assembler must reproduce (generated/vectors/fixes.jsonl, from
the examples of spec/fix.yaml): per stream, the fixes in order with the facts each names."""

from __future__ import annotations

import json
from typing import Any

import pytest

from .gpsd_oracle import ROOT
from nmeaspec.fixes import Fix, fixes

VECTORS = [json.loads(line) for line in (ROOT / "generated" / "vectors" / "fixes.jsonl").open(encoding="utf-8")]


def neutral(fix: Fix) -> dict[str, Any]:
    """A fix in the vectors' form: Fix.to_dict() and the two satellite counts."""
    return {**fix.to_dict(), "used_count": fix.used_count, "in_view_count": fix.in_view_count}


def same(got: Any, want: Any) -> bool:
    if isinstance(want, float) and isinstance(got, (int, float)):
        return abs(got - want) <= 1e-6
    return bool(got == want)


@pytest.mark.parametrize("vector", VECTORS, ids=[v["where"][:40] for v in VECTORS])
def test_fix_vector(vector: dict[str, Any]) -> None:
    got = [neutral(fix) for fix in fixes(vector["lines"])]
    assert len(got) == len(vector["fixes"])
    for number, (fix, want) in enumerate(zip(got, vector["fixes"]), 1):
        for fact, value in want.items():
            assert same(fix[fact], value), f"fix {number}, {fact}: {fix[fact]!r}, the vector says {value!r}"
