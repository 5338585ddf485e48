"""The u-blox configuration database (generation 9 receivers and later): keys by name, and the
UBX-CFG-VALSET, -VALGET and -VALDEL messages that write, read and delete their values.

    from nmeaspec import ubx_config

    frame = ubx_config.valset({"CFG-RATE-MEAS": 0.1, "CFG-UART1-BAUDRATE": 115200}, layers=("ram", "bbr"))
    poll = ubx_config.valget(["CFG-RATE-*"], layer="ram")
    values = ubx_config.values(reply)     # {"CFG-RATE-MEAS": 0.1, "CFG-RATE-NAV": 1, ...}

A key is named as u-blox names it (CFG-RATE-MEAS; CFG_RATE_MEAS too, and an alias a receiver's
documents use), or given by its 32-bit id. A value is typed by its key: L a bool, an enumeration
(E1..E4) the name of its value (an int when the table does not name it), a scaled number its
value in the key's unit (raw integer / divisor: CFG-RATE-MEAS 0.1 s is raw 100), the rest ints
and R4/R8 floats (a NaN kept as a Special with its bits). Raw(n) gives a key its raw integer as
it is. A key id the table does not know is read as its raw integer, its size from the id's bits
28-30 (1 one bit in a byte, 2 one byte, 3 two, 4 four, 5 eight), and named "0x<id>"; writing
back gives the same bytes. The keys, their types, scales and units are the spec's
(spec/binary/ubx/config_keys.yaml, the generated nmeaspec.ubx_config_keys). Facts from u-blox
UBX-18010854 (ZED-F9P Interface description: "Configuration interface": keys, layers,
transactions and wildcards).
"""

from __future__ import annotations

import struct
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from .ais import Special
from .runtime import NmeaError

__all__ = ["Database", "Key", "Raw", "SET_LAYERS", "GET_LAYERS", "database", "key", "valdel", "valget", "valset",
           "values"]

SET_LAYERS = {"ram": 0x01, "bbr": 0x02, "flash": 0x04}
"""The `layers` bits of CFG-VALSET and CFG-VALDEL (VALDEL: bbr and flash only)."""
GET_LAYERS = {"ram": 0, "bbr": 1, "flash": 2, "default": 7}
"""The `layer` number of CFG-VALGET."""
SIZES = {1: 1, 2: 1, 3: 2, 4: 4, 5: 8}
"""The value's bytes by the size code of its key id (bits 28-30)."""
MAX_KEYS = 64
"""Most keys (or key-value pairs) one message carries."""
ALL_KEYS = 0x0FFFFFFF
"""The key id of every item of every group (CFG-*)."""
WILDCARD_ITEM = 0xFFFF
"""The item id (bits 0-15) of a group's wildcard (CFG-RATE-*)."""


class Raw(NamedTuple):
    """A key's raw integer, written as it is (no scale, no enumeration)."""

    value: int


