"""`nmea config get|set|del` and `nmea send ubx`, and Receiver.send of a UBX message, against a
fake receiver behind TCP that answers with ACK-ACK, ACK-NAK, a CFG-VALGET answer or nothing."""

from __future__ import annotations

import io
import json
import socket
import sys
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager, redirect_stderr, redirect_stdout
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec import ubx, ubx_config, ubx_messages  # noqa: E402
from nmeaspec.apps.nmea_cli import main  # noqa: E402
from nmeaspec.receiver import Receiver, ReplyTimeout  # noqa: E402

DB = ubx_config.database()


def ack(msg_id: int, ok: bool = True) -> bytes:
    return ubx.Frame(0x05, 0x01 if ok else 0x00, bytes((0x06, msg_id))).encode()


def valget_answer(pairs: bytes, layer: int = 0, position: int = 0) -> bytes:
    return ubx.Frame(0x06, 0x8B, bytes((1, layer)) + position.to_bytes(2, "little") + pairs).encode()


@contextmanager
def fake_receiver(answer: Callable[[bytes], bytes | None]) -> Iterator[tuple[str, list[bytes]]]:
    """A receiver behind TCP: each connection's first frame is answered with answer(frame), or
    with nothing; yields its HOST:PORT and the frames it got."""
    server = socket.create_server(("127.0.0.1", 0))
    host, port = server.getsockname()[:2]
    got: list[bytes] = []

    def serve() -> None:
        while True:
            try:
                connection, _ = server.accept()
            except OSError:
                return
            with connection:
                connection.settimeout(5)
                data = b""
                while True:
                    if len(data) >= 8 and len(data) >= 8 + int.from_bytes(data[4:6], "little"):
                        frame, data = data[:8 + int.from_bytes(data[4:6], "little")], data[8 + int.from_bytes(
                            data[4:6], "little"):]
                        got.append(frame)
                        reply = answer(frame)
                        if reply is None:
                            break
                        connection.sendall(reply)
                        continue
                    try:
                        chunk = connection.recv(4096)
                    except OSError:
                        break
                    if not chunk:
                        break
                    data += chunk

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield f"{host}:{port}", got
    finally:
        server.close()


