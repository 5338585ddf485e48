"""Keep the first N lines of each kind of a tool's JSON output (a sentence and variant, or an error
kind): every kind the whole input has, in a few lines, for a checker too slow for all of it
(valgrind).   python3 tools/distinct_lines.py N < decoded.jsonl > sample.jsonl"""

from __future__ import annotations

import json
import sys
from collections import Counter


def kind(record: dict) -> tuple:
    if record.get("ok"):
        return ("ok", record.get("sentence"), record.get("variant"), record.get("address"))
    return ("error", record.get("error", {}).get("kind"), record.get("error", {}).get("address"))


def main() -> None:
    keep = int(sys.argv[1])
    seen: Counter[tuple] = Counter()
    for line in sys.stdin:
        key = kind(json.loads(line))
        seen[key] += 1
        if seen[key] <= keep:
            sys.stdout.write(line)


if __name__ == "__main__":
    main()
