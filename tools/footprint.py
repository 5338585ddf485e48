"""The C pair's footprint: code size and sizeof(nmea_sentence), for a subset and the full spec.

    python3 tools/footprint.py                       # the table of docs/performance.md
    python3 tools/footprint.py --only GGA,RMC --cc arm-none-eabi-gcc --cflags "-mcpu=cortex-m4 -mthumb" \
        --ldflags "--specs=nano.specs --specs=nosys.specs"

For each build it generates the C pair (`generate --only ...` into a temporary directory, or
generated/c for the full spec), compiles nmea.c alone at -Os with -DNMEA_NO_JSON, with and
without -DNMEA_NO_FAST_PATH, and reports `size`'s text and data of the object, and
sizeof(nmea_sentence) as the target's compiler lays it out (a probe object's one array).

The object holds every function of the pair; a firmware links only what it calls. The `linked`
columns are what a program that reads a receiver (the stream framer and nmea_parse, nothing else)
adds to an empty one when both are linked with -ffunction-sections -fdata-sections
-Wl,--gc-sections: the flash a firmware pays for reading NMEA.
"""

from __future__ import annotations

import argparse
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SUBSET = "GGA,RMC,GSV,GSA,VTG"

PROBE = """#include "nmea.h"
char sentence_probe[sizeof(nmea_sentence)];
"""


def generate(only: str | None, out: Path) -> Path:
    """The directory of the C pair: generated/c for the whole spec, else a subset written to `out`."""
    if only is None:
        return ROOT / "generated" / "c"
    subprocess.run([sys.executable, "-m", "generator", "generate", "--only", only, "--out", str(out)], cwd=ROOT,
                   check=True, stdout=subprocess.DEVNULL)
    return out / "c"


def object_size(cc: list[str], cflags: list[str], source: Path, flags: list[str], work: Path) -> tuple[int, int]:
    """(text, data) of nmea.c compiled with `flags`."""
    obj = work / "nmea.o"
    subprocess.run([*cc, "-std=c99", "-Os", *cflags, *flags, "-c", "-o", str(obj), str(source / "nmea.c")], check=True)
    return sizes(obj)


def size_columns(binary: Path) -> tuple[int, int, int]:
    """`size`'s text, data and bss of an object or a program."""
    line = subprocess.run(["size", str(binary)], check=True, capture_output=True, text=True).stdout.splitlines()[-1]
    text, data, bss = line.split()[:3]
    return int(text), int(data), int(bss)


def sizes(binary: Path) -> tuple[int, int]:
    """`size`'s text and data of an object or a program."""
    text, data, _ = size_columns(binary)
    return text, data


FIRMWARE = """#include "nmea.h"
static nmea_framer framer;
static nmea_sentence sentence;
volatile size_t sink;
static void feed(const char *data, size_t len)
{
    nmea_framed line;
    nmea_error err;
    while (nmea_framer_push(&framer, &data, &len, &line))
        if (line.ptr && nmea_parse(&sentence, line.ptr, line.len, &err))
            sink += (size_t)sentence.id;
}
int main(void)
{
    feed("$GPGGA,,,,,,0,,,,,,,,*66\\r\\n", 26);
    return (int)sink;
}
"""
EMPTY = "int main(void) { return 0; }\n"
SECTIONS = ["-ffunction-sections", "-fdata-sections", "-Wl,--gc-sections", "-no-pie"]  # no PIE: its relocations are not code


def linked_size(cc: list[str], cflags: list[str], ldflags: list[str], sources: list[Path], flags: list[str],
                work: Path) -> int:
    """text + data of a program built from `sources` at -Os with unused sections dropped."""
    exe = work / "program.elf"
    subprocess.run([*cc, "-std=c99", "-Os", *cflags, *flags, *SECTIONS, *ldflags, "-o", str(exe),
                    *map(str, sources)], check=True)
    return sum(sizes(exe))


def firmware_size(cc: list[str], cflags: list[str], ldflags: list[str], source: Path, flags: list[str],
                  work: Path) -> int:
    """What reading NMEA (framer and parser) adds to an empty program."""
    (work / "firmware.c").write_text(FIRMWARE, encoding="utf-8")
    (work / "empty.c").write_text(EMPTY, encoding="utf-8")
    with_nmea = linked_size(cc, [*cflags, "-I", str(source)], ldflags, [work / "firmware.c", source / "nmea.c"],
                            flags, work)
    return with_nmea - linked_size(cc, cflags, ldflags, [work / "empty.c"], [], work)


def sentence_size(cc: list[str], cflags: list[str], source: Path, work: Path) -> int:
    """sizeof(nmea_sentence) on the target: the one zeroed array of a probe object (its bss)."""
    probe = work / "probe.c"
    probe.write_text(PROBE, encoding="utf-8")
    obj = work / "probe.o"
    subprocess.run([*cc, "-std=c99", *cflags, "-fno-common", "-I", str(source), "-c", "-o", str(obj), str(probe)],
                   check=True)
    return size_columns(obj)[2]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", default=SUBSET, help=f"the subset (default {SUBSET})")
    parser.add_argument("--cc", default="cc", help="the compiler (default cc)")
    parser.add_argument("--cflags", default="", help="more compiler flags, e.g. a target CPU")
    parser.add_argument("--ldflags", default="", help="more link flags, e.g. a C library's specs")
    args = parser.parse_args()
    cc, cflags, ldflags = shlex.split(args.cc), shlex.split(args.cflags), shlex.split(args.ldflags)
    print("| build | text, no fast path | text, fast path | data | linked, no fast path | linked, fast path "
          "| sizeof(nmea_sentence) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, only in ((f"--only {args.only}", args.only), ("full spec", None)):
        with tempfile.TemporaryDirectory() as tmp:
            work = Path(tmp)
            source = generate(only, work / "out")
            small, data = object_size(cc, cflags, source, ["-DNMEA_NO_JSON", "-DNMEA_NO_FAST_PATH"], work)
            fast, _ = object_size(cc, cflags, source, ["-DNMEA_NO_JSON"], work)
            linked_small = firmware_size(cc, cflags, ldflags, source, ["-DNMEA_NO_JSON", "-DNMEA_NO_FAST_PATH"], work)
            linked_fast = firmware_size(cc, cflags, ldflags, source, ["-DNMEA_NO_JSON"], work)
            print(f"| {name} | {small:,} | {fast:,} | {data:,} | {linked_small:,} | {linked_fast:,} "
                  f"| {sentence_size(cc, cflags, source, work):,} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
