"""Parsing any line into the class of its sentence, and the tools' JSON in both directions."""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from typing import Any

from . import runtime
from .runtime import NmeaError
from . import sentences
from .sentences import BY_ADDRESS, ENCAPSULATED, STANDARD, TEXT_COMMANDS
from .tag_block import TagBlock


@dataclass(slots=True)
class Generic:
    """A well-formed sentence the spec does not describe: its address and raw fields."""

    address: str
    fields: list[str] = field(default_factory=list)
    start: str = "$"
    checksum: str | None = "upper"

    SENTENCE = None
    VARIANT = None

    def to_sentence(self) -> str:
        return runtime.assemble(self.start, self.address, self.fields, self.checksum)

    def to_dict(self) -> dict[str, Any]:
        """The sentence as plain values, as a typed sentence's to_dict: its address and fields."""
        return {"address": self.address, "fields": list(self.fields)}


@dataclass(slots=True)
class Tagged:
    """A line with something before its sentence, kept as received: TAG blocks, then the stray
    `$` of a start sent twice (an ST Teseo's `$$GNGSA,...`: `stray` is "$", the checksum is the
    sentence's own). The sentence is None for a line of TAG blocks only.
    `Tagged((TagBlock(source="r003669945", time=1241544035),), gga).to_bytes()` puts a block
    before a sentence."""

    tag_blocks: tuple[TagBlock, ...]
    sentence: Any = None
    stray: str = ""

    def to_sentence(self) -> str:
        """The line as received, byte for byte (no line ending)."""
        head = "".join(block.to_text() for block in self.tag_blocks) + self.stray
        return head if self.sentence is None else head + self.sentence.to_sentence()

    def to_bytes(self) -> bytes:
        """The exact bytes to send, CR LF included, the sentence checked as its to_bytes does."""
        head = ("".join(block.to_text() for block in self.tag_blocks) + self.stray).encode("ascii")
        return head + (b"\r\n" if self.sentence is None else self.sentence.to_bytes())

    def to_dict(self) -> dict[str, Any]:
        """The sentence's to_dict (if any) and `tag_blocks`, each block's to_dict (and `stray`,
        when the start was sent twice)."""
        out: dict[str, Any] = {} if self.sentence is None else self.sentence.to_dict()
        out["tag_blocks"] = [block.to_dict() for block in self.tag_blocks]
        if self.stray:
            out["stray"] = self.stray
        return out


