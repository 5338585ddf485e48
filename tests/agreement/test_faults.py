"""Fault injection over the real logs: a log damaged the way a serial line damages it
(fuzz/faults.py: bytes lost, doubled, bit flips, lines cut short, garbage and NULs, two talkers
interleaved, line endings lost, all of them at once) through the three tools' `stream` verb,
with and without --require-checksum.

For every kind of damage:
(a) every item of the clean log that the damaged stream still holds whole and framed (faults.intact,
    from the damage's positions, not from a reader's output) decodes to exactly its JSON in the
    clean log;
(b) a damaged item is accepted (`"ok":true`) only when its checksum matches its damaged text (a
    checksum collision, counted; one hex digit matches a sum under 16, which the contract keeps
    as sent), or when it has no checksum at all (a `$`/`!` sentence without one,
    or with a bare `*`, counted: the contract accepts it unless --require-checksum, which must
    refuse it), or as a text command (which never has one); an accepted item holds printable ASCII
    only;
(c) the three tools print byte-identical output (AIS messages and those given up included);
(d) every tool exits 0 within the timeout and prints exactly one line per framed item (besides the
    incomplete_message lines of AIS messages given up), each line bounded by the item's length.
The counts per kind are printed at the end of the run (conftest.py) and written to
build/reports/faults.md.

`make test` runs a short version: three logs (about 20,000 lines), one seed. `make fuzz-faults`
runs every log with several seeds: FAULT_LOGS=all, FAULT_SEEDS=N (seeds 1..N), FAULT_RATE=x
(multiplies every damage rate). A failure names the kind, the seed, the position and the bytes,
and writes the damaged stream to build/faults/.
"""

from __future__ import annotations

import json
import os
import subprocess
from dataclasses import dataclass
from functools import lru_cache

import pytest

from fuzz import faults

from .test_agreement import BIN, CORPUS, ROOT, TOOLS

SHORT_LOGS = ("aerorust/aerorust-nmea1.nmea", "marine-api/garmin-gps15h.nmea", "gpsd/ais-nmea.nmea")
LONG = os.environ.get("FAULT_LOGS", "short") == "all"
SEEDS = range(1, int(os.environ.get("FAULT_SEEDS", "1")) + 1)
RATE = float(os.environ.get("FAULT_RATE", "1"))
TIMEOUT = 300
# (b) and the counts come from the first two; the others are held to (c) and (d) only.
RUNS = (("stream",), ("stream", "--require-checksum")) + ((("stream", "--lenient", "--values"),) if LONG else ())
OUT = ROOT / "build" / "faults"
REPORT = ROOT / "build" / "reports" / "faults.md"


@dataclass
class Row:
    kind: str
    seed: int
    clean: int = 0  # items of the clean stream(s)
    clean_ok: int = 0  # of which decode ("ok":true)
    intact: int = 0  # clean items the damaged stream holds whole
    recovered: int = 0  # intact items decoded exactly as in the clean log
    lost: int = 0  # clean sentences that decode, not recovered
    damaged: int = 0  # items of the damaged stream that are not an intact clean item
    same_bytes: int = 0  # damaged, but byte for byte a clean item (a '$' from the other talker)
    collision: int = 0  # damaged, accepted: the checksum matches the damaged text
    no_checksum: int = 0  # damaged, accepted: a sentence without a checksum
    text_command: int = 0  # damaged, accepted as a text command
    required: int = 0  # damaged, accepted with --require-checksum (collisions and text commands only)


ROWS: list[Row] = []


@dataclass
class Clean:
    """The clean stream(s): their bytes, framed items and the tools' output per run."""

    streams: tuple[bytes, ...]
    items: list[list[tuple[int, int]]]
    json: dict[tuple[str, ...], list[list[bytes]]]
    texts: dict[bytes, tuple[int, int]]  # an item's bytes: (stream, index) of its first occurrence


def log() -> tuple[bytes, bytes]:
    """The log to damage, and its partner for `interleave`: the same lines rotated by half (so the
    two talkers send different sentences at the same time)."""
    paths = sorted(CORPUS.rglob("*.nmea")) if LONG else [CORPUS / name for name in SHORT_LOGS]
    parts = [path.read_bytes() for path in paths]
    data = b"".join(part if part.endswith(b"\n") else part + b"\n" for part in parts)
    return data, rotated(data)


