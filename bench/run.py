"""`make bench`: builds the corpus and the drivers, times every implementation, writes the results.

Each figure is the median over --rounds rounds; within a round every (implementation, operation)
runs once, as its own process, pinned to one core, in the same order (A B C A B C ...), so that
the noise of a shared machine falls on all of them alike. Each process reads the corpus into
memory once and times only its loop. Quote the ratios, not the absolute times.

    python3 bench/run.py [--rounds 5] [--lines 1000000] [--python-lines 100000] [--cpu N]
                         [--no-peers] [--no-docs] [--no-memory] [--no-instructions] [--cargo-profile P] [--out DIR]

Writes DIR/results.json, DIR/results.md and (unless --no-docs) docs/performance.md.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import venv
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import corpus  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
BENCH = ROOT / "bench"
CFLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2"]
HEAP_SYMBOLS = ("malloc", "calloc", "realloc", "free", "aligned_alloc", "posix_memalign", "strdup", "strndup")


def sh(cmd: list[str], **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, check=True, text=True, cwd=ROOT, **kwargs)


def log(message: str) -> None:
    print(message, file=sys.stderr, flush=True)


# --- building ----------------------------------------------------------------------------------

def build_c(out: Path, optimization: str, compiled: Path | None = None) -> Path:
    """The C driver, linked with nmea.o compiled as `make build` does (heap_symbols reads it), at
    another optimization level (the smoke test's -O0), or the object `compiled` (the smoke test's
    make test object)."""
    obj, binary = out / "nmea.o", out / "bench-c"
    flags = [*CFLAGS[:-1], optimization]
    if compiled:
        shutil.copyfile(compiled, obj)
    else:
        sh(["gcc", *flags, "-c", "-o", str(obj), "generated/c/nmea.c"])
    sh(["gcc", *flags, "-Igenerated/c", "-Ibench/c", "-o", str(binary), "bench/c/driver.c", "bench/c/ceiling.c",
        "generated/c/nmea_ais.c", "generated/c/nmea_ubx.c", str(obj)])
    return binary


def build_rust(out: Path, peers: bool, profile: str, standard_only: bool) -> Path:
    target = out / "rust-target"
    cmd = ["cargo", "build", "--quiet", "--profile", profile, "--locked", "--manifest-path", "bench/rust/Cargo.toml",
           "--target-dir", str(target)]
    if standard_only:
        cmd.append("--no-default-features")
    if peers:
        cmd += ["--features", "peers"]
        sh(cmd)
    else:
        # Without the peers no crate is fetched; cargo still reads the registry index once to resolve
        # Cargo.lock when it has no copy of it, so offline first, then online.
        try:
            sh(cmd, env={**os.environ, "CARGO_NET_OFFLINE": "true"}, stderr=subprocess.DEVNULL)
        except subprocess.CalledProcessError:
            sh(cmd)
    return target / profile / "nmea-bench"


def python_for(out: Path, peers: bool) -> str:
    """The interpreter of the Python runs: the bench venv with the pinned peers, or (no peers)
    this interpreter, since ours needs nothing beyond the standard library."""
    if not peers:
        return sys.executable
    env_dir = out / "venv"
    python = env_dir / "bin" / "python"
    stamp = env_dir / ".installed"
    requirements = BENCH / "requirements.txt"
    if not stamp.exists() or stamp.read_text() != requirements.read_text():
        venv.create(env_dir, with_pip=True, clear=True)
        sh([str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check", "-r", str(requirements)])
        stamp.write_text(requirements.read_text())
    return str(python)


# --- the timed runs ----------------------------------------------------------------------------

def jobs(c_bin: Path, rust_bin: Path, python: str, corpus_path: Path, ais_corpus_path: Path, ubx_corpus_path: Path,
         mixed_corpus_path: Path, python_lines: int, peers: bool) -> list[dict]:
    """Every (name, lang, op) with its command line and the corpus it runs over (nmea, ais, ubx or
    mixed)."""
    py_driver = [python, str(BENCH / "python" / "driver.py")]
    py_slice = ["--lines", str(python_lines)] if python_lines else []
    found = []

    def add(name, lang, op, cmd, corpus_name="nmea"):
        found.append({"name": name, "lang": lang, "op": op, "corpus": corpus_name, "cmd": [str(part) for part in cmd]})

    ops = ("parse", "serialize", "roundtrip")
    for op in ops:
        add("ours-c", "c", op, [c_bin, "ours", op, corpus_path, "--by-type"])
    add("ours-c", "c", "fixes", [c_bin, "ours", "fixes", corpus_path])
    add("ceiling-c", "c", "parse", [c_bin, "ceiling", "parse", corpus_path])
    for op in ops:
        add("ours-rust", "rust", op, [rust_bin, "ours", op, corpus_path, "--by-type"])
    add("ours-rust", "rust", "fixes", [rust_bin, "ours", "fixes", corpus_path])
    if peers:
        add("nmea-rs", "rust", "parse", [rust_bin, "nmea", "parse", corpus_path])
        add("nmea0183-rs", "rust", "parse", [rust_bin, "nmea0183", "parse", corpus_path])
    for op in ops:
        add("ours-python", "python", op, [*py_driver, "ours", op, corpus_path, *py_slice, "--by-type"])
    add("ours-python", "python", "fixes", [*py_driver, "ours", "fixes", corpus_path, *py_slice])
    if peers:
        for op in ops:
            add("pynmea2", "python", op, [*py_driver, "pynmea2", op, corpus_path, *py_slice])
        add("pynmea2-allfields", "python", "parse", [*py_driver, "pynmea2-allfields", "parse", corpus_path, *py_slice])
        for op in ops:
            add("pynmeagps", "python", op, [*py_driver, "pynmeagps", op, corpus_path, *py_slice])
    # AIS: parse is the line read and its message decoded, every field; serialize the message encoded
    # and the line written back.
    add("ours-c-ais", "c", "parse", [c_bin, "ours-ais", "parse", ais_corpus_path], "ais")
    add("ours-rust-ais", "rust", "parse", [rust_bin, "ours-ais", "parse", ais_corpus_path], "ais")
    if peers:
        add("nmea-parser", "rust", "parse", [rust_bin, "nmea-parser", "parse", ais_corpus_path], "ais")
    for op in ("parse", "serialize"):
        add("ours-python-ais", "python", op, [*py_driver, "ours-ais", op, ais_corpus_path, *py_slice], "ais")
        if peers:
            add("pyais", "python", op, [*py_driver, "pyais", op, ais_corpus_path, *py_slice], "ais")
    # UBX: a frame decoded, every field of its message.
    add("ours-c-ubx", "c", "parse", [c_bin, "ours-ubx", "parse", ubx_corpus_path], "ubx")
    add("ours-rust-ubx", "rust", "parse", [rust_bin, "ours-ubx", "parse", ubx_corpus_path], "ubx")
    if peers:
        add("ublox-rs", "rust", "parse", [rust_bin, "ublox", "parse", ubx_corpus_path], "ubx")
    add("ours-python-ubx", "python", "parse", [*py_driver, "ours-ubx", "parse", ubx_corpus_path, *py_slice], "ubx")
    if peers:
        add("pyubx2", "python", "parse", [*py_driver, "pyubx2", "parse", ubx_corpus_path, *py_slice], "ubx")
    # Stream splitting: the C framer over the mixed log (NMEA, UBX, RTCM 3) and over the NMEA corpus.
    add("ours-c-stream", "c", "frame", [c_bin, "framer", "frame", mixed_corpus_path], "mixed")
    add("ours-c-stream-nmea", "c", "frame", [c_bin, "framer", "frame", corpus_path], "nmea")
    return found


def run_rounds(all_jobs: list[dict], rounds: int, cpu: int) -> list[dict]:
    pin = ["taskset", "-c", str(cpu)] if shutil.which("taskset") else []
    runs: dict[tuple, list[dict]] = {}
    for round_number in range(1, rounds + 1):
        for job in all_jobs:
            key = (job["name"], job["op"])
            output = sh([*pin, *job["cmd"]], capture_output=True).stdout
            runs.setdefault(key, []).append(json.loads(output))
            log(f"round {round_number}/{rounds}: {job['name']} {job['op']}: {runs[key][-1]['ns_per_line']} ns/line")
    results = []
    for job in all_jobs:
        samples = runs[(job["name"], job["op"])]
        first = samples[0]
        row = {"name": job["name"], "lang": job["lang"], "op": job["op"], "corpus": job["corpus"],
               "ns_per_line": round(statistics.median(s["ns_per_line"] for s in samples), 2),
               "ok_lines": first["ok_lines"], "lines": first["lines"], "runs": len(samples),
               "samples": [s["ns_per_line"] for s in samples]}
        if any(s["ok_lines"] != first["ok_lines"] for s in samples):
            sys.exit(f"{job['name']} {job['op']}: ok_lines differ between runs")
        if "allocations" in first:
            row["allocations"] = max(s["allocations"] for s in samples)
        if "ns_per_byte" in first:
            row["ns_per_byte"] = round(statistics.median(s["ns_per_byte"] for s in samples), 4)
            row.update({key: first[key] for key in ("bytes", "text_lines", "frames", "rejected")})
        if "to_bytes_ns_per_line" in first:
            row["to_bytes_ns_per_line"] = round(statistics.median(s["to_bytes_ns_per_line"] for s in samples), 2)
            row["to_bytes_ok_lines"] = first["to_bytes_ok_lines"]
        if "by_type" in first:
            row["by_type"] = {kind: {"ns_per_line": round(statistics.median(s["by_type"][kind]["ns_per_line"]
                                                                           for s in samples), 2),
                                     "ok_lines": value["ok_lines"], "lines": value["lines"]}
                              for kind, value in first["by_type"].items()}
        results.append(row)
    return results


# --- the other facts of the report ------------------------------------------------------------

INSTRUCTION_LINES = 20_000
WARM_UP_LINES = 10_000  # what the C and Rust drivers run before the timed pass


def instruction_counts(c_bin: Path, rust_bin: Path, out: Path, corpus_path: Path, peers: bool) -> dict:
    """Instructions per line under callgrind, over the first 20,000 lines: deterministic where the
    clock is not. A process's count for `op` less its count for `none` (reading the corpus only),
    over the lines the driver went through (warm-up included). serialize is roundtrip less parse
    (the serialize runs of the drivers also parse, outside their timed region)."""
    if not shutil.which("valgrind"):
        return {}
    small = out / "corpus-20k.nmea"
    with corpus_path.open("rb") as source:
        small.write_bytes(b"".join(line for _, line in zip(range(INSTRUCTION_LINES), source)))
    with small.open("rb") as text:
        lines = sum(1 for _ in text)
    processed = lines + min(lines, WARM_UP_LINES)

    def count(binary: Path, impl: str, op: str) -> int:
        result = sh(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", str(binary), impl, op,
                     str(small)], capture_output=True)
        return int(re.search(r"Collected : (\d+)", result.stderr).group(1))

    wanted = [("ours-c", c_bin, "ours", ("parse", "roundtrip")), ("ceiling-c", c_bin, "ceiling", ("parse",)),
              ("ours-rust", rust_bin, "ours", ("parse", "roundtrip"))]
    if peers:
        wanted += [("nmea-rs", rust_bin, "nmea", ("parse",)), ("nmea0183-rs", rust_bin, "nmea0183", ("parse",))]
    found: dict = {"lines": lines}
    for name, binary, impl, ops in wanted:
        baseline = count(binary, impl, "none")
        found[name] = {op: round((count(binary, impl, op) - baseline) / processed, 1) for op in ops}
        if "roundtrip" in found[name]:
            found[name]["serialize"] = round(found[name]["roundtrip"] - found[name]["parse"], 1)
        log(f"instructions: {name}: {found[name]}")
    return found


def struct_sizes(out: Path) -> dict[str, int]:
    """sizeof of nmea_sentence and of every member of its union, by a C program made from nmea.h."""
    header = (ROOT / "generated" / "c" / "nmea.h").read_text()
    union = re.search(r"typedef struct \{\s*nmea_sentence_id id;[^{]*union \{(.*?)\} as;\s*\} nmea_sentence;", header, re.S)
    members = re.findall(r"^\s*(nmea_\w+) (\w+);", union.group(1), re.M)
    lines = ['#include <stdio.h>', '#include "nmea.h"', "int main(void)", "{",
             '    printf("{\\"nmea_sentence\\": %zu", sizeof(nmea_sentence));']
    lines += [f'    printf(", \\"{type_name}\\": %zu", sizeof({type_name}));' for type_name, _ in members]
    lines += ['    printf("}\\n");', "    return 0;", "}", ""]
    source = out / "sizes.c"
    source.write_text("\n".join(lines))
    sh(["gcc", *CFLAGS, "-Igenerated/c", "-o", str(out / "sizes"), str(source)])
    return json.loads(sh([str(out / "sizes")], capture_output=True).stdout)


def heap_symbols(out: Path) -> dict:
    """The undefined symbols of nmea.o (build_c compiles it as `make build` does): the heap functions
    it calls."""
    undefined = sh(["nm", "-u", str(out / "nmea.o")], capture_output=True).stdout.split()
    names = sorted({name.split("@")[0] for name in undefined if name not in ("U", "w")})
    return {"undefined": names, "heap": [name for name in names if name in HEAP_SYMBOLS]}


def peak_rss_kib(cmd: list[str], stdin: Path) -> int | None:
    """Peak resident set size of `cmd` reading `stdin`, output discarded. Through /usr/bin/time
    when there is one: a child forked by this (large) process would report this process's peak,
    which Linux carries over fork and exec."""
    with stdin.open("rb") as source:
        if Path("/usr/bin/time").exists():
            result = subprocess.run(["/usr/bin/time", "-f", "%M", *cmd], stdin=source, stdout=subprocess.DEVNULL,
                                    stderr=subprocess.PIPE, text=True, cwd=ROOT)
            return int(result.stderr.split()[-1]) if result.returncode == 0 else None
        process = subprocess.Popen(cmd, stdin=source, stdout=subprocess.DEVNULL, cwd=ROOT)
        _, status, usage = os.wait4(process.pid, 0)
    return usage.ru_maxrss if status == 0 else None


def memory(out: Path, corpus_path: Path) -> dict:
    """Peak RSS of the tools' decode over the whole corpus and over its first 10,000 lines."""
    small = out / "corpus-10k.nmea"
    with corpus_path.open("rb") as source:
        small.write_bytes(b"".join(line for _, line in zip(range(10_000), source)))
    found = {}
    for tool in ("nmea-c", "nmea-rs"):
        binary = ROOT / "build" / "bin" / tool
        if binary.exists():
            found[tool] = {"corpus_kib": peak_rss_kib([str(binary), "decode"], corpus_path),
                           "10k_lines_kib": peak_rss_kib([str(binary), "decode"], small)}
    return found


