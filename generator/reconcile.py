"""`reconcile MANUAL.txt`: the example sentences of a manual's text against the spec.

The first step when a vendor publishes a new revision of a manual: find every example sentence in
the text, check its checksum, and tell which ones the spec already holds (as an example's raw text
or its correction), which decode with the spec as it is (and to what, or with which error), and
which have an address the spec does not know.

Extraction: a `$` or `!`, a 2-6 character address in capitals, then fields up to an optional
`*HH`. Typesetting damage is undone before comparing: `\\$` escapes, no-break and thin spaces,
typographic dashes, and spaces after commas (the intact sentence has none); a sentence cut at
the end of a line after a comma continues on the next line. Format templates (`$--GGA`,
`<field>`, `*hh`, `*CKSUM`) are not examples and are skipped.
"""

from __future__ import annotations

import argparse
import json
import re
from dataclasses import asdict, dataclass
from pathlib import Path

from . import reference
from .model import Spec

_TYPOGRAPHY = str.maketrans({"\u00a0": " ", "\u2009": " ", "\u202f": " ", "\u2007": " ", "\u2013": "-",
                             "\u2014": "-", "\u2212": "-", "\uff0c": ",", "\u2217": "*", "\u00d7": "*"})
_START = re.compile(r"(?<![A-Za-z0-9])[$!][A-Z][A-Z0-9]{1,15}(?=[,*\s<]|$)")
# A sentence that ends in a checksum on the same line: any printable ASCII up to the first `*HH`.
_WITH_SUM = re.compile(r"[$!][A-Z][A-Z0-9]{1,15}[ -#%-)+-;=?-~]{0,90}?\*\s?([0-9A-Fa-f]{2})(?![0-9A-Za-z])")
# Field characters; a space is allowed only right after a comma (typeset ", ").
_BODY = re.compile(r"(?:[A-Za-z0-9.+\-#/_:=;@&%]|,(?: (?=[A-Za-z0-9.+\-]))?)*")
_CHECKSUM = re.compile(r"\*\s?([0-9A-Fa-f]{2})(?![0-9A-Za-z])")
_LINE_END = re.compile(r"<(?:cr|CR)>(?:<(?:lf|LF)>)?")
# A text command (ComNav): capital words separated by single spaces, alone on its line.
_TEXT_COMMAND = re.compile(r"[A-Z][A-Z0-9]*(?: [A-Z0-9.]+){0,6}")


@dataclass
class Found:
    line: int                 # 1-based line of the manual's text where the sentence starts
    text: str                 # as printed (typography normalised, wrapped lines joined)
    checksum: str             # "intact", "damaged", "none" or "intact without spaces"
    sentence: str             # the text compared and decoded (no typeset spaces, no <cr><lf>)
    status: str = ""          # in_spec, new, new_bad_checksum, new_error, unknown_address, mention
    in_spec: str | None = None            # which spec example holds it
    decodes: str | None = None            # the sentence id (and variant) it decodes as
    error: str | None = None              # why it does not decode
    corrected: str | None = None          # the spec's correction of a damaged example


def _checksum(body: str) -> int:
    value = 0
    for byte in body.encode("latin-1", "replace"):
        value ^= byte
    return value


