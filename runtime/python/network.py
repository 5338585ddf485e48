"""Sentences from the network: IEC 61162-450 datagrams, plain UDP feeds and TCP feeds.

    from nmeaspec import Receiver
    from nmeaspec.network import tcp_feed, udp_feed

    with Receiver(udp_feed(60001, group="239.192.0.1")) as network:   # a ship's MISC group
        for sentence in network:
            print(sentence)

A ship's network under IEC 61162-450 multicasts one sentence (or a few) per UDP datagram, each
datagram opened by the six bytes `UdPbC\\0` and the sentence carrying a TAG block that names its
source (`\\s:GP0001,n:52*hh\\$GPGGA,...`). Instruments and gateways that do not follow the standard
send the same lines without the header, over UDP or as a TCP stream. Both sources here give the
bytes of the sentences as a stream that `Receiver` (and `nmeaspec.stream.lines`) frames: the
header is taken off, and a datagram's last line ends with it, so that a line never runs on into
the next datagram. Datagrams of the standard's other kinds carry no sentences (binary file
transfer under `RaUdP\\0` and `RrUdP\\0`, and the like: five letters and a NUL): they are counted
in `UdpFeed.other` by their header and skipped.

Only the standard library is used.
"""

from __future__ import annotations

import socket
from collections import Counter
from typing import Any

SENTENCE_HEADER = b"UdPbC\x00"
"""What opens a datagram of sentences under IEC 61162-450."""

_DATAGRAM = 65535


class UdpFeed:
    """The datagrams of a UDP port as a byte stream of lines (a socket-like object for `Receiver`
    and `nmeaspec.stream.lines`): the IEC 61162-450 header taken off, each datagram's last line
    ended."""

    def __init__(self, sock: socket.socket) -> None:
        self.socket = sock
        self.datagrams = 0
        """Datagrams received, of every kind."""
        self.other: Counter[bytes] = Counter()
        """Datagrams skipped because they carry no sentences, by their header."""

    def recv(self, size: int = _DATAGRAM) -> bytes:
        """The sentences of the next datagram that has any (blocks until one comes)."""
        while True:
            data = self.socket.recv(_DATAGRAM)
            self.datagrams += 1
            header = data[: len(SENTENCE_HEADER)]
            if header == SENTENCE_HEADER:
                data = data[len(SENTENCE_HEADER) :]
            elif header[5:] == b"\x00" and header[:5].isalpha():
                self.other[header] += 1
                continue
            if data and not data.endswith((b"\n", b"\r")):
                data += b"\r\n"
            if data:  # an empty datagram would read as the end of the stream
                return data

    def fileno(self) -> int:
        return self.socket.fileno()

    def close(self) -> None:
        self.socket.close()

    def __enter__(self) -> UdpFeed:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def udp_feed(port: int, group: str | None = None, address: str = "") -> UdpFeed:
    """Listen on UDP `port` (of every local address, or of `address`); with `group`, join that IPv4
    multicast group (IEC 61162-450 groups are 239.192.0.1 to 239.192.0.64), on the interface of
    `address` when one is given. Raises OSError when the port cannot be bound or the group
    joined."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    try:
        # Several listeners of one multicast group on one machine, as the standard expects.
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        # A group's datagrams reach a socket bound to every address; `address` then only says
        # which interface joins the group.
        sock.bind(("" if group else address, port))
        if group:
            interface = address or "0.0.0.0"
            membership = socket.inet_aton(group) + socket.inet_aton(interface)
            sock.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, membership)
    except BaseException:
        sock.close()
        raise
    return UdpFeed(sock)


def tcp_feed(host: str, port: int, timeout: float | None = 10.0) -> socket.socket:
    """A connected TCP socket to a feed that sends lines (a gateway, gpsd's NMEA port, a
    multiplexer); `timeout`: seconds to connect. Raises OSError when it cannot connect."""
    sock = socket.create_connection((host, port), timeout=timeout)
    sock.settimeout(None)
    return sock


def host_port(text: str) -> tuple[str, int]:
    """`HOST:PORT` (an IPv6 address in brackets: `[::1]:10110`) as (host, port); raises
    ValueError saying what is wrong."""
    host, sep, port = text.rpartition(":")
    host = host[1:-1] if host.startswith("[") and host.endswith("]") else host
    if not sep or not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise ValueError(f"{text!r}: give HOST:PORT, e.g. 192.168.1.10:10110")
    return host, int(port)