def command_version(cmd: list[str]) -> str:
    try:
        return sh(cmd, capture_output=True).stdout.splitlines()[0].strip()
    except (OSError, subprocess.CalledProcessError, IndexError):
        return "?"


def machine() -> dict:
    cpu = "?"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"cpu": cpu, "cores": os.cpu_count(), "kernel": platform.release(),
            "gcc": command_version(["gcc", "--version"]), "rustc": command_version(["rustc", "--version"]),
            "python": platform.python_version()}


# --- the report --------------------------------------------------------------------------------

def row(results: list[dict], name: str, op: str) -> dict | None:
    return next((r for r in results if r["name"] == name and r["op"] == op), None)


def ratio(results, name_a, op_a, name_b, op_b) -> float | None:
    a, b = row(results, name_a, op_a), row(results, name_b, op_b)
    if a is None or b is None or not b["ns_per_line"]:
        return None
    return a["ns_per_line"] / b["ns_per_line"]


def targets(results: list[dict], heap_free: bool, counts: dict) -> list[dict]:
    """The targets of the issue, each with its measured value and whether it is met (on the times;
    the C and Rust ratios also on the instruction counts, when there are some)."""
    checks = []

    def at_most(label, value, limit):
        checks.append({"target": label, "value": None if value is None else round(value, 3), "limit": limit,
                       "met": None if value is None else value <= limit})

    def counted(name_a, op_a, name_b, op_b):
        a, b = counts.get(name_a, {}).get(op_a), counts.get(name_b, {}).get(op_b)
        return a / b if a and b else None

    at_most("C parse / ceiling-c parse", ratio(results, "ours-c", "parse", "ceiling-c", "parse"), 2.0)
    at_most("Rust parse / nmea-rs parse", ratio(results, "ours-rust", "parse", "nmea-rs", "parse"), 0.25)
    at_most("Rust parse / C parse", ratio(results, "ours-rust", "parse", "ours-c", "parse"), 1.5)
    at_most("Python parse / pynmea2-allfields parse",
            ratio(results, "ours-python", "parse", "pynmea2-allfields", "parse"), 0.5)
    at_most("Python parse / pynmeagps parse", ratio(results, "ours-python", "parse", "pynmeagps", "parse"), 0.15)
    for name in ("ours-c", "ours-rust", "ours-python"):
        at_most(f"{name} serialize / parse", ratio(results, name, "serialize", name, "parse"), 1.0)
    at_most("Python AIS decode / pyais decode", ratio(results, "ours-python-ais", "parse", "pyais", "parse"), 0.5)
    at_most("Python AIS encode / decode", ratio(results, "ours-python-ais", "serialize", "ours-python-ais", "parse"),
            1.0)
    at_most("Rust AIS decode / nmea-parser decode", ratio(results, "ours-rust-ais", "parse", "nmea-parser", "parse"),
            0.5)
    at_most("C AIS decode / Rust AIS decode", ratio(results, "ours-c-ais", "parse", "ours-rust-ais", "parse"), 1.0)
    at_most("Python UBX decode / pyubx2 decode", ratio(results, "ours-python-ubx", "parse", "pyubx2", "parse"), 0.05)
    at_most("Rust UBX decode / ublox decode", ratio(results, "ours-rust-ubx", "parse", "ublox-rs", "parse"), 0.5)
    at_most("C UBX decode / Rust UBX decode", ratio(results, "ours-c-ubx", "parse", "ours-rust-ubx", "parse"), 1.0)
    mixed, nmea_alone = row(results, "ours-c-stream", "frame"), row(results, "ours-c-stream-nmea", "frame")
    at_most("C stream splitting, mixed log / NMEA alone (ns per byte)",
            mixed["ns_per_byte"] / nmea_alone["ns_per_byte"] if mixed and nmea_alone else None, 2.0)
    if counts:
        at_most("C parse / ceiling-c parse (instructions)", counted("ours-c", "parse", "ceiling-c", "parse"), 2.0)
        at_most("Rust parse / nmea-rs parse (instructions)", counted("ours-rust", "parse", "nmea-rs", "parse"), 0.25)
        at_most("Rust parse / C parse (instructions)", counted("ours-rust", "parse", "ours-c", "parse"), 1.5)
        for name in ("ours-c", "ours-rust"):
            at_most(f"{name} serialize / parse (instructions)", counted(name, "serialize", name, "parse"), 1.0)
    for name, written in (("ours-c", "roundtrip"), ("ours-rust", "roundtrip"), ("ours-python", "roundtrip"),
                          ("ours-python-ais", "serialize")):
        parsed, trip = row(results, name, "parse"), row(results, name, written)
        if parsed and trip:
            exact = trip["ok_lines"] == parsed["ok_lines"]
            checks.append({"target": f"{name} {written} byte-exact (every parsed line)",
                           "value": f"{trip['ok_lines']}/{parsed['ok_lines']}", "limit": "all", "met": exact})
    for name, op in (("ours-rust", "parse"), ("ours-rust", "serialize"), ("ours-rust", "roundtrip"),
                     ("ours-rust-ais", "parse")):
        rust = row(results, name, op)
        if rust:
            checks.append({"target": f"{name} {op} allocates nothing", "value": rust.get("allocations"),
                           "limit": 0, "met": rust.get("allocations") == 0})
    checks.append({"target": "C nmea.o calls no heap function", "value": None, "limit": None, "met": heap_free})
    return checks


