//! Timings of the closed-form laws: one forward evaluation and one inverse (with its shape check).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use wavy::models::{a_over_lambda_at, Coefficients, PressureLaw, Reading, Wnl};

fn laws(c: &mut Criterion) {
    let law = Wnl::new(0.18, 0.05, Reading::BracketSq, Coefficients::PAPER_TABLE1);
    c.bench_function("wnl forward p(a)", |b| {
        b.iter(|| law.p_over_estar(black_box(0.3)))
    });
    let p = law.p_over_estar(0.3);
    c.bench_function("wnl inverse a(p) incl. shape check", |b| {
        b.iter(|| a_over_lambda_at(&law, black_box(p)))
    });
}

criterion_group!(benches, laws);
criterion_main!(benches);