def rotated(data: bytes) -> bytes:
    half = data.index(b"\n", len(data) // 2) + 1
    return data[half:] + data[:half]


def run_tools(args: tuple[str, ...], data: bytes, where: str) -> tuple[dict[str, bytes], list[str]]:
    """Each tool's output; the problems (d) finds: an exit status, a timeout."""
    outputs, problems = {}, []
    for tool in TOOLS:
        try:
            done = subprocess.run([str(BIN / tool), *args], input=data, capture_output=True, timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            problems.append(f"{where}: {tool} {' '.join(args)} did not finish in {TIMEOUT} s")
            outputs[tool] = b""
            continue
        if done.returncode != 0:
            problems.append(f"{where}: {tool} {' '.join(args)} exited {done.returncode}: {done.stderr[-500:]!r}")
        outputs[tool] = done.stdout
    return outputs, problems


@lru_cache(maxsize=None)
def clean() -> Clean:
    return prepare(log())


def prepare(streams: tuple[bytes, bytes]) -> Clean:
    items = [faults.items(data) for data in streams]
    out: dict[tuple[str, ...], list[list[bytes]]] = {}
    for args in RUNS[:2]:
        out[args] = []
        for data, spans in zip(streams, items):
            outputs, problems = run_tools(args, data, "the clean log")
            assert not problems, problems
            assert len(set(outputs.values())) == 1, f"the tools disagree on the clean log ({' '.join(args)})"
            lines = item_lines(outputs[TOOLS[0]])[:-1]
            assert len(lines) == len(spans), "the tools frame the clean log differently from faults.items"
            out[args].append(lines)
    texts: dict[bytes, tuple[int, int]] = {}
    for s, (data, spans) in enumerate(zip(streams, items)):
        for i, (start, end) in enumerate(spans):
            texts.setdefault(data[start:end], (s, i))
    return Clean(streams, items, out, texts)


INCOMPLETE = b'{"ok":false,"error":{"kind":"incomplete_message"'
AIS_MEMBERS = (b',"ais":', b',"ais_error":')


def item_lines(output: bytes) -> list[bytes]:
    """stream's output split on LF, one line per framed item: without the incomplete_message lines
    of AIS messages given up, and without the AIS message a line ends with (these checks are about
    the sentences; (c) holds the AIS answers alike in the three tools)."""
    lines = output.split(b"\n")
    items = [line for line in lines[:-1] if not line.startswith(INCOMPLETE)] + lines[-1:]
    for member in AIS_MEMBERS:
        items = [line[:line.find(member)] + b"}" if member in line else line for line in items]
    return items


def shown(data: bytes) -> str:
    return repr(data if len(data) <= 160 else data[:120] + b"..." + data[-30:])


Outputs = dict[tuple[str, ...], dict[str, bytes]]  # per run of RUNS, per tool


def check(damaged: faults.Damaged, base: Clean, outputs: Outputs) -> tuple[Row, list[str]]:
    """The invariants over the tools' outputs for one damaged stream: the counts and every
    violation, each naming the kind, seed, position and bytes."""
    row = Row(damaged.kind, damaged.seed)
    data = damaged.data
    streams = (0, 1) if damaged.kind == "interleave" else (0,)
    row.clean = sum(len(base.items[s]) for s in streams)
    ok_line = b'{"ok":true'
    row.clean_ok = sum(line.startswith(ok_line) for s in streams for line in base.json[RUNS[0]][s])
    spans = faults.items(data)
    whole = faults.intact(damaged, base.items)
    problems: list[str] = []

    def where(x: int, y: int) -> str:
        origin = damaged.origin(x)
        clean_at = f"clean stream {origin[0]} byte {origin[1]}" if origin else "a byte the damage made"
        near = "; ".join(e.describe() for e in damaged.events_near(x, y)[:6]) or "none"
        return (f"{damaged.kind} seed {damaged.seed}: damaged byte {x} ({clean_at}) {shown(data[x:y])}"
                f"\n    damage near it: {near}")

    framed = {start: end for start, end in spans}
    for x, (s, i, length) in whole.items():
        assert framed.get(x) == x + length, f"faults.intact and faults.items disagree at {x}: {where(x, x + length)}"
    recovered: dict[tuple[int, int], bool] = {}
    for args in RUNS:
        tools = outputs[args]
        # (c) byte-identical output
        for tool, out in tools.items():
            if out != tools[TOOLS[0]]:
                first, other = item_lines(tools[TOOLS[0]]), item_lines(out)
                if first == other:  # they differ in an AIS answer: the lines as printed
                    first, other = tools[TOOLS[0]].split(b"\n"), out.split(b"\n")
                at = next(k for k in range(max(len(first), len(other)))
                          if k >= len(first) or k >= len(other) or first[k] != other[k])
                x, y = spans[at] if at < len(spans) else (len(data), len(data))
                problems.append(f"(c) {TOOLS[0]} and {tool} differ ({' '.join(args)}) on item {at + 1}, {where(x, y)}"
                                f"\n    {TOOLS[0]}: {shown(first[at]) if at < len(first) else '(none)'}"
                                f"\n    {tool}: {shown(other[at]) if at < len(other) else '(none)'}")
        lines = {tool: item_lines(out) for tool, out in tools.items()}
        first = lines[TOOLS[0]]
        # (d) one line per framed item, each bounded
        for tool, out in lines.items():
            if out[-1] != b"" or len(out) - 1 != len(spans):
                problems.append(f"(d) {damaged.kind} seed {damaged.seed}: {tool} {' '.join(args)} printed "
                                f"{len(out) - 1} lines (last ended: {out[-1] == b''}) for {len(spans)} framed items")
                continue
            for (x, y), line in zip(spans, out):
                if len(line) > 8 * min(y - x, 1025) + 1024:
                    problems.append(f"(d) {tool} {' '.join(args)} printed {len(line)} bytes for {where(x, y)}")
        if problems or args not in RUNS[:2]:
            continue
        expected = base.json[args]
        required = args == RUNS[1]
        for (x, y), line in zip(spans, first):
            if x in whole:
                # (a) an intact item decodes as in the clean log
                s, i, _ = whole[x]
                same = line == expected[s][i]
                recovered[s, i] = recovered.get((s, i), True) and same
                if not same:
                    problems.append(f"(a) intact item {i + 1} decodes differently ({' '.join(args)}): {where(x, y)}"
                                    f"\n    clean: {shown(expected[s][i])}\n    here:  {shown(line)}")
                continue
            row.damaged += not required
            twin = base.texts.get(data[x:y])
            if twin is not None:
                # (a) the damage made the bytes of a clean item: they decode as that item does
                row.same_bytes += not required
                if line != expected[twin[0]][twin[1]]:
                    problems.append(f"(a) an item with the bytes of clean item {twin[1] + 1} decodes differently "
                                    f"({' '.join(args)}): {where(x, y)}"
                                    f"\n    clean: {shown(expected[twin[0]][twin[1]])}\n    here:  {shown(line)}")
            elif line.startswith(ok_line):
                kind = accepted(data[x:y], json.loads(line), required)
                if kind.startswith("violation"):
                    problems.append(f"(b) a damaged item is accepted, {kind[10:]} ({' '.join(args)}): {where(x, y)}"
                                    f"\n    decoded: {shown(line)}")
                elif required:
                    row.required += 1
                else:
                    setattr(row, kind, getattr(row, kind) + 1)
    row.intact = len(recovered)
    row.recovered = sum(recovered.values())
    decoded = {(s, i) for s in streams for i, line in enumerate(base.json[RUNS[0]][s]) if line.startswith(ok_line)}
    row.lost = len(decoded - {key for key, same in recovered.items() if same})
    return row, problems


def accepted(item: bytes, decoded: dict, required: bool) -> str:
    """Why a damaged item may be accepted: the Row field that counts it, or "violation: why"."""
    if any(b < 0x20 or b > 0x7E for b in item):
        return "violation: it holds a byte outside printable ASCII"
    if item[:1] not in (b"$", b"!"):
        return "text_command" if decoded["start"] == "" else "violation: it does not start with '$' or '!'"
    star = item.find(b"*")
    if star < 0 or star == len(item) - 1:
        return "violation: it has no checksum, with --require-checksum" if required else "no_checksum"
    digits = item[star + 1:]
    total = 0
    for byte in item[1:star]:
        total ^= byte
    if len(digits) not in (1, 2) or any(c not in b"0123456789abcdefABCDEF" for c in digits) or int(digits, 16) != total:
        return f"violation: its checksum {digits!r} does not match, computed {total:02X}"
    if decoded["checksum"] != digits.decode():
        return f"violation: its checksum {digits!r} is reported as {decoded['checksum']!r}"
    return "collision"


def outputs_of(damaged: faults.Damaged) -> tuple[Outputs, list[str]]:
    outputs, problems = {}, []
    for args in RUNS:
        outputs[args], failed = run_tools(args, damaged.data, f"{damaged.kind} seed {damaged.seed}")
        problems += failed
    return outputs, problems


def damage_and_check(kind: str, seed: int, base: Clean) -> tuple[faults.Damaged, Row, list[str]]:
    partner = base.streams[1] if kind == "interleave" else b""
    damaged = faults.damage(kind, seed, base.streams[0], partner, RATE)
    outputs, problems = outputs_of(damaged)
    row, found = check(damaged, base, outputs)
    return damaged, row, problems + found


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("kind", faults.KINDS)
def test_fault_injection(kind: str, seed: int) -> None:
    base = clean()
    damaged, row, problems = damage_and_check(kind, seed, base)
    if problems:
        OUT.mkdir(parents=True, exist_ok=True)
        saved = OUT / f"{kind}-{seed}.bin"
        saved.write_bytes(damaged.data)
        more = f"\n... and {len(problems) - 10} more" if len(problems) > 10 else ""
        pytest.fail(f"{len(problems)} violation(s); the damaged stream is in {saved}:\n"
                    + "\n".join(problems[:10]) + more)
    ROWS.append(row)
    REPORT.parent.mkdir(parents=True, exist_ok=True)
    REPORT.write_text(report())
    # The damage must have done something, and (but at ten times the rates and more) left
    # something to recover. A lost line ending only damages an item when the next line does not
    # start with '$' or '!'.
    assert damaged.events and damaged.data not in base.streams and row.recovered <= row.clean, row
    assert row.recovered > 0 or RATE > 10, row
    if kind not in ("cr_lost", "lf_lost", "eol_lost"):
        assert 0 < row.damaged and row.intact < row.clean, row


def report() -> str:
    rows = ["| damage | seed | clean items | of which decode | intact | recovered | lost | damaged items | "
            "a clean item's bytes | accepted: checksum collision | accepted: no checksum | accepted: text command | "
            "accepted with --require-checksum |",
            "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in ROWS:
        rows.append(f"| {r.kind} | {r.seed} | {r.clean} | {r.clean_ok} | {r.intact} | {r.recovered} | {r.lost} | "
                    f"{r.damaged} | {r.same_bytes} | {r.collision} | {r.no_checksum} | {r.text_command} | "
                    f"{r.required} |")
    return "\n".join(rows) + "\n"


# --- the model and the check themselves ----------------------------------------------------------


def test_damage_is_deterministic_and_its_runs_hold_the_bytes() -> None:
    data, partner = log()
    data, partner = data[:50000], partner[:50000]
    for kind in faults.KINDS:
        damaged = faults.damage(kind, 3, data, partner)
        again = faults.damage(kind, 3, data, partner)
        assert damaged.data == again.data and damaged.runs == again.runs, kind
        assert damaged.data != faults.damage(kind, 4, data, partner).data, kind
        assert damaged.events and damaged.data != data, kind
        streams = (data, partner)
        at = 0
        for run in damaged.runs:
            assert run.at == at, kind
            if run.stream >= 0:
                assert damaged.data[at:at + run.end - run.start] == streams[run.stream][run.start:run.end], kind
            at += run.end - run.start
        assert at == len(damaged.data), kind


def test_intact_means_whole_and_framed() -> None:
    data = b"$A,1\r\nTXT\r\n$B,2\r\n"
    spans = [faults.items(data)]
    assert [data[a:b] for a, b in spans[0]] == [b"$A,1", b"TXT", b"$B,2"]

    def whole(*events: faults.Event) -> list[bytes]:
        damaged = faults.apply("test", 0, data, list(events))
        return [damaged.data[x:x + n] for x, (_, _, n) in sorted(faults.intact(damaged, spans).items())]

    assert whole(faults.Event(9, "drop", size=2)) == [b"$A,1", b"TXT", b"$B,2"]  # TXT$B,2: '$' ends TXT
    assert whole(faults.Event(4, "drop", size=2)) == [b"$B,2"]  # $A,1TXT
    assert whole(faults.Event(5, "dup", size=1)) == [b"$A,1", b"TXT", b"$B,2"]  # a doubled LF
    assert whole(faults.Event(7, "flip", mask=1)) == [b"$A,1", b"$B,2"]
    assert whole(faults.Event(0, "dup", size=1)) == [b"$A,1", b"TXT", b"$B,2"]  # $ then $A,1
    assert whole(faults.Event(14, "insert", made=b"\0")) == [b"$A,1", b"TXT"]  # $B,\02
    assert whole(faults.Event(15, "insert", made=b"x")) == [b"$A,1", b"TXT"]  # $B,2x


@pytest.fixture(scope="module")
def small():
    """A few hundred lines, heavily damaged, and the tools' outputs."""
    data = log()[0]
    head = data[:data.index(b"\n", 40000) + 1]
    base = prepare((head, rotated(head)))
    damaged = faults.damage("mix", 7, head, rate=10)
    outputs, problems = outputs_of(damaged)
    row, found = check(damaged, base, outputs)
    assert not problems and not found, problems + found
    assert row.no_checksum and row.damaged > 100, row
    return base, damaged, outputs


def changed(outputs: dict, args: tuple[str, ...], index: int, line: bytes, tools=TOOLS) -> dict:
    out = {a: dict(per_tool) for a, per_tool in outputs.items()}
    for tool in tools:
        lines = out[args][tool].split(b"\n")
        lines[index] = line
        out[args][tool] = b"\n".join(lines)
    return out


def test_the_check_fails_on_wrong_output(small) -> None:
    """Each invariant fails when the tools' output is made wrong in its way."""
    base, damaged, outputs = small
    spans = faults.items(damaged.data)
    whole = faults.intact(damaged, base.items)
    lines = {args: outputs[args][TOOLS[0]].split(b"\n") for args in RUNS}
    plain, required = RUNS[0], RUNS[1]
    some_ok = next(line for line in lines[plain] if line.startswith(b'{"ok":true'))

    def fails(out: dict, tag: str) -> None:
        found = check(damaged, base, out)[1]
        assert found and all(p.startswith(tag) for p in found), (tag, found)
        assert "mix seed 7" in found[0], found[0]

    intact_at = next(k for k, (x, _) in enumerate(spans) if x in whole)
    other = next(line for line in lines[plain] if line != lines[plain][intact_at])
    fails(changed(outputs, plain, intact_at, other), "(a)")
    fails(changed(outputs, required, intact_at, other), "(a)")
    mismatch = next(k for k, line in enumerate(lines[plain]) if b'"checksum_mismatch"' in line)
    fails(changed(outputs, plain, mismatch, some_ok), "(b)")
    missing = next(k for k, line in enumerate(lines[required]) if b'"missing_checksum"' in line)
    fails(changed(outputs, required, missing, some_ok), "(b)")
    fails(changed(outputs, plain, mismatch, some_ok, tools=TOOLS[2:]), "(c)")
    fails(changed(outputs, required, len(spans) - 1, b"", tools=TOOLS[:1]), "(c)")
    dropped = {a: {t: out.replace(b"\n", b"", 1) for t, out in per.items()} for a, per in outputs.items()}
    fails(dropped, "(d)")
