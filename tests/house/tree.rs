//! The tree shows the architecture: docs/architecture.md names every source file of `src/` (a
//! folder's `mod.rs` by its file or by its folder), no module name stands in two places, and no
//! folder holds more than [`MAX_FILES_PER_FOLDER`] source files side by side.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The most source files one folder holds before it wants sub-folders by concept.
const MAX_FILES_PER_FOLDER: usize = 15;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `src/`, relative to `src/`, sorted.
fn source_files() -> Vec<PathBuf> {
    crate::rust_files_under(Path::new("src"))
        .into_iter()
        .map(|f| f.strip_prefix("src").unwrap().to_path_buf())
        .collect()
}

/// The source files a text does not name in backticks: `` `a/b.rs` ``, or for `a/mod.rs` also
/// `` `a/` ``.
fn unnamed_in(text: &str, files: &[PathBuf]) -> Vec<PathBuf> {
    files
        .iter()
        .filter(|f| {
            let path = f.to_string_lossy().replace('\\', "/");
            let folder = path.strip_suffix("mod.rs").map(|d| format!("`{d}`"));
            !text.contains(&format!("`{path}`")) && folder.is_none_or(|d| !text.contains(&d))
        })
        .cloned()
        .collect()
}

#[test]
fn architecture_names_every_source_file() {
    let doc = std::fs::read_to_string(root().join("docs/architecture.md")).unwrap();
    let files = source_files();
    assert!(files.len() > 100, "{} source files", files.len());
    let unnamed = unnamed_in(&doc, &files);
    assert!(
        unnamed.is_empty(),
        "docs/architecture.md does not name these source files (a row each, with its job): {unnamed:?}"
    );
}

/// A file missing from the doc is named.
#[test]
fn a_file_missing_from_the_doc_is_named() {
    let files = [PathBuf::from("fe/mod.rs"), PathBuf::from("fe/curve.rs")];
    assert_eq!(
        unnamed_in("| `fe/` | the solver |", &files),
        [PathBuf::from("fe/curve.rs")]
    );
    assert!(unnamed_in("`fe/mod.rs`, `fe/curve.rs`", &files).is_empty());
}

#[test]
fn no_module_name_stands_in_two_places() {
    let mut places: BTreeMap<String, Vec<PathBuf>> = BTreeMap::new();
    for f in source_files() {
        let stem = f.file_stem().unwrap().to_string_lossy().into_owned();
        if !matches!(stem.as_str(), "mod" | "lib" | "main") {
            places.entry(stem).or_default().push(f);
        }
    }
    let twice: Vec<_> = places.into_iter().filter(|(_, fs)| fs.len() > 1).collect();
    assert!(twice.is_empty(), "module names in two places: {twice:?}");
}

#[test]
fn no_folder_is_crowded() {
    let mut per_folder: BTreeMap<PathBuf, usize> = BTreeMap::new();
    for f in source_files() {
        *per_folder
            .entry(f.parent().unwrap().to_path_buf())
            .or_default() += 1;
    }
    let crowded: Vec<_> = per_folder
        .into_iter()
        .filter(|&(_, n)| n > MAX_FILES_PER_FOLDER)
        .collect();
    assert!(
        crowded.is_empty(),
        "folders of src/ with more than {MAX_FILES_PER_FOLDER} source files (group them by concept): {crowded:?}"
    );
}
