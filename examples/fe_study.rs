//! Mesh-convergence study (development tool): `cargo run --release --example fe_study`
//! with environment variables AR, LEVELS (nx list, e.g. "32,64,128"), NY_OVER_NX,
//! PEAK (grading peak_ratio), FIRST (first_layer_over_dx), RULE (fraction|power|periodic), KIN (finite|linear),
//! DUMP (print the curves), PRED (tangent|extrap), PHI_CALIB (calibrate `DISCRETE_EDGE_FRACTION` instead),
//! ASPECT_CALIB (calibrate `EDGE_FRACTION_BY_ASPECT` instead), LAYER_PHI (the discrete edge
//! fraction of each event up to a/λ = 0.5 against the boundary-element solution on the layer).
use faer::prelude::*;
use std::ops::ControlFlow;
use std::time::Instant;
use wavy::fe::*;

fn env(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_string())
}

/// The aspect ratio of the edge calibrations: small enough that the linear problem is
/// Westergaard's.
const CALIBRATION_AR: f64 = 0.01;

/// The problem the edge rules are calibrated on: linear kinematics at [`CALIBRATION_AR`].
fn calibration_problem() -> LayerProblem {
    LayerProblem {
        kinematics: Kinematics::Linear,
        ..wavy::defaults::layer_problem(CALIBRATION_AR)
    }
}

/// The contact half-width a/λ that Westergaard's `p̄/E* = π AR sin²(π a)` gives for `p̄/E*` at
/// [`CALIBRATION_AR`] (NaN beyond full contact).
fn westergaard_a(p_over_estar: f64) -> f64 {
    let pi = std::f64::consts::PI;
    (p_over_estar / (pi * CALIBRATION_AR)).sqrt().asin() / pi
}

/// The curve of `pb` under `opts` with the edge at the fractions 0 and 1 of the last loaded
/// element: event by event, the element's two ends (the points converged, where the curve stops
/// short of its target).
fn element_ends(pb: &LayerProblem, opts: &SolveOptions) -> (Vec<CurvePoint>, Vec<CurvePoint>) {
    let run = |phi| {
        let o = SolveOptions {
            contact: ContactOptions {
                edge_rule: EdgeRule::Fraction(phi),
                ..opts.contact
            },
            ..*opts
        };
        match solve_curve(pb, &o, &mut |_| ControlFlow::Continue(())) {
            Ok(c) => c.points,
            Err(f) => f.points,
        }
    };
    (run(0.0), run(1.0))
}

/// Calibration of `DISCRETE_EDGE_FRACTION`: the edge that Westergaard gives for the computed `p̄`
/// on [`calibration_problem`], as a fraction of `[x_{k−1}, x_k]` (the two ends from the fractions
/// 0 and 1), per mesh level.
fn calibrate(levels: &[usize], ny_over_nx: f64, opts: &SolveOptions) {
    let pb = calibration_problem();
    for &nx in levels {
        let ny = ((nx as f64 * ny_over_nx).round() as usize).max(1);
        let o = SolveOptions {
            mesh: MeshLevel::Elements { nx, ny },
            ..*opts
        };
        let (lo, hi) = element_ends(&pb, &o);
        let mut phis = Vec::new();
        for (l, h) in lo.iter().zip(&hi) {
            let a = westergaard_a(l.p_over_estar);
            if (0.1..=0.35).contains(&a) {
                phis.push((a - l.a_over_lambda) / (h.a_over_lambda - l.a_over_lambda));
            }
        }
        phis.sort_by(f64::total_cmp);
        println!(
            "nx {nx}: phi over a in [0.1, 0.35]: min {:.3} median {:.3} max {:.3} ({} events)",
            phis[0],
            phis[phis.len() / 2],
            phis[phis.len() - 1],
            phis.len()
        );
    }
}

