"""`nmea config` and `nmea send ubx`: u-blox configuration keys by name, and any UBX message, sent
to a receiver with the reply the spec pairs with them (nmeaspec.ubx_config, nmeaspec.receiver).

    nmea config get CFG-RATE-MEAS CFG-UART1-BAUDRATE --port /dev/ttyACM0
    nmea config get 'CFG-RATE-*' --layer flash --port /dev/ttyACM0
    nmea config set CFG-RATE-MEAS 0.1 CFG-NAVSPG-DYNMODEL AUTOM --layer ram,bbr --port /dev/ttyACM0
    nmea config del CFG-RATE-MEAS --layer bbr,flash --port /dev/ttyACM0
    nmea config set CFG-RATE-MEAS 0.1 > valset.ubx          no port: the frame to stdout
    nmea send --port /dev/ttyACM0 ubx MON-VER                a poll, and its answer
    nmea send --port /dev/ttyACM0 ubx CFG-RATE '{"meas_rate": 200, "nav_rate": 1, "time_ref": 1}'
    nmea send --port /dev/ttyACM0 ubx b5 62 06 08 00 00 0e 30  a whole frame as hex

Exit status as `nmea send`'s: 0 the receiver acknowledged (ACK-ACK, or the answer to a poll), 1
it refused (ACK-NAK), 2 no reply within --timeout (or a mistake on the command line), 3 the port
cannot be used. Values are in the key's unit (CFG-RATE-MEAS 0.1 is 100 ms); --raw takes and
prints raw integers.
"""

from __future__ import annotations

import argparse
import io
import json
import sys
from dataclasses import replace
from typing import IO, Any

from .. import ubx, ubx_config
from ..ais import Field, Group, Special, flat_fields
from ..receiver import Receiver, ReceiverError, Reply, ReplyTimeout
from ..runtime import NmeaError
from .nmea_cli import CliError, PortProblem, _append_log, _meanwhile, _open_source, _seconds

TRUE = ("1", "true", "on", "yes")
FALSE = ("0", "false", "off", "no")


def config_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="nmea config",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Read, write and delete u-blox configuration keys (CFG-VALGET, CFG-VALSET, "
        "CFG-VALDEL) by name, on a receiver (--port, --tcp) or, without one, as the frame written "
        "to stdout.",
        epilog=__doc__.split("\n\n")[1] if __doc__ else None,
    )
    p.add_argument("action", choices=("get", "set", "del"), help="read, write or delete")
    p.add_argument("words", nargs="+", metavar="KEY [VALUE]",
                   help="get, del: keys (a name, an id 0x..., a group's wildcard CFG-RATE-*); "
                   "set: KEY VALUE pairs")
    p.add_argument("--layer", help="get: one of ram (default), bbr, flash, default; set: layers, "
                   "e.g. ram,bbr,flash (default ram); del: bbr,flash (the default)")
    p.add_argument("--port", metavar="DEVICE", help="the serial port (pyserial)")
    p.add_argument("--tcp", metavar="HOST:PORT", help="a receiver behind TCP")
    p.add_argument("--baud", default="9600", metavar="N", help="its speed in bit/s (default: 9600)")
    p.add_argument("--timeout", default="5", metavar="S", help="how long to wait for each reply (default: 5)")
    p.add_argument("--log", metavar="FILE", help="append every byte received to FILE")
    p.add_argument("--raw", action="store_true", help="values as raw integers (no scale, no enumeration names)")
    p.add_argument("--json", action="store_true", help="get: the values as one JSON object")
    p.add_argument("--show-all", action="store_true", help="print what came before each reply")
    return p


def value_of(key: ubx_config.Key, text: str, raw: bool) -> Any:
    """The typed value of a command-line word for `key` (see ubx_config.Key.to_raw)."""
    word = text.strip()
    try:
        if raw or key.name.startswith("0x"):
            return ubx_config.Raw(int(word, 0))
        if key.type == "L":
            if word.lower() in TRUE + FALSE:
                return word.lower() in TRUE
            raise ValueError
        if key.type[0] == "R":
            return float(word)
        if key.enum:
            by_upper = {name.upper(): name for name in key.enum}
            if word.upper() in by_upper:
                return by_upper[word.upper()]
        if key.divisor != 1:
            return float(word)
        return int(word, 0)
    except ValueError:
        wanted = ("true or false" if key.type == "L" else f"one of {', '.join(key.enum)} or a number" if key.enum
                  else "a number")
        raise CliError(f"{key.name} takes {wanted}, not {text!r}") from None


def _shown(key: ubx_config.Key | None, value: Any, raw: bool) -> str:
    """A value as `config get` prints it: in its unit, an enumeration's name with its number,
    a bitfield in hex; --raw and keys the table does not know: the raw integer."""
    if key is None or raw or key.name.startswith("0x"):
        return str(value)
    text = str(value).lower() if isinstance(value, bool) else str(value)
    if key.type[0] == "X" and isinstance(value, int):
        text = f"0x{value:X}"
    if key.enum and isinstance(value, str):
        text += f" ({key.enum[value]})"
    return f"{text} {key.unit}" if key.unit and not key.enum else text


