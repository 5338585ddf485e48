"""Python emitter: a stdlib-only package `nmeaspec` with a dataclass, parser and serializer per
sentence layout, over the hand-written runtime."""

from __future__ import annotations

import json

import jinja2

from . import emit_vectors, pairing
from .emit import TEMPLATES, header
from .model import Field, Group, Layout, Sentence, Spec, fmt_num

PACKAGE = "nmeaspec"


def py_type(f: Field) -> str:
    base = {
        "integer": "rt.Number", "decimal": "rt.Number", "hex": "rt.Hex", "time": "rt.Time",
        "date": "rt.Date", "latitude": "rt.Coordinate", "longitude": "rt.Coordinate", "char": "str",
        "literal": "str", "text": "str", "keyword": "str",
    }.get(f.type)
    if base is None:
        assert f.enum is not None
        base = f"{f.enum.camel} | str" if f.type == "enum" else f"list[{f.enum.camel} | str]"
    if f.type == "keyword":
        return base + (" | rt._Absent" if f.is_optional else "")
    return base + " | None" + (" | rt._Absent" if f.is_optional else "")


def known_table(f: Field) -> tuple[str, str] | None:
    """The module-level table of values already read (rt.known) that a field of `f`'s type and
    rule shares, as (Python name, rule), or None for types that are not looked up."""
    t = f.type
    if t in ("integer", "decimal"):
        rule = t
        if f.min is not None or f.max is not None:
            rule += f" {'' if f.min is None else fmt_num(f.min)}..{'' if f.max is None else fmt_num(f.max)}"
    elif t in ("hex", "time", "date", "latitude", "longitude"):
        rule = t
    else:
        return None
    name = "_" + "".join(ch if ch.isalnum() else "_" for ch in rule.upper().replace("-", "MINUS_")
                         .replace("..", "_TO_").replace(".", "_POINT_")).strip("_")
    return name.rstrip("_"), rule


def py_parse(f: Field, pos: str, name: str, ignore_case: bool = False) -> str:
    """The expression that reads field `f` from `fields[pos]` (and `fields[pos + 1]` for lat/lon);
    `ignore_case` for the words of a text command. A text already read under the same rule is
    looked up first (rt.known); the reader only runs for a new text, and raises for a bad one."""
    text = f"fields[{pos}]"
    index = _plus(pos, 1)
    common = f'{text}, address, {index}, {name}, {json.dumps(f.expected)}'
    t = f.type
    table = known_table(f)
    if t in ("integer", "decimal"):
        bounds = ""
        if f.min is not None or f.max is not None:
            bounds = f", {_bound(f.min)}, {_bound(f.max)}"
        elif table:
            bounds = ", None, None"
        read = f"rt.{t}_field({common}{bounds}, {table[0]})" if table else f"rt.{t}_field({common}{bounds})"
        # An empty field is None (the reader's answer too), without a call for it.
        return f"({table[0]}.get({text}) or {read}) if {text} else None" if table else read
    if t in ("hex", "time", "date"):
        assert table
        return f"({table[0]}.get({text}) or rt.{t}_field({common}, {table[0]})) if {text} else None"
    if t in ("latitude", "longitude"):
        assert table
        pair = f"fields[{index}]"
        return (f"{table[0]}.get(({text}, {pair})) or rt.coordinate_field({text}, {pair}, address, {index}, {name}, "
                f"{json.dumps(f.expected)}, {json.dumps(f.hemisphere_expected)}, {json.dumps(f.hemispheres)}, {table[0]})")
    if t == "char":
        return f"rt.{t}_field({common})"
    if t == "literal":
        return f"{json.dumps(f.value)} if {text} == {json.dumps(f.value)} else rt.literal_field({common}, {json.dumps(f.value)})"
    if t == "text":
        return f"rt.text_field({common}, {f.max_length})"
    if t == "keyword":
        return f"rt.keyword_field({common}, {json.dumps(f.value)}{', True' if ignore_case else ''})"
    assert f.enum is not None
    e = f.enum
    if t == "enum":
        if ignore_case:
            return f'rt.enum_field({common}, {e.camel}.BY_CODE, "{e.code_class}", {e.min_len}, {e.max_len}, True)'
        return (f'{e.camel}.BY_CODE.get({text}) or '
                f'rt.enum_field({common}, {e.camel}.BY_CODE, "{e.code_class}", {e.min_len}, {e.max_len})')
    return f'rt.enum_chars_field({common}, {e.camel}.BY_CODE, "{e.code_class}", {f.max_length})'


