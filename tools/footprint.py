"""The C pair's footprint on a microcontroller: flash, RAM and worst-case stack (issue 32).

    python3 tools/footprint.py                 # x86-64 and, when arm-none-eabi-gcc is installed, Cortex-M4
    python3 tools/footprint.py --subset-only   # the five-sentence firmware only (no full-spec row)

For each target and build (a subset generated with `generate --only`, and the whole spec of
generated/c) it compiles nmea.c at -Os with -DNMEA_NO_JSON, with and without -DNMEA_NO_FAST_PATH:

- flash, object: text + data of nmea.o, every function of the pair;
- flash, linked: what a firmware that feeds the receiver's bytes one by one to the stream framer
  (nmea_framer_feed) and nmea_parse adds to the same program without the library, both linked with
  -ffunction-sections -fdata-sections -Wl,--gc-sections (newlib-nano on Cortex-M4);
- RAM: sizeof(nmea_framer) and sizeof(nmea_sentence) as the target's compiler lays them out;
- the options a firmware sets for flash and RAM (-DNMEA_NO_PROBLEMS, -DNMEA_TERSE_ERRORS,
  -DNMEA_NO_TAG_BLOCKS, -DNMEA_DIGITS_32, -DNMEA_NO_BINARY_FRAMES), each measured, all together and
  as the small profile -DNMEA_SMALL (all of them at once, and nmea_parse reading with the small
  reader, runtime/c/small.c, when the generator wrote its tables for the subset);
- with --symbols N: the N largest symbols the small profile's firmware links (nm --size-sort), on
  each target;
- stack: the worst case of each entry point over the call graph that gcc writes with
  -fcallgraph-info=su (each function's frame from -fstack-usage), without the C library's
  leaf functions (memcpy, the 64-bit division helpers ...), which are named instead. A recursive
  call or a frame of unbounded size makes the figure unbounded, and it is reported as such.
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SUBSET = "GGA,RMC,GSV,GSA,VTG"
SMALL = ["-DNMEA_NO_JSON", "-DNMEA_NO_FAST_PATH"]
FAST = ["-DNMEA_NO_JSON"]
# What a firmware short of flash sets besides SMALL, each measured on its own and all together.
OPTIONS = [["-DNMEA_NO_PROBLEMS"], ["-DNMEA_TERSE_ERRORS"], ["-DNMEA_NO_TAG_BLOCKS"], ["-DNMEA_DIGITS_32"],
           ["-DNMEA_NO_BINARY_FRAMES"],
           ["-DNMEA_NO_PROBLEMS", "-DNMEA_TERSE_ERRORS", "-DNMEA_NO_TAG_BLOCKS", "-DNMEA_DIGITS_32",
            "-DNMEA_NO_BINARY_FRAMES"],
           ["-DNMEA_SMALL"]]
SECTIONS = ["-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections"]
CROSS_PACKAGES = "apt-get install gcc-arm-none-eabi libnewlib-arm-none-eabi"


@dataclass(frozen=True)
class Target:
    name: str
    cc: list[str]
    cflags: list[str]
    ldflags: list[str]
    tools_prefix: str  # of nm and size


TARGETS = [
    Target("x86-64", ["cc"], [], ["-no-pie"], ""),  # no PIE: its relocations are not code
    Target("Cortex-M4", ["arm-none-eabi-gcc"], ["-mcpu=cortex-m4", "-mthumb"],
           ["--specs=nano.specs", "--specs=nosys.specs"], "arm-none-eabi-"),
]

# The firmware of the issue: the receiver's bytes, one at a time as a UART gives them, through the
# framer and the parser; the baseline reads the same bytes without the library.
FIRMWARE = """#include "nmea.h"
volatile char uart_data;
volatile unsigned sink;
static nmea_framer framer;
static nmea_sentence sentence;
int main(void)
{
    nmea_error err;
    nmea_framed line;
    for (;;) {
        bool more = nmea_framer_feed(&framer, uart_data, &line);
        while (more) {
            if (line.ptr && nmea_parse(&sentence, line.ptr, line.len, &err))
                sink += (unsigned)sentence.id;
#ifndef NMEA_NO_BINARY_FRAMES
            more = nmea_framer_next(&framer, &line); /* what a rejected binary frame held */
#else
            more = false;
#endif
        }
    }
}
"""
BASELINE = """volatile char uart_data;
volatile unsigned sink;
int main(void)
{
    for (;;)
        sink += (unsigned)uart_data;
}
"""
PROBE = """#include "nmea.h"
nmea_framer framer_probe;
nmea_sentence sentence_probe;
"""

# The public functions a firmware calls; the per-layout ones (nmea_parse_gga ...) are summed up
# by their prefix.
ENTRY_POINTS = ["nmea_framer_feed", "nmea_framer_next", "nmea_framer_push", "nmea_framer_end", "nmea_parse", "nmea_parse_ex", "nmea_serialize",
                "nmea_build", "nmea_error_message"]
PER_LAYOUT = ["nmea_parse_", "nmea_serialize_", "nmea_build_"]


def run(*command: str | Path, cwd: Path | None = None) -> str:
    return subprocess.run([str(c) for c in command], check=True, capture_output=True, text=True, cwd=cwd).stdout


def generate(only: str | None, out: Path) -> Path:
    """The directory of the C pair: generated/c for the whole spec, else a subset written to `out`."""
    if only is None:
        return ROOT / "generated" / "c"
    run(sys.executable, "-m", "generator", "generate", "--only", only, "--out", out, cwd=ROOT)
    return out / "c"


def text_and_data(target: Target, binary: Path) -> int:
    """text + data of an object or a program, as `size` counts them."""
    text, data = run(f"{target.tools_prefix}size", binary).splitlines()[-1].split()[:2]
    return int(text) + int(data)


def compile_object(target: Target, source: Path, flags: list[str], work: Path, extra: tuple[str, ...] = ()) -> Path:
    """nmea.o at -Os (`extra`: more flags)."""
    obj = work / "nmea.o"
    run(*target.cc, "-std=c99", "-Os", *target.cflags, *flags, *extra, "-c", "-o", obj,
        source / "nmea.c", cwd=work)
    return obj


def firmware_size(target: Target, source: Path, flags: list[str], work: Path) -> int:
    """What reading NMEA (framer and parser) adds to the same program without the library."""
    (work / "firmware.c").write_text(FIRMWARE, encoding="utf-8")
    (work / "baseline.c").write_text(BASELINE, encoding="utf-8")
    sizes = []
    for sources, more in (([work / "firmware.c", source / "nmea.c"], [*flags, "-I", str(source)]),
                          ([work / "baseline.c"], [])):
        exe = work / "program.elf"
        run(*target.cc, "-std=c99", "-Os", *target.cflags, *more, *SECTIONS, *target.ldflags, "-o", exe, *sources)
        sizes.append(text_and_data(target, exe))
    return sizes[0] - sizes[1]


def ram_sizes(target: Target, source: Path, work: Path, flags: list[str]) -> dict[str, int]:
    """sizeof(nmea_framer) and sizeof(nmea_sentence) on the target, from a probe object's symbols."""
    (work / "probe.c").write_text(PROBE, encoding="utf-8")
    obj = work / "probe.o"
    run(*target.cc, "-std=c99", *target.cflags, *flags, "-fno-common", "-I", source, "-c", "-o", obj, work / "probe.c")
    sizes = {}
    for line in run(f"{target.tools_prefix}nm", "-S", obj).splitlines():
        _, size, _, name = line.split()
        sizes[name.removesuffix("_probe")] = int(size, 16)
    return sizes


