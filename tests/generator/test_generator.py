"""Tests of the generator: the real spec validates, bad specs are rejected with the rule, file,
line and YAML path at fault, generation is deterministic and every output carries its header."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from generator.build import load_spec
from generator.render import render_all
from generator.errors import SpecErrors
from generator import emit_c, emit_docs, reference
from generator.field_types import TYPES

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "spec"
BAD = Path(__file__).with_name("bad_specs")


@pytest.fixture(scope="module")
def spec():
    return load_spec(SPEC)


def test_spec_is_valid(spec) -> None:
    assert len(spec.sentences) >= 12
    assert {s.id for s in spec.sentences} >= {"GGA", "GLL", "GNS", "GSA", "GSV", "RMC", "VTG", "ZDA", "DTM",
                                               "GST", "HDT", "RLM"}


def _fixture_header(path: Path) -> tuple[str, str]:
    lines = path.read_text().splitlines()
    return lines[0].split(":", 1)[1].strip(), lines[1].split(":", 1)[1].strip()


def test_the_registry_knows_every_field_type_of_the_schema() -> None:
    schema = json.loads((SPEC / "schema" / "sentence.schema.json").read_text(encoding="utf-8"))
    named: set[str] = set()

    def walk(node: object) -> None:  # every "type": {"enum": [...]} of the field definitions
        if isinstance(node, dict):
            if isinstance(node.get("type"), dict) and "enum" in node["type"] and "keyword" in node["type"]["enum"]:
                named.update(node["type"]["enum"])
            for value in node.values():
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)

    walk(schema)
    assert named == set(TYPES)
    # and every runtime has the pieces the registry names
    python = (ROOT / "runtime" / "python" / "runtime.py").read_text(encoding="utf-8")
    c = emit_c.runtime_source("runtime.c")
    for t in TYPES.values():
        assert f"class {t.python_spec}(" in python, t.name
        assert f"FIELD_{t.name.upper()}," in c or f"FIELD_{t.name.upper()}\n" in c, t.name
        assert f" fast_{t.c_fast}(" in c and f" fast_put_{t.c_put}(" in c, t.name


@pytest.fixture(scope="module")
def spec_copy(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A copy of the spec that each bad fixture joins for its test alone (one copy, not one a test)."""
    copy = tmp_path_factory.mktemp("bad") / "spec"
    shutil.copytree(SPEC, copy)
    return copy


@pytest.mark.parametrize("fixture", sorted(BAD.glob("*.yaml")), ids=lambda p: p.stem)
def test_bad_spec_is_rejected(fixture: Path, spec_copy: Path) -> None:
    rule, message = _fixture_header(fixture)
    text = fixture.read_text(encoding="utf-8")
    binary = "\nlayouts:" in text
    name = fixture.name if fixture.stem == "wrong_file_name" else "nav_xyz.yaml" if binary else "xyz.yaml"
    protocol = next((line.split(":", 1)[1].strip() for line in text.splitlines()[:3] if line.startswith("# protocol:")),
                    "ubx")
    folder = f"binary/{protocol}/messages" if binary else "binary/rtcm3/messages" if "\nnumbers: " in text else \
        "standard" if "\nmessage: " not in text else \
        "ais/applications" if "\napplication: " in text else "ais/messages"
    if "\nconfig_keys: " in text:   # a configuration database takes the place of the protocol's
        name = "config_keys.yaml"
        folder = "binary/ubx"
    added = spec_copy / folder / name
    kept = added.read_bytes() if added.exists() else None
    shutil.copy(fixture, added)
    try:
        with pytest.raises(SpecErrors) as caught:
            load_spec(spec_copy)
    finally:
        added.unlink()
        if kept is not None:
            added.write_bytes(kept)
    errors = caught.value.errors
    ours = [e for e in errors if e.file.endswith(name)]
    assert ours, f"no error in the fixture; got {[str(e) for e in errors]}"
    assert len(ours) == len(errors), f"errors outside the fixture: {[str(e) for e in errors]}"
    assert any(e.rule == rule and message in e.message for e in ours), [str(e) for e in ours]
    for e in ours:
        assert e.line > 1 and e.path, str(e)


