"""A live receiver without hardware: a simulated GNSS module on a pseudo-terminal streams a real
log and answers commands the way the spec says it does (an OK reply, an error reply, or nothing),
and `nmea listen`, `nmea send` (pip-installed with the serial extra) and the Receiver API talk to
it as they would to /dev/ttyUSB0."""

from __future__ import annotations

import dataclasses
import io
import json
import os
import select
import signal
import subprocess
import sys
import threading
import time
import tty
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from .conftest import GENERATED, Venv, corpus_log, run

sys.path.insert(0, str(GENERATED / "python"))
import nmeaspec  # noqa: E402
from nmeaspec import Number, NmeaError, Receiver, ReplyTimeout, sentences  # noqa: E402
from nmeaspec.receiver import PortError  # noqa: E402
from nmeaspec.stream import Framer  # noqa: E402

LOG = "gpsd/quectel-L70.nmea"  # an MTK receiver: it also acknowledges other PMTK commands
EXAMPLES = [json.loads(line) for line in (GENERATED / "vectors/examples.jsonl").read_text().splitlines()]
ANSWER = 20.0  # seconds: the timeout where a reply must come (it comes after DELAY)
DELAY = 0.3  # seconds from a command to its reply: sentences of the log come meanwhile
SILENCE = 0.5  # seconds: the timeout where no reply comes


# --------------------------------------------------------------------------------------------
# Replies built from the spec: its pairing rules and its examples


def _field_spec(layout: Any, field_id: str) -> Any:
    return next(f for f in layout.LAYOUT.items if getattr(f, "id", None) == field_id)


def _value(layout: Any, field_id: str, kind: str, want: Any) -> Any:
    """The value of a (field, kind, value) test of REPLY_RULES / OUTCOME, as the field holds it."""
    if kind == "integer":
        return Number.of(want)
    if kind == "enum":
        return next(m for m in _field_spec(layout, field_id).enum if m.id == want)
    return want


def _instance(layout: Any) -> Any:
    """The reply layout's example in the spec, else an instance with every required field set."""
    for example in EXAMPLES:
        if example["sentence"] == layout.SENTENCE and example["variant"] == layout.VARIANT and example["checksum_ok"]:
            sentence = nmeaspec.parse(example["line"])
            if type(sentence) is layout:
                return sentence
    values = {}
    for spec in layout.LAYOUT.items:
        kind = getattr(spec, "KIND", None)
        if getattr(spec, "enum", None) is not None:
            values[spec.id] = next(iter(spec.enum))
        elif kind == "integer":
            values[spec.id] = Number.of(spec.low if spec.low is not None else 0)
    return layout(**values)


def reply_for(command: Any, outcome: str) -> bytes:
    """The bytes of a reply that the spec pairs with `command` and that reports `outcome` ("ok"
    or "error"): a reply layout of its REPLY_RULES, with the fields the rule names set (the
    command number of $PMTK001) and, when the layout's OUTCOME is a field, that field set to a
    value that means `outcome`."""
    for reply_id, variant, tests in command.REPLY_RULES:
        layout = next(lay for lay in sentences.layouts(reply_id) if lay.VARIANT == variant)
        values = {f: _value(layout, f, kind, want) for f, kind, want in tests}
        judged = getattr(layout, "OUTCOME", None)
        if judged is None or judged == "error":
            if (judged or "ok") != outcome:
                continue
        else:
            field_id, kind, _ = judged[0]
            ok_values = {want for f, _, want in judged if f == field_id}
            members = list(_field_spec(layout, field_id).enum)
            values[field_id] = next(m for m in members if (m.id in ok_values) == (outcome == "ok"))
        reply = dataclasses.replace(_instance(layout), **values)
        data: bytes = reply.to_bytes()
        assert nmeaspec.reply_to(command, nmeaspec.parse(data)) == outcome
        return data
    raise LookupError(f"the spec gives {command.SENTENCE} no {outcome} reply")