def extract(text: str, text_words: set[str] = frozenset()) -> list[tuple[int, str]]:
    """Every example sentence of the text: (line number, sentence as printed). `text_words` are
    the command words of the text commands to look for (lines such as `LOG GPGGA ONTIME 1`)."""
    lines = text.replace("\\$", "$").translate(_TYPOGRAPHY).splitlines()
    found: list[tuple[int, str]] = []
    for number, line in enumerate(lines, 1):
        bare = line.strip().strip("|`\"").strip()
        if text_words and _TEXT_COMMAND.fullmatch(bare) and bare.split(" ")[0] in text_words:
            found.append((number, bare))
            continue
        for start in _START.finditer(line):
            with_sum = _WITH_SUM.match(line, start.start())
            if with_sum and "<" not in with_sum.group(0) and "--" not in with_sum.group(0):
                found.append((number, with_sum.group(0)))
                continue
            body = _BODY.match(line, start.end())
            assert body is not None
            sentence = line[start.start():body.end()]
            rest = line[body.end():]
            if "--" in sentence or (rest.startswith("<") and not _LINE_END.match(rest)):
                continue                      # a format template ($--GGA, BDR---, <field>), not an example
            if rest.startswith("*<") or (rest.startswith("*") and not _CHECKSUM.match(rest)):
                # A bare '*' (kept: the manuals print some examples so) or a *<checksum> placeholder.
                sentence += "*" if not rest.startswith("*<") else ""
                if rest.startswith("*") and rest[1:2].isalpha():
                    continue                  # *hh, *CKSUM: a template
            elif sentence.endswith(",") and rest.strip():
                continue                      # "$PSTMSET, not $PSTMGET": a name in prose
            elif sentence.endswith(",") and number < len(lines):
                # Cut at the end of the line: the rest of the sentence opens the next line.
                following = lines[number].strip()
                more = _WITH_SUM.match("$X" + following)
                if more:
                    sentence += more.group(0)[2:]
            alone = bare in (sentence, sentence.rstrip("*")) or _LINE_END.fullmatch(bare[len(sentence):] or "-")
            if "," not in sentence and "*" not in sentence and not alone:
                continue                      # an address named in prose ("Message ID $GPGGA")
            found.append((number, sentence))
    return found


def _key(text: str) -> str:
    """A sentence as compared with the spec: no line-end marks, checksum placeholders or typeset
    spaces after commas."""
    text = _LINE_END.sub("", text)
    text = re.sub(r"\*<[^>]*>$", "", text)
    return re.sub(r",\s+", ",", text).strip()


def _examples(spec: Spec, manual: str | None) -> dict[str, list[tuple[str, str | None]]]:
    """Spec example texts (also as compared: see _key) -> [(where, correction)], the manual's own
    examples first."""
    index: dict[str, list[tuple[bool, str, str | None]]] = {}
    for s in spec.sentences:
        for e in s.examples:
            for text, how in ((e.raw, "raw"), (e.corrected, "corrected")):
                if text:
                    other = "" if e.manual == manual or manual is None else f", {e.manual} manual"
                    for key in {text, _key(text)}:
                        index.setdefault(key, []).append((e.manual != manual, f"{s.id} example ({how}{other})",
                                                          e.corrected))
    return {k: [(w, c) for _, w, c in sorted(v, key=lambda x: x[0])] for k, v in index.items()}


def _decode(spec: Spec, line: str) -> tuple[str | None, str | None, bool]:
    """(what it decodes as, or None; the error, or None; whether the address is unknown)."""
    try:
        decoded = reference.decode(spec, line)
    except reference.rt.NmeaError as err:
        return None, str(err), False
    if decoded.sentence is None:
        return "a generic sentence", None, True
    variant = f" [{decoded.layout.id}]" if decoded.layout and decoded.layout.id else ""
    return decoded.sentence.id + variant, None, False


def reconcile(spec: Spec, text: str, manual: str | None) -> list[Found]:
    examples = _examples(spec, manual)
    words = {s.address for s in spec.sentences if s.framing == "text" and s.address}
    words |= {e.raw.split(" ")[0] for s in spec.sentences if s.framing == "text" for e in s.examples}
    results = []
    for number, printed in extract(text, words):
        compact = _key(printed)
        star = compact.rfind("*")
        if star < 0 or star == len(compact) - 1 or compact[0] not in "$!":
            status = "none"
        else:
            printed_star = printed.rfind("*")
            ok = _checksum(compact[1:star]) == int(compact[star + 1:], 16)
            ok_printed = _checksum(printed[1:printed_star]) == int(compact[star + 1:], 16)
            status = "intact" if ok_printed else "intact without spaces" if ok else "damaged"
        found = Found(number, printed, status, compact)
        hits = examples.get(printed) or examples.get(compact)
        if hits:
            found.in_spec, found.corrected = hits[0]
        line = found.corrected or compact
        if status == "damaged" and not found.in_spec:
            line = compact[:star]             # decode with the checksum left out: is the rest sound?
        found.decodes, found.error, unknown = _decode(spec, line)
        if found.in_spec:
            found.status = "in_spec"
        elif unknown:
            found.status = "unknown_address"
        elif compact[:1] in "$!" and "," not in compact and "*" not in compact and found.error:
            found.status = "mention"          # an address alone: a heading or a name in a table
        elif status == "damaged":
            found.status = "new_bad_checksum"
        else:
            found.status = "new" if found.decodes else "new_error"
        results.append(found)
    return results


