//! The many-scale scene at test size (`tests/specs/many_scale_small.toml`; the full scene,
//! `experiments/many_scale.toml`, is recomputed by CI's `make stale`): at K = 1 the recursion is
//! Westergaard's law and the boundary elements solve the FE's layer in the linear limit, so both
//! follow the FE of a shallow wave (AR 0.03) closely; its tables are pinned by snapshots.

use std::path::Path;
use wavy::runner::{run_spec_file, RunOptions};
use wavy::table::Table;

/// The RMS relative error of `model` against the FE at K scales and τ_max 0, from the errors
/// table.
fn rms_error(errors: &Table, scales: f64, model: &str) -> f64 {
    let col = |name: &str| errors.header.iter().position(|h| h == name).unwrap();
    let (k, tau, m, rms) = (
        col("scales"),
        col("tau_max_mpa"),
        col("model"),
        col("rms_rel_error"),
    );
    let row = errors
        .rows
        .iter()
        .find(|r| {
            r[k].to_string() == scales.to_string()
                && r[tau].to_string() == "0"
                && r[m].to_string() == model
        })
        .unwrap_or_else(|| panic!("no row for K = {scales}, {model}"));
    row[rms].to_string().parse().unwrap()
}

#[test]
fn test_size_many_scale_scene() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cache = tempfile::tempdir().unwrap();
    let mut opts = RunOptions::default();
    opts.sweep.cache_dir = cache.path().to_path_buf();
    let out = run_spec_file(&root.join("tests/specs/many_scale_small.toml"), &opts).unwrap();
    assert!(out.incomplete.is_empty(), "{:?}", out.incomplete);
    let errors = &out.tables[1];
    // K = 1: Westergaard's law and the linear BEM against the finite-strain FE of AR 0.03 on 48
    // face elements (measured 2.5e-3 and 2.3e-3 RMS: the coarse mesh's own error)
    let single = rms_error(errors, 1.0, "recursion-westergaard");
    let bem = rms_error(errors, 1.0, "bem-linear");
    assert!(single < 3.5e-3 && bem < 3.5e-3, "{single} {bem}");
    // K = 2: the recursion is a model (R14), the BEM the same physics in the linear limit
    // (measured 0.103 against 0.0048 RMS, 21 times)
    let recursion = rms_error(errors, 2.0, "recursion-westergaard");
    let bem = rms_error(errors, 2.0, "bem-linear");
    assert!(recursion > 5.0 * bem, "{recursion} {bem}");
    crate::in_snapshot_folder(|| {
        insta::assert_snapshot!(
            "many_scale__many_scale_small_curves",
            out.tables[0].to_csv()
        );
        insta::assert_snapshot!("many_scale__many_scale_small_errors", errors.to_csv());
    });
}

/// A family steeper than the finite-strain solver is verified on is refused before solving,
/// naming the field and the profile; so is a frictional first τ_max.
#[test]
fn steep_families_and_frictional_first_curves_are_refused() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("tests/specs/many_scale_small.toml")).unwrap();
    let family = "{ ar0 = 0.03, gamma = 3, dimension = 1.3, scales = 2 }";
    assert!(text.contains(family));
    let steep = text.replace(
        family,
        "{ ar0 = 0.2, gamma = 3, dimension = 1.3, scales = 2 }",
    );
    let message = wavy::runner::Spec::parse(&steep, "many_scale_small.toml")
        .unwrap_err()
        .to_string();
    assert!(message.contains("many_scale.families"), "{message}");
    assert!(message.contains("weierstrass:0.2,3,1.3,2"), "{message}");
    assert!(message.contains("slope"), "{message}");
    let frictional_first = text.replace("tau_max_mpa = [0.0, 0.1]", "tau_max_mpa = [0.1, 0.0]");
    let message = wavy::runner::Spec::parse(&frictional_first, "many_scale_small.toml")
        .unwrap_err()
        .to_string();
    assert!(message.contains("many_scale.tau_max_mpa"), "{message}");
}
