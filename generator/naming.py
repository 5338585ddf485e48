"""`generate --prefix P --namespace N`: rename the generated code so that two copies can live in
one program.

The templates and runtimes write the default names (C `nmea_`/`NMEA_`, files nmea.c/nmea.h, the
Rust crate and the Python package `nmeaspec`). Renaming is one pass over the emitted files, token
by token, so it cannot miss a template:

C (and the C names quoted in the docs): every identifier token that starts with `nmea_` or `NMEA_`
is a file-scope name of the API (function, object, type, macro, enum constant) and becomes `p_` /
`P_`, except the spec's own ids (a field `nmea_version`, an enum value `nmea_v2`) that start the
same way: those are struct members and JSON texts. C string literals are left alone (they hold the
JSON ids), except the `#include "nmea.h"` lines. Files nmea.c, nmea.h, nmea_tool.c become p.c,
p.h, p_tool.c; in the other files of c/ (build files) the word `nmea` (a target name) becomes p too. The test compiles two renamed copies into one program and checks with `nm` that no
external symbol is left unprefixed.

Rust and Python: the token `nmeaspec` (crate name, package name, `use nmeaspec::`, doc examples)
becomes N; the Python package directory moves to N/ (its own imports are relative), and the
console scripts `nmea...` become `N...` so that two installs do not overwrite each other's.

The tools follow their copy: nmea-c becomes P-c (CMake target, usage text), nmea-py and nmea-rs
become N-py and N-rs (console script, cargo bin, usage texts), the `nmea` CLI N.
"""

from __future__ import annotations

import re

from .model import Group, Spec

DEFAULT_PREFIX = "nmea"
DEFAULT_NAMESPACE = "nmeaspec"

_C_IDENT = re.compile(r"\b(?:nmea|NMEA)_\w*")
# Comments (renamed like code: an apostrophe in one starts no character literal) and literals.
_C_COMMENTS_AND_LITERALS = re.compile(r'(/\*.*?\*/|//[^\n]*)|"(?:[^"\\\n]|\\.)*"|\'(?:[^\'\\\n]|\\.)*\'', re.S)
_INCLUDE = re.compile(r'(#include\s+")((?:\.\./)?)nmea(\.h")')
_FILE_NAMES = re.compile(r"\bnmea(?=(?:_tool)?\.[ch]\b)")


class NamingError(ValueError):
    pass


def check_names(prefix: str | None, namespace: str | None) -> None:
    if prefix is not None and not re.fullmatch(r"[a-z][a-z0-9]*", prefix):
        raise NamingError(f"--prefix {prefix!r}: lower-case letters and digits, starting with a letter")
    if namespace is not None and not re.fullmatch(r"[a-z][a-z0-9_]*", namespace):
        raise NamingError(f"--namespace {namespace!r}: a valid Rust crate and Python package name "
                          "(lower-case letters, digits, underscores, starting with a letter)")


def spec_ids(spec: Spec) -> set[str]:
    """Every id of the spec that could look like a C name: they must keep their text."""
    ids: set[str] = set()
    for s in spec.sentences:
        for layout in s.layouts:
            if layout.id:
                ids.add(layout.id)
            for item in layout.items:
                ids.add(item.id)
                if isinstance(item, Group):
                    ids.update(f.id for f in item.fields)
    for e in spec.enums:
        ids.add(e.id)
        ids.update(v.id for v in e.values)
    for b in spec.bitfields:
        ids.add(b.id)
        for bits in b.bits:
            ids.add(bits.id)
            ids.update(v.id for v in bits.values)
    for t in spec.tables:
        ids.add(t.id)
        ids.update(p.id for p in t.parameters)
    return {i for i in ids if i.lower().startswith("nmea_")}


def _c_token(prefix: str, keep: set[str]):
    def rename(match: re.Match[str]) -> str:
        token = match.group(0)
        if token in keep:
            return token
        return (prefix.upper() if token.startswith("NMEA") else prefix) + token[4:]
    return rename