def test_replies_come_from_the_spec() -> None:
    pmtk220 = sentences.Pmtk220(interval=Number.of(1000))
    assert reply_for(pmtk220, "ok") == b"$PMTK001,220,3*30\r\n"
    assert reply_for(pmtk220, "error").startswith(b"$PMTK001,220,")
    fixrate = sentences.Pqtmcfgfixrate(fix_interval=Number.of(1000))
    assert reply_for(fixrate, "ok").startswith(b"$PQTMCFGFIXRATE,OK")
    assert reply_for(fixrate, "error").startswith(b"$PQTMCFGFIXRATE,ERROR,")


# --------------------------------------------------------------------------------------------
# The simulated receiver


class SimulatedReceiver:
    """A GNSS module on a pseudo-terminal: it streams the lines of a real log, a line every
    `pace` seconds (for ever, from the top again), with a garbage line and a line with a bad
    checksum now and then, and answers the commands of `answers` (sentence id -> "ok", "error"
    or "silent") `delay` seconds after they come. A line the port has no room for is dropped
    whole, as a UART drops what nobody reads; replies are never dropped."""

    def __init__(self, log: Path, answers: dict[str, str], delay: float = DELAY, pace: float = 0.01) -> None:
        self.master, self.slave = os.openpty()
        tty.setraw(self.slave)  # no echo, no line editing, until a client sets the port up itself
        os.set_blocking(self.master, False)
        self.path = os.ttyname(self.slave)
        self.log_lines = [line + b"\r\n" for line in log.read_bytes().splitlines() if line.strip()]
        self.answers = answers
        self.delay = delay
        self.pace = pace
        self.sent = bytearray()  # every byte written to the port
        self.commands: list[Any] = []  # every command received, decoded
        self.replies: list[bytes] = []  # every reply written
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def __enter__(self) -> SimulatedReceiver:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join(10)
        os.close(self.master)
        os.close(self.slave)

    def wait_for_command(self, timeout: float = ANSWER, count: int = 1) -> Any:
        """The `count`th command received (None if it does not come in time)."""
        deadline = time.monotonic() + timeout
        while len(self.commands) < count and time.monotonic() < deadline:
            time.sleep(0.01)
        return self.commands[count - 1] if len(self.commands) >= count else None

    def _write(self, data: bytes, must: bool) -> None:
        written = 0
        deadline = time.monotonic() + 5
        while written < len(data):
            try:
                written += os.write(self.master, data[written:])
            except BlockingIOError:
                if not must and written == 0:
                    return
                if time.monotonic() > deadline:
                    break
                select.select([], [self.master], [], 0.05)
        self.sent += data[:written]

    def _run(self) -> None:
        framer = Framer()
        due: list[tuple[float, bytes]] = []
        count = 0
        next_line = time.monotonic()
        while not self._stop.is_set():
            wake = min([next_line, *(t for t, _ in due)])
            ready, _, _ = select.select([self.master], [], [], max(0.0, min(wake - time.monotonic(), 0.05)))
            if ready:
                try:
                    data = os.read(self.master, 4096)
                except (BlockingIOError, OSError):
                    data = b""
                for line in framer.feed(data):
                    self._command(line, due)
            now = time.monotonic()
            for item in [d for d in due if d[0] <= now]:
                due.remove(item)
                self.replies.append(item[1])
                self._write(item[1], must=True)
            if now >= next_line:
                count += 1
                if count % 40 == 0:
                    line = b"\x00\xffgarbage \x13\r\n"
                elif count % 40 == 20:
                    line = b"$GPGGA,150119.000,5104.0859,N,11405.7387,W,2,8,0.94,1102.4,M,-17.5,M,,*00\r\n"
                else:
                    line = self.log_lines[count % len(self.log_lines)]
                self._write(line, must=False)
                next_line += self.pace

    def _command(self, line: bytes | int, due: list[tuple[float, bytes]]) -> None:
        try:
            command = nmeaspec.parse(line) if isinstance(line, bytes) else None
        except NmeaError:
            return
        if getattr(command, "KIND", None) != "command":
            return
        self.commands.append(command)
        answer = self.answers.get(command.SENTENCE, "silent")
        if answer != "silent" and getattr(command, "REPLY_RULES", ()):
            due.append((time.monotonic() + self.delay, reply_for(command, answer)))