def test_every_error_is_reported_at_once(tmp_path: Path) -> None:
    shutil.copytree(SPEC, tmp_path / "spec")
    for fixture in ("unknown_enum", "unknown_manual"):
        text = (BAD / f"{fixture}.yaml").read_text().replace("sentence: XYZ", f"sentence: X{fixture[8:10].upper()}")
        stem = f"x{fixture[8:10]}"
        (tmp_path / "spec" / "standard" / f"{stem}.yaml").write_text(text)
    with pytest.raises(SpecErrors) as caught:
        load_spec(tmp_path / "spec")
    assert {e.rule for e in caught.value.errors} == {"S002", "S003"}


@pytest.fixture(scope="module")
def files(spec) -> dict[str, str]:
    """The generated files of the real spec, rendered once for the tests that read them."""
    return render_all(spec)


@pytest.mark.slow  # a second rendering of the whole spec
def test_generation_is_deterministic(files) -> None:
    assert render_all(load_spec(SPEC)) == files


def test_every_generated_file_has_a_header(files) -> None:
    """The banner and the license of every generated file but the ones whose format has no comments
    and the license texts themselves (verbatim, in each package folder)."""
    for path, content in files.items():
        if path.endswith((".jsonl", "py.typed")) or "/LICENSE-" in path:
            continue
        assert "DO NOT EDIT" in content[:400], path
        assert "SPDX-License-Identifier: MIT OR Apache-2.0" in content[:400], path
    for package in ("c", "python", "rust"):
        for name in ("LICENSE-MIT", "LICENSE-APACHE"):
            assert files[f"{package}/{name}"] == (ROOT / name).read_text(encoding="utf-8")


def test_generated_python_modules_keep_to_100_columns(files) -> None:
    """The modules made from the spec read like hand-written code: no line over 100 characters
    but a manual's example sentence quoted whole in a docstring."""
    for path, content in files.items():
        if not path.startswith("python/nmeaspec/") or not path.endswith(".py") \
                or "Source: runtime/python/" in content[:400]:   # hand-written, copied as it is
            continue
        for number, line in enumerate(content.splitlines(), 1):
            assert len(line) <= 100 or line.lstrip().startswith(("$", "!")), f"{path}:{number}: {line}"


def test_vectors_cover_every_example(spec, files) -> None:
    vectors = [json.loads(line) for line in files["vectors/examples.jsonl"].splitlines()]
    assert len(vectors) == sum(len(s.examples) for s in spec.sentences)
    for v in vectors:
        assert {"manual", "raw", "checksum_ok", "line", "expect"} <= set(v) or v.get("unrecoverable")
        assert v["manual"].endswith(".txt") or spec.manual(v["manual"]) is not None
        if not v["checksum_ok"]:
            kind = json.loads(v["raw_decode"])["error"]["kind"]
            if not v["raw"].isascii():  # a manual's typography (a Unicode minus) damaged it
                assert kind == "not_a_sentence", v["raw"]
            elif v["raw"].startswith(("$", "!")):
                assert kind in ("checksum_mismatch", "bad_checksum"), v["raw"]
            else:
                assert kind == "not_a_sentence", v["raw"]


@pytest.mark.parametrize("line,kind,field", [
    ("$GPGGA,075241.00,5550.613576,N,03732.251532,E,1,22,0.5,00188.976,M,0014.4,M,,*68", "checksum_mismatch", None),
    ("$GPGGA,075241.00,5550.613576,N,03732.251532,E,1,22,0.5,00188.976,M,0014.4,M,,*6", "bad_checksum", None),
    ("GPGGA,1", "not_a_sentence", None),
    ("$GPGGA,075241.00", "too_few_fields", None),
    ("$GPGGA,075241.00,5550.613576,N,03732.251532,E,1,22,0.5,00188.976,M,0014.4,M,,,,", "too_many_fields", None),
    ("$GPGGA,075241.00,5550.613576,X,03732.251532,E,1,22,0.5,00188.976,M,0014.4,M,,", "bad_field", 3),
    ("$GPGGA,995241.00,5550.613576,N,03732.251532,E,1,22,0.5,00188.976,M,0014.4,M,,", "bad_field", 1),
    ("$GPTXT," + "A" * 1100, "too_long", None),
])
def test_reference_errors(spec, line: str, kind: str, field: int | None) -> None:
    with pytest.raises(reference.rt.NmeaError) as caught:
        reference.decode(spec, line)
    assert caught.value.kind == kind
    assert caught.value.field == field