def _layers(text: str | None, default: str) -> list[str]:
    return [w.strip().lower() for w in (text or default).split(",") if w.strip()]


def _exchange(receiver: Receiver, message: Any, timeout: float, out: IO[str], show_all: bool) -> Reply:
    """Write a UBX message and wait for its reply: printed as `nmea send` prints them."""
    data = receiver.write(message)
    out.write(f"> {data.hex(' ')}\n")
    out.flush()
    try:
        reply = receiver.wait_reply(message, timeout)
    except ReplyTimeout as err:
        if show_all:
            _meanwhile(err.received, out)
        out.flush()
        raise
    if show_all:
        _meanwhile(reply.received, out)
    out.write(f"< {reply.line.hex(' ')}\n")
    return reply


def _built(args: argparse.Namespace) -> list[Any]:
    """The messages an action sends (a get of wildcards may need more: see _get)."""
    db = ubx_config.database()
    if args.action == "set":
        if len(args.words) % 2:
            raise CliError("set takes KEY VALUE pairs")
        pairs: dict[str | int, Any] = {}
        for name, text in zip(args.words[::2], args.words[1::2]):
            k = db.key(name)
            pairs[k.id] = value_of(k, text, args.raw)
        return [db.valset(pairs, _layers(args.layer, "ram"))]
    if args.action == "del":
        return [db.valdel(args.words, _layers(args.layer, "bbr,flash"))]
    layer = _layers(args.layer, "ram")
    if len(layer) != 1:
        raise CliError(f"get reads one layer, not {args.layer!r}")
    return [db.valget(args.words, layer[0])]


def config(argv: list[str]) -> int:
    args = config_parser().parse_args(argv)
    timeout = _seconds("--timeout", args.timeout)
    assert timeout is not None
    try:
        messages = _built(args)
    except NmeaError as err:
        raise CliError(err.message) from None
    if not args.port and not args.tcp:
        for message in messages:
            sys.stdout.buffer.write(message.encode())
        sys.stdout.flush()
        return 0
    out = sys.stdout
    with _open_source(args, errors="yield", binary=True) as receiver:
        receiver.log = log = _append_log(args.log)
        try:
            if args.action == "get":
                return _get(receiver, messages[0], args, timeout, out)
            reply = _exchange(receiver, messages[0], timeout, out, args.show_all)
        except ReplyTimeout as err:
            sys.stderr.write(f"nmea: {err}\n")
            return 2
        except ReceiverError as err:
            raise PortProblem(str(err)) from None
        finally:
            if log is not None:
                log.close()
    out.write(f"{reply.outcome}: {reply.sentence.ADDRESS}\n")
    return 0 if reply.ok else 1


def _get(receiver: Receiver, poll: Any, args: argparse.Namespace, timeout: float, out: IO[str]) -> int:
    """CFG-VALGET, asked again from the next position while the answer to a wildcard is full (64
    values: the group has more)."""
    db = ubx_config.database()
    found: dict[str, Any] = {}
    wildcard = any(e.key & 0xFFFF == ubx_config.WILDCARD_ITEM for e in poll.keys)
    while True:
        reply = _exchange(receiver, poll, timeout, out if not args.json else io.StringIO(), args.show_all)
        if not reply.ok:
            sys.stderr.write(f"nmea: {reply.sentence.ADDRESS}: the receiver refused CFG-VALGET (a key it "
                             "does not know, or more than 64)\n")
            return 1
        try:
            values = db.values(reply.sentence, raw=args.raw)
        except NmeaError as err:
            sys.stderr.write(f"nmea: {err}\n")
            return 1
        found.update(values)
        if len(values) < ubx_config.MAX_KEYS or not wildcard:  # named keys: answered at once
            break
        poll = replace(poll, position=poll.position + len(values))
    if args.json:
        out.write(json.dumps({name: str(v) if isinstance(v, Special) else v for name, v in found.items()}) + "\n")
        return 0
    for name, value in found.items():
        out.write(f"{name} {_shown(db.by_name.get(name), value, args.raw)}\n")
    return 0


# --------------------------------------------------------------------------------------------
# nmea send ubx NAME [JSON] | HEX


def _layouts() -> list[type[ubx.Message]]:
    from ..ubx_messages import BY_ID

    return [c for layouts in BY_ID.values() for c in layouts]


