"""The applications of the Python package, in its subpackage `apps/` (runtime/python/apps/, copied
as they are): the `nmea-py` tool and `python -m nmeaspec`, the user's `nmea` CLI with its
`report` verb, and the table of vendor commands `nmea command` builds (generated from the command
sentences and the `cli` shortcuts of their enums)."""

from __future__ import annotations

import re

import jinja2

from .emit import header, runtime_file
from .emit_python import PACKAGE, py_call, py_literal, py_str
from .model import Spec


def _one_line(text: str) -> str:
    return " ".join(text.split())


def _first_sentence(text: str) -> str:
    text = _one_line(text)
    end = re.search(r"(?<!e\.g)(?<!i\.e)\.\s+(?=[A-Z(])", text)
    return text if end is None else text[:end.start() + 1]


def command_views(spec: Spec) -> tuple[list[dict], list[dict]]:
    commands, shortcuts = [], []
    for s in spec.sentences:
        if s.kind != "command" or s.vendor is None:
            continue
        for layout in s.layouts:
            name = s.command_name(layout)
            arguments = [{"id": f.id, "type": f.type, "doc": _first_sentence(f.doc),
                          "enum": f.enum.camel if f.enum else None, "value": f.value, "optional": f.is_optional,
                          "keyword": f.field_type.keyword}
                         for f in layout.fields]
            commands.append({"sentence": s, "layout_id": layout.id, "vendor": s.vendor, "name": name, "layout": s.layout_camel(layout),
                             "doc": _one_line(layout.name if layout.id else s.name), "arguments": arguments,
                             "text": s.framing == "text"})
            for f in layout.fields:
                for v in (f.enum.values if f.enum else []):
                    if v.cli:
                        shortcuts.append({"vendor": s.vendor, "words": tuple(v.cli.split()), "command": name,
                                          "settings": ((f.id, v.code),), "doc": _first_sentence(v.doc)})
    return commands, shortcuts


def usage(command: dict) -> str:
    """How `nmea command --list` writes a command: its name, then its arguments (optional ones and
    keywords, which may be left out, in brackets)."""
    words = [command["name"]]
    for a in command["arguments"]:
        word = (a["value"] or "").lower() if a["keyword"] else a["id"].upper()
        words.append(f"[{word}]" if a["optional"] or a["keyword"] else word)
    return " ".join(words)


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    base = f"python/{PACKAGE}"
    commands, shortcuts = command_views(spec)
    vendors = [m for m in spec.manuals if any(c["vendor"] == m.id for c in commands)]
    files = {f"{base}/apps/{module}.py": runtime_file(spec, "#", f"python/apps/{module}.py")
             for module in ("__init__", "contract_tool", "nmea_cli", "report", "export")}
    files[f"{base}/apps/commands.py"] = env.get_template("python/apps/commands.py.j2").render(
        header=header(spec, "#"), commands=commands, shortcuts=shortcuts, vendors=vendors, py=py_literal,
        py_call=py_call, py_str=py_str)
    files[f"{base}/__main__.py"] = header(spec, "#", ["runtime/python/apps/contract_tool.py"]) + \
        "from .apps.contract_tool import main\n\nraise SystemExit(main())\n"
    return files
