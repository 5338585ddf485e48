"""Semantic checks of the bit messages told by a number (spec/binary/rtcm3/messages): the field
checks of the bit payloads (checks_payload, rules A001-A007, A012) on each, where a message lives,
its numbers (A008) and documents (B005), and its example frames (B007)."""

from __future__ import annotations

from typing import Callable

from . import checks_payload, reference_rtcm3
from .model import Spec

Report = Callable[..., None]   # checks._Reporter: (origin, rule, message, *yaml path)


def check(spec: Spec, report: Report) -> None:
    """Everything but the examples (check_examples, once the spec holds together)."""
    documents = {p.id: p.documents for p in spec.protocols}
    owners: dict[tuple[str, int], str] = {}
    for message in spec.bit_messages:
        stem = message.origin.file.rsplit("/", 1)[-1].removesuffix(".yaml")
        if stem != message.id:
            report(message.origin, "S010", f"message {message.id} must live in {message.id}.yaml", "message")
        for i, number in enumerate(message.types):
            key = (message.protocol, number)
            if key in owners:
                report(message.origin, "A008", f"message number {number} is also described by {owners[key]}",
                       "numbers", i)
            owners.setdefault(key, message.id)
        known = documents.get(message.protocol, {})
        for i, document in enumerate(message.manuals):
            if document not in known:
                report(message.origin, "B005", f"{document} is not a document of protocol {message.protocol} "
                       f"({', '.join(known)})", "documents", i)
        checks_payload.check_items(message, report)


def check_examples(spec: Spec, report: Report) -> None:
    """Every example is a whole frame of its message that the reference decoder reads, leaving
    only zero bits (the padding to a whole byte; some senders, u-blox's, pad whole bytes more),
    to the values of its `expect`."""
    for message in spec.bit_messages:
        for example in message.frame_examples:
            try:
                payload = reference_rtcm3.payload_of(example.frame)
                found, decoded = reference_rtcm3.decode_payload(spec, message.protocol, payload)
            except reference_rtcm3.FrameError as err:
                report(example.origin, "B007", f"the example does not decode: {err}", "frame")
                continue
            if found is not message:
                report(example.origin, "B007", f"the example is a message of {found.id}", "frame")
                continue
            if "1" in decoded["trailing"]:
                report(example.origin, "B007", f"the layout leaves {len(decoded['trailing'])} bits of the payload "
                       "unread, not all zero padding", "frame")
            for key, value in (example.expect or {}).items():
                if key not in decoded:
                    report(example.origin, "B007", f"expect names {key}, which the example does not have", "expect", key)
                elif decoded[key] != value or type(decoded[key]) is not type(value):
                    report(example.origin, "B007", f"{key} decodes to {decoded[key]!r}, not {value!r}", "expect", key)
