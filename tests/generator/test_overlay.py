"""Overlays (--spec-extra): a receiver's own manuals, sentences and additions to built-in
sentences, laid over the spec, under the same schema and rules; `new` starts their files."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import jinja2
import pytest

from generator import cache
from generator.build import load_spec
from generator.cli import main
from generator.emit import environment
from generator.errors import SpecErrors
from generator.selection import parse_selector, subset

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "spec"


@pytest.fixture
def overlay(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """An overlay started by `new`: a manual, a sentence and a command, as written."""
    monkeypatch.chdir(tmp_path)
    for argv in (["new", "manual", "acme", "--maker", "acme", "--title", "ACME X1, NMEA reference"],
                 ["new", "sentence", "PACMEPOS", "--manual", "acme"],
                 ["new", "command", "PACMESET", "--manual", "acme"]):
        assert main([*argv, "--spec-extra", "my-nmea"]) == 0
    return Path("my-nmea")


def test_what_new_writes_validates_and_only_selects_it(overlay: Path) -> None:
    spec = load_spec(SPEC, [overlay])
    pos = spec.sentence("PACMEPOS")
    assert pos is not None and pos.source == "my-nmea/proprietary/pacmepos.yaml" and pos.kind == "output"
    assert spec.sentence("PACMESET").kind == "command"
    chosen = subset(spec, parse_selector("acme"))
    assert [s.id for s in chosen.sentences] == ["PACMEPOS", "PACMESET"]
    assert [m.id for m in chosen.manuals if m.maker != "standard"] == ["acme"]


def test_errors_name_the_overlay_file_and_line(overlay: Path) -> None:
    path = overlay / "proprietary" / "pacmepos.yaml"
    path.write_text(path.read_text().replace("type: integer", "type: enum\n  enum: no_such_enum"))
    line = path.read_text().splitlines().index("  enum: no_such_enum") + 1
    with pytest.raises(SpecErrors) as caught:
        load_spec(SPEC, [overlay])
    [error] = caught.value.errors
    assert (error.file, error.line, error.rule) == (str(path), line, "S002"), str(error)


def test_a_clash_names_both_files(overlay: Path) -> None:
    for folder, name in (("standard", "gga.yaml"), ("bitfields", "geos5_status_word.yaml")):
        (overlay / folder).mkdir()
        shutil.copy(SPEC / folder / name, overlay / folder)
    manuals = overlay / "manuals.yaml"
    manuals.write_text(manuals.read_text() + "  - id: geos5\n    title: a second GeoS-5\n    maker: geostar\n")
    with pytest.raises(SpecErrors) as caught:
        load_spec(SPEC, [overlay])
    found = {(e.file, e.rule, e.message) for e in caught.value.errors}
    assert found == {
        ("my-nmea/manuals.yaml", "S001", "manual geos5 is also defined in spec/manuals.yaml"),
        ("my-nmea/bitfields/geos5_status_word.yaml", "S001",
         "bitfield geos5_status_word is also defined in spec/bitfields/geos5_status_word.yaml"),
    }, found
    manuals.write_text(manuals.read_text().rsplit("  - id: geos5", 1)[0])
    for path in (overlay / "bitfields").iterdir():
        path.unlink()
    with pytest.raises(SpecErrors) as caught:
        load_spec(SPEC, [overlay])
    assert [str(e) for e in caught.value.errors] == [
        "my-nmea/standard/gga.yaml:1: sentence: sentence GGA is also defined in spec/standard/gga.yaml [S001]"]


def test_an_extension_adds_examples_to_a_built_in_sentence(overlay: Path) -> None:
    (overlay / "extensions").mkdir()
    extension = overlay / "extensions" / "zda.yaml"
    extension.write_text("""\
extends: ZDA
manuals: [acme]
examples:
- manual: acme
  where: ACME X1 reference, ZDA
  raw: $GPZDA,201530.00,04,07,2002,00,00*60
  expect: {time: '20:15:30.00', day: 4, month: 7, year: 2002, local_zone_hours: 0, local_zone_minutes: 0}
""")
    spec = load_spec(SPEC, [overlay])
    zda = spec.sentence("ZDA")
    assert "acme" in zda.manuals and zda.examples[-1].origin.file == str(extension)
    # the files of the sentence, and so the digest in its generated files' headers, take the extension in
    assert zda.files == [zda.source, str(extension)]
    before = spec.digest_of(zda.files)
    extension.write_text(extension.read_text().replace("ACME X1 reference, ZDA", "ACME X1 reference rev. B, ZDA"))
    spec = load_spec(SPEC, [overlay])
    assert spec.digest_of(spec.sentence("ZDA").files) != before
    extension.write_text(extension.read_text().replace("local_zone_minutes: 0", "local_zone_minutes: 5"))
    with pytest.raises(SpecErrors) as caught:
        load_spec(SPEC, [overlay])
    assert [(e.file, e.rule) for e in caught.value.errors] == [(str(extension), "S008")]
    extension.write_text(extension.read_text().replace("extends: ZDA", "extends: XYZ"))
    with pytest.raises(SpecErrors) as caught:
        load_spec(SPEC, [overlay])
    assert [(e.file, e.line, e.rule) for e in caught.value.errors] == [(str(extension), 1, "S046")]


def test_a_template_changed_after_a_run_is_compiled_again(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The templates a run compiled are kept for the next (generator/emit.py), found by name and
    used only while their source is the same."""
    monkeypatch.setattr(cache, "CACHE", tmp_path / "cache")
    templates = tmp_path / "templates"
    templates.mkdir()
    (templates / "t.j2").write_text("{{ x }} one")

    def render() -> str:
        env = environment()
        env.loader = jinja2.FileSystemLoader(str(templates))
        return env.get_template("t.j2").render(x=1)

    assert render() == "1 one"
    assert len(list((tmp_path / "cache" / "templates").iterdir())) == 1
    assert render() == "1 one"
    (templates / "t.j2").write_text("{{ x }} two")
    assert render() == "1 two"


def test_the_cache_between_runs_never_hides_a_change(overlay: Path, tmp_path: Path) -> None:
    """The parsed and valid documents a run keeps for the next (NMEASPEC_GEN_CACHE) are found by
    their text: a file changed after a valid run is parsed and checked again, whole."""
    env = {**os.environ, "NMEASPEC_GEN_CACHE": str(tmp_path / "cache")}

    def validate() -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, "-m", "generator", "validate", "--spec-extra", str(overlay.resolve())],
                              cwd=ROOT, env=env, capture_output=True, text=True)

    assert validate().returncode == 0
    assert any((tmp_path / "cache").glob("valid-*")) and any((tmp_path / "cache").glob("parsed-*/*"))
    sentence = overlay / "proprietary" / "pacmepos.yaml"
    text = sentence.read_text()
    sentence.write_text(text + "colour: blue\n")
    broken = validate()
    assert broken.returncode == 1 and "pacmepos.yaml" in broken.stderr and "colour" in broken.stderr, broken.stderr
    sentence.write_text(text)
    assert validate().returncode == 0
