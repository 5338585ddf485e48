"""The generator's commands, run the way a spec maintainer runs them, from fresh temporary
directories:

- regenerate when a manual changes: edit the YAML, `generate` (prints what changed), `diff`
  (the API changelog, BREAKING or compatible), `reconcile` a manual's text;
- vendor a renamed subset next to the default copy: one C program, one Rust project and one
  Python environment using both;
- the generator's own command line: --help on every verb (the installed generator: tests/workflows/test_own_receiver.py).
"""

from __future__ import annotations

import copy
import json
import os
import re
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

from generator import diff, reconcile
from generator.build import load_spec
from generator.model import Field
from generator.selection import SelectionError, subset

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "spec"
BAD = Path(__file__).with_name("bad_specs")
SEEDS = ROOT.parent / "shared" / "seeds"
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}


def gen(*args: str | Path, cwd: Path, check: bool = True) -> subprocess.CompletedProcess[str]:
    """`python -m generator ARGS` from `cwd`, as a user runs it."""
    result = subprocess.run([sys.executable, "-m", "generator", *map(str, args)], cwd=cwd, env=ENV,
                            capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"generator {args} failed ({result.returncode}):\n{result.stdout}\n{result.stderr}")
    return result


def run(*args: str | Path, cwd: Path, env: dict[str, str] | None = None) -> str:
    result = subprocess.run(list(map(str, args)), cwd=cwd, env=env, capture_output=True, text=True)
    assert result.returncode == 0, f"{args} failed:\n{result.stdout}\n{result.stderr}"
    return result.stdout


# --- the generator's command line -----------------------------------------------------------

@pytest.mark.parametrize("verb", ["validate", "generate", "check", "diff", "reconcile", "new", "rules"])
def test_every_verb_has_help_with_examples(verb: str, tmp_path: Path) -> None:
    out = gen(verb, "--help", cwd=tmp_path).stdout
    assert out.startswith(f"usage: nmeaspec-gen {verb}") and "examples:\n" in out and "nmeaspec-gen " + verb in out


def test_validate_reports_every_error_at_once(tmp_path: Path) -> None:
    """Schema errors in two files, each with its file, line and YAML path, in one run."""
    shutil.copytree(SPEC, tmp_path / "spec")
    for fixture in ("bad_type", "unknown_key"):
        text = (BAD / f"{fixture}.yaml").read_text().replace("sentence: XYZ", f"sentence: X{fixture[:2].upper()}")
        (tmp_path / "spec" / "standard" / f"x{fixture[:2]}.yaml").write_text(text)
    result = gen("--spec", tmp_path / "spec", "validate", cwd=tmp_path, check=False)
    assert result.returncode == 1
    errors = [line for line in result.stderr.splitlines() if re.match(r"spec/standard/x\w\w\.yaml:\d+: ", line)]
    assert {e.split(":")[0] for e in errors} == {"spec/standard/xba.yaml", "spec/standard/xun.yaml"}, result.stderr
    assert all(re.match(r"[^:]+:\d+: \S+: .+ \[\w+\]$", e) for e in errors), errors
    assert f"{len(errors)} error(s) in the spec" in result.stderr


# --- regenerate when a manual changes: the worked example of the README ----------------------

NEW_FIELD = """\
  - id: gst_rate
    name: GST output rate
    type: enum
    enum: geos5_message_rate
    format: x
    optional: true
    doc: Rate of GST, the 11th per-sentence field added by manual revision 4.1.
    manuals: [geos5]
"""
NEW_VALUE = """\
  - code: "4"
    id: rate_20hz
    doc: 20 Hz (manual revision 4.1).
    manuals: [geos5]
"""


def _checksum(body: str) -> str:
    value = 0
    for ch in body:
        value ^= ord(ch)
    return f"{value:02X}"


NEW_BODY = "GPSGG,NQUERY,1,4,2,R,0,R,1,0,0,0,1,1,0,1"


def _new_example() -> str:
    body = NEW_BODY
    return f"""\
  - manual: geos5
    where: "3.12 NQUERY example of revision 4.1: 20 Hz, GST every second"
    raw: "${body}*{_checksum(body)}"
    expect: {{keyword: NQUERY, port: 1, output_rate: rate_20hz, nmea_version: v2_x,
             gga_rate: output_rate, gll_rate: "off", gsa_rate: output_rate, gsv_rate: every_1s,
             rmc_rate: "off", vtg_rate: "off", gns_rate: "off", zda_rate: every_1s, dtm_rate: every_1s,
             rlm_rate: "off", gst_rate: every_1s}}
"""


