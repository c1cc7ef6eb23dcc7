//! The robustness grid of issue 42, goal 6 (docs/verification.md, "Robustness grid"): every
//! combination of AR ∈ {0.05, 0.1, 0.2, 0.3, 0.4}, μ ∈ {0.2, 1, 100} and
//! τ_max ∈ {0, 0.05, 0.1, 0.2, 0.3} MPa (E* = 1 MPa; τ_max = 0 is frictionless, once per AR)
//! at each mesh of `--mesh`, loaded to a/λ 0.45 and unloaded by `wavy solve --unload`, one
//! case per core. One CSV row per case on stdout: whether the curve completed, its rows, the
//! mean of its `newton_iterations` column, its wall time, and the solver's message when it
//! stopped; a case still running after `--timeout-s` seconds is stopped and reported as such.
//!
//! Run: `make robustness` (after a release build; `--wavy` names the binary,
//! `--mesh 48,96,160` the meshes, `--tau-max-mpa 0,0.05,…` the columns of τ_max (every one by
//! default), `--timeout-s 1200` the limit per case: a frictional loop on mesh 160 takes minutes on
//! one core, docs/verification.md).
#[path = "common/child.rs"]
mod child;
use child::wait_within;
use rayon::prelude::*;
use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use wavy::csv_text::CsvTable;

const ASPECT_RATIOS: [f64; 5] = [0.05, 0.1, 0.2, 0.3, 0.4];
const FRICTION_COEFFICIENTS: [f64; 3] = [0.2, 1.0, 100.0];
const TAU_MAX_MPA: [f64; 5] = [0.0, 0.05, 0.1, 0.2, 0.3];

/// One case of the grid.
#[derive(Clone, Copy)]
struct Case {
    aspect_ratio: f64,
    tau_max_mpa: f64,
    friction_coefficient: f64,
    mesh: usize,
}

/// What one case did.
struct Outcome {
    completed: bool,
    rows: usize,
    mean_newton_iterations: f64,
    wall_s: f64,
    message: String,
}

fn cases(meshes: &[usize], taus: &[f64]) -> Vec<Case> {
    let mut cases = Vec::new();
    for &mesh in meshes {
        for aspect_ratio in ASPECT_RATIOS {
            for &tau_max_mpa in taus {
                // frictionless once per AR: μ plays no part
                let mus: &[f64] = if tau_max_mpa == 0.0 {
                    &FRICTION_COEFFICIENTS[..1]
                } else {
                    &FRICTION_COEFFICIENTS
                };
                for &friction_coefficient in mus {
                    cases.push(Case {
                        aspect_ratio,
                        tau_max_mpa,
                        friction_coefficient,
                        mesh,
                    });
                }
            }
        }
    }
    cases
}

/// The mean of the `newton_iterations` column of a `wavy solve` CSV, and its row count
/// (none, and a NaN mean, when the solve wrote no table).
fn newton_iterations(csv: &str) -> (usize, f64) {
    let Ok(table) = CsvTable::parse(csv) else {
        return (0, f64::NAN);
    };
    let Some(column) = table.column("newton_iterations") else {
        return (0, f64::NAN);
    };
    let its: Vec<f64> = table
        .rows
        .iter()
        .filter_map(|r| r.get(column)?.parse().ok())
        .collect();
    let mean = its.iter().sum::<f64>() / its.len() as f64;
    (its.len(), mean)
}