def test_reference_round_trips_the_examples(spec) -> None:
    for sentence in spec.sentences:
        for example in sentence.examples:
            if example.line:
                decoded = reference.decode(spec, example.line)
                assert decoded.sentence is sentence


def test_every_domain_has_a_docs_heading() -> None:
    schema = json.loads((ROOT / "spec" / "schema" / "sentence.schema.json").read_text())
    assert list(emit_docs.DOMAINS) == schema["properties"]["domain"]["enum"]


@pytest.mark.parametrize("message, example, rule, error", [
    ("$PSTMCPU", "$PSTMCPU,56.23,-1,98*41", "S045", "$PSTMCPU is no longer generic (PSTMCPU reads it)"),
    ("$PORZD", "$PORZD,A,024.2*39", "S017", "checksum is 39, computed 38"),
    ("$PORZD", "$PERC,GPppr,423451,02405,00050,12,0,0*4D", "S017", "does not start with $PORZD"),
])
def test_what_stays_generic_must(message: str, example: str, rule: str, error: str, tmp_path: Path) -> None:
    """manuals.yaml's `generic` list stays true: a real line (checksum right) of the message it
    names, which no layout reads."""
    shutil.copytree(SPEC, tmp_path / "spec")
    manuals = tmp_path / "spec" / "manuals.yaml"
    manuals.write_text(manuals.read_text() + f'''  - message: "{message}"
    maker: test
    example: "{example}"
    where: a test
    why: a test
''')
    with pytest.raises(SpecErrors) as caught:
        load_spec(tmp_path / "spec")
    assert [(e.rule, error in e.message) for e in caught.value.errors] == [(rule, True)], \
        [str(e) for e in caught.value.errors]


@pytest.mark.parametrize("address, shadows", [("XXFIX", True), ("GPXYZ", False)])
def test_a_proprietary_look_alike_of_a_standard_sentence(address: str, shadows: bool, tmp_path: Path) -> None:
    """A proprietary address of five letters reads like a talker and a sentence id. The C fast
    path looks such addresses up only when one names a standard sentence ($XXFIX beside FIX);
    either way the look-alike reads with its own layout (even a line FIX's layout would read too)
    and the standard sentence with its own, on the fast path and the general one."""
    golden = Path(__file__).with_name("golden") / "spec"
    shutil.copytree(golden, tmp_path / "spec")
    body = f"{address},123519.50,4807.038,N"  # as FIX's second example
    look_alike = f"${body}*{reference.rt.checksum(body):02X}"
    (tmp_path / "spec" / "proprietary" / f"{address.lower()}.yaml").write_text(f"""sentence: {address}
address: {address}
framing: sentence
kind: output
vendor: acme
name: A look-alike
doc: A proprietary sentence whose address reads like a talker and a standard sentence id.
manuals: [acme]
fields:
  - {{id: first, name: First, type: text, doc: A word.}}
  - {{id: second, name: Second, type: text, doc: A word.}}
  - {{id: third, name: Third, type: text, doc: A word.}}
examples:
  - manual: acme
    where: a test
    raw: "{look_alike}"
    expect: {{first: "123519.50", second: "4807.038", third: N}}
""")
    files = render_all(load_spec(tmp_path / "spec"))
    # the definition, after its declaration
    fast_parse = files["c/nmea.c"].rsplit("bool fast_parse(", 1)[1].split("\n}\n", 1)[0]
    assert ("find_layouts(TALKER_LIKE" in fast_parse) == shadows
    for name in ("nmea.h", "nmea.c"):
        (tmp_path / name).write_text(files[f"c/{name}"])
    standard = "$GPFIX,123519.50,4807.038,N,01131.000,E,230394,1,08,-12.5,1F,Q,M,AD,HELLO,5*69"  # fix.yaml
    (tmp_path / "main.c").write_text(f"""#include <stdio.h>
#include <string.h>
#include "nmea.h"
static int check(const char *line, nmea_sentence_id want)
{{
    nmea_sentence s;
    nmea_error err;
    int failed = 0;
    if (!nmea_parse(&s, line, strlen(line), &err) || s.id != want)
        failed |= 1;
    if (!nmea_parse_general(&s, line, strlen(line), NULL, &err) || s.id != want)
        failed |= 2;
    return failed;
}}
int main(void)
{{
    return check("{look_alike}", NMEA_SENTENCE_{address}) | check("{standard}", NMEA_SENTENCE_FIX) << 2;
}}
""")
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Werror", "-DNMEA_TEST_HOOKS", "-o", str(tmp_path / "main"),
                    str(tmp_path / "main.c"), str(tmp_path / "nmea.c")], check=True)
    assert subprocess.run([str(tmp_path / "main")]).returncode == 0


