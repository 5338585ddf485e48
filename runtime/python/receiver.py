"""A live receiver: the sentences of a serial port (or of any byte stream), and commands sent to it
with the reply the spec pairs with them.

    from nmeaspec import Number, Pmtk220, Receiver

    with Receiver.open("/dev/ttyUSB0", 9600) as gps:    # pip install 'nmeaspec[serial]'
        reply = gps.send(Pmtk220(interval=Number.of(200)), timeout=2.0)
        print(reply.ok, reply.sentence)                 # True Pmtk001(command=220, flag=success)
        for sentence in gps:                            # decoded sentences, as they come
            print(sentence)

`Receiver(stream)` takes any binary stream instead of a port: a socket (a receiver behind a TCP
bridge), a file, a pseudo-terminal, a pyserial port you opened yourself. Lines are cut by
nmeaspec.stream's framer, so garbage, cut lines and sentences run together are handled the way
`nmea-py stream` handles them.

Lines that do not decode (garbage, a bad checksum, the line cut short when the port was opened)
are skipped by default and counted in `Receiver.skipped` by kind: on a live port the first line is
usually cut, and noise happens. `errors="yield"` yields each as its NmeaError instead, and
`errors="raise"` raises it. Well-formed sentences the spec does not describe are yielded as
`Generic` sentences.

`binary=True` also reads the binary frames a receiver interleaves with its sentences: a UBX frame
is yielded as its decoded message (nmeaspec.ubx_messages), an RTCM 3 frame as its
stream.BinaryFrame, and one whose checksum fails as an NmeaError of its reason. A UBX message is
sent like a command: `send(ubx_config.valset({...}))` waits for the ACK-ACK or ACK-NAK of its class
and id, a poll for its answer (the layouts its REPLIES names).

Only the standard library is imported here; pyserial is imported when a port is opened by name.
"""

from __future__ import annotations

import errno
import importlib
import os
import select
import socket
import time
from collections import Counter, deque
from collections.abc import Iterator
from dataclasses import dataclass, field
from types import TracebackType
from typing import Any

from .api import parse, reply_to
from .runtime import NmeaError
from .stream import BadFrame, BinaryFrame, Framer, Item, too_long, typed

# The rates a serial port is set to (pyserial's list, and 14400 and 28800 that some receivers
# offer); anything else is a mistake.
BAUD_RATES = (
    50, 75, 110, 134, 150, 200, 300, 600, 1200, 1800, 2400, 4800, 9600, 14400, 19200, 28800,
    38400, 57600, 115200, 230400, 460800, 500000, 576000, 921600, 1000000, 1152000, 1500000,
    2000000, 2500000, 3000000, 3500000, 4000000,
)  # fmt: skip
POLL = 0.05  # seconds: how long one read of a pyserial port waits, so that timeouts are kept
ERRORS = ("skip", "yield", "raise")


class ReceiverError(Exception):
    """Something the receiver or its port did: the base of this module's errors."""


class PortError(ReceiverError):
    """The port cannot be opened, or failed while it was read or written."""


class SerialUnavailable(ReceiverError, ImportError):
    """A port was opened by name, and pyserial is not installed."""


class ReplyTimeout(ReceiverError, TimeoutError):
    """No reply to `command` came within `timeout` seconds (or the stream ended first).
    `expected`: the reply sentences the spec pairs with it, e.g. ("PMTK001 command=220",);
    `received`: what came meanwhile."""

    def __init__(
        self, command: Any, expected: tuple[str, ...], timeout: float, received: list[Any]
    ) -> None:
        self.command = command
        self.expected = expected
        self.timeout = timeout
        self.received = received
        super().__init__(
            f"no reply to {_name(command)} within {timeout:g} s "
            f"(expected {' or '.join(expected)}); {len(received)} other sentences came meanwhile"
        )


@dataclass(slots=True)
class Reply:
    """The answer to a command: "ok" or "error" (`outcome`, as the spec judges the reply), the
    decoded reply `sentence` and its `line` as received, the `command` it answers, and the
    sentences that came `received` meanwhile (NmeaErrors too, with errors="yield")."""

    command: Any
    outcome: str
    sentence: Any
    line: bytes
    received: list[Any] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.outcome == "ok"