@pytest.fixture
def simulate() -> Iterator[Any]:
    """simulate(answers) -> a running SimulatedReceiver on the L70 log, stopped after the test."""
    running: list[SimulatedReceiver] = []

    def start(answers: dict[str, str], **options: float) -> SimulatedReceiver:
        sim = SimulatedReceiver(corpus_log(LOG), answers, **options).__enter__()
        running.append(sim)
        return sim

    yield start
    for sim in running:
        sim.__exit__()


def framed(data: bytes) -> list[bytes | int]:
    framer = Framer()
    return framer.feed(data) + framer.end()


def test_the_framer_keeps_a_tag_block_with_its_sentence() -> None:
    """A '\\' at the start of a line opens a TAG block: the '$' or '!' after its closing '\\'
    continues the line (the cases of the C and Rust framers' tests), in chunks of any size."""
    stream = (b"junk\\s:1*00\\$GPGGA,1*00\r\n\\s:x*31\\\\c:1*00\\!AIVDM,x\n$GPRMC\\x\\$GPGGA\n"
              b"\\g:1$2\\$GP\\x")
    expected = [b"junk\\s:1*00\\", b"$GPGGA,1*00", b"\\s:x*31\\\\c:1*00\\!AIVDM,x", b"$GPRMC\\x\\",
                b"$GPGGA", b"\\g:1$2\\$GP\\x"]
    for size in range(1, len(stream) + 1):
        framer = Framer()
        items = [i for at in range(0, len(stream), size) for i in framer.feed(stream[at:at + size])]
        assert items + framer.end() == expected, size


# --------------------------------------------------------------------------------------------
# The API


def test_receiver_on_a_file_yields_decoded_sentences() -> None:
    data = corpus_log("gpsd/blumax-gps009.nmea").read_bytes()  # 59 sentences, 8 lines of SiRF text
    with Receiver(io.BytesIO(data)) as rx:
        got = list(rx)
    good = []
    for line in data.splitlines():
        try:
            good.append(nmeaspec.parse(line))
        except NmeaError:
            pass
    assert got == good and len(got) == 59
    assert rx.skipped == {"not_a_sentence": 8} and rx.ended
    errors = [item for item in Receiver(io.BytesIO(data), errors="yield") if isinstance(item, NmeaError)]
    assert [e.kind for e in errors] == ["not_a_sentence"] * 8
    with pytest.raises(NmeaError):
        list(Receiver(io.BytesIO(data), errors="raise"))
    unknown = nmeaspec.Generic("PXYZQ", ["1", "2"]).to_sentence().encode()  # kept, as a Generic
    generic = list(Receiver(io.BytesIO(unknown + b"\r\n$GPZDA,150119.000,09,03,2022,,*53\r\n")))
    assert generic == [nmeaspec.Generic("PXYZQ", ["1", "2"]), nmeaspec.parse("$GPZDA,150119.000,09,03,2022,,*53")]


def test_api_send_ok_error_and_timeout_over_pyserial(simulate: Any) -> None:
    sim = simulate({"PMTK220": "ok"})
    with Receiver.open(sim.path, 9600) as rx:
        command = sentences.Pmtk220(interval=Number.of(1000))
        reply = rx.send(command, timeout=ANSWER)
        assert reply.ok and reply.outcome == "ok" and reply.line == b"$PMTK001,220,3*30"
        assert isinstance(reply.sentence, sentences.Pmtk001) and reply.sentence.command == Number.of(220)
        assert reply.command is command
        # the log kept coming meanwhile, acknowledgements of other commands among it
        assert len(reply.received) >= 5 and all(not isinstance(s, sentences.Pmtk001)
                                                 or s.command != Number.of(220) for s in reply.received)
        sim.answers["PMTK220"] = "error"
        reply = rx.send("$PMTK220,200*2C", timeout=ANSWER)  # a command as text
        assert not reply.ok and reply.outcome == "error" and reply.sentence.command == Number.of(220)
        assert reply.sentence.flag != nmeaspec.enums.MtkAckFlag.SUCCESS
        sim.answers["PMTK220"] = "silent"
        started = time.monotonic()
        with pytest.raises(ReplyTimeout) as silent:
            rx.send(sentences.Pmtk220(interval=Number.of(200)), timeout=SILENCE)
        assert SILENCE <= time.monotonic() - started < SILENCE + 2
        assert silent.value.expected == ("PMTK001 command=220",) and silent.value.received
        assert "no reply to PMTK220 within 0.5 s (expected PMTK001 command=220)" in str(silent.value)
        assert isinstance(silent.value, TimeoutError)
        # after all that, the stream goes on
        assert rx.read(timeout=ANSWER) is not None
    assert [c.to_sentence() for c in sim.commands] == ["$PMTK220,1000*1F", "$PMTK220,200*2C", "$PMTK220,200*2C"]


