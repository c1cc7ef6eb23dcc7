//! Development tool: a two-scale profile's FE contact fraction against an independent reference.
//! With linear kinematics the reference is the half-plane boundary-element solution
//! (`wavy::bem`) at each FE point's mean pressure; with finite strain, the finest mesh's curve.
//! Env: PROFILE (`1:0.1,8:0.05`), MESHES (`48,96`), KIN (`linear`|`finite`), TAU (MPa, 0),
//! UNTIL (contact fraction, 0.9), BEM_N (points per wavelength, 16384), OUT (folder for
//! `mN.csv`, optional). Prints the relative RMS / mean / max error over points with contact
//! fraction ≥ 0.05. Diagnostics: BEM_AT (comma-separated p̄/E*: only the BEM's fraction and
//! patches there), DIAG (`lo,hi`: each FE point's patches in that p̄/E* range beside the BEM's).
use std::ops::ControlFlow;
use std::time::Instant;
use wavy::fe::*;
use wavy::profile::Profile;

fn env(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_string())
}

/// Linear interpolation of `(p, c)` points (increasing `p`) at `p`; `None` outside.
fn interpolate(curve: &[(f64, f64)], p: f64) -> Option<f64> {
    let k = curve.windows(2).position(|w| w[0].0 <= p && p <= w[1].0)?;
    let (a, b) = (curve[k], curve[k + 1]);
    let t = if b.0 > a.0 {
        (p - a.0) / (b.0 - a.0)
    } else {
        0.0
    };
    Some(a.1 + t * (b.1 - a.1))
}

fn main() {
    let profile: Profile = env("PROFILE", "1:0.1,8:0.05").parse().expect("profile");
    let linear = env("KIN", "linear") == "linear";
    let tau: f64 = env("TAU", "0").parse().expect("TAU");
    let until: f64 = env("UNTIL", "0.9").parse().expect("UNTIL");
    let bem_n: usize = env("BEM_N", "16384").parse().expect("BEM_N");
    let meshes: Vec<usize> = env("MESHES", "48,96")
        .split(',')
        .map(|m| m.parse().expect("mesh"))
        .collect();
    let out = std::env::var("OUT").ok();
    if let Ok(ps) = std::env::var("BEM_AT") {
        for p in ps.split(',').map(|p| p.parse::<f64>().expect("p")) {
            let b = wavy::bem::solve(&profile, p, bem_n, 1e-10).expect("bem");
            println!(
                "p {p}: fraction {:.5}, patches {:?}",
                b.contact_fraction, b.patches
            );
        }
        return;
    }
    let pb = LayerProblem {
        finer_harmonics: profile.finer,
        kinematics: if linear {
            Kinematics::Linear
        } else {
            Kinematics::Finite
        },
        interface: Interface::coulomb_orowan(1.0, tau, wavy::defaults::elastic_slip_over_element()),
        ..wavy::defaults::layer_problem(profile.aspect_ratio)
    };
    let mut curves = vec![];
    for &mesh in &meshes {
        let opts = SolveOptions {
            mesh: MeshLevel::along_face(mesh),
            grading: Grading::uniform_face(),
            until_contact_fraction: Some(until),
            ..Default::default()
        };
        let t = Instant::now();
        let c = solve_curve(&pb, &opts, &mut |_| ControlFlow::Continue(())).expect("curve");
        eprintln!(
            "mesh {mesh}: {} points in {:.1} s",
            c.points.len(),
            t.elapsed().as_secs_f64()
        );
        if let Ok(range) = std::env::var("DIAG") {
            let r: Vec<f64> = range.split(',').map(|v| v.parse().expect("DIAG")).collect();
            for (p, e) in c.points.iter().zip(&c.patch_edges) {
                if p.p_over_estar >= r[0] && p.p_over_estar <= r[1] {
                    let b = wavy::bem::solve(&profile, p.p_over_estar, bem_n, 1e-10).expect("bem");
                    println!(
                        "p {:.5} fe {:.5} {:?}\n          bem {:.5} {:?}",
                        p.p_over_estar, p.contact_fraction, e, b.contact_fraction, b.patches
                    );
                }
            }
        }
        curves.push((mesh, c.points));
    }
    let reference: Option<Vec<(f64, f64)>> = (!linear).then(|| {
        let (_, pts) = curves.last().expect("a mesh");
        pts.iter()
            .map(|p| (p.p_over_estar, p.contact_fraction))
            .collect()
    });
    for (mesh, pts) in &curves {
        let (mut sum, mut sum_rel, mut n, mut worst) = (0.0, 0.0, 0, 0.0_f64);
        let mut rows = String::from("p_over_estar,contact_fraction,reference,patches\n");
        for p in pts.iter().filter(|p| p.contact_fraction >= 0.05) {
            let r = match &reference {
                None => wavy::bem::solve(&profile, p.p_over_estar, bem_n, 1e-10)
                    .ok()
                    .map(|b| b.contact_fraction),
                Some(curve) => interpolate(curve, p.p_over_estar),
            };
            let Some(r) = r else { continue };
            let rel = p.contact_fraction / r - 1.0;
            rows += &format!(
                "{},{},{},{}\n",
                p.p_over_estar, p.contact_fraction, r, p.patches
            );
            sum += rel * rel;
            sum_rel += rel;
            n += 1;
            worst = worst.max(rel.abs());
        }
        if let Some(dir) = &out {
            std::fs::write(format!("{dir}/m{mesh}.csv"), rows).expect("write");
        }
        if n > 0 {
            println!(
                "mesh {mesh}: {n} points, rms {:.3} %, mean {:+.3} %, max {:.3} %",
                100.0 * (sum / n as f64).sqrt(),
                100.0 * sum_rel / n as f64,
                100.0 * worst
            );
        }
    }
}