@pytest.mark.slow
def test_worked_example_new_manual_revision(tmp_path: Path) -> None:
    """GeoS-5 manual revision 4.1 adds a per-sentence rate field to NQUERY and a 20 Hz output
    rate: edit the YAML, run `generate` and `diff`, read the changelog and the regenerated code."""
    git = ["git", "-c", "user.name=t", "-c", "user.email=t@example.com"]
    shutil.copytree(SPEC, tmp_path / "spec")
    run(*git, "init", "-q", cwd=tmp_path)
    run(*git, "add", "spec", cwd=tmp_path)
    run(*git, "commit", "-q", "-m", "spec", cwd=tmp_path)
    first = gen("--spec", "spec", "generate", "--out", "generated", "-q", cwd=tmp_path)
    assert re.search(r"generated/: \d+ created, 0 updated, 0 removed, 0 unchanged", first.stdout), first.stdout

    nquery = tmp_path / "spec" / "proprietary" / "geos5_nquery.yaml"
    text = nquery.read_text()
    nquery.write_text(text.replace("\nnotes:\n", "\n" + NEW_FIELD + "notes:\n", 1) + _new_example())
    with (tmp_path / "spec" / "enums" / "geos5_output_rate.yaml").open("a") as f:
        f.write(NEW_VALUE)

    out = gen("--spec", "spec", "generate", "--out", "generated", cwd=tmp_path).stdout
    updated = {line.split(" ", 1)[1] for line in out.splitlines() if line.startswith("updated ")}
    for path in ("c/nmea.h", "c/nmea.c", "python/nmeaspec/sentences/geos5_nquery.py",
                 "python/nmeaspec/enums/geos5_output_rate.py", "rust/src/sentences/geos5_nquery.rs", "rust/src/enums.rs", "vectors/examples.jsonl"):
        assert f"generated/{path}" in updated, out
    for path in ("python/nmeaspec/sentences/gga.py", "rust/src/sentences/gga.rs", "python/nmeaspec/runtime.py",
                 "python/nmeaspec/enums/gga_quality.py", "docs/sentences/gga.md", "docs/enums/gga_quality.md", "docs/json.md"):
        assert f"generated/{path}" not in updated
    summary = out.splitlines()[-1]
    assert re.fullmatch(rf"generated/: 0 created, {len(updated)} updated, 0 removed, \d+ unchanged", summary), summary
    code = (tmp_path / "generated/python/nmeaspec/sentences/geos5_nquery.py").read_text()
    assert "gst_rate" in code
    assert "RATE_20HZ" in (tmp_path / "generated/python/nmeaspec/enums/geos5_output_rate.py").read_text()
    assert "gst_rate" in (tmp_path / "generated/c/nmea.h").read_text()
    assert gen("--spec", "spec", "generate", "--out", "generated", cwd=tmp_path).stdout.startswith("nothing changed")

    changelog = gen("diff", "HEAD", "spec", "--fail-on-breaking", cwd=tmp_path).stdout    # exit 0: nothing breaks
    assert "3 change(s): 0 BREAKING, 3 compatible." in changelog, changelog
    assert "- compatible: `GEOS5_NQUERY`: optional field `gst_rate` (enum(geos5_message_rate)) added at the end" in changelog
    assert "- compatible: `geos5_output_rate`: value `rate_20hz` (code 4) added" in changelog
    assert re.search(r"- compatible: `GEOS5_NQUERY`: example from geos5 added: `\$GPSGG,NQUERY,[0-9,R]+\*[0-9A-F]{2}`",
                     changelog)
    assert changelog.index("## Fields") < changelog.index("## Enums") < changelog.index("## Examples")

    # Backwards, with a sentence dropped too: what breaks, as JSON, and the exit status for CI.
    (tmp_path / "spec" / "proprietary" / "psrf150.yaml").unlink()
    result = gen("diff", "spec", "HEAD:spec", "--json", "--fail-on-breaking", cwd=tmp_path, check=False)
    assert result.returncode == 1, result.stderr
    report = json.loads(result.stdout)
    changes = {c["change"]: c["breaking"] for c in report["changes"]}
    assert changes == {
        "sentence `PSRF150` added (vendor gs501, address PSRF150)": False,
        "`GEOS5_NQUERY`: field `gst_rate` removed": True,
        "`geos5_output_rate`: value `rate_20hz` (code 4) removed": True,
        f"`GEOS5_NQUERY`: example from geos5 removed: `${NEW_BODY}*{_checksum(NEW_BODY)}`": False,
    }, changes
    assert report["breaking"] == 2 and report["old"] == "spec" and report["new"] == "HEAD:spec"


