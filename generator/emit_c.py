"""Placeholder while the c emitter is written."""

from __future__ import annotations

import jinja2

from .model import Spec


def emit(spec: Spec, env: jinja2.Environment) -> dict[str, str]:
    return {}
