"""Random sentences that are valid by the spec: every layout, every field type, empty and absent
fields, leading zeros, signs, decimals, checksum styles. The property tests feed them to the three
tools, which must decode every one, agree byte for byte and write each back unchanged."""

from __future__ import annotations

import random
from decimal import Decimal

from generator import reference
from generator.model import Field, Group, Layout, Sentence, Spec

# NMEA 0183 talker IDs a standard sentence may carry.
TALKERS = ["GP", "GL", "GA", "GB", "BD", "GQ", "GN", "GI", "II", "IN"]


def _digits(rng: random.Random, n: int) -> str:
    return "".join(rng.choice("0123456789") for _ in range(n))


def _number(rng: random.Random, f: Field, integer: bool) -> str:
    low = Decimal(str(f.min)) if f.min is not None else Decimal(-999 if rng.random() < 0.2 else 0)
    high = Decimal(str(f.max)) if f.max is not None else Decimal(99999)
    scale = 0 if integer else rng.choice([0, 1, 1, 2, 3, 5, 6])
    step = Decimal(1).scaleb(-scale)
    span = int((high - low) / step)
    value = low + step * rng.randint(0, max(span, 0))
    sign = "-" if value < 0 else ("+" if rng.random() < 0.05 else "")
    whole, _, frac = f"{abs(value):.{scale}f}".partition(".")
    whole = whole.zfill(len(whole) + rng.choice([0, 0, 1, 2]))
    if sign == "-" and Decimal(f"{whole}.{frac or 0}") == 0:
        sign = ""
    return sign + whole + ("." + frac if scale else ("." if not integer and rng.random() < 0.05 else ""))


def field_texts(rng: random.Random, f: Field, ignore_case: bool = False) -> list[str]:
    """Wire text(s) of one field: sometimes empty, else a valid value of its type."""
    t = f.type
    if t == "keyword":
        word = f.value or ""
        return [word.lower() if ignore_case and rng.random() < 0.3 else word]
    if rng.random() < 0.15 and t not in ("keyword",):
        return ["", ""] if f.wire_width == 2 else [""]
    if t == "integer":
        return [_number(rng, f, integer=True)]
    if t == "decimal":
        return [_number(rng, f, integer=False)]
    if t == "hex":
        text = "".join(rng.choice("0123456789ABCDEF") for _ in range(rng.randint(1, 8)))
        return [text.lower() if rng.random() < 0.2 else text]
    if t == "time":
        frac = _digits(rng, rng.choice([0, 1, 2, 3, 3]))
        return [f"{rng.randint(0, 23):02d}{rng.randint(0, 59):02d}{rng.randint(0, 59):02d}" + (f".{frac}" if frac else "")]
    if t == "date":
        return [f"{rng.randint(1, 28):02d}{rng.randint(1, 12):02d}{rng.randint(0, 99):02d}"]
    if t in ("latitude", "longitude"):
        deg_digits, max_deg = (2, 89) if t == "latitude" else (3, 179)
        frac = _digits(rng, rng.choice([2, 3, 4, 5, 6, 7]))
        value = f"{rng.randint(0, max_deg):0{deg_digits}d}{rng.randint(0, 59):02d}.{frac}"
        return [value, rng.choice("NS" if t == "latitude" else "EW")]
    if t == "char":
        return [rng.choice("ABCXYZ019")]
    if t == "literal":
        return [f.value or ""]
    if t == "text":
        n = rng.randint(1, min(f.max_length or 12, 12))
        return ["".join(rng.choice("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789.-_") for _ in range(n))]
    assert f.enum is not None
    codes = [v.code for v in f.enum.values]
    if t == "enum":
        code = rng.choice(codes)
        return [code.lower() if ignore_case and rng.random() < 0.3 else code]
    return ["".join(rng.choice(codes) for _ in range(rng.randint(1, min(f.max_length or 4, 4))))]


def layout_fields(rng: random.Random, layout: Layout, ignore_case: bool) -> list[str]:
    out: list[str] = []
    optional = layout.optional_fields
    keep = rng.randint(0, len(optional))
    for item in layout.items:
        if isinstance(item, Group):
            for _ in range(rng.randint(item.min, item.max)):
                for f in item.fields:
                    out += field_texts(rng, f, ignore_case)
            continue
        if item.is_optional:
            if optional.index(item) >= keep:
                break
        out += field_texts(rng, item, ignore_case)
    return out


def _checksum(body: str) -> int:
    value = 0
    for ch in body:
        value ^= ord(ch)
    return value


def sentence_line(rng: random.Random, sentence: Sentence, layout: Layout) -> str:
    text = sentence.framing == "text"
    fields = layout_fields(rng, layout, text)
    if text:
        word = sentence.address or ""
        return " ".join([word.lower() if rng.random() < 0.3 else word, *fields])
    # A standard sentence's talker; the query's (Q) is two: the requester's and the listener's.
    talker = rng.choice(TALKERS) + (rng.choice(TALKERS) if sentence.id == "Q" else "")
    address = sentence.address or (talker + sentence.id)
    body = ",".join([address, *fields])
    start = sentence.start
    style = rng.random()
    if style < 0.1:
        return start + body
    if style < 0.15:
        return f"{start}{body}*"
    checksum = f"{_checksum(body):02X}"
    return f"{start}{body}*{checksum.lower() if style < 0.3 else checksum}"


def random_lines(spec: Spec, per_layout: int, seed: int) -> list[tuple[Sentence, Layout, str]]:
    rng = random.Random(seed)
    out = []
    for sentence in spec.sentences:
        for layout in sentence.layouts:
            for _ in range(per_layout):
                out.append((sentence, layout, _fitting_line(rng, spec, sentence, layout)))
    return out


def _fitting_line(rng: random.Random, spec: Spec, sentence: Sentence, layout: Layout) -> str:
    """A random line of the layout that the parsers take, drawn again until it is: no longer than
    MAX_LINE (a layout with a long group, Ashtech's satellite list, can draw a longer one) and, for
    a variant, not one that its main layout refuses at a field the variant reads alike (a variant
    never takes what the main layout rightly rejects: RMC's no-fix sentinel variant, drawn with a
    latitude but no hemisphere)."""
    line = sentence_line(rng, sentence, layout)
    for _ in range(20):
        if len(line) <= reference.rt.MAX_LINE and (layout is sentence.layout or _decodes(spec, line)):
            break
        line = sentence_line(rng, sentence, layout)
    return line


def _decodes(spec: Spec, line: str) -> bool:
    try:
        reference.decode(spec, line)
    except reference.rt.NmeaError:
        return False
    return True
