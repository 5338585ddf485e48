"""The rule table (generator/rules.py): one id per check, each id reported somewhere, and the
docs page written from it."""

from __future__ import annotations

import re
from pathlib import Path

from generator import rules
from generator.cli import main

ROOT = Path(__file__).resolve().parents[2]
GENERATOR = ROOT / "generator"
BAD = Path(__file__).with_name("bad_specs")


def _reported_ids() -> set[str]:
    """The rule ids the generator's code reports (as the rule argument of an error)."""
    ids = set()
    for path in GENERATOR.glob("*.py"):
        if path.name != "rules.py":
            ids |= set(re.findall(r'"([SAB]\d{3}|schema|yaml)"', path.read_text(encoding="utf-8")))
    return ids


def test_every_reported_id_is_in_the_table_and_every_rule_is_reported() -> None:
    assert _reported_ids() == set(rules.RULES)


def test_an_unknown_id_cannot_be_reported() -> None:
    from generator.errors import SpecError
    try:
        SpecError("spec/x.yaml", 1, "x", "a message", "S999")
    except ValueError as err:
        assert "S999" in str(err)
    else:
        raise AssertionError("S999 was reported")


def test_every_bad_spec_names_a_rule_of_the_table() -> None:
    for fixture in BAD.glob("*.yaml"):
        rule = fixture.read_text(encoding="utf-8").splitlines()[0].split(":", 1)[1].strip()
        assert rule in rules.RULES, fixture.name


def test_the_docs_page_is_the_table(capsys) -> None:
    assert main(["rules", "--markdown"]) == 0
    assert (ROOT / "docs" / "rules.md").read_text(encoding="utf-8") == capsys.readouterr().out, \
        "docs/rules.md is stale: nmeaspec-gen rules --markdown > docs/rules.md"


def test_rules_lists_every_id_once(capsys) -> None:
    assert main(["rules"]) == 0
    listed = re.findall(r"^(\S+) ", capsys.readouterr().out, re.MULTILINE)
    assert listed == list(rules.RULES)
