//! The frictional solver against its limits: no shear without coupling, Westergaard without
//! friction, the closed form of proportional loading, and the energy of a loop. Tolerances sit
//! near what was measured (docs/verification.md, "Frictional boundary elements").

use super::frictional_contact::*;
use super::frictional_curve::*;
use super::{dundurs_beta, ElasticBody};
use crate::models::{spence, PressureLaw, Westergaard};
use crate::profile::Profile;

fn problem(profile: &Profile, poisson: f64, mu: f64, n: usize) -> FrictionalProblem<'_> {
    FrictionalProblem {
        profile,
        body: ElasticBody::HalfPlane,
        poisson,
        law: InterfaceLaw {
            friction_coefficient: mu,
            tau_max_over_estar: f64::INFINITY,
        },
        coupling: NormalCoupling::Full,
        points_per_wavelength: n,
        tol: 1e-10,
    }
}

fn westergaard_pressure(ar: f64, a_over_lambda: f64) -> f64 {
    Westergaard { aspect_ratio: ar }.p_over_estar(a_over_lambda)
}

/// β = 0 (ν = ½): pressure makes no tangential displacement, so friction carries nothing and
/// the pressure is the frictionless solver's, to rounding.
#[test]
fn an_incompressible_half_plane_carries_no_shear() {
    let profile = Profile::sinusoid(0.05);
    let mut contact = FrictionalContact::new(&problem(&profile, 0.5, 1.0, 1024)).unwrap();
    let inc = contact.increment(0.05).unwrap();
    assert!(inc.state.shear_over_estar.iter().all(|&q| q == 0.0));
    assert_eq!(inc.dissipation_over_estar_lambda2, 0.0);
    let frictionless = super::solve(&profile, 0.05, 1024, 1e-10).unwrap();
    let worst = inc
        .state
        .pressure_over_estar
        .iter()
        .zip(&frictionless.pressure_over_estar)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(worst < 1e-12, "largest pressure difference {worst:e}");
}

/// Without friction the curve is Westergaard's: p̄ at the measured a/λ within 1e-4 at N = 8192
/// (measured 7.0e-5 over a/λ 0.14–0.4; 2.8e-4 at 4096, 6.3e-5 at 16384), and the target
/// a/λ = 0.4 is landed on.
#[test]
fn a_frictionless_curve_is_westergaard() {
    let profile = Profile::sinusoid(0.1);
    let request = CurveRequest {
        target: LoadTarget::ContactHalfWidth(0.4),
        points: 8,
        unload: false,
    };
    let curve = solve_curve(&problem(&profile, 0.3, 0.0, 8192), &request, &mut |_, _| {
        std::ops::ControlFlow::Continue(())
    })
    .unwrap();
    for inc in &curve.loading {
        let a = outermost_edge(inc);
        let rel = inc.p_over_estar / westergaard_pressure(0.1, a) - 1.0;
        assert!(rel.abs() < 1e-4, "a/λ = {a}: relative error {rel:e}");
    }
    let last = outermost_edge(curve.loading.last().unwrap());
    assert!((last - 0.4).abs() < 1e-9, "landed at {last}");
}

/// One increment from the unloaded state is proportional loading: the stick zone is where the
/// total tangential displacement vanishes, the self-similar solution of
/// [`spence::proportional_stick_ratio`]. At a/λ = 0.01 on a parabola-like crest (AR 0.001), N = 8192:
/// measured c/a 0.1648 / 0.5553 / 0.7872 against 0.1551 / 0.5517 / 0.7792 (μ 0.2 / 0.5 / 1,
/// ν 0.3); the stick front is read to half a grid step, 0.006 of a here.
#[test]
fn proportional_loading_has_the_self_similar_stick_zone() {
    let profile = Profile::sinusoid(0.001);
    let beta = dundurs_beta(0.3);
    for (mu, tolerance) in [(0.2, 0.012), (0.5, 0.008), (1.0, 0.012)] {
        let mut contact = FrictionalContact::new(&FrictionalProblem {
            coupling: NormalCoupling::Goodman,
            ..problem(&profile, 0.3, mu, 8192)
        })
        .unwrap();
        let inc = contact
            .increment(westergaard_pressure(0.001, 0.01))
            .unwrap();
        let ratio = inc.stick_half_width_over_lambda / outermost_edge(&inc);
        let want = spence::proportional_stick_ratio(mu, beta);
        assert!(
            (ratio - want).abs() < tolerance,
            "μ = {mu}: c/a = {ratio}, closed form {want}"
        );
    }
}