# --- diff: every kind of change, on the model ------------------------------------------------

@pytest.fixture(scope="module")
def spec():
    return load_spec(SPEC)


def test_a_subset_of_binary_messages(spec) -> None:
    """`--only` words naming binary messages or protocols: only those and their replies are kept
    (another protocol not at all); the configuration keys only beside CFG-VALSET/GET/DEL."""
    chosen = subset(spec, ["GGA", "ubx:NAV-PVT", "ubx:cfg_rate", "rtcm3:1005", "sirf"])
    kept = {(m.protocol, m.id) for m in chosen.binary}
    assert {i for p, i in kept if p == "ubx"} == {"nav_pvt", "cfg_rate", "ack_ack", "ack_nak"}
    assert {p for p, _ in kept} == {"ubx", "sirf"}
    assert {i for p, i in kept if p == "sirf"} == {m.id for m in spec.binary if m.protocol == "sirf"}
    assert [s.id for s in chosen.sentences] == ["GGA"] and not chosen.config_keys
    assert [m.id for m in chosen.bit_messages] == [m.id for m in spec.bit_messages if 1005 in m.types]
    every = [(m.protocol, m.id) for m in spec.binary]
    assert [(m.protocol, m.id) for m in subset(spec, ["GGA"]).binary] == every   # no binary word: all
    assert subset(spec, ["CFG-VALSET"]).config_keys and not subset(spec, ["CFG-VALSET"]).sentences
    both = {m.protocol for m in subset(spec, ["CFG-MSG"]).binary if m.id == "cfg_msg"}
    assert both == {"ubx", "casic"}   # a bare name: every protocol's message of that name
    unicore = {m.id for m in spec.binary if m.protocol == "unicore"}
    assert {m.id for m in subset(spec, ["unicore"]).binary} == unicore and len(unicore) == 8   # a protocol: all its messages
    for words, error in ((["ubx:NAV-NOPE"], "ubx has no message 'nav-nope'"), (["nope:NAV-PVT"], "unknown protocol 'nope'"),
                         (["unicore:BESTPOSB"], "unicore has no message 'bestposb'")):
        with pytest.raises(SelectionError, match=error):
            subset(spec, words)


def _changes(old, new) -> dict[str, bool]:
    return {c.change: c.breaking for c in diff.compare(old, new)}


def test_diff_classifies_field_changes(spec) -> None:
    new = copy.deepcopy(spec)
    gga = new.sentence("GGA")
    items = gga.layout.items
    quality = next(i for i in items if i.id == "quality")
    items.insert(items.index(quality), Field("extra", "Extra", "integer", "", [], quality.origin))
    hdop = next(i for i in items if i.id == "hdop")
    hdop.id = "horizontal_dop"
    sats = next(i for i in items if i.id == "satellites")
    sats.type = "decimal"
    rmc = new.sentence("RMC").layout.items
    rmc[0], rmc[1] = rmc[1], rmc[0]
    vtg = new.sentence("VTG").layout.items
    vtg.append(Field("trailing", "Trailing", "integer", "", [], vtg[0].origin, optional=True))
    zda = new.sentence("ZDA").layout.items
    zda.append(Field("required_tail", "Required", "integer", "", [], zda[0].origin))
    changes = _changes(spec, new)
    assert changes["`GGA`: field `extra` (integer) inserted after `lon`: the fields after it move on the wire"] is True
    assert changes["`GGA`: field `hdop` renamed to `horizontal_dop` (same place and type)"] is True
    assert changes["`GGA.satellites`: type integer(xx) -> decimal(xx)"] is True
    assert any(c.startswith("`RMC`: fields reordered") and b for c, b in changes.items()), changes
    assert changes["`VTG`: optional field `trailing` (integer) added at the end"] is False
    assert changes["`ZDA`: required field `required_tail` (integer) added at the end: "
                   "existing sentences without it no longer parse"] is True


