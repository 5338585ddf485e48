"""Keeps what a fuzz campaign grew: merges the corpora of the C target and of the in-process
differential (C and Rust coverage in one) into a minimal set with libFuzzer's -merge=1, and writes
it to fuzz/corpus.tar.xz (files named by their SHA-1, sorted, no timestamps: the same set gives the
same archive), which fuzz/seeds.py adds to every target's seeds.

    python fuzz/keep_corpus.py [--add] FUZZER_BINARY... -- CORPUS_DIR...

With --add, every input the archive holds stays, and only inputs that reach what none of them
reaches are added (a merge into the archive's inputs rather than a minimal set of all).
"""

from __future__ import annotations

import hashlib
import io
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ARCHIVE = ROOT / "fuzz" / "corpus.tar.xz"


def archived() -> dict[str, bytes]:
    """The inputs fuzz/corpus.tar.xz holds, by name."""
    if not ARCHIVE.exists():
        return {}
    with tarfile.open(ARCHIVE, mode="r:xz") as archive:
        members = [m for m in archive.getmembers() if m.isfile()]
        return {m.name: archive.extractfile(m).read() for m in members}  # type: ignore[union-attr]


def merged(binary: str, corpora: list[str], start: dict[str, bytes]) -> dict[str, bytes]:
    """The inputs of `corpora` that add coverage for `binary` to those of `start`, and `start`.
    The corpora are read from copies: a fuzzer still running on one replaces its inputs as it
    shrinks them, and libFuzzer's merge, given a file that has gone, retries it for ever."""
    with tempfile.TemporaryDirectory(prefix="nmeaspec-merge-") as tmp:
        kept, copies = Path(tmp) / "kept", Path(tmp) / "corpora"
        kept.mkdir()
        for name, data in start.items():
            (kept / name).write_bytes(data)
        for i, corpus in enumerate(corpora):
            copy = copies / str(i)
            copy.mkdir(parents=True)
            for path in Path(corpus).iterdir():
                try:
                    (copy / path.name).write_bytes(path.read_bytes())
                except (FileNotFoundError, IsADirectoryError):
                    continue  # removed by a running fuzzer since it was listed
        subprocess.run([binary, "-merge=1", "-max_len=1100", "-timeout=10", str(kept),
                        *(str(copies / str(i)) for i in range(len(corpora)))], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return {hashlib.sha1(p.read_bytes()).hexdigest(): p.read_bytes() for p in kept.iterdir()}


def main() -> int:
    args = sys.argv[1:]
    add = "--add" in args[:1]
    args = args[1:] if add else args
    if "--" not in args:
        raise SystemExit(__doc__)
    split = args.index("--")
    binaries, corpora = args[:split], [c for c in args[split + 1:] if Path(c).is_dir()]
    start = archived() if add else {}
    keep: dict[str, bytes] = dict(start)
    for binary in binaries:
        keep.update(merged(binary, corpora, start))
    buffer = io.BytesIO()
    with tarfile.open(fileobj=buffer, mode="w:xz") as archive:
        for name in sorted(keep):
            info = tarfile.TarInfo(name)
            info.size = len(keep[name])
            archive.addfile(info, io.BytesIO(keep[name]))
    ARCHIVE.write_bytes(buffer.getvalue())
    print(f"{ARCHIVE.relative_to(ROOT)}: {len(keep)} inputs, {sum(map(len, keep.values())):,} bytes, "
          f"{len(buffer.getvalue()):,} compressed")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
