# golden/expected holds generated code as text to compare with (its tests are not ours to run).
collect_ignore_glob = ["golden/*"]


def pytest_configure(config) -> None:  # type: ignore[no-untyped-def]
    config.addinivalue_line("markers", "slow: builds or generates whole copies; `make test-quick` leaves it out")