/// The discrete edge fraction of [`calibrate`] at every event up to full contact, the exact edge
/// from the boundary-element solution on the FE's own layer (`wavy::bem::solve_on`, 16384 points
/// per wavelength) rather than Westergaard's half-plane, which is softer for the big wave by
/// 6.4e-4 and moves the edge near the valley: each 16th event and the last ten.
fn layer_phi(levels: &[usize], ny_over_nx: f64, opts: &SolveOptions) {
    let pb = calibration_problem();
    let body = wavy::bem::ElasticBody::Layer {
        thickness: pb.thickness_over_lambda,
        poisson: poisson_ratio(pb.kappa_over_g),
    };
    let profile = wavy::profile::Profile::sinusoid(CALIBRATION_AR);
    for &nx in levels {
        let ny = ((nx as f64 * ny_over_nx).round() as usize).max(1);
        let o = SolveOptions {
            mesh: MeshLevel::Elements { nx, ny },
            until_a_over_lambda: 0.4999,
            ..*opts
        };
        let (lo, hi) = element_ends(&pb, &o);
        println!("nx {nx}, ny {ny}:");
        for (k, (l, h)) in lo.iter().zip(&hi).enumerate() {
            if k % 16 != 0 && k + 10 < lo.len() {
                continue;
            }
            let exact = wavy::bem::solve_on(&profile, body, l.p_over_estar, 16384, 1e-11)
                .map(|b| 0.5 * b.contact_fraction);
            match exact {
                Ok(a) => println!(
                    "  event {k}: a/λ {a:.5}, phi {:.4}",
                    (a - l.a_over_lambda) / (h.a_over_lambda - l.a_over_lambda)
                ),
                Err(e) => println!("  event {k}: {e}"),
            }
        }
    }
}

/// Calibration of `EDGE_FRACTION_BY_ASPECT`: as [`calibrate`], on the 64 × 32 mesh with the
/// gradings (peak ratio, first layer) ∈ {4, 16} × {0.25, 0.5, 1} and (2, 2), each event with
/// a/λ ∈ [0.05, 0.30] and element aspect r ≤ 1.7 giving a pair (r, φ), then the least-squares
/// quadratic φ(r). The rule changes only the reported a, so three runs give, event by event, the
/// ends of the last loaded element (fractions 0 and 1) and r (the fraction r/2).
fn calibrate_aspect() {
    let pb = calibration_problem();
    let gradings = [
        (4.0, 0.25),
        (4.0, 0.5),
        (4.0, 1.0),
        (16.0, 0.25),
        (16.0, 0.5),
        (16.0, 1.0),
        (2.0, 2.0),
    ];
    let mut pairs = Vec::new();
    for (peak_ratio, first_layer_over_dx) in gradings {
        let run = |edge_rule| {
            let o = SolveOptions {
                mesh: MeshLevel::Elements { nx: 64, ny: 32 },
                grading: Grading {
                    peak_ratio,
                    first_layer_over_dx,
                    ..Grading::default()
                },
                until_a_over_lambda: 0.47,
                contact: ContactOptions {
                    edge_rule,
                    ..ContactOptions::default()
                },
                ..SolveOptions::default()
            };
            solve_curve(&pb, &o, &mut |_| ControlFlow::Continue(()))
                .expect("linear curve")
                .points
        };
        let lo = run(EdgeRule::Fraction(0.0));
        let hi = run(EdgeRule::Fraction(1.0));
        let half_r = run(EdgeRule::AspectFraction([0.0, 0.5, 0.0]));
        for ((l, h), m) in lo.iter().zip(&hi).zip(&half_r) {
            assert_eq!(
                l.p_over_estar, m.p_over_estar,
                "the rule moved the solution"
            );
            let width = h.a_over_lambda - l.a_over_lambda;
            let a = westergaard_a(l.p_over_estar);
            if width <= 0.0 || !a.is_finite() {
                continue;
            }
            let r = 2.0 * (m.a_over_lambda - l.a_over_lambda) / width;
            if (0.05..=0.30).contains(&a) && r <= 1.7 {
                pairs.push((r, (a - l.a_over_lambda) / width));
            }
        }
    }
    let (r, phi): (Vec<f64>, Vec<f64>) = pairs.iter().cloned().unzip();
    let c = wavy::accuracy::extrapolation::polynomial_least_squares(&r, &phi, 2)
        .expect("enough events for a quadratic");
    let resid: Vec<f64> = pairs
        .iter()
        .map(|&(r, phi)| phi - (c[0] + c[1] * r + c[2] * r * r))
        .collect();
    println!(
        "phi(r) = {:.4} + {:.4} r + {:.4} r^2 from {} events; residuals {:.4} .. {:.4}",
        c[0],
        c[1],
        c[2],
        pairs.len(),
        resid.iter().cloned().fold(f64::INFINITY, f64::min),
        resid.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
    );
}

