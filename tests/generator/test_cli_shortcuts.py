"""The `cli` shortcuts of enum values (`set-baud 115200` of `nmea command`): checked like
the rest of the spec, with the file, line and YAML path of the value at fault."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from generator.build import load_spec
from generator.emit_python_apps import command_views
from generator.errors import SpecErrors

ROOT = Path(__file__).resolve().parents[2]
WORDS = Path("enums") / "geos5_command_word.yaml"


def _spec_with(tmp_path: Path, old: str, new: str) -> Path:
    shutil.copytree(ROOT / "spec", tmp_path / "spec")
    path = tmp_path / "spec" / WORDS
    text = path.read_text(encoding="utf-8")
    assert old in text
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return tmp_path / "spec"


def test_shortcuts_reach_the_command_table() -> None:
    commands, shortcuts = command_views(load_spec(ROOT / "spec"))
    baud = next(s for s in shortcuts if s["words"] == ("set-baud", "115200"))
    assert baud["vendor"] == "geos5" and baud["command"] == "command" and baud["settings"] == (("command", "BDR115"),)
    names = {(c["vendor"], c["name"]) for c in commands}
    assert {("geos5", "nquery-request"), ("teseo", "pstmsetpar-dop"), ("comnav", "nmeatalker-list")} <= names


@pytest.mark.parametrize(("old", "new", "rule", "message"), [
    ("cli: set-baud 9600", "cli: set-baud 4800", "S026", "appears twice in enum geos5_command_word"),
    ("cli: cold-start", "cli: nquery-request", "S027", "is named like a command"),
])
def test_bad_shortcut_is_rejected(tmp_path: Path, old: str, new: str, rule: str, message: str) -> None:
    with pytest.raises(SpecErrors) as caught:
        load_spec(_spec_with(tmp_path, old, new))
    errors = caught.value.errors
    assert len(errors) == 1 and errors[0].rule == rule and message in errors[0].message, [str(e) for e in errors]
    assert errors[0].file.endswith(str(WORDS)) and errors[0].path.endswith("cli") and errors[0].line > 1


def test_shortcut_format_is_in_the_schema(tmp_path: Path) -> None:
    with pytest.raises(SpecErrors) as caught:
        load_spec(_spec_with(tmp_path, "cli: set-baud 9600", "cli: Set_Baud 9600"))
    assert any("cli" in str(e) for e in caught.value.errors), [str(e) for e in caught.value.errors]
