"""`generate --only`: cut the model down to a subset before the emitters see it.

A selector is a comma-separated list of words, each one of:
  - `standard`: every standard sentence (GGA, RMC, ...);
  - a manual id of spec/manuals.yaml (`geos5`, `teseo`, `gs501`, `globalsat`, `comnav`): every
    proprietary sentence and command of that vendor;
  - a sentence or command id (`GGA`, `GEOS5_JAMDET`, `PSTMSETPAR`, case ignored);
  - a proprietary address or text command word (`GPSGG`, `PSTMSETPAR`, `PSRF100`): every item
    with that address;
  - a binary protocol (`ubx`, `sbf`, `skytraq`, `sirf`, `casic`, `rtcm3`): all its messages;
  - a binary message by its name in its protocol's documents or its spec id (`NAV-PVT`,
    `nav_pvt`: of every protocol that has one so named), or with its protocol (`ubx:NAV-PVT`,
    `casic:CFG-MSG`, `sbf:pvt_geodetic`, `rtcm3:1005`: an RTCM 3 message by number or id).
A command drags its replies along (a UBX SET its ACK-ACK and ACK-NAK, a poll the message it asks
for). Binary messages are all kept unless a word names a binary message or protocol; then only
those named and their replies are (a protocol none is named of is left out whole: the stream
readers still split its frames, which the tools show as frames, untyped), and the configuration
database only beside a CFG-VALSET, -VALGET or -VALDEL. A frame of a message left out is kept as
an unknown message of its protocol, with its payload. The subset keeps only the enums, bitfields
and parameter tables its items use and the manuals it cites (a standard sentence keeps the
examples of every manual: they are its tests), so that the code, the docs, the vectors and the
tests generated from it speak only of the subset.
"""

from __future__ import annotations

import copy

from .model import Field, Sentence, Spec


class SelectionError(ValueError):
    pass


def parse_selector(text: str) -> list[str]:
    words = [w.strip() for w in text.split(",") if w.strip()]
    if not words:
        raise SelectionError("--only needs at least one vendor, `standard`, sentence id or address")
    return words


def _binary_words(spec: Spec, words: list[str]) -> tuple[list[str], set[tuple[str, str]], set[str]]:
    """The words that name no binary message, and the binary messages (protocol, id) and RTCM 3
    messages (ids) the others name."""
    protocols = {p.id for p in spec.protocols}
    rest: list[str] = []
    binary: set[tuple[str, str]] = set()
    numbered: set[str] = set()
    for word in words:
        protocol, colon, name = word.lower().rpartition(":")
        if colon and protocol not in protocols:
            raise SelectionError(f"--only: unknown protocol {protocol!r} in {word!r} (give {', '.join(sorted(protocols))})")
        whole = not colon and name in protocols   # `ubx`: every message of the protocol
        if whole:
            hits = {(m.protocol, m.id) for m in spec.binary if m.protocol == name}
            rtcm3 = {m.id for m in spec.bit_messages if m.protocol == name}
        else:
            hits = {(m.protocol, m.id) for m in spec.binary
                    if protocol in ("", m.protocol) and name in (m.id, m.address.lower())}
            rtcm3 = {m.id for m in spec.bit_messages
                     if protocol == m.protocol and name in (m.id, *(str(t) for t in m.types))}
        if (colon or whole) and not (hits or rtcm3):
            raise SelectionError(f"--only: {protocol or name} has no message{f' {name!r}' if colon else 's'}")
        if not (hits or rtcm3):
            rest.append(word)
        binary |= hits
        numbered |= rtcm3
    return rest, binary, numbered


def _with_replies(spec: Spec, chosen: set[tuple[str, str]]) -> set[tuple[str, str]]:
    """The binary messages chosen and those whose layouts answer theirs (ACK-ACK, a polled message)."""
    owner = {(m.protocol, layout.id): (m.protocol, m.id) for m in spec.binary for layout in m.layouts}
    replies = {owner[(m.protocol, r)] for m in spec.binary if (m.protocol, m.id) in chosen
               for layout in m.layouts for r in layout.replies if (m.protocol, r) in owner}
    return chosen | replies


