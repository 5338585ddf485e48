"""The configuration database (spec/binary/<protocol>/config_keys.yaml) as the Python package's
key table (nmeaspec.ubx_config_keys, read by the runtime's ubx_config: keys by name and id for
CFG-VALSET, -VALGET and -VALDEL), as static data of the C pair (nmea_ubx_config.h/.c: a macro
per key id, a table sorted by id) and of the Rust crate (ubx_config_keys.rs: a constant per key,
KEYS), and as a docs page with every key (docs/ubx/config_keys.md). Called by emit_python_ubx."""

from __future__ import annotations

import json
import textwrap

import jinja2

from .emit import header, markdown_banner
from .emit_python import WIDTH
from .emit_rust import rustfmt
from .model import ConfigDatabase, ConfigKey, Spec

PACKAGE = "nmeaspec"


def _key_lines(key: ConfigKey) -> list[str]:
    """The Key(...) of a key as lines of at most WIDTH characters at an indent of 4."""
    args = [json.dumps(key.name), f"0x{key.id:08X}", json.dumps(key.type)]
    rest = [str(key.divisor), json.dumps(key.unit) if key.unit else "None",
            key.enum.id.upper() if key.enum else "None"]
    while rest and rest[-1] in ("None", "1") and not key.doc:
        rest.pop()
    args += rest
    first = f"    Key({', '.join(args)}"
    if not key.doc:
        return [first + "),"]
    doc = json.dumps(key.doc)
    if len(first) + len(doc) + 4 <= WIDTH:
        return [f"{first}, {doc}),"]
    words = textwrap.wrap(key.doc, WIDTH - 12, drop_whitespace=False, break_long_words=False)
    return [first + ",", *(f"        {json.dumps(w)}" for w in words[:-1]), f"        {json.dumps(words[-1])}),"]


def _python(spec: Spec, env: jinja2.Environment, db: ConfigDatabase) -> str:
    groups: dict[str, list[int]] = {}
    for g in db.groups:
        groups.setdefault(f"CFG-{g.name}", []).append(g.id)
    return env.get_template("python/ubx_config_keys.py.j2").render(
        header=header(spec, "#", [db.origin.file, "templates/python/ubx_config_keys.py.j2"]), db=db,
        enums=[(e.id.upper(), e) for e in db.enums.values()],
        keys=[line for k in db.keys for line in _key_lines(k)],
        groups=[(name, ", ".join(f"0x{i:02X}" for i in ids) + ("," if len(ids) == 1 else ""))
                for name, ids in groups.items()],
        aliases=[(f"CFG-{k.group}-{a}", k.name) for k in db.keys for a in k.aliases])


def _cell(text: str) -> str:
    return " ".join(text.split()).replace("|", "\\|")


def _scale(key: ConfigKey) -> str:
    if key.scale is None:
        return ""
    return f"1e-{len(str(key.divisor)) - 1}" if key.divisor >= 10_000 else f"{key.scale:g}"


def _docs(spec: Spec, env: jinja2.Environment, db: ConfigDatabase) -> str:
    documents = {d: title for p in spec.protocols for d, title in p.documents.items()}
    groups = [{"group": g, "wildcard": f"0x{g.id << 16 | 0xFFFF:08X}",
               "rows": [{"key": k, "id": f"0x{k.id:08X}", "scale": _scale(k), "unit": k.unit or "",
                         "doc": _cell(k.doc + (f" Values: {', '.join(f'{n} {v}' for n, v in k.enum.values.items())}."
                                               if k.enum else "")),
                         "aliases": ", ".join(f"CFG-{k.group}-{a}" for a in k.aliases)} for k in g.keys]}
              for g in db.groups]
    return env.get_template("docs/config_keys.md.j2").render(
        banner=markdown_banner(spec, [db.origin.file, "templates/docs/config_keys.md.j2"]), db=db, groups=groups,
        documents=documents, count=len(db.keys), not_found=" ".join(db.not_found.split()))


TYPES = {"L": "One bit (in a byte): false or true.", "U1": "Unsigned, one byte.", "U2": "Unsigned, two bytes.",
         "U4": "Unsigned, four bytes.", "U8": "Unsigned, eight bytes.", "I1": "Signed, one byte.",
         "I2": "Signed, two bytes.", "I4": "Signed, four bytes.", "I8": "Signed, eight bytes.",
         "X1": "Bits, one byte.", "X2": "Bits, two bytes.", "X4": "Bits, four bytes.", "X8": "Bits, eight bytes.",
         "E1": "An enumeration, one byte.", "E2": "An enumeration, two bytes.", "E4": "An enumeration, four bytes.",
         "R4": "An IEEE 754 single.", "R8": "An IEEE 754 double."}


def _static_keys(db: ConfigDatabase) -> list[dict]:
    """Each key's name, id, type, divisor, unit and description, and its name as a C macro and a
    Rust constant (CFG_RATE_MEAS; no two alike)."""
    keys = [{"name": k.name, "id": k.id, "type": k.type, "divisor": k.divisor, "unit": k.unit, "doc": k.doc,
             "const": k.name.replace("-", "_").upper(), "macro": "NMEA_UBX_" + k.name.replace("-", "_").upper()}
            for k in db.keys]
    assert len({k["const"] for k in keys}) == len(keys)
    return keys


def _c(spec: Spec, env: jinja2.Environment, db: ConfigDatabase) -> dict[str, str]:
    keys = _static_keys(db)
    context = {"keys": keys, "keys_by_id": sorted(keys, key=lambda k: k["id"]), "types": list(TYPES)}
    return {f"c/nmea_ubx_config.{ext}": env.get_template(f"c/nmea_ubx_config.{ext}.j2").render(
        header=header(spec, "//", [db.origin.file, f"templates/c/nmea_ubx_config.{ext}.j2"]), **context)
        for ext in ("h", "c")}


def _rust(spec: Spec, env: jinja2.Environment, db: ConfigDatabase) -> dict[str, str]:
    keys = _static_keys(db)
    sizes: dict[int, list[str]] = {}
    for t in TYPES:
        sizes.setdefault(1 if t == "L" else int(t[1:]), []).append(f"Self::{t}")
    test = "templates/rust/ubx_config_keys_test.rs.j2"
    return rustfmt({
        "rust/src/ubx_config_keys.rs": env.get_template("rust/ubx_config_keys.rs.j2").render(
            header=header(spec, "//", [db.origin.file, "templates/rust/ubx_config_keys.rs.j2"]), keys=keys,
            keys_by_id=sorted(keys, key=lambda k: k["id"]), types=list(TYPES.items()), sizes=sorted(sizes.items())),
        "rust/tests/ubx_config_keys.rs": env.get_template(test.removeprefix("templates/")).render(
            header=header(spec, "//", [db.origin.file, test]), count=len(keys))})


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    files: dict[str, str] = {}
    for db in spec.config_keys:
        if db.protocol != "ubx":
            continue
        files[f"python/{PACKAGE}/ubx_config_keys.py"] = _python(spec, env, db)
        files["docs/ubx/config_keys.md"] = _docs(spec, env, db)
        files.update(_c(spec, env, db))
        files.update(_rust(spec, env, db))
    return files