def test_api_on_a_plain_stream_quectel(simulate: Any) -> None:
    """No pyserial: the Receiver on the pseudo-terminal opened as a file, and Quectel's PQTM
    replies (OK / ERROR variants of one reply sentence)."""
    sim = simulate({"PQTMCFGFIXRATE": "ok"})
    fd = os.open(sim.path, os.O_RDWR | os.O_NOCTTY)
    with Receiver(open(fd, "r+b", buffering=0)) as rx:
        reply = rx.send(sentences.Pqtmcfgfixrate(fix_interval=Number.of(1000)), timeout=ANSWER)
        assert reply.ok and reply.sentence.SENTENCE == "PQTMCFGFIXRATE_RESULT"
        sim.answers["PQTMCFGFIXRATE"] = "error"
        reply = rx.send(sentences.Pqtmcfgfixrate(fix_interval=Number.of(1000)), timeout=ANSWER)
        assert reply.outcome == "error" and reply.sentence.VARIANT == "error"
        assert reply.line + b"\r\n" == sim.replies[-1]
        baud = sentences.Pmtk251(baud=nmeaspec.enums.MtkBaud.BAUD_9600)
        with pytest.raises(ValueError, match="nothing answers PMTK251"):
            rx.send(baud)
        assert rx.write(baud) == b"$PMTK251,9600*17\r\n" and sim.wait_for_command(ANSWER, 3).SENTENCE == "PMTK251"
        sentence = rx.read(timeout=ANSWER)
        assert sentence is not None and not isinstance(sentence, NmeaError)


def test_api_port_errors() -> None:
    with pytest.raises(ValueError, match="not a standard baud rate"):
        Receiver.open("/dev/null", 12345)
    with pytest.raises(PortError, match="cannot open /dev/ttyNOSUCHPORT: No such file or directory"):
        Receiver.open("/dev/ttyNOSUCHPORT", 9600)


# --------------------------------------------------------------------------------------------
# `nmea listen` and `nmea send`, pip-installed with the serial extra


def nmea(env: Venv, *args: str | Path, check: bool = False, timeout: float = 120) -> subprocess.CompletedProcess:
    return run(env.bin / "nmea", *args, check=check, cwd=env.path.parent, timeout=timeout)


def _out(result: subprocess.CompletedProcess) -> tuple[str, str]:
    return result.stdout.decode(), result.stderr.decode()


def test_send_ok_and_error(installed_extras: Venv, simulate: Any) -> None:
    sim = simulate({"PMTK220": "ok", "PQTMCFGFIXRATE": "error"})
    result = nmea(installed_extras, "send", "--port", sim.path, "--baud", "9600", "mtk_pmtk", "pmtk220", "1000",
                  "--timeout", str(ANSWER))
    out, err = _out(result)
    assert result.returncode == 0, err
    assert out == "> $PMTK220,1000*1F\n< $PMTK001,220,3*30\nok: PMTK001  command=220 flag=success\n"
    result = nmea(installed_extras, "send", "--port", sim.path, "quectel_lg290p", "pqtmcfgfixrate", "1000",
                  "--timeout", str(ANSWER))
    out, err = _out(result)
    error_reply = sim.replies[-1].decode().rstrip()
    assert result.returncode == 1, err
    assert out.splitlines() == ["> $PQTMCFGFIXRATE,W,1000*59", f"< {error_reply}",
                                out.splitlines()[2]]
    assert out.splitlines()[2].startswith("error: PQTMCFGFIXRATE_RESULT  status=ERROR error_code=")


