"""`nmea report`: a real receiver log drawn as one HTML page by the package installed with its
`report` extra, checked as a page (self-contained, every section there) and as a picture (headless
Chromium's screenshot of it is not blank); its errors; and the package without the extra."""

from __future__ import annotations

import base64
import re
from html.parser import HTMLParser
from pathlib import Path

import matplotlib.image
import numpy

from .conftest import Venv, corpus_log, need, run

MULTI_GNSS = "gpsd/ublox-neo-m9n-nmea.nmea"  # GN/GP/GL/GA/GB: GGA, GSA, GSV with signal ids, 1 min
RMC_ONLY = "gpsd/magellan-ec10.nmea"  # RMC and RMB only: a fix, no satellites
BAD_LINES = "gpsd/blumax-gps009.nmea"  # 8 SiRF text lines that are not sentences
AIS_LOG = "gpsd/ais-nmea.nmea"  # AIVDM of 30 ships in a Dutch harbour, type 5 in two sentences
SECTIONS = ("summary", "track", "sky", "cn0", "quality", "sentences")


def nmea(env: Venv, *args: str | Path, cwd: Path, check: bool = True):  # type: ignore[no-untyped-def]
    return run(env.bin / "nmea", *args, check=check, cwd=cwd, timeout=120)


class Page(HTMLParser):
    """The sections (their ids and pictures), every src/href and the table cells of a page."""

    def __init__(self, text: str) -> None:
        super().__init__()
        self.sections: dict[str, list[str]] = {}
        self.links: list[str] = []
        self.cells: list[str] = []
        self.empty: dict[str, str] = {}
        self._section: str | None = None
        self._cell: list[str] | None = None
        self._empty: list[str] | None = None
        self.feed(text)

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = dict(attrs)
        self.links += [v or "" for k, v in attrs if k in ("src", "href", "srcset", "data", "action")]
        if tag == "section" and values.get("id"):
            self._section = values["id"]
            self.sections[self._section] = []
        elif tag == "img" and self._section is not None:
            self.sections[self._section].append(values.get("src") or "")
        elif tag in ("td", "th"):
            self._cell = []
        elif tag == "p" and values.get("class") == "empty":
            self._empty = []

    def handle_endtag(self, tag: str) -> None:
        if tag in ("td", "th") and self._cell is not None:
            self.cells.append("".join(self._cell).strip())
            self._cell = None
        elif tag == "p" and self._empty is not None and self._section is not None:
            self.empty[self._section] = "".join(self._empty)
            self._empty = None

    def handle_data(self, data: str) -> None:
        for part in (self._cell, self._empty):
            if part is not None:
                part.append(data)


def _report(env: Venv, log: str, tmp_path: Path, *options: str) -> tuple[str, Page, str]:
    out = tmp_path / "report.html"
    result = nmea(env, "report", corpus_log(log), "-o", out, *options, cwd=tmp_path)
    text = out.read_text(encoding="utf-8")
    return text, Page(text), result.stderr.decode()


def _self_contained(text: str, page: Page) -> None:
    """Nothing is loaded from elsewhere: pictures are data: URIs, links stay on the page."""
    assert page.links, "no src or href at all"
    for link in page.links:
        assert link.startswith(("data:image/png;base64,", "#")), link[:80]
    assert not re.search(r"(?i)(https?:)?//[a-z0-9.-]+\.[a-z]{2,}/", text.replace("\\", "")), "a URL"
    assert "<script" not in text and "<link" not in text and "@import" not in text and "url(" not in text


def _pngs(sources: list[str]) -> list[bytes]:
    data = [base64.b64decode(s.partition(",")[2], validate=True) for s in sources]
    assert all(d.startswith(b"\x89PNG\r\n\x1a\n") and len(d) > 5000 for d in data)
    return data


