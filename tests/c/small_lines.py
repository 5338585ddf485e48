"""The lines of the shared vectors whose sentence is one of the five-sentence firmware's (issue 32),
one a line, for tests/c/test_small.c: the examples (as the manuals print them and as corrected),
the tolerance cases and the edge cases of the agreement tests, each once."""

import json
import re
import sys
from pathlib import Path

FIVE = re.compile(r"^[$!][A-Z0-9]{2}(GGA|RMC|GSV|GSA|VTG)[,*]")


def main() -> int:
    root = Path(__file__).resolve().parents[2]
    seen: dict[str, None] = {}
    for name in ("examples", "tolerance"):
        for row in (json.loads(text) for text in (root / "generated" / "vectors" / f"{name}.jsonl").open(encoding="utf-8")):
            for key in ("raw", "line"):
                if isinstance(row.get(key), str):
                    seen.setdefault(row[key], None)
    for line in (root / "tests" / "agreement" / "edge_cases.txt").read_text(encoding="utf-8", errors="replace").splitlines():
        seen.setdefault(line, None)
    lines = [line for line in seen if FIVE.match(line) and "\n" not in line and "\r" not in line and line.isascii()]
    sys.stdout.write("".join(f"{line}\n" for line in lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