def message_of(words: list[str]) -> Any:
    """The UBX message of `nmea send ubx` words: a whole frame as hex, or a message and its
    values as a JSON object: by address (CFG-RATE: its poll without values, its input with
    them) or by layout id (cfg_rate_poll, cfg_valset_v0)."""
    if not words:
        raise CliError("give a UBX message: NAME [JSON] (e.g. MON-VER, CFG-RATE '{...}') or a frame as hex")
    text = "".join(words).replace(" ", "")
    if text.lower().startswith("b562"):
        try:
            data = bytes.fromhex(text)
        except ValueError:
            raise CliError(f"{' '.join(words)!r} is not a frame in hex") from None
        from ..ubx_messages import decode

        try:
            return decode(data)
        except NmeaError as err:
            raise CliError(str(err)) from None
    name, values_text = words[0], " ".join(words[1:])
    try:
        values = json.loads(values_text) if values_text else None
    except json.JSONDecodeError as err:
        raise CliError(f"the values of {name} are not a JSON object: {err}") from None
    if values is not None and not isinstance(values, dict):
        raise CliError(f"the values of {name} are a JSON object, not {values_text!r}")
    layouts = _layouts()
    chosen = [c for c in layouts if c.ID == name.lower()]   # a layout id: cfg_rate_poll
    if not chosen:  # an address (CFG-RATE): its poll without values, else its input
        same = [c for c in layouts if c.ADDRESS == name.upper().replace("_", "-", 1)]
        wanted = ("input",) if values else ("poll", "input")
        chosen = [c for d in wanted for c in same if d in c.DIRECTIONS][:1]
        selected = [c for c in same if "input" in c.DIRECTIONS and c.SELECT is not None and c.SELECT[0] in (values or {})]
        if values and selected:   # the layout whose selector (type, version) has the value given
            chosen = [c for c in selected if c.SELECT is not None and c.SELECT[2] == values[c.SELECT[0]]][:1]
        if not chosen:
            sent = sorted({c.ADDRESS for c in layouts if {"poll", "input"} & set(c.DIRECTIONS)})
            raise CliError(f"no UBX message {name!r} to send; these are sent: {', '.join(sent)}")
    cls = chosen[0]
    try:
        return _from_values(cls, values or {})
    except NmeaError as err:
        raise CliError(str(err)) from None
    except TypeError as err:
        raise CliError(f"UBX {cls.ADDRESS}: {err}") from None


def _from_values(cls: type[ubx.Message], values: dict[str, Any]) -> Any:
    """A message of layout `cls` with `values` (by member; bytes as hex, a group as a list of
    objects), the rest zero; written and read again, so that it is what the receiver will read."""
    size = 0
    for item in cls.LAYOUT:
        if isinstance(item, Group):
            size += item.entry_width * (item.count if isinstance(item.count, int) else item.min)
        elif isinstance(item, Field):
            size += item.width or 0
    payload = bytearray(size // 8)
    if cls.SELECT is not None:
        payload[cls.SELECT[1]] = cls.SELECT[2]
    message = cls.read_generic(bytes(payload))
    fields = {f.id: f for f in flat_fields(cls.LAYOUT)}
    groups = {g.id: g for g in cls.LAYOUT if isinstance(g, Group)}
    changes: dict[str, Any] = {}
    for member, value in values.items():
        if member in groups:
            group = groups[member]
            if not isinstance(value, list) or not all(isinstance(e, dict) for e in value):
                raise CliError(f"UBX {cls.ADDRESS}: {member} is a list of objects")
            changes[member] = [group.entry(**e) for e in value]
            if isinstance(group.count, str) and group.count not in values:
                changes[group.count] = None
        elif member in fields:
            if isinstance(fields[member], ubx.Bytes) and isinstance(value, str):
                value = bytes.fromhex(value)
            changes[member] = value
        else:
            raise CliError(f"UBX {cls.ADDRESS} has no member {member!r}: {', '.join(fields)}")
    built = replace(message, **changes)
    return type(built).from_payload(built.payload())


def send_ubx(args: argparse.Namespace) -> int:
    """`nmea send ... ubx NAME [JSON] | HEX`."""
    timeout = _seconds("--timeout", args.timeout)
    assert timeout is not None
    message = message_of(args.words[1:])
    out = sys.stdout
    with _open_source(args, errors="yield", binary=True) as receiver:
        receiver.log = log = _append_log(args.log)
        try:
            if not message.REPLIES:
                data = receiver.write(message)
                out.write(f"> {data.hex(' ')}\nnothing answers UBX {message.ADDRESS} in the spec: sent, not waiting\n")
                return 0
            reply = _exchange(receiver, message, timeout, out, args.show_all)
        except ReplyTimeout as err:
            sys.stderr.write(f"nmea: {err}\n")
            return 2
        except ReceiverError as err:
            raise PortProblem(str(err)) from None
        finally:
            if log is not None:
                log.close()
    fields = {k: v for k, v in reply.sentence.to_dict().items() if k not in ("message", "trailing")}
    summary = " ".join(f"{k}={v}" for k, v in fields.items() if not isinstance(v, (list, dict)))
    out.write(f"{reply.outcome}: {reply.sentence.ADDRESS}  {summary}\n".rstrip() + "\n")
    if reply.sentence.ID == "cfg_valget":
        for name, value in ubx_config.values(reply.sentence).items():
            out.write(f"  {name} {_shown(ubx_config.database().by_name.get(name), value, False)}\n")
    out.flush()
    return 0 if reply.ok else 1