def parse(
    line: str | bytes, lenient: bool = False, require_checksum: bool = False, strict: bool = False
) -> Any:
    """Decode one line (a trailing CR LF is allowed) into the class of its layout, or a Generic
    for a well-formed sentence the spec does not describe; a line that starts with TAG blocks
    into a Tagged (the blocks and that sentence, None for a line of blocks only). Raises
    NmeaError.

    A number outside its field's range (but of the right type) is kept as sent and listed in the
    result's `problems` (`out_of_range`); `strict` refuses it as bad_field instead.
    `require_checksum` refuses a `$`/`!` sentence without a checksum (missing_checksum).
    `lenient` keeps a sentence whose fields do not all fit their types: each such field is left
    empty and listed in the result's `problems` with its text, which the sentence is written back
    with, so the round trip stays exact. Text commands are always read strictly."""
    if line[:1] == "!":
        # An encapsulation sentence (`!AIVDM,1,1,,A,15RTgt0PAso;90TKcjM8h6g208CQ,0*4A`: str, no
        # line ending) read as the general path below reads it, with fewer steps: when its first
        # 14 characters are a start read before (`!AIVDM,1,1,,A,`: its layout and the values of
        # its first fields, see _learn), only its payload and fill bits are checked, as the
        # general path checks them, and its checksum summed; else _encapsulation_fields. A line
        # they do not read (a line ending, a checksum that does not match, a field its layout
        # refuses) takes the general path, which reads it or says why not.
        text: Any = line  # a str: bytes start with no "!"
        head: Any = _HEADS.get(text[:14])
        star = len(text) - 3
        fill = None if head is None else head[1].get(text[star - 2 : star + 1])  # ",0*": read before
        payload = text[14 : star - 2]
        if (
            fill is None
            or star > 129  # a longer line (up to runtime.MAX_LINE): the general path
            or not payload
            or "," in payload
            or "*" in payload
            or not payload.isascii()
            or not payload.isprintable()
        ):
            sentence = _encapsulation_fields(text)
            if sentence is not None:
                return sentence
        else:
            # runtime.checksum in line, of the payload's up to 113 ASCII bytes (folded only as far
            # as they need), the start's and the fill bits' sums kept from _learn
            value = int.from_bytes(payload.encode(), "little") ^ fill[1]
            size = star - 16
            if size > 64:
                value ^= value >> 512
            if size > 32:
                value ^= value >> 256
            if size > 16:
                value ^= value >> 128
            value ^= value >> 64
            value ^= value >> 32
            value ^= value >> 16
            computed = (value ^ value >> 8) & 0xFF
            sent = text[star + 1 :]
            if sent == _UPPER_HEX[computed]:
                return head[0](payload, fill[0], "upper")
            if sent == _LOWER_HEX[computed]:
                return head[0](payload, fill[0], "lower")
    if isinstance(line, bytes):
        line = line.decode("latin-1")
    if line.endswith("\n"):
        line = line[:-2] if line.endswith("\r\n") else line[:-1]
    if line[:1] == "\\":
        return _tagged(line, lenient, require_checksum, strict)
    if line[:2] == "$$":
        return _stray(line, lenient, require_checksum, strict)
    # The common case first: a `$` or `!` sentence in printable ASCII whose checksum matches,
    # decoded without building a Frame; anything else takes the general path below, which reports
    # it.
    star = len(line) - 3
    start = line[:1]
    if (
        (start == "$" or start == "!")
        and line.find("*") == star
        and len(line) <= runtime.MAX_LINE
        and line.isascii()
        and line.isprintable()
    ):
        body = line[1:star]
        sent = line[star + 1 :]
        computed = runtime.checksum(body)
        checksum = (
            "upper"
            if sent == _UPPER_HEX[computed]
            else "lower"
            if sent == _LOWER_HEX[computed]
            else None
        )
        fields = body.split(",")
        address = fields[0]
        if checksum is not None and address.isalnum():
            del fields[0]
            return _read(start, address, fields, checksum, line, lenient, strict)
    if line[:1] not in ("$", "!"):
        word = runtime.first_word(line).upper()
        layouts = TEXT_COMMANDS.get(word) or sentences.text_command(word)
        if layouts is not None:
            frame = runtime.text_frame(line)
            return _first_fit(layouts, frame.address, frame.fields, None, line)
    frame = runtime.frame(line, require_checksum, strict)
    checksum = runtime.checksum_case(frame.checksum)
    return _read(frame.start, frame.address, frame.fields, checksum, line, lenient, strict)


def _encapsulation_fields(line: Any) -> Any:
    """An `!` line as parse's first step reads it when its start is not known: split once, the
    checksum (two hex digits) summed in one pass, its layout's compiled reader; the line's start
    kept for that step (_learn). None for a line it does not read."""
    fields = line.split(",")
    address = fields[0][1:]
    cls = _ENCAPSULATION_CLASSES.get(address)
    if cls is None:
        cls = _encapsulation_class(address)
        if cls is None:
            return None
    star = len(line) - 3
    last = fields[-1]
    if (
        line.find("*") != star
        or last[-3:-2] != "*"
        or star > _MAX_STAR
        or not line.isascii()
        or not line.isprintable()
    ):
        return None
    sent = last[-2:]
    computed = runtime.checksum(line[1:star])
    checksum = (
        "upper" if sent == _UPPER_HEX[computed] else "lower" if sent == _LOWER_HEX[computed] else None
    )
    if checksum is None:
        return None
    fields[-1] = last[:-3]
    del fields[0]
    try:
        sentence = cls.parse_fields(address, fields, checksum, line)
    except NmeaError:
        return None
    if line[13:14] == "," and len(fields) == 6 and len(fields[5]) == 1 and len(_HEADS) < _MAX_HEADS:
        _learn(line, sentence)
    return sentence


