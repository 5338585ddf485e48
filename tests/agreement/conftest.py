"""Print the corpus decode rates (test_corpus.py) and the fault-injection figures (test_faults.py)
at the end of the run."""

from __future__ import annotations


def pytest_terminal_summary(terminalreporter) -> None:  # type: ignore[no-untyped-def]
    from . import test_corpus, test_faults

    if test_corpus.RATES:
        terminalreporter.write_sep("-", "decode rates on the real logs (build/reports/corpus.md)")
        terminalreporter.write(test_corpus.report())
    if test_faults.ROWS:
        terminalreporter.write_sep("-", "fault injection over the real logs (build/reports/faults.md)")
        terminalreporter.write(test_faults.report())