def test_send_silence_is_a_timeout(installed_extras: Venv, simulate: Any) -> None:
    sim = simulate({})
    started = time.monotonic()
    result = nmea(installed_extras, "send", "--port", sim.path, "mtk_pmtk", "pmtk220", "200", "--timeout", str(SILENCE))
    elapsed = time.monotonic() - started
    out, err = _out(result)
    assert result.returncode == 2 and SILENCE < elapsed < SILENCE + 10
    assert out == "> $PMTK220,200*2C\n"
    assert err.startswith("nmea: no reply to PMTK220 within 0.5 s (expected PMTK001 command=220)")
    assert "Traceback" not in err and sim.wait_for_command().SENTENCE == "PMTK220"


def test_send_keeps_what_comes_meanwhile(installed_extras: Venv, simulate: Any, tmp_path: Path) -> None:
    sim = simulate({"PMTK220": "ok"}, delay=1.5)  # more than a round of the log (115 lines)
    log = tmp_path / "raw.nmea"
    log.write_bytes(b"$GPTXT,01,01,02,earlier*00\r\n")  # appended to, never overwritten
    result = nmea(installed_extras, "send", "--port", sim.path, "--show-all", "--log", log, "mtk_pmtk", "pmtk220",
                  "1000", "--timeout", str(ANSWER))
    out, err = _out(result)
    assert result.returncode == 0, err
    data = log.read_bytes()
    assert data.startswith(b"$GPTXT,01,01,02,earlier*00\r\n")
    received = data[len(b"$GPTXT,01,01,02,earlier*00\r\n"):]
    assert bytes(received) in bytes(sim.sent)  # byte for byte what the port delivered
    items = framed(received)
    before = items[:items.index(b"$PMTK001,220,3*30")]
    assert len(before) >= 100
    rows = out.splitlines()
    assert rows[0] == "> $PMTK220,1000*1F" and rows[-2:] == ["< $PMTK001,220,3*30",
                                                            "ok: PMTK001  command=220 flag=success"]
    shown = rows[1:-2]
    assert len(shown) == len(before)
    for row, line in zip(shown, before):
        try:
            sentence = nmeaspec.parse(line)
        except NmeaError as error:
            assert row.startswith(f"  ({error.kind}: "), (row, line)
            continue
        name = sentence.address if isinstance(sentence, nmeaspec.Generic) else sentence.SENTENCE
        assert row.startswith(f"  {name}  "), (row, line)
    assert any(row.startswith("  PMTK001  command=3") for row in shown)  # other acknowledgements


def test_send_mistakes(installed_extras: Venv, simulate: Any) -> None:
    missing = nmea(installed_extras, "send", "--port", "/dev/ttyNOSUCHPORT", "mtk_pmtk", "pmtk220", "1000")
    assert missing.returncode == 3
    assert missing.stderr == b"nmea: cannot open /dev/ttyNOSUCHPORT: No such file or directory\n"
    for baud in ("12345", "-9600", "fast", "0"):
        bad = nmea(installed_extras, "send", "--port", "/dev/ttyNOSUCHPORT", "--baud", baud, "mtk_pmtk", "pmtk220",
                   "1000")
        assert bad.returncode == 2 and bad.stderr.startswith(f"nmea: --baud '{baud}' is not a standard baud rate: ".encode())
    bad = nmea(installed_extras, "send", "--port", "/dev/ttyNOSUCHPORT", "mtk_pmtk", "pmtk220", "50")
    assert bad.returncode == 2
    assert bad.stderr == b'nmea: pmtk220 interval: expected integer 100..10000, found "50"; usage: pmtk220 INTERVAL\n'
    bad = nmea(installed_extras, "send", "--port", "/dev/ttyNOSUCHPORT", "mtk_pmtk", "pmtk251", "1234")
    assert bad.returncode == 2 and bad.stderr.startswith(b"nmea: baud: '1234' is not one of 0 (default), 4800 (baud-4800)")
    bad = nmea(installed_extras, "send", "--port", "/dev/ttyNOSUCHPORT", "mtk_pmtk", "pmtk220", "1000", "--timeout", "0")
    assert bad.returncode == 2 and b"--timeout '0'" in bad.stderr
    assert all(b"Traceback" not in r.stderr for r in (missing, bad))
    # a command that nothing answers: sent, and done
    sim = simulate({})
    sent = nmea(installed_extras, "send", "--port", sim.path, "teseo", "pstmhot", "--timeout", str(SILENCE))
    assert sent.returncode == 0
    assert sent.stdout == b"> $PSTMHOT*49\nnothing answers PSTMHOT in the spec: sent, not waiting\n"
    assert sim.wait_for_command().SENTENCE == "PSTMHOT"
    # --baud after the command is the command's own argument when it has one
    sim = simulate({})
    sent = nmea(installed_extras, "send", "--port", sim.path, "--baud", "9600", "mtk_pmtk", "pmtk251", "--baud",
                "115200", "--timeout", str(SILENCE))
    assert sent.stdout == b"> $PMTK251,115200*1F\nnothing answers PMTK251 in the spec: sent, not waiting\n"