def _plus(pos: str, n: int) -> str:
    """`pos + n` as Python source, folded when `pos` is a constant."""
    if pos.isdigit():
        return str(int(pos) + n)
    base, _, offset = pos.partition(" + ")
    return f"{base} + {int(offset or 0) + n}"


def _bound(value: float | None) -> str:
    """A bound as Python source: an int when whole, else an exact Decimal."""
    if value is None:
        return "None"
    text = fmt_num(value)
    return text if "." not in text and "e" not in text.lower() else f'Decimal("{text}")'


def py_literal(value: object) -> str:
    """A Python literal for a spec value (None, a string, a number)."""
    if value is None:
        return "None"
    if isinstance(value, str):
        return json.dumps(value)
    return repr(value)


def py_texts(f: Field, value: str) -> str:
    """The expression that yields the wire text(s) of a field value, as a list fragment."""
    if f.type in ("latitude", "longitude"):
        return f"*rt.coordinate_texts({value})"
    return f"rt.text_of({value})"


def entry_class(sentence: Sentence, layout: Layout, group: Group) -> str:
    """The class of one entry of a repeated group: GsvSatellite for GSV's `satellites`."""
    word = group.camel
    return sentence.layout_camel(layout) + (word[:-1] if word.endswith("s") else word + "Entry")


def layout_view(sentence: Sentence, layout: Layout) -> dict:
    """Everything the template prints for one layout, with wire positions worked out: constant
    before the repeated group, relative to `pos` (the position right after it) behind it."""
    items: list[dict] = []
    at = 0
    after_group = False
    optional_seen = 0
    for item in layout.items:
        if isinstance(item, Group):
            items.append({"group": item, "start": at, "entry": entry_class(sentence, layout, item),
                          "optional_index": None})
            after_group, at = True, 0
            continue
        pos = (f"pos + {at}" if at else "pos") if after_group else str(at)
        view = {"field": item, "pos": pos, "optional_index": None}
        if item.is_optional:
            optional_seen += item.wire_width
            view["optional_index"] = optional_seen
        items.append(view)
        at += item.wire_width
    fields = [v for v in items if "field" in v]
    return {
        "layout": layout, "class": sentence.layout_camel(layout), "items": items, "group": layout.group,
        # Required fields before the group (all of them when there is none), required fields
        # after it, and the optional trailing fields: the order fields() and fields_json() emit.
        "before": [v for v in fields if not v["field"].is_optional and not v["pos"].startswith("pos")],
        "after": [v for v in fields if not v["field"].is_optional and v["pos"].startswith("pos")],
        "optional": [v for v in fields if v["field"].is_optional],
        "reply_rules": [f"({json.dumps(p.reply.id)}, {json.dumps(p.layout.id) if p.layout.id else 'None'}, ({''.join(reply_test(c) + ', ' for c in p.conditions)}))"
                        for p in pairing.pairings(sentence)],
        "outcome": _outcome(layout),
    }


def reply_test(condition: pairing.Condition) -> str:
    """A (field id, kind, value) triple that runtime.holds() interprets."""
    f = condition.field
    kind = {"integer": "integer", "enum": "enum"}.get(f.type, "text")
    return f"({json.dumps(f.id)}, {json.dumps(kind)}, {json.dumps(condition.value)})"


def _outcome(layout: Layout) -> str | None:
    """The OUTCOME of a reply layout that does not always report success: "error", or the field
    and the values that mean success, for runtime.reply_outcome."""
    j = pairing.judgement(layout)
    if j.fixed == "ok":
        return None
    if j.fixed == "error" or j.field is None:
        return '"error"'
    tests = [reply_test(pairing.Condition(j.field, v)) for v in j.ok]
    return f"({''.join(t + ', ' for t in tests)})"


