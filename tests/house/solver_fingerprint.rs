//! The finite-element cache is keyed by everything the solver compiles from: every source file
//! that the files of `src/fe/` reach through `crate::` paths (and those files in turn) is among
//! the files build.rs fingerprints (`wavy::runner::sweep::fe_cases::FE_SOURCE_FILES`). A solver
//! that starts importing a module build.rs does not hash fails here, naming the file.
//!
//! The reach is resolved here independently of build.rs, to the file: `crate::a::b::C` is
//! `src/a/b.rs` (or `src/a/b/mod.rs`) when that exists, else `src/a.rs` or `src/a/mod.rs`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use wavy::runner::sweep::fe_cases::FE_SOURCE_FILES;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The file that the path `segments` (after `crate::`) names: the longest prefix that is a
/// module file.
fn file_of(segments: &[&str]) -> Option<PathBuf> {
    (1..=segments.len()).rev().find_map(|n| {
        let module = segments[..n].join("/");
        [format!("src/{module}.rs"), format!("src/{module}/mod.rs")]
            .into_iter()
            .map(PathBuf::from)
            .find(|f| root().join(f).is_file())
    })
}

/// The files a source text names through `crate::` paths outside `//` comments.
fn files_named(text: &str) -> BTreeSet<PathBuf> {
    let mut named = BTreeSet::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        for (i, _) in code.match_indices("crate::") {
            let path: String = code[i + "crate::".len()..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            let segments: Vec<&str> = path.split("::").filter(|s| !s.is_empty()).collect();
            named.extend(file_of(&segments));
        }
    }
    named
}

/// Every file the solver's files reach, transitively, `src/fe/` included.
fn solver_reach() -> BTreeSet<PathBuf> {
    let mut reached: BTreeSet<PathBuf> = BTreeSet::new();
    let mut pending = crate::rust_files_under(Path::new("src/fe"));
    while let Some(file) = pending.pop() {
        if !reached.insert(file.clone()) {
            continue;
        }
        let text = std::fs::read_to_string(root().join(&file)).expect("a readable source file");
        pending.extend(files_named(&text));
    }
    reached
}

/// The files of `reach` that `fingerprinted` (build.rs's comma-separated list) leaves out.
fn unfingerprinted(reach: &BTreeSet<PathBuf>, fingerprinted: &str) -> Vec<PathBuf> {
    let hashed: BTreeSet<PathBuf> = fingerprinted.split(',').map(PathBuf::from).collect();
    reach
        .iter()
        .filter(|f| !hashed.contains(*f))
        .cloned()
        .collect()
}

#[test]
fn every_file_the_solver_reaches_is_fingerprinted() {
    let reach = solver_reach();
    // the solver reads the profile of its indenter (crate::profile)
    assert!(reach.contains(Path::new("src/profile.rs")), "{reach:?}");
    let missing = unfingerprinted(&reach, FE_SOURCE_FILES);
    assert!(
        missing.is_empty(),
        "the FE cache key (build.rs) does not hash {missing:?}, which the solver compiles from"
    );
}

/// The check fails on a solver import that build.rs would not hash: `src/profile.rs` left out of
/// the fingerprinted list is named.
#[test]
fn a_file_left_out_of_the_fingerprint_is_named() {
    let reach = solver_reach();
    let without_profile: Vec<&str> = FE_SOURCE_FILES
        .split(',')
        .filter(|f| *f != "src/profile.rs")
        .collect();
    let missing = unfingerprinted(&reach, &without_profile.join(","));
    assert_eq!(missing, vec![PathBuf::from("src/profile.rs")]);
}
