//! The frictional-speed table of `make bench` (docs/performance.md):
//!
//! 1. per-curve wall time (median of `--runs` runs, one thread), DOFs, load steps, Newton
//!    iterations on the converged path, tangent assemblies and factorisations of every
//!    attempt, for AR ∈ {0.1, 0.18, 0.3} × τ_max ∈ {0, 0.2} MPa (E* = 1 MPa) at the
//!    default mesh, and the ratio frictional / frictionless per AR;
//! 2. the Fig. 3 sweep from an empty cache (`wavy run experiments/fig3_fe_vs_model.toml`
//!    with a fresh cache folder, all cores), median of `--runs` runs;
//! 3. cost growth at AR 0.3 with and without friction, mesh 16 to `--max-mesh` (one run
//!    each, in a child process that also reports its peak memory `VmHWM`): the exponent
//!    of wall time against DOFs (least squares in log–log), split into its factors
//!    (load steps, tangent assemblies per step, time per assembly), and the growth from mesh 48
//!    to 192 of the wall time and of the time per assembly (issue 42 goal 3); frictionless both
//!    node by node (the scenes) and in steps of 0.01 in a/λ (`wavy solve`'s default,
//!    `StepOptions::da_target`).
//!
//! Run: `make bench` (after a release build; `--wavy` names the binary of step 2).
//! `--no-branch-switch` measures steps 1 and 3 without the semismooth choice of the
//! friction branches (`NewtonOptions::semismooth_friction` off): the same build with and
//! without it.
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::time::Instant;
#[path = "../benches/common/mod.rs"]
mod common;
use common::peak_memory_kb;
use wavy::fe::{
    solve_curve, Curve, Interface, Kinematics, LayerProblem, MeshLevel, NewtonOptions, SolveOptions,
};
use wavy::runner::scenes::speed_accuracy::time_tiers::median;

const CHILD: &str = "WAVY_SPEED_TABLE_CHILD";

/// Set (to any value) for `--no-branch-switch`, inherited by the child processes.
const NO_BRANCH_SWITCH: &str = "WAVY_SPEED_TABLE_NO_BRANCH_SWITCH";

/// The layer problem at aspect ratio `ar`, frictional when `τ_max/E*` > 0 (the project's
/// other defaults).
fn problem(ar: f64, tau_max_over_estar: f64) -> LayerProblem {
    LayerProblem {
        kinematics: Kinematics::Finite,
        interface: Interface::coulomb_orowan(
            wavy::defaults::friction_coefficient(),
            tau_max_over_estar,
            wavy::defaults::elastic_slip_over_element(),
        ),
        ..wavy::defaults::layer_problem(ar)
    }
}

fn options(mesh: MeshLevel) -> SolveOptions {
    SolveOptions {
        mesh,
        newton: NewtonOptions {
            semismooth_friction: std::env::var_os(NO_BRANCH_SWITCH).is_none(),
            ..Default::default()
        },
        ..Default::default()
    }
}