def fmt_ratio(value: float | None) -> str:
    return "" if value is None else f"{value:.2f}x"


def markdown(report: dict) -> str:
    results = report["results"]
    corpus_info, ais_info, ubx_info = report["corpus"], report["ais_corpus"], report["ubx_corpus"]
    mixed_info = report["mixed_corpus"]
    out = [f"Corpus: {corpus_info['lines']:,} lines, {corpus_info['bytes']:,} bytes "
           f"({corpus_info['distinct_lines']:,} distinct lines of the real logs, repeated); AIS corpus (the rows "
           f"marked AIS): {ais_info['lines']:,} lines, {ais_info['bytes']:,} bytes ({ais_info['distinct_lines']:,} "
           f"distinct real single-sentence AIS lines, repeated); UBX corpus (the rows marked UBX, ns per frame): "
           f"{ubx_info['frames']:,} frames, {ubx_info['bytes']:,} bytes ({ubx_info['distinct_frames']:,} distinct "
           f"frames of gpsd's u-blox logs, repeated); mixed corpus (the rows marked MIXED, ns per item): "
           f"{mixed_info['bytes']:,} bytes (gpsd's {mixed_info['source_bytes']:,} bytes of logs interleaving NMEA, UBX "
           f"and RTCM 3, whole, {mixed_info['repeats']:,}x); the Python "
           f"implementations, ours included, run over the first {report['python_lines']:,} lines of each. "
           f"Median of {report['rounds']} rounds, pinned to CPU {report['cpu']}.", "",
           "| name | lang | op | ns/line | vs ceiling-c | vs ours (same lang, op) | ok lines | byte-identical |",
           "| --- | --- | --- | ---: | ---: | ---: | ---: | --- |"]
    ceiling = row(results, "ceiling-c", "parse")
    for r in results:
        other = r["corpus"] if r["corpus"] in ("ais", "ubx", "mixed") else ""  # not the NMEA corpus
        ours = row(results, f"ours-{r['lang']}" + (f"-{other}" if other else ""), r["op"])
        vs_ours = "" if ours is None or ours is r else fmt_ratio(r["ns_per_line"] / ours["ns_per_line"])
        vs_ceiling = fmt_ratio(r["ns_per_line"] / ceiling["ns_per_line"]) if ceiling and r["op"] != "frame" \
            and not other else ""
        if r["op"] in ("parse", "fixes", "frame"):
            identical = ""
        else:
            parsed = row(results, r["name"], "parse")
            identical = "yes" if parsed and r["ok_lines"] == parsed["ok_lines"] else "no"
        out.append(f"| {r['name']} | {r['lang']} | {r['op']}{f' ({other.upper()})' if other else ''} | {r['ns_per_line']:,.1f} | {vs_ceiling} | {vs_ours} "
                   f"| {r['ok_lines']:,}/{r['lines']:,} | {identical} |")
    out += ["", "ok lines: lines parsed (parse, fixes) or written back byte for byte (serialize, roundtrip). "
            "fixes: each line parsed and fed to the fix assembler (C `nmea_fix_feed`, Rust `FixAssembler::feed`, "
            "Python `nmeaspec.fixes.FixAssembler.feed`). "
            "byte-identical: every line the implementation parsed is written back byte for byte. The corpus "
            "keeps every checksummed line of those types, malformed ones included (too few or too many fields, "
            "values out of range): ours refuses those with a typed error, so its ok lines are below the corpus "
            "size. "
            "nmea-rs, nmea0183-rs and pynmea2-allfields have no serialize or roundtrip row: the crates have "
            "no serializer, and pynmea2's is measured under `pynmea2`. Rust serialize is `Sentence::serialize_into` "
            "(the sentence's text into a byte buffer, as `nmea_serialize` in C); `to_bytes`, which also reads the "
            "line back and appends CR LF, is listed below. "
            "AIS: parse is the `!AIVDM` line read and its message decoded, every field (ours in C: `nmea_parse`, "
            "`nmea_ais_fragment_of`, `nmea_ais_decode`; in Rust: `nmeaspec::parse`, `Sentence::fragment`, "
            "`ais_messages::Message::decode`; nmea-parser: `NmeaParser::parse_sentence`; in Python: "
            "`nmeaspec.parse(line).message`; pyais: "
            "`pyais.decode`); serialize is the decoded message encoded and "
            "the line written back (ours: `Message.encode` and `to_sentence`; pyais: `encode_msg`, which writes "
            "some lines otherwise, so fewer of its lines count). "
            "UBX: parse is a frame (its bytes) decoded into its message, every field, the checksum checked (ours: "
            "`nmeaspec.ubx_messages.decode`; in Rust: `ubx_messages::Message::from_frame`, then every entry of its "
            "groups read, `Message::for_each_entry` (a group keeps its entries' bytes, an entry read when iterated; a "
            "bitfield's parts are methods of its word, not read); pyubx2: `UBXReader.parse`). In C, `ours-c-ubx` is `nmea_ubx_decode_frame` (sync, length and checksum checked, "
            "every field of the layout read into its struct, bitfields' parts and groups' entries included). "
            "`ublox-rs` is the ublox crate (pinned in `bench/rust/Cargo.lock`, protocol 23: u-blox 8/M8, the generation "
            "of most of the corpus's frames): one `Parser` with a fixed buffer fed each frame (`consume_ubx`), every "
            "packet it yields read whole through its `Serialize` implementation (the crate's `serde` feature: the "
            "getter of every field, scaled values and repeated groups' entries included) into a serializer that only "
            "reads each value; its ok count is the packets of a message it knows read whole. Of the corpus's "
            "messages it does not know NAV-POSECEF, NAV-SVINFO, NAV-SBAS and NAV-EELL (0x01 0x3D), which "
            "it yields as unknown packets (read, not counted), and reading the one CFG-PRT frame (a USB port's, "
            "mode 0) panics in its `mode` getter (caught; not counted). "
            "Stream splitting: `ours-c-stream` is the C framer (`nmea_framer_push`, chunks of 4,096 bytes as a "
            "serial port's reads deliver them) over the mixed corpus, cutting it into NMEA lines, UBX and RTCM 3 "
            "frames (each checksum checked) and the logs' other bytes; `ours-c-stream-nmea` is the same over the "
            "NMEA corpus; ok: the lines kept and the frames whose checksum holds. Their ns per byte are listed "
            "below.", ""]
    streams = [r for r in results if "ns_per_byte" in r]
    if streams:
        out += ["## Stream splitting (C framer)", "", "| name | corpus | bytes | ns/byte | lines | frames | rejected |",
                "| --- | --- | ---: | ---: | ---: | ---: | ---: |"]
        out += [f"| {r['name']} | {r['corpus']} | {r['bytes']:,} | {r['ns_per_byte']:.3f} | {r['text_lines']:,} "
                f"| {r['frames']:,} | {r['rejected']:,} |" for r in streams]
        out += ["", "(rejected: what began like a binary frame and is none, its checksum wrong or the frame cut short: "
                "the logs hold a few.)", ""]
    out += ["## Targets", "", "| target | measured | limit | met |", "| --- | --- | --- | --- |"]
    for check in report["targets"]:
        met = {True: "yes", False: "**no**", None: "n/a"}[check["met"]]
        out.append(f"| {check['target']} | {'' if check['value'] is None else check['value']} "
                   f"| {'' if check['limit'] is None else check['limit']} | {met} |")
    out += ["", "## Per sentence type (ours, ns/line)", ""]
    ours_rows = [r for r in results if "by_type" in r]
    kinds = sorted({kind for r in ours_rows for kind in r["by_type"]})
    out += ["| name | op | " + " | ".join(f"{k} ({corpus_info['by_type'].get(k, 0):,})" for k in kinds) + " |",
            "| --- | --- | " + " | ".join("---:" for _ in kinds) + " |"]
    for r in ours_rows:
        cells = [f"{r['by_type'][k]['ns_per_line']:,.1f}" if k in r["by_type"] else "" for k in kinds]
        out.append(f"| {r['name']} | {r['op']} | " + " | ".join(cells) + " |")
    out += ["", "(count of each type in the corpus in brackets; each type is timed over its own lines, "
            "copied next to each other.)", ""]
    counts = report.get("instructions_per_line")
    if counts:
        out += ["## Instructions per line (callgrind)", "",
                f"Deterministic, unlike the times: over the first {counts['lines']:,} lines, the process's count "
                "less its count when it only reads the corpus; serialize = roundtrip - parse.", "",
                "| name | op | instructions/line | vs ceiling-c | vs ours-c |", "| --- | --- | ---: | ---: | ---: |"]
        ceiling_ir = counts.get("ceiling-c", {}).get("parse")
        for name, ops in counts.items():
            if name == "lines":
                continue
            for op, value in ops.items():
                c_value = counts.get("ours-c", {}).get(op)
                out.append(f"| {name} | {op} | {value:,.0f} | {fmt_ratio(value / ceiling_ir) if ceiling_ir else ''} "
                           f"| {fmt_ratio(value / c_value) if c_value and name != 'ours-c' else ''} |")
        out.append("")
    rust_serialize = row(results, "ours-rust", "serialize")
    out += ["## Memory and allocation", ""]
    for tool, mem in report["memory"].items():
        out.append(f"- `build/bin/{tool} decode` peak RSS: {mem['corpus_kib']:,} KiB over the corpus "
                   f"({corpus_info['lines']:,} lines), {mem['10k_lines_kib']:,} KiB over its first 10,000 lines.")
    heap = report["c_object"]["heap"]
    out.append(f"- `nm -u` of nmea.o (gcc {' '.join(CFLAGS)}): heap functions called: "
               f"{', '.join(heap) if heap else 'none'} (undefined symbols: {', '.join(report['c_object']['undefined'])}).")
    for r in results:
        if r["name"] == "ours-rust":
            out.append(f"- Rust counting `#[global_allocator]`: {r['allocations']} allocations in the timed "
                       f"{r['op']} loops over {r['lines']:,} lines.")
    if rust_serialize and "to_bytes_ns_per_line" in rust_serialize:
        out.append(f"- Rust `Sentence::to_bytes` (text, read back with its layout, CR LF): "
                   f"{rust_serialize['to_bytes_ns_per_line']:,.1f} ns/line, "
                   f"{rust_serialize['to_bytes_ok_lines']:,} lines byte-identical.")
    out += ["", "## Size of the C sentence structs (bytes)", "", "| struct | sizeof |", "| --- | ---: |"]
    out += [f"| `{name}` | {size:,} |" for name, size in report["struct_sizes"].items()]
    return "\n".join(out) + "\n"


