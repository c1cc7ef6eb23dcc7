//! Time per full load curve (first contact to a/λ = 0.45) at each mesh level and at
//! 64 × 32 (a level between default and fine), finite
//! kinematics, AR = 0.1 and AR = 0.3, κ/G = 1000; the linear curve at the default mesh
//! (AR = 0.1); frictional curves at the default mesh (μ = 1, τ_max/E* = 0.2, the
//! costliest panels of Fig. 3); and AR 0.3, τ_max/E* = 0.1 at the default mesh with the node
//! that has just touched held in the load tangent and free. Before the timings, the peak memory of one curve per AR
//! and mesh level is printed: each curve runs in a fresh child process (this bench
//! binary re-invoked with `WAVY_BENCH_CURVE=AR,level`), which reports its `VmHWM` from
//! `/proc/self/status`.
//! Run: `cargo bench --bench solver` (criterion reports the median of the samples).
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::ops::ControlFlow;
mod common;
use common::peak_memory_kb;
use wavy::fe::*;

const CHILD: &str = "WAVY_BENCH_CURVE";

fn curve(ar: f64, kin: Kinematics, mesh: MeshLevel) -> usize {
    frictional_curve(ar, kin, mesh, 0.0)
}

fn frictional_curve(ar: f64, kin: Kinematics, mesh: MeshLevel, tau_max_over_estar: f64) -> usize {
    let opts = SolveOptions {
        mesh,
        ..Default::default()
    };
    frictional_curve_with(ar, kin, tau_max_over_estar, &opts)
}

fn frictional_curve_with(
    ar: f64,
    kin: Kinematics,
    tau_max_over_estar: f64,
    opts: &SolveOptions,
) -> usize {
    let pb = LayerProblem {
        kinematics: kin,
        interface: Interface::coulomb_orowan(
            wavy::defaults::friction_coefficient(),
            tau_max_over_estar,
            wavy::defaults::elastic_slip_over_element(),
        ),
        ..wavy::defaults::layer_problem(ar)
    };
    solve_curve(&pb, opts, &mut |_| ControlFlow::Continue(()))
        .expect("curve")
        .points
        .len()
}

fn levels() -> [(&'static str, MeshLevel); 4] {
    [
        ("coarse", MeshLevel::Coarse),
        ("default", MeshLevel::Default),
        ("64x32", MeshLevel::Elements { nx: 64, ny: 32 }),
        ("fine", MeshLevel::Fine),
    ]
}

/// Child mode: one curve, then print `VmHWM` and exit.
fn child(spec: &str) -> ! {
    let (ar, name) = spec.split_once(',').expect("AR,level");
    let ar: f64 = ar.parse().expect("AR");
    let level = levels()
        .into_iter()
        .find(|(n, _)| *n == name)
        .expect("level")
        .1;
    curve(ar, Kinematics::Finite, level);
    println!("{}", peak_memory_kb().unwrap_or(0));
    std::process::exit(0)
}

fn print_peak_memory() {
    let exe = std::env::current_exe().expect("bench executable");
    for ar in ["0.1", "0.3"] {
        for (name, _) in levels() {
            let out = std::process::Command::new(&exe)
                .env(CHILD, format!("{ar},{name}"))
                .output()
                .expect("child curve");
            let kb = String::from_utf8_lossy(&out.stdout).trim().to_string();
            eprintln!("peak memory (VmHWM), finite, AR {ar}, {name} mesh: {kb} kB");
        }
    }
}

fn bench(c: &mut Criterion) {
    if let Ok(spec) = std::env::var(CHILD) {
        child(&spec);
    }
    print_peak_memory();
    let mut g = c.benchmark_group("curve_ar0.1");
    g.sample_size(10);
    g.bench_function("linear_default", |b| {
        b.iter(|| black_box(curve(0.1, Kinematics::Linear, MeshLevel::Default)))
    });
    for (name, level) in levels() {
        g.bench_function(format!("finite_{name}"), |b| {
            b.iter(|| black_box(curve(0.1, Kinematics::Finite, level)))
        });
    }
    g.finish();
    let mut g = c.benchmark_group("curve_ar0.3");
    g.sample_size(10);
    for (name, level) in levels() {
        g.bench_function(format!("finite_{name}"), |b| {
            b.iter(|| black_box(curve(0.3, Kinematics::Finite, level)))
        });
    }
    g.finish();
    let mut g = c.benchmark_group("friction_tau0.2");
    g.sample_size(10);
    for ar in [0.1, 0.3] {
        g.bench_function(format!("finite_default_ar{ar}"), |b| {
            b.iter(|| {
                black_box(frictional_curve(
                    ar,
                    Kinematics::Finite,
                    MeshLevel::Default,
                    0.2,
                ))
            })
        });
    }
    g.finish();
    // the node that has just touched held in the load tangent, or free as before
    // (`StepOptions::touched_nodes`; docs/performance.md, "the node that has just touched")
    let mut g = c.benchmark_group("friction_tau0.1_touched_node");
    g.sample_size(10);
    for (name, touched) in [("held", TouchedNodes::Held), ("free", TouchedNodes::Free)] {
        let mut opts = SolveOptions::default();
        opts.steps.touched_nodes = touched;
        g.bench_function(format!("finite_default_ar0.3_{name}"), |b| {
            b.iter(|| black_box(frictional_curve_with(0.3, Kinematics::Finite, 0.1, &opts)))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
