//! Development tool: a two-scale profile's FE contact fraction against an independent reference.
//! With linear kinematics the reference is the boundary-element solution (`wavy::bem`) on the
//! FE's layer (its Fourier compliance; BODY=half-plane for the half-plane) at each FE point's
//! mean pressure; with finite strain, the finest mesh's curve.
//! Env: PROFILE (`1:0.1,8:0.05`), MESHES (`48,96`), KIN (`linear`|`finite`), TAU (MPa, 0),
//! UNTIL (contact fraction, 0.9), BEM_N (points per wavelength, 16384), DEPTH (elements across
//! the thickness per element along the face, 0.25 as the two-scale scenes), REF (a curve CSV
//! written by OUT, the finite-strain reference instead of the finest mesh), OUT (folder for
//! `mN.csv`, optional), COARSEN (the grading's `coarsen_at_aspect`, 0). Prints the relative
//! RMS / mean / max error over points with contact fraction ≥ 0.05. Diagnostics: BEM_AT (comma-separated p̄/E*: only the BEM's fraction and
//! patches there), DIAG (`lo,hi`: each FE point's patches in that p̄/E* range beside the BEM's),
//! CHANGES (linear: where the FE's patch count changes, whether the BEM's changes over the same
//! load step, and both contact fractions' change over it), SUPERPOSITION (no FE: the
//! superposition of Westergaard's laws against the BEM, the linear limit of the two-scale scene's
//! comparison, at 60 mean pressures up to p̄/E* 0.3).
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

/// Each load step over which the FE's patch count changes: the BEM's count at both ends (its
/// change falls in the same step when they differ alike), and the contact fraction's change over
/// the step, FE and BEM; then how many steps agree.
fn patch_count_changes<E: std::fmt::Debug>(
    points: &[CurvePoint],
    bem: &dyn Fn(f64) -> Result<wavy::bem::HalfSpaceContact, E>,
) {
    let (mut changes, mut alike) = (0, 0);
    for w in points.windows(2) {
        if w[0].patches == w[1].patches {
            continue;
        }
        let (Ok(b0), Ok(b1)) = (bem(w[0].p_over_estar), bem(w[1].p_over_estar)) else {
            continue;
        };
        changes += 1;
        let same = b1.patches.len() as isize - b0.patches.len() as isize
            == w[1].patches as isize - w[0].patches as isize;
        alike += usize::from(same);
        println!(
            "p {:.5} → {:.5}: FE {} → {} patches, ΔF {:+.5}; BEM {} → {}, ΔF {:+.5}{}",
            w[0].p_over_estar,
            w[1].p_over_estar,
            w[0].patches,
            w[1].patches,
            w[1].contact_fraction - w[0].contact_fraction,
            b0.patches.len(),
            b1.patches.len(),
            b1.contact_fraction - b0.contact_fraction,
            if same { "" } else { "  (not in this step)" }
        );
    }
    println!("{alike} of {changes} patch-count changes in the same load step as the BEM's");
}

