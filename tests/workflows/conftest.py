"""The users' workflows, run the way a user would: from fresh temporary directories, with copies of
generated/ and the ecosystem's own tools (cmake, cargo, pip, a browser). A missing tool is a
failure with the command that installs it, never a skip."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
GENERATED = ROOT / "generated"
CORPUS = ROOT.parent / "shared" / "corpus" / "real"
# Test-only tools installed into the temporary virtual environment, pinned.
MYPY = "mypy==2.4.1"


def need(tool: str, hint: str) -> str:
    path = shutil.which(tool)
    if path is None:
        pytest.fail(f"{tool} is not installed; {hint}")
    return path


def run(*args: str | Path, cwd: Path | None = None, input: bytes | None = None,
        env: dict[str, str] | None = None, check: bool = True, timeout: float = 600) -> subprocess.CompletedProcess:
    """Run a command; on failure, fail the test with its output."""
    result = subprocess.run([str(a) for a in args], cwd=cwd, input=input, capture_output=True, env=env,
                            timeout=timeout)
    if check and result.returncode != 0:
        pytest.fail(f"{' '.join(map(str, args))} exited with {result.returncode}\n"
                    f"stdout:\n{result.stdout.decode(errors='replace')[-4000:]}\n"
                    f"stderr:\n{result.stderr.decode(errors='replace')[-4000:]}")
    return result


class Venv:
    def __init__(self, path: Path) -> None:
        self.path = path
        self.bin = path / "bin"

    @property
    def python(self) -> Path:
        return self.bin / "python"

    def pip(self, *args: str | Path) -> None:
        # --no-compile: Python compiles what a test imports when it imports it, not all of it ahead.
        run(self.python, "-m", "pip", "install", "--quiet", "--disable-pip-version-check", "--no-compile", *args)


@pytest.fixture(scope="session")
def wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The wheel pip builds from a copy of generated/python, as it does for a user's `pip install
    DIR` (setuptools from PyPI, in an isolated build environment); built once, installed into each
    fresh environment below."""
    home = tmp_path_factory.mktemp("pywheel")
    source = home / "nmeaspec-src"
    shutil.copytree(GENERATED / "python", source, ignore=shutil.ignore_patterns("__pycache__", ".pytest_cache"))
    run(sys.executable, "-m", "pip", "wheel", "--quiet", "--disable-pip-version-check", "--no-deps",
        "--wheel-dir", home / "dist", source)
    (built,) = (home / "dist").glob("nmeaspec-*.whl")
    return built


def _install(tmp_path_factory: pytest.TempPathFactory, wheel: Path, name: str, extra: str = "") -> Venv:
    home = tmp_path_factory.mktemp(name)
    venv.create(home / "venv", with_pip=True)
    env = Venv(home / "venv")
    if extra:  # the extra's packages at the versions requirements.txt pins for the tests
        env.pip(f"{wheel}[{extra}]", "--constraint", ROOT / "requirements.txt")
    else:
        env.pip(wheel)
    return env


@pytest.fixture(scope="session")
def installed(tmp_path_factory: pytest.TempPathFactory, wheel: Path) -> Venv:
    """A fresh virtual environment with generated/python installed by pip, as a user would: the
    standard library only, no extra."""
    return _install(tmp_path_factory, wheel, "pyuser")


@pytest.fixture(scope="session")
def installed_extras(tmp_path_factory: pytest.TempPathFactory, wheel: Path) -> Venv:
    """The same with both extras (`pip install 'nmeaspec[serial,report]'`): pyserial for `nmea
    listen` and `nmea send`, matplotlib for `nmea report`. One environment for both: each is
    a venv and an install less, and neither extra changes what the other does."""
    return _install(tmp_path_factory, wheel, "pyextrasuser", "serial,report")



def corpus_log(name: str) -> Path:
    path = CORPUS / name
    if not path.is_file():
        pytest.fail(f"{path} is missing: the real logs live in ../shared/corpus/real beside the worktree")
    return path


def clean_env() -> dict[str, str]:
    """The environment without this repository's virtual environment on PATH."""
    env = dict(os.environ)
    env.pop("VIRTUAL_ENV", None)
    env.pop("PYTHONPATH", None)
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep)
                                  if not p.startswith(str(ROOT)) and p != str(Path(sys.executable).parent))
    return env
