"""The one error type of the generator: a broken rule, with the file, line and YAML path."""

from __future__ import annotations

from .rules import rule as known_rule


class SpecError(Exception):
    def __init__(self, file: str, line: int, path: str, message: str, rule: str) -> None:
        super().__init__(message)
        self.file = file
        self.line = line
        self.path = path
        self.message = message
        self.rule = known_rule(rule).id  # only the ids of generator/rules.py can be reported

    def __str__(self) -> str:
        return f"{self.file}:{self.line}: {self.path}: {self.message} [{self.rule}]"


class SpecErrors(Exception):
    """Everything wrong with a spec tree, reported at once."""

    def __init__(self, errors: list[SpecError]) -> None:
        super().__init__(f"{len(errors)} spec error(s)")
        self.errors = errors

    def __str__(self) -> str:
        return "\n".join(str(e) for e in self.errors)
