//! A mesh study of the finite-element curve, one curve per core (docs/replication.md R11,
//! "Friction on fine meshes"; docs/performance.md): for each case `AR:τ_max` of `--cases` and
//! each mesh of `--mesh`, `wavy solve --ar AR --tau-max-mpa τ --mesh N` (the curve's defaults
//! otherwise), the finest meshes first. One CSV row per curve on stdout: whether it completed,
//! how far it got, its points, the mean of its `newton_iterations` column, its wall time, and
//! how far its p̄(a) lies over a/λ ∈ [0.05, 0.45] from the case's finest complete curve and
//! from the mesh limit `p₀ + c₁/n + c₂/n²` through the complete curves of `--limit-meshes`
//! (`accuracy::extrapolation`), with that limit's spread.
//!
//! `nonmonotone_part` is the largest amount, over the a/λ grid, by which this mesh's deviation
//! from the finest complete curve exceeds the next coarser mesh's: zero when refining never
//! moves the curve away from the finest one (empty on the coarsest mesh and on meshes finer than
//! the finest complete one, a curve stopped by its time limit).
//!
//! A case `AR:τ_max:N` stops at mesh N.
//!
//! Run: `make mesh-study` (after a release build; `--wavy`, `--cases`, `--mesh`,
//! `--limit-meshes`, `--curves DIR`, `--jobs N` (all cores by default) and `--timeout-s`
//! override its defaults). Each curve goes to `DIR/arAR_tauT_mN.csv` (DIR by default
//! `.wavy-tmp/mesh_study`) with its wall time and exit status in `….csv.wall`; a curve already
//! there is read, not solved again, so the summary can be redone without the solves.
#[path = "common/child.rs"]
mod child;
use child::wait_within;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use wavy::accuracy::extrapolation::mesh_limit_with_spread;
use wavy::fe::{convergence::p_at, CurvePoint};

/// Where the deviations are taken: 41 values of a/λ from 0.05 to 0.45 (the speed–accuracy grid).
fn a_grid() -> Vec<f64> {
    (0..=40).map(|i| 0.05 + 0.01 * i as f64).collect()
}

/// One curve of the study.
#[derive(Clone, Copy)]
struct Case {
    aspect_ratio: f64,
    tau_max_mpa: f64,
    mesh: usize,
}

impl Case {
    fn file(&self, dir: &Path) -> PathBuf {
        dir.join(format!(
            "ar{}_tau{}_m{}.csv",
            self.aspect_ratio, self.tau_max_mpa, self.mesh
        ))
    }
}

/// A solved (or stopped) curve: its points, whether `wavy solve` completed, its wall time.
struct Solved {
    points: Vec<CurvePoint>,
    completed: bool,
    wall_s: f64,
}

/// Solves `case` into its file (the file's curve when already there).
fn solve(wavy: &str, case: Case, dir: &Path, timeout: Duration) -> Solved {
    let file = case.file(dir);
    let wall_file = file.with_extension("csv.wall");
    if !wall_file.exists() {
        let out = std::fs::File::create(&file).expect("create a curve file");
        let start = Instant::now();
        let mut child = Command::new(wavy)
            .args(["solve", "--ar", &case.aspect_ratio.to_string()])
            .args(["--tau-max-mpa", &case.tau_max_mpa.to_string()])
            .args(["--mesh", &case.mesh.to_string()])
            .env("RAYON_NUM_THREADS", "1")
            .stdout(out)
            .stderr(Stdio::null())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot run {wavy}: {e}"));
        let status = wait_within(&mut child, start, timeout);
        let rc = status.and_then(|s| s.code()).unwrap_or(124);
        let wall = format!("{},{rc}\n", start.elapsed().as_secs_f64());
        std::fs::write(&wall_file, wall).expect("write a curve's wall time");
    }
    let wall = std::fs::read_to_string(&wall_file).expect("read a curve's wall time");
    let (wall_s, rc) = wall.trim().split_once(',').expect("wall_s,rc");
    let text = std::fs::read_to_string(&file).expect("read a curve");
    let points = text
        .lines()
        .skip(1)
        .map(|row| row.parse().expect("a wavy solve row"))
        .collect();
    Solved {
        points,
        completed: rc == "0",
        wall_s: wall_s.parse().expect("wall seconds"),
    }
}