@pytest.mark.slow
@pytest.mark.parametrize("only", ["GGA,RMC", "GSV", "PSRF100"])
def test_a_subset_compiles_without_a_warning(only: str, tmp_path: Path) -> None:
    """A subset leaves runtime pieces unused (no group: nothing reads an entry; a text command
    only: no fast reader or writer); its C pair still
    compiles under -Wall -Wextra -Werror with each build option. The unused-code warnings come from
    any level; -O2 and -Os (whose code differs) add the optimizer's own, so the options alone are
    compiled at -O0 (a fifth of -O2's time)."""
    out = tmp_path / "out"
    subprocess.run([sys.executable, "-m", "generator", "generate", "--only", only, "--out", str(out), "-q"],
                   cwd=ROOT, check=True, capture_output=True)
    for flags in (["-O2"], ["-Os"], ["-O0", "-DNMEA_NO_JSON"], ["-O0", "-DNMEA_NO_FAST_PATH"],
                  ["-O0", "-DNMEA_NO_JSON", "-DNMEA_NO_FAST_PATH"]):
        done = subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", *flags,
                               "-c", "-o", os.devnull, str(out / "c" / "nmea.c")], capture_output=True, text=True)
        assert done.returncode == 0, (flags, done.stderr[-2000:])
    # clang also warns of an unused static inline function, in its front end (make test installs
    # clang: tools/system_deps.sh); the small profile's build too.
    for flags in ([], ["-Os", "-DNMEA_SMALL"], ["-DNMEA_NO_JSON", "-DNMEA_NO_FAST_PATH"]):
        done = subprocess.run(["clang", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-fsyntax-only", *flags,
                               str(out / "c" / "nmea.c")], capture_output=True, text=True)
        assert done.returncode == 0, (flags, done.stderr[-2000:])


def test_a_c_name_an_enum_and_an_ais_record_would_share_is_a_clash(spec) -> None:
    """An enum `ais_<message>` would be typedef'd nmea_ais_<message>, the AIS message's struct
    (nmea.h and nmea_ais.h meet in one build): the spec's checks say so, not the C compiler."""
    from dataclasses import replace
    from generator import names_c
    assert names_c.clashes(spec) == []
    record = next(p for p in spec.applications if any(hasattr(i, "max") for i in p.items))
    entry = names_c.ais_records(record.id, record.items, record.origin)[1][0]   # a group entry's record
    for clashing in (f"ais_{record.id}", f"ais_{entry}"):
        enum = replace(spec.enums[0], id=clashing)
        found = names_c.clashes(replace(spec, enums=[*spec.enums, enum]))
        assert [message for _, message in found] == \
            [f"the C name nmea_{clashing} of AIS record {clashing[4:]} is also the name of enum {clashing}"]
