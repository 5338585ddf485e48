"""The real-log lines of some sentences, and how the spec decodes them.

    python3 tools/corpus_lines.py MWV DBT        # every checksum-valid line whose formatter is MWV or DBT
    python3 tools/corpus_lines.py --failing XDR  # only those that do not decode with the spec

For each sentence id: how many checksum-valid lines of ../shared/corpus/real carry it, how many
decode with the reference decoder (generator/reference.py, straight from spec/: no generation
needed), the distinct field counts and talkers seen, and the lines that fail with the reason.
Use it when you write or change a sentence file, to take examples from the wire and to see the
dialects real equipment sends. Standard ids match the formatter after any talker ID; ids that
start with P (proprietary) match the whole address.
"""

from __future__ import annotations

import argparse
import collections
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from generator import reference  # noqa: E402
from generator.build import load_spec  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "real"


def checksum_valid(line: str) -> bool:
    """A `$` or `!` line of printable ASCII whose two-digit checksum matches."""
    star = line.find("*")
    if line[:1] not in ("$", "!") or star < 0 or len(line) != star + 3 or not all(" " <= c <= "~" for c in line):
        return False
    return line[star + 1:].upper() == f"{reference.rt.checksum(line[1:star]):02X}"


def sentence_id(line: str) -> str:
    address = line[1:].split(",", 1)[0].split("*", 1)[0]
    return address if address.startswith("P") else address[2:]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("ids", nargs="+", help="sentence ids (MWV) or proprietary addresses (PGRME)")
    parser.add_argument("--failing", action="store_true", help="print only the lines that do not decode")
    parser.add_argument("--show", type=int, default=5, help="decoded lines to print per id (default 5)")
    args = parser.parse_args()
    wanted = {i.upper() for i in args.ids}
    spec = load_spec(ROOT / "spec")
    seen: dict[str, list[tuple[str, str]]] = collections.defaultdict(list)
    for path in sorted(CORPUS.glob("*/*.nmea")):
        for raw in path.read_bytes().split(b"\n"):
            line = raw.rstrip(b"\r").decode("latin-1")
            if checksum_valid(line) and sentence_id(line) in wanted:
                seen[sentence_id(line)].append((str(path.relative_to(CORPUS)), line))
    for sid in sorted(wanted):
        lines = seen.get(sid, [])
        ok, failures, counts, talkers = [], [], collections.Counter(), collections.Counter()
        for name, line in lines:
            counts[line.count(",")] += 1
            talkers[line[1:3]] += 1
            try:
                decoded = reference.decode(spec, line)
            except reference.rt.NmeaError as err:
                failures.append((name, line, str(err)))
                continue
            if decoded.sentence is None:
                failures.append((name, line, "not typed: the spec has no such sentence"))
            else:
                ok.append((name, line))
        print(f"== {sid}: {len(lines)} checksum-valid lines, {len(ok)} decode; "
              f"fields {dict(sorted(counts.items()))}; talkers {dict(talkers.most_common())}")
        if not args.failing:
            for name, line in ok[:args.show]:
                print(f"  ok   {name}: {line}")
        for name, line, why in failures[:50]:
            print(f"  FAIL {name}: {line}\n       {why}")
        if len(failures) > 50:
            print(f"  ... and {len(failures) - 50} more failures")
    return 0


if __name__ == "__main__":
    sys.exit(main())
