"""The Rust crate, packed as crates.io serves it, as a path dependency of a fresh cargo project: one receiver family only
(`default-features = false, features = ["geos5"]`, still no_std) and `serde` with serde_json (the standard
sentences and GeoS-5's: clippy checks serde with every receiver feature)."""

from __future__ import annotations

import json
import os
import tarfile
from pathlib import Path

from .conftest import GENERATED, need, run

GEOS5_MAIN = r'''
use nmeaspec::{parse, Sentence};

fn main() {
    let reply = parse("$GPSGG,NQUERY,1,3,2,R,0,R,1,0,0,0,1,1,0*71").expect("a GeoS-5 reply");
    let Sentence::Geos5Nquery(nquery) = reply else { panic!("not GEOS5_NQUERY: {reply:?}") };
    // Without the teseo feature an ST sentence is a well-formed sentence the crate does not know.
    let st = parse("$PSTMSETPAR,1201,40,1*00").expect("frames");
    assert!(matches!(st, Sentence::Generic(_)), "{st:?}");
    let gga = parse("$GPGGA,193221.00,2037.72792,N,08704.08478,W,1,04,1.7,-30.40,M,-13.9,M,,*7D").expect("GGA");
    let mut buf = [0u8; nmeaspec::BUILD_CAPACITY];
    let bytes = nmeaspec::Geos5NqueryRequest::default().to_bytes(&mut buf).expect("a command");
    println!("{} {} {}", nquery, gga.sentence().unwrap_or("?"), core::str::from_utf8(bytes).unwrap().trim_end());
}
'''

SERDE_TEST = r'''
#[test]
fn serializes_a_parsed_sentence() {
    let gga = nmeaspec::parse("$GPGGA,193221.00,2037.72792,N,08704.08478,W,1,04,1.7,-30.40,M,-13.9,M,,*7D").unwrap();
    println!("JSON {}", serde_json::to_string(&gga).unwrap());
    let gsv = nmeaspec::parse("$GPGSV,3,1,12,28,14,150,41,09,15,254,41,10,43,192,47,13,06,081,36*7A").unwrap();
    println!("JSON {}", serde_json::to_string(&gsv).unwrap());
}
'''


def _packaged_crate(root: Path) -> Path:
    """The crate as crates.io would hand it to a user: `cargo package` of generated/rust, unpacked,
    with every source file of the crate in it (release-check packs the crate without building it;
    the projects here build only the receiver features they name)."""
    target = root / "package-target"
    run("cargo", "package", "--quiet", "--no-verify", "--allow-dirty", "--manifest-path", GENERATED / "rust" / "Cargo.toml",
        "--target-dir", target)
    (crate,) = (target / "package").glob("nmeaspec-*.crate")
    with tarfile.open(crate) as archive:
        archive.extractall(root / "vendor", filter="data")
    (unpacked,) = (root / "vendor").glob("nmeaspec-*")
    assert _rust_sources(unpacked) == _rust_sources(GENERATED / "rust")
    return unpacked.rename(root / "vendor" / "nmeaspec")


def _rust_sources(crate: Path) -> set[str]:
    return {str(path.relative_to(crate)) for path in (crate / "src").rglob("*.rs")}


def _project(root: Path, name: str, dependency: str) -> Path:
    if not (root / "vendor" / "nmeaspec").exists():
        _packaged_crate(root)
    project = root / name
    (project / "src").mkdir(parents=True)
    (project / "Cargo.toml").write_text(f'[package]\nname = "{name}"\nversion = "0.1.0"\nedition = "2021"\n\n'
                                        f'[dependencies]\n{dependency}\n')
    return project


def _cargo_env(root: Path) -> dict[str, str]:
    env = dict(os.environ)
    env["CARGO_TARGET_DIR"] = str(root / "target")
    return env


def test_one_vendor_without_default_features_and_with_serde(tmp_path: Path) -> None:
    """One project for both (the crate compiled once): a binary that reads GeoS-5's sentences and
    not ST's, and a test that serializes sentences with serde_json."""
    cargo = need("cargo", "install Rust (rustup)")
    project = _project(tmp_path, "geos5-serde",
                       'nmeaspec = { path = "../vendor/nmeaspec", default-features = false, features = ["geos5", "serde"] }'
                       '\n\n[dev-dependencies]\nserde_json = "1"')
    (project / "src" / "main.rs").write_text(GEOS5_MAIN)
    out = run(cargo, "run", "--quiet", cwd=project, env=_cargo_env(tmp_path)).stdout.decode()
    assert out == "$GPSGG,NQUERY,1,3,2,R,0,R,1,0,0,0,1,1,0*71 GGA $GPSGG,NQUERY*6C\n"
    # Without serde the crate depends on nothing.
    tree = run(cargo, "tree", "--edges", "normal", "--prefix", "none", "--no-default-features", "--features", "geos5",
               cwd=tmp_path / "vendor" / "nmeaspec", env=_cargo_env(tmp_path)).stdout
    assert [line.split()[0] for line in tree.decode().splitlines()] == ["nmeaspec"]
    (project / "tests").mkdir()
    (project / "tests" / "serde.rs").write_text(SERDE_TEST)
    out = run(cargo, "test", "--quiet", "--", "--nocapture", cwd=project, env=_cargo_env(tmp_path)).stdout.decode()
    objects = [json.loads(line[5:]) for line in out.splitlines() if line.startswith("JSON ")]
    gga = objects[0]["Gga"]
    assert gga["talker"] == "GP" and gga["time"] == "19:32:21.00" and gga["quality"] == "autonomous"
    assert gga["satellites"] == 4 and gga["altitude"] == -30.4 and abs(gga["lat"] - 20.6287987) < 1e-6
    assert gga["dgps_age"] is None and gga["checksum"] == "Upper"
    gsv = objects[1]["Gsv"]
    assert [s["prn"] for s in gsv["satellites"]] == [28, 9, 10, 13]
