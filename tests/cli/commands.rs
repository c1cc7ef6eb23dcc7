//! The `wavy` binary driven as a user would: `eval` and `solve`, and every kind of bad flag,
//! with the message text checked and nothing written (spec files: tests/cli/cli_specs.rs).

use crate::common::{here, stderr, stdout, wavy};
use std::f64::consts::PI;
use std::process::{Command, Output};

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

/// `wavy solve --points N` of a frictionless sinusoid: steps of a/λ of about the target over N,
/// so about N rows, each an edge event (45 by default); refused with friction and with a
/// profile, exit 2.
#[test]
fn solve_takes_loading_points_for_a_frictionless_sinusoid() {
    let args = ["solve", "--ar", "0.1", "--until-a-over-lambda", "0.3"];
    let o = wavy(&[&args[..], &["--points", "10"]].concat(), here());
    let rows = eval_rows(&o);
    assert!((7..=10).contains(&rows.len()), "{} rows", rows.len());
    assert!(rows.last().unwrap().0 >= 0.3);
    // every step but the last (which stops at the first node beyond the target) ends on the
    // first face node 0.03 beyond the edge: within a tenth of 0.03 below (the edge lies between
    // nodes) and the largest face spacing of mesh 48 above, 4/(5 · 48) ≈ 0.017
    let steps: Vec<f64> = rows.windows(2).map(|w| w[1].0 - w[0].0).collect();
    let within = |s: &f64| (0.027..=0.047).contains(s);
    assert!(steps[..steps.len() - 1].iter().all(within), "{steps:?}");
    // each point up to the target is an edge event of the node-by-node curve (steps of 3·10⁻⁵,
    // below every face spacing): the same a/λ, and p̄ to 10⁻⁷ relative (measured 3·10⁻⁹, the
    // events' gap tolerance)
    let node_by_node = eval_rows(&wavy(&[&args[..], &["--points", "10000"]].concat(), here()));
    assert!(
        node_by_node.len() > 2 * rows.len(),
        "{}",
        node_by_node.len()
    );
    let last = node_by_node.last().unwrap().0;
    for &(a, p) in rows.iter().filter(|r| r.0 <= last) {
        let same = node_by_node.iter().find(|q| (q.0 - a).abs() < 1e-9);
        let &(_, q) = same.unwrap_or_else(|| panic!("a/λ {a} is not a node-by-node event"));
        assert!((p / q - 1.0).abs() < 1e-7, "a/λ {a}: p̄ {p} against {q}");
    }
    // without --points, steps of 0.01 to a/λ 0.45: about 40 points at mesh 96 (43 measured), not
    // one per face node (91)
    let default = eval_rows(&wavy(&["solve", "--ar", "0.1", "--mesh", "96"], here()));
    assert!((38..=45).contains(&default.len()), "{} rows", default.len());
    for (asked, says) in [
        (
            vec!["--ar", "0.1", "--tau-max-mpa", "0.1", "--points", "10"],
            "--points = 10: is for a frictionless curve; a frictional one steps node by node",
        ),
        (
            vec!["--profile", "1:0.1,4:0.01", "--points", "10"],
            "--points = 10: is for a single sinusoid; a profile steps from contact event to contact event",
        ),
        (
            vec!["--ar", "0.1", "--points", "1"],
            "--points = 1 is out of range; allowed: [2, 10000]",
        ),
    ] {
        let o = wavy(&[&["solve"], &asked[..]].concat(), here());
        assert_eq!(o.status.code(), Some(2), "{asked:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{asked:?}: {}", stderr(&o));
        assert!(stdout(&o).is_empty());
    }
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
    assert!(lines.next().unwrap().ends_with(
        ",active_nodes,contact_fraction,patches,stick_fraction,stick_half_width_over_lambda,friction_work_over_estar_lambda2,branch"
    ));
    let rows: Vec<(f64, &str)> = lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[1].parse().unwrap(), *f.last().unwrap())
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

