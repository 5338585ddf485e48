"""`diff OLD NEW`: the API changelog between two spec trees.

Both trees go through the normal loader and model; the comparison is of the models, so it speaks
of what the generated code offers (sentences, fields, enum values...), not of YAML lines. Every
change is BREAKING when existing user code or existing wire data stops working with the new code
(a sentence, field or enum value removed, a type changed, a field renamed, moved or made required,
a required field added before others) and compatible otherwise (an optional trailing field, a new
enum value, sentence or example).
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path

from .errors import SpecErrors
from .migrate import upgrade_tree
from .model import EnumDef, Field, Group, Item, Layout, Sentence, Spec, TableDef

SECTIONS = {
    "sentence": "Sentences and commands",
    "field": "Fields",
    "enum": "Enums",
    "bitfield": "Bitfields",
    "table": "Parameter tables",
    "example": "Examples",
}


@dataclass
class Change:
    kind: str           # a key of SECTIONS
    subject: str        # what changed: `GGA`, `GGA.quality`, `gga_quality.rtk`
    change: str         # the sentence of the changelog
    breaking: bool


class _Log:
    def __init__(self) -> None:
        self.changes: list[Change] = []

    def __call__(self, kind: str, subject: str, change: str, breaking: bool) -> None:
        self.changes.append(Change(kind, subject, change, breaking))


def compare(old: Spec, new: Spec) -> list[Change]:
    log = _Log()
    _sentences(old, new, log)
    _enums(old, new, log)
    _bitfields(old, new, log)
    _tables(old, new, log)
    _examples(old, new, log)
    return log.changes


def _what(s: Sentence) -> str:
    return "command" if s.kind == "command" else "text command" if s.framing == "text" else "sentence"


def _sentences(old: Spec, new: Spec, log: _Log) -> None:
    olds = {s.id: s for s in old.sentences}
    news = {s.id: s for s in new.sentences}
    for sid, s in olds.items():
        if sid not in news:
            log("sentence", sid, f"{_what(s)} `{sid}` removed", True)
    for sid, s in news.items():
        if sid not in olds:
            where = f" (vendor {s.vendor}, address {s.address})" if s.vendor else ""
            log("sentence", sid, f"{_what(s)} `{sid}` added{where}", False)
    for sid in sorted(olds.keys() & news.keys()):
        _sentence(olds[sid], news[sid], log)


def _sentence(a: Sentence, b: Sentence, log: _Log) -> None:
    sid = a.id
    if a.address != b.address:
        log("sentence", sid, f"`{sid}`: address {a.address} -> {b.address}", True)
    if a.kind != b.kind or a.framing != b.framing:
        log("sentence", sid, f"`{sid}`: kind {a.kind}/{a.framing} -> {b.kind}/{b.framing}", True)
    gone = [t for t in a.talkers if t not in b.talkers]
    added = [t for t in b.talkers if t not in a.talkers]
    if gone:
        log("sentence", sid, f"`{sid}`: talkers removed: {', '.join(gone)}", True)
    if added:
        log("sentence", sid, f"`{sid}`: talkers added: {', '.join(added)}", False)
    if a.reply_ids != b.reply_ids:
        log("sentence", sid, f"`{sid}`: replies {a.reply_ids or '[]'} -> {b.reply_ids or '[]'}",
            any(r not in b.reply_ids for r in a.reply_ids))
    old_variants = {v.id: v for v in a.variants}
    new_variants = {v.id: v for v in b.variants}
    for vid in sorted(old_variants.keys() - new_variants.keys()):
        log("sentence", f"{sid}.{vid}", f"`{sid}`: variant `{vid}` removed", True)
    for vid in sorted(new_variants.keys() - old_variants.keys()):
        log("sentence", f"{sid}.{vid}", f"`{sid}`: variant `{vid}` added", False)
    _layout(sid, a.layout, b.layout, log)
    for vid in sorted(old_variants.keys() & new_variants.keys()):
        _layout(f"{sid}[{vid}]", old_variants[vid], new_variants[vid], log)


def _optional(item: Item) -> bool:
    return isinstance(item, Field) and item.is_optional


def _type(f: Field) -> str:
    extra = f.enum_id or f.bitfield_id or (repr(f.value) if f.value is not None else None) or f.format
    return f"{f.type}({extra})" if extra else f.type


def _items(owner: str, old: list[Item], new: list[Item], log: _Log, group: bool = False) -> None:
    """Compare two wire-ordered lists of fields (or groups)."""
    old_ids = [i.id for i in old]
    new_ids = [i.id for i in new]
    olds = {i.id: i for i in old}
    news = {i.id: i for i in new}
    removed = [i for i in old_ids if i not in news]
    added = [i for i in new_ids if i not in olds]
    # A removed and an added item after the same surviving item, with the same type: a rename.
    def after(ids: list[str], iid: str) -> str | None:
        return next((x for x in reversed(ids[:ids.index(iid)]) if x in olds and x in news), None)

    renamed: dict[str, str] = {}
    for rid in removed:
        for aid in added:
            if after(old_ids, rid) == after(new_ids, aid) and aid not in renamed.values() \
                    and _same_shape(olds[rid], news[aid]):
                renamed[rid] = aid
                break
    for rid, aid in renamed.items():
        log("field", f"{owner}.{rid}", f"`{owner}`: field `{rid}` renamed to `{aid}` (same place and type)", True)
        _item(owner, olds[rid], news[aid], log)
    for rid in removed:
        if rid not in renamed:
            log("field", f"{owner}.{rid}", f"`{owner}`: field `{rid}` removed", True)
    kept_new = [i for i in new_ids if i in olds or i in renamed.values()]
    for aid in added:
        if aid in renamed.values():
            continue
        item = news[aid]
        pos = new_ids.index(aid)
        trailing = all(x in added and x not in renamed.values() for x in new_ids[pos:]) and not group
        what = "group" if isinstance(item, Group) else f"{'optional ' if _optional(item) else ''}field"
        if trailing and _optional(item):
            log("field", f"{owner}.{aid}", f"`{owner}`: {what} `{aid}` ({_desc(item)}) added at the end", False)
        elif trailing:
            log("field", f"{owner}.{aid}", f"`{owner}`: required {what} `{aid}` ({_desc(item)}) added at the end: "
                "existing sentences without it no longer parse", True)
        else:
            after = new_ids[pos - 1] if pos else None
            log("field", f"{owner}.{aid}", f"`{owner}`: {what} `{aid}` ({_desc(item)}) inserted "
                f"{f'after `{after}`' if after else 'first'}: the fields after it move on the wire", True)
    common_old = [renamed.get(i, i) for i in old_ids if i in news or i in renamed]
    common_new = [i for i in kept_new]
    if common_old != common_new:
        log("field", owner, f"`{owner}`: fields reordered: {', '.join(common_old)} -> {', '.join(common_new)}", True)
    for iid in sorted(olds.keys() & news.keys()):
        _item(owner, olds[iid], news[iid], log)


def _same_shape(a: Item, b: Item) -> bool:
    if isinstance(a, Field) and isinstance(b, Field):
        return _type(a) == _type(b)
    return isinstance(a, Group) and isinstance(b, Group)


def _desc(item: Item) -> str:
    if isinstance(item, Group):
        return f"group of {', '.join(f.id for f in item.fields)}"
    return _type(item) + (f", since NMEA {item.since}" if item.since else "")


def _num(value: float | None) -> str:
    return "none" if value is None else f"{value:g}"


def _item(owner: str, a: Item, b: Item, log: _Log) -> None:
    name = f"{owner}.{b.id}"
    if isinstance(a, Group) != isinstance(b, Group):
        log("field", name, f"`{owner}`: `{b.id}` changed between a field and a group", True)
        return
    if isinstance(a, Group) and isinstance(b, Group):
        if (a.min, a.max) != (b.min, b.max):
            log("field", name, f"`{owner}`: group `{b.id}` repeats {a.min}..{a.max} -> {b.min}..{b.max} times",
                b.min > a.min or b.max < a.max)
        _items(f"{owner}.{b.id}", list(a.fields), list(b.fields), log, group=True)
        return
    assert isinstance(a, Field) and isinstance(b, Field)
    if _type(a) != _type(b):
        log("field", name, f"`{name}`: type {_type(a)} -> {_type(b)}", True)
    if a.is_optional != b.is_optional:
        if b.is_optional:
            log("field", name, f"`{name}`: now optional (may be absent)", False)
        else:
            log("field", name, f"`{name}`: now required: sentences without it no longer parse", True)
    if a.since != b.since:
        log("field", name, f"`{name}`: since NMEA {a.since or '-'} -> {b.since or '-'}", False)
    if (a.min, a.max) != (b.min, b.max):
        narrower = (b.min is not None and (a.min is None or b.min > a.min)) or \
                   (b.max is not None and (a.max is None or b.max < a.max))
        log("field", name, f"`{name}`: range {_num(a.min)}..{_num(a.max)} -> {_num(b.min)}..{_num(b.max)}", narrower)
    if a.max_length != b.max_length:
        narrower = b.max_length is not None and (a.max_length is None or b.max_length < a.max_length)
        log("field", name, f"`{name}`: max length {a.max_length} -> {b.max_length}", narrower)
    if a.unit != b.unit:
        log("field", name, f"`{name}`: unit {a.unit} -> {b.unit}", True)
    if a.name != b.name:
        log("field", name, f"`{name}`: name {a.name!r} -> {b.name!r} (docs only)", False)


def _layout(owner: str, a: Layout, b: Layout, log: _Log) -> None:
    _items(owner, list(a.items), list(b.items), log)


def _by_id(xs):
    return {x.id: x for x in xs}


def _enums(old: Spec, new: Spec, log: _Log) -> None:
    olds, news = _by_id(old.enums), _by_id(new.enums)
    for eid in sorted(olds.keys() - news.keys()):
        log("enum", eid, f"enum `{eid}` removed", True)
    for eid in sorted(news.keys() - olds.keys()):
        e = news[eid]
        log("enum", eid, f"enum `{eid}` added ({', '.join(f'{v.id}={v.code}' for v in e.values)})", False)
    for eid in sorted(olds.keys() & news.keys()):
        _enum(olds[eid], news[eid], log)


def _enum(a: EnumDef, b: EnumDef, log: _Log) -> None:
    if a.closed != b.closed:  # closed: a code the enum does not list is refused, not kept
        log("enum", a.id, f"`{a.id}`: a code it does not list is now "
            + ("refused (codes closed)" if b.closed else "kept (codes open)"), b.closed)
    by_id_a, by_id_b = _by_id(a.values), _by_id(b.values)
    for v in a.values:
        if v.id not in by_id_b:
            same_code = b.by_code(v.code)
            if same_code and same_code.id not in by_id_a:
                log("enum", f"{a.id}.{v.id}", f"`{a.id}`: value `{v.id}` renamed to `{same_code.id}` (code {v.code})", True)
            else:
                log("enum", f"{a.id}.{v.id}", f"`{a.id}`: value `{v.id}` (code {v.code}) removed", True)
    for v in b.values:
        if v.id not in by_id_a and not (a.by_code(v.code) and a.by_code(v.code).id not in by_id_b):
            since = f", since NMEA {v.since}" if v.since else ""
            log("enum", f"{b.id}.{v.id}", f"`{b.id}`: value `{v.id}` (code {v.code}{since}) added", False)
        elif v.id in by_id_a and by_id_a[v.id].code != v.code:
            log("enum", f"{b.id}.{v.id}", f"`{b.id}`: value `{v.id}` code {by_id_a[v.id].code} -> {v.code}", True)


def _bitfields(old: Spec, new: Spec, log: _Log) -> None:
    olds, news = _by_id(old.bitfields), _by_id(new.bitfields)
    for bid in sorted(olds.keys() - news.keys()):
        log("bitfield", bid, f"bitfield `{bid}` removed", True)
    for bid in sorted(news.keys() - olds.keys()):
        log("bitfield", bid, f"bitfield `{bid}` added", False)
    for bid in sorted(olds.keys() & news.keys()):
        a, b = olds[bid], news[bid]
        if a.width != b.width:
            log("bitfield", bid, f"`{bid}`: width {a.width} -> {b.width} bits", b.width < a.width)
        bits_a, bits_b = _by_id(a.bits), _by_id(b.bits)
        for x in a.bits:
            if x.id not in bits_b:
                log("bitfield", f"{bid}.{x.id}", f"`{bid}`: bits `{x.id}` ({x.label}) removed", True)
            elif bits_b[x.id].label != x.label:
                log("bitfield", f"{bid}.{x.id}", f"`{bid}`: bits `{x.id}` moved {x.label} -> {bits_b[x.id].label}", True)
            else:
                old_values = {v.id: v.value for v in x.values}
                new_values = {v.id: v.value for v in bits_b[x.id].values}
                for vid in sorted(old_values.keys() - new_values.keys()):
                    log("bitfield", f"{bid}.{x.id}.{vid}", f"`{bid}`: bits `{x.id}` value `{vid}` removed", True)
                for vid in sorted(new_values.keys() - old_values.keys()):
                    log("bitfield", f"{bid}.{x.id}.{vid}", f"`{bid}`: bits `{x.id}` value `{vid}` added", False)
        for x in b.bits:
            if x.id not in bits_a:
                log("bitfield", f"{bid}.{x.id}", f"`{bid}`: bits `{x.id}` ({x.label}) added", False)


def _tables(old: Spec, new: Spec, log: _Log) -> None:
    olds, news = _by_id(old.tables), _by_id(new.tables)
    for tid in sorted(olds.keys() - news.keys()):
        log("table", tid, f"table `{tid}` removed", True)
    for tid in sorted(news.keys() - olds.keys()):
        log("table", tid, f"table `{tid}` added", False)
    for tid in sorted(olds.keys() & news.keys()):
        _table(olds[tid], news[tid], log)


def _param_shape(p) -> tuple:
    return (p.number, p.encoding, p.size, p.count, p.enum_id, p.bitfield_id, p.min, p.max, p.max_length)


def _table(a: TableDef, b: TableDef, log: _Log) -> None:
    pa, pb = _by_id(a.parameters), _by_id(b.parameters)
    for pid in sorted(pa.keys() - pb.keys()):
        log("table", f"{a.id}.{pid}", f"`{a.id}`: parameter `{pid}` ({pa[pid].number}) removed", True)
    for p in b.parameters:
        if p.id not in pa:
            log("table", f"{a.id}.{p.id}", f"`{a.id}`: parameter `{p.id}` ({p.number}, {p.encoding}) added", False)
        elif _param_shape(pa[p.id]) != _param_shape(p):
            log("table", f"{a.id}.{p.id}", f"`{a.id}`: parameter `{p.id}` changed: number/encoding/size/range "
                f"{_param_shape(pa[p.id])} -> {_param_shape(p)}", True)
        elif pa[p.id].default != p.default:
            log("table", f"{a.id}.{p.id}", f"`{a.id}`: parameter `{p.id}` default {pa[p.id].default} -> {p.default}", False)


def _examples(old: Spec, new: Spec, log: _Log) -> None:
    def index(spec: Spec) -> dict[tuple[str, str, str], object]:
        return {(s.id, e.manual, e.raw): e for s in spec.sentences for e in s.examples}
    olds, news = index(old), index(new)
    for key in sorted(olds.keys() - news.keys()):
        log("example", key[0], f"`{key[0]}`: example from {key[1]} removed: `{key[2]}`", False)
    for key in sorted(news.keys() - olds.keys()):
        log("example", key[0], f"`{key[0]}`: example from {key[1]} added: `{key[2]}`", False)
    for key in sorted(olds.keys() & news.keys()):
        a, b = olds[key], news[key]
        what = [name for name in ("corrected", "expect", "variant", "where")
                if getattr(a, name) != getattr(b, name)]
        if what:
            log("example", key[0], f"`{key[0]}`: example `{key[2]}` changed ({', '.join(what)})", False)


# --- output ------------------------------------------------------------------------------------

def markdown(changes: list[Change], old_name: str, new_name: str, title: str | None = None,
             level: int = 1) -> str:
    """The changelog as Markdown: a heading of `level` (`title`, by default the two names), then
    the counts and a section per kind of change."""
    breaking = sum(c.breaking for c in changes)
    lines = [f"{'#' * level} {title or f'API changelog: {old_name} -> {new_name}'}", ""]
    if not changes:
        return "\n".join(lines + ["No change to the generated API.", ""])
    lines += [f"{len(changes)} change(s): {breaking} BREAKING, {len(changes) - breaking} compatible.", ""]
    for kind, section in SECTIONS.items():
        ours = [c for c in changes if c.kind == kind]
        if not ours:
            continue
        lines += [f"{'#' * (level + 1)} {section}", ""]
        ours.sort(key=lambda c: (not c.breaking, c.subject))
        lines += [f"- {'**BREAKING**' if c.breaking else 'compatible'}: {c.change}" for c in ours]
        lines.append("")
    return "\n".join(lines)


def as_json(changes: list[Change], old_name: str, new_name: str) -> str:
    return json.dumps({"old": old_name, "new": new_name, "breaking": sum(c.breaking for c in changes),
                       "changes": [asdict(c) for c in changes]}, indent=2, ensure_ascii=False) + "\n"


# --- spec trees from directories or git revisions ----------------------------------------------

def resolve_tree(arg: str, tmp: Path, label: str) -> Path:
    """A spec directory (or overlay) on disk, or a git revision (REV for its spec/, or REV:DIR) extracted
    into tmp."""
    path = Path(arg)
    if path.is_dir():
        if not upgrade_tree(path, write=False):
            return path
        copy = tmp / label  # written for an older schema: upgraded in a copy
        shutil.copytree(path, copy)
        upgrade_tree(copy)
        return copy
    rev, _, sub = arg.partition(":")
    sub = sub or "spec"
    top = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True, text=True)
    if top.returncode != 0:
        raise ValueError(f"{arg!r} is neither a directory nor a git revision (not in a git repository)")
    prefix = subprocess.run(["git", "rev-parse", "--show-prefix"], capture_output=True, text=True).stdout.strip()
    where = (prefix + sub).strip("/")
    if subprocess.run(["git", "cat-file", "-e", f"{rev}:{where}"], capture_output=True).returncode != 0:
        raise ValueError(f"{arg!r} is neither a directory nor a git revision holding {where}/")
    dest = tmp / label
    dest.mkdir()
    archive = subprocess.run(["git", "-C", top.stdout.strip(), "archive", "--format=tar", rev, where],
                             capture_output=True, check=True)
    subprocess.run(["tar", "-x", "-C", str(dest)], input=archive.stdout, check=True)
    upgrade_tree(dest / where)  # an older release's spec, in today's schema
    return dest / where


def main(args: argparse.Namespace) -> int:
    from .build import load_spec
    with tempfile.TemporaryDirectory(prefix="nmeaspec-diff-") as tmp:
        specs = []
        for arg, label in ((args.old, "old"), (args.new, "new")):
            try:
                tree = resolve_tree(arg, Path(tmp), label)
                specs.append(load_spec(args.spec, [tree]) if args.overlays else load_spec(tree))
            except ValueError as err:
                print(f"diff: {err}", file=sys.stderr)
                return 2
            except SpecErrors as errs:
                print(errs, file=sys.stderr)
                print(f"diff: {arg}: {len(errs.errors)} error(s) in the spec", file=sys.stderr)
                return 2
    changes = compare(*specs)
    print(as_json(changes, args.old, args.new) if args.json else markdown(changes, args.old, args.new), end="")
    return 1 if args.fail_on_breaking and any(c.breaking for c in changes) else 0