_CHECKSUM_TEXT = {"intact": "checksum ok", "damaged": "checksum DAMAGED", "none": "no checksum",
                  "intact without spaces": "checksum ok once the typeset spaces are removed"}
_STATUS_TEXT = {
    "in_spec": "already in the spec",
    "new": "NOT IN THE SPEC",
    "new_bad_checksum": "NOT IN THE SPEC",
    "new_error": "NOT IN THE SPEC",
    "unknown_address": "NOT IN THE SPEC, address unknown to the spec",
    "mention": "an address alone (a heading or a name in a table), not an example",
}


def report(results: list[Found], manual: str | None, only_new: bool) -> str:
    out = []
    for r in results:
        if only_new and r.status == "in_spec":
            continue
        what = f"{r.in_spec}" if r.in_spec else _STATUS_TEXT[r.status]
        how = " (corrected)" if r.corrected else " (checksum left out)" if r.status == "new_bad_checksum" else ""
        decode = f"decodes{how} as {r.decodes}" if r.decodes else f"does not decode{how}: {r.error}"
        if r.status == "mention":
            decode = f"as a sentence: {r.error}"
        out.append(f"line {r.line}: {r.text}\n    {_CHECKSUM_TEXT[r.checksum]}; {what}; {decode}")
    counts = {key: sum(1 for r in results if r.status == key) for key in _STATUS_TEXT}
    examples = len(results) - counts["mention"]
    damaged = sum(1 for r in results if r.checksum == "damaged")
    fixed = sum(1 for r in results if r.checksum == "damaged" and r.corrected)
    out.append("")
    out.append(f"{examples} example sentence(s) in the manual{f' ({manual})' if manual else ''}: "
               f"{counts['in_spec']} already in the spec, {examples - counts['in_spec']} not"
               + (f" ({counts['new']} decode with the spec, {counts['new_bad_checksum']} with a damaged checksum, "
                  f"{counts['new_error']} do not decode, {counts['unknown_address']} with an unknown address)"
                  if examples - counts["in_spec"] else "") + ".")
    out.append(f"checksums: {sum(1 for r in results if r.checksum.startswith('intact'))} intact, {damaged} damaged "
               f"({fixed} of them corrected in the spec), {sum(1 for r in results if r.checksum == 'none')} absent; "
               f"{counts['mention']} address(es) alone on a line (headings) left out of the counts.")
    return "\n".join(out) + "\n"


def guess_manual(spec: Spec, path: Path) -> str | None:
    return next((m.id for m in spec.manuals if m.file and m.file == path.name), None)


def main(spec: Spec, args: argparse.Namespace) -> int:
    path: Path = args.manual_text
    manual = args.manual or guess_manual(spec, path)
    if manual is not None and spec.manual(manual) is None:
        print(f"reconcile: unknown manual id {manual!r} (see spec/manuals.yaml)")
        return 2
    text = path.read_text(encoding="utf-8", errors="replace")
    results = reconcile(spec, text, manual)
    if args.json:
        for r in results:
            if not (args.only_new and r.status == "in_spec"):
                print(json.dumps(asdict(r), ensure_ascii=False))
    else:
        print(report(results, manual, args.only_new), end="")
    return 0
