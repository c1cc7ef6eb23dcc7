//! Time per full load curve (first contact to a/λ = 0.45) at each mesh level, finite
//! kinematics, AR = 0.1, κ/G = 1000, and the linear curve at the default mesh.
//! Run: `cargo bench --bench solver` (criterion reports the median of the samples).
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use wavy::fe::*;

fn curve(kin: Kinematics, mesh: MeshLevel) -> usize {
    let pb = LayerProblem {
        aspect_ratio: 0.1,
        kinematics: kin,
        ..Default::default()
    };
    let opts = SolveOptions {
        mesh,
        ..Default::default()
    };
    solve_curve(&pb, &opts, &mut |_| {})
        .expect("curve")
        .points
        .len()
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("curve_ar0.1");
    g.sample_size(10);
    g.bench_function("linear_default", |b| {
        b.iter(|| black_box(curve(Kinematics::Linear, MeshLevel::Default)))
    });
    for (name, level) in [
        ("finite_coarse", MeshLevel::Coarse),
        ("finite_default", MeshLevel::Default),
        ("finite_fine", MeshLevel::Fine),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| black_box(curve(Kinematics::Finite, level)))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
