//! Pins every experiment's numbers and figure: one snapshot per spec for each CSV table (numbers
//! through the shared six-significant-digit formatter, `wavy::numfmt`) and one for its SVG.
//! Finite-element sections run at the spec's mesh (the coarse mesh fails at AR = 0.3) and with a fresh
//! cache (a temporary folder: no test reads or writes the developer's `.wavy-cache/`), so the
//! snapshots pin the solver itself, not a cache. The specs in [`HEAVY_SPECS`] take
//! tens of minutes (meshes up to 144 elements along the face): make test pins a test-size run of
//! each (`tests/scenes/speed_accuracy.rs`, `tests/scenes/two_scale.rs`, `tests/scenes/many_scale.rs`,
//! [`test_size_hysteresis`]), and CI's
//! `make stale` recomputes them in full and compares
//! with the committed figures. A snapshot only says "did our
//! output change?"; review changes with `cargo insta review`.

use crate::in_snapshot_folder;
use wavy::runner::{run_spec_file, RunOptions};

/// Specs too heavy for make test (see the module docs).
const HEAVY_SPECS: [&str; 5] = [
    "speed_accuracy.toml",
    "many_scale.toml",
    "two_scale.toml",
    "two_scale_separation.toml",
    "hysteresis.toml",
];

fn test_options(cache: &std::path::Path) -> RunOptions {
    let mut opts = RunOptions {
        fe_mesh_override: None,
        ..RunOptions::default()
    };
    opts.sweep.cache_dir = cache.to_path_buf();
    opts
}

#[test]
fn experiment_outputs() {
    let cache = tempfile::tempdir().unwrap();
    let opts = test_options(cache.path());
    in_snapshot_folder(|| {
        insta::glob!("../../experiments", "*.toml", |path| {
            if HEAVY_SPECS.iter().any(|h| path.ends_with(h)) {
                return;
            }
            let out =
                run_spec_file(path, &opts).unwrap_or_else(|e| panic!("{}: {e:#}", path.display()));
            assert!(
                out.incomplete.is_empty(),
                "{}: a committed figure rests on incomplete FE curves: {:?}",
                path.display(),
                out.incomplete
            );
            for table in &out.tables {
                let name = if table.name.is_empty() {
                    "snapshots__csv".to_string()
                } else {
                    format!("snapshots__csv_{}", table.name)
                };
                insta::assert_snapshot!(name, table.to_csv());
            }
            insta::assert_snapshot!("snapshots__svg", out.svg);
        });
    });
}

/// The hysteresis scene at test size (`tests/specs/hysteresis_small.toml`): frictionless and
/// frictional loops at two aspect ratios, the confinement series and the Richardson estimate of
/// W, on a coarser mesh; the full scene (its 48 loops take minutes) is recomputed by `make stale`.
#[test]
fn test_size_hysteresis() {
    let spec =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/specs/hysteresis_small.toml");
    let cache = tempfile::tempdir().unwrap();
    let out = run_spec_file(&spec, &test_options(cache.path())).unwrap();
    assert!(out.incomplete.is_empty(), "{:?}", out.incomplete);
    let [points, dissipation] = &out.tables[..] else {
        panic!("two tables: {:?}", out.tables.len())
    };
    in_snapshot_folder(|| {
        insta::assert_snapshot!("snapshots__hysteresis_small_csv", points.to_csv());
        insta::assert_snapshot!(
            "snapshots__hysteresis_small_dissipation",
            dissipation.to_csv()
        );
        insta::assert_snapshot!("snapshots__hysteresis_small_svg", out.svg);
    });
}

/// The first run computes its FE curves into an empty cache, the second reads them back: the
/// outputs are the same bytes either way.
#[test]
fn outputs_are_byte_identical_across_runs() {
    let spec =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/fig5_warman_ennos.toml");
    let cache = tempfile::tempdir().unwrap();
    let opts = test_options(cache.path());
    let a = run_spec_file(&spec, &opts).unwrap();
    let b = run_spec_file(&spec, &opts).unwrap();
    assert_eq!(a.svg, b.svg);
    assert_eq!(a.tables, b.tables);
}

/// Every committed snapshot belongs to a spec in `experiments/` (a removed or renamed spec
/// leaves none behind), or is named in full in the test file it comes from (`<test>__<name>.snap`,
/// from `tests/scenes/<test>.rs`): unreferenced snapshots are rejected.
#[test]
fn no_snapshot_without_its_spec() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut checked = 0;
    for e in std::fs::read_dir(root.join("tests/snapshots"))
        .unwrap()
        .flatten()
    {
        let name = e.file_name().to_string_lossy().into_owned();
        if let Some(spec) = name
            .strip_prefix("snapshots__")
            .and_then(|n| n.split_once('@'))
            .and_then(|(_, rest)| rest.strip_suffix(".snap"))
        {
            assert!(
                root.join("experiments").join(spec).exists(),
                "tests/snapshots/{name}: no experiments/{spec}; remove the snapshot"
            );
            assert!(
                !HEAVY_SPECS.contains(&spec),
                "tests/snapshots/{name}: {spec} is pinned at test size; remove the snapshot"
            );
        } else {
            let (test, snapshot) = name
                .strip_suffix(".snap")
                .and_then(|n| n.split_once("__"))
                .unwrap_or_else(|| panic!("tests/snapshots/{name}: not a snapshot name"));
            let file = root.join("tests/scenes").join(format!("{test}.rs"));
            let source = std::fs::read_to_string(file)
                .unwrap_or_else(|_| panic!("tests/snapshots/{name}: no tests/scenes/{test}.rs"));
            assert!(
                source.contains(&format!("\"{test}__{snapshot}\"")),
                "tests/snapshots/{name}: tests/scenes/{test}.rs has no snapshot `{snapshot}`; remove it"
            );
        }
        checked += 1;
    }
    assert!(checked >= 10, "{checked} snapshots");
}
