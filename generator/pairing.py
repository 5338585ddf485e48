"""Replies paired with their commands, resolved for the emitters.

A command's `replies` name the sentences that answer it, optionally with the values some of their
fields must hold (`when`: an acknowledgement such as `$PMTK001,220,3` names the command it answers);
a reply's `outcome` says whether it reports success. Here both become layouts and fields, and each
language gets the same test of a field against a value, written once per language below.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .model import Field, Layout, Sentence


@dataclass(frozen=True)
class Condition:
    """Field `field` of the reply holds `value` (expect form: an int for an integer field, the
    value id for an enum, the text for text and char)."""

    field: Field
    value: Any


@dataclass(frozen=True)
class Pairing:
    """Layout `layout` of sentence `reply` answers the command when every condition holds."""

    reply: Sentence
    layout: Layout
    conditions: tuple[Condition, ...]


@dataclass(frozen=True)
class Judgement:
    """How a reply layout reports its result: `fixed` "ok" or "error", or (fixed None) success
    when `field` holds one of `ok`."""

    fixed: str | None
    field: Field | None = None
    ok: tuple[Any, ...] = ()


def pairings(command: Sentence) -> list[Pairing]:
    """Every reply layout that may answer `command`, with what its fields must hold. A rule with
    `when` applies to the layouts of the reply that have all its fields."""
    out: list[Pairing] = []
    for rule in command.reply_rules:
        if rule.sentence is None:
            continue
        for layout in rule.sentence.layouts:
            fields = {f.id: f for f in layout.fields}
            if all(field_id in fields for field_id in rule.when):
                out.append(Pairing(rule.sentence, layout,
                                   tuple(Condition(fields[k], v) for k, v in rule.when.items())))
    return out


def judgement(layout: Layout) -> Judgement:
    """The layout's `outcome`; a reply without one carries the data asked for: success."""
    outcome = layout.outcome
    if outcome is None or outcome.fixed is not None:
        return Judgement(outcome.fixed if outcome else "ok")
    field = next(f for f in layout.fields if f.id == outcome.field_id)
    return Judgement(None, field, tuple(outcome.ok))


def judged(sentence: Sentence) -> list[tuple[Layout, Judgement]]:
    """The layouts of `sentence` whose result is not plain success."""
    return [(layout, j) for layout in sentence.layouts if (j := judgement(layout)).fixed != "ok"]


def any_of(tests: list[str]) -> str:
    """Tests joined by `||` (in parentheses when there are several), in C and Rust alike."""
    return tests[0] if len(tests) == 1 else "(" + " || ".join(tests) + ")"


# ------------------------------------------------------------------------------------------------
# Test cases: the examples of each command's replies, against the command, with the answer the
# spec gives from the examples' expected values (no parser involved).


@dataclass(frozen=True)
class ReplyCase:
    command: Sentence
    layout: Layout          # the command's layout
    line: str               # an intact example of a reply
    outcome: str | None     # "ok", "error", or None: no answer to this command


MAX_CASES_PER_REPLY = 3


def reply_cases(spec: Any) -> list[ReplyCase]:
    """For every command (main layout), up to three examples of each sentence named in its
    replies, and what `reply_to` must say of them."""
    cases = []
    for command in spec.proprietary:
        found = pairings(command)
        for reply in dict.fromkeys(p.reply.id for p in found):
            sentence = spec.sentence(reply)
            examples = [e for e in sentence.examples if e.line and e.expect is not None][:MAX_CASES_PER_REPLY]
            for e in examples:
                layout = next(lay for lay in sentence.layouts if lay.id == e.variant)
                answers = any(p.reply is sentence and p.layout is layout and
                              all(e.expect.get(c.field.id) == c.value for c in p.conditions) for p in found)
                cases.append(ReplyCase(command, command.layout, e.line,
                                       _expected_outcome(layout, e.expect) if answers else None))
    return cases


def _expected_outcome(layout: Layout, expect: dict[str, Any]) -> str:
    j = judgement(layout)
    if j.fixed is not None:
        return j.fixed
    assert j.field is not None
    return "ok" if expect.get(j.field.id) in j.ok else "error"