/// `--unloading-substeps N` retraces each interval between the loading rows' loads in N steps:
/// a frictionless loop, which lets no node go between them, has N unloading rows per loading
/// row. N must be a whole number ≥ 1, and needs `--unload` and the finite-element solver.
#[test]
fn unloading_substeps_split_each_unloading_interval() {
    let branches = |substeps: &str| {
        let loop_args = "solve --ar 0.1 --mesh 16 --until-a-over-lambda 0.3 --unload";
        let mut args: Vec<&str> = loop_args.split(' ').collect();
        args.extend(["--unloading-substeps", substeps]);
        let o = wavy(&args, here());
        assert!(o.status.success(), "{}", stderr(&o));
        let text = stdout(&o);
        let last: Vec<String> = (text.lines().skip(1))
            .map(|l| l.rsplit(',').next().unwrap().to_string())
            .collect();
        let loading = last.iter().filter(|b| *b == "loading").count();
        (loading, last.len() - loading)
    };
    let (loading, unloading) = branches("3");
    assert!(loading >= 3, "{loading} loading rows");
    assert_eq!(unloading, 3 * loading);
    assert_eq!(branches("1"), (loading, loading));
    for (args, flag) in [
        (
            &["--unload", "--unloading-substeps", "0"][..],
            "--unloading-substeps",
        ),
        (&["--unloading-substeps", "2"][..], "--unload"),
        (
            &["--unload", "--unloading-substeps", "2", "--solver", "bem"][..],
            "--unloading-substeps",
        ),
    ] {
        let o = wavy(&[&["solve", "--ar", "0.1"][..], args].concat(), here());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(flag), "{args:?}: {}", stderr(&o));
    }
}

