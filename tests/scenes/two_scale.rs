//! The two-scale scene at test size (`tests/specs/two_scale_small.toml`; the full scene,
//! `experiments/two_scale.toml`, is recomputed by CI's `make stale`): the FE contact splits
//! into several patches, and its tables (curves, the models' errors against the FE) are pinned
//! by snapshots.

use std::path::Path;
use wavy::runner::{run_spec_file, RunOptions};

#[test]
fn test_size_two_scale_scene() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cache = tempfile::tempdir().unwrap();
    let mut opts = RunOptions::default();
    opts.sweep.cache_dir = cache.path().to_path_buf();
    let out = run_spec_file(&root.join("tests/specs/two_scale_small.toml"), &opts).unwrap();
    assert!(out.incomplete.is_empty(), "{:?}", out.incomplete);
    let curves = &out.tables[0];
    let errors = &out.tables[1];
    // the FE contact splits into several patches on the way
    let patches = curves.header.iter().position(|h| h == "patches").unwrap();
    let most = curves
        .rows
        .iter()
        .filter_map(|r| r[patches].to_string().parse::<f64>().ok())
        .fold(0.0, f64::max);
    assert!(most >= 2.0, "{most}");
    crate::in_snapshot_folder(|| {
        insta::assert_snapshot!("two_scale__two_scale_small_curves", curves.to_csv());
        insta::assert_snapshot!("two_scale__two_scale_small_errors", errors.to_csv());
    });
}

/// The contact maps draw each profile's curve at the first τ_max, which the scene calls
/// frictionless: a spec whose first τ_max is not 0 is refused, naming the field.
#[test]
fn contact_maps_need_a_frictionless_first_curve() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("tests/specs/two_scale_small.toml")).unwrap();
    assert!(text.contains("tau_max_mpa = [0.0, 0.1]"));
    let frictional_first = text.replace("tau_max_mpa = [0.0, 0.1]", "tau_max_mpa = [0.1, 0.0]");
    let err = wavy::runner::Spec::parse(&frictional_first, "two_scale_small.toml").unwrap_err();
    let message = err.to_string();
    assert!(message.contains("two_scale.tau_max_mpa"), "{message}");
    assert!(message.contains("frictionless"), "{message}");
    let without_maps = frictional_first.replace("contact_maps = [0]", "contact_maps = []");
    wavy::runner::Spec::parse(&without_maps, "two_scale_small.toml").expect("no map, no rule");
}

/// `mesh_by_order` gives the profiles whose finer harmonic has an order their own mesh; an
/// entry for an order no profile has, an order twice or no elements is refused, naming the field.
#[test]
fn mesh_by_order_names_orders_of_the_profiles() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("tests/specs/two_scale_small.toml")).unwrap();
    assert!(text.contains("mesh = 64\n"));
    let with = |entries: &str| {
        text.replace(
            "mesh = 64\n",
            &format!("mesh = 64\nmesh_by_order = {entries}\n"),
        )
    };
    wavy::runner::Spec::parse(&with("[[8, 48]]"), "two_scale_small.toml").expect("n = 8 on 48");
    for bad in ["[[16, 96]]", "[[8, 48], [8, 96]]", "[[8, 0]]"] {
        let err = wavy::runner::Spec::parse(&with(bad), "two_scale_small.toml").unwrap_err();
        let message = err.to_string();
        assert!(
            message.contains("two_scale.mesh_by_order"),
            "{bad}: {message}"
        );
    }
}
