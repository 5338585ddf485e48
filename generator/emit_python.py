"""Python emitter: the codec, a stdlib-only package `nmeaspec` with a dataclass, parser and
serializer per sentence layout, over the hand-written runtime. Its applications (`nmea`, `nmea-py`)
are emit_python_apps.py's."""

from __future__ import annotations

import json
import textwrap

import jinja2

from . import emit_vectors, pairing
from .emit import header, package_readme, runtime_file
from .model import Field, FixField, Group, Layout, Sentence, Spec
from .numbers import fmt_num

PACKAGE = "nmeaspec"


def py_type(f: Field) -> str:
    t = f.field_type
    base = t.python_type.format(enum=f.enum.camel if f.enum else "")
    absent = " | rt._Absent" if f.is_optional else ""
    return base + absent if t.keyword else base + " | None" + absent


WIDTH = 100  # the longest line of the generated Python


def field_spec(f: Field) -> list[str]:
    """The lines of the runtime's FieldSpec of `f` in a layout's items (a call with its id, what
    it takes and its type's arguments), each of at most WIDTH characters at an indent of 8."""
    args = [json.dumps(f.id), json.dumps(f.expected)]
    for word in f.field_type.args:
        args += _arg(word, f)
    if f.is_optional:
        args.append("optional=True")
    return call_lines(f"rt.{f.field_type.python_spec}", args, 8, ",")


def _arg(word: str, f: Field) -> list[str]:
    """A word of the registry's argument vocabulary (field_types.py) as FieldSpec arguments for
    `f` (none for a range or length the field does not give)."""
    if word == "range":
        return [_bound(f.min), _bound(f.max)] if f.min is not None or f.max is not None else []
    if word == "word":
        return [json.dumps(f.value)]
    if word == "hemisphere":
        return [json.dumps(f.field_type.hemisphere_expected)]
    if word == "table":
        assert f.enum is not None
        return [f.enum.camel]
    assert word == "max_length", word
    return [str(f.max_length)] if f.max_length is not None else []


def call_lines(function: str, args: list[str], indent: int, end: str = "") -> list[str]:
    """A call as lines of at most WIDTH characters (after `indent` spaces): on one line when it
    fits, else one argument a line (a long string split where it has spaces)."""
    one = f"{function}({', '.join(args)}){end}"
    if indent + len(one) <= WIDTH:
        return [one]
    lines = [f"{function}("]
    for arg in args:
        lines += ["    " + part for part in _split_str(arg, WIDTH - indent - 5)]
        lines[-1] += ","
    return lines + [")" + end]


def _split_str(arg: str, width: int) -> list[str]:
    """A JSON string literal `arg` (or a keyword argument `name="..."`) as implicitly joined
    literals of at most `width` characters."""
    name, _, literal = arg.partition("=") if arg[:1].isalpha() and '="' in arg else ("", "", arg)
    if len(arg) <= width or not literal.startswith('"'):
        return [arg]
    if name:
        return [f"{name}=(", *("    " + part for part in _split_str(literal, width - 4)), ")"]
    text = json.loads(literal)
    parts: list[str] = []
    while text:
        cut = len(text)
        while len(json.dumps(text[:cut])) > width:
            space = text.rfind(" ", 0, cut - 1)
            cut = space + 1 if space > 0 else cut - 1
        parts.append(json.dumps(text[:cut]))
        text = text[cut:]
    return parts


def py_call(function: str, args: list[str], indent: int, end: str = "") -> str:
    """call_lines for a template: the lines joined, all but the first indented by `indent`."""
    return ("\n" + " " * indent).join(call_lines(function, args, indent, end))


def py_import(module: str, names: list[str], indent: int, reexport: bool = True) -> str:
    """`from module import A, ...` (`reexport`: `A as A`), in parentheses a name a line when it is
    longer than WIDTH."""
    names = [f"{n} as {n}" if reexport else n for n in names]
    one = f"from {module} import {', '.join(names)}"
    if indent + len(one) <= WIDTH:
        return one
    pad = "\n" + " " * (indent + 4)
    return f"from {module} import (" + "".join(f"{pad}{n}," for n in names) + "\n" + " " * indent + ")"