@dataclass(frozen=True, slots=True)
class Key:
    """One configuration key: its name (CFG-RATE-MEAS), 32-bit id, type (L, U1..U8, I1..I8,
    X1..X8, E1..E4, R4, R8), the divisor of a scaled number (raw / divisor is the value in
    `unit`), its enumeration (value names) and its description."""

    name: str
    id: int
    type: str
    divisor: int = 1
    unit: str | None = None
    enum: Mapping[str, int] | None = None
    doc: str = ""
    _names: Mapping[int, str] = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.enum:
            object.__setattr__(self, "_names", {v: k for k, v in self.enum.items()})

    @property
    def size(self) -> int:
        """The value's bytes."""
        return SIZES[self.id >> 28 & 7]

    def from_raw(self, raw: int) -> Any:
        """The typed value of the raw integer (the value's bytes, little endian, unsigned)."""
        kind = self.type[0]
        if kind == "L":
            return bool(raw) if raw in (0, 1) else raw
        if kind == "R":
            value = struct.unpack("<f" if self.size == 4 else "<d", raw.to_bytes(self.size, "little"))[0]
            return value if value == value else Special("nan", raw)
        if kind == "I" and raw >> (8 * self.size - 1):
            raw -= 1 << 8 * self.size
        if kind in "EU" and self._names:
            name = self._names.get(raw)
            if name is not None:
                return name
        return raw if self.divisor == 1 else raw / self.divisor

    def to_raw(self, value: Any, where: str = "UBX CFG-VALSET") -> int:
        """The raw integer (unsigned, the value's bytes) of a typed value; NmeaError bad_value
        naming the key when the value is not one of its type or does not fit."""
        bits = 8 * self.size
        if isinstance(value, Raw):
            raw = value.value
        elif isinstance(value, Special) and self.type[0] == "R":
            return value.raw
        elif self.type == "L":
            if value not in (True, False) or not isinstance(value, (bool, int)):
                raise _bad(self, value, "true or false", where)
            return int(value)
        elif self.type[0] == "R":
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise _bad(self, value, "a number", where)
            return int.from_bytes(struct.pack("<f" if bits == 32 else "<d", value), "little")
        elif isinstance(value, str):
            if not self.enum or value not in self.enum:
                names = f"one of {', '.join(self.enum)}" if self.enum else "a number"
                raise _bad(self, value, names, where)
            raw = self.enum[value]
        elif isinstance(value, bool) or not isinstance(value, (int, float)):
            raise _bad(self, value, "a number", where)
        elif self.divisor == 1 and not isinstance(value, int):
            raise _bad(self, value, "a whole number", where)
        else:
            raw = round(value * self.divisor)
        low, high = (-(1 << bits - 1), (1 << bits - 1) - 1) if self.type[0] == "I" else (0, (1 << bits) - 1)
        if not low <= raw <= high:
            unit = f" ({self.unit} x {self.divisor})" if self.divisor != 1 else ""
            raise _bad(self, value, f"a raw value {low}..{high}{unit}", where)
        return raw & ((1 << bits) - 1)


def _normal(name: str) -> str:
    """A key's name as u-blox writes it: CFG_RATE_MEAS and cfg-rate-meas are CFG-RATE-MEAS (a
    group's name has no underscore; an item's may)."""
    text = name.strip().upper()
    return text if "-" in text else text.replace("_", "-", 2)


def _bad(key: Key, value: Any, wanted: str, where: str) -> NmeaError:
    return NmeaError("bad_value", f"{key.name} takes {wanted}, not {value!r}", where, name=key.name)


def _unknown(key_id: int) -> Key:
    """A key id the table does not know: its raw integer, sized by its id."""
    return Key(f"0x{key_id:08X}", key_id, "X" if key_id >> 28 & 7 != 1 else "L")


