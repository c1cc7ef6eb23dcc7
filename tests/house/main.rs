//! The house rules: the layers point one way, the file structure, and the docs agree with the CSVs
//! they restate.
//!
//! One test binary per concern, each module one file as it was before the grouping (fewer binaries
//! link faster, and the tests of a binary share its threads).

mod doc_tables;
mod file_structure;
mod layers;
mod solver_fingerprint;
mod tree;

use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir` (relative to the crate root), sorted, relative to the crate root.
pub fn rust_files_under(dir: &Path) -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = vec![];
    let mut stack = vec![root.join(dir)];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("a readable folder").flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p.strip_prefix(root).expect("under the crate").to_path_buf());
            }
        }
    }
    out.sort();
    out
}
