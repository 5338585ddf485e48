"""What the generator keeps between runs, found by the digest of what it was made from: the
generator runs many times over unchanged files (make check, the tests, a firmware build). The
loader keeps the parsed documents and the digests of the valid ones, the Rust emitter what rustfmt
wrote. NMEASPEC_GEN_CACHE names the folder (`off`: no cache); by default the user's cache folder."""

from __future__ import annotations

import os
from pathlib import Path


def _cache_dir() -> Path | None:
    configured = os.environ.get("NMEASPEC_GEN_CACHE")
    if configured == "off":
        return None
    return Path(configured) if configured else Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "nmeaspec-gen"


CACHE = _cache_dir()


def read(name: str) -> bytes | None:
    """The cache's file `name`, if there is one."""
    if CACHE is None:
        return None
    try:
        return (CACHE / name).read_bytes()
    except OSError:
        return None


def write_atomically(path: Path, data: bytes) -> None:
    """Write `path` whole or not at all (runs side by side share the cache); a cache that cannot be
    written is no error."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        temporary = path.with_name(f"{path.name}.{os.getpid()}")
        temporary.write_bytes(data)
        os.replace(temporary, path)
    except OSError:
        pass


def write(name: str, data: bytes) -> None:
    """Keep `data` as the cache's file `name` (nothing when the cache is off)."""
    if CACHE is not None:
        write_atomically(CACHE / name, data)