class Database:
    """The keys of a configuration database, by name and by id, and its groups' ids (a group's
    wildcard: CFG-RATE-*)."""

    def __init__(self, keys: Iterable[Key], groups: Mapping[str, tuple[int, ...]],
                 aliases: Mapping[str, str] | None = None) -> None:
        self.keys = tuple(keys)
        self.by_id = {k.id: k for k in self.keys}
        self.by_name = {k.name: k for k in self.keys}
        for alias, name in (aliases or {}).items():
            self.by_name[alias] = self.by_name[name]
        self.groups = dict(groups)

    def key(self, name: str | int) -> Key:
        """The key of a name (CFG-RATE-MEAS or CFG_RATE_MEAS, any case) or id (an int, or its
        text 0x30210001: a key the table does not know is sized by its id); NmeaError
        unknown_key when there is none."""
        if isinstance(name, int):
            return self.by_id.get(name) or self._sized(name, f"0x{name:08X}")
        text = _normal(name)
        found = self.by_name.get(text)
        if found is not None:
            return found
        if text.startswith("0X"):
            try:
                number = int(text, 16)
            except ValueError:
                number = -1
            if 0 <= number <= 0xFFFFFFFF:
                return self.by_id.get(number) or self._sized(number, name)
        raise NmeaError("unknown_key", f"no configuration key {name!r}{self._near(text)}", "UBX CFG", name=name)

    def _near(self, text: str) -> str:
        group = text.rsplit("-", 1)[0]
        if group in self.groups:
            return f" (keys of {group}: {', '.join(k.name for k in self.keys if k.name.startswith(group + '-'))[:200]})"
        return ""

    @staticmethod
    def _sized(key_id: int, name: str) -> Key:
        if key_id >> 28 & 7 not in SIZES:
            raise NmeaError("unknown_key", f"key id {name}: bits 28-30 ({key_id >> 28 & 7}) give no value size",
                            "UBX CFG", name=name)
        return _unknown(key_id)

    def key_ids(self, names: Iterable[str | int]) -> list[int]:
        """The key ids of names, ids and wildcards: CFG-RATE-* (the group's id, item 0xFFFF; a
        group of two ids gives both), CFG-* (every key)."""
        ids: list[int] = []
        for name in names:
            if isinstance(name, str) and name.strip().endswith("*"):
                group = name.strip().upper().rstrip("*").rstrip("-_").replace("_", "-")
                if group == "CFG":
                    ids.append(ALL_KEYS)
                    continue
                if group not in self.groups:
                    raise NmeaError("unknown_key", f"no configuration group {group!r} for {name!r}", "UBX CFG",
                                    name=name)
                ids += [group_id << 16 | WILDCARD_ITEM for group_id in self.groups[group]]
            else:
                ids.append(self.key(name).id)
        if not 1 <= len(ids) <= MAX_KEYS:
            raise NmeaError("bad_value", f"a message carries 1 to {MAX_KEYS} keys, not {len(ids)}", "UBX CFG")
        return ids

    def encode_values(self, pairs: Mapping[str | int, Any], where: str = "UBX CFG-VALSET") -> bytes:
        """The key-value pairs as CFG-VALSET's and CFG-VALGET's cfg_data: each key id (u4) and its
        value in the bytes its id gives, in the order given."""
        if not 1 <= len(pairs) <= MAX_KEYS:
            raise NmeaError("bad_value", f"a message carries 1 to {MAX_KEYS} values, not {len(pairs)}", where)
        out = bytearray()
        for name, value in pairs.items():
            k = self.key(name)
            out += k.id.to_bytes(4, "little") + k.to_raw(value, where).to_bytes(k.size, "little")
        return bytes(out)

    def decode_values(self, data: bytes, where: str = "UBX CFG-VALGET", raw: bool = False) -> dict[str, Any]:
        """cfg_data's key-value pairs, by key name, typed (`raw`: their raw integers, unsigned; a
        key the table does not know: by "0x<id>", its raw integer). NmeaError short_payload naming the key whose id or value
        the data cuts; bad_key when a key id's size bits give no size."""
        out: dict[str, Any] = {}
        at = 0
        while at < len(data):
            if len(data) - at < 4:
                raise NmeaError("short_payload", f"a key id needs 4 bytes at byte {at}, there are {len(data) - at}",
                                where, name="key")
            key_id = int.from_bytes(data[at:at + 4], "little")
            k = self.by_id.get(key_id)
            if k is None:
                if key_id >> 28 & 7 not in SIZES:
                    raise NmeaError("bad_key", f"key id 0x{key_id:08X} at byte {at}: bits 28-30 "
                                    f"({key_id >> 28 & 7}) give no value size", where, name=f"0x{key_id:08X}")
                k = _unknown(key_id)
            at += 4
            if len(data) - at < k.size:
                raise NmeaError("short_payload", f"{k.name} needs {k.size} bytes at byte {at}, there are "
                                f"{len(data) - at}", where, name=k.name)
            number = int.from_bytes(data[at:at + k.size], "little")
            at += k.size
            out[k.name] = number if raw or k.name[0] == "0" else k.from_raw(number)
        return out

    def valset(self, pairs: Mapping[str | int, Any], layers: Iterable[str] = ("ram",),
               transaction: int | None = None) -> Any:
        """CFG-VALSET writing `pairs` (key -> typed value) to `layers` (ram, bbr, flash): version 0,
        or version 1 with a transaction action (0 none, 1 (re)start, 2 continue, 3 apply and end)."""
        bits = _layer_bits(layers, SET_LAYERS, "CFG-VALSET")
        data = self.encode_values(pairs)
        if transaction is None:
            return _message(0x8A, bytes((0, bits, 0, 0)) + data)
        if transaction not in range(4):
            raise NmeaError("bad_value", f"a transaction action is 0 to 3, not {transaction!r}", "UBX CFG-VALSET",
                            name="action")
        return _message(0x8A, bytes((1, bits, transaction, 0)) + data)

    def valget(self, names: Iterable[str | int], layer: str = "ram", position: int = 0) -> Any:
        """CFG-VALGET's poll of keys (names, ids, wildcards) from `layer` (ram, bbr, flash,
        default), answered from the `position`-th item on."""
        if layer not in GET_LAYERS:
            raise NmeaError("bad_value", f"CFG-VALGET reads one layer of {', '.join(GET_LAYERS)}, not {layer!r}",
                            "UBX CFG-VALGET", name="layer")
        if not 0 <= position <= 0xFFFF:
            raise NmeaError("bad_value", f"position is 0 to 65535, not {position!r}", "UBX CFG-VALGET",
                            name="position")
        ids = self.key_ids(names)
        return _message(0x8B, bytes((0, GET_LAYERS[layer])) + position.to_bytes(2, "little")
                        + b"".join(i.to_bytes(4, "little") for i in ids))

    def valdel(self, names: Iterable[str | int], layers: Iterable[str] = ("bbr", "flash")) -> Any:
        """CFG-VALDEL (version 0) deleting keys (names, ids, wildcards) from `layers` (bbr, flash)."""
        bits = _layer_bits(layers, {"bbr": 0x02, "flash": 0x04}, "CFG-VALDEL")
        ids = self.key_ids(names)
        return _message(0x8C, bytes((0, bits, 0, 0)) + b"".join(i.to_bytes(4, "little") for i in ids))

    def values(self, message: Any, raw: bool = False) -> dict[str, Any]:
        """The typed values (`raw`: raw integers) of a decoded CFG-VALGET answer or CFG-VALSET
        message (its cfg_data)."""
        data = getattr(message, "cfg_data", None)
        if not isinstance(data, bytes):
            raise TypeError(f"{type(message).__name__} carries no configuration values")
        return self.decode_values(data, f"UBX {getattr(message, 'ADDRESS', 'CFG')}", raw)


