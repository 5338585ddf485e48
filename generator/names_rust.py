"""Rust identifiers: how the spec's ids become the names of the generated crate, and which two
things of a spec (or a thing and the runtime) would share one."""

from __future__ import annotations

import re

from .model import BitValue, Bits, Group, Layout, Origin, Parameter, Sentence, Spec
from .names import NameClaims
from .paths import ROOT

KEYWORDS = {
    "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for", "if", "impl",
    "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return", "self", "static", "struct",
    "super", "trait", "true", "type", "unsafe", "use", "where", "while", "async", "await", "dyn", "abstract",
    "become", "box", "do", "final", "macro", "override", "priv", "typeof", "unsized", "virtual", "yield", "try",
    "gen",
}

# Names the sentence modules import from the runtime; generated type names must differ.
def _runtime_exports() -> set[str]:
    """The type names runtime/mod.rs exports (`pub use module::{A, B};`), read from it."""
    text = (ROOT / "runtime" / "rust" / "src" / "mod.rs").read_text(encoding="utf-8")
    names = set()
    for group in re.findall(r"pub use \w+::\{([^}]*)\}", text):
        names |= {n.strip() for n in group.split(",") if n.strip()[:1].isupper()}
    return names


# Names the sentence modules and lib.rs use, which generated type names must not take: the
# runtime's exports, lib.rs's own types and the prelude's.
RUNTIME_NAMES = _runtime_exports() | {"Sentence", "Generic", "LayoutId", "Option", "Result", "Self", "Parsed",
                                      "Options", "Framer", "Item"}


def ident(name: str) -> str:
    """A Rust identifier for a spec id (raw when it is a keyword)."""
    if name in ("self", "super", "crate", "Self"):
        return name + "_"
    return f"r#{name}" if name in KEYWORDS else name


def entry_name(sentence: Sentence, layout: Layout, group: Group) -> str:
    word = group.camel
    return sentence.layout_camel(layout) + (word[:-1] if word.endswith("s") else word + "Entry")


def bits_const(bits: Bits, value: BitValue) -> str:
    """A named value of some bits, an associated constant of its bitfield's type."""
    return f"{bits.id}_{value.id}".upper()


def parameter_const(p: Parameter) -> str:
    """A parameter of a table, a constant of its module."""
    return p.id.upper()


def clashes(spec: Spec) -> list[tuple[Origin, str]]:
    """The Rust names built from the spec's ids that two things, or a thing and the runtime, would
    share."""
    names = NameClaims("Rust")
    names.owners.update({name: "the runtime" for name in RUNTIME_NAMES})
    for e in spec.enums:
        names.claim(e.camel, f"enum {e.id}", e.origin)
    for s in spec.sentences:
        for lay in s.layouts:
            names.claim(s.layout_camel(lay), f"layout {s.layout_snake(lay)}", lay.origin)
            g = lay.group
            if g is not None and not g.single:  # the layouts of a sentence may share an entry type
                names.claim(entry_name(s, lay, g), f"the entries of group {g.id} of sentence {s.id}", g.origin)
    for b in spec.bitfields:
        names.claim(b.camel, f"bitfield {b.id}", b.origin)
        constants = NameClaims("Rust")
        for bits in b.bits:
            for v in bits.values:
                constants.claim(bits_const(bits, v), f"value {v.id} of bits {bits.id} of bitfield {b.id}",
                                bits.origin)
        names.clashes += constants.clashes
    for t in spec.tables:
        for param in t.parameters:
            if parameter_const(param) == "TABLE":
                names.clashes.append((param.origin, f"parameter {param.id} of table {t.id} would be named TABLE, the "
                                      "name of the table itself"))
    return names.clashes