def test_diff_classifies_enum_and_sentence_changes(spec) -> None:
    new = copy.deepcopy(spec)
    quality = next(e for e in new.enums if e.id == "gga_quality")
    removed = quality.values.pop()
    quality.values[0].code = "Z"
    new.sentences = [s for s in new.sentences if s.id != "HDT"]
    new.sentences.append(copy.deepcopy(spec.sentence("ZDA")))
    new.sentences[-1].id = "ZDX"
    changes = _changes(spec, new)
    assert changes[f"`gga_quality`: value `{removed.id}` (code {removed.code}) removed"] is True
    assert changes[f"`gga_quality`: value `{quality.values[0].id}` code {spec.enum_by_id['gga_quality'].values[0].code} -> Z"] is True
    assert changes["sentence `HDT` removed"] is True
    assert changes["sentence `ZDX` added"] is False
    assert not _changes(spec, copy.deepcopy(spec))
    text = diff.markdown(diff.compare(spec, new), "old", "new")
    assert text.startswith("# API changelog: old -> new\n\n")
    assert "\n## Sentences and commands\n\n- **BREAKING**: sentence `HDT` removed\n" in text
    assert "- compatible: sentence `ZDX` added\n" in text
    assert "No change to the generated API." in diff.markdown([], "a", "b")


def test_diff_loads_a_spec_written_for_the_first_release_schema(spec, tmp_path: Path) -> None:
    """0.1.0's spec (manuals with `vendor`, enums without `codes`) is upgraded in a copy and compared."""
    old = tmp_path / "spec-0.1"
    shutil.copytree(SPEC, old)
    manuals = old / "manuals.yaml"
    manuals.write_text(re.sub(r"(?m)^(\s+)maker:", r"\1vendor:", manuals.read_text()))
    hemisphere = old / "enums" / "north_south.yaml"
    hemisphere.write_text(re.sub(r"(?m)^codes: closed\n", "", hemisphere.read_text()))
    before = (manuals.read_text(), hemisphere.read_text())
    tree = diff.resolve_tree(str(old), tmp_path, "old")
    assert tree != old and (manuals.read_text(), hemisphere.read_text()) == before   # the user's files untouched
    changes = _changes(load_spec(tree), spec)
    assert changes == {"`north_south`: a code it does not list is now refused (codes closed)": True}
    assert diff.resolve_tree(str(SPEC), tmp_path, "new") == SPEC                    # today's: read in place


# --- reconcile a manual's text -------------------------------------------------------------------

def test_reconcile_finds_the_manuals_examples_in_the_spec(spec, tmp_path: Path) -> None:
    assert SEEDS.is_dir(), f"the manuals' texts are expected in {SEEDS}"
    for manual in spec.manuals:
        if not manual.file:
            continue
        results = reconcile.reconcile(spec, (SEEDS / manual.file).read_text(), manual.id)
        out = reconcile.report(results, manual.id, only_new=False)
        summary = out.splitlines()[-2]
        found = re.match(rf"(\d+) example sentence\(s\) in the manual \({manual.id}\): (\d+) already in the spec, (\d+) not",
                         summary)
        assert found, out[-2000:]
        total, in_spec, new = map(int, found.groups())
        assert total > 0 and in_spec >= total - 2, summary
        if manual.id == "teseo":    # a heading the spec has no example of, and an OCR fragment
            assert "line 287: $PSTMCOLD" in out and "$GPGGA5" in out and "address unknown to the spec" in out
        for r in results:
            if r.checksum == "damaged":
                assert r.in_spec and r.corrected, r
    out = gen("reconcile", SEEDS / spec.manual("gs501").file, cwd=tmp_path).stdout     # the command itself
    assert "10 example sentence(s) in the manual (gs501): 10 already in the spec, 0 not." in out


