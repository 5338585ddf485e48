"""Build and release files that let another project use the generated code the way its ecosystem
expects: a CMakeLists.txt beside the C pair, and the license texts in each package folder (the
Python pyproject.toml and the Rust Cargo.toml come with their emitters)."""

from __future__ import annotations

import jinja2

from .emit import header, license_texts
from .emit_c import MAX_LINE, longest_line
from .emit_c_ais import carries_ais
from .emit_c_ubx import carries_ubx
from .model import Spec
from .paths import PACKAGE_FOLDERS


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    files = {"c/CMakeLists.txt": env.get_template("c/CMakeLists.txt.j2").render(
        header=header(spec, "#", ["templates/c/CMakeLists.txt.j2"]), max_line=longest_line(spec),
        contract_max_line=MAX_LINE, ais=carries_ais(spec), ubx=carries_ubx(spec),
        rtcm3=bool(spec.bit_messages))}
    for folder in PACKAGE_FOLDERS:
        files.update(license_texts(folder))
    return files