def _screenshot(page: Path, shot: Path) -> numpy.ndarray:
    browser = need("chromium", "apt-get install chromium (.ci/run does)")
    run(browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--hide-scrollbars",
        "--virtual-time-budget=3000", f"--screenshot={shot}", "--window-size=1280,2600", page.as_uri(),
        timeout=120)
    pixels: numpy.ndarray = matplotlib.image.imread(shot)[:, :, :3]
    return pixels


def test_report_of_a_multi_gnss_log(installed_extras: Venv, tmp_path: Path) -> None:
    text, page, stderr = _report(installed_extras, MULTI_GNSS, tmp_path)
    assert stderr == f"wrote {tmp_path / 'report.html'}: 1403 lines, 1403 sentences, 0 errors\n"
    _self_contained(text, page)
    assert list(page.sections) == list(SECTIONS)
    pictures = {name: _pngs(srcs) for name, srcs in page.sections.items() if srcs}
    assert sorted(pictures) == ["cn0", "quality", "sky", "track"] and not page.empty
    assert all(len(p) == 1 for p in pictures.values())
    assert "61 fixes with a position, merged from GSV, GSA, RMC, VTG, GGA, GLL, GST, ZDA" in text
    assert "43 satellites in view" in text
    assert "30 satellite signals with a C/N0" in text
    assert "22:37:45 – 22:38:45" in text and "2020-07-11" in text  # UTC span and date of the log
    # the sentence table: GSV per talker, GGA, with their counts; no errors
    rows = page.cells
    assert rows[rows.index("GGA"):rows.index("GGA") + 4] == ["GGA", "GN", "Global positioning system fix data", "61"]
    gsv = [rows[i + 1:i + 4:2] for i, cell in enumerate(rows) if cell == "GSV"]
    assert sorted(gsv) == [["GA", "183"], ["GB", "122"], ["GL", "183"], ["GP", "244"]]
    assert "No decode errors." in text

    pixels = _screenshot(tmp_path / "report.html", tmp_path / "report.png")
    height, width, _ = pixels.shape
    assert (height, width) == (2600, 1280)
    background = numpy.array([0xEE, 0xF1, 0xF4]) / 255
    painted = (numpy.abs(pixels - background).max(axis=2) > 0.05).mean()
    colourful = (pixels.max(axis=2) - pixels.min(axis=2) > 0.35).mean()
    distinct = len(numpy.unique((pixels * 31).round().reshape(-1, 3), axis=0))
    # the white sections cover most of the page; the charts' colours (the constellations, the
    # C/N0 colour map) a good part of it, in many shades: a blank page or broken pictures fail
    assert painted > 0.5, painted
    assert colourful > 0.05, colourful
    assert distinct > 500, distinct


def test_report_of_an_rmc_only_log(installed_extras: Venv, tmp_path: Path) -> None:
    text, page, stderr = _report(installed_extras, RMC_ONLY, tmp_path, "--progress")
    assert "100%" in stderr and stderr.startswith("\r[")  # the bar `show` draws, on request
    _self_contained(text, page)
    assert list(page.sections) == list(SECTIONS)
    assert [name for name, srcs in page.sections.items() if srcs] == ["track", "quality"]
    _pngs(page.sections["track"] + page.sections["quality"])
    assert page.empty["sky"].startswith("No satellite positions in this log")
    assert page.empty["cn0"].startswith("No signal strengths in this log")
    assert "21 fixes with a position, merged from RMC" in text  # 17 of its 38 say V: no fix
    assert "Not in this log: satellite counts" in text
    assert "2005-06-09" in text
    again = tmp_path / "again.html"
    nmea(installed_extras, "report", "-q", "--no-progress", corpus_log(RMC_ONLY), "-o", again, cwd=tmp_path)
    assert again.read_text(encoding="utf-8") == text, "two reports of one log differ"