/// The state's last loaded face node `i` and its three quantities the progress law of
/// `EDGE_PROGRESS_BY_FORCE_RATIO` reads: the force ratio `ρ = f_i/f_{i−1}`, the mean element
/// aspect `r` of the elements on either side of `i`, and the two ends `E₀`, `E₁` of the edge's
/// travel (the edge rule's positions with `i` and with `i + 1` as the event's node).
fn edge_progress_inputs(s: &DeformedState) -> Option<(f64, f64, f64, f64)> {
    let n = s.bottom.len();
    let x = |k: usize| s.nodes[s.bottom[k]][0];
    let trib = |k: usize| {
        0.5 * (if k > 0 { x(k) - x(k - 1) } else { 0.0 }
            + if k + 1 < n { x(k + 1) - x(k) } else { 0.0 })
    };
    let f: Vec<f64> = (0..n)
        .map(|k| s.contact_pressure_over_estar[k] * trib(k))
        .collect();
    let scale = f.iter().cloned().fold(0.0, f64::max);
    let i = (0..n)
        .rev()
        .find(|&k| s.in_contact[k] && f[k] > 1e-8 * scale)?;
    if i < 2 || i + 1 >= n {
        return None;
    }
    // the face node's neighbour above: the structured mesh numbers rows of n nodes
    let aspect = |a: usize, b: usize| {
        let h = |k: usize| s.nodes[s.bottom[k] + n][1] - s.nodes[s.bottom[k]][1];
        0.5 * (h(a) + h(b)) / (x(b) - x(a))
    };
    let c = EDGE_FRACTION_BY_ASPECT;
    let phi = |r: f64| c[0] + c[1] * r + c[2] * r * r;
    let (r0, r1) = (aspect(i - 1, i), aspect(i, i + 1));
    let e0 = x(i - 1) + phi(r0) * (x(i) - x(i - 1));
    let e1 = x(i) + phi(r1) * (x(i + 1) - x(i));
    Some((f[i] / f[i - 1], 0.5 * (r0 + r1), e0, e1))
}

