"""The three `stream` verbs read a stream in bounded memory: their peak resident memory on an
8 MB stream (real lines, garbage, NULs, overlong lines, and a last line that never ends) is the
one they have on a 2 MB stream. `make fuzz-memory` runs the same with 1 GB (fuzz/bounded_memory.py)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "fuzz"))

import bounded_memory  # noqa: E402

SLACK_MB = 4.0  # a reader that kept its input would grow by 6 MB


def test_the_measure_sees_a_reader_that_keeps_its_input() -> None:
    """A reader that keeps all it reads grows with its input: the measure must show it."""
    lines = bounded_memory.real_lines()
    keeping = [sys.executable, "-c", "import sys; data = sys.stdin.buffer.read(); print(len(data))"]
    small = bounded_memory.run("keeping", 2 << 20, lines, keeping)
    big = bounded_memory.run("keeping", 32 << 20, lines, keeping)
    assert big.peak_mb > small.peak_mb + 24, (small, big)


def test_stream_verbs_keep_their_memory() -> None:
    result = subprocess.run([sys.executable, str(ROOT / "fuzz" / "bounded_memory.py"), "--size", "2M", "--size", "8M",
                             "--slack", str(SLACK_MB)], capture_output=True, text=True, timeout=600)
    print(result.stdout)
    assert result.returncode == 0, result.stdout + result.stderr
    rows = [line for line in result.stdout.splitlines() if line.startswith("| nmea-")]
    assert len(rows) == 6, result.stdout