def test_report_counts_bad_lines(installed_extras: Venv, tmp_path: Path) -> None:
    text, page, stderr = _report(installed_extras, BAD_LINES, tmp_path)
    assert stderr.endswith(": 67 lines, 59 sentences, 8 errors\n")
    rows = page.cells
    assert rows[rows.index("not_a_sentence"):rows.index("not_a_sentence") + 2] == ["not_a_sentence", "8"]
    assert "first 8 errors" in rows
    assert sum(1 for cell in rows if cell == "not_a_sentence") == 1 + 8  # the kind, then each line
    assert sorted(name for name, srcs in page.sections.items() if srcs) == ["cn0", "quality", "sky", "track"]


def test_report_errors(installed_extras: Venv, tmp_path: Path) -> None:
    missing = nmea(installed_extras, "report", tmp_path / "nowhere.nmea", "-o", tmp_path / "out.html",
                   cwd=tmp_path, check=False)
    assert missing.returncode == 2 and missing.stdout == b""
    assert missing.stderr.decode() == f"nmea: cannot read {tmp_path / 'nowhere.nmea'}: No such file or directory\n"
    binary = tmp_path / "photo.jpg"
    binary.write_bytes(bytes(range(256)) * 40 + b"\nhello\nworld\n")
    not_nmea = nmea(installed_extras, "report", binary, "-o", tmp_path / "out.html", cwd=tmp_path, check=False)
    assert not_nmea.returncode == 2
    message = not_nmea.stderr.decode()
    assert message.startswith(f"nmea: {binary} is not an NMEA log: none of its ") and message.count("\n") == 1
    empty = tmp_path / "empty.nmea"
    empty.write_bytes(b"")
    assert nmea(installed_extras, "report", empty, cwd=tmp_path, check=False).stderr == \
        f"nmea: {empty} is empty\n".encode()
    assert not (tmp_path / "out.html").exists() and not (tmp_path / "empty.html").exists()


def test_report_without_the_extra(installed: Venv, tmp_path: Path) -> None:
    """The package itself needs only the standard library: without matplotlib (pyarrow) `nmea
    report` (`nmea export`) says what to install, and the rest of `nmea` works."""
    result = nmea(installed, "report", corpus_log(RMC_ONLY), cwd=tmp_path, check=False)
    assert result.returncode == 2
    assert result.stderr == b"nmea: nmea report draws with matplotlib, which is not installed: " \
                            b"pip install 'nmeaspec[report]'\n"
    assert not list(tmp_path.iterdir())
    assert b"RMC" in nmea(installed, "show", "-q", corpus_log(RMC_ONLY), cwd=tmp_path).stdout
    assert b"report" in nmea(installed, "--help", cwd=tmp_path).stdout
    exported = nmea(installed, "export", corpus_log(RMC_ONLY), "-o", tmp_path / "tables", cwd=tmp_path, check=False)
    assert exported.returncode == 2 and not (tmp_path / "tables").exists()
    assert exported.stderr == b"nmea: nmea export writes Parquet with pyarrow, which is not installed: " \
                              b"pip install 'nmeaspec[parquet]'\n"


def test_report_of_an_ais_log(installed_extras: Venv, tmp_path: Path) -> None:
    """A ship's AIS feed: the stations' tracks on a map and the table of those that sent most,
    names from their static reports (joined across sentences), between the charts and the sentences."""
    text, page, stderr = _report(installed_extras, AIS_LOG, tmp_path)
    assert stderr == f"wrote {tmp_path / 'report.html'}: 1496 lines, 1496 sentences, 0 errors\n"
    _self_contained(text, page)
    assert list(page.sections) == ["summary", "track", "sky", "cn0", "quality", "ais", "sentences"]
    assert len(_pngs(page.sections["ais"])) == 1
    assert "30 AIS stations with positions (141 position reports)" in text
    rows = page.cells
    first = rows.index("MMSI")
    assert rows[first:first + 8] == ["MMSI", "name", "messages", "last position",
                                     "235084466", "VOS DOROTHEA", "17", "52.83810° N, 5.70402° E"]
    assert "TIJMA" in rows  # a name from a type 5 message of two sentences
    assert '<a href="#ais">AIS targets</a>' in text
