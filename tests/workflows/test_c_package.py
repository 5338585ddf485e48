"""The C pair in another project: add_subdirectory() of a copy from a fresh CMake project, its own
CMake build installed and found by find_package(), and the plain two-file build any other build
system does. The CMake projects build a pair of GGA alone, as a firmware team generates it (its
CMake files are those of any pair; compiling all 641 sentences three times would test nothing
more): the plain build compiles the whole pair of generated/c."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import pytest

from .conftest import GENERATED, ROOT, need, run

APP = r"""
#include <stdio.h>
#include <string.h>
#include "nmea.h"

int main(void) {
    const char *line = "$GPGGA,193221.00,2037.72792,N,08704.08478,W,1,04,1.7,-30.40,M,-13.9,M,,*7D";
    nmea_sentence s;
    nmea_error err;
    char out[NMEA_MAX_LINE + 3];
    if (!nmea_parse(&s, line, strlen(line), &err) || s.id != NMEA_SENTENCE_GGA) {
        fprintf(stderr, "parse failed\n");
        return 1;
    }
    if (nmea_serialize(&s, out, sizeof out) == 0 || strcmp(out, line) != 0) {
        fprintf(stderr, "round trip failed: %s\n", out);
        return 1;
    }
    printf("GGA satellites=%ld\n", (long)s.as.gga.satellites.digits);
    return 0;
}
"""

CMAKE = """cmake_minimum_required(VERSION 3.13)
project(app C)
add_subdirectory(third_party/nmea)
add_executable(app app.c)
target_link_libraries(app PRIVATE nmea::nmea)
"""


@pytest.fixture(scope="module")
def gga_pair(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("gga-pair")
    run(sys.executable, "-m", "generator", "generate", "--quiet", "--only", "GGA", "--out", out, cwd=ROOT)
    return out / "c"


def _project(tmp_path: Path, pair: Path) -> Path:
    shutil.copytree(pair, tmp_path / "third_party" / "nmea", ignore=shutil.ignore_patterns("tests"))
    (tmp_path / "app.c").write_text(APP)
    return tmp_path


def test_cmake_add_subdirectory(tmp_path: Path, gga_pair: Path) -> None:
    cmake = need("cmake", "apt-get install cmake")
    project = _project(tmp_path, gga_pair)
    (project / "CMakeLists.txt").write_text(CMAKE)
    run(cmake, "-S", project, "-B", project / "build", "-DCMAKE_C_FLAGS=-Wall -Wextra -Werror -pedantic")
    run(cmake, "--build", project / "build")
    out = run(project / "build" / "app").stdout.decode()
    assert out == "GGA satellites=4\n"
    assert not (project / "build" / "third_party" / "nmea" / "nmea-c").exists(), "the tool is opt-in when vendored"


def test_cmake_top_level_builds_the_tool_and_installs(tmp_path: Path, gga_pair: Path) -> None:
    cmake = need("cmake", "apt-get install cmake")
    source = tmp_path / "nmea"
    shutil.copytree(gga_pair, source, ignore=shutil.ignore_patterns("tests"))
    run(cmake, "-S", source, "-B", tmp_path / "build", f"-DCMAKE_INSTALL_PREFIX={tmp_path / 'prefix'}")
    run(cmake, "--build", tmp_path / "build")
    run(cmake, "--install", tmp_path / "build")
    prefix = tmp_path / "prefix"
    assert (prefix / "include" / "nmea.h").is_file()
    assert list(prefix.glob("lib*/libnmea.a")) and list(prefix.glob("lib*/cmake/nmea/nmeaConfig.cmake"))
    line = b"$GPGGA,193221.00,2037.72792,N,08704.08478,W,1,04,1.7,-30.40,M,-13.9,M,,*7D\n"
    out = run(prefix / "bin" / "nmea-c", "decode", input=line).stdout
    assert out.startswith(b'{"ok":true,') and b'"sentence":"GGA"' in out
    # and found by find_package() from another project
    consumer = tmp_path / "consumer"
    consumer.mkdir()
    (consumer / "app.c").write_text(APP)
    (consumer / "CMakeLists.txt").write_text("cmake_minimum_required(VERSION 3.13)\nproject(app C)\n"
                                             "find_package(nmea REQUIRED)\nadd_executable(app app.c)\n"
                                             "target_link_libraries(app PRIVATE nmea::nmea)\n")
    run(cmake, "-S", consumer, "-B", consumer / "build", f"-DCMAKE_PREFIX_PATH={prefix}")
    run(cmake, "--build", consumer / "build")
    assert run(consumer / "build" / "app").stdout == b"GGA satellites=4\n"


def test_plain_two_file_build(tmp_path: Path) -> None:
    cc = need("cc", "apt-get install gcc")
    for name in ("nmea.c", "nmea.h"):
        shutil.copy(GENERATED / "c" / name, tmp_path / name)
    (tmp_path / "app.c").write_text(APP)
    # Unoptimized: the answer is what counts here (make test builds nmea.c with -O2 -Werror too).
    run(cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-o", "app", "app.c", "nmea.c", cwd=tmp_path)
    assert run(tmp_path / "app").stdout == b"GGA satellites=4\n"