def py_tuple(items: list[str], indent: int, used: int = 0, end: str = "", brackets: str = "()") -> str:
    """A tuple of `items` (or, `brackets` "{}", a dict of "key: value" items) that `used`
    characters precede: on its line when it fits in WIDTH, else an item a line."""
    one = f"{brackets[0]}{', '.join(items)}{',' if len(items) == 1 and brackets == '()' else ''}{brackets[1]}{end}"
    if indent + used + len(one) <= WIDTH:
        return one
    pad = "\n" + " " * (indent + 4)
    return brackets[0] + "".join(f"{pad}{item}," for item in items) + "\n" + " " * indent + brackets[1] + end


def py_str(text: str, indent: int, used: int = 0) -> str:
    """A string literal of `text` that `used` characters precede on a line indented by `indent`:
    one literal when it fits in WIDTH, else pieces in parentheses, a line each."""
    literal = json.dumps(text)
    if indent + used + len(literal) + 1 <= WIDTH:
        return literal
    pad = "\n" + " " * (indent + 4)
    return "(" + pad + pad.join(_split_str(literal, WIDTH - indent - 4)) + "\n" + " " * indent + ")"


def py_doc(text: str, indent: int) -> str:
    """A docstring of `text` wrapped to WIDTH, all but its first line indented by `indent`."""
    return ("\n" + " " * indent).join(docstring(text, indent))


def docstring(text: str, indent: int) -> list[str]:
    """A docstring of `text` as lines of at most WIDTH characters (after `indent` spaces)."""
    words = " ".join(text.split()).replace("\\", "\\\\").replace('"', '\\"')
    return textwrap.wrap(f'"""{words}"""', WIDTH - indent, break_long_words=False, break_on_hyphens=False)


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


def entry_class(sentence: Sentence, layout: Layout, group: Group) -> str:
    """The class of one entry of a repeated group: GsvSatellite for GSV's `satellites`."""
    word = group.camel
    return sentence.layout_camel(layout) + (word[:-1] if word.endswith("s") else word + "Entry")


def member_view(f: Field) -> dict:
    """A dataclass member of a field: its declaration and its docstring."""
    default = "rt.ABSENT" if f.is_optional else (json.dumps(f.value) if f.field_type.keyword else "None")
    unit = f" [{f.unit}]" if f.unit else ""
    since = f" (NMEA {f.since})" if f.since else ""
    return {"line": f"{f.id}: {py_type(f)} = {default}", "doc": docstring(f"{f.name}{unit}{since}: {f.doc}", 4)}


def layout_view(sentence: Sentence, layout: Layout) -> dict:
    """Everything the template prints for one layout: its dataclass members and the lines of its
    LAYOUT (the runtime's description of its wire form)."""
    members: list[dict] = []
    items: list[str] = []
    entry = None
    for item in layout.items:
        if isinstance(item, Group):
            name = entry_class(sentence, layout, item)
            value_type = py_type(item.fields[0]) if item.single else name
            members.append({"line": f"{item.id}: list[{value_type}] = field(default_factory=list)",
                            "doc": docstring(f"{item.name}: {item.min} to {item.max} entries.", 4)})
            fields = [line for f in item.fields for line in field_spec(f)]
            items += [f"rt.Group({json.dumps(item.id)}, {'None' if item.single else name}, (",
                      *("    " + line for line in fields), f"), {item.min}, {item.max}),"]
            if not item.single:
                entry = {"class": name, "group": item,
                         "doc": docstring(f"One entry of {item.name.lower()} ({item.min} to {item.max} per "
                                          "sentence).", 4),
                         "members": [{"line": f"{f.id}: {py_type(f)} = None",
                                      "doc": docstring(f"{f.name}{f' [{f.unit}]' if f.unit else ''}: {f.doc}", 4)}
                                     for f in item.fields]}
        else:
            members.append(member_view(item))
            items += field_spec(item)
    head = (f"LAYOUT: ClassVar[rt.Layout] = rt.Layout({json.dumps(sentence.id)}, {json.dumps(sentence.wire_kind)}, "
            f"{json.dumps(sentence.start)}, {layout.fixed_count}, {layout.max_fields}, (")
    example = sentence.example_of(layout)
    title = f"{sentence.id}{' (' + layout.name + ')' if layout.id else ''}: " + \
        f"{sentence.name if layout.id else layout.name}."
    doc = textwrap.wrap(title, WIDTH - 7)
    if layout.id:
        doc += ["", *textwrap.wrap(" ".join(layout.doc.split()), WIDTH - 4)]
    if example:
        doc += ["", f"Example ({example.manual}):", example.line or ""]
    return {
        "layout": layout, "class": sentence.layout_camel(layout), "entry": entry, "members": members,
        "doc": [line.replace("\\", "\\\\").replace('"""', '\\"\\"\\"') for line in doc],
        "layout_head": head, "layout_items": items,
        "reply_rules": [f"({json.dumps(p.reply.id)}, {json.dumps(p.layout.id) if p.layout.id else 'None'}, "
                        f"({''.join(reply_test(c) + ', ' for c in p.conditions)})),"
                        for p in pairing.pairings(sentence)],
        "outcome": _outcome(layout),
        "same_as_main": _same_as_main(sentence, layout),
        "derived": derived_view(layout),
        "encapsulates": sentence.encapsulates,
    }


