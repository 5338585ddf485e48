"""Build files that let another project use the generated code the way its ecosystem expects:
a CMakeLists.txt beside the C pair (the Python pyproject.toml and the Rust Cargo.toml come with
their emitters)."""

from __future__ import annotations

import jinja2

from .emit import TEMPLATES, header
from .model import Spec


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    cmake = (TEMPLATES / "c" / "CMakeLists.txt").read_text(encoding="utf-8")
    return {"c/CMakeLists.txt": header(spec, "#", ["templates/c/CMakeLists.txt"]) + cmake}
