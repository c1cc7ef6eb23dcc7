//! What the tests that drive the `wavy` binary share.

use std::path::Path;
use std::process::{Command, Output};

/// Runs `wavy args` in `dir`.
pub fn wavy(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wavy"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the wavy binary runs")
}

/// The standard output of a finished run.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The standard error of a finished run.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The repository root.
pub fn here() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}
