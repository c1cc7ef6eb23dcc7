//! The `wavy` binary driven as a user would: `eval`, and every kind of bad input, with the
//! message text checked and nothing written.

use std::f64::consts::PI;
use std::path::Path;
use std::process::{Command, Output};

fn wavy(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wavy"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the wavy binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}
fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Rows of `wavy eval` as (a/λ, p̄/E*), checking the header.
fn eval_rows(o: &Output) -> Vec<(f64, f64)> {
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(o));
    let text = stdout(o);
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let (ix, ip) = (
        header
            .iter()
            .position(|h| *h == "a_over_lambda")
            .expect("a_over_lambda column"),
        header
            .iter()
            .position(|h| *h == "p_over_estar")
            .expect("p_over_estar column"),
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[ix].parse().unwrap(), f[ip].parse().unwrap())
        })
        .collect()
}

fn here() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn eval_westergaard_matches_r4_to_1e_12() {
    let o = wavy(
        &[
            "eval",
            "--model",
            "westergaard",
            "--ar",
            "0.18",
            "--a-over-lambda",
            "0.1",
            "0.25",
            "0.4",
        ],
        here(),
    );
    let rows = eval_rows(&o);
    assert_eq!(rows.len(), 3);
    for (x, p) in rows {
        let expected = PI * 0.18 * (PI * x).sin().powi(2); // R4
        assert!(
            (p - expected).abs() <= 1e-12 * expected,
            "{p} vs {expected}"
        );
    }
}

#[test]
fn eval_wnl_matches_r5_to_1e_12_and_inverts() {
    // R5 bracket-sq at AR = 0.1, τ = 0: A = −0.75459598, B = 1.08526713 (Table 1 by hand).
    let (a, b) = (-0.75459598_f64, 1.08526713_f64);
    let o = wavy(
        &[
            "eval",
            "--model",
            "wnl",
            "--ar",
            "0.1",
            "--tau-max-mpa",
            "0",
            "--a-over-lambda",
            "0.3",
        ],
        here(),
    );
    let (x, p) = eval_rows(&o)[0];
    let expected = PI * 0.1 * (PI * x).sin().powi(2) * (b + x * a * (PI * x).cos().powi(2));
    assert!(
        (p - expected).abs() <= 1e-12 * expected,
        "{p} vs {expected}"
    );
    // The inverse returns the a/λ that the forward call maps to the printed p̄/E*.
    let o = wavy(
        &[
            "eval",
            "--model",
            "wnl",
            "--ar",
            "0.1",
            "--p-over-estar",
            &p.to_string(),
        ],
        here(),
    );
    let (x_back, _) = eval_rows(&o)[0];
    assert!((x_back - 0.3).abs() <= 1e-12 * 0.3, "inverse gave {x_back}");
}

#[test]
fn eval_rejects_out_of_range_flags_with_exit_2() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["--ar", "-1", "--a-over-lambda", "0.2"],
            "--ar = -1 is out of range; allowed: > 0",
        ),
        (
            &[
                "--ar",
                "0.1",
                "--tau-max-mpa",
                "-0.1",
                "--a-over-lambda",
                "0.2",
            ],
            "--tau-max-mpa = -0.1 is out of range; allowed: >= 0",
        ),
        (
            &["--ar", "0.1", "--a-over-lambda", "0.6"],
            "--a-over-lambda = 0.6 is out of range; allowed: [0, 0.5]",
        ),
        (
            &["--ar", "0.1", "--p-over-estar", "-0.01"],
            "--p-over-estar = -0.01 is out of range; allowed: >= 0",
        ),
        (
            &["--ar", "0.1", "--p-over-estar", "1"],
            "--p-over-estar = 1 is out of range; allowed: [0, 0.314159",
        ),
    ];
    for (args, message) in cases {
        let mut all = vec!["eval", "--model", "westergaard"];
        all.extend_from_slice(args);
        let o = wavy(&all, here());
        assert_eq!(o.status.code(), Some(2), "{all:?}");
        assert!(stderr(&o).contains(message), "{all:?}: {}", stderr(&o));
        assert!(stdout(&o).is_empty(), "nothing on stdout for bad input");
    }
    let o = wavy(
        &[
            "eval",
            "--model",
            "wnl",
            "--reading",
            "literal",
            "--ar",
            "0.1",
            "--p-over-estar",
            "0.01",
        ],
        here(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("negative pressure"), "{}", stderr(&o));
}