def selected_sentences(spec: Spec, words: list[str]) -> list[Sentence]:
    """The sentences the words name, in spec order; every unknown word is an error."""
    manual_ids = {m.id for m in spec.manuals}
    chosen: set[str] = set()
    unknown = []
    for word in words:
        lower, upper = word.lower(), word.upper()
        if lower == "standard":
            hits = [s for s in spec.sentences if not s.is_proprietary]
        elif lower in manual_ids:
            hits = [s for s in spec.sentences if s.is_proprietary and s.vendor == lower]
            if lower == "nmea0183":
                hits = [s for s in spec.sentences if not s.is_proprietary]
        else:
            hits = [s for s in spec.sentences
                    if s.id.upper() == upper or (s.address is not None and s.address.upper() == upper)]
        if not hits and lower not in manual_ids:
            unknown.append(word)
        chosen.update(s.id for s in hits)
    if unknown:
        known = ", ".join(["standard", *sorted(manual_ids - {"nmea0183"})])
        raise SelectionError(f"--only: unknown {', '.join(repr(w) for w in unknown)} "
                             f"(give {known}, a sentence id or an address)")
    # Commands bring their replies: a builder that pairs replies must be able to parse them.
    for s in spec.sentences:
        if s.id in chosen:
            chosen.update(r.id for r in s.replies)
    return [s for s in spec.sentences if s.id in chosen]


def _fields(sentence: Sentence) -> list[Field]:
    return [f for layout in sentence.layouts for f in layout.all_fields]


def subset(spec: Spec, words: list[str]) -> Spec:
    """A copy of the model holding only what the words select (see the module doc)."""
    words, binary, numbered = _binary_words(spec, words)
    keep_ids = {s.id for s in selected_sentences(spec, words)} if words else set()
    lowered = {w.lower() for w in words}
    model = copy.deepcopy(spec)
    sentences = [s for s in model.sentences if s.id in keep_ids]
    if binary or numbered:
        kept = _with_replies(model, binary)
        model.binary = [m for m in model.binary if (m.protocol, m.id) in kept]
        model.bit_messages = [m for m in model.bit_messages if m.id in numbered]
        if not any(m.protocol == db.protocol and m.id in ("cfg_valset", "cfg_valget", "cfg_valdel")
                   for db in model.config_keys for m in model.binary):
            model.config_keys = []

    # Manuals: the standard, every vendor named or owning a kept item, and the manuals the kept
    # examples come from (a standard sentence keeps the examples of every manual: they are its tests).
    vendors = {s.vendor for s in sentences if s.vendor} | (lowered & {m.id for m in model.manuals})
    vendors |= {e.manual for s in sentences for e in s.examples}
    manuals = [m for m in model.manuals if m.maker == "standard" or m.id in vendors]
    manual_ids = {m.id for m in manuals}
    for s in sentences:
        s.manuals = [m for m in s.manuals if m in manual_ids]
        s.notes = [n for n in s.notes if any(m in manual_ids for m in n.manuals)]
        s.replies = [r for r in s.replies if r.id in keep_ids]
        s.reply_rules = [r for r in s.reply_rules if r.sentence_id in keep_ids]

    # Tables: those of a vendor whose sentences are kept or that is named (its commands address
    # them), not of a vendor that only lends examples to standard sentences.
    owners = {s.vendor for s in sentences if s.vendor} | (lowered & {m.id for m in model.manuals})
    tables = [t for t in model.tables if any(m in owners and m != "nmea0183" for m in t.manuals)]
    enum_ids = {f.enum.id for s in sentences for f in _fields(s) if f.enum}
    # The AIS and binary messages are kept whole (a subset selects sentences): their enums too.
    enum_ids |= {f.enum.id for p in (*model.payloads, *model.applications) for f in p.fields if f.enum}
    enum_ids |= {part.enum.id for m in model.binary for layout in m.layouts for f in layout.fields
                 for part in (f, *f.parts) if part.enum}
    enum_ids |= {f.enum.id for p in model.bit_messages for f in p.fields if f.enum}
    enum_ids |= {p.enum.id for t in tables for p in t.parameters if p.enum}
    bitfield_ids = {f.bitfield.id for s in sentences for f in _fields(s) if f.bitfield}
    bitfield_ids |= {p.bitfield.id for t in tables for p in t.parameters if p.bitfield}

    model.sentences = sentences
    model.manuals = manuals
    model.tables = tables
    model.enums = [e for e in model.enums if e.id in enum_ids]
    model.bitfields = [b for b in model.bitfields if b.id in bitfield_ids]
    model.enum_by_id = {e.id: e for e in model.enums}
    kept_files = {f for s in sentences for f in s.files} | {x.origin.file for x in (*model.enums, *model.bitfields, *model.tables)}
    model.sources = [f for f in model.sources if f in kept_files]
    return model
