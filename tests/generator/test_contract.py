"""The runtimes keep to the contract (runtime/contract.yaml): the same limits, error kinds and
messages in runtime/c, runtime/rust and runtime/python, in the C emitter and in json.md's table."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from generator import emit_c

RUNTIME = Path(__file__).resolve().parents[2] / "runtime"
CONTRACT = yaml.safe_load((RUNTIME / "contract.yaml").read_text(encoding="utf-8"))
LIMITS = CONTRACT["limits"]

C_HEADER = (RUNTIME / "c" / "runtime.h").read_text(encoding="utf-8")
C_SOURCE = emit_c.runtime_source("runtime.c")
RUST = "\n".join(p.read_text(encoding="utf-8") for p in sorted((RUNTIME / "rust" / "src").glob("*.rs")))
PYTHON = (RUNTIME / "python" / "runtime.py").read_text(encoding="utf-8")
SOURCES = {"c": C_SOURCE, "rust": RUST, "python": PYTHON}


def one(pattern: str, text: str) -> str:
    found = re.findall(pattern, text, re.S)
    assert len(found) == 1, f"{pattern!r}: found {found}"
    return found[0]


@pytest.mark.parametrize("limit", sorted(LIMITS))
def test_limits(limit: str) -> None:
    value = LIMITS[limit]
    name = limit.upper()
    assert int(one(rf"#define NMEA_{name} (\d+)", C_HEADER)) == value
    assert int(one(rf"pub const {name}: usize = (\d+);", RUST)) == value
    assert int(one(rf"\n{name}: Final = (\d+)", PYTHON)) == value


def test_the_c_runtime_writes_the_line_limit_by_its_name() -> None:
    assert not re.search(rf"\b{LIMITS['max_line']}\b", C_SOURCE), "runtime.c: use NMEA_MAX_LINE"


def test_the_c_emitter_takes_its_limits_from_the_contract() -> None:
    assert emit_c.MAX_PROBLEMS == LIMITS["max_problems"]


def snake(camel: str) -> str:
    return re.sub(r"(?<!^)([A-Z])", r"_\1", camel).lower()


def test_error_kinds() -> None:
    kinds = CONTRACT["kinds"]
    own = CONTRACT["api_only_kinds"]
    c_enum = one(r"typedef enum \{([^}]*)\} nmea_error_kind;", C_HEADER)
    c_kinds = [k.lower() for k in re.findall(r"NMEA_ERR_(\w+)", c_enum)]
    c_names = re.findall(r'"(\w+)"', one(r"ERROR_KINDS\[\] = \{([^}]*)\}", C_SOURCE))
    assert c_names == c_kinds, "nmea_error_kind_name's table follows the C enum"
    assert sorted(c_kinds) == sorted(kinds + own["c"])
    rust_enum = one(r"pub enum ErrorKind \{([^}]*)\}", RUST)
    rust_kinds = [snake(k) for k in re.findall(r"^\s*(\w+),", rust_enum, re.M)]
    assert sorted(rust_kinds) == sorted(kinds + own["rust"])
    error_rs = (RUNTIME / "rust" / "src" / "error.rs").read_text(encoding="utf-8")
    as_str = one(r"impl ErrorKind \{.*?pub const fn as_str\(self\) -> &'static str \{(.*?)\n    \}", error_rs)
    rust_names = dict(re.findall(r'Self::(\w+) => "(\w+)"', as_str))
    assert {snake(variant): name for variant, name in rust_names.items()} == {k: k for k in rust_kinds}
    python_kinds = set(re.findall(r'NmeaError\(\s*"(\w+)"', PYTHON))
    assert python_kinds == set(kinds + own["python"])


def test_payload_kinds() -> None:
    ais = (RUNTIME / "python" / "ais.py").read_text(encoding="utf-8")
    assert set(re.findall(r'NmeaError\(\s*"(\w+)"', ais)) == set(CONTRACT["payload_kinds"])
    ais_rs = (RUNTIME / "rust" / "src" / "ais.rs").read_text(encoding="utf-8")
    as_str = one(r"impl AisErrorKind \{.*?pub const fn as_str\(self\) -> &'static str \{(.*?)\n    \}", ais_rs)
    assert {snake(variant): name for variant, name in re.findall(r'AisErrorKind::(\w+) => "(\w+)"', as_str)} \
        == {k: k for k in CONTRACT["payload_kinds"]}
    for kind in CONTRACT["payload_kinds"]:
        assert f"| `{kind}` |" in (RUNTIME / "json.md").read_text(encoding="utf-8"), kind


def test_assembly_kinds_and_bounds() -> None:
    """The kind of a message given up and the assemblers' bounds, alike in the three runtimes and
    their tools (json.md's "AIS messages in decode and stream")."""
    bounds = CONTRACT["assembly"]
    python = (RUNTIME / "python" / "assembly.py").read_text(encoding="utf-8")
    rust = (RUNTIME / "rust" / "src" / "assembly.rs").read_text(encoding="utf-8")
    c = (RUNTIME / "c" / "ais.h").read_text(encoding="utf-8")
    assert one(r"slots: int = (\d+), lifetime: int = (\d+), capacity: int = (\d+)", python) \
        == (str(bounds["slots"]), str(bounds["lifetime"]), str(bounds["capacity"]))
    assert int(one(r"KEY_CAPACITY = (\d+)", python)) == bounds["key_capacity"]
    assert one(r"pub struct Assembler<const SLOTS: usize = (\d+), const CAPACITY: usize = (\d+)>", rust) \
        == (str(bounds["slots"]), str(bounds["capacity"]))
    assert int(one(r"pub const KEY_CAPACITY: usize = (\d+);", rust)) == bounds["key_capacity"]
    for name, key in (("SLOTS", "slots"), ("CAPACITY", "capacity"), ("KEY_CAPACITY", "key_capacity")):
        assert int(one(rf"#define NMEA_AIS_{name} (\d+)", c)) == bounds[key], name
    tools = {"c": RUNTIME / "c" / "tool.c", "rust": RUNTIME / "rust" / "crate" / "bin" / "nmea-rs.rs",
             "python": RUNTIME / "python" / "apps" / "contract_tool.py"}
    lifetimes = {"c": r"nmea_ais_assembler_init\(&ais_assembler, (\d+)\)", "rust": r"Assembler::new\((\d+)\)",
                 "python": r"MessageAssembler\(\)"}
    for language, path in tools.items():
        text = path.read_text(encoding="utf-8")
        found = re.search(lifetimes[language], text)
        assert found and (language == "python" or int(found[1]) == bounds["lifetime"]), language
        for kind in CONTRACT["assembly_kinds"]:
            assert kind in text or kind in python, (language, kind)
    json_md = (RUNTIME / "json.md").read_text(encoding="utf-8")
    for kind in CONTRACT["assembly_kinds"]:
        assert f"| `{kind}` |" in json_md, kind
    for text in ("16 messages", "100 encapsulation sentences", "558 characters", "40 bytes"):
        assert text in json_md.replace("\n", " "), text


def test_problem_kinds() -> None:
    kinds = CONTRACT["problem_kinds"]
    c_enum = one(r"typedef enum \{([^}]*)\} nmea_problem_kind;", C_HEADER)
    assert sorted(re.findall(r'"(\w+)"', c_enum)) == sorted(kinds)
    json_md = (RUNTIME / "json.md").read_text(encoding="utf-8")
    for kind in kinds:
        for language, source in SOURCES.items():
            assert f'"{kind}"' in source, f"{language} runtime: problem kind {kind}"
        assert f'"kind":"{kind}"' in json_md


def test_binary_frames() -> None:
    """The stream readers hold the same longest frame and name the same protocols and reasons, as
    json.md tells (its "Binary frames in stream")."""
    frames, kinds = CONTRACT["frames"], CONTRACT["frame_kinds"]
    python = (RUNTIME / "python" / "stream.py").read_text(encoding="utf-8")
    rust = (RUNTIME / "rust" / "src" / "stream.rs").read_text(encoding="utf-8")
    # the protocols are spec/binary's, in the tables generator/emit_framing.py writes
    c_table = (RUNTIME / "c" / "framings.h").read_text(encoding="utf-8")
    rust_table = (RUNTIME / "rust" / "src" / "framings.rs").read_text(encoding="utf-8")
    python_table = (RUNTIME / "python" / "framings.py").read_text(encoding="utf-8")
    assert frames["protocols"] == sorted(p.parent.name for p in (RUNTIME.parent / "spec" / "binary").glob("*/protocol.yaml"))
    assert int(one(r"#define NMEA_MAX_FRAME (\d+)", C_HEADER)) == frames["max_frame"]
    assert int(one(r"pub const MAX_FRAME: usize = (\d+);", rust)) == frames["max_frame"]
    assert int(one(r"\nMAX_FRAME = (\d+)", python)) == frames["max_frame"]
    c_enum = one(r"typedef enum \{([^}]*)\} nmea_frame_error;", C_HEADER)
    assert [k.lower() for k in re.findall(r"NMEA_FRAME_(\w+)", c_enum)] == ["ok"] + kinds
    assert [p.lower() for p in re.findall(r"NMEA_(\w+)", one(r"typedef enum \{([^}]*)\} nmea_protocol;", c_table))] \
        == ["line"] + frames["protocols"]
    json_md = (RUNTIME / "json.md").read_text(encoding="utf-8")
    for kind in kinds:
        assert f'"{kind}"' in rust and f'"{kind}"' in python, kind
        assert f"| `{kind}` |" in json_md, kind
    for protocol in frames["protocols"]:
        assert f'"{protocol}"' in rust_table and f"'{protocol}'" in python_table, protocol
        assert f'"protocol":"{protocol}"' in json_md, protocol
    assert f"limit is {frames['max_frame']}" in json_md


def fragments(message: str) -> list[str]:
    """The literal runs of a message pattern, quotes around a {quoted} part left out."""
    runs = re.split(r"\{\w+\}", message)
    return [run.strip(' "') for run in runs if len(run.strip(' "')) >= 3]


@pytest.mark.parametrize("row", CONTRACT["messages"], ids=lambda r: r["message"])
def test_every_runtime_writes_the_message(row: dict[str, str]) -> None:
    for language, source in SOURCES.items():
        for run in fragments(row["message"]):
            assert run in source, f"{language} runtime: no {run!r} (of the message {row['message']!r})"


def test_json_md_tells_the_contract() -> None:
    text = (RUNTIME / "json.md").read_text(encoding="utf-8")
    table = text[text.index("| kind | when | message |"):].split("\n\n")[0]
    rows = [[cell.strip() for cell in line.strip("|").split("|")]
            for line in table.splitlines()[2:] if line.startswith("| `")]
    assert len(rows) == len(CONTRACT["messages"])
    for (kind, when, message), row in zip(rows, CONTRACT["messages"]):
        assert kind == f"`{row['kind']}`"
        assert when == row["when"].format(**LIMITS)
        parts = re.split(r"(\{\w+\})", row["message"])
        pattern = "".join(str(LIMITS[p[1:-1]]) if p[1:-1] in LIMITS else ".+?" if p.startswith("{")
                          else re.escape(p) for p in parts)
        assert re.fullmatch(f"`{pattern}`", message), (message, row["message"])
