//! The library's layers point one way (docs/architecture.md): a module may use its own layer
//! and the layers below it, never one above. The command line is in the binary, so the
//! compiler already keeps the library from using it; this test keeps the core (models, fe,
//! fit) free of specs, runner, plotting and tables, and every other layer from reaching up.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Bottom first: each layer's top-level modules of `src/lib.rs`.
const LAYERS: &[(&str, &[&str])] = &[
    (
        "core",
        &[
            "models", "fe", "fit", "accuracy", "profile", "bem", "csv_text",
        ],
    ),
    (
        "output primitives",
        &["numfmt", "table", "plot", "vtk", "atomic_write"],
    ),
    ("specs", &["defaults", "spec"]),
    ("runner", &["runner"]),
];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|(_, ms)| ms.contains(&module))
}

/// The `.rs` files of a top-level module (`src/<m>.rs` or everything under `src/<m>/`).
fn files_of(module: &str) -> Vec<PathBuf> {
    let file = src().join(format!("{module}.rs"));
    if file.exists() {
        return vec![file];
    }
    crate::rust_files_under(&Path::new("src").join(module))
        .into_iter()
        .map(|f| Path::new(env!("CARGO_MANIFEST_DIR")).join(f))
        .collect()
}

/// Top-level modules named by `crate::<m>` in code (comments stripped).
fn crate_references(text: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(i) = rest.find("crate::") {
            let after = &rest[i + "crate::".len()..];
            if let Some(group) = after.strip_prefix('{') {
                // `crate::{a, b::c}`: the first name of each item
                let group = group.split('}').next().unwrap_or("");
                for item in group.split(',') {
                    let name = item.trim().split("::").next().unwrap_or("");
                    if !name.is_empty() {
                        found.insert(name.to_string());
                    }
                }
            }
            let name: String = after
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                found.insert(name);
            }
            rest = after;
        }
    }
    found
}

/// (file, module it reaches up to) for every upward reference in `module`'s files.
fn upward_references(module: &str) -> Vec<(PathBuf, String)> {
    let own = layer_of(module).expect("a layered module");
    let mut bad = vec![];
    for f in files_of(module) {
        let text = std::fs::read_to_string(&f).unwrap();
        for m in crate_references(&text) {
            match layer_of(&m) {
                Some(l) if l > own => bad.push((f.clone(), m)),
                _ => {}
            }
        }
    }
    bad
}

#[test]
fn every_library_module_has_a_layer() {
    let lib = std::fs::read_to_string(src().join("lib.rs")).unwrap();
    let modules: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.trim().strip_prefix("pub mod "))
        .map(|m| m.trim_end_matches(';'))
        .collect();
    assert!(modules.len() >= 9, "{modules:?}");
    for m in &modules {
        assert!(
            layer_of(m).is_some(),
            "src/lib.rs declares `{m}`, which tests/house/layers.rs places in no layer"
        );
    }
    assert!(
        !modules.contains(&"cli"),
        "the command line belongs to the binary"
    );
}

#[test]
fn no_module_uses_a_layer_above_its_own() {
    let mut checked = 0;
    let mut bad = vec![];
    for (_, modules) in LAYERS {
        for m in *modules {
            checked += files_of(m).len();
            bad.extend(upward_references(m));
        }
    }
    println!("{checked} source files checked");
    assert!(checked > 30, "{checked} files");
    assert!(
        bad.is_empty(),
        "upward references (file → module of a higher layer): {bad:#?}"
    );
}

#[test]
fn the_scan_sees_a_reference() {
    let refs = crate_references(
        "use crate::spec::Grid; // crate::runner\nlet x = crate::plot::padded_range(v);\nuse crate::{table::Table, numfmt};",
    );
    assert_eq!(
        refs.into_iter().collect::<Vec<_>>(),
        ["numfmt", "plot", "spec", "table"]
    );
}
