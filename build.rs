//! Fingerprints the finite-element solver's source so that cached FE results are keyed by the
//! exact solver that computed them (`WAVY_FE_SOURCE_SHA256`, read by `runner::fe_cases`).

use sha2::{Digest, Sha256};
use std::path::Path;

fn main() {
    let dir = Path::new("src/fe");
    println!("cargo:rerun-if-changed=src/fe");
    let mut files = vec![];
    collect(dir, &mut files);
    files.sort();
    let mut h = Sha256::new();
    for f in &files {
        println!("cargo:rerun-if-changed={}", f.display());
        h.update(f.to_string_lossy().as_bytes());
        h.update(std::fs::read(f).expect("readable solver source"));
    }
    let hex: String = h.finalize().iter().map(|b| format!("{b:02x}")).collect();
    println!("cargo:rustc-env=WAVY_FE_SOURCE_SHA256={hex}");
}

fn collect(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    if let Ok(entries) = std::fs::read_dir(dir) {
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                collect(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
}
