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

/// `wavy solve --unload`: the loading rows, then the unloading rows back to zero load, each
/// with its branch in a last column; `--unload` with `--error-estimate` is refused.
#[test]
fn solve_with_unload_prints_both_branches() {
    let o = wavy(
        &[
            "solve",
            "--ar",
            "0.1",
            "--tau-max-mpa",
            "0.05",
            "--mesh",
            "16",
            "--until-a-over-lambda",
            "0.3",
            "--unload",
        ],
        here(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    let mut lines = text.lines();
    assert!(lines.next().unwrap().ends_with(",active_nodes,branch"));
    let rows: Vec<(f64, &str)> = lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[1].parse().unwrap(), f[6])
        })
        .collect();
    let turn = rows.iter().position(|r| r.1 == "unloading").unwrap();
    assert!(turn >= 3 && rows[..turn].iter().all(|r| r.1 == "loading"));
    assert!(rows[turn..].iter().all(|r| r.1 == "unloading"));
    let p_max = rows[turn - 1].0;
    assert!(rows.last().unwrap().0.abs() <= 1e-10 * p_max);
    let o = wavy(
        &["solve", "--ar", "0.1", "--unload", "--error-estimate"],
        here(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--error-estimate"), "{}", stderr(&o));
    let o = wavy(
        &["solve", "--ar", "0.1", "--until-p-over-estar", "0"],
        here(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--until-p-over-estar"),
        "{}",
        stderr(&o)
    );
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

/// Issue #9 (3, 4): a value that overflows or is negative is an error naming the inputs
/// (exit 1), never a NaN, ±inf or negative row with exit 0.
#[test]
fn eval_refuses_non_finite_and_negative_pressures() {
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "--model",
                "wnl",
                "--ar",
                "1e200",
                "--a-over-lambda",
                "0",
                "0.25",
            ],
            "--ar 1e200",
        ),
        (
            &[
                "--model",
                "westergaard",
                "--ar",
                "1e308",
                "--a-over-lambda",
                "0",
                "0.25",
            ],
            "not a finite number",
        ),
        (
            &[
                "--model",
                "wnl",
                "--reading",
                "literal",
                "--ar",
                "0.2",
                "--tau-max-mpa",
                "0.1",
                "--a-over-lambda",
                "0.02",
            ],
            "< 0 at a/λ = 0.02",
        ),
        (
            &[
                "--model",
                "wnl",
                "--ar",
                "0.6",
                "--tau-max-mpa",
                "2",
                "--a-over-lambda",
                "0.25",
            ],
            "negative mean pressure is unphysical",
        ),
        (
            &[
                "--model",
                "wnl",
                "--ar",
                "0.1",
                "--tau-max-mpa",
                "1e300",
                "--p-over-estar",
                "0.1",
            ],
            "overflows",
        ),
    ];
    for (args, message) in cases {
        let mut all = vec!["eval"];
        all.extend_from_slice(args);
        let o = wavy(&all, here());
        assert_eq!(o.status.code(), Some(1), "{all:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{all:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("negative pressure p/E* = NaN"));
        assert!(stdout(&o).is_empty(), "{all:?}: {}", stdout(&o));
    }
}

/// Issue #9 (5, 7): negative numbers with an exponent or in word form reach the range check,
/// and an unknown coefficient set is refused whatever the model.
#[test]
fn hyphenated_numbers_and_unknown_names_are_refused_by_flag() {
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "eval",
                "--model",
                "wnl",
                "--ar",
                "0.1",
                "--tau-max-mpa",
                "-1e-3",
                "--a-over-lambda",
                "0.1",
            ],
            "--tau-max-mpa = -0.001 is out of range; allowed: >= 0",
        ),
        (
            &[
                "eval",
                "--model",
                "wnl",
                "--ar",
                "-inf",
                "--a-over-lambda",
                "0.1",
            ],
            "--ar = -inf is out of range; allowed: > 0",
        ),
        (
            &[
                "eval",
                "--model",
                "wnl",
                "--ar",
                "0.1",
                "--a-over-lambda",
                "0.1",
                "-1e-3",
            ],
            "--a-over-lambda = -0.001 is out of range; allowed: [0, 0.5]",
        ),
        (
            &["solve", "--ar", "0.1", "--mu", "-1e-2"],
            "--mu = -0.01 is out of range; allowed: >= 0",
        ),
        (
            &[
                "eval",
                "--model",
                "westergaard",
                "--coefficients",
                "nonsense",
                "--ar",
                "0.1",
                "--a-over-lambda",
                "0.1",
            ],
            "nonsense",
        ),
    ];
    for (args, message) in cases {
        let o = wavy(args, here());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
        assert!(stdout(&o).is_empty());
    }
}

/// A spec in a scratch folder, with the given text (or bytes) under `name`.
fn scratch_spec(name: &std::ffi::OsStr, bytes: &[u8]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join(name), bytes).unwrap();
    dir
}

fn fig5_text() -> String {
    std::fs::read_to_string(here().join("experiments/fig5_warman_ennos.toml")).unwrap()
}