def check_baud(baud: int | str) -> int:
    """`baud` as an int when it is a standard rate; raises ValueError saying which are."""
    try:
        rate = int(baud)
    except ValueError:
        rate = 0
    if rate not in BAUD_RATES:
        raise ValueError(
            f"{baud!r} is not a standard baud rate: {', '.join(str(b) for b in BAUD_RATES)}"
        )
    return rate


def _name(command: Any) -> str:
    if _is_ubx(command):
        return f"UBX {command.ADDRESS}"
    sentence = getattr(command, "SENTENCE", None)
    return str(sentence) if sentence is not None else repr(command)


def _is_ubx(command: Any) -> bool:
    """A UBX message (nmeaspec.ubx.Message: an instance or class of nmeaspec.ubx_messages)."""
    return all(hasattr(command, name) for name in ("ADDRESS", "MSG_ID", "REPLIES"))


def _ubx_outcome(command: Any, reply: Any) -> str | None:
    """How a decoded UBX message answers the UBX `command`: "error" (an ACK-NAK of its class
    and id), "ok" (an ACK-ACK of them, or another layout its REPLIES names), None (no answer)."""
    from .ubx import Message, answers

    if not isinstance(reply, Message) or not answers(command, reply):
        return None
    return "error" if reply.ID == "ack_nak" else "ok"


def expected_replies(command: Any) -> tuple[str, ...]:
    """The replies the spec pairs with `command`, as text: ("PMTK001 command=220",); a UBX
    message's: ("ACK-ACK", "ACK-NAK")."""
    if _is_ubx(command):
        from .ubx_messages import BY_ID

        names = {c.ID: c.ADDRESS for layouts in BY_ID.values() for c in layouts}
        return tuple(dict.fromkeys(names.get(r, r) for r in command.REPLIES))
    out: list[str] = []
    for reply_id, _variant, tests in getattr(command, "REPLY_RULES", ()):
        text = " ".join([reply_id, *(f"{field_id}={value}" for field_id, _, value in tests)])
        if text not in out:
            out.append(text)
    return tuple(out)


def serial_module() -> Any:
    """pyserial's `serial` module, imported on first use."""
    try:
        module = importlib.import_module("serial")
    except ImportError:
        module = None
    if not hasattr(module, "serial_for_url"):  # not installed, or another package named serial
        raise SerialUnavailable(
            "reading a serial port needs pyserial: pip install 'nmeaspec[serial]'"
        )
    return module


