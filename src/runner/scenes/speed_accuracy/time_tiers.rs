//! `wavy time-tiers`: measures the wall time of every tier of a speed_accuracy spec, on one
//! thread, into the timings file the scene reads (`crate::runner::scenes::speed_accuracy::tier_timings`).

use crate::accuracy::Tier;
use crate::models::PressureLaw;
use crate::runner::scenes::speed_accuracy::tier_timings::{TierTiming, Timings};
use crate::runner::scenes::speed_accuracy::SpeedAccuracyScene;
use anyhow::{bail, Result};
use std::time::Instant;

/// The median of `v` (the mean of the middle two for an even count).
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Evaluations of a closed-form curve per timed run: enough that a run lasts milliseconds.
const CLOSED_FORM_REPEATS: usize = 20_000;

/// Times every tier of `scene` at every case: `runs` runs each on the calling thread, FE curves
/// solved from scratch (no cache). `progress` hears one line per tier and case. The provenance
/// names `machine`.
pub fn measure(
    scene: &SpeedAccuracyScene,
    runs: usize,
    machine: &str,
    progress: &mut dyn FnMut(&str),
) -> Result<Timings> {
    if runs == 0 {
        bail!("runs must be at least 1");
    }
    let xs = scene.a_over_lambda.values();
    let mut rows = vec![];
    for tau in scene.fe.tau_max_mpa.iter().map(|t| t.get()) {
        for ar in scene.aspect_ratios.iter().map(|a| a.get()) {
            // a Richardson tier is timed as its two meshes, which are tiers too
            for tier in scene.tiers.iter().filter(|t| t.timed_tiers() == [**t]) {
                let mut times = vec![];
                let mut points = xs.len();
                for _ in 0..runs {
                    match *tier {
                        Tier::Fe {
                            kinematics,
                            elements_along_face,
                        } => {
                            let case = scene.case(kinematics, elements_along_face, ar, tau);
                            let start = Instant::now();
                            let outcome = case.solve();
                            times.push(start.elapsed().as_secs_f64());
                            points = outcome.points.len();
                        }
                        _ => {
                            let law = tier.law(ar, tau).expect("a closed-form tier has a law");
                            let start = Instant::now();
                            let mut sum = 0.0;
                            for _ in 0..CLOSED_FORM_REPEATS {
                                for &x in &xs {
                                    sum += law.p_over_estar(std::hint::black_box(x));
                                }
                            }
                            std::hint::black_box(sum);
                            times.push(start.elapsed().as_secs_f64() / CLOSED_FORM_REPEATS as f64);
                        }
                    }
                }
                let m = median(times);
                progress(&format!(
                    "{tier} at AR = {ar}, τ_max = {tau} MPa: {m:.3e} s per curve ({runs} runs)"
                ));
                rows.push(TierTiming {
                    tier: *tier,
                    aspect_ratio: ar,
                    tau_max_mpa: tau,
                    runs,
                    median_seconds_per_curve: m,
                    points_per_curve: points,
                });
            }
        }
    }
    Ok(Timings {
        provenance: vec![
            (
                "measured_by".into(),
                "wavy time-tiers (make bench-tiers)".into(),
            ),
            ("machine".into(), machine.into()),
            ("threads".into(), "1".into()),
            ("runs".into(), runs.to_string()),
        ],
        rows,
    })
}