/// Writes a variant of a committed spec into a temporary folder, runs it, and checks the
/// message and that no output appeared.
fn bad_spec(source: &str, from: &str, to: &str, expected: &[&str]) {
    let text = std::fs::read_to_string(here().join("experiments").join(source)).unwrap();
    assert!(text.contains(from), "{source} no longer contains `{from}`");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.toml"), text.replacen(from, to, 1)).unwrap();
    let o = wavy(&["run", "bad.toml", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(2), "exit code for {to}");
    let err = stderr(&o);
    for part in expected {
        assert!(
            err.contains(part),
            "message for `{to}` lacks `{part}`:\n{err}"
        );
    }
    assert!(
        !dir.path().join("out").exists(),
        "bad input must write nothing"
    );
}

#[test]
fn spec_with_unknown_field_names_it_with_line_and_column() {
    bad_spec(
        "fig2_correction_surfaces.toml",
        "title =",
        "colour = \"red\"\ntitle =",
        &["bad.toml", "unknown field `colour`", "line 2, column 1"],
    );
}

#[test]
fn spec_with_wrong_type_names_field_and_type() {
    bad_spec(
        "fig3_fe_vs_model.toml",
        "count = 101",
        "count = \"many\"",
        &[
            "bad.toml",
            "fe_vs_model.a_over_lambda.count",
            "invalid type: string \"many\", expected usize",
            "line 7",
        ],
    );
}

#[test]
fn spec_with_missing_field_names_it() {
    bad_spec(
        "fig3_fe_vs_model.toml",
        "draw = [\"westergaard\", \"wnl\"]",
        "",
        &["bad.toml", "fe_vs_model.models", "missing field `draw`"],
    );
    bad_spec(
        "fig5_warman_ennos.toml",
        "amplitude_mm = 0.04",
        "",
        &["bad.toml", "fingertip_area", "missing field `amplitude_mm`"],
    );
}

#[test]
fn spec_values_out_of_physical_range_name_field_value_and_range() {
    // λ ≤ 0
    bad_spec(
        "fig5_warman_ennos.toml",
        "wavelength_mm = 0.5",
        "wavelength_mm = -0.5",
        &[
            "bad.toml",
            "fingertip_area.wavelength_mm",
            "line 5, column 17",
            "value -0.5 is out of range; allowed: > 0",
        ],
    );
    // AR < 0
    bad_spec(
        "fig3_fe_vs_model.toml",
        "aspect_ratios = [0.1,",
        "aspect_ratios = [-0.1,",
        &[
            "fe_vs_model.aspect_ratios[0]",
            "value -0.1 is out of range; allowed: > 0",
        ],
    );
    // E* ≤ 0
    bad_spec(
        "fig5_warman_ennos.toml",
        "estar_mpa = 0.15",
        "estar_mpa = 0",
        &[
            "fingertip_area.estar_mpa",
            "value 0 is out of range; allowed: > 0",
        ],
    );
    // τ_max < 0
    bad_spec(
        "fig5_warman_ennos.toml",
        "tau_max_mpa = 0.05",
        "tau_max_mpa = -0.05",
        &[
            "fingertip_area.tau_max_mpa",
            "value -0.05 is out of range; allowed: >= 0",
        ],
    );
    bad_spec(
        "fig3_fe_vs_model.toml",
        "tau_max_mpa = [0.0,",
        "tau_max_mpa = [-0.01,",
        &["fe_vs_model.tau_max_mpa[0]", "allowed: >= 0"],
    );
    // a/λ ∉ [0, 0.5]
    bad_spec(
        "fig3_fe_vs_model.toml",
        "max = 0.5, count",
        "max = 0.6, count",
        &[
            "fe_vs_model.a_over_lambda.max",
            "(line 7, column 36)",
            "value 0.6 is out of range; allowed: [0, 0.5]",
        ],
    );
}

#[test]
fn reproduce_with_one_bad_spec_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let exp = dir.path().join("experiments");
    std::fs::create_dir(&exp).unwrap();
    for f in ["fig2_correction_surfaces.toml", "fig3_fe_vs_model.toml"] {
        std::fs::copy(here().join("experiments").join(f), exp.join(f)).unwrap();
    }
    let bad = std::fs::read_to_string(exp.join("fig3_fe_vs_model.toml"))
        .unwrap()
        .replace("count = 101", "count = 1");
    std::fs::write(exp.join("fig3_fe_vs_model.toml"), bad).unwrap();
    let o = wavy(&["reproduce"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("fe_vs_model.a_over_lambda.count"),
        "{}",
        stderr(&o)
    );
    assert!(
        stderr(&o).contains("value 1 is out of range; allowed: [2, 100000]"),
        "{}",
        stderr(&o)
    );
    assert!(
        !dir.path().join("figures").exists(),
        "no figure of the good spec either"
    );
}

/// `wavy solve` with friction: one CSV row per converged step up to the target a/λ, and bad
/// friction flags rejected with exit 2, naming the flag, the value and the range.
#[test]
fn solve_with_friction_prints_the_curve_and_rejects_bad_flags() {
    let o = wavy(
        &[
            "solve",
            "--ar",
            "0.1",
            "--tau-max-mpa",
            "0.05",
            "--mu",
            "0.5",
            "--mesh",
            "16",
            "--until-a-over-lambda",
            "0.2",
        ],
        here(),
    );
    let rows = eval_rows(&o);
    assert!(rows.len() >= 3, "{} rows", rows.len());
    assert!(rows.last().unwrap().0 >= 0.2);
    assert!(rows.windows(2).all(|w| w[1].1 > w[0].1));
    for (flag, value, message) in [
        ("--mu", "-1", "--mu = -1 is out of range; allowed: >= 0"),
        (
            "--tau-max-mpa",
            "-0.1",
            "--tau-max-mpa = -0.1 is out of range; allowed: >= 0",
        ),
        (
            "--estar-mpa",
            "0",
            "--estar-mpa = 0 is out of range; allowed: > 0",
        ),
    ] {
        let o = wavy(&["solve", "--ar", "0.1", flag, value], here());
        assert_eq!(o.status.code(), Some(2), "{flag}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{}", stderr(&o));
        assert!(stdout(&o).is_empty());
    }
}

/// A reader that closes the pipe early (`wavy eval … | head -1`) ends every command quietly
/// with exit 0: no panic, no error message.
#[test]
fn closed_stdout_pipe_ends_quietly_with_exit_0() {
    use std::process::Stdio;
    let many: Vec<String> = (0..20_000)
        .map(|i| format!("{}", i as f64 / 40_000.0))
        .collect();
    let mut eval = vec!["eval", "--model", "wnl", "--ar", "0.1", "--a-over-lambda"];
    eval.extend(many.iter().map(String::as_str));
    let solve = [
        "solve",
        "--ar",
        "0.1",
        "--mesh",
        "16",
        "--until-a-over-lambda",
        "0.2",
    ];
    for args in [&eval[..], &solve[..]] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_wavy"))
            .args(args)
            .current_dir(here())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take()); // the reader goes away before the first line
        let o = child.wait_with_output().unwrap();
        assert_eq!(o.status.code(), Some(0), "{}: {}", args[0], stderr(&o));
        assert!(stderr(&o).is_empty(), "{}: {}", args[0], stderr(&o));
    }
}