def test_listen_count_and_formats(installed_extras: Venv, simulate: Any, tmp_path: Path) -> None:
    sim = simulate({})
    log = tmp_path / "raw.nmea"
    result = nmea(installed_extras, "listen", "--port", sim.path, "--baud", "9600", "--count", "5", "--log", log)
    out, err = _out(result)
    assert result.returncode == 0, err
    rows = out.splitlines()
    assert rows[0].split() == ["line", "talker", "sentence", "fields"] and len(rows) == 6
    assert " lines: " in err.splitlines()[0]
    assert bytes(log.read_bytes()) in bytes(sim.sent)
    result = nmea(installed_extras, "listen", "--port", sim.path, "--json", "--sentences", "GGA", "--fields",
                  "sentence,time,lat,quality", "--count", "3", "-q")
    lines = result.stdout.decode().splitlines()
    assert result.returncode == 0 and result.stderr == b"" and len(lines) == 3
    assert all(json.loads(line)["sentence"] == "GGA" and set(json.loads(line)) == {"sentence", "time", "lat", "quality"}
               for line in lines)
    started = time.monotonic()
    result = nmea(installed_extras, "listen", "--port", sim.path, "--csv", "--fields", "sentence", "--duration", "1")
    assert result.returncode == 0 and 1 <= time.monotonic() - started < 10
    assert result.stdout.decode().splitlines()[0] == "sentence" and len(result.stdout.splitlines()) > 10
    assert result.stderr.decode().startswith(f"{result.stderr.decode().split()[0]} lines: ")


def test_listen_until_ctrl_c(installed_extras: Venv, simulate: Any) -> None:
    sim = simulate({})
    # As at a terminal: SIGINT not ignored (a shell's background job inherits it ignored, and
    # Python then installs no KeyboardInterrupt handler).
    process = subprocess.Popen([installed_extras.bin / "nmea", "listen", "--port", sim.path, "--fields", "sentence"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        assert process.stdout is not None
        header = process.stdout.readline()
        first = process.stdout.readline()  # rows come as they arrive, not when the run ends
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=30)
    finally:
        process.kill()
    assert header == b"sentence\n" and first.strip()
    assert process.returncode == 0 and b"Traceback" not in err and b" lines: " in err


def test_listen_and_send_bad_ports(installed_extras: Venv, installed: Venv) -> None:
    result = nmea(installed_extras, "listen", "--port", "/dev/ttyNOSUCHPORT", "--count", "1")
    assert result.returncode == 3 and result.stderr == b"nmea: cannot open /dev/ttyNOSUCHPORT: No such file or directory\n"
    result = nmea(installed_extras, "listen", "--port", "/dev/null", "--baud", "9601")
    assert result.returncode == 2 and b"not a standard baud rate" in result.stderr
    # without the extra: the package works, and the verbs say what to install
    for verb in (["listen"], ["send", "mtk_pmtk", "pmtk220", "1000"]):
        result = nmea(installed, verb[0], "--port", "/dev/ttyUSB0", *verb[1:])
        assert result.returncode == 3
        assert result.stderr == b"nmea: reading a serial port needs pyserial: pip install 'nmeaspec[serial]'\n"