/// Issue #9 (6, 7): bad spec files and data files are input errors (exit 2) that say where,
/// in a message of bounded size, and nothing is written.
#[test]
fn bad_spec_and_data_files_exit_2_with_bounded_messages() {
    use std::os::unix::ffi::OsStrExt;
    let run = |dir: &Path, spec: &std::ffi::OsStr| {
        let o = Command::new(env!("CARGO_BIN_EXE_wavy"))
            .arg("run")
            .arg(spec)
            .args(["--out", "out"])
            .current_dir(dir)
            .output()
            .unwrap();
        assert!(!dir.join("out").exists(), "nothing written");
        o
    };
    // a 10⁶-element array with one bad value
    let text = std::fs::read_to_string(here().join("experiments/fig3_fe_vs_model.toml"))
        .unwrap()
        .replacen(
            "aspect_ratios = [0.1, 0.18, 0.3]",
            &format!("aspect_ratios = [{}-0.5]", "0.1,".repeat(1_000_000)),
            1,
        );
    let name = std::ffi::OsStr::new("big.toml");
    let d = scratch_spec(name, text.as_bytes());
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).len() < 4000, "{} bytes", stderr(&o).len());
    assert!(
        stderr(&o).contains("big.toml: field `fe_vs_model.aspect_ratios[1000000]`"),
        "{}",
        stderr(&o)
    );
    // invalid UTF-8, named by byte, line and column
    let mut bytes = fig5_text().into_bytes();
    let at = bytes.iter().position(|&b| b == b'\n').unwrap() + 1;
    bytes.insert(at, 0xff);
    let name = std::ffi::OsStr::new("latin.toml");
    let d = scratch_spec(name, &bytes);
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains(&format!("not valid UTF-8 at byte {at} (line 2, column 1)")),
        "{}",
        stderr(&o)
    );
    // a spec whose name is not UTF-8
    let name = std::ffi::OsStr::from_bytes(b"fig\xff.toml");
    let d = scratch_spec(name, fig5_text().as_bytes());
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("file name is not valid UTF-8"),
        "{}",
        stderr(&o)
    );
    // a measured-data file without provenance, and a folder in its place
    let name = std::ffi::OsStr::new("fig5.toml");
    let d = scratch_spec(name, fig5_text().as_bytes());
    std::fs::create_dir(d.path().join("data")).unwrap();
    std::fs::write(
        d.path().join("data/warman_ennos_2009.csv"),
        "load_n,area_mm2\n1,2\n",
    )
    .unwrap();
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("cannot use the data file"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("provenance"), "{}", stderr(&o));
    std::fs::remove_file(d.path().join("data/warman_ennos_2009.csv")).unwrap();
    std::fs::create_dir(d.path().join("data/warman_ennos_2009.csv")).unwrap();
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("cannot use the data file"),
        "{}",
        stderr(&o)
    );
}

/// Issue #9 (7): every output target is checked before the first is written: a folder in
/// place of the CSV leaves the SVG as it was.
#[test]
fn an_unwritable_target_leaves_every_output_as_it_was() {
    let name = std::ffi::OsStr::new("fig5.toml");
    let d = scratch_spec(name, fig5_text().as_bytes());
    let out = d.path().join("out");
    std::fs::create_dir_all(out.join("fig5.csv")).unwrap();
    std::fs::write(out.join("fig5.svg"), "old").unwrap();
    let o = wavy(&["run", "fig5.toml", "--out", "out"], d.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("a folder is in its place"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(out.join("fig5.svg")).unwrap(),
        "old"
    );
}

/// Issue #9 (1): a scene whose FE curve stops short of its target says so in the CSV, on the
/// figure and in the run's output, exits 1, and `wavy check` fails on it.
#[test]
fn an_incomplete_fe_curve_is_marked_and_fails_run_and_check() {
    let text = std::fs::read_to_string(here().join("experiments/fig3_fe_vs_model.toml"))
        .unwrap()
        .replace("aspect_ratios = [0.1, 0.18, 0.3]", "aspect_ratios = [0.1]")
        .replace(
            "tau_max_mpa = [0.0, 0.01, 0.05, 0.1, 0.15, 0.2]",
            "tau_max_mpa = [0.0]",
        )
        // the valley element ends at a/λ = 0.438
        .replace("[fe_vs_model.fe]", "[fe_vs_model.fe]\nmesh = \"4\"");
    let d = tempfile::tempdir().unwrap();
    std::fs::create_dir(d.path().join("experiments")).unwrap();
    std::fs::write(d.path().join("experiments/coarse.toml"), text).unwrap();
    let o = wavy(
        &[
            "run",
            "experiments/coarse.toml",
            "--out",
            "out",
            "--cache",
            "cache",
        ],
        d.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("stopped short of their target"),
        "{}",
        stderr(&o)
    );
    assert!(stdout(&o).contains("INCOMPLETE (coarse)"), "{}", stdout(&o));
    let mse = std::fs::read_to_string(d.path().join("out/coarse_mse.csv")).unwrap();
    assert!(
        mse.contains("incomplete: the contact is complete at a/λ = 0.4377"),
        "{mse}"
    );
    let svg = std::fs::read_to_string(d.path().join("out/coarse.svg")).unwrap();
    assert!(svg.contains("INCOMPLETE"));
    let o = wavy(
        &["check", "--expected", "out", "--cache", "cache"],
        d.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    assert!(
        stdout(&o).contains("FAIL coarse: incomplete finite-element curve"),
        "{}",
        stdout(&o)
    );
}
