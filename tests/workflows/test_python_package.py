"""The Python package in a fresh virtual environment: pip-installed from a copy of generated/python,
imported from elsewhere, its console scripts on PATH, its types accepted by mypy --strict, and the
package itself strict-clean when vendored into a project that runs mypy --strict."""

from __future__ import annotations

from pathlib import Path

import shutil

from .conftest import GENERATED, MYPY, Venv, run

USER_SCRIPT = '''
from decimal import Decimal

import nmeaspec
from nmeaspec import Gga, Geos5Command, Geos5CommandWord


def altitude(line: str) -> Decimal | None:
    sentence = nmeaspec.parse(line)
    if isinstance(sentence, Gga) and isinstance(sentence.altitude, nmeaspec.Number):
        return sentence.altitude.value
    return None


command: bytes = Geos5Command(command=Geos5CommandWord.BAUD_115200).to_bytes()
print(altitude("$GPGGA,193221.00,2037.72792,N,08704.08478,W,1,04,1.7,-30.40,M,-13.9,M,,*7D"), command)
'''


def test_import_from_anywhere(installed: Venv, tmp_path: Path) -> None:
    script = tmp_path / "user.py"
    script.write_text(USER_SCRIPT)
    out = run(installed.python, script, cwd=tmp_path).stdout
    assert out == b"-30.40 b'$GPSGG,BDR115*09\\r\\n'\n"
    location = run(installed.python, "-c", "import nmeaspec; print(nmeaspec.__file__)", cwd=tmp_path).stdout
    assert b"site-packages" in location
    typed = run(installed.python, "-c", "import importlib.resources as r; print(r.files('nmeaspec')"
                ".joinpath('py.typed').is_file())", cwd=tmp_path).stdout
    assert typed == b"True\n"
    apps = run(installed.python, "-c", "import sys, nmeaspec; nmeaspec.Receiver, nmeaspec.Gga; "
               "print(sorted(m for m in sys.modules if m.startswith('nmeaspec.apps')))", cwd=tmp_path).stdout
    assert apps == b"[]\n", f"the codec imports its applications: {apps!r}"


def test_console_scripts(installed: Venv, tmp_path: Path) -> None:
    line = b"$GPGGA,193221.00,2037.72792,N,08704.08478,W,1,04,1.7,-30.40,M,-13.9,M,,*7D\n"
    decoded = run(installed.bin / "nmea-py", "decode", input=line, cwd=tmp_path).stdout
    assert decoded.startswith(b'{"ok":true,') and b'"sentence":"GGA"' in decoded
    assert run(installed.bin / "nmea-py", "encode", input=decoded, cwd=tmp_path).stdout == line
    assert b"show" in run(installed.bin / "nmea", "--help", cwd=tmp_path).stdout


def test_mypy_strict_accepts_the_package_and_a_user_script(installed: Venv, tmp_path: Path) -> None:
    """A user who copies the package into their tree checks it with their own code: one mypy run
    over both (the installed package's py.typed, which points mypy at the same modules, is
    checked by test_import_from_anywhere)."""
    installed.pip(MYPY)
    shutil.copytree(GENERATED / "python" / "nmeaspec", tmp_path / "nmeaspec",
                    ignore=shutil.ignore_patterns("__pycache__"))
    (tmp_path / "user.py").write_text(USER_SCRIPT)
    out = run(installed.python, "-m", "mypy", "--strict", "--no-incremental", "nmeaspec", "user.py", cwd=tmp_path).stdout
    assert b"Success: no issues found" in out
