"""Writes CHANGELOG.md: for each release, what a regeneration changes for the users of the
generated code (`nmeaspec-gen diff` between the spec of the previous release and its own).

The releases come from git: a commit belongs to the release its VERSION file names (before
VERSION existed, the version of the root pyproject.toml), so the last commit of a release is the
one before VERSION moved on. The current VERSION is compared with the working tree's spec/.

    python tools/changelog.py            # rewrite CHANGELOG.md (make changelog)
    python tools/changelog.py --check    # exit 1 when CHANGELOG.md is not what it would write
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from generator.build import load_spec  # noqa: E402
from generator.diff import compare, markdown, resolve_tree  # noqa: E402
from generator.errors import SpecErrors  # noqa: E402

INTRO = """\
# Changelog

What regenerating changes for the users of the generated code, release by release: the API
changelog of `nmeaspec-gen diff` between the spec of the previous release and the spec of this one.
**BREAKING** means that existing user code or existing wire data stops working; compatible means
that it keeps working. Written by `make changelog` (tools/changelog.py) from the git history.
"""


@dataclass
class Release:
    version: str
    commit: str | None  # its last commit; None for the release in the working tree


def git(*args: str) -> str:
    return subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True, text=True,
                          check=True).stdout


def version_at(commit: str) -> str | None:
    """The release a commit belongs to: its VERSION, else its root pyproject.toml's version."""
    for path, pattern in (("VERSION", r"\A\s*(\S+)\s*\Z"), ("pyproject.toml", r'(?m)^version = "([^"]+)"')):
        shown = subprocess.run(["git", "-C", str(ROOT), "show", f"{commit}:{path}"], capture_output=True,
                               text=True)
        found = re.search(pattern, shown.stdout) if shown.returncode == 0 else None
        if found:
            return found.group(1)
    return None


def releases() -> list[Release]:
    """Every release, oldest first, the current one (the working tree's VERSION) last."""
    current = (ROOT / "VERSION").read_text(encoding="utf-8").strip()
    # Each change of the version (the newest first, the working tree's own on top) ends the
    # release of the version before it at the commit before it.
    head = git("rev-parse", "HEAD").strip()
    changes = [(head, version_at(head), current)]
    for commit in git("log", "--format=%H %P", "--", "VERSION", "pyproject.toml").splitlines():
        commit, *parents = commit.split()
        if parents:
            changes.append((parents[0], version_at(parents[0]), version_at(commit)))
    found: list[Release] = []
    seen = {current}
    for before, old, new in changes:
        if old and old != new and old not in seen:
            seen.add(old)
            found.append(Release(old, before))
    return [*reversed(found), Release(current, None)]


def section(previous: Release | None, release: Release, tmp: Path) -> str:
    where = f" (commit {release.commit[:12]})" if release.commit else ""
    title = f"{release.version}{where}"
    new = load_spec(resolve_tree(release.commit, tmp, f"new-{release.version}") if release.commit else ROOT / "spec")
    if previous is None:
        return (f"## {title}\n\nThe first release: {len(new.sentences)} sentences "
                f"({len(new.standard)} standard, {len(new.proprietary)} proprietary), {len(new.enums)} "
                f"lookup tables.\n")
    assert previous.commit is not None
    old = load_spec(resolve_tree(previous.commit, tmp, f"old-{previous.version}"))
    return markdown(compare(old, new), previous.version, release.version,
                    title=f"{title}: since {previous.version}", level=2)


def changelog() -> str:
    history = releases()
    parts = [INTRO]
    with tempfile.TemporaryDirectory(prefix="nmeaspec-changelog-") as tmp:
        for i in reversed(range(len(history))):
            parts.append(section(history[i - 1] if i else None, history[i], Path(tmp)))
    return "\n".join(parts)


def main() -> int:
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("--check", action="store_true", help="exit 1 when CHANGELOG.md is stale")
    check = args.parse_args().check
    try:
        text = changelog()
    except (subprocess.CalledProcessError, ValueError) as err:
        print(f"changelog: the git history is needed ({err})", file=sys.stderr)
        return 2
    except SpecErrors as errs:
        print(f"changelog: a release's spec does not load:\n{errs}", file=sys.stderr)
        return 2
    path = ROOT / "CHANGELOG.md"
    if check:
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            print("CHANGELOG.md is stale: run make changelog", file=sys.stderr)
            return 1
        return 0
    path.write_text(text, encoding="utf-8")
    print(f"wrote {path.relative_to(ROOT)}: {text.count(chr(10) + '## ')} release(s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
