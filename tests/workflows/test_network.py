"""`nmea listen` on the network, pip-installed without any extra (the standard library reads
sockets): IEC 61162-450 datagrams to a multicast group and to a plain UDP port, and a TCP feed,
all on the loopback address."""

from __future__ import annotations

import errno
import json
import socket
import subprocess
import threading
import time
from collections.abc import Callable
from functools import reduce
from pathlib import Path

from .conftest import Venv, corpus_log, run

GGA = b"$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47"
VDM = b"!AIVDM,1,1,,B,13nUgBWP01PkHvDU7<kC4wvJ2>`<,0*27"
WAIT = 30.0  # seconds a listener may take to start and to get what it is sent


def tag_block(text: str) -> bytes:
    checksum = reduce(lambda total, char: total ^ ord(char), text, 0)
    return f"\\{text}*{checksum:02X}\\".encode()


# What a ship's network sends, one datagram each: sentences of the standard with their source and
# line count, a binary file transfer (no sentences: skipped), a plain datagram whose last line has
# no ending (it must not run on into the TAG block of the next datagram), two sentences in one.
DATAGRAMS = [
    b"UdPbC\x00" + tag_block("s:GP0001,n:1") + GGA + b"\r\n",
    b"RaUdP\x00" + bytes(range(40)),
    GGA,
    b"UdPbC\x00" + tag_block("s:AI0002,n:2") + VDM + b"\r\n",
    VDM + b"\r\n" + GGA + b"\r\n",
]
# What `nmea listen --json` prints of them: the line number, sentence, source.
EXPECTED = [(1, "GGA", "GP0001"), (2, "GGA", None), (3, "VDM", "AI0002"), (4, "VDM", None), (5, "GGA", None)]


def free_udp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def wait_until_bound(port: int, listener: subprocess.Popen) -> None:
    """Until the listener holds the UDP port (binding it again without SO_REUSEADDR then fails)."""
    deadline = time.monotonic() + WAIT
    while time.monotonic() < deadline:
        assert listener.poll() is None, listener.communicate()
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
            try:
                probe.bind(("", port))
            except OSError as err:
                assert err.errno == errno.EADDRINUSE
                time.sleep(0.2)  # it joins its group right after binding
                return
        time.sleep(0.05)
    raise AssertionError(f"nothing listens on UDP port {port}")


def listen_to(env: Venv, args: list[str], send: Callable[[subprocess.Popen], None]) -> tuple[list[dict], str]:
    """What `nmea listen ARGS --json` prints (records, and the summary on stderr) while `send`
    feeds it."""
    listener = subprocess.Popen([str(env.bin / "nmea"), "listen", *args, "--json"], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE)
    try:
        send(listener)
        out, err = listener.communicate(timeout=WAIT)
    finally:
        listener.kill()
    assert listener.returncode == 0, err
    return [json.loads(line) for line in out.decode().splitlines()], err.decode()


def udp_case(env: Venv, group: str | None) -> None:
    port = free_udp_port()
    where = ["--group", group, "--interface", "127.0.0.1"] if group else []

    def send(listener: subprocess.Popen) -> None:
        wait_until_bound(port, listener)
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sender:
            if group:  # the loopback interface, where the listener joined the group
                sender.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_IF, socket.inet_aton("127.0.0.1"))
            for datagram in DATAGRAMS:
                sender.sendto(datagram, (group or "127.0.0.1", port))

    records, err = listen_to(env, ["--udp", str(port), *where, "--count", str(len(EXPECTED))], send)
    assert [(r["line"], r["sentence"], (r.get("tag_block") or {}).get("source")) for r in records] == EXPECTED
    assert records[0]["tag_block"] == {"source": "GP0001", "line_count": 1}
    assert err.startswith(f"{len(EXPECTED)} lines: {len(EXPECTED)} sentences, 0 unknown, 0 errors\n"), err


def test_listen_to_an_iec_61162_450_multicast_group(installed: Venv) -> None:
    udp_case(installed, "239.192.0.1")


def test_listen_to_a_plain_udp_port(installed: Venv) -> None:
    udp_case(installed, None)


def test_listen_to_a_tcp_feed_as_show_reads_its_log(installed: Venv, tmp_path: Path) -> None:
    log = corpus_log("gpsd/quectel-L70.nmea")
    server = socket.create_server(("127.0.0.1", 0))
    host, port = server.getsockname()[:2]

    def serve() -> None:
        connection, _ = server.accept()
        with connection:
            data = log.read_bytes()
            for start in range(0, len(data), 500):  # in pieces that cut lines
                connection.sendall(data[start:start + 500])
        server.close()

    thread = threading.Thread(target=serve, daemon=True)
    records, err = listen_to(installed, ["--tcp", f"{host}:{port}"], lambda _: thread.start())
    shown_log = run(installed.bin / "nmea", "show", "--json", log)
    assert [json.dumps(r) for r in records] == shown_log.stdout.decode().splitlines()
    assert err == shown_log.stderr.decode()
    assert len(records) > 100


def test_listen_to_the_network_mistakes(installed: Venv) -> None:
    nmea = installed.bin / "nmea"
    cases = [
        (["--udp", "10110", "--port", "/dev/ttyUSB0"], 2, "nmea: give one source, not --port and --udp\n"),
        (["--group", "239.192.0.1"], 2, "nmea: --group joins a multicast group of a UDP port: give --udp PORT too\n"),
        (["--udp", "70000"], 2, "nmea: --udp 70000: give a port number from 1 to 65535\n"),
        (["--tcp", "localhost"], 2, "nmea: --tcp 'localhost': give HOST:PORT, e.g. 192.168.1.10:10110\n"),
        ([], 2, "nmea: which port? give --port DEVICE (e.g. --port /dev/ttyUSB0), --tcp HOST:PORT or --udp PORT\n"),
    ]
    for args, status, message in cases:
        result = run(nmea, "listen", *args, check=False, timeout=WAIT)
        assert (result.returncode, result.stderr.decode()) == (status, message), args
    closed = socket.create_server(("127.0.0.1", 0))
    port = closed.getsockname()[1]
    closed.close()
    result = run(nmea, "listen", "--tcp", f"127.0.0.1:{port}", check=False, timeout=WAIT)
    assert result.returncode == 3
    assert result.stderr.decode() == f"nmea: cannot connect to 127.0.0.1:{port}: Connection refused\n"


def test_send_to_a_receiver_behind_tcp(installed: Venv) -> None:
    """`nmea send --tcp`: the command written to the socket, the reply the spec pairs with it read
    back (a serial-to-TCP bridge in front of an MTK receiver)."""
    server = socket.create_server(("127.0.0.1", 0))
    host, port = server.getsockname()[:2]
    received: list[bytes] = []

    def bridge() -> None:
        connection, _ = server.accept()
        with connection:
            received.append(connection.recv(100))
            connection.sendall(b"$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n"
                               b"$PMTK001,220,3*30\r\n")
        server.close()

    thread = threading.Thread(target=bridge, daemon=True)
    thread.start()
    result = run(installed.bin / "nmea", "send", "--tcp", f"{host}:{port}", "mtk_pmtk", "pmtk220", "1000",
                 check=False, timeout=WAIT)
    thread.join(WAIT)
    assert received == [b"$PMTK220,1000*1F\r\n"]
    assert (result.returncode, result.stdout.decode()) == (
        0, "> $PMTK220,1000*1F\n< $PMTK001,220,3*30\nok: PMTK001  command=220 flag=success\n"), result.stderr