/// Wall time (s) and the curve.
fn timed_curve(ar: f64, tau: f64, mesh: MeshLevel) -> (f64, Curve) {
    let start = Instant::now();
    let curve = solve_curve(&problem(ar, tau), &options(mesh), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap_or_else(|f| panic!("AR {ar}, τ_max/E* {tau}, {mesh:?}: {}", f.error));
    (start.elapsed().as_secs_f64(), curve)
}

/// The mesh of `n` elements along the contact face and `n/2` across (as `--mesh N`).
fn face_mesh(n: usize) -> MeshLevel {
    MeshLevel::Elements { nx: n, ny: n / 2 }
}

/// Child mode (`AR,τ,N,da`): one curve (`da`: `StepOptions::da_target`), then
/// `seconds steps assemblies factorisations kB`.
fn child(spec: &str) -> ! {
    let v: Vec<f64> = spec
        .split(',')
        .map(|x| x.parse().expect("number"))
        .collect();
    let mut opts = options(face_mesh(v[2] as usize));
    opts.steps.da_target = v[3];
    let start = Instant::now();
    let c = match solve_curve(&problem(v[0], v[1]), &opts, &mut |_| {
        ControlFlow::Continue(())
    }) {
        Ok(c) => c,
        Err(f) => {
            println!("failed: {}", f.error);
            std::process::exit(0)
        }
    };
    let t = start.elapsed().as_secs_f64();
    println!(
        "{t} {} {} {} {}",
        c.points.len(),
        c.work.tangent_assemblies,
        c.work.factorisations,
        peak_memory_kb().unwrap_or(0)
    );
    std::process::exit(0)
}

/// Least-squares slope of `ln y` against `ln x`.
fn log_slope(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

struct Args {
    runs: usize,
    max_mesh: usize,
    wavy: Option<PathBuf>,
}

fn args() -> Args {
    let mut a = Args {
        runs: 3,
        max_mesh: 192,
        wavy: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().unwrap_or_else(|| panic!("{flag} needs a value"));
        match flag.as_str() {
            "--runs" => a.runs = value().parse().expect("--runs: a count ≥ 1"),
            "--max-mesh" => a.max_mesh = value().parse().expect("--max-mesh: elements"),
            "--wavy" => a.wavy = Some(PathBuf::from(value())),
            "--no-branch-switch" => std::env::set_var(NO_BRANCH_SWITCH, "1"),
            other => panic!(
                "unknown flag {other} (--runs N, --max-mesh N, --wavy PATH, --no-branch-switch)"
            ),
        }
    }
    assert!(a.runs >= 1, "--runs must be ≥ 1");
    a
}

fn per_curve_table(runs: usize) {
    let tau = 0.2; // τ_max = 0.2 MPa at E* = 1 MPa
    println!("## Per curve, default mesh (48×24), one thread, median of {runs} runs\n");
    println!("| AR | τ_max (MPa) | wall (s) | DOFs | load steps | Newton its (converged path) | tangent assemblies | factorisations |");
    println!("|---|---|---|---|---|---|---|---|");
    let mut ratios = Vec::new();
    for ar in [0.1, 0.18, 0.3] {
        let mut walls = [0.0; 2];
        for (i, t) in [0.0, tau].into_iter().enumerate() {
            let mut times = Vec::new();
            let mut last = None;
            for _ in 0..runs {
                let (s, c) = timed_curve(ar, t, MeshLevel::Default);
                times.push(s);
                last = Some(c);
            }
            let c = last.expect("runs ≥ 1");
            walls[i] = median(times);
            println!(
                "| {ar} | {t} | {:.2} | {} | {} | {} | {} | {} |",
                walls[i],
                MeshLevel::Default.unknowns(),
                c.points.len(),
                c.points.iter().map(|p| p.newton_iterations).sum::<usize>(),
                c.work.tangent_assemblies,
                c.work.factorisations
            );
        }
        ratios.push((ar, walls[1] / walls[0]));
    }
    println!();
    for (ar, r) in ratios {
        println!("frictional / frictionless wall time, AR {ar}: {r:.2}");
    }
    println!();
}

fn cold_sweep(wavy: &PathBuf, runs: usize) {
    let mut times = Vec::new();
    for _ in 0..runs {
        let dir = tempfile::tempdir().expect("temporary folder");
        let start = Instant::now();
        let status = std::process::Command::new(wavy)
            .args(["run", "experiments/fig3_fe_vs_model.toml", "--cache"])
            .arg(dir.path().join("cache"))
            .arg("--out")
            .arg(dir.path().join("out"))
            .stdout(std::process::Stdio::null())
            .status()
            .expect("run the wavy binary");
        assert!(status.success(), "the Fig. 3 sweep failed");
        times.push(start.elapsed().as_secs_f64());
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "Fig. 3 sweep (18 curves) from an empty cache, {cores} cores: {:.1} s (median of {runs}; runs: {})\n",
        median(times.clone()),
        times.iter().map(|t| format!("{t:.1}")).collect::<Vec<_>>().join(", ")
    );
}

fn cost_growth(max_mesh: usize) {
    let exe = std::env::current_exe().expect("this executable");
    let meshes: Vec<usize> = [16, 24, 32, 48, 64, 96, 128, 192]
        .into_iter()
        .filter(|&n| n <= max_mesh)
        .collect();
    println!("## Cost growth, AR 0.3, one run per mesh (child process each)\n");
    println!("| τ_max (MPa) | steps of a/λ | mesh | DOFs | wall (s) | load steps | tangent assemblies | factorisations | s per assembly | peak memory (MB) |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (tau, da) in [(0.0, 0.0), (0.0, 0.01), (0.2, 0.0)] {
        let steps_of = if da > 0.0 {
            da.to_string()
        } else {
            "node by node".into()
        };
        let mut rows: Vec<[f64; 5]> = Vec::new();
        let mut fitted: Vec<usize> = Vec::new();
        for &n in &meshes {
            let out = std::process::Command::new(&exe)
                .env(CHILD, format!("0.3,{tau},{n},{da}"))
                .output()
                .expect("child curve");
            assert!(out.status.success(), "mesh {n}, τ {tau}: child failed");
            let text = String::from_utf8_lossy(&out.stdout);
            if let Some(reason) = text.trim().strip_prefix("failed: ") {
                println!("| {tau} | {steps_of} | {n} | | no curve: {reason} (left out of the fit) | | | | | |");
                continue;
            }
            let v: Vec<f64> = text
                .split_whitespace()
                .map(|x| x.parse().expect("child output"))
                .collect();
            let d = face_mesh(n).unknowns() as f64;
            println!(
                "| {tau} | {steps_of} | {n} | {d} | {:.2} | {} | {} | {} | {:.2e} | {:.1} |",
                v[0],
                v[1],
                v[2],
                v[3],
                v[0] / v[2],
                v[4] / 1024.0
            );
            rows.push([d, v[0], v[1], v[2], v[0] / v[2]]);
            fitted.push(n);
        }
        let col = |j: usize| rows.iter().map(|r| r[j]).collect::<Vec<f64>>();
        let (d, wall, steps, asm, per) = (col(0), col(1), col(2), col(3), col(4));
        let per_step: Vec<f64> = asm.iter().zip(&steps).map(|(a, s)| a / s).collect();
        let upper = d.len() / 2;
        let at = |n: usize| fitted.iter().position(|&m| m == n).map(|i| rows[i]);
        if let (Some(coarse), Some(fine)) = (at(48), at(192)) {
            println!(
                "\nτ_max {tau} MPa, steps {steps_of}: mesh 192 over mesh 48, wall {:.0}×, time per assembly {:.0}× (goal 3: wall at most 1.1 × that)",
                fine[1] / coarse[1],
                fine[4] / coarse[4]
            );
        }
        println!(
            "\nτ_max {tau} MPa, steps {steps_of}: wall ∝ DOFs^{:.2} (mesh {}–{}; upper half {}–{}: ^{:.2}) = steps ^{:.2} × assemblies per step ^{:.2} × time per assembly ^{:.2}\n",
            log_slope(&d, &wall),
            fitted[0],
            fitted[fitted.len() - 1],
            fitted[upper],
            fitted[fitted.len() - 1],
            log_slope(&d[upper..], &wall[upper..]),
            log_slope(&d, &steps),
            log_slope(&d, &per_step),
            log_slope(&d, &per),
        );
    }
}

fn main() {
    if let Ok(spec) = std::env::var(CHILD) {
        child(&spec);
    }
    let a = args();
    println!("# wavy frictional speed (make bench)\n");
    if std::env::var_os(NO_BRANCH_SWITCH).is_some() {
        println!("(without the semismooth friction-branch switch)\n");
    }
    per_curve_table(a.runs);
    if let Some(w) = &a.wavy {
        cold_sweep(w, a.runs);
    }
    cost_growth(a.max_mesh);
}