NODE = re.compile(r'^node: \{ title: "([^"]+)" label: "[^"]*?(?:\\n(\d+) bytes \(([^)]+)\))?"')
EDGE = re.compile(r'^edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')


@dataclass
class Stack:
    """The worst-case stack of a function: bytes, the path that takes them, and what it leaves out."""
    bytes: int | None  # None: unbounded (recursion, a frame of dynamic size, an indirect call)
    path: list[str]
    library: set[str]
    why: str = ""


class CallGraph:
    """gcc's -fcallgraph-info=su graph of one translation unit: frames and calls."""

    def __init__(self, ci: str) -> None:
        self.frame: dict[str, int | None] = {}
        self.calls: dict[str, list[str]] = {}
        for line in ci.splitlines():
            if node := NODE.match(line):
                name, size, kind = node.groups()
                if size is not None:  # a function of the unit (the others are the library's)
                    self.frame[name] = int(size) if kind in ("static", "dynamic,bounded") else None
            elif edge := EDGE.match(line):
                self.calls.setdefault(edge[1], []).append(edge[2])
        self.memo: dict[str, Stack] = {}

    def worst(self, name: str, active: tuple[str, ...] = ()) -> Stack:
        if name in active:
            return Stack(None, [name], set(), "recursion")
        if name not in self.frame:
            return Stack(0, [], {name.split(":")[-1]}) if name != "__indirect_call" else \
                Stack(None, [name], set(), "indirect call")
        if name in self.memo:
            return self.memo[name]
        frame = self.frame[name]
        if frame is None:
            return Stack(None, [name], set(), "frame of dynamic size")
        best = Stack(0, [], set())
        library: set[str] = set()
        for callee in dict.fromkeys(self.calls.get(name, [])):
            below = self.worst(callee, (*active, name))
            library |= below.library
            if below.bytes is None:
                return Stack(None, [name, *below.path], library, below.why)
            if below.bytes > best.bytes or not best.path:
                best = below
        stack = Stack(frame + best.bytes, [name, *best.path], library)
        self.memo[name] = stack
        return stack