/// A loading–unloading loop under normal load alone: `∮ p̄ dδ` vanishes to rounding (the loop
/// encloses no area), while the work friction does at the face is the backward-Euler slip of
/// finite increments, falling as the increments shrink (measured 8.3e-8, 3.3e-8, 1.2e-8 E*λ²
/// for 10, 20, 40 loading points at AR 0.01, μ 0.5, ν 0.3, a/λ 0.3, N 4096; |∮ p̄ dδ| ≤ 3e-15): the audit says
/// the dissipation of such a loop is an artefact of the step, not physics. Here, N 2048, halving
/// the steps (8 → 16 loading points) takes the face work from 1.09e-7 to 4.46e-8 (ratio 0.41).
#[test]
fn a_normal_loop_dissipates_only_through_its_steps() {
    let profile = Profile::sinusoid(0.01);
    let loop_with = |points| {
        let request = CurveRequest {
            target: LoadTarget::ContactHalfWidth(0.3),
            points,
            unload: true,
        };
        solve_curve(&problem(&profile, 0.3, 0.5, 2048), &request, &mut |_, _| {
            std::ops::ControlFlow::Continue(())
        })
        .unwrap()
    };
    let coarse = loop_with(8);
    let fine = loop_with(16);
    for curve in [&coarse, &fine] {
        let (work, face) = (
            curve.cycle_work_over_estar_lambda2(),
            curve.face_dissipation_over_estar_lambda2(),
        );
        assert!(
            face > 0.0 && work.abs() < 1e-5 * face,
            "∮ p̄ dδ = {work:e}, face {face:e}"
        );
        assert_eq!(curve.unloading.len(), curve.loading.len() - 1);
    }
    let ratio =
        fine.face_dissipation_over_estar_lambda2() / coarse.face_dissipation_over_estar_lambda2();
    eprintln!(
        "face work: 8 points {:e}, 16 points {:e}, ratio {ratio}",
        coarse.face_dissipation_over_estar_lambda2(),
        fine.face_dissipation_over_estar_lambda2()
    );
    assert!(
        ratio > 0.25 && ratio < 0.7,
        "dissipation ratio {ratio} on halving the steps"
    );
}

/// A layer much thicker than the wavelength carries friction as the half-plane does: on
/// `h/λ = 4` every harmonic's matrix is the half-plane's to `e^{−16π}`, so the pressure and the
/// shear of an increment are the half-plane's to the solver's tolerance.
#[test]
fn a_thick_layer_has_the_half_planes_friction() {
    let profile = Profile::sinusoid(0.01);
    let increment = |body| {
        let mut contact = FrictionalContact::new(&FrictionalProblem {
            body,
            ..problem(&profile, 0.3, 0.5, 1024)
        })
        .unwrap();
        contact.increment(0.005).unwrap()
    };
    let half = increment(ElasticBody::HalfPlane);
    let layer = increment(ElasticBody::Layer {
        thickness: 4.0,
        poisson: 0.3,
    });
    let largest = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let differ = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
    };
    let shear = largest(&half.state.shear_over_estar);
    assert!(shear > 0.0);
    let dq = differ(&half.state.shear_over_estar, &layer.state.shear_over_estar);
    let dp = differ(
        &half.state.pressure_over_estar,
        &layer.state.pressure_over_estar,
    );
    let peak = largest(&half.state.pressure_over_estar);
    eprintln!(
        "thick layer against the half-plane: shear {:.1e}, pressure {:.1e} of their peaks",
        dq / shear,
        dp / peak
    );
    assert!(dq < 1e-6 * shear, "shear differs by {dq:e} of {shear:e}");
    assert!(dp < 1e-6 * peak, "pressure differs by {dp:e} of {peak:e}");
}

/// A layer whose ν differs from the problem's is refused, naming the layer.
#[test]
fn a_layer_of_another_poisson_ratio_is_refused() {
    let profile = Profile::sinusoid(0.1);
    let layered = FrictionalProblem {
        body: ElasticBody::Layer {
            thickness: 1.0,
            poisson: 0.4,
        },
        ..problem(&profile, 0.3, 0.5, 1024)
    };
    let error = FrictionalContact::new(&layered).err().unwrap();
    assert!(error.to_string().contains("of the layer"), "{error}");
}

/// Incremental loading of a parabola-like crest (AR 0.001) in Goodman's approximation: the stick
/// zone is Spence's, [`spence::incremental_stick_ratio`] (ν 0.3: 0.4057 at μ 0.2, 0.9677 at μ
/// 0.5), to the grid's reading of the front (a step is 0.012 of a at N 16384, a/λ 0.005) and the
/// periodic crest's departure from a parabola, which grows with a/λ (at μ 0.2 about
/// 3 a/λ in c/a: 0.409, 0.418, 0.425, 0.432 at a/λ 0.0025 … 0.01 on N 32768, whose limit
/// a/λ → 0 is 0.403). 64 equal steps of a.
#[test]
fn incremental_loading_has_spences_stick_zone() {
    let profile = Profile::sinusoid(0.001);
    let beta = dundurs_beta(0.3);
    for (mu, tolerance) in [(0.2, 0.025), (0.5, 0.012)] {
        let mut contact = FrictionalContact::new(&FrictionalProblem {
            coupling: NormalCoupling::Goodman,
            ..problem(&profile, 0.3, mu, 16384)
        })
        .unwrap();
        let steps = 64;
        let mut last = None;
        for j in 1..=steps {
            let a = 0.005 * j as f64 / steps as f64;
            let inc = contact.increment(westergaard_pressure(0.001, a)).unwrap();
            contact.commit(&inc);
            last = Some(inc);
        }
        let inc = last.unwrap();
        let ratio = inc.stick_half_width_over_lambda / outermost_edge(&inc);
        let want = spence::incremental_stick_ratio(mu, beta);
        eprintln!("μ = {mu}: incremental c/a = {ratio}, Spence {want}");
        assert!(
            (ratio - want).abs() < tolerance,
            "μ = {mu}: c/a = {ratio}, Spence {want}"
        );
    }
}