/// Calibration of `EDGE_PROGRESS_BY_FORCE_RATIO`: states between edge events on the calibration
/// problem (mesh 64 × 32, gradings (peak ratio, first layer) ∈ {1, 4, 16} × {0.5, 1} and (2, 2)),
/// at loads a quarter, half and three quarters of the way between consecutive events with
/// a/λ ∈ [0.05, 0.30]; each gives (ρ, r, t) with t the exact edge's place between `E₀` and `E₁`;
/// then the least-squares `t = ρ + (c₀ + c₁ r) ρ² + (c₂ + c₃ r) ρ³`.
fn calibrate_progress() {
    let pb = calibration_problem();
    let gradings = [
        (1.0, 1.0),
        (1.0, 0.5),
        (4.0, 1.0),
        (4.0, 0.5),
        (16.0, 1.0),
        (16.0, 0.5),
        (2.0, 2.0),
    ];
    let mut rows: Vec<(f64, f64, f64)> = Vec::new();
    for (peak_ratio, first_layer_over_dx) in gradings {
        let o = SolveOptions {
            mesh: MeshLevel::Elements { nx: 64, ny: 32 },
            grading: Grading {
                peak_ratio,
                first_layer_over_dx,
                ..Grading::default()
            },
            until_a_over_lambda: 0.32,
            ..SolveOptions::default()
        };
        let events = solve_curve(&pb, &o, &mut |_| ControlFlow::Continue(()))
            .expect("linear curve")
            .points;
        for w in events.windows(2) {
            if !(0.05..=0.30).contains(&westergaard_a(w[0].p_over_estar)) {
                continue;
            }
            for q in [0.25, 0.5, 0.75] {
                let p = w[0].p_over_estar + q * (w[1].p_over_estar - w[0].p_over_estar);
                let ol = SolveOptions {
                    until_p_over_estar: Some(p),
                    until_a_over_lambda: 0.45,
                    ..o
                };
                let c = solve_curve(&pb, &ol, &mut |_| ControlFlow::Continue(())).expect("landing");
                let Some((rho, r, e0, e1)) = edge_progress_inputs(&c.final_state) else {
                    continue;
                };
                let a = westergaard_a(c.points.last().expect("a point").p_over_estar);
                rows.push((rho, r, (a - e0) / (e1 - e0)));
            }
        }
    }
    // least squares of t − ρ = (c₀ + c₁ r) ρ² + (c₂ + c₃ r) ρ³ (column-pivoted QR, faer)
    let basis = |rho: f64, r: f64| [rho * rho, r * rho * rho, rho.powi(3), r * rho.powi(3)];
    let design = faer::Mat::from_fn(rows.len(), 4, |i, k| basis(rows[i].0, rows[i].1)[k]);
    let rhs = faer::Mat::from_fn(rows.len(), 1, |i, _| rows[i].2 - rows[i].0);
    let solution = design.col_piv_qr().solve_lstsq(&rhs);
    let c: Vec<f64> = (0..4).map(|k| solution[(k, 0)]).collect();
    let resid: Vec<f64> = rows
        .iter()
        .map(|&(rho, r, t)| {
            t - rho
                - basis(rho, r)
                    .iter()
                    .zip(&c)
                    .map(|(b, c)| b * c)
                    .sum::<f64>()
        })
        .collect();
    if std::env::var_os("DUMP").is_some() {
        for (row, e) in rows.iter().zip(&resid) {
            println!("{:.4} {:.4} {:.4} {:+.4}", row.0, row.1, row.2, e);
        }
    }
    println!(
        "t = rho + ({:.4} + {:.4} r) rho^2 + ({:.4} + {:.4} r) rho^3 from {} states; residuals {:.4} .. {:.4}, rms {:.4}",
        c[0], c[1], c[2], c[3], rows.len(),
        resid.iter().cloned().fold(f64::INFINITY, f64::min),
        resid.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        (resid.iter().map(|e| e * e).sum::<f64>() / resid.len() as f64).sqrt()
    );
}