def _learn(line: str, sentence: Any) -> None:
    """Keeps the start of `line` (its first 14 characters, five fields: `!AIVDM,1,1,,A,`) and its
    fill bits' text for parse's first step, when its layout is an encapsulation's six fields (four, the
    payload as text of any length, the fill bits), all required: the values the general path read
    from them are those it reads from the same texts again."""
    cls = type(sentence)
    layout = cls.LAYOUT
    payload = layout.items[4] if len(layout.items) == 6 else None
    members = ["talker", *layout.field_ids, "problems", "checksum"]
    if (
        layout.kind != "standard"
        or layout.group is not None
        or layout.fixed != 6
        or layout.max_fields != 6
        or type(payload) is not runtime.TextField
        or payload.max_length is not None
        or line[:14].count(",") != 5
        or [f.name for f in dataclasses.fields(cls)] != members
        or hasattr(cls, "__post_init__")
    ):
        return
    start = line[:14]
    known = _HEADS.get(start)
    fills = {} if known is None else known[1]
    star = len(line) - 3
    fill = line[star - 2 : star + 1]  # ",0*": its value, the checksum of the start and ",0"
    fills[fill] = (getattr(sentence, layout.field_ids[5]), runtime.checksum(line[1:14] + fill[:2]))
    if known is not None:
        return
    # make(payload, fill_bits, checksum): the sentence as cls() makes it, its first members those
    # read from this start
    names = {f"v{n}": getattr(sentence, member) for n, member in enumerate(members[:5])}
    names.update(new=object.__new__, cls=cls)
    values = [*(f"v{n}" for n in range(5)), "payload", "fill", "[]", "checksum"]
    code = ["def make(payload, fill, checksum):", "    s = new(cls)"]
    code += [f"    s.{member} = {value}" for member, value in zip(members, values)]
    exec("\n".join([*code, "    return s"]), names)  # noqa: S102 (made from the class's own members)
    _HEADS[start] = (names["make"], fills)


_ENCAPSULATION_CLASSES: dict[str, Any] = {}
"""The class of each `!` address the fast path has read (AIVDM: Vdm)."""
_MAX_STAR = runtime.MAX_LINE - 3
_HEADS: dict[str, tuple[Any, ...]] = {}
"""The starts parse reads in fewer steps (`!AIVDM,1,1,,A,`): (the function that makes a sentence
of that start, the fill bits' values by text (as `,0*`), each with the checksum of the start and
that text), as _learn keeps them."""
_MAX_HEADS = 256


def _encapsulation_class(address: str) -> Any:
    """The one layout of a `!` address the general path would read it with, or None."""
    if not runtime.is_standard_address("!", address) or not address.isalnum():
        return None
    layouts = ENCAPSULATED.get(address[2:]) or sentences.encapsulated(address[2:])
    if not layouts or len(layouts) != 1:
        return None
    _ENCAPSULATION_CLASSES[address] = layouts[0]
    return layouts[0]


def _read(
    start: str,
    address: str,
    fields: list[str],
    checksum: str | None,
    line: str,
    lenient: bool,
    strict: bool,
) -> Any:
    """A framed `$` or `!` sentence read with the layouts of its address (a Generic when none
    claims it), by the fast path and the general one alike."""
    layouts = None
    if start == "$":
        layouts = BY_ADDRESS.get(address) or sentences.by_address(address)
        if layouts is not None and not runtime.claimed(layouts, fields):
            layouts = None
    if layouts is None and runtime.is_standard_address(start, address):
        formatter = address[2:]
        if start == "$":
            layouts = STANDARD.get(formatter) or sentences.standard(formatter)
            if layouts is None and runtime.is_query_address(start, address):
                layouts = STANDARD.get(runtime.QUERY) or sentences.standard(runtime.QUERY)
        else:  # an encapsulation sentence (AIS VDM): by its formatter only
            layouts = ENCAPSULATED.get(formatter) or sentences.encapsulated(formatter)
    if layouts is None:
        return Generic(address, fields, start, checksum)
    try:
        if len(layouts) == 1:
            return layouts[0].parse_fields(address, fields, checksum, line)
        return _first_fit(layouts, address, fields, checksum, line)
    except NmeaError as err:
        if err.kind != "bad_field" or (strict and not lenient):
            raise
        return _refit(layouts, address, fields, checksum, err, lenient, strict)


