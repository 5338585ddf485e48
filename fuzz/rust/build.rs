//! Builds the generated C pair (and its AIS pair), the shim the differential target calls it through, and the
//! field mutator the targets share (../c/field_mutator.c). With clang and libFuzzer (the default
//! feature), the C code carries libFuzzer's coverage counters too, so the fuzzer also steers by the
//! C pair's branches.
use std::process::Command;

fn main() {
    let generated = "../../generated/c";
    let mut build = cc::Build::new();
    build
        .file(format!("{generated}/nmea.c"))
        .file(format!("{generated}/nmea_ais.c"))
        .file("c_shim.c")
        .file("../c/field_mutator.c")
        .include(generated)
        .flag("-std=c99")
        .warnings(false);
    let libfuzzer = std::env::var_os("CARGO_FEATURE_LIBFUZZER").is_some();
    if libfuzzer && Command::new("clang").arg("--version").output().is_ok() {
        build.compiler("clang").flag("-fsanitize-coverage=inline-8bit-counters,pc-table,trace-cmp");
    }
    build.compile("nmea_c");
    let sources = [
        format!("{generated}/nmea.c"),
        format!("{generated}/nmea.h"),
        format!("{generated}/nmea_ais.c"),
        format!("{generated}/nmea_ais.h"),
        "c_shim.c".into(),
        "../c/field_mutator.c".into(),
    ];
    for path in sources {
        println!("cargo:rerun-if-changed={path}");
    }
}