fn run(wavy: &str, case: Case, timeout: Duration) -> Outcome {
    let start = Instant::now();
    let mut child = Command::new(wavy)
        .args(["solve", "--unload", "--until-a-over-lambda", "0.45"])
        .args(["--ar", &case.aspect_ratio.to_string()])
        .args(["--tau-max-mpa", &case.tau_max_mpa.to_string()])
        .args(["--mu", &case.friction_coefficient.to_string()])
        .args(["--mesh", &case.mesh.to_string()])
        .env("RAYON_NUM_THREADS", "1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot run {wavy}: {e}"));
    // the pipes are drained while the case runs, so that a long curve never blocks on them
    let mut stdout = child.stdout.take().expect("piped stdout");
    let mut stderr = child.stderr.take().expect("piped stderr");
    let out_reader = std::thread::spawn(move || {
        let mut s = String::new();
        stdout.read_to_string(&mut s).map(|_| s)
    });
    let err_reader = std::thread::spawn(move || {
        let mut s = String::new();
        stderr.read_to_string(&mut s).map(|_| s)
    });
    let status = wait_within(&mut child, start, timeout);
    let wall_s = start.elapsed().as_secs_f64();
    let stdout = out_reader
        .join()
        .expect("stdout reader")
        .unwrap_or_default();
    let stderr = err_reader
        .join()
        .expect("stderr reader")
        .unwrap_or_default();
    let (rows, mean_newton_iterations) = newton_iterations(&stdout);
    let completed = status.is_some_and(|s| s.success());
    let message = match status {
        Some(_) if completed => String::new(),
        Some(_) => stderr.lines().last().unwrap_or("").replace(['"', ','], " "),
        None => format!("stopped after the time limit of {} s", timeout.as_secs()),
    };
    Outcome {
        completed,
        rows,
        mean_newton_iterations,
        wall_s,
        message,
    }
}

fn main() {
    let mut wavy = String::from("target/release/wavy");
    let mut meshes = vec![48, 96, 160];
    let mut taus = TAU_MAX_MPA.to_vec();
    let mut timeout = Duration::from_secs(1200);
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let value = args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--wavy" => wavy = value,
            "--mesh" => {
                meshes = value
                    .split(',')
                    .map(|m| m.parse().unwrap_or_else(|_| panic!("bad mesh {m}")))
                    .collect()
            }
            "--tau-max-mpa" => {
                taus = value
                    .split(',')
                    .map(|t| match t.parse() {
                        Ok(t) if TAU_MAX_MPA.contains(&t) => t,
                        _ => panic!("τ_max {t} is not one of the grid's {TAU_MAX_MPA:?}"),
                    })
                    .collect()
            }
            "--timeout-s" => {
                timeout = Duration::from_secs(
                    value
                        .parse()
                        .unwrap_or_else(|_| panic!("bad time limit {value}")),
                )
            }
            other => {
                panic!("unknown argument {other} (--wavy PATH, --mesh 48,96,160, --tau-max-mpa 0,0.05,0.1,0.2,0.3, --timeout-s 1200)")
            }
        }
    }
    let cases = cases(&meshes, &taus);
    let outcomes: Vec<Outcome> = cases.par_iter().map(|&c| run(&wavy, c, timeout)).collect();
    let date = Command::new("date")
        .args(["-u", "+%Y-%m-%d"])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    println!("# written by `make robustness` (examples/robustness_grid.rs): `wavy solve --unload --until-a-over-lambda 0.45` per case, E* = 1 MPa, the other physics at its defaults");
    println!(
        "# meshes {}, τ_max {} MPa, time limit {} s per case, {} cases at a time, {date}",
        meshes
            .iter()
            .map(|m| m.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        taus.iter()
            .map(|t| t.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        timeout.as_secs(),
        rayon::current_num_threads()
    );
    println!("aspect_ratio,tau_max_mpa,friction_coefficient,mesh,completed,rows,mean_newton_iterations,wall_s,message");
    for (c, o) in cases.iter().zip(&outcomes) {
        println!(
            "{},{},{},{},{},{},{:.2},{:.1},\"{}\"",
            c.aspect_ratio,
            c.tau_max_mpa,
            c.friction_coefficient,
            c.mesh,
            o.completed,
            o.rows,
            o.mean_newton_iterations,
            o.wall_s,
            o.message
        );
    }
    let failed = outcomes.iter().filter(|o| !o.completed).count();
    eprintln!("{failed} of {} cases did not complete", outcomes.len());
}