# Names parse_fields already uses (arguments, counters, module names): a field id among them gets
# a trailing underscore as a local variable.
_TAKEN_LOCALS = frozenset({"cls", "address", "fields", "checksum", "line", "count", "repeats", "optional",
                           "pos", "entry", "rt", "Decimal", "Any", "ClassVar", "dataclass", "field"})


def py_local(name: str) -> str:
    """The local variable parse_fields reads field `name` into."""
    return name + "_" if name in _TAKEN_LOCALS else name


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    env.globals.update(py_type=py_type, py_parse=py_parse, local=py_local, py_texts=py_texts, py=py_literal, json=json)
    base = f"python/{PACKAGE}"
    files: dict[str, str] = {}
    runtime = (TEMPLATES / "python" / "runtime.py").read_text(encoding="utf-8")
    files[f"{base}/runtime.py"] = header(spec, "#", ["templates/python/runtime.py"]) + runtime
    for module in ("api", "cli", "stream"):
        text = (TEMPLATES / "python" / f"{module}.py").read_text(encoding="utf-8")
        files[f"{base}/{module}.py"] = header(spec, "#", [f"templates/python/{module}.py"]) + text
    files[f"{base}/__main__.py"] = header(spec, "#", ["templates/python/cli.py"]) + \
        "from .cli import main\n\nraise SystemExit(main())\n"
    files[f"{base}/py.typed"] = ""
    files[f"{base}/enums.py"] = env.get_template("python/enums.py.j2").render(
        header=header(spec, "#", [e.origin.file for e in spec.enums]), enums=spec.enums)
    for sentence in spec.sentences:
        files[f"{base}/sentences/{sentence.id.lower()}.py"] = env.get_template("python/sentence.py.j2").render(
            header=header(spec, "#", [sentence.source, *sorted({f.enum.origin.file for lay in sentence.layouts
                                                               for f in _all_fields(lay) if f.enum})]),
            sentence=sentence,
            layouts=[layout_view(sentence, lay) for lay in sentence.layouts],
            enums=sorted({f.enum.camel for lay in sentence.layouts for f in _all_fields(lay) if f.enum}),
            uses_decimal=any(f.type in ("integer", "decimal") and "Decimal" in _bound(f.min) + _bound(f.max)
                             for lay in sentence.layouts for f in _all_fields(lay)),
            tables=sorted({t for lay in sentence.layouts for f in _all_fields(lay) if (t := known_table(f))}))
    by_address = {s.address: spec.by_address(s.address) for s in spec.proprietary if s.framing == "sentence"}
    text_commands = {s.address.upper(): spec.text_command(s.address) for s in spec.proprietary if s.framing == "text"}
    files[f"{base}/bitfields.py"] = env.get_template("python/bitfields.py.j2").render(
        header=header(spec, "#", [b.origin.file for b in spec.bitfields]), bitfields=spec.bitfields)
    files[f"{base}/tables.py"] = env.get_template("python/tables.py.j2").render(
        header=header(spec, "#", [t.origin.file for t in spec.tables]), tables=spec.tables,
        uses_enums=any(p.enum for t in spec.tables for p in t.parameters),
        uses_bitfields=any(p.bitfield for t in spec.tables for p in t.parameters))
    files[f"{base}/sentences/__init__.py"] = env.get_template("python/sentences_init.py.j2").render(
        header=header(spec, "#"), sentences=spec.sentences, by_address=sorted(by_address.items()),
        text_commands=sorted(text_commands.items()))
    files[f"{base}/__init__.py"] = env.get_template("python/init.py.j2").render(
        header=header(spec, "#"), sentences=spec.sentences, enums=spec.enums)
    files["python/pyproject.toml"] = env.get_template("python/pyproject.toml.j2").render(
        header=header(spec, "#", ["templates/python/pyproject.toml.j2"]), package=PACKAGE)
    files["python/tests/test_examples.py"] = env.get_template("python/test_examples.py.j2").render(
        header=header(spec, "#"), vectors=[v for v in emit_vectors.example_vectors(spec)], package=PACKAGE,
        json=json, reply_cases=pairing.reply_cases(spec))
    return files


def _all_fields(layout: Layout) -> list[Field]:
    out: list[Field] = []
    for item in layout.items:
        out += item.fields if isinstance(item, Group) else [item]
    return out