def derived_view(layout: Layout) -> list[dict]:
    """The sentence-level values of a layout with one position or one date and time (the model's
    position and calendar): each property's name, type, docstring and the runtime call it returns."""
    out: list[dict] = []
    if layout.position:
        for name, f, negative in (("latitude", layout.position.lat, "south"),
                                  ("longitude", layout.position.lon, "west")):
            out.append({"name": name, "type": "float | None", "call": f"rt.degrees(self.{f.id})",
                        "doc": docstring(f"{f.name} in signed decimal degrees ({negative} negative); None when "
                                         "empty.", 8)})
    if (c := layout.calendar):
        call = (f"rt.utc_datetime(self.{c.date.id}, self.{c.time.id})" if c.date else
                f"rt.utc_datetime_of(self.{c.year.id}, self.{c.month.id}, self.{c.day.id}, self.{c.time.id})")
        parts = c.date.id if c.date else f"{c.day.id}, {c.month.id}, {c.year.id}"
        out.append({"name": "datetime", "type": "dt.datetime | None", "call": call,
                    "doc": docstring(f"UTC date and time ({parts}, {c.time.id}), timezone-aware"
                                     f"{'; two-digit years 00-68 are 20yy, 69-99 19yy' if c.date else ''}. "
                                     "None when a field is empty, for a day its month lacks or a leap second.", 8)})
    return out


def _same_as_main(sentence: Sentence, layout: Layout) -> list[str]:
    """The SAME_AS_MAIN line of a variant (wrapped as ruff would), or none."""
    fields = sentence.same_as_main(layout) if layout.id else []
    if not fields:
        return []
    head, value = "    SAME_AS_MAIN: ClassVar[frozenset[int]] = frozenset(", "{" + ", ".join(map(str, fields)) + "}"
    if len(head) + len(value) + 1 <= 100:
        return [f"{head}{value})"]
    return [head, f"        {value}", "    )"]


def reply_test(condition: pairing.Condition) -> str:
    """A (field id, kind, value) triple that runtime.holds() interprets."""
    f = condition.field
    return f"({json.dumps(f.id)}, {json.dumps(f.field_type.python_pairing)}, {json.dumps(condition.value)})"


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


def fix_field(fix: FixField) -> str:
    """The FixField(...) entry of a field that carries a fact, for fix_fields.py (at an indent of
    8, on one line when it fits)."""
    f, fact = fix.field, fix.fact
    values = fact.values_of(f)
    items = [f"{json.dumps(k)}: {json.dumps(v)}" for k, v in (values or {}).items()]
    args = [json.dumps(fact.id), py_literal(fix.group.id if fix.group else None),
            py_literal(None if fix.group is not None and fix.group.single else f.id), repr(float(fact.scale(f)))]
    one = f"FixField({', '.join(args)}, {'{' + ', '.join(items) + '}' if values else 'None'}),"
    if 8 + len(one) <= WIDTH:
        return one
    args.append(py_tuple(items, 12, 0, brackets="{}") if values else "None")
    return "FixField(" + "".join(f"\n            {arg}," for arg in args) + "\n        ),"