def _tagged(line: str, lenient: bool, require_checksum: bool, strict: bool) -> Tagged:
    """A line that starts with a TAG block: the blocks, then the sentence after them."""
    if len(line) > runtime.MAX_LINE:
        raise NmeaError("too_long", f"line is {len(line)} bytes, the limit is {runtime.MAX_LINE}")
    blocks, rest = runtime.read_tag_blocks(TagBlock, line)
    if not rest:
        return Tagged(blocks)
    sentence = parse(rest, lenient, require_checksum, strict)
    if isinstance(sentence, Tagged):  # a stray start after the blocks
        return Tagged(blocks, sentence.sentence, sentence.stray)
    return Tagged(blocks, sentence)


def _stray(line: str, lenient: bool, require_checksum: bool, strict: bool) -> Tagged:
    """A line whose `$` start is sent more than once: the sentence from the last `$`, the ones
    before it kept as its stray start."""
    if len(line) > runtime.MAX_LINE:
        raise NmeaError("too_long", f"line is {len(line)} bytes, the limit is {runtime.MAX_LINE}")
    runtime.check_printable(line)
    rest = line.lstrip("$")
    stray = line[: len(line) - len(rest) - 1]
    return Tagged((), parse("$" + rest, lenient, require_checksum, strict), stray)


_UPPER_HEX = [f"{value:02X}" for value in range(256)]
_LOWER_HEX = [f"{value:02x}" for value in range(256)]


def _refit(
    layouts: tuple[Any, ...],
    address: str,
    fields: list[str],
    checksum: str | None,
    err: NmeaError,
    lenient: bool,
    strict: bool,
) -> Any:
    """Parse again, one field at fault at a time: a number outside its range kept as sent (unless
    `strict`), any other field (`lenient`) left empty. A field neither can take (or one that is
    already empty and still does not fit), or one problem more than MAX_PROBLEMS, ends the
    attempt with its error."""
    fields = list(fields)
    problems: list[NmeaError] = []
    while (
        err.kind == "bad_field"
        and err.field is not None
        and fields[err.field - 1]
        and len(problems) < runtime.MAX_PROBLEMS
    ):
        if err.out_of_range and not strict:
            fields[err.field - 1] = runtime.RangeKept(fields[err.field - 1])
        elif lenient:
            fields[err.field - 1] = ""
            err.out_of_range = False  # its problem: a field left empty, not a value kept
        else:
            break
        problems.append(err)
        try:
            sentence = _first_fit(layouts, address, fields, checksum, "")
        except NmeaError as again:
            err = again
            continue
        sentence.problems = problems
        return sentence
    raise err


def _first_fit(
    layouts: tuple[Any, ...], address: str, fields: list[str], checksum: str | None, line: str
) -> Any:
    """The first layout that parses the fields; a variant is passed over when the main layout of
    its sentence, tried last before it, refused a field the variant reads the same way
    (SAME_AS_MAIN). When none does, the error of the layouts whose keyword the line holds in its
    place (else of all): the first bad field, else the first error."""
    errors = []
    refused: tuple[str, int] | None = None  # the main layout tried last: its sentence, bad field
    for layout in layouts:
        if (
            refused is not None
            and layout.VARIANT is not None
            and refused[0] == layout.SENTENCE
            and refused[1] in layout.SAME_AS_MAIN
        ):
            continue
        try:
            return layout.parse_fields(address, fields, checksum, line)
        except NmeaError as err:
            errors.append((layout, err))
            if layout.VARIANT is None:
                bad = err.field if err.kind == "bad_field" else None
                refused = (layout.SENTENCE, bad) if bad is not None else None
    contenders = [err for layout, err in errors if runtime.holds_selector(layout, fields)]
    contenders = contenders or [err for _, err in errors]
    raise next((err for err in contenders if err.kind == "bad_field"), contenders[0])


