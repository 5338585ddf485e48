"""`nmea export`: logs as Parquet tables, for pandas, Polars, DuckDB, Spark and the like.

    nmea export drive1.nmea drive2.nmea -o tables/

writes into tables/:

- `fixes.parquet`: one row per epoch (nmeaspec.fixes: date and time, position, altitudes, speed,
  mode, DOPs, errors, satellites used and in view), with the log and the lines it came from;
- one file per sentence type seen (`GGA.parquet`, `PUBX_POSITION.parquet`, ...): one row per
  sentence, a column per field as the sentence's `to_dict()` gives it (numbers as int64 or
  float64, coordinates in signed decimal degrees, times, dates, enums as their value ids, a
  repeated group as a list), the variant it was read as, the problems tolerant reading noted,
  and the log and line;
- one file per AIS message kind decoded from VDM/VDO sentences, assembled across sentences
  (`ais_position_report.parquet`, `ais_static_voyage_data.parquet`, ...): a column per field, a
  number in its unit beside its raw integer (`speed`, `speed_raw`) and its special value's name
  where it has one (`heading_special`: not_available), codes as value ids, text as sent;
- `unknown.parquet`: the well-formed sentences the spec does not describe (address, fields);
- `errors.parquet`: the lines that do not decode (kind, message, the line as text).

A table's columns follow from the spec, not from what a log holds, so the tables of separate
exports (one per log, on many machines: docs/export.md) have the same schema and concatenate.
Rows are written in row groups as they come: memory stays bounded however long the logs are.
pyarrow is an optional dependency (`pip install 'nmeaspec[parquet]'`), imported only here.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime as dt
import os
import sys
import types
import typing
from collections.abc import Iterable, Iterator
from typing import Any

from .. import ais
from .. import fixes as fix_module
from .. import runtime as rt
from ..ais_messages import BY_TYPE
from ..assembly import MessageAssembler
from ..api import Generic, Tagged, parse
from ..runtime import NmeaError
from ..sentences import layouts
from ..stream import lines, too_long
from .nmea_cli import CliError, Progress, _chunks, add_progress_options, open_log, progress_for

EXPORT_EXAMPLES = """\
examples:
  nmea export track.nmea -o tables/          fixes.parquet, GGA.parquet, RMC.parquet, ... in tables/
  nmea export logs/*.nmea -o tables/ --progress
  nmea export --only fixes logs/*.nmea -o tables/

Read them with pandas.read_parquet("tables/fixes.parquet"), duckdb, polars or pyarrow. Writing
needs pyarrow: pip install 'nmeaspec[parquet]'.
"""

INSTALL_HINT = "nmea export writes Parquet with pyarrow, which is not installed: " \
    "pip install 'nmeaspec[parquet]'"

ROW_GROUP = 16384  # rows of one table written together
BUFFERED = 131072  # rows held in all tables together before every table is written out

FIXES = "fixes"
UNKNOWN = "unknown"
ERRORS = "errors"
AIS = "ais_"  # the prefix of an AIS message kind's table: ais_position_report


# --- Rows --------------------------------------------------------------------------------------

class Row(typing.NamedTuple):
    """One row of one table."""

    table: str
    values: dict[str, Any]


def rows(items: Iterable[bytes | int], log: str) -> Iterator[Row]:
    """The rows of a log's framed lines (nmeaspec.stream.lines): one per sentence, unknown
    sentence or error, and one per fix as its epoch ends. The engine-neutral core of the export:
    docs/export.md feeds it to Dask."""
    assembler = fix_module.FixAssembler()
    messages = MessageAssembler()
    first = last = number = 0  # the lines of the epoch under way that carried facts; the line
    for number, item in enumerate(items, 1):
        try:
            if isinstance(item, int):
                raise too_long(item)
            sentence = parse(item)
        except NmeaError as err:
            text = f"({item} bytes)" if isinstance(item, int) else item.decode("latin-1")
            yield Row(ERRORS, {"log": log, "line": number, "kind": err.kind,
                               "message": str(err), "text": text})
            continue
        for done in messages.feed(sentence):
            if done.message is not None:
                yield _ais_row(done.message, log, number)
        if isinstance(sentence, Tagged):  # the sentence behind its TAG blocks, if any
            sentence = sentence.sentence
            if sentence is None:
                continue
        if isinstance(sentence, Generic):
            yield Row(UNKNOWN, {"log": log, "line": number, "address": sentence.address,
                                "fields": list(sentence.fields)})
            continue
        yield Row(sentence.SENTENCE, _sentence_row(sentence, log, number))
        if fix_module.carries_facts(sentence):
            fix = assembler.feed(sentence)
            if fix is not None:
                yield Row(FIXES, _fix_row(fix, log, first, last))
                first = 0
            first, last = first or number, number
    fix = assembler.close()
    if fix is not None:
        yield Row(FIXES, _fix_row(fix, log, first, last))
    # what is left incomplete at the end of the log is no message
    for done in messages.finish():
        if done.message is not None:
            yield _ais_row(done.message, log, number)


def _sentence_row(sentence: Any, log: str, number: int) -> dict[str, Any]:
    row: dict[str, Any] = {"log": log, "line": number}
    if sentence.ADDRESS is None:  # a standard sentence: its talker
        row["talker"] = sentence.talker
    row["variant"] = sentence.VARIANT
    row.update(sentence.LAYOUT.to_dict(sentence))
    row["problems"] = [_problem(p) for p in sentence.problems]
    return row


def _problem(problem: NmeaError) -> dict[str, Any]:
    return {"kind": problem.problem_kind, "field": problem.name, "message": str(problem)}


def _ais_row(message: Any, log: str, number: int) -> Row:
    """An AIS message's row; `number`: the line of its last sentence."""
    row: dict[str, Any] = {"log": log, "line": number}
    for item in message.LAYOUT:
        if isinstance(item, ais.Group):
            row[item.id] = [_ais_values(entry, item.fields, {}) for entry in getattr(message, item.id) or ()]
    _ais_values(message, _ais_fields(message.LAYOUT), row)
    row["trailing"], row["padding"] = message.trailing, message.padding
    return Row(AIS + message.ID, row)


def _ais_fields(items: Iterable[Any]) -> list[Any]:
    """The fields outside groups, each id once (a choice's cases may name one twice)."""
    seen: dict[str, Any] = {}
    for f in ais.flat_fields(tuple(items)):
        seen.setdefault(f.id, f)
    return list(seen.values())


def _ais_values(record: Any, fields: Iterable[Any], row: dict[str, Any]) -> dict[str, Any]:
    """The columns of `fields` of a message or group entry, into `row`."""
    for f in fields:
        value = getattr(record, f.id, None)
        if isinstance(f, ais.Unsigned):
            number = value if isinstance(value, (int, float)) and not isinstance(value, bool) else None
            row[f.id] = float(number) if number is not None and _scaled(f) else number
            if _scaled(f) or f.special:
                row[f"{f.id}_raw"] = None if value is None else f.raw_number(value, "")
            if f.special:
                row[f"{f.id}_special"] = value.id if isinstance(value, ais.Special) else None
        elif isinstance(f, ais.Code):
            row[f.id] = None if value is None else value.name.lower() if isinstance(value, f.enum) else str(value)
        else:
            row[f.id] = value
    return row


def _scaled(f: Any) -> bool:
    """Whether a number's value is in a unit (a float), not its raw integer."""
    return f.divisor != 1 or isinstance(f.base, float)


def _fix_row(fix: fix_module.Fix, log: str, first: int, last: int) -> dict[str, Any]:
    row: dict[str, Any] = {"log": log, "first_line": first, "last_line": last,
                           "datetime": fix.datetime}
    for member in dataclasses.fields(fix):
        value = getattr(fix, member.name)
        if member.name == "in_view":
            value = [dataclasses.asdict(s) for s in value]
        elif member.name == "used":
            value = [{"system": system, "id": id} for system, ids in value.items() for id in ids]
        row[member.name] = value
    row["used_count"], row["in_view_count"] = fix.used_count, fix.in_view_count
    return row


# --- Schemas: from the spec's layouts and the Fix type, never from the data ---------------------

def _arrow_type(pa: Any, hint: Any) -> Any:
    """The Arrow type of a plain Python type (a type hint: int, float, list[str], a dataclass)."""
    origin, args = typing.get_origin(hint), typing.get_args(hint)
    if origin in (typing.Union, types.UnionType):  # X | None: the column is nullable anyway
        (hint,) = [a for a in args if a is not type(None)]
        return _arrow_type(pa, hint)
    if origin is list:
        return pa.list_(_arrow_type(pa, args[0]))
    if dataclasses.is_dataclass(hint):
        hints = typing.get_type_hints(hint)
        return pa.struct([(f.name, _arrow_type(pa, hints[f.name])) for f in dataclasses.fields(hint)])
    scalar = {
        int: pa.int64(), float: pa.float64(), str: pa.string(), bool: pa.bool_(),
        dt.time: pa.time64("us"), dt.date: pa.date32(),
        dt.datetime: pa.timestamp("us", tz="UTC"),
    }
    return scalar[hint]


@dataclasses.dataclass
class _Problem:
    kind: str
    field: str | None
    message: str


@dataclasses.dataclass
class _Used:
    system: str
    id: int


def sentence_schema(pa: Any, layouts: Iterable[Any]) -> Any:
    """The schema of a sentence type's table: the columns of all its layouts (variants), the
    first layout's order first, a column met again taken once."""
    layouts = list(layouts)
    columns: dict[str, Any] = {"log": pa.string(), "line": pa.int64()}
    if layouts[0].ADDRESS is None:
        columns["talker"] = pa.string()
    columns["variant"] = pa.string()
    for layout in layouts:
        for item in layout.LAYOUT.items:
            if isinstance(item, rt.Group):
                if item.entry is None:
                    kind = pa.list_(_arrow_type(pa, item.fields[0].PLAIN))
                else:
                    kind = pa.list_(pa.struct([(f.id, _arrow_type(pa, f.PLAIN)) for f in item.fields]))
            else:
                kind = _arrow_type(pa, item.PLAIN)
            known = columns.get(item.id)
            try:
                columns[item.id] = kind if known is None else _merged(pa, known, kind)
            except TypeError:
                raise ValueError(f"{layout.SENTENCE}: field {item.id} is {known} in one layout "
                                 f"and {kind} in another") from None
    columns["problems"] = pa.list_(_arrow_type(pa, _Problem))
    return pa.schema(list(columns.items()))


def _merged(pa: Any, a: Any, b: Any) -> Any:
    """One type for a column two layouts give (a group whose entries differ by layout: a struct of
    the members of both); TypeError when they cannot be one."""
    if a == b:
        return a
    if pa.types.is_list(a) and pa.types.is_list(b):
        return pa.list_(_merged(pa, a.value_type, b.value_type))
    if pa.types.is_struct(a) and pa.types.is_struct(b):
        members = {a.field(i).name: a.field(i).type for i in range(a.num_fields)}
        for i in range(b.num_fields):
            name, kind = b.field(i).name, b.field(i).type
            members[name] = kind if name not in members else _merged(pa, members[name], kind)
        return pa.struct(list(members.items()))
    raise TypeError(f"{a} and {b}")


def _ais_field_columns(pa: Any, f: Any) -> list[tuple[str, Any]]:
    if isinstance(f, ais.Unsigned):
        columns = [(f.id, pa.float64() if _scaled(f) else pa.int64())]
        if _scaled(f) or f.special:
            columns.append((f"{f.id}_raw", pa.int64()))
        if f.special:
            columns.append((f"{f.id}_special", pa.string()))
        return columns
    if isinstance(f, ais.Flag):
        return [(f.id, pa.bool_())]
    if isinstance(f, (ais.Code, ais.Text, ais.Data)):
        return [(f.id, pa.string())]
    return [(f.id, pa.int64())]  # spare bits, a bitfield's word: their raw integer


def ais_schema(pa: Any, cls: Any) -> Any:
    """The schema of an AIS message kind's table."""
    columns: list[tuple[str, Any]] = [("log", pa.string()), ("line", pa.int64())]
    for f in _ais_fields(cls.LAYOUT):
        columns += _ais_field_columns(pa, f)
    for item in cls.LAYOUT:
        if isinstance(item, ais.Group):
            entry = [c for f in item.fields for c in _ais_field_columns(pa, f)]
            columns.append((item.id, pa.list_(pa.struct(entry))))
    columns += [("trailing", pa.string()), ("padding", pa.string())]
    return pa.schema(columns)


def fix_schema(pa: Any) -> Any:
    hints = typing.get_type_hints(fix_module.Fix)
    columns: list[tuple[str, Any]] = [
        ("log", pa.string()), ("first_line", pa.int64()), ("last_line", pa.int64()),
        ("datetime", _arrow_type(pa, dt.datetime)),
    ]
    for member in dataclasses.fields(fix_module.Fix):
        hint = list[_Used] if member.name == "used" else hints[member.name]
        columns.append((member.name, _arrow_type(pa, hint)))
    columns += [("used_count", pa.int64()), ("in_view_count", pa.int64())]
    return pa.schema(columns)


def schema(pa: Any, table: str) -> Any:
    """The schema of a table by its name (a sentence id, fixes, unknown or errors)."""
    if table == FIXES:
        return fix_schema(pa)
    if table == UNKNOWN:
        return pa.schema([("log", pa.string()), ("line", pa.int64()), ("address", pa.string()),
                          ("fields", pa.list_(pa.string()))])
    if table.startswith(AIS):
        kinds = {cls.ID: cls for cls in BY_TYPE.values()}
        if table[len(AIS):] in kinds:
            return ais_schema(pa, kinds[table[len(AIS):]])
    if table == ERRORS:
        return pa.schema([("log", pa.string()), ("line", pa.int64()), ("kind", pa.string()),
                          ("message", pa.string()), ("text", pa.string())])
    found = layouts(table)
    if found is None:
        raise ValueError(f"no table {table}: not a sentence id of the spec")
    return sentence_schema(pa, found)


# --- Writing -------------------------------------------------------------------------------------

class Writer:
    """Tables of rows written as Parquet files into a directory, a row group at a time."""

    def __init__(self, directory: str, only: set[str] | None = None) -> None:
        self.pa, self.pq = _pyarrow()
        self.directory = directory
        self.only = only
        self.counts: dict[str, int] = {}
        self._rows: dict[str, list[dict[str, Any]]] = {}
        self._writers: dict[str, Any] = {}
        self._schemas: dict[str, Any] = {}
        self._buffered = 0

    def add(self, row: Row) -> None:
        if self.only is not None and row.table not in self.only:
            return
        self._rows.setdefault(row.table, []).append(row.values)
        self.counts[row.table] = self.counts.get(row.table, 0) + 1
        self._buffered += 1
        if len(self._rows[row.table]) >= ROW_GROUP:
            self._flush(row.table)
        elif self._buffered >= BUFFERED:
            for table in list(self._rows):
                self._flush(table)

    def _flush(self, table: str) -> None:
        rows = self._rows.pop(table, [])
        if not rows:
            return
        self._buffered -= len(rows)
        if table not in self._writers:
            self._schemas[table] = schema(self.pa, table)
            path = os.path.join(self.directory, f"{table}.parquet")
            self._writers[table] = self.pq.ParquetWriter(path, self._schemas[table])
        batch = self.pa.Table.from_pylist(rows, schema=self._schemas[table])
        self._writers[table].write_table(batch)

    def close(self) -> None:
        for table in list(self._rows):
            self._flush(table)
        for writer in self._writers.values():
            writer.close()


def export_logs(paths: Iterable[str], directory: str, only: set[str] | None = None,
                progress: Progress | None = None) -> dict[str, int]:
    """Export logs (files; - for stdin) into `directory` (made if need be); the rows written per
    table."""
    os.makedirs(directory, exist_ok=True)
    writer = Writer(directory, only)
    try:
        for path in paths:
            source, _ = open_log(path)
            name = "stdin" if path == "-" else os.path.basename(path)
            try:
                for row in rows(lines(_chunks(source, progress)), name):
                    writer.add(row)
            finally:
                if source is not sys.stdin.buffer:
                    source.close()
    finally:
        writer.close()
    return writer.counts


def _pyarrow() -> tuple[Any, Any]:
    try:
        import pyarrow  # type: ignore[import-not-found, unused-ignore]
        import pyarrow.parquet  # type: ignore[import-not-found, unused-ignore]
    except ImportError:
        raise CliError(INSTALL_HINT) from None
    return pyarrow, pyarrow.parquet


def export(args: argparse.Namespace) -> int:
    _pyarrow()  # before reading long logs for nothing
    sizes = []
    for path in args.logs:
        if path != "-" and not os.path.isfile(path):
            raise CliError(f"cannot read {path}: No such file or directory")
        sizes.append(0 if path == "-" else os.path.getsize(path))
    progress = progress_for(args.progress, sum(sizes))
    only = set(args.only.split(",")) if args.only else None
    try:
        counts = export_logs(args.logs, args.output, only, progress)
    except OSError as err:
        raise CliError(f"cannot write {args.output}: {err.strerror}") from None
    if progress is not None:
        progress.finish()
    if not args.quiet:
        tables = ", ".join(f"{table} {count}" for table, count in sorted(counts.items()))
        sys.stderr.write(f"wrote {len(counts)} tables to {args.output}: {tables or 'no rows'}\n")
    return 0


def add_parser(verbs: Any) -> None:
    """The `export` verb of `nmea` (nmea_cli.py)."""
    e = verbs.add_parser(
        "export",
        help="write logs as Parquet tables: the fixes, one table per sentence type, errors",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=EXPORT_EXAMPLES,
    )
    e.add_argument("logs", nargs="+", metavar="LOG", help="the log files (- for stdin)")
    e.add_argument("-o", "--output", required=True, metavar="DIR",
                   help="the directory to write the tables into (made if need be)")
    e.add_argument("--only", metavar="TABLES",
                   help="only these tables, comma-separated (fixes, GGA, unknown, errors, ...)")
    add_progress_options(e)
    e.add_argument("-q", "--quiet", action="store_true", help="no summary line on stderr")
    e.set_defaults(run=export)
