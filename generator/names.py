"""How the spec's ids become the names of generated code, and the clashes among those names.

The checks (checks.py, S016) and the emitters share these rules: names_c.py for C identifiers,
names_rust.py for Rust ones, and here what is common to them and the names of the `nmea command`
tool. (naming.py is another matter: it renames a whole output for `--prefix`/`--namespace`.)
"""

from __future__ import annotations

from .model import Origin, Spec


class NameClaims:
    """The identifiers a generated file declares and who declares each: a second owner of a name
    is a clash, which the spec's checks report at the second owner (generator/checks.py, S016)."""

    def __init__(self, language: str) -> None:
        self.language = language
        self.owners: dict[str, str] = {}
        self.clashes: list[tuple[Origin, str]] = []

    def claim(self, name: str, what: str, origin: Origin) -> None:
        other = self.owners.setdefault(name, what)
        if other != what:
            self.clashes.append((origin, f"the {self.language} name {name} of {what} is also the name of {other}"))


def command_clashes(spec: Spec) -> list[tuple[Origin, str]]:
    """The names `nmea command VENDOR NAME` would know two commands of a vendor by."""
    names = NameClaims("command")
    for s in spec.sentences:
        if s.kind == "command" and s.vendor is not None:
            for layout in s.layouts:
                names.claim(f"{s.vendor} {s.command_name(layout)}", f"layout {s.layout_snake(layout)}", layout.origin)
    return names.clashes