def docs_page(report: dict, table: str) -> str:
    m = report["machine"]
    return "\n".join([
        "# Performance", "",
        "The latest figures of `make bench` (written by `bench/run.py`; do not edit by hand).", "",
        f"- Date: {report['date']}",
        f"- Machine: {m['cpu']}, {m['cores']} cores, Linux {m['kernel']} (shared with other jobs: quote the ratios, "
        "not the absolute times)",
        f"- Compilers: {m['gcc']}; {m['rustc']}; Python {m['python']}",
        f"- Peers: Rust crates `nmea`, `nmea0183`, `nmea-parser` (AIS) and `ublox` (UBX) as pinned in `bench/rust/Cargo.lock`; Python "
        "`pynmea2`, `pynmeagps`, `pyais` and `pyubx2` as pinned in `bench/requirements.txt`.", "",
        "## How it is measured", "",
        "The corpus is every line of `../shared/corpus/real` that is `$...*HH` with a valid checksum and one of "
        "GGA RMC GSV GSA VTG GLL ZDA GST, in sorted file order, repeated to the wanted length, CR LF endings. "
        "Every implementation runs as its own process, pinned to one core with `taskset`, reads the corpus into "
        "memory once and times only its loop; the rounds run the implementations interleaved (A B C A B C ...) "
        "and each figure is the median over the rounds. parse converts every field into its typed value; "
        "serialize times only writing back sentences parsed beforehand (chunks of 2,048 lines), one after another into one buffer as a program writing a stream would; roundtrip is "
        "parse plus serialize per line. ceiling-c (bench/c/ceiling.c) only checks the checksum and records "
        "where each field starts: no parser can do less. The AIS corpus (`bench/corpus.py --ais`) is every "
        "single-sentence `!AIVDM`/`!AIVDO` line with a valid checksum of gpsd's real AIS logs in tests/data/ais, "
        "repeated the same way.", "",
        "Reproduce: `make bench` (`BENCH_ROUNDS=5 BENCH_LINES=1000000`; `BENCH_PY_LINES` for the Python slice).", "",
        "## Results", "", table])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--lines", type=int, default=1_000_000)
    parser.add_argument("--python-lines", type=int, default=100_000,
                        help="the Python implementations run over this many first lines (0: all)")
    parser.add_argument("--cpu", type=int, default=(os.cpu_count() or 1) - 1)
    parser.add_argument("--no-peers", action="store_true", help="ours and the ceiling only: nothing is fetched")
    parser.add_argument("--no-docs", action="store_true", help="do not write docs/performance.md")
    parser.add_argument("--no-memory", action="store_true", help="skip the peak RSS of the tools")
    parser.add_argument("--no-instructions", action="store_true", help="skip the instruction counts (callgrind)")
    parser.add_argument("--cargo-profile", default="release",
                        help="smoke: a quick build for the smoke test, whose timings mean nothing")
    parser.add_argument("--c-optimization", default=CFLAGS[-1],
                        help="-O0: a quick build of the C driver for the smoke test, whose timings mean nothing")
    parser.add_argument("--c-object", type=Path,
                        help="link this object of generated/c/nmea.c instead of compiling it (the smoke test: "
                             "make test's test object)")
    parser.add_argument("--standard-only", action="store_true",
                        help="the Rust driver with the crate's standard sentences only, the others read as generic "
                             "sentences (the smoke test: a quicker build of the same harness)")
    parser.add_argument("--out", type=Path, default=ROOT / "build" / "bench")
    args = parser.parse_args()
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    peers = not args.no_peers

    corpus_path = out / "corpus.nmea"
    corpus_info = corpus.build(args.lines, out=corpus_path)
    ais_corpus_path = out / "corpus-ais.nmea"
    ais_info = corpus.build_ais(args.lines, out=ais_corpus_path)
    ubx_corpus_path = out / "corpus-ubx.hex"
    ubx_info = corpus.build_ubx(args.lines, out=ubx_corpus_path)
    mixed_corpus_path = out / "corpus-mixed.log"
    mixed_info = corpus.build_mixed(corpus_info["bytes"], out=mixed_corpus_path)
    python_lines = min(args.python_lines, args.lines) if args.python_lines else args.lines
    log(f"corpus: {corpus_info['lines']} lines, {corpus_info['bytes']} bytes")
    c_bin = build_c(out, args.c_optimization, args.c_object)
    rust_bin = build_rust(out, peers, args.cargo_profile, args.standard_only)
    python = python_for(out, peers)

    all_jobs = jobs(c_bin, rust_bin, python, corpus_path, ais_corpus_path, ubx_corpus_path, mixed_corpus_path,
                    python_lines if python_lines < args.lines else 0, peers)
    results = run_rounds(all_jobs, args.rounds, args.cpu)
    c_object = heap_symbols(out)
    instructions = {} if args.no_instructions else instruction_counts(c_bin, rust_bin, out, corpus_path, peers)
    report = {
        "corpus": {"lines": corpus_info["lines"], "bytes": corpus_info["bytes"],
                   "distinct_lines": corpus_info["distinct_lines"], "by_type": corpus_info["by_type"]},
        "ais_corpus": ais_info,
        "ubx_corpus": ubx_info,
        "mixed_corpus": mixed_info,
        "python_lines": python_lines,
        "rounds": args.rounds,
        "cpu": args.cpu,
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "machine": machine(),
        "results": results,
        "memory": {} if args.no_memory else memory(out, corpus_path),
        "c_object": c_object,
        "instructions_per_line": instructions,
        "struct_sizes": struct_sizes(out),
    }
    report["targets"] = targets(results, not c_object["heap"], instructions)
    table = markdown(report)
    (out / "results.json").write_text(json.dumps(report, indent=1) + "\n")
    (out / "results.md").write_text(table)
    if not args.no_docs:
        (ROOT / "docs").mkdir(exist_ok=True)
        (ROOT / "docs" / "performance.md").write_text(docs_page(report, table))
    print(table)


if __name__ == "__main__":
    main()