def replies_of(command: Any) -> tuple[Any, ...]:
    """The sentence classes (all layouts) that answer a command class or instance."""
    return tuple(layout for reply in command.REPLIES for layout in sentences.layouts(reply) or ())


def reply_to(command: Any, sentence: Any) -> str | None:
    """Whether decoded `sentence` answers `command` (a command class or instance), holding the
    field values the spec pairs them by (e.g. the command number in $PMTK001): "ok" when it reports
    success, "error" when it reports a failure, None when it is no answer to that command."""
    return runtime.reply_outcome(command, sentence)


def to_json(sentence: Any, values: bool = False) -> str:
    """The tools' JSON line for a decoded sentence (`values`: decoded values, not texts); a
    Tagged one has its TAG blocks last."""
    if isinstance(sentence, Tagged):
        members = []
        if sentence.tag_blocks or not sentence.stray:
            members.append('"tag_blocks":[' + ",".join(b.to_json() for b in sentence.tag_blocks) + "]")
        if sentence.stray:
            members.append(f'"stray":{runtime.json_str(sentence.stray)}')
        tail = ",".join(members) + "}"
        if sentence.sentence is None:
            return '{"ok":true,' + tail
        return to_json(sentence.sentence, values)[:-1] + "," + tail
    text = sentence.to_sentence()
    star = text.rfind("*") if sentence.checksum is not None else -1
    sent = text[star + 1 :] if star >= 0 else None
    short = runtime.short_checksum_json(sent)  # a checksum of one digit, as received
    if isinstance(sentence, Generic):
        fields = "[" + ",".join(runtime.json_str(f) for f in sentence.fields) + "]"
        if short:
            fields += f',"problems":[{short}]'
        head = (
            f'{{"ok":true,"start":{runtime.json_str(sentence.start)},"address":{runtime.json_str(sentence.address)},'
            '"talker":null,"sentence":null,"variant":null,"fields":'
        )
    else:
        if sentence.ADDRESS is None:
            start, address, talker = (
                text[0],
                sentence.talker + sentence.SENTENCE,
                runtime.json_str(sentence.talker),
            )
        elif sentence.checksum is None and not text.startswith("$"):
            start, address, talker = "", runtime.first_word(text), "null"
        else:
            start, address, talker = "$", sentence.ADDRESS, "null"
        head = (
            f'{{"ok":true,"start":"{start}","address":{runtime.json_str(address)},"talker":{talker},'
            f'"sentence":"{sentence.SENTENCE}","variant":{runtime.json_opt(sentence.VARIANT)},"fields":'
        )
        fields = sentence.fields_json(values)
        if sentence.problems or short:
            problems = [short] if short else []
            problems += [runtime.problem_json(p) for p in sentence.problems]
            fields += ',"problems":[' + ",".join(problems) + "]"
    return f'{head}{fields},"checksum":{runtime.json_opt(sent)}}}'


def decode_json(
    line: str | bytes,
    values: bool = False,
    lenient: bool = False,
    require_checksum: bool = False,
    strict: bool = False,
) -> str:
    """`decode`'s output for one line: the sentence as JSON, or the error as JSON."""
    try:
        return to_json(parse(line, lenient, require_checksum, strict), values)
    except NmeaError as err:
        return err.to_json()


