"""The emit pass: runs every emitter over the checked model and returns the generated files
(path -> content)."""

from __future__ import annotations

from typing import Callable

import jinja2

from . import (emit_c, emit_docs, emit_packaging, emit_python, emit_python_ais, emit_python_apps,
               emit_python_rtcm3, emit_python_ubx, emit_rust,
               emit_c_ais, emit_c_rtcm3, emit_c_ubx, emit_rust_ais, emit_rust_rtcm3, emit_rust_ubx, emit_vectors)
from .emit import environment
from .model import Spec


def render_all(spec: Spec) -> dict[str, str]:
    env = environment()
    files: dict[str, str] = {}
    emitters: list[Callable[[Spec, jinja2.Environment], dict[str, str]]] = [
        emit_vectors.emit, emit_python.emit, emit_python_ais.emit, emit_python_ubx.emit, emit_python_rtcm3.emit, emit_python_apps.emit, emit_c.emit, emit_c_ais.emit, emit_c_rtcm3.emit, emit_c_ubx.emit, emit_packaging.emit, emit_rust.emit, emit_rust_ais.emit, emit_rust_rtcm3.emit, emit_rust_ubx.emit, emit_docs.emit,
    ]
    with emit_vectors.one_render_pass():
        for emitter in emitters:
            for path, content in emitter(spec, env).items():
                assert path not in files, path
                files[path] = content
    return files
