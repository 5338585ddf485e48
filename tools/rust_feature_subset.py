"""The `--only` selector of the crate `make test` checks each receiver feature on (test-rust-lint).

A receiver feature on its own must compile without a warning: its gates (generator/rust_features.py)
must leave nothing unused and nothing missing. Those gates depend only on which sentences and
tables use an item: an enum or bitfield that a standard sentence uses is always compiled, one that
only receivers' sentences use compiles with their features. So every proprietary sentence plus,
for each item that both kinds use, one standard sentence that uses it gives every gated item the
gate it has in the whole crate, while the checks no longer type-check the other standard sentences
(always compiled, never gated) once per feature.

    python3 tools/rust_feature_subset.py             # prints the selector
    python3 tools/rust_feature_subset.py --check DIR # DIR's crate gates its items as generated/rust does
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from generator.build import load_spec  # noqa: E402
from generator.model import Sentence  # noqa: E402
from generator.rust_features import vendor_features  # noqa: E402


def gated_items(sentence: Sentence) -> set[str]:
    """The enums and bitfields a sentence's layouts use, the things a feature gate can leave out."""
    used = set()
    for layout in sentence.layouts:
        for f in layout.all_fields:
            if f.enum is not None:
                used.add("enum:" + f.enum.id)
            if f.bitfield is not None:
                used.add("bitfield:" + f.bitfield.id)
    return used


def selector() -> str:
    spec = load_spec(ROOT / "spec")
    receivers = set().union(*(gated_items(s) for s in spec.proprietary))
    for table in spec.tables:
        receivers |= {"enum:" + p.enum.id for p in table.parameters if p.enum is not None}
        receivers |= {"bitfield:" + p.bitfield.id for p in table.parameters if p.bitfield is not None}
    standard = [(s.id, gated_items(s) & receivers) for s in spec.standard]
    shared = set().union(*(items for _, items in standard))
    chosen: list[str] = []
    while shared:  # greedy: the standard sentence that covers most of what is left
        sentence_id, items = max(standard, key=lambda pair: len(pair[1] & shared))
        chosen.append(sentence_id)
        shared -= items
    return ",".join(vendor_features(spec) + sorted(chosen))


# The files whose top-level items carry the gates of enums, bitfields, tables and sentence modules.
GATED_FILES = ("enums.rs", "bitfields.rs", "tables.rs", "sentences/mod.rs", "fix_fields.rs")
ITEM = re.compile(r"(?:pub )?(?:enum|struct|const|static|fn|mod|impl)\b.*")


def gates(source: str) -> dict[str, str]:
    """Each top-level item's first line and the cfg attribute right above it ("" for none)."""
    found: dict[str, str] = {}
    lines = source.split("\n")
    gate, i = "", 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("#[cfg("):
            gate = line
            while not gate.rstrip().endswith(")]"):
                i += 1
                gate += lines[i].strip()
        elif not line.startswith(("#[", "///")):
            if ITEM.fullmatch(line):
                found[line] = gate
            gate = ""
        i += 1
    return found


def check(crate: Path) -> list[str]:
    """What the crate at `crate` gates otherwise than the whole crate, or leaves out though gated."""
    problems = []
    for name in GATED_FILES:
        whole = gates((ROOT / "generated" / "rust" / "src" / name).read_text())
        subset = gates((crate / "src" / name).read_text())
        problems += [f"{name}: {item!r} is {gate or 'ungated'} here, {whole.get(item) or 'ungated'} in the whole crate"
                     for item, gate in subset.items() if whole.get(item, "") != gate]
        problems += [f"{name}: {item!r} ({gate}) is missing" for item, gate in whole.items()
                     if gate and item not in subset]
    return problems


if __name__ == "__main__":
    if sys.argv[1:2] == ["--check"]:
        differences = check(Path(sys.argv[2]))
        print("\n".join(differences) or f"{sys.argv[2]} gates every item as the whole crate does")
        sys.exit(1 if differences else 0)
    print(selector())