def run(*args: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        status = main(list(args))
    return status, out.getvalue(), err.getvalue()


GGA = b"$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n"


def test_receiver_send_pairs_ack_nak_and_times_out() -> None:
    replies = iter([GGA + ack(0x8B) + ack(0x8A, ok=False), GGA + ack(0x8A), None])
    with fake_receiver(lambda frame: next(replies)) as (where, got):
        host, port = where.split(":")
        with Receiver(socket.create_connection((host, int(port))), binary=True) as receiver:
            nak = receiver.send(ubx_config.valset({"CFG-RATE-MEAS": 0.2}), timeout=5)
            assert (nak.outcome, nak.sentence.ID, len(nak.received)) == ("error", "ack_nak", 2)   # GGA, other ACK
            okay = receiver.send(ubx_config.valset({"CFG-RATE-MEAS": 0.2}).encode(), timeout=5)  # its bytes
            assert (okay.ok, okay.sentence.ID, okay.line) == (True, "ack_ack", ack(0x8A))
            with pytest.raises(ReplyTimeout) as caught:
                receiver.send(ubx_config.valdel(["CFG-RATE-MEAS"]), timeout=0.3)
            assert "no reply to UBX CFG-VALDEL within 0.3 s (expected ACK-ACK or ACK-NAK)" in str(caught.value)
    assert got[0] == ubx_config.valset({"CFG-RATE-MEAS": 0.2}).encode()
    with Receiver(io.BytesIO(b"")) as text_only, pytest.raises(ValueError, match="binary=True"):
        text_only.send(ubx_config.valdel(["CFG-RATE-MEAS"]), timeout=0.1)


def _answers(frame: bytes) -> bytes | None:
    """A ZED-F9P that knows CFG-RATE and CFG-UART1 (RAM: CFG-RATE-MEAS 100 ms, ...) and refuses the rest."""
    known = {0x30210001: (100, 2), 0x30210002: (1, 2), 0x20210003: (1, 1), 0x20210004: (0, 1),
             0x40520001: (38400, 4)}
    f = ubx.decode_frame(frame)
    if f.msg_id == 0x8B:
        ids = [int.from_bytes(f.payload[i:i + 4], "little") for i in range(4, len(f.payload), 4)]
        pairs = b""
        for key_id in ids:
            matching = [k for k in known if k == key_id or key_id & 0xFFFF == 0xFFFF and k >> 16 & 0xFF ==
                        key_id >> 16 & 0xFF]
            if not matching:
                return ack(0x8B, ok=False)
            pairs += b"".join(k.to_bytes(4, "little") + known[k][0].to_bytes(known[k][1], "little") for k in matching)
        return valget_answer(pairs) + ack(0x8B)
    if f.msg_id in (0x8A, 0x8C):
        keys = DB.decode_values(f.payload[4:]) if f.msg_id == 0x8A else {}
        return ack(f.msg_id, ok=all(DB.key(name).id in known for name in keys))
    return None


def test_nmea_config_get_set_del() -> None:
    with fake_receiver(_answers) as (where, got):
        status, out, err = run("config", "get", "CFG-RATE-*", "CFG-UART1-BAUDRATE", "--tcp", where)
        assert (status, err) == (0, "")
        assert out.splitlines()[2:] == ["CFG-RATE-MEAS 0.1 s", "CFG-RATE-NAV 1 cycles", "CFG-RATE-TIMEREF GPS (1)",
                                        "CFG-RATE-NAV_PRIO 0 Hz", "CFG-UART1-BAUDRATE 38400 Bd"]
        assert out.startswith("> " + ubx_config.valget(["CFG-RATE-*", "CFG-UART1-BAUDRATE"]).encode().hex(" "))
        status, out, err = run("config", "get", "CFG-RATE-MEAS", "CFG-RATE-TIMEREF", "--raw", "--json", "--tcp",
                               where, "--layer", "bbr")
        assert (status, json.loads(out)) == (0, {"CFG-RATE-MEAS": 100, "CFG-RATE-TIMEREF": 1})
        assert got[-1] == ubx_config.valget(["CFG-RATE-MEAS", "CFG-RATE-TIMEREF"], layer="bbr").encode()
        status, out, err = run("config", "set", "CFG-RATE-MEAS", "0.2", "cfg_rate_timeref", "gal", "--layer",
                               "ram,bbr,flash", "--tcp", where)
        assert (status, out.splitlines()[-1], err) == (0, "ok: ACK-ACK", "")
        assert got[-1] == ubx_config.valset({"CFG-RATE-MEAS": 0.2, "CFG-RATE-TIMEREF": "GAL"},
                                            layers=("ram", "bbr", "flash")).encode()
        status, out, err = run("config", "set", "CFG-NAVSPG-DYNMODEL", "automot", "--tcp", where)
        assert (status, out, err) == (2, "", "nmea: CFG-NAVSPG-DYNMODEL takes one of PORT, STAT, PED, AUTOM, SEA, "
                                      "AIR1, AIR2, AIR4, WRIST, BIKE, MOWER, ESCOOTER or a number, not 'automot'\n")
        status, out, err = run("config", "set", "CFG-NAVSPG-DYNMODEL", "automot".upper()[:5], "--tcp", where)
        assert (status, out.splitlines()[-1]) == (1, "error: ACK-NAK")   # this receiver does not know it
        status, out, err = run("config", "get", "CFG-NAVSPG-DYNMODEL", "--tcp", where)
        assert status == 1 and "refused CFG-VALGET" in err
        status, out, err = run("config", "del", "CFG-RATE-*", "--tcp", where)
        assert (status, out.splitlines()[-1]) == (0, "ok: ACK-ACK")
        assert got[-1] == ubx_config.valdel(["CFG-RATE-*"], layers=("bbr", "flash")).encode()


def test_nmea_config_times_out_and_needs_a_port_only_to_send() -> None:
    with fake_receiver(lambda frame: None) as (where, got):
        status, out, err = run("config", "set", "CFG-RATE-MEAS", "0.2", "--tcp", where, "--timeout", "0.3")
        assert status == 2 and "no reply to UBX CFG-VALSET within 0.3 s (expected ACK-ACK or ACK-NAK)" in err
    buffer = io.BytesIO()
    stdout = io.TextIOWrapper(buffer)
    with redirect_stdout(stdout):
        assert main(["config", "set", "CFG-RATE-MEAS", "0.2", "--layer", "flash"]) == 0
    stdout.flush()
    assert buffer.getvalue() == ubx_config.valset({"CFG-RATE-MEAS": 0.2}, layers=("flash",)).encode()
    assert run("config", "get", "CFG-RATE-MEAS", "--layer", "ram,bbr")[2] == "nmea: get reads one layer, not " \
        "'ram,bbr'\n"
    assert run("config", "get", "CFG-NOPE-X")[2].startswith("nmea: no configuration key 'CFG-NOPE-X'")


def test_nmea_send_ubx() -> None:
    def answer(frame: bytes) -> bytes | None:
        f = ubx.decode_frame(frame)
        if (f.msg_class, f.msg_id) == (0x06, 0x08) and not f.payload:   # CFG-RATE poll
            return ubx.Frame(0x06, 0x08, bytes((0xE8, 0x03, 0x01, 0x00, 0x01, 0x00))).encode()
        if (f.msg_class, f.msg_id) == (0x06, 0x08):
            return ack(0x08, ok=f.payload[0] != 0)
        return _answers(frame)

    with fake_receiver(answer) as (where, got):
        status, out, err = run("send", "--tcp", where, "ubx", "CFG-RATE")
        assert (status, got[-1]) == (0, bytes.fromhex("b562060800000e30")), err
        assert out.splitlines()[-1].startswith("ok: CFG-RATE  ")
        status, out, err = run("send", "--tcp", where, "ubx", "CFG-RATE", '{"meas_rate": 200, "nav_rate": 1}')
        assert (status, out.splitlines()[-1]) == (0, "ok: ACK-ACK  cls_id=6 msg_id=8"), err
        assert ubx_messages.decode(got[-1]).to_dict()["meas_rate"] == 200
        status, out, err = run("send", "--tcp", where, "ubx", *ubx_config.valget(["CFG-RATE-MEAS"]).encode().hex(" ")
                               .split())
        assert status == 0 and out.splitlines()[-1] == "  CFG-RATE-MEAS 0.1 s", err
        status, out, err = run("send", "--tcp", where, "ubx", "CFG-RATE", '{"speed": 3}')
        assert status == 2 and err.startswith("nmea: UBX CFG-RATE has no member 'speed'")
        status, out, err = run("send", "--tcp", where, "ubx", "b5 62 06 08 00 00 0e 31")
        assert status == 2 and "bad_checksum" in err


def test_the_readme_example_as_written() -> None:
    """README.md's `nmea config get 'CFG-RATE-*'`, against a receiver with the defaults it shows."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    block = text.split("$ nmea config get 'CFG-RATE-*' --port /dev/ttyACM0\n", 1)[1].split("\n$ ", 1)[0]
    rate = {0x30210001: (1000, 2), 0x30210002: (1, 2), 0x20210003: (1, 1), 0x20210004: (0, 1)}

    def answer(frame: bytes) -> bytes:
        pairs = b"".join(k.to_bytes(4, "little") + v.to_bytes(n, "little") for k, (v, n) in rate.items())
        return valget_answer(pairs) + ack(0x8B)

    with fake_receiver(answer) as (where, got):
        status, out, err = run("config", "get", "CFG-RATE-*", "--tcp", where)
    assert (status, out, err) == (0, block + "\n", "")


def test_a_wildcard_get_pages_and_named_keys_do_not() -> None:
    """CFG-MSGOUT-* has more than 64 keys: asked again from position 64 until an answer is short;
    64 named keys are one poll."""
    msgout = [k for k in DB.keys if k.name.startswith("CFG-MSGOUT-")]
    named = msgout[:64]

    def answer(frame: bytes) -> bytes:
        payload = ubx.decode_frame(frame).payload
        position = int.from_bytes(payload[2:4], "little")
        wanted = msgout if payload[4:8] == (0x0091FFFF).to_bytes(4, "little") else named
        page = wanted[position:position + 64]
        return valget_answer(b"".join(k.id.to_bytes(4, "little") + b"\x01" for k in page), position=position) \
            + ack(0x8B)

    with fake_receiver(answer) as (where, got):
        status, out, err = run("config", "get", "CFG-MSGOUT-*", "--json", "--tcp", where)
        assert (status, err) == (0, "")
        assert json.loads(out) == {k.name: 1 for k in msgout}
        assert len(got) == len(msgout) // 64 + 1
        status, out, err = run("config", "get", *(k.name for k in named), "--json", "--tcp", where)
        assert (status, len(json.loads(out)), len(got)) == (0, 64, len(msgout) // 64 + 2)
