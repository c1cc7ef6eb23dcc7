//! Print the median of every criterion benchmark of the last `cargo bench` (criterion's own
//! summary line is an interval around the mean), with its 95 % confidence interval, from
//! `target/criterion/<group>/<bench>/new/estimates.json`. Run by `make bench` after the
//! benchmarks.
use std::path::{Path, PathBuf};

fn estimates(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            let file = path.join("new").join("estimates.json");
            if file.is_file() {
                out.push(file);
            } else {
                estimates(&path, out);
            }
        }
    }
}

fn seconds(ns: f64) -> String {
    if ns >= 1e9 {
        format!("{:.3} s", ns / 1e9)
    } else if ns >= 1e6 {
        format!("{:.2} ms", ns / 1e6)
    } else if ns >= 1e3 {
        format!("{:.2} µs", ns / 1e3)
    } else {
        format!("{ns:.1} ns")
    }
}

fn main() {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("target"));
    let root = target.join("criterion");
    let mut files = Vec::new();
    estimates(&root, &mut files);
    if files.is_empty() {
        eprintln!("no criterion results under {}", root.display());
        std::process::exit(1);
    }
    println!("benchmark medians (95 % confidence interval of the median)");
    for file in files {
        let name = file
            .parent()
            .and_then(Path::parent)
            .and_then(|p| p.strip_prefix(&root).ok())
            .map(|p| p.display().to_string())
            .unwrap_or_default();
        let text = std::fs::read_to_string(&file).expect("readable estimates.json");
        let v: serde_json::Value = serde_json::from_str(&text).expect("criterion estimates JSON");
        let m = &v["median"];
        let (Some(point), Some(lo), Some(hi)) = (
            m["point_estimate"].as_f64(),
            m["confidence_interval"]["lower_bound"].as_f64(),
            m["confidence_interval"]["upper_bound"].as_f64(),
        ) else {
            eprintln!("{name}: no median in {}", file.display());
            continue;
        };
        println!(
            "  {name:<45} {:>10}  [{} – {}]",
            seconds(point),
            seconds(lo),
            seconds(hi)
        );
    }
}
