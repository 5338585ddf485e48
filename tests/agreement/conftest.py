"""Print the corpus decode rates (test_corpus.py) at the end of the run."""

from __future__ import annotations


def pytest_terminal_summary(terminalreporter) -> None:  # type: ignore[no-untyped-def]
    from .test_corpus import RATES, report

    if RATES:
        terminalreporter.write_sep("-", "decode rates on the real logs (build/reports/corpus.md)")
        terminalreporter.write(report())