def test_reconcile_reports_a_new_revision(tmp_path: Path) -> None:
    body = "GPSGG,NQUERY,1,4,2,R,0,R,1,0,0,0,1,1,0,1"
    text = (f"3.12 NQUERY\nExample: \\$GPSGG, NQUERY,1,3,2,R,0,R,1,0,0,0,1,1,0*71 (port 1)\n"
            f"Revision 4.1: ${body}*{_checksum(body)}\nBroken: $GPSGG,JAMDET,*58\n"
            "Wrapped: $GPGGA,075241.00,5550.613576,N,03732.251532,E,1,22,0.5,\n00188.976,M,0014.4,M,,*66\n"
            "Format: $--GGA,hhmmss.ss,llll.ll,a*hh and $PSTMCOLD,<Mask><cr><lf>\nUnknown: $PXYZ,1,2*00\n")
    (tmp_path / "manual.txt").write_text(text)
    out = gen("reconcile", "manual.txt", "--manual", "geos5", cwd=tmp_path).stdout
    assert "line 2: $GPSGG, NQUERY,1,3,2,R,0,R,1,0,0,0,1,1,0*71\n    checksum ok once the typeset spaces are removed; GEOS5_NQUERY example" in out
    assert f"line 3: ${body}*{_checksum(body)}\n    checksum ok; NOT IN THE SPEC; does not decode: too_many_fields: GPSGG: GEOS5_NQUERY takes at most 14 fields, found 15" in out
    assert "line 4: $GPSGG,JAMDET,*58\n    checksum DAMAGED; NOT IN THE SPEC; decodes (checksum left out) as GEOS5_JAMDET" in out
    assert "line 5: $GPGGA,075241.00,5550.613576,N,03732.251532,E,1,22,0.5,00188.976,M,0014.4,M,,*66\n    checksum ok; GGA example" in out
    assert "$--GGA" not in out and "<Mask>" not in out
    assert "$PXYZ,1,2*00" in out and "address unknown to the spec" in out
    assert "5 example sentence(s) in the manual (geos5): 2 already in the spec, 3 not" in out


# --- vendor a renamed subset next to the default copy ----------------------------------------

# Two standard sentences and a receiver's: what a firmware vendors, and quick to build beside the default copy.
SUBSET = ("--only", "GGA,RMC,geos5,ubx:NAV-PVT,ubx:CFG-RATE", "--prefix", "gs5", "--namespace", "gs5nmea")
GEOS5 = "$GPSGG,JAMDET,*57"
TESEO = "$PSTMSETPAROK,1121*"