fn main() {
    if std::env::var_os("PROGRESS_CALIB").is_some() {
        calibrate_progress();
        return;
    }
    let ar: f64 = env("AR", "0.1").parse().unwrap();
    let levels: Vec<usize> = env("LEVELS", "32,48,72")
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    let ny_over_nx: f64 = env("NY_OVER_NX", "0.5").parse().unwrap();
    let mut opts = SolveOptions::default();
    opts.grading.peak_ratio = env("PEAK", &opts.grading.peak_ratio.to_string())
        .parse()
        .unwrap();
    opts.grading.first_layer_over_dx = env("FIRST", &opts.grading.first_layer_over_dx.to_string())
        .parse()
        .unwrap();
    opts.contact.edge_rule = match env("RULE", "fraction").as_str() {
        "power" => EdgeRule::GapPower,
        "periodic" => EdgeRule::PeriodicGap,
        _ => EdgeRule::default(),
    };
    opts.steps.tangent_predictor = env("PRED", "tangent") == "tangent";
    if std::env::var_os("ASPECT_CALIB").is_some() {
        calibrate_aspect();
        return;
    }
    if std::env::var_os("PHI_CALIB").is_some() {
        calibrate(&levels, ny_over_nx, &opts);
        return;
    }
    if std::env::var_os("LAYER_PHI").is_some() {
        layer_phi(&levels, ny_over_nx, &opts);
        return;
    }
    let pb = LayerProblem {
        kinematics: if env("KIN", "finite") == "linear" {
            Kinematics::Linear
        } else {
            Kinematics::Finite
        },
        ..wavy::defaults::layer_problem(ar)
    };
    let a_values: Vec<f64> = (0..8).map(|i| 0.1 + 0.05 * i as f64).collect();
    let mut curves = Vec::new();
    for &nx in &levels {
        let ny = ((nx as f64 * ny_over_nx).round() as usize).max(1);
        let o = SolveOptions {
            mesh: MeshLevel::Elements { nx, ny },
            ..opts
        };
        let t = Instant::now();
        let r = solve_curve(&pb, &o, &mut |_| ControlFlow::Continue(()));
        let el = t.elapsed().as_secs_f64();
        let pts = match r {
            Ok(c) => c.points,
            Err(f) => {
                eprintln!(
                    "nx {nx}: FAILED {} after a {:?}",
                    f.error,
                    f.points.last().map(|p| p.a_over_lambda)
                );
                f.points
            }
        };
        let its: usize = pts.iter().map(|p| p.newton_iterations).sum();
        eprintln!(
            "nx {nx} ny {ny}: {el:.2} s, {} steps, {its} Newton, last a {:.4}",
            pts.len(),
            pts.last().map_or(0.0, |p| p.a_over_lambda)
        );
        if std::env::var("DUMP").is_ok() {
            for p in &pts {
                println!(
                    "{nx} {:.6} {:.8e} {:.8e}",
                    p.a_over_lambda, p.p_over_estar, p.slab_displacement_over_lambda
                );
            }
        }
        curves.push(pts);
    }
    for &a in &a_values {
        let ps: Vec<Option<f64>> = curves.iter().map(|c| p_at(c, a)).collect();
        let mut line = format!("a {a:.2}:");
        for p in &ps {
            match p {
                Some(p) => line += &format!(" {p:.6e}"),
                None => line += " -",
            }
        }
        for w in ps.windows(2) {
            if let (Some(x), Some(y)) = (w[0], w[1]) {
                line += &format!("  d {:+.3}%", 100.0 * (x / y - 1.0));
            }
        }
        if ps.len() >= 3 {
            let n = ps.len();
            if let (Some(f1), Some(f2), Some(f3)) = (ps[n - 3], ps[n - 2], ps[n - 1]) {
                let r = levels[n - 2] as f64 / levels[n - 3] as f64;
                let q = ((f1 - f2).abs() / (f2 - f3).abs()).ln() / r.ln();
                line += &format!(
                    "  q {q:.2}  err2 {:.3}%",
                    100.0 * ((f2 - f3) / f3).abs() * r * r / (r * r - 1.0)
                );
            }
        }
        println!("{line}");
    }
    if curves.len() >= 3 {
        let n = curves.len();
        let ratio = levels[n - 2] as f64 / levels[n - 3] as f64;
        if let Some(t) = convergence_table(
            [&curves[n - 3], &curves[n - 2], &curves[n - 1]],
            ratio,
            &a_values,
        ) {
            println!("global q {:.2}", t.observed_order);
            for r in &t.rows {
                println!(
                    "  a {:.2} q {:.2} default err {:.3}%",
                    r.a_over_lambda,
                    r.observed_order,
                    100.0 * r.default_relative_error
                );
            }
        }
    }
}
