"""The reference docs as a reader meets them: Markdown on a code host (every relative link and
anchor resolves, headings name the sentence), and the HTML site of `make docs-site` rendered by
headless Chromium (Debian's `chromium`), with its search index."""

from __future__ import annotations

import json
import re
import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from html.parser import HTMLParser
from pathlib import Path

import pytest

from .conftest import GENERATED, ROOT, need, run

DOCS = GENERATED / "docs"
LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)\)")
MKDOCS = ROOT / ".venv-docs" / "bin" / "mkdocs"


def _slug(heading: str) -> str:
    """The anchor a code host (and mkdocs' toc) gives a heading."""
    text = re.sub(r"[`*_\[\]()]|<[^>]+>", "", heading).strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return re.sub(r"[\s]+", "-", text)


def _anchors(path: Path) -> set[str]:
    """The headings' anchors and the explicit ones (`<a id="...">`, e.g. of a table's rows)."""
    text = path.read_text(encoding="utf-8")
    headings = {_slug(m.group(1)) for m in re.finditer(r"^#+ (.+)$", text, re.M)}
    return headings | set(re.findall(r'<a id="([^"]+)">', text))


def test_every_relative_link_resolves() -> None:
    pages = sorted(DOCS.rglob("*.md"))
    assert len(pages) > 100
    broken, checked = [], 0
    for page in pages:
        for target in LINK.findall(page.read_text(encoding="utf-8")):
            if re.match(r"[a-z]+:", target):
                continue
            assert not target.startswith("/"), f"{page}: absolute link {target}"
            file, _, anchor = target.partition("#")
            resolved = (page.parent / file).resolve() if file else page
            checked += 1
            if not resolved.is_file():
                broken.append(f"{page.relative_to(DOCS)}: {target}")
            elif anchor and resolved.suffix == ".md" and anchor not in _anchors(resolved):
                broken.append(f"{page.relative_to(DOCS)}: {target} (no such heading)")
    assert not broken, "\n".join(broken)
    assert checked > 500


def test_headings_name_the_sentence() -> None:
    gga = (DOCS / "sentences" / "gga.md").read_text(encoding="utf-8")
    assert "\n# GGA: Global positioning system fix data\n" in gga
    command = (DOCS / "sentences" / "geos5_command.md").read_text(encoding="utf-8")
    assert "\n# GEOS5_COMMAND: GeoS-5 input command (`$GPSGG`)\n" in command
    for index in ("sentences.md", "vendors.md", "commands.md"):
        assert (DOCS / index).is_file() and f"]({index})" in (DOCS / "README.md").read_text(encoding="utf-8")


class _Tables(HTMLParser):
    """Rows of the rendered tables (cell texts), and the ids of the page's elements."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: list[list[str]] = []
        self.ids: set[str] = set()
        self._cell: list[str] | None = None

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.ids.update(v for k, v in attrs if k == "id" and v)
        if tag == "tr":
            self.rows.append([])
        elif tag in ("td", "th"):
            self._cell = []

    def handle_endtag(self, tag: str) -> None:
        if tag in ("td", "th") and self._cell is not None and self.rows:
            self.rows[-1].append("".join(self._cell).strip())
            self._cell = None

    def handle_data(self, data: str) -> None:
        if self._cell is not None:
            self._cell.append(data)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@contextmanager
def _serve(site: Path) -> Iterator[str]:
    port = _free_port()
    server = subprocess.Popen([sys.executable, "-m", "http.server", str(port), "--bind", "127.0.0.1"], cwd=site,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        url = f"http://127.0.0.1:{port}"
        for _ in range(100):
            try:
                urllib.request.urlopen(url + "/index.html", timeout=1).close()
                break
            except OSError:
                time.sleep(0.1)
        yield url
    finally:
        server.terminate()
        server.wait(timeout=10)


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    if not MKDOCS.is_file():
        pytest.fail(f"{MKDOCS} is missing; `make test-workflows` installs it from docs/requirements-docs.txt")
    out = tmp_path_factory.mktemp("site")
    run(MKDOCS, "build", "--strict", "--quiet", "--config-file", ROOT / "mkdocs.yml", "--site-dir", out, cwd=ROOT)
    return out


def _render(url: str) -> _Tables:
    browser = need("chromium", "apt-get install chromium (.ci/run does)")
    dom = run(browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              "--virtual-time-budget=3000", "--dump-dom", url, timeout=120).stdout.decode()
    parsed = _Tables()
    parsed.feed(dom)
    return parsed


def test_site_renders_tables_in_chromium(site: Path) -> None:
    with _serve(site) as url:
        index = _render(url + "/index.html")
        assert "mkdocs-search-query" in index.ids, "no search box"
        assert any(row[:1] == ["GGA"] and "Global positioning system fix data" in row for row in index.rows)
        header = next(line for line in (DOCS / "README.md").read_text(encoding="utf-8").splitlines()
                      if line.startswith("| sentence | nmea0183 |"))
        width = header.count("|") - 1  # the sentence, the standard and one column per receiver
        assert sum(1 for row in index.rows if len(row) == width) > 50, "support matrix rows"
        gga = _render(url + "/sentences/gga.html")
        assert ["1", "time", "UTC time", "UTC time"] == gga.rows[1][:4]
        assert any(row[1:2] == ["quality"] for row in gga.rows)
        geos5 = _render(url + "/vendors/geos5.html")
        assert any(row[:1] == ["GEOS5_COMMAND"] and "GeoS-5 input command" in row for row in geos5.rows)
        assert any(row[:1] == ["GGA"] for row in geos5.rows)
        search = json.loads(urllib.request.urlopen(url + "/search/search_index.json", timeout=10).read())
    titles = {doc["title"] for doc in search["docs"]}
    assert "GGA: Global positioning system fix data" in titles
    assert any(doc["location"] == "sentences/gga.html" for doc in search["docs"])
