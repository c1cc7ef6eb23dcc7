//! Recursive Westergaard (docs/replication.md R14) against the boundary-element solution of the
//! same Weierstrass profile on the half-plane, over γ ∈ {3, 4, 8}, D ∈ {1.3, 1.5, 1.7},
//! K = 2 … 5, AR₀ = 0.05, at p̄ = 0.05, 0.2, 0.5, 0.8 × π AR₀ on 64 points per finest
//! wavelength (at least 4096): one markdown row per (γ, D), the RMS of recursion / BEM − 1 over
//! the four loads and, in parentheses, the difference of largest magnitude, per K
//! (docs/verification.md). About 5 minutes, most of it γ = 8, K = 5 (262 144 points).
//!
//! `cargo run --release --example recursion_vs_bem`

use wavy::models::{profile_contact, Westergaard};
use wavy::profile::Profile;

/// recursion / BEM − 1 of the contact fraction at the four loads.
fn differences(profile: &Profile) -> Vec<f64> {
    let points = (64 * profile.max_order() as usize)
        .next_power_of_two()
        .max(4096);
    [0.05, 0.2, 0.5, 0.8]
        .iter()
        .map(|load| {
            let p = load * std::f64::consts::PI * profile.aspect_ratio;
            let recursion = profile_contact(profile, Westergaard::new, p).expect("p̄ below p₀*");
            let bem = wavy::bem::solve(profile, p, points, 1e-10).expect("the BEM converges");
            recursion.contact_fraction / bem.contact_fraction - 1.0
        })
        .collect()
}

fn main() {
    println!("| profile | K = 2 | K = 3 | K = 4 | K = 5 |\n|---|---|---|---|---|");
    for gamma in [3u32, 4, 8] {
        for d in [1.3, 1.5, 1.7] {
            let mut line = format!("| `weierstrass:0.05,{gamma},{d},K` |");
            for k in 2..=5 {
                let profile: Profile = format!("weierstrass:0.05,{gamma},{d},{k}")
                    .parse()
                    .expect("valid parameters");
                let e = differences(&profile);
                let rms = (e.iter().map(|e| e * e).sum::<f64>() / e.len() as f64).sqrt();
                let worst = e
                    .iter()
                    .copied()
                    .fold(0.0, |m: f64, e| match e.abs() > m.abs() {
                        true => e,
                        false => m,
                    });
                line += &format!(" {:.1} % ({:+.1} %) |", 100.0 * rms, 100.0 * worst);
            }
            println!("{line}");
        }
    }
}
