"""Where the generator finds its templates/, the hand-written runtimes (runtime/) and spec/ (schema
included).

They live in the project checkout next to generator/. A checkout run (`python -m generator`) or an
editable install (`pip install -e .`) finds them there; a plain install (`pip install .`) has only
the Python code, so it uses $NMEASPEC_ROOT or the nearest directory at or above the current one
that holds templates/, runtime/ and spec/schema/: run `nmeaspec-gen` from inside the checkout.
"""

from __future__ import annotations

import os
from pathlib import Path


def _is_root(path: Path) -> bool:
    return all((path / folder).is_dir() for folder in ("templates", "runtime", "spec/schema"))


def find_root() -> Path:
    env = os.environ.get("NMEASPEC_ROOT")
    if env:
        return Path(env).resolve()
    beside = Path(__file__).resolve().parent.parent
    if _is_root(beside):
        return beside
    here = Path.cwd().resolve()
    for path in (here, *here.parents):
        if _is_root(path):
            return path
    return beside


ROOT = find_root()
# The release of the project and of everything it generates, defined once in the checkout's VERSION.
VERSION = (ROOT / "VERSION").read_text(encoding="utf-8").strip()
# The license of the project and of everything it generates; its texts are LICENSE-* at the root.
LICENSE = "MIT OR Apache-2.0"
LICENSE_FILES = ("LICENSE-MIT", "LICENSE-APACHE")
# The folders of the output that are packages of their own: each carries the license texts.
PACKAGE_FOLDERS = ("c", "python", "rust")
