"""The C pair's configuration key table (generated/c/nmea_ubx_config.h/.c) compiles under the
project's strict C99 flags and holds what the Python table holds: every key's id, name, type and
divisor, sorted by id, found by id and by name. (The Rust table tests itself: its #[cfg(test)].)"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "generated" / "python"))

from nmeaspec import ubx_config  # noqa: E402

C = ROOT / "generated" / "c"
FLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O1"]
TYPES = ["L", "U1", "U2", "U4", "U8", "I1", "I2", "I4", "I8", "X1", "X2", "X4", "X8", "E1", "E2", "E4", "R4", "R8"]

PROGRAM = r"""
#include <stdio.h>
#include "nmea_ubx_config.h"

int main(void) {
    size_t i;
    for (i = 0; i < NMEA_UBX_CFG_KEY_COUNT; i++) {
        const nmea_ubx_cfg_key *k = &nmea_ubx_cfg_keys[i];
        if (nmea_ubx_cfg_find(k->id) != k || nmea_ubx_cfg_find_name(k->name) != k) {
            return 1;
        }
        printf("%08lX %s %u %lu %lu\n", (unsigned long)k->id, k->name, (unsigned)k->type,
               (unsigned long)k->divisor, (unsigned long)nmea_ubx_cfg_value_size(k->id));
    }
    if (nmea_ubx_cfg_find(UINT32_C(0x40FE0001)) != NULL || nmea_ubx_cfg_find_name("CFG-RATE-MESA") != NULL) {
        return 2;
    }
    printf("%08lX\n", (unsigned long)NMEA_UBX_CFG_RATE_MEAS);
    return 0;
}
"""


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")
def test_the_c_table_is_the_python_table(tmp_path: Path) -> None:
    (tmp_path / "main.c").write_text(PROGRAM)
    binary = tmp_path / "keys"
    subprocess.run(["gcc", *FLAGS, "-I", str(C), "-o", str(binary), str(tmp_path / "main.c"),
                    str(C / "nmea_ubx_config.c")], check=True)
    out = subprocess.run([str(binary)], capture_output=True, text=True, check=True).stdout.splitlines()
    keys = sorted(ubx_config.database().keys, key=lambda k: k.id)
    assert out[:-1] == [f"{k.id:08X} {k.name} {TYPES.index(k.type)} {k.divisor} {k.size}" for k in keys]
    assert out[-1] == "30210001"
