//! The speed–accuracy trade: the scene's errors on a test-size measurement (snapshotted; times
//! never are), the committed measurements, and the choice of a tier by tolerance through the
//! binary (`wavy eval --tolerance`, `wavy solve --tolerance`, `wavy solve --error-estimate`).

use std::path::Path;
use std::process::{Command, Output};
use wavy::accuracy::measured::{committed, Query};
use wavy::runner::scenes::speed_accuracy::{reference_curves, tier_timings};
use wavy::runner::{load_spec, run_spec_file, RunOptions};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn wavy(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wavy"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("the wavy binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The columns of the scene's main table that do not depend on a clock.
const ERROR_COLUMNS: [&str; 9] = [
    "tier",
    "aspect_ratio",
    "tau_max_mpa",
    "status",
    "max_rel_error",
    "rms_rel_error",
    "dofs",
    "load_steps",
    "newton_iterations",
];

#[test]
fn test_size_measurement_orders_the_tiers_and_pins_the_errors() {
    let cache = tempfile::tempdir().unwrap();
    let mut opts = RunOptions::default();
    opts.sweep.cache_dir = cache.path().to_path_buf();
    let out = run_spec_file(&root().join("tests/specs/speed_accuracy_small.toml"), &opts).unwrap();
    let main = &out.tables[0];
    let col = |name: &str| main.header.iter().position(|h| h == name).unwrap();
    let error_of = |tier: &str| -> f64 {
        let row = main
            .rows
            .iter()
            .find(|r| r[col("tier")].to_string() == tier)
            .unwrap();
        row[col("max_rel_error")].to_string().parse().unwrap()
    };
    let reference = &out.tables[1];
    let j = reference
        .header
        .iter()
        .position(|h| h == "reference_uncertainty")
        .unwrap();
    let reference_error: f64 = reference.rows[0][j].to_string().parse().unwrap();
    // refinement reduces the error, the reference is better than every tier, and the linear
    // frictionless closed form is the least accurate at AR 0.1 (4.49 % against the full
    // reference of meshes 64–192, expected/speed_accuracy.csv; the test-size reference of meshes
    // 24–72 gives 4.49 % too)
    let (e16, e24, ew) = (
        error_of("fe-finite-16"),
        error_of("fe-finite-24"),
        error_of("westergaard"),
    );
    assert!(
        reference_error < e24 && e24 < e16 && e16 < ew,
        "{reference_error} {e24} {e16} {ew}"
    );
    assert!((0.005..0.2).contains(&ew), "{ew}");
    // the snapshot holds the errors and the deterministic costs, never a time
    let keep: Vec<usize> = ERROR_COLUMNS.iter().map(|c| col(c)).collect();
    let mut pinned = wavy::table::Table::new("", &ERROR_COLUMNS);
    for r in &main.rows {
        pinned.push(keep.iter().map(|&k| r[k].clone()).collect());
    }
    crate::in_snapshot_folder(|| {
        insta::assert_snapshot!("speed_accuracy__errors", pinned.to_csv());
        insta::assert_snapshot!("speed_accuracy__reference", reference.to_csv());
    });
}

/// The test-size reference file is what `wavy refine-reference` computes from its spec, byte for
/// byte; a spec whose `reference_meshes` differ from the file's is refused before any solve.
#[test]
fn refine_reference_writes_the_committed_test_size_reference() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("reference.csv");
    let cache = dir.path().join("cache");
    let spec = "tests/specs/speed_accuracy_small.toml";
    let o = wavy(&[
        "refine-reference",
        spec,
        "--out",
        out.to_str().unwrap(),
        "--cache",
        cache.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let committed =
        std::fs::read_to_string(root().join("tests/specs/data/speed_accuracy_small_reference.csv"))
            .unwrap();
    assert_eq!(std::fs::read_to_string(&out).unwrap(), committed);

    // the same spec elsewhere, its data files named by absolute path, asking for other meshes
    let specs = root().join("tests/specs");
    let text = std::fs::read_to_string(root().join(spec))
        .unwrap()
        .replace(
            "reference_meshes = [24, 36, 48, 72]",
            "reference_meshes = [24, 36, 48]",
        )
        .replace("\"data/", &format!("\"{}/data/", specs.display()))
        .replace("\"../../", &format!("\"{}/../../", specs.display()));
    let spec = dir.path().join("other_meshes.toml");
    std::fs::write(&spec, text).unwrap();
    let o = wavy(&[
        "run",
        spec.to_str().unwrap(),
        "--out",
        dir.path().to_str().unwrap(),
        "--cache",
        cache.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("limit of meshes [24, 36, 48, 72], the spec asks for [24, 36, 48]"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn committed_spec_has_a_timing_for_every_tier_and_case() {
    let spec = load_spec(&root().join("experiments/speed_accuracy.toml")).unwrap();
    let s = spec.speed_accuracy.as_ref().unwrap();
    let timings = tier_timings::read(&root().join("experiments").join(&s.timings)).unwrap();
    let mut n = 0;
    for ar in &s.aspect_ratios {
        for tau in &s.fe.tau_max_mpa {
            for tier in s.tiers.iter().flat_map(|t| t.timed_tiers()) {
                let t = timings.get(&tier, ar.get(), tau.get());
                assert!(t.is_some_and(|t| t.runs >= 3), "{tier} at {ar:?}, {tau:?}");
                n += 1;
            }
        }
    }
    // 3 aspect ratios × 2 τ_max × (11 tiers + the 2 meshes of fe-richardson-48-96 + the 3 of
    // fe-limit-48-64-96) of experiments/speed_accuracy.toml
    assert_eq!(n, 96);
}

#[test]
fn committed_measurements_answer_inside_their_region_only() {
    let table = committed().unwrap();
    let q = |ar: f64, tau: f64, a: f64| Query {
        aspect_ratio: ar,
        tau_max_mpa: tau,
        a_over_lambda: (a, a),
        physics: &[],
    };
    let loose = table.choose(0.5, &q(0.18, 0.1, 0.3), |_| true).unwrap();
    assert!(loose.tier.is_closed_form(), "{loose:?}");
    assert!(table.choose(0.005, &q(0.18, 0.1, 0.3), |_| true).is_ok());
    assert!(table.choose(1e-7, &q(0.18, 0.1, 0.3), |_| true).is_err());
    for outside in [q(0.05, 0.0, 0.3), q(0.2, 0.15, 0.3), q(0.2, 0.05, 0.48)] {
        assert!(
            table.choose(0.5, &outside, |_| true).is_err(),
            "{outside:?}"
        );
    }
    let order = table.fe_order().unwrap();
    assert!((1.0..=2.0).contains(&order), "{order}");
}

#[test]
fn eval_tolerance_names_its_tier_or_refuses_with_exit_2() {
    let ok = wavy(&[
        "eval",
        "--tolerance",
        "0.005",
        "--ar",
        "0.18",
        "--tau-max-mpa",
        "0.1",
        "--a-over-lambda",
        "0.3",
    ]);
    assert_eq!(ok.status.code(), Some(0), "{}", stderr(&ok));
    let err = stderr(&ok);
    assert!(
        err.contains("tolerance 0.005: tier ") && err.contains("measured error ≤"),
        "{err}"
    );
    let text = String::from_utf8_lossy(&ok.stdout);
    let row: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
    let p: f64 = row[6].parse().unwrap();
    assert!(p > 0.0 && p < 1.0, "{p}");

    for (args, flag) in [
        (
            vec![
                "--tolerance",
                "1e-7",
                "--ar",
                "0.18",
                "--tau-max-mpa",
                "0.1",
            ],
            "--tolerance = 1e-7",
        ),
        (vec!["--tolerance", "0.01", "--ar", "0.05"], "--ar = 0.05"),
        (
            vec![
                "--tolerance",
                "0.01",
                "--ar",
                "0.18",
                "--tau-max-mpa",
                "0.2",
            ],
            "--tau-max-mpa = 0.2",
        ),
        (vec!["--tolerance", "0", "--ar", "0.18"], "--tolerance = 0"),
    ] {
        let mut a = vec!["eval"];
        a.extend(args);
        a.extend(["--a-over-lambda", "0.3"]);
        let o = wavy(&a);
        assert_eq!(o.status.code(), Some(2), "{a:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(flag), "{a:?}: {}", stderr(&o));
        assert!(o.stdout.is_empty());
    }
    let below = wavy(&[
        "eval",
        "--tolerance",
        "0.01",
        "--ar",
        "0.18",
        "--a-over-lambda",
        "0.02",
    ]);
    assert_eq!(below.status.code(), Some(2));
    assert!(
        stderr(&below).contains("--a-over-lambda = 0.02"),
        "{}",
        stderr(&below)
    );
}

/// `wavy eval --tolerance 0.001` at (AR, τ_max) over the whole curve: the tier it says it
/// picked, and the largest relative difference of its answers at a/λ 0.05, 0.1, 0.25 and 0.45
/// from the committed converged reference.
fn eval_at_a_tenth_of_a_percent(ar: &str, tau_max_mpa: &str) -> (String, f64) {
    let o = wavy(&[
        "eval",
        "--tolerance",
        "0.001",
        "--ar",
        ar,
        "--tau-max-mpa",
        tau_max_mpa,
        "--a-over-lambda",
        "0.05",
        "0.1",
        "0.25",
        "0.45",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let spec = load_spec(&root().join("experiments/speed_accuracy.toml")).unwrap();
    let s = spec.speed_accuracy.as_ref().unwrap();
    let reference = reference_curves::read(&root().join("experiments").join(&s.reference)).unwrap();
    let limit = reference.case(
        ar.parse().unwrap(),
        tau_max_mpa.parse().unwrap(),
        s.physics(),
    );
    let text = String::from_utf8_lossy(&o.stdout);
    let (mut rows, mut tier, mut largest) = (0, String::new(), 0.0f64);
    for line in text.lines().skip(1) {
        let row: Vec<&str> = line.split(',').collect();
        tier = row[0].to_string();
        let (a, p): (f64, f64) = (row[5].parse().unwrap(), row[6].parse().unwrap());
        let r = limit
            .iter()
            .find(|r| (r.a_over_lambda - a).abs() < 1e-9)
            .unwrap();
        largest = largest.max((p / r.p_over_estar - 1.0).abs());
        rows += 1;
    }
    assert_eq!(rows, 4);
    assert!(
        stderr(&o).contains(&format!("tier {tier} (measured error ≤")),
        "{}",
        stderr(&o)
    );
    (tier, largest)
}

/// Frictionless, `--tolerance 0.001` picks the Richardson tier where it is measured to meet it
/// (AR 0.3: 0.086 % against 0.17 % for mesh 96), and what it answers is within the tolerance
/// of the converged reference (measured 0.02–0.09 %).
#[test]
fn eval_tolerance_picks_the_richardson_tier_and_meets_it() {
    let (tier, largest) = eval_at_a_tenth_of_a_percent("0.3", "0");
    assert_eq!(tier, "fe-richardson-48-96");
    assert!(largest <= 0.001, "{largest:.2e}");
}

/// With friction (AR 0.18, τ_max 0.1 MPa) the first-order Richardson tier errs 0.13 % and
/// `--tolerance 0.001` picks the mesh limit of meshes 48, 64 and 96 (measured 0.031 % over the
/// curve); at the four a/λ asked its answers lie within 0.014 % of the converged reference
/// (measured 2026-11-30).
#[test]
fn eval_tolerance_with_friction_picks_the_mesh_limit_tier_and_meets_it() {
    let (tier, largest) = eval_at_a_tenth_of_a_percent("0.18", "0.1");
    assert_eq!(tier, "fe-limit-48-64-96");
    assert!(largest <= 2e-4, "{largest:.2e}");
}

#[test]
fn solve_tolerance_picks_a_mesh_and_error_estimate_adds_a_column() {
    let o = wavy(&[
        "solve",
        "--ar",
        "0.1",
        "--tolerance",
        "0.05",
        "--until-a-over-lambda",
        "0.3",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stderr(&o).contains("tier fe-finite-"), "{}", stderr(&o));
    let refused = wavy(&[
        "solve",
        "--ar",
        "0.1",
        "--tolerance",
        "0.01",
        "--kappa-over-g",
        "10",
    ]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(
        stderr(&refused).contains("--kappa-over-g = 10"),
        "{}",
        stderr(&refused)
    );

    let o = wavy(&[
        "solve",
        "--ar",
        "0.1",
        "--mesh",
        "24",
        "--error-estimate",
        "--until-a-over-lambda",
        "0.3",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    let mut lines = text.lines();
    assert!(lines.next().unwrap().ends_with(",error_estimate"));
    let estimates: Vec<f64> = lines
        .filter_map(|l| l.rsplit(',').next().unwrap().parse().ok())
        .collect();
    assert!(estimates.len() > 10, "{text}");
    // a 24-element mesh errs by 0.22 % at AR 0.1 (expected/speed_accuracy.csv, fe-finite-24): every
    // estimate is positive and below 10 %
    assert!(
        estimates.iter().all(|e| (0.0..0.1).contains(e)),
        "{estimates:?}"
    );
}

#[test]
fn fe_section_error_estimate_adds_a_column_and_a_note_per_panel() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("estimate.toml");
    std::fs::write(
        &spec,
        r#"title = "error estimate"
[fe_vs_model]
aspect_ratios = [0.1]
tau_max_mpa = [0.0]
a_over_lambda = { min = 0.0, max = 0.5, count = 11 }
[fe_vs_model.models]
draw = ["westergaard"]
[fe_vs_model.fe]
tau_max_mpa = [0.0]
until_a_over_lambda = 0.3
mesh = "24"
error_estimate = true
[check]
rel_tol = 1e-5
abs_tol = 1e-6
"#,
    )
    .unwrap();
    let mut opts = RunOptions::default();
    opts.sweep.cache_dir = dir.path().join("cache");
    let out = run_spec_file(&spec, &opts).unwrap();
    let points = out.tables.iter().find(|t| t.name == "fe_points").unwrap();
    assert_eq!(points.header.last().unwrap(), "error_estimate");
    let estimates: Vec<f64> = points
        .rows
        .iter()
        .filter_map(|r| r.last().unwrap().to_string().parse().ok())
        .collect();
    // only the first points, before the 16-element curve's first contact, lack an estimate
    assert!(estimates.len() + 3 >= points.rows.len(), "{estimates:?}");
    assert!(
        estimates.iter().all(|e| (0.0..0.1).contains(e)),
        "{estimates:?}"
    );
    assert!(out.svg.contains("FE error ≤"), "no note in the figure");

    // a tolerance instead of a mesh: the section takes the mesh it needs; both is an error
    let both = std::fs::read_to_string(&spec)
        .unwrap()
        .replace("error_estimate = true", "tolerance = 0.05");
    std::fs::write(&spec, &both).unwrap();
    let e = format!("{:#}", run_spec_file(&spec, &opts).unwrap_err());
    assert!(
        e.contains("fe_vs_model.fe.tolerance") && e.contains("absent when `mesh` is set"),
        "{e}"
    );
    std::fs::write(&spec, both.replace("mesh = \"24\"\n", "")).unwrap();
    assert!(run_spec_file(&spec, &opts).is_ok());
}