def from_json(obj: Any) -> Any:
    """Rebuild a sentence from one object of `decode`'s lossless JSON; raises NmeaError."""
    if not isinstance(obj, dict):
        raise runtime.bad_json("not a JSON object")
    if "tag_blocks" in obj or "stray" in obj:
        blocks = runtime.tag_blocks_from_json(TagBlock, obj["tag_blocks"]) if "tag_blocks" in obj else ()
        stray = obj.get("stray", "")
        if "stray" in obj and (not isinstance(stray, str) or not stray or stray.strip("$")):
            raise runtime.bad_json('"stray" is not one or more "$"')
        rest = {k: v for k, v in obj.items() if k not in ("tag_blocks", "stray")}
        if "start" not in obj:
            if stray:
                raise runtime.bad_json('"stray" without a sentence')
            return Tagged(blocks)
        return Tagged(blocks, from_json(rest), stray)
    checksum = runtime.checksum_case(runtime.json_opt_text(obj, "checksum"))
    sentence_id = runtime.json_opt_text(obj, "sentence")
    if sentence_id is None:
        fields = runtime.json_list(obj, "fields")
        start = runtime.json_str_member(obj, "start")
        if start not in ("$", "!"):
            raise runtime.bad_json('"start" is not "$" or "!"')
        return Generic(
            runtime.json_word(obj, "address"),
            [runtime.json_text(f) for f in fields],
            start,
            checksum,
        )
    variant = runtime.json_opt_text(obj, "variant")
    layout = next(
        (lay for lay in sentences.layouts(sentence_id) or () if lay.VARIANT == variant), None
    )
    if layout is None:
        raise runtime.bad_json(f'unknown sentence "{sentence_id}"')
    fields = runtime.json_member(obj, "fields")
    if not isinstance(fields, dict):
        raise runtime.bad_json('"fields" is not an object')
    texts = layout.fields_from_json(fields)
    if "problems" in obj:
        return _with_problems(layout, obj, texts, checksum)
    if layout.checksum is None:  # a text command: its word as written, its letter case kept
        word = runtime.json_word(obj, "address")
        if word.upper() != layout.ADDRESS.upper():
            raise runtime.bad_json(f'"address" is not {layout.ADDRESS}')
        return layout.parse_fields(word, texts, None, " ".join([word, *texts]))
    return _read_again(layout, _json_address(layout, obj), texts, checksum, lenient=False)


def _json_address(layout: Any, obj: dict[str, Any]) -> str:
    """The address of a `$`/`!` sentence rebuilt from JSON: its talker and sentence id, or the
    proprietary address."""
    address: str = layout.ADDRESS or runtime.json_talker(obj, layout.SENTENCE) + layout.SENTENCE
    return address


def _read_again(
    layout: Any, address: str, texts: list[str], checksum: str | None, lenient: bool
) -> Any:
    """A sentence rebuilt from JSON read as a received line is: a number outside its range kept,
    as decoding kept it, whether or not the JSON lists it among the problems; `lenient` (its
    JSON lists problems) other fields at fault left empty."""
    try:
        return _first_fit((layout,), address, texts, checksum, "")
    except NmeaError as err:
        if err.kind != "bad_field":
            raise
        return _refit((layout,), address, texts, checksum, err, lenient=lenient, strict=False)


def _with_problems(layout: Any, obj: dict[str, Any], texts: list[str], checksum: str | None) -> Any:
    """A sentence decoded with problems: its problem fields' texts go back where they were, and it
    is parsed leniently again."""
    if runtime.json_str_member(obj, "start") == "":
        raise runtime.bad_json("a text command has no problems")
    for problem in runtime.json_list(obj, "problems"):
        index = runtime.json_member(problem, "field")
        if index is None:  # no field's: a short checksum, which "checksum" says
            continue
        if not isinstance(index, int) or isinstance(index, bool) or not 1 <= index <= len(texts):
            raise runtime.bad_json('a problem\'s "field" is not the index of a field')
        texts[index - 1] = runtime.json_text(runtime.json_member(problem, "text"))
    return _read_again(layout, _json_address(layout, obj), texts, checksum, lenient=True)


def encode_json(line: str) -> str:
    """`encode`'s output for one line of `decode` output: the sentence, or the error as JSON."""
    try:
        obj = read_json_line(line)
    except NmeaError as err:
        return err.to_json()
    return encode_object(obj)


def read_json_line(line: str) -> Any:
    """One line of JSON as Python values; NmeaError (bad_json) where it is no JSON or nests
    deeper than the tools read."""
    try:
        if runtime.json_too_deep(line):
            raise ValueError("too deep")
        return json.loads(line)
    except ValueError:
        raise runtime.bad_json("not JSON") from None


def encode_object(obj: Any) -> str:
    """encode_json of a line already read (read_json_line)."""
    try:
        sentence: str = from_json(obj).to_sentence()
    except NmeaError as err:
        return err.to_json()
    return sentence