/// `p/p_ref − 1` on the a/λ grid (None where either curve does not reach).
fn deviation(curve: &[CurvePoint], reference: &[CurvePoint]) -> Vec<Option<f64>> {
    a_grid()
        .into_iter()
        .map(|a| Some(p_at(curve, a)? / p_at(reference, a)? - 1.0))
        .collect()
}

fn largest(values: &[Option<f64>]) -> Option<f64> {
    values.iter().flatten().map(|v| v.abs()).reduce(f64::max)
}

fn list<T: std::str::FromStr>(text: &str) -> Vec<T> {
    text.split(',')
        .map(|v| v.parse().unwrap_or_else(|_| panic!("bad list entry {v}")))
        .collect()
}

/// What to solve and how (the command line; the defaults are `make mesh-study`'s).
struct Study {
    wavy: String,
    /// `(AR, τ_max in MPa, finest mesh)`.
    cases: Vec<(f64, f64, usize)>,
    meshes: Vec<usize>,
    limit_meshes: Vec<usize>,
    curves: PathBuf,
    jobs: usize,
    timeout: Duration,
}

fn case(text: &str) -> (f64, f64, usize) {
    let f: Vec<&str> = text.split(':').collect();
    let finest = f.get(2).map_or(usize::MAX, |m| m.parse().expect("mesh"));
    match f[..] {
        [ar, tau, ..] => (ar.parse().expect("AR"), tau.parse().expect("τ_max"), finest),
        _ => panic!("a case is AR:τ_max or AR:τ_max:finest mesh, not {text}"),
    }
}

fn study_from_args() -> Study {
    let mut study = Study {
        wavy: String::from("target/release/wavy"),
        cases: "0.3:0.1,0.3:0.2,0.18:0.1,0.18:0.2,0.3:0:192,0.18:0:192"
            .split(',')
            .map(case)
            .collect(),
        meshes: vec![48, 64, 96, 128, 160, 192, 256, 320],
        limit_meshes: vec![64, 96, 128, 160, 192, 256],
        curves: PathBuf::from(".wavy-tmp/mesh_study"),
        jobs: 0,
        timeout: Duration::from_secs(450),
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let value = args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--wavy" => study.wavy = value,
            "--cases" => study.cases = value.split(',').map(case).collect(),
            "--mesh" => study.meshes = list(&value),
            "--limit-meshes" => study.limit_meshes = list(&value),
            "--curves" => study.curves = PathBuf::from(value),
            "--jobs" => study.jobs = value.parse().expect("jobs"),
            "--timeout-s" => study.timeout = Duration::from_secs(value.parse().expect("seconds")),
            other => panic!(
                "unknown argument {other} (--wavy PATH, --cases 0.3:0.1,0.18:0:192, --mesh 48,96, \
                 --limit-meshes 64,96,128, --curves DIR, --jobs N, --timeout-s S)"
            ),
        }
    }
    study.meshes.sort_unstable();
    study
}

