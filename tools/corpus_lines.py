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
import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from generator import reference  # noqa: E402
from generator.build import load_spec  # noqa: E402
from generator.errors import SpecErrors  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "real"


def checksum_valid(line: str) -> bool:
    star = line.find("*")
    if line[:1] not in ("$", "!") or star < 0 or len(line) != star + 3:
        return False
    try:
        value = int(line[star + 1:], 16)
    except ValueError:
        return False
    check = 0
    for char in line[1:star]:
        check ^= ord(char)
    return check == value and all(" " <= c <= "~" for c in line)


def sentence_id(line: str) -> str:
    address = line[1:].split(",", 1)[0].split("*", 1)[0]
    return address if address.startswith("P") else address[2:]


def load_spec_skipping_broken(wanted: set[str]):
    """The spec; while files are being written (by several people at once), a copy of it without
    the sentence files that do not load, so that the others can still be checked. The problems of
    the files of the `wanted` sentences are printed."""
    try:
        return load_spec(ROOT / "spec")
    except SpecErrors as errors:
        problems = errors.errors
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / "spec"
        shutil.copytree(ROOT / "spec", copy)
        for _ in range(20):
            broken = {Path(str(e).split(":", 1)[0]).name for e in problems}
            for name in sorted(broken):
                if name.removesuffix(".yaml").upper() in wanted:
                    print(f"spec problems in {name}:", *[f"  {e}" for e in problems if Path(str(e).split(':', 1)[0]).name == name],
                          sep="\n")
                for path in copy.glob(f"*/{name}"):
                    if path.parent.name in ("standard", "proprietary"):
                        path.unlink()
            try:
                return load_spec(copy)
            except SpecErrors as errors:
                problems = errors.errors
    raise SystemExit("the spec does not load: " + "; ".join(str(e) for e in problems[:5]))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("ids", nargs="+", help="sentence ids (MWV) or proprietary addresses (PGRME)")
    parser.add_argument("--failing", action="store_true", help="print only the lines that do not decode")
    parser.add_argument("--show", type=int, default=5, help="decoded lines to print per id (default 5)")
    args = parser.parse_args()
    wanted = {i.upper() for i in args.ids}
    spec = load_spec_skipping_broken(wanted)
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