def rename_c(text: str, prefix: str, keep: set[str]) -> str:
    """Rename the C API names in C source (string literals untouched but for #include lines)."""
    rename = _c_token(prefix, keep)

    def code(part: str) -> str:
        return _FILE_NAMES.sub(prefix, _C_IDENT.sub(rename, part))

    parts, at = [], 0
    for found in _C_COMMENTS_AND_LITERALS.finditer(text):
        parts += [code(text[at:found.start()]), code(found[0]) if found[1] else found[0]]
        at = found.end()
    out = "".join(parts) + code(text[at:])
    return _INCLUDE.sub(lambda m: m.group(1) + m.group(2) + prefix + m.group(3), out)


def rename_text(text: str, prefix: str, keep: set[str]) -> str:
    """Rename C API names quoted in prose (the Markdown docs): no string literals there."""
    return _FILE_NAMES.sub(prefix, _C_IDENT.sub(_c_token(prefix, keep), text))


def rename_namespace(text: str, namespace: str) -> str:
    return re.sub(r"\bnmeaspec\b", namespace, text)


def rename_tools(text: str, prefix: str | None, namespace: str | None) -> str:
    """The tools' names where the tools name themselves (usage texts, bin and script names)."""
    if prefix not in (None, DEFAULT_PREFIX):
        text = re.sub(r"\bnmea-c\b", f"{prefix}-c", text)
    if namespace not in (None, DEFAULT_NAMESPACE):
        text = re.sub(r"\bnmea-(py|rs)\b", namespace + r"-\1", text)
        text = text.replace('prog="nmea"', f'prog="{namespace}"')
    return text


def _rename_scripts(text: str, namespace: str) -> str:
    """pyproject.toml: console scripts `nmea...` -> `<namespace>...`."""
    out, in_scripts = [], False
    for line in text.splitlines(keepends=True):
        if line.startswith("["):
            in_scripts = line.strip() == "[project.scripts]"
        elif in_scripts:
            line = re.sub(r'^(\s*"?)nmea', lambda m: m.group(1) + namespace, line)
        out.append(line)
    return "".join(out)


def rename_files(files: dict[str, str], spec: Spec, prefix: str | None, namespace: str | None) -> dict[str, str]:
    """The generated files (path -> content) with their names and contents renamed."""
    if prefix in (None, DEFAULT_PREFIX) and namespace in (None, DEFAULT_NAMESPACE):
        return files
    keep = spec_ids(spec)
    out: dict[str, str] = {}
    for path, content in files.items():
        if path.endswith(".jsonl") or "/LICENSE-" in path:   # test vectors (wire texts and JSON ids only)
            out[path] = content                                  # and the license texts, verbatim
            continue
        if prefix not in (None, DEFAULT_PREFIX):
            if path.startswith("c/") and path.endswith((".c", ".h")):
                content = rename_c(content, prefix, keep)
                path = "c/" + _FILE_NAMES.sub(prefix, path[2:])
            elif path.startswith("c/"):           # build files (CMakeLists.txt): the target and tool names too
                content = re.sub(r"\bnmea\b", prefix, rename_text(content, prefix, keep))
            elif path.endswith(".md"):
                content = rename_text(content, prefix, keep)
        if namespace not in (None, DEFAULT_NAMESPACE):
            content = rename_namespace(content, namespace)
            if path.startswith("python/nmeaspec/"):
                path = f"python/{namespace}/" + path[len("python/nmeaspec/"):]
            if path == "python/pyproject.toml":
                content = _rename_scripts(content, namespace)
        content = rename_tools(content, prefix, namespace)
        if path.startswith("rust/"):
            path = rename_tools(path, None, namespace)   # src/bin/nmea-rs.rs, named in Cargo.toml
        assert path not in out, path
        out[path] = content
    return out
