//! What the fuzz targets share: a replay of saved inputs without libFuzzer.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::process::ExitCode;

/// Runs `check` once on each file named on the command line, in order; stops at the first that
/// panics, naming it (the panic's message is printed before).
pub fn replay_files(check: fn(&[u8])) -> ExitCode {
    for path in std::env::args_os().skip(1) {
        let data = match std::fs::read(&path) {
            Ok(data) => data,
            Err(err) => {
                eprintln!("{}: {err}", path.to_string_lossy());
                return ExitCode::FAILURE;
            }
        };
        if catch_unwind(AssertUnwindSafe(|| check(&data))).is_err() {
            eprintln!("{}: the check failed on this input", path.to_string_lossy());
            return ExitCode::FAILURE;
        }
    }
    ExitCode::SUCCESS
}