/// `--coarsen-at-aspect 4` joins the deep columns three to one: a profile's curve has the same
/// events, its mean pressures within COARSENED_PRESSURE_RTOL of the mesh that keeps every column.
/// Below 1, with a measured-error option (`--tolerance`, `--error-estimate`) or with the
/// boundary-element solver it is refused, naming the flag.
#[test]
fn coarsened_columns_keep_a_profiles_curve() {
    // measured 2026-11-29: at most 1.2e-4 over the 49 rows of this curve
    const COARSENED_PRESSURE_RTOL: f64 = 2.5e-4;
    let pressures = |extra: &[&str]| {
        let base = "solve --profile 1:0.1,8:0.05 --mesh 64 --until-contact-fraction 0.6";
        let args: Vec<&str> = base.split(' ').chain(extra.iter().copied()).collect();
        let o = wavy(&args, here());
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        let text = stdout(&o);
        let p = text
            .lines()
            .next()
            .unwrap()
            .split(',')
            .position(|c| c == "p_over_estar");
        let p = p.expect("a p_over_estar column");
        let rows: Vec<f64> = (text.lines().skip(1))
            .map(|l| l.split(',').nth(p).unwrap().parse().unwrap())
            .collect();
        rows
    };
    let full = pressures(&[]);
    let coarsened = pressures(&["--coarsen-at-aspect", "4"]);
    assert_eq!(full.len(), coarsened.len());
    let largest = (full.iter().zip(&coarsened))
        .map(|(f, c)| (c / f - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(largest > 0.0, "the mesh did not change");
    assert!(largest <= COARSENED_PRESSURE_RTOL, "{largest:e}");
    for args in [
        &["--coarsen-at-aspect", "0.5"][..],
        &["--coarsen-at-aspect", "4", "--tolerance", "0.01"][..],
        &["--coarsen-at-aspect", "4", "--error-estimate"][..],
        &["--coarsen-at-aspect", "4", "--solver", "bem"][..],
    ] {
        let o = wavy(&[&["solve", "--ar", "0.1"][..], args].concat(), here());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("--coarsen-at-aspect"),
            "{args:?}: {}",
            stderr(&o)
        );
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

/// `wavy eval --profile`: the recursive superposition's contact fraction per mean pressure, the
/// same as the library's; a profile whose orders do not nest, or a pressure at or beyond the big
/// wave's full contact, is invalid input naming the flag. `wavy solve` takes the same profile.
#[test]
fn eval_and_solve_take_a_weierstrass_profile() {
    let profile = "weierstrass:0.05,3,1.3,3";
    let o = wavy(
        &[
            "eval",
            "--model",
            "westergaard",
            "--profile",
            profile,
            "--p-over-estar",
            "0.01",
            "0.1",
        ],
        here(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "model,reading,coefficients,profile,tau_max_mpa,p_over_estar,contact_fraction,extrapolated"
    );
    let p: wavy::profile::Profile = profile.parse().unwrap();
    for (line, pressure) in lines[1..].iter().zip([0.01, 0.1]) {
        let expected =
            wavy::models::profile_contact(&p, wavy::models::Westergaard::new, pressure).unwrap();
        let fraction: f64 = line.rsplit(',').nth(1).unwrap().parse().unwrap();
        assert_eq!(fraction, expected.contact_fraction, "{line}");
        assert!(line.starts_with("westergaard,,,\"1:0.05,3:"), "{line}");
    }
    for (args, message) in [
        (
            ["--profile", "1:0.1,4:0.05,6:0.05", "--p-over-estar", "0.05"],
            "--profile",
        ),
        (
            ["--profile", profile, "--p-over-estar", "0.2"],
            "--p-over-estar = 0.2",
        ),
        (
            [
                "--profile",
                "weierstrass:0.05,3,2.5,3",
                "--p-over-estar",
                "0.1",
            ],
            "D = 2.5",
        ),
    ] {
        let mut all = vec!["eval", "--model", "westergaard"];
        all.extend(args);
        let o = wavy(&all, here());
        assert_eq!(o.status.code(), Some(2), "{all:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{all:?}: {}", stderr(&o));
        assert!(stdout(&o).is_empty());
    }
    let o = wavy(
        &[
            "solve",
            "--profile",
            profile,
            "--kinematics",
            "linear",
            "--until-contact-fraction",
            "0.3",
        ],
        here(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

/// `--profile`: a two-scale curve with its contact fraction and patches; a profile the mesh
/// cannot resolve, or bad syntax, is invalid input (exit 2) naming the harmonic.
#[test]
fn solve_takes_a_profile() {
    let o = wavy(
        &[
            "solve",
            "--profile",
            "1:0.1,8:0.1",
            "--mesh",
            "64",
            "--until-contact-fraction",
            "0.4",
        ],
        here(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    let last: Vec<&str> = text.lines().last().unwrap().split(',').collect();
    assert!(last[6].parse::<f64>().unwrap() >= 0.4, "{last:?}");
    let o = wavy(
        &["solve", "--profile", "1:0.1,16:0.1", "--mesh", "32"],
        here(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("harmonic 16"), "{}", stderr(&o));
    let o = wavy(&["solve", "--profile", "1:0.1;8:0.1"], here());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("order:aspect_ratio"), "{}", stderr(&o));
}

/// `--solver bem`: the curve's rows with the FE's columns and branches, the loop's energy on
/// stderr, and what the boundary-element solver does not model refused with exit 2, naming it.
#[test]
fn solve_with_the_boundary_element_solver() {
    let dir = tempfile::tempdir().unwrap();
    let o = wavy(
        &[
            "solve",
            "--solver",
            "bem",
            "--ar",
            "0.01",
            "--kappa-over-g",
            "2.1667",
            "--mu",
            "0.5",
            "--tau-max-mpa",
            "1000",
            "--half-plane",
            "--until-a-over-lambda",
            "0.2",
            "--points",
            "5",
            "--grid-points",
            "1024",
            "--unload",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        format!("{},branch", wavy::fe::CurvePoint::CSV_HEADER)
    );
    let rows: Vec<&str> = lines.collect();
    let loading = rows.iter().filter(|r| r.ends_with(",loading")).count();
    assert!(loading >= 5 && rows.len() == 2 * loading - 1, "{text}");
    let last_loading: f64 = rows[loading - 1]
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((last_loading - 0.2).abs() < 1e-9, "{last_loading}");
    assert!(
        stderr(&o).contains("work of friction at the face"),
        "{}",
        stderr(&o)
    );
    for (args, says) in [
        (
            vec!["--ar", "0.1", "--kinematics", "finite"],
            "small-strain",
        ),
        (vec!["--ar", "0.1", "--mesh", "8"], "--mesh = given"),
        (
            vec!["--ar", "0.1", "--grid-points", "1000"],
            "--grid-points = 1000",
        ),
    ] {
        let o = wavy(
            &[&["solve", "--solver", "bem"], &args[..]].concat(),
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
    }
}
