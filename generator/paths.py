"""Where the generator finds its templates/, the hand-written runtimes (runtime/) and the built-in
spec/ (schema included).

In a checkout (`python -m generator`, or an editable install) they are the checkout's folders
next to generator/. An installed wheel carries them in the package, as generator/data/ (see
pyproject.toml), so the installed generator runs from any directory.
"""

from __future__ import annotations

from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent


def _is_root(path: Path) -> bool:
    return all((path / folder).is_dir() for folder in ("templates", "runtime", "spec/schema"))


# The checkout the generator runs from, or None when it runs from an installed wheel.
CHECKOUT = _PACKAGE.parent if _is_root(_PACKAGE.parent) else None
# The folder holding templates/, runtime/, spec/, VERSION and the license texts.
ROOT = CHECKOUT or _PACKAGE / "data"
# The release of the project and of everything it generates, defined once in the checkout's VERSION.
VERSION = (ROOT / "VERSION").read_text(encoding="utf-8").strip()
# The license of the project and of everything it generates; its texts are LICENSE-* at the root.
LICENSE = "MIT OR Apache-2.0"
LICENSE_FILES = ("LICENSE-MIT", "LICENSE-APACHE")
# The folders of the output that are packages of their own: each carries the license texts.
PACKAGE_FOLDERS = ("c", "python", "rust")