/// The relative RMS error of the superposition of Westergaard's laws (docs/replication.md R13)
/// against the BEM at 60 mean pressures up to p̄/E* 0.3 (contact fraction ≥ 0.05).
fn superposition_against_bem<E>(
    profile: &Profile,
    bem: &dyn Fn(f64) -> Result<wavy::bem::HalfSpaceContact, E>,
) {
    use wavy::models::{CoefficientSet, ModelKind, ModelLaw, Reading};
    let small = profile.finer.iter().next().expect("a finer harmonic");
    let law = |ar| {
        ModelLaw::new(
            ModelKind::Westergaard,
            ar,
            0.0,
            Reading::default(),
            CoefficientSet::default(),
        )
    };
    let (big, fine) = (law(profile.aspect_ratio), law(small.aspect_ratio));
    let (mut sum, mut n) = (0.0, 0);
    for i in 1..=60 {
        let p = 0.3 * i as f64 / 60.0;
        let Ok(b) = bem(p) else { continue };
        let superposed =
            wavy::models::superposition::superposed_contact(&big, &fine, small.order, p);
        let Ok(c) = superposed else { continue };
        if b.contact_fraction < 0.05 {
            continue;
        }
        sum += (c.contact_fraction / b.contact_fraction - 1.0).powi(2);
        n += 1;
    }
    println!(
        "{profile}: superposition (Westergaard) against the BEM: rms {:.2} % over {n} pressures",
        100.0 * (sum / n as f64).sqrt()
    );
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
    let depth: f64 = env("DEPTH", "0.25").parse().expect("DEPTH");
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
    let body = match env("BODY", "layer").as_str() {
        "half-plane" => wavy::bem::ElasticBody::HalfPlane,
        _ => wavy::bem::ElasticBody::Layer {
            thickness: pb.thickness_over_lambda,
            poisson: poisson_ratio(pb.kappa_over_g),
        },
    };
    let bem = |p: f64| wavy::bem::solve_on(&profile, body, p, bem_n, 1e-10);
    if let Ok(ps) = std::env::var("BEM_AT") {
        for p in ps.split(',').map(|p| p.parse::<f64>().expect("p")) {
            let b = bem(p).expect("bem");
            println!(
                "p {p}: fraction {:.5}, patches {:?}",
                b.contact_fraction, b.patches
            );
        }
        return;
    }
    if std::env::var_os("SUPERPOSITION").is_some() {
        superposition_against_bem(&profile, &bem);
        return;
    }
    let mut curves = vec![];
    for &mesh in &meshes {
        let opts = SolveOptions {
            mesh: MeshLevel::Elements {
                nx: mesh,
                ny: ((mesh as f64 * depth).round() as usize).max(2),
            },
            grading: Grading {
                coarsen_at_aspect: env("COARSEN", "0").parse().expect("COARSEN"),
                ..Grading::uniform_face()
            },
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
                    let b = bem(p.p_over_estar).expect("bem");
                    println!(
                        "p {:.5} fe {:.5} {:?}\n          bem {:.5} {:?}",
                        p.p_over_estar, p.contact_fraction, e, b.contact_fraction, b.patches
                    );
                }
            }
        }
        if linear && std::env::var_os("CHANGES").is_some() {
            patch_count_changes(&c.points, &bem);
        }
        curves.push((mesh, c.points));
    }
    let reference: Option<Vec<(f64, f64)>> = (!linear).then(|| match std::env::var("REF") {
        Ok(file) => std::fs::read_to_string(&file)
            .expect("REF")
            .lines()
            .skip(1)
            .map(|l| {
                let v: Vec<f64> = l.split(',').map(|x| x.parse().expect("REF")).collect();
                (v[0], v[1])
            })
            .collect(),
        Err(_) => {
            let (_, pts) = curves.last().expect("a mesh");
            pts.iter()
                .map(|p| (p.p_over_estar, p.contact_fraction))
                .collect()
        }
    });
    for (mesh, pts) in &curves {
        let (mut sum, mut sum_rel, mut n, mut worst) = (0.0, 0.0, 0, 0.0_f64);
        if let Some(dir) = &out {
            let mut rows = String::from("p_over_estar,contact_fraction,patches\n");
            for p in pts {
                rows += &format!("{},{},{}\n", p.p_over_estar, p.contact_fraction, p.patches);
            }
            std::fs::write(format!("{dir}/m{mesh}.csv"), rows).expect("write");
        }
        for p in pts.iter().filter(|p| p.contact_fraction >= 0.05) {
            let r = match &reference {
                None => bem(p.p_over_estar).ok().map(|b| b.contact_fraction),
                Some(curve) => interpolate(curve, p.p_over_estar),
            };
            let Some(r) = r else { continue };
            let rel = p.contact_fraction / r - 1.0;
            sum += rel * rel;
            sum_rel += rel;
            n += 1;
            worst = worst.max(rel.abs());
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
