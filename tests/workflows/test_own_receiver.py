"""README's "Your own receiver's sentences", command for command: the generator's wheel installed
into a fresh venv, run in a temporary git repository outside the checkout, with an overlay of the
team's own sentence; the generated Python subset parses it, the C pair compiles, and `diff`
reports the manual's change."""

from __future__ import annotations

import os
import re
import sys
import venv
from pathlib import Path

import pytest

from .conftest import ROOT, need, run

# The two command blocks of the README section that run in the team's repository.
SECTION = re.search(r"^## Your own receiver's sentences\n(.*?)^## ", (ROOT / "README.md").read_text(encoding="utf-8"),
                    re.MULTILINE | re.DOTALL)
BLOCKS = [block.strip().splitlines() for block in re.findall(r"```sh\n(.*?)```", SECTION.group(1), re.DOTALL)][1:] \
    if SECTION else []


@pytest.fixture(scope="session")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A venv with the generator's wheel, built once from the checkout's tracked files."""
    home = tmp_path_factory.mktemp("own-receiver")
    source = home / "src"
    tracked = run("git", "ls-files", "-z", "--cached", "--others", "--exclude-standard", "pyproject.toml", "VERSION",
                  "LICENSE-*", "generator", "spec", "templates", "runtime", cwd=ROOT).stdout.decode().split("\0")
    for name in filter(None, tracked):
        (source / name).parent.mkdir(parents=True, exist_ok=True)
        (source / name).write_bytes((ROOT / name).read_bytes())
    run(sys.executable, "-m", "build", "--wheel", "--no-isolation", "--outdir", home / "dist", source)
    [wheel] = (home / "dist").glob("*.whl")
    venv.create(home / "venv", with_pip=True)
    python = home / "venv" / "bin" / "python"
    run(python, "-m", "pip", "install", "--quiet", "--disable-pip-version-check", "--no-compile", "--no-deps", wheel)
    # The generator's dependencies come from the project's environment, not from the network.
    site = run(python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])").stdout.decode().strip()
    ours = [p for p in sys.path if p.endswith("site-packages") and Path(p, "jinja2").is_dir()]
    Path(site, "project-deps.pth").write_text("\n".join(ours) + "\n")
    return home / "venv" / "bin"


def _shell(lines: list[str], repo: Path, bin_dir: Path) -> str:
    env = {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}", "GIT_AUTHOR_NAME": "firmware",
           "GIT_AUTHOR_EMAIL": "fw@example.com", "GIT_COMMITTER_NAME": "firmware", "GIT_COMMITTER_EMAIL": "fw@example.com"}
    env.pop("PYTHONPATH", None)
    out = []
    for line in lines:
        out.append(run("bash", "-c", line, cwd=repo, env=env).stdout.decode())
    return "".join(out)


def test_a_firmware_team_keeps_its_receiver_in_its_own_repository(installed: Path, tmp_path: Path) -> None:
    assert len(BLOCKS) == 2 and all(line.startswith(("nmeaspec-gen ", "git ")) for block in BLOCKS for line in block)
    repo = tmp_path / "firmware"
    repo.mkdir()
    run("git", "init", "-q", cwd=repo)

    out = _shell(BLOCKS[0], repo, installed)
    assert "created nmea-spec/proprietary/pacmepos.yaml" in out and "spec ok: " in out, out
    nmea = repo / "third_party" / "nmea"
    line = re.search(r"raw: (\S+)", (repo / "nmea-spec/proprietary/pacmepos.yaml").read_text()).group(1)
    assert _parse(nmea, line, tmp_path) == "Pacmepos 1 None\n"
    assert not (nmea / "python" / "acmenmea" / "sentences" / "gsa.py").exists()  # only the subset
    cc = need("cc", "install a C compiler (apt-get install gcc)")
    run(cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-c", "-o", tmp_path / "acme.o", nmea / "c" / "acme.c")

    # Revision B of the manual adds a trailing fix-quality field, with its example.
    spec_file = repo / "nmea-spec/proprietary/pacmepos.yaml"
    text = spec_file.read_text().replace("examples:", """\
- id: quality
  name: Fix quality
  type: integer
  optional: true
  doc: Quality of the fix (revision B).
examples:""", 1)
    spec_file.write_text(text + """\
- manual: acme
  where: revision B, PACMEPOS
  raw: $PACMEPOS,1,2*15
  expect: {value: 1, quality: 2}
""")
    out = _shell(BLOCKS[1], repo, installed)
    assert "0 BREAKING" in out and "compatible: `PACMEPOS`: optional field `quality` (integer) added at the end" in out, out
    assert "updated nmea/python/acmenmea/sentences/pacmepos.py" in out, out
    assert _parse(nmea, "$PACMEPOS,1,2*15", tmp_path) == "Pacmepos 1 2\n"


def _parse(nmea: Path, line: str, cwd: Path) -> str:
    """The line through the generated Python package: its type and fields."""
    script = (f"import acmenmea; s = acmenmea.parse({line!r}); "
              "print(type(s).__name__, int(s.value), getattr(s, 'quality', None) and int(s.quality))")
    return run(sys.executable, "-c", script, cwd=cwd, env={**os.environ, "PYTHONPATH": str(nmea / "python")}).stdout.decode()


def test_the_installed_generator_needs_out_outside_a_checkout(installed: Path, tmp_path: Path) -> None:
    result = run(installed / "nmeaspec-gen", "generate", cwd=tmp_path, check=False)
    assert result.returncode == 2 and b"give --out DIR" in result.stderr
    assert run(installed / "nmeaspec-gen", "rules", cwd=tmp_path).stdout.startswith(b"yaml ")