def stacks(target: Target, source: Path, flags: list[str], work: Path) -> dict[str, Stack]:
    """The worst-case stack of each entry point (the per-layout ones: the worst of their kind)."""
    obj = compile_object(target, source, flags, work, ("-fcallgraph-info=su", *SECTIONS[:2]))
    graph = CallGraph(obj.with_suffix(".ci").read_text(encoding="utf-8"))
    public = [line.split()[2] for line in run(f"{target.tools_prefix}nm", "-g", "--defined-only", obj).splitlines()
              if line.split()[1] == "T"]
    found: dict[str, Stack] = {}
    for name in ENTRY_POINTS:
        if name in public:
            found[name] = graph.worst(name)
    for prefix in PER_LAYOUT:
        worst = [graph.worst(name) for name in public if name.startswith(prefix) and name not in ENTRY_POINTS]
        if worst:
            found[f"{prefix}<layout> ({len(worst)})"] = max(
                worst, key=lambda s: float("inf") if s.bytes is None else s.bytes)
    return found


def shown(stack: Stack) -> str:
    if stack.bytes is None:
        return f"unbounded ({stack.why})"
    return f"{stack.bytes:,}"


def path_of(stack: Stack) -> str:
    return " -> ".join(name.split(":")[-1] for name in stack.path)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", default=SUBSET, help=f"the subset (default {SUBSET})")
    parser.add_argument("--subset-only", action="store_true", help="leave out the full spec's row")
    parser.add_argument("--symbols", type=int, default=0, metavar="N",
                        help="the N largest symbols of the small profile's firmware (-DNMEA_SMALL)")
    args = parser.parse_args()
    targets = []
    for target in TARGETS:
        if shutil.which(target.cc[0]):
            targets.append(target)
        else:
            print(f"{target.name}: skipped, {target.cc[0]} is not installed ({CROSS_PACKAGES})")
    builds: list[tuple[str, str | None]] = [(f"--only {args.only}", args.only)]
    if not args.subset_only:
        builds.append(("full spec", None))
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        sources = {name: generate(only, work / "out") for name, only in builds}
        print("\n| target, build | object, no fast path | object, fast path | linked, no fast path "
              "| linked, fast path | nmea_framer | nmea_sentence | stack of nmea_parse |")
        print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        details = []
        for target in targets:
            for name, source in sources.items():
                small = text_and_data(target, compile_object(target, source, SMALL, work))
                fast = text_and_data(target, compile_object(target, source, FAST, work))
                linked_small = firmware_size(target, source, SMALL, work)
                linked_fast = firmware_size(target, source, FAST, work)
                ram = ram_sizes(target, source, work, SMALL)
                entry = stacks(target, source, SMALL, work)
                print(f"| {target.name}, {name} | {small:,} | {fast:,} | {linked_small:,} | {linked_fast:,} "
                      f"| {ram['framer']:,} | {ram['sentence']:,} | {shown(entry['nmea_parse'])} |")
                if source == sources[builds[0][0]]:
                    details.append((target, source))
        print(f"\nThe options a firmware sets, {builds[0][0]}, linked (no fast path, -DNMEA_NO_JSON), "
              "nmea_sentence and the stack of nmea_parse:")
        print("\n| options | " + " | ".join(f"{t.name} linked | {t.name} nmea_sentence | {t.name} stack"
                                           for t, _ in details) + " |")
        print("| --- |" + " ---: | ---: | ---: |" * len(details))
        for option in [[], *OPTIONS]:
            cells = []
            for target, source in details:
                cells.append(f"{firmware_size(target, source, [*SMALL, *option], work):,}")
                cells.append(f"{ram_sizes(target, source, work, [*SMALL, *option])['sentence']:,}")
                cells.append(shown(stacks(target, source, [*SMALL, *option], work)["nmea_parse"]))
            label = " ".join(option) or "(none)"
            if option == ["-DNMEA_SMALL"] and "#define NMEA_SMALL_READER" in (details[0][1] / "nmea.c").read_text(
                    encoding="utf-8"):
                label += " (its own reader, runtime/c/small.c)"
            print(f"| {label} | {' | '.join(cells)} |")
        for target, source in details:
            print(f"\nWorst-case stack on {target.name}, {builds[0][0]} (bytes; without the C library's leaf functions):")
            print("\n| entry point | no fast path | fast path | deepest path (no fast path) |")
            print("| --- | ---: | ---: | --- |")
            small, fast = stacks(target, source, SMALL, work), stacks(target, source, FAST, work)
            library: set[str] = set()
            for name, stack in small.items():
                library |= stack.library | fast[name].library
                print(f"| {name} | {shown(stack)} | {shown(fast[name])} | {path_of(stack)} |")
            print(f"\nC library functions called (not counted): {', '.join(sorted(library))}")
        for target, source in details:
            if args.symbols:
                print(f"\nThe largest symbols of the firmware on {target.name}, {builds[0][0]}, -DNMEA_SMALL "
                      "(bytes; the C library's and the program's own included):\n")
                for size, kind, name in largest_symbols(target, source, work)[:args.symbols]:
                    print(f"    {size:6,} {kind} {name}")
    return 0


def largest_symbols(target: Target, source: Path, work: Path) -> list[tuple[int, str, str]]:
    """The symbols of the small profile's firmware (-DNMEA_SMALL), largest first."""
    (work / "firmware.c").write_text(FIRMWARE, encoding="utf-8")
    exe = work / "firmware.elf"
    run(*target.cc, "-std=c99", "-Os", *target.cflags, *SMALL, "-DNMEA_SMALL", "-I", str(source), *SECTIONS,
        *target.ldflags, "-o", exe, work / "firmware.c", source / "nmea.c")
    symbols = []
    for line in run(f"{target.tools_prefix}nm", "--size-sort", "-S", exe).splitlines():
        parts = line.split()
        if len(parts) == 4:
            symbols.append((int(parts[1], 16), parts[2], parts[3]))
    return sorted(symbols, reverse=True)


if __name__ == "__main__":
    sys.exit(main())