@pytest.fixture(scope="module")
def copies(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One temp dir for the session: a copy under the default names and the renamed GeoS-5 subset.
    The default-named copy is a subset too (the two receivers the tests read, GGA and RMC): what
    the tests check is that the names do not clash, and a subset is built in a fraction of the time
    of the whole spec (the whole crate alone is a minute of CPU)."""
    tmp = tmp_path_factory.mktemp("vendor")
    gen("generate", "--only", "GGA,RMC,geos5,teseo", "--out", tmp / "default", cwd=tmp)
    out = gen("generate", *SUBSET, "--out", tmp / "gs5", cwd=tmp).stdout
    assert "created gs5/c/gs5.h" in out and "created gs5/python/gs5nmea/__init__.py" in out
    return tmp


@pytest.mark.slow
def test_subset_leaves_other_vendors_out(copies: Path) -> None:
    gs5 = copies / "gs5"
    vectors = [json.loads(line) for line in (gs5 / "vectors/examples.jsonl").read_text().splitlines()]
    full = load_spec(SPEC)
    kept = {s.id for s in full.sentences if s.id in ("GGA", "RMC") or s.vendor == "geos5"}
    assert {v["sentence"] for v in vectors} == {s.id for s in full.sentences if s.id in kept and s.examples}
    # Other receivers' pages list only the subset's standard sentences (whose examples they wrote).
    others = [p for p in gs5.rglob("*") if p.parent.name != "vendors"]
    assert not [p for p in others if any(word in p.name for word in ("pstm", "psrf", "comnav"))]
    pages = {page.stem: page.read_text() for page in (gs5 / "docs/vendors").glob("*.md")}
    assert "teseo" in pages and "geos5" in pages
    assert not [name for name, text in pages.items() if name != "geos5" and ("PSTM" in text or "COMNAV_" in text)]
    assert "GS5_SENTENCE_PSTM" not in (gs5 / "c/gs5.h").read_text() and "GS5_SENTENCE_GEOS5_JAMDET" in (gs5 / "c/gs5.h").read_text()


@pytest.mark.slow
def test_renaming_is_complete(copies: Path) -> None:
    gs5 = copies / "gs5"
    for path in gs5.rglob("*"):
        if path.is_file() and path.suffix != ".jsonl" and not path.name.startswith("LICENSE-"):
            text = path.read_text()
            assert not re.search(r"\bnmeaspec\b", text), path
            if path.suffix in (".c", ".h"):
                code = re.sub(r'"(?:[^"\\\n]|\\.)*"', '""', text)
                leftover = set(re.findall(r"\b(?:nmea|NMEA)_\w*", code))
                assert leftover <= {"nmea_version"}, (path, leftover)   # a GeoS-5 field id, a struct member
            assert not re.search(r"\bnmea-(?:c|py|rs)\b", text), path       # the tools name their copy
    assert (gs5 / "rust/src/bin/gs5nmea-rs.rs").is_file()
    assert 'name = "gs5nmea-rs"' in (gs5 / "rust/Cargo.toml").read_text()
    assert 'prog="gs5nmea"' in (gs5 / "python/gs5nmea/apps/nmea_cli.py").read_text()


@pytest.mark.slow
def test_two_c_copies_in_one_program(copies: Path) -> None:
    program = copies / "both.c"
    program.write_text(f"""\
#include <stdio.h>
#include <string.h>
#include "nmea.h"
#include "gs5.h"

static int check(const char *line, int want_gs5, int want_nmea) {{
    gs5_sentence a;
    gs5_error ea;
    nmea_sentence b;
    nmea_error eb;
    if (!gs5_parse(&a, line, strlen(line), &ea) || !nmea_parse(&b, line, strlen(line), &eb)) return 0;
    return (int)a.id == want_gs5 && (int)b.id == want_nmea;
}}

int main(void) {{
    if (!check("{GEOS5}", GS5_SENTENCE_GEOS5_JAMDET, NMEA_SENTENCE_GEOS5_JAMDET)) return 1;
    if (!check("{TESEO}", GS5_SENTENCE_GENERIC, NMEA_SENTENCE_PSTMSETPAROK)) return 2;
    puts("both copies parse");
    return 0;
}}
""")
    cc = os.environ.get("CC", "gcc")
    run(cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-Idefault/c", "-Igs5/c", "-o", "both",
        "both.c", "default/c/nmea.c", "gs5/c/gs5.c", cwd=copies)
    assert run("./both", cwd=copies) == "both copies parse\n"
    run(cc, "-std=c99", "-c", "-o", "gs5.o", "gs5/c/gs5.c", cwd=copies)
    symbols = run("nm", "-g", "--defined-only", "gs5.o", cwd=copies).split()[2::3]
    assert symbols and all(s.startswith("gs5_") for s in symbols), [s for s in symbols if not s.startswith("gs5_")]
    run(cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-o", "gs5_tests", "gs5/c/gs5.c",
        "gs5/c/tests/test_examples.c", cwd=copies)
    assert " 0 failed" in run("./gs5_tests", cwd=copies)
    pair = [str(p.relative_to(copies)) for p in sorted((copies / "gs5" / "c").glob("*.c"))]  # with the AIS pair, if any
    run(cc, "-std=c99", "-o", "gs5-c", *pair, cwd=copies)
    usage = subprocess.run(["./gs5-c"], cwd=copies, capture_output=True, text=True)
    assert usage.returncode == 2 and usage.stderr.startswith("usage: gs5-c decode"), usage.stderr


@pytest.mark.slow
def test_two_rust_crates_in_one_project(copies: Path) -> None:
    app = copies / "app"
    (app / "src").mkdir(parents=True)
    (app / "Cargo.toml").write_text(f"""\
[package]
name = "app"
version = "0.1.0"
edition = "2021"

[dependencies]
nmeaspec = {{ path = "{copies / 'default/rust'}", default-features = false, features = ["geos5", "teseo"] }}
gs5nmea = {{ path = "{copies / 'gs5/rust'}" }}
""")
    (app / "src/main.rs").write_text(f"""\
fn main() {{
    let geos5 = "{GEOS5}";
    assert!(matches!(gs5nmea::parse(geos5), Ok(gs5nmea::Sentence::Geos5Jamdet(_))));
    assert!(matches!(nmeaspec::parse(geos5), Ok(nmeaspec::Sentence::Geos5Jamdet(_))));
    let teseo = "{TESEO}";
    assert!(matches!(gs5nmea::parse(teseo), Ok(gs5nmea::Sentence::Generic(_))));
    assert!(matches!(nmeaspec::parse(teseo), Ok(nmeaspec::Sentence::Pstmsetparok(_))));
    println!("both crates parse");
}}
""")
    out = run("cargo", "run", "--quiet", "--offline", "--target-dir", copies / "target", cwd=app)
    assert out == "both crates parse\n"


@pytest.fixture(scope="module")
def python_env(copies: Path) -> Path:
    """A fresh venv with the default package and the renamed subset installed by pip."""
    env = copies / "venv"
    venv.create(env, with_pip=True)
    python = env / "bin" / "python"
    # Build from copies: pip builds in the source tree and leaves build/ and *.egg-info behind.
    # With setuptools 77 or later (the license is an SPDX expression) and wheel in the venv, pip
    # builds without fetching a build environment for each package.
    has_tools = subprocess.run([python, "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
                                "--no-compile", "setuptools>=77", "wheel"], capture_output=True).returncode == 0
    options = ["--no-compile", "--no-deps"] + (["--no-build-isolation"] if has_tools else [])
    run(python, "-m", "pip", "install", "--quiet", *options, copies / "default/python", copies / "gs5/python",
        cwd=copies)
    return python


@pytest.mark.slow
def test_two_python_packages_in_one_environment(copies: Path, python_env: Path) -> None:
    script = f"""
import gs5nmea, nmeaspec
assert type(gs5nmea.parse({GEOS5!r})).__name__ == "Geos5Jamdet"
assert type(nmeaspec.parse({GEOS5!r})).__name__ == "Geos5Jamdet"
assert type(gs5nmea.parse({TESEO!r})).__name__ == "Generic"
assert type(nmeaspec.parse({TESEO!r})).__name__ == "Pstmsetparok"
assert gs5nmea.parse({GEOS5!r}).to_sentence() == {GEOS5!r}
assert not hasattr(gs5nmea, "Pstmsetpar") and hasattr(nmeaspec, "Pstmsetpar")
print("both packages parse")
"""
    assert run(python_env, "-c", script, cwd=copies) == "both packages parse\n"
    bin_dir = python_env.parent
    assert (bin_dir / "gs5nmea-py").exists() and (bin_dir / "nmea-py").exists()
    out = subprocess.run([bin_dir / "gs5nmea-py", "decode"], input=GEOS5 + "\n", capture_output=True, text=True)
    assert '"sentence":"GEOS5_JAMDET"' in out.stdout


@pytest.mark.slow
def test_a_subset_s_binary_messages_in_its_c_and_python_tools(copies: Path, python_env: Path) -> None:
    """The renamed subset names NAV-PVT and CFG-RATE: its tools type those (and ACK-ACK/NAK),
    keep UBX frames of other messages as unknown ones and show SBF frames untyped, alike in C and
    Python, over a UBX log and a log that mixes NMEA, RTCM 3 and SBF."""
    pair = [str(p.relative_to(copies)) for p in sorted((copies / "gs5" / "c").glob("*.c"))]
    run(os.environ.get("CC", "gcc"), "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O1",
        "-o", "gs5-ubx-c", *pair, cwd=copies)
    logs = ROOT / "tests/data/ubx/ublox-neo-m8l.log", ROOT / "tests/data/sbf/pygpsdata_mixed.log"
    data = b"".join(log.read_bytes() for log in logs)
    outputs = [subprocess.run([tool, "stream", "--ubx"], input=data, capture_output=True, check=True).stdout
               for tool in (copies / "gs5-ubx-c", python_env.parent / "gs5nmea-py")]
    assert outputs[0] == outputs[1]
    text = outputs[0].decode()
    assert '"ubx":{"message":"nav_pvt"' in text and '"ubx":{"message":null' in text
    assert '"protocol":"sbf"' in text and '"sbf":' not in text and '"sbf_error":' not in text
