"""The Rust crate's cargo features: one per receiver family with sentences of its own (its manual
id), all on by default. A vendor's sentences, commands, and the enums, registers and parameter
tables only they use compile only with its feature; without it their lines parse as `Generic`."""

from __future__ import annotations

from .model import Sentence, Spec


def vendor_features(spec: Spec) -> list[str]:
    """The manual ids that own a proprietary sentence, in manual order."""
    owners = {s.vendor for s in spec.proprietary}
    return [m.id for m in spec.manuals if m.id in owners]


def cfg(vendors: set[str] | None) -> str:
    """The attribute that compiles an item with any of `vendors`; "" for an item always compiled."""
    if not vendors:
        return ""
    features = sorted(vendors)
    if len(features) == 1:
        return f'#[cfg(feature = "{features[0]}")]'
    one = "#[cfg(any(" + ", ".join(f'feature = "{f}"' for f in features) + "))]"
    if len(one) <= 120:
        return one
    # As rustfmt writes it (items at the top level, where long ones occur).
    return "\n".join(["#[cfg(any(", *(f'    feature = "{f}",' for f in features[:-1]), f'    feature = "{features[-1]}"', "))]"])


class Gates:
    """The vendors each generated item belongs to; None: always compiled."""

    def __init__(self, spec: Spec) -> None:
        self.features = vendor_features(spec)
        feature_set = set(self.features)
        users: dict[str, list[set[str] | None]] = {}

        def use(key: str, vendors: set[str] | None) -> None:
            users.setdefault(key, []).append(vendors)

        for s in spec.sentences:
            for layout in s.layouts:
                for f in layout.all_fields:
                    if f.enum is not None:
                        use("enum:" + f.enum.id, self.sentence_vendors(s))
                    if f.bitfield is not None:
                        use("bitfield:" + f.bitfield.id, self.sentence_vendors(s))
        self.tables = {t.id: (set(t.manuals) & feature_set) or None for t in spec.tables}
        for t in spec.tables:
            for p in t.parameters:
                if p.enum is not None:
                    use("enum:" + p.enum.id, self.tables[t.id])
                if p.bitfield is not None:
                    use("bitfield:" + p.bitfield.id, self.tables[t.id])
        self._items: dict[str, set[str] | None] = {}
        for key, owners in users.items():
            self._items[key] = None if any(o is None for o in owners) else set().union(*owners)  # type: ignore[arg-type]

    @staticmethod
    def sentence_vendors(s: Sentence) -> set[str] | None:
        return {s.vendor} if s.vendor else None

    def sentence(self, s: Sentence) -> str:
        return cfg(self.sentence_vendors(s))

    def enum(self, enum_id: str) -> str:
        return cfg(self._items.get("enum:" + enum_id))

    def bitfield(self, bitfield_id: str) -> str:
        return cfg(self._items.get("bitfield:" + bitfield_id))

    def table(self, table_id: str) -> str:
        return cfg(self.tables[table_id])

    def union(self, attributes: list[str]) -> str:
        """The attribute that compiles what any of the items behind `attributes` needs."""
        if not attributes or any(not a for a in attributes):
            return ""
        return cfg({f for a in attributes for f in self.features if f'"{f}"' in a})


def with_cfg(indent: int, attribute: str, lines: list[str]) -> list[str]:
    """`lines` (a match arm, an array item) preceded by the attribute, when there is one."""
    return ([" " * indent + attribute] if attribute else []) + lines