/// The summary rows of one case (module documentation); `of_case(mesh)` is its curve there.
fn summarise<'a>(
    (ar, tau): (f64, f64),
    meshes: &[usize],
    limit_meshes: &[usize],
    of_case: impl Fn(usize) -> Option<&'a Solved>,
) {
    let finest = *meshes
        .iter()
        .rev()
        .find(|&&m| of_case(m).is_some_and(|s| s.completed))
        .expect("a complete curve in every case");
    let reference = &of_case(finest).expect("finest").points;
    let fit: Vec<(usize, &Solved)> = limit_meshes
        .iter()
        .filter_map(|&m| of_case(m).filter(|s| s.completed).map(|s| (m, s)))
        .collect();
    let fit_meshes: Vec<usize> = fit.iter().map(|(m, _)| *m).collect();
    let limit: Vec<Option<(f64, f64)>> = a_grid()
        .into_iter()
        .map(|a| {
            let values: Option<Vec<f64>> = fit.iter().map(|(_, s)| p_at(&s.points, a)).collect();
            mesh_limit_with_spread(&fit_meshes, &values?)
        })
        .collect();
    let spread = limit.iter().flatten().map(|l| l.1).reduce(f64::max);
    let fmt = |v: Option<f64>| v.map(|v| format!("{v:.3e}")).unwrap_or_default();
    let mut coarser: Option<Vec<Option<f64>>> = None;
    for &m in meshes {
        let s = of_case(m).expect("solved");
        let dev = deviation(&s.points, reference);
        // beyond the finest complete curve the deviation is that curve's own error
        let nonmonotone = coarser.as_ref().filter(|_| m <= finest).map(|c| {
            dev.iter()
                .zip(c)
                .filter_map(|(d, c)| Some(((*d)?.abs() - (*c)?.abs()).max(0.0)))
                .fold(0.0, f64::max)
        });
        let vs_limit: Vec<Option<f64>> = a_grid()
            .into_iter()
            .zip(&limit)
            .map(|(a, l)| Some(p_at(&s.points, a)? / l.as_ref()?.0 - 1.0))
            .collect();
        let its: f64 = s.points.iter().map(|p| p.newton_iterations as f64).sum();
        println!(
            "{ar},{tau},{m},{},{:.4},{},{:.2},{:.2},{finest},{},{},{},{}",
            s.completed,
            s.points.last().map_or(0.0, |p| p.a_over_lambda),
            s.points.len(),
            its / s.points.len() as f64,
            s.wall_s,
            fmt(largest(&dev)),
            fmt(nonmonotone),
            fmt(largest(&vs_limit)),
            fmt(spread),
        );
        coarser = Some(dev);
    }
}

fn main() {
    let study = study_from_args();
    std::fs::create_dir_all(&study.curves).expect("create the curves folder");
    let mut all: Vec<Case> = study
        .cases
        .iter()
        .flat_map(|&(aspect_ratio, tau_max_mpa, finest)| {
            study
                .meshes
                .iter()
                .filter(move |&&m| m <= finest)
                .map(move |&mesh| Case {
                    aspect_ratio,
                    tau_max_mpa,
                    mesh,
                })
        })
        .collect();
    all.sort_by_key(|c| std::cmp::Reverse(c.mesh)); // the longest first
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(study.jobs)
        .build()
        .expect("a thread pool");
    let solved: Vec<Solved> = pool.install(|| {
        all.par_iter()
            .map(|&c| solve(&study.wavy, c, &study.curves, study.timeout))
            .collect()
    });
    println!("# written by `make mesh-study` (examples/mesh_study.rs): `wavy solve --ar AR --tau-max-mpa T --mesh N` per curve, one core each (wall_s: of that run), stopped after {} s; deviations over a/λ 0.05–0.45; limit p0 + c1/n + c2/n^2 through the complete curves of meshes {:?}", study.timeout.as_secs(), study.limit_meshes);
    println!("aspect_ratio,tau_max_mpa,mesh,completed,reach_a_over_lambda,points,mean_newton_iterations,wall_s,finest_mesh,max_rel_dev_from_finest,nonmonotone_part,max_rel_error_vs_limit,limit_spread");
    for &(ar, tau, finest_asked) in &study.cases {
        let meshes: Vec<usize> = (study.meshes.iter().copied())
            .filter(|&m| m <= finest_asked)
            .collect();
        let of_case = |m: usize| {
            all.iter()
                .position(|c| c.aspect_ratio == ar && c.tau_max_mpa == tau && c.mesh == m)
                .map(|i| &solved[i])
        };
        summarise((ar, tau), &meshes, &study.limit_meshes, of_case);
    }
}