def _layer_bits(layers: Iterable[str], known: Mapping[str, int], address: str) -> int:
    names = [layers] if isinstance(layers, str) else list(layers)
    bits = 0
    for name in names:
        bit = known.get(name)
        if bit is None:
            raise NmeaError("bad_value", f"{address} takes the layers {', '.join(known)}, not {name!r}",
                            f"UBX {address}", name="layers")
        bits |= bit
    if not bits:
        raise NmeaError("bad_value", f"{address} needs a layer", f"UBX {address}", name="layers")
    return bits


def _message(msg_id: int, payload: bytes) -> Any:
    """The CFG message (class 0x06) of a payload, as nmeaspec.ubx_messages decodes it (imported
    when needed): the layout its version picks."""
    from . import ubx
    from .ubx_messages import message

    return message(ubx.Frame(0x06, msg_id, payload))


_DATABASE: list[Database] = []


def database() -> Database:
    """The spec's configuration database (nmeaspec.ubx_config_keys), loaded on first use."""
    if not _DATABASE:
        from .ubx_config_keys import DATABASE

        _DATABASE.append(DATABASE)
    return _DATABASE[0]


def key(name: str | int) -> Key:
    """database().key(name): the key of a name or id."""
    return database().key(name)


def valset(pairs: Mapping[str | int, Any], layers: Iterable[str] = ("ram",), transaction: int | None = None) -> Any:
    """database().valset(...): CFG-VALSET writing typed values by key name."""
    return database().valset(pairs, layers, transaction)


def valget(names: Iterable[str | int], layer: str = "ram", position: int = 0) -> Any:
    """database().valget(...): CFG-VALGET's poll of keys by name, id or wildcard."""
    return database().valget(names, layer, position)


def valdel(names: Iterable[str | int], layers: Iterable[str] = ("bbr", "flash")) -> Any:
    """database().valdel(...): CFG-VALDEL of keys by name, id or wildcard."""
    return database().valdel(names, layers)


def values(message: Any, raw: bool = False) -> dict[str, Any]:
    """database().values(message): the typed values of a CFG-VALGET answer or CFG-VALSET."""
    return database().values(message, raw)