def fix_fields(spec: Spec, env: jinja2.Environment) -> str:
    """fix_fields.py: the fields that carry facts of a fix, per layout (spec/fix.yaml)."""
    layouts = [(f"({json.dumps(s.id)}, {py_literal(layout.id)})", [fix_field(fix) for fix in layout.fix_fields])
               for s, layout in spec.fix_layouts]
    units = py_tuple([f"{json.dumps(fact.id)}: {json.dumps(fact.unit)}" for fact in spec.facts if fact.unit], 0,
                     len("FACT_UNITS: dict[str, str] = "), brackets="{}")
    decimal = py_tuple([json.dumps(fact.id) for fact in spec.facts if "decimal" in fact.types], 0,
                       len("DECIMAL_FACTS: frozenset[str] = frozenset("), brackets="{}")
    talkers = py_tuple([f"{json.dumps(k)}: {json.dumps(v)}" for k, v in spec.talker_systems.items()], 0,
                       len("TALKER_SYSTEMS: dict[str, str] = "), brackets="{}")
    ids = py_tuple([f"({json.dumps(s)}, {low}, {high})" for s, low, high in spec.satellite_ids], 0,
                   len("SATELLITE_IDS: tuple[tuple[str, int, int], ...] = "))
    sources = sorted({*spec.fix_sources, *(f for s, _ in spec.fix_layouts for f in s.files)})
    return env.get_template("python/fix_fields.py.j2").render(
        header=header(spec, "#", ["templates/python/fix_fields.py.j2", *sources]), layouts=layouts,
        fact_units=units, decimal_facts=decimal, talkers=talkers, satellite_ids=ids, combined_talker=py_literal(spec.combined_talker))


# A TAG block value type's Python type and the runtime.TagBlock method that reads it.
TAG_VALUE_TYPES = {"integer": ("int", "integer_of"), "group": ("rt.TagGroup", "group_of"), "text": ("str", "text_of")}


def tag_block(spec: Spec, env: jinja2.Environment) -> str:
    """tag_block.py: the TAG block class with the codes of spec/tag_block.yaml."""
    codes = [{"code": py_literal(c.code), "id": c.id, "id_literal": py_literal(c.id), "type": py_literal(c.type),
              "py_type": TAG_VALUE_TYPES[c.type][0], "reader": TAG_VALUE_TYPES[c.type][1],
              "doc": py_doc(f"{c.name} ({c.code}): {c.doc}", 8)} for c in spec.tag_codes]
    return env.get_template("python/tag_block.py.j2").render(
        header=header(spec, "#", ["templates/python/tag_block.py.j2", *spec.tag_sources]), codes=codes)


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    env.globals.update(py=py_literal, json=json, py_call=py_call, py_str=py_str, py_doc=py_doc,
                       py_import=py_import, py_tuple=py_tuple)
    base = f"python/{PACKAGE}"
    files: dict[str, str] = {}
    for module in ("runtime", "api", "stream", "receiver", "network", "fixes", "ais", "assembly", "ubx", "rtcm3",
                   "framings", "binary"):
        files[f"{base}/{module}.py"] = runtime_file(spec, "#", f"python/{module}.py")
    files[f"{base}/py.typed"] = ""
    files[f"{base}/fix_fields.py"] = fix_fields(spec, env)
    files[f"{base}/tag_block.py"] = tag_block(spec, env)
    files[f"{base}/enums/__init__.py"] = env.get_template("python/enums_init.py.j2").render(
        header=header(spec, "#"), enums=spec.enums)
    for e in spec.enums:
        files[f"{base}/enums/{e.id}.py"] = env.get_template("python/enum.py.j2").render(
            header=header(spec, "#", [e.origin.file]), e=e)
    for sentence in spec.sentences:
        files[f"{base}/sentences/{sentence.id.lower()}.py"] = env.get_template("python/sentence.py.j2").render(
            header=header(spec, "#", [*sentence.files, *sorted({f.enum.origin.file for lay in sentence.layouts
                                                               for f in lay.all_fields if f.enum})]),
            sentence=sentence,
            layouts=[layout_view(sentence, lay) for lay in sentence.layouts],
            enums=sorted({f.enum.camel for lay in sentence.layouts for f in lay.all_fields if f.enum}),
            uses_datetime=any(lay.calendar for lay in sentence.layouts),
            uses_decimal=any(f.field_type.numeric and "Decimal" in _bound(f.min) + _bound(f.max)
                             for lay in sentence.layouts for f in lay.all_fields))
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
    files["python/README.md"] = package_readme(spec, env, "python/README.md.j2", package=PACKAGE)
    files["python/tests/test_examples.py"] = env.get_template("python/test_examples.py.j2").render(
        header=header(spec, "#"), vectors=[v for v in emit_vectors.example_vectors(spec)], package=PACKAGE,
        json=json, reply_cases=pairing.reply_cases(spec))
    return files