class Receiver:
    """Decoded sentences from a byte stream, and commands written to it with their replies.

    `stream`: a binary file-like object (read/write), a socket or a pyserial port; the receiver
    closes it on close() (`close_stream=False`: leaves it open). `log`: a binary file to which
    every byte read is written as it came. `errors`: "skip" (the default: counted in `skipped`),
    "yield" or "raise" lines that do not decode. `lenient`: parse()'s lenient decoding."""

    def __init__(
        self,
        stream: Any,
        *,
        errors: str = "skip",
        lenient: bool = False,
        log: Any = None,
        close_stream: bool = True,
        binary: bool = False,
    ) -> None:
        if errors not in ERRORS:
            raise ValueError(f"errors={errors!r}: one of {', '.join(ERRORS)}")
        self.stream = stream
        self.on_error = errors
        self.lenient = lenient
        self.log = log
        self.close_stream = close_stream
        self.skipped: Counter[str] = Counter()
        """The lines skipped (errors="skip"), by error kind."""
        self.ended = False
        """The stream has ended (a file read to its end, a closed socket)."""
        self.binary = binary
        """Binary frames (UBX, RTCM 3) are read too."""
        self._framer = Framer(binary=binary)
        self._pending: deque[Item] = deque()
        self._fd = _selectable(stream)
        if _is_serial(stream) and stream.timeout != POLL:
            stream.timeout = POLL

    @classmethod
    def open(cls, port: str, baud: int = 9600, **options: Any) -> Receiver:
        """A receiver on serial port `port` (a device, or a pyserial URL such as
        socket://host:port) at `baud` bit/s; `options` are the constructor's. Raises ValueError
        for a baud rate that is not a standard one, PortError when the port cannot be opened,
        SerialUnavailable without pyserial."""
        rate = check_baud(baud)
        serial = serial_module()
        try:
            stream = serial.serial_for_url(port, baudrate=rate, timeout=POLL)
        except (OSError, ValueError) as err:  # pyserial's SerialException is an OSError
            number = getattr(err, "errno", None)
            reason = os.strerror(number) if isinstance(number, int) else str(err)
            if number == errno.EACCES and os.name == "posix":
                reason += " (is your user in the group that owns the port, e.g. dialout?)"
            raise PortError(f"cannot open {port}: {reason}") from None
        return cls(stream, **options)

    # ----------------------------------------------------------------------------------------
    # reading

    def _read_some(self, timeout: float | None) -> bytes | None:
        """The next bytes the stream has, within `timeout` seconds (None: however long it
        takes); b"" when none came in time, None when the stream has ended."""
        stream = self.stream
        try:
            if _is_serial(stream):
                deadline = None if timeout is None else time.monotonic() + timeout
                while True:
                    data = stream.read(max(1, stream.in_waiting))
                    if data or (deadline is not None and time.monotonic() >= deadline):
                        return bytes(data)
            if self._fd is not None and timeout is not None:
                ready, _, _ = select.select([self._fd], [], [], max(timeout, 0.0))
                if not ready:
                    return b""
            if hasattr(stream, "recv"):  # a socket, or nmeaspec.network's UdpFeed
                data = stream.recv(65536)
            else:
                read = getattr(stream, "read1", None) or stream.read
                data = read(65536)
        except OSError as err:  # pyserial's SerialException too, when a device goes away
            if err.errno == errno.EIO:  # the other end of a pseudo-terminal closed
                return None
            raise PortError(f"reading failed: {err}") from None
        if data is None:  # a non-blocking stream with nothing to read
            return b""
        return bytes(data) if data else None

    def _fill(self, timeout: float | None) -> bool:
        """Read once more into the pending lines; False when the stream has ended."""
        if self.ended:
            return False
        data = self._read_some(timeout)
        if data is None:
            self.ended = True
            self._pending.extend(self._framer.end())
            return False
        if data:
            if self.log is not None:
                self.log.write(data)
                self.log.flush()
            self._pending.extend(self._framer.feed(data))
        return True

    def lines(self, duration: float | None = None) -> Iterator[Item]:
        """The framed lines as they come (an int: the length of a line too long to keep; with
        binary=True, also BinaryFrame and BadFrame), for `duration` seconds (None: until the
        stream ends)."""
        deadline = None if duration is None else time.monotonic() + duration
        while True:
            while self._pending:
                yield self._pending.popleft()
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0:
                return
            if not self._fill(left) and not self._pending:
                return

    def _decode(self, item: Any) -> Any:
        """The sentence of a framed line (a binary frame: its UBX message, or the frame), its
        NmeaError (errors="yield"), or None (skipped)."""
        try:
            if isinstance(item, int):
                raise too_long(item)
            if isinstance(item, BinaryFrame):
                return item.message() if item.protocol == "ubx" and typed("ubx") else item
            if isinstance(item, BadFrame):
                raise NmeaError(item.reason, item.message, item.protocol.upper())
            return parse(item, lenient=self.lenient)
        except NmeaError as err:
            if self.on_error == "raise":
                raise
            if self.on_error == "yield":
                return err
            self.skipped[err.kind] += 1
            return None

    def read(self, timeout: float | None = None) -> Any:
        """The next sentence (or NmeaError, errors="yield") within `timeout` seconds (None: however
        long it takes); None when none came in time. Raises EOFError when the stream has ended."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            while self._pending:
                item = self._decode(self._pending.popleft())
                if item is not None:
                    return item
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0:
                return None
            if not self._fill(left) and not self._pending:
                raise EOFError("the stream has ended")

    def __iter__(self) -> Iterator[Any]:
        """Every sentence until the stream ends (a serial port: for ever)."""
        while True:
            try:
                yield self.read()
            except EOFError:
                return

    # ----------------------------------------------------------------------------------------
    # writing

    def write(self, command: Any) -> bytes:
        """Send a command (a sentence instance, a UBX message, or its text or bytes; CR LF is
        added to a text's when missing, not to a binary frame's) without waiting for anything;
        returns the bytes written."""
        if isinstance(command, str):
            command = command.encode("latin-1")
        if isinstance(command, (bytes, bytearray)):
            binary = command.startswith(b"\xb5\x62") or command.endswith(b"\n")
            data = bytes(command) if binary else bytes(command) + b"\r\n"
        elif _is_ubx(command):
            data = command.encode()
        else:
            data = command.to_bytes()
        try:
            if isinstance(self.stream, socket.socket):
                self.stream.sendall(data)
            else:
                self.stream.write(data)
                flush = getattr(self.stream, "flush", None)
                if flush is not None:
                    flush()
        except OSError as err:
            raise PortError(f"writing failed: {err}") from None
        return data

    def send(self, command: Any, timeout: float = 5.0) -> Reply:
        """Write `command` (a command sentence, or its text: it is decoded to find its replies)
        and read until a sentence answers it, as the spec pairs replies with commands (see
        nmeaspec.reply_to). Returns the Reply, whose `received` holds what came meanwhile; raises
        ReplyTimeout when nothing answers within `timeout` seconds, ValueError for a command
        that the spec gives no reply (send it with write())."""
        if isinstance(command, (bytes, bytearray)) and command.startswith(b"\xb5\x62"):
            from .ubx_messages import decode

            sentence = decode(bytes(command))
        elif isinstance(command, (str, bytes, bytearray)):
            text = command if isinstance(command, str) else bytes(command).decode("latin-1")
            sentence = parse(text.rstrip("\r\n"))
        else:
            sentence = command
        if not expected_replies(sentence):
            raise ValueError(f"nothing answers {_name(sentence)} in the spec; send it with write()")
        self.write(command)
        return self.wait_reply(sentence, timeout)

    def wait_reply(self, command: Any, timeout: float = 5.0) -> Reply:
        """send() after write(): read until a sentence answers `command` (a sentence instance or
        class; a UBX message: the message that answers it, which needs binary=True), for at most
        `timeout` seconds."""
        ubx = _is_ubx(command)
        if ubx and not self.binary:
            raise ValueError(
                f"the reply to {_name(command)} is a binary frame: open the receiver with binary=True"
            )
        deadline = time.monotonic() + timeout
        received: list[Any] = []
        while True:
            while self._pending:
                line = self._pending.popleft()
                item = self._decode(line)
                if item is None:
                    continue
                if ubx and isinstance(line, BinaryFrame):
                    outcome = _ubx_outcome(command, item)
                    if outcome is not None:
                        return Reply(command, outcome, item, line.data, received)
                elif not ubx and not isinstance(item, NmeaError) and isinstance(line, bytes):
                    outcome = reply_to(command, item)
                    if outcome is not None:
                        return Reply(command, outcome, item, line, received)
                received.append(item)
            left = deadline - time.monotonic()
            if left <= 0 or (not self._fill(left) and not self._pending):
                raise ReplyTimeout(command, expected_replies(command), timeout, received)

    # ----------------------------------------------------------------------------------------

    def close(self) -> None:
        """Close the stream (unless close_stream=False). The log is the caller's to close."""
        if self.close_stream:
            self.stream.close()

    def __enter__(self) -> Receiver:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        trace: TracebackType | None,
    ) -> None:
        self.close()


def _is_serial(stream: Any) -> bool:
    """A pyserial port (it reads with a timeout of its own)."""
    return hasattr(stream, "in_waiting") and hasattr(stream, "timeout")


def _selectable(stream: Any) -> int | None:
    """The file descriptor to wait on with select(), when the stream has one that select()
    takes (not on Windows but for sockets)."""
    if _is_serial(stream):
        return None
    try:
        fd = stream.fileno()
    except (AttributeError, OSError, ValueError):
        return None
    if not isinstance(fd, int):
        return None
    if os.name == "nt" and not hasattr(stream, "recv"):
        return None
    return fd
