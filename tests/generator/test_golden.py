"""Golden outputs of the emitters on a small fixture spec (golden/spec: every field type, a group,
a variant, a `!` sentence, a command with its reply, a text command). The files it generates are
committed under golden/expected, so that a change to an emitter shows as a small diff there. The
runtimes and tools, copied from runtime/ as they are, and the license texts are left out (their
own tests cover them).

After checking that the difference is the one you meant, accept it with
`UPDATE_GOLDEN=1 .venv/bin/python -m pytest tests/generator/test_golden.py`."""

from __future__ import annotations

import difflib
import os
import shutil
from pathlib import Path

from generator.build import load_spec
from generator.emit_c import RUNTIME_C, runtime_header, runtime_source
from generator.render import render_all

GOLDEN = Path(__file__).with_name("golden")
EXPECTED = GOLDEN / "expected"

# The C runtime is pasted into nmea.h / nmea.c: it is replaced by a line that names it.
EMBEDDED = {"c/nmea.h": ["runtime.h", "api.h"], "c/nmea.c": ["runtime.c"]}
RUNTIME_TEXTS = {"runtime.h": runtime_header("runtime.h"),
                 "api.h": (RUNTIME_C / "api.h").read_text(encoding="utf-8"),
                 "runtime.c": runtime_source("runtime.c")}


def rendered() -> dict[str, str]:
    files = render_all(load_spec(GOLDEN / "spec"))
    out = {}
    for path, text in files.items():
        if "Source: runtime/" in text[:400] or "/LICENSE-" in path:  # a runtime/ file as it is
            continue
        for name in EMBEDDED.get(path, []):
            runtime = RUNTIME_TEXTS[name]
            assert runtime in text, f"{path} no longer holds runtime/c/{name} as it is"
            text = text.replace(runtime, f"/* runtime/c/{name} */\n")
        out[path] = text
    return out


def test_emitters_write_the_golden_files() -> None:
    files = rendered()
    if os.environ.get("UPDATE_GOLDEN"):
        shutil.rmtree(EXPECTED, ignore_errors=True)
        for path, text in files.items():
            (EXPECTED / path).parent.mkdir(parents=True, exist_ok=True)
            (EXPECTED / path).write_text(text, encoding="utf-8")
    found = {p.relative_to(EXPECTED).as_posix(): p.read_text(encoding="utf-8")
             for p in sorted(EXPECTED.rglob("*")) if p.is_file()}
    assert sorted(found) == sorted(files), (
        f"files added: {sorted(set(files) - set(found))}, removed: {sorted(set(found) - set(files))}")
    diffs = []
    for path in sorted(files):
        if files[path] != found[path]:
            diffs += difflib.unified_diff(found[path].splitlines(), files[path].splitlines(),
                                          f"golden/expected/{path}", f"generated {path}", lineterm="")
    assert not diffs, "\n".join(diffs[:400]) + "\n(after checking it: UPDATE_GOLDEN=1 to accept)"
