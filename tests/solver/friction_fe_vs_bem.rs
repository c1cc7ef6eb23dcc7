//! The finite elements' friction against the frictional boundary elements of the same layer, on
//! the same load path (issue 43; docs/verification.md, "The finite elements against it"): a
//! compressible layer a quarter wavelength thick (κ/G 2.1667, ν 0.3) on a rigid base, where
//! the normal–tangential coupling is strong, linear kinematics, AR 0.001 (the indenter's tilt
//! negligible), μ 0.5, exact stick, loaded to a/λ 0.3 and unloaded. The boundary elements follow
//! the FE's mean pressures increment for increment, so both solve the same backward-Euler problem
//! of friction; what differs is the discretisation of space.
use std::ops::ControlFlow;
use wavy::bem::frictional_contact::{FrictionalProblem, InterfaceLaw, NormalCoupling};
use wavy::bem::frictional_curve::{follow_pressures, outermost_edge, FrictionalCurve};
use wavy::bem::ElasticBody;
use wavy::fe::{
    cycle_friction_work_over_estar_lambda2, solve_cycle, Curve, CurvePoint, Interface, Kinematics,
    LayerProblem, LoadDirection, MeshLevel, SolveOptions,
};
use wavy::profile::Profile;

const THICKNESS: f64 = 0.25;
const KAPPA_OVER_G: f64 = 2.1667;
const AR: f64 = 0.001;
const MU: f64 = 0.5;
/// An Orowan cap below μ p over most of the contact (the peak pressure is about 7 AR E*): the
/// loop then dissipates by slip, not only through its steps.
const TAU_CAP: f64 = 1e-4;

fn fe_loop(kappa_over_g: f64, (mu, tau): (f64, f64), nx: usize) -> Curve {
    let problem = LayerProblem {
        thickness_over_lambda: THICKNESS,
        kappa_over_g,
        kinematics: Kinematics::Linear,
        interface: Interface::coulomb_orowan(mu, tau, 0.0),
        ..wavy::defaults::layer_problem(AR)
    };
    let opts = SolveOptions {
        mesh: MeshLevel::Elements { nx, ny: nx / 4 },
        until_a_over_lambda: 0.3,
        ..Default::default()
    };
    solve_cycle(&problem, &opts, &mut |_: LoadDirection, _: &CurvePoint| {
        ControlFlow::Continue(())
    })
    .expect("FE loop")
}

fn bem_along(kappa_over_g: f64, (mu, tau): (f64, f64), fe: &Curve, grid: usize) -> FrictionalCurve {
    let profile = Profile::sinusoid(AR);
    let poisson = wavy::fe::poisson_ratio(kappa_over_g);
    let problem = FrictionalProblem {
        profile: &profile,
        body: ElasticBody::Layer {
            thickness: THICKNESS,
            poisson,
        },
        poisson,
        law: InterfaceLaw {
            friction_coefficient: mu,
            tau_max_over_estar: tau,
        },
        coupling: NormalCoupling::Full,
        points_per_wavelength: grid,
        tol: 1e-10,
    };
    let pressures = |points: &[CurvePoint]| -> Vec<f64> {
        points
            .iter()
            .map(|p| p.p_over_estar)
            .filter(|&p| p > 0.0)
            .collect()
    };
    follow_pressures(&problem, &pressures(&fe.points), &pressures(&fe.unloading))
        .expect("BEM curve")
}

/// Over the loading points from a/λ 0.03: the largest `|a_FE/a_BEM − 1|` and the largest
/// stick half-width difference in face elements at the contact edge (the FE's a/λ step there).
fn differences(fe: &Curve, bem: &FrictionalCurve) -> (f64, f64) {
    let mut a_error = 0.0f64;
    let mut stick_elements = 0.0f64;
    for (i, (f, b)) in fe.points.iter().zip(&bem.loading).enumerate().skip(1) {
        if f.a_over_lambda < 0.03 {
            continue;
        }
        a_error = a_error.max((f.a_over_lambda / outermost_edge(b) - 1.0).abs());
        let element = f.a_over_lambda - fe.points[i - 1].a_over_lambda;
        let dc = f.stick_half_width_over_lambda - b.stick_half_width_over_lambda;
        stick_elements = stick_elements.max(dc.abs() / element);
    }
    (a_error, stick_elements)
}

/// What one mesh measured against the boundary elements on its own path.
#[derive(Debug)]
struct Measured {
    frictionless_a_error: f64,
    a_error: f64,
    stick_elements: f64,
    /// The capped loop's face work of friction, FE over BEM, minus 1.
    capped_work_error: f64,
}

fn measure(nx: usize, grid: usize) -> Measured {
    let along = |law: (f64, f64)| {
        let fe = fe_loop(KAPPA_OVER_G, law, nx);
        let bem = bem_along(KAPPA_OVER_G, law, &fe, grid);
        (fe, bem)
    };
    let (fe, bem) = along((0.0, 0.0));
    let (frictionless_a_error, _) = differences(&fe, &bem);
    let (fe, bem) = along((MU, 1e3));
    let (a_error, stick_elements) = differences(&fe, &bem);
    let (fe, bem) = along((MU, TAU_CAP));
    let capped_work_error = cycle_friction_work_over_estar_lambda2(&fe.unloading)
        / bem.face_dissipation_over_estar_lambda2()
        - 1.0;
    Measured {
        frictionless_a_error,
        a_error,
        stick_elements,
        capped_work_error,
    }
}

/// Meshes 32 × 8 and 64 × 16 against N 2048. Friction adds no error of its own to the contact
/// half-width: the largest |a_FE/a_BEM − 1| from a/λ 0.03 is 9.2e-3 and 6.6e-3 with friction,
/// 1.23e-2 and 6.6e-3 without (order 0.9; asserted: with friction at most 1.05 times without,
/// and without at most 0.6 times on the finer mesh). The stick zone's half-width is within one
/// face element at every point (0.66 and 0.61 elements). The capped loop's work of friction
/// converges to the boundary elements' (−14.0 % and −3.8 %, order 1.9; asserted: at least
/// halved).
#[test]
fn fe_friction_follows_the_boundary_elements_on_the_same_path() {
    let [coarse, fine] = [32, 64].map(|nx| measure(nx, 2048));
    eprintln!("mesh 32: {coarse:?}\nmesh 64: {fine:?}");
    for m in [&coarse, &fine] {
        assert!(m.a_error <= 1.05 * m.frictionless_a_error, "{m:?}");
        assert!(m.stick_elements < 1.0, "{m:?}");
    }
    assert!(fine.frictionless_a_error < 0.6 * coarse.frictionless_a_error);
    assert!(fine.capped_work_error.abs() < 0.5 * coarse.capped_work_error.abs());
}

/// A layer that slips everywhere by the end of loading (ν 0.45, κ/G 9.667, where the fundamental's
/// coupling is −0.17, the Orowan cap): on unloading every node must first stick and then slip
/// back, so the face's work of friction never falls. Newton used to accept a state whose nodes
/// slid back under their loading force (a round-off correction on pieces of the law it had not
/// obeyed): the face work then retraced its loading values, to 1.0e-9 where the boundary
/// elements on the same path dissipate 8.3e-9. Mesh 32 × 8 against N 2048: the first unloading
/// point sticks whole, the face work falls by 3e-4 of its loaded value on that step (the
/// trapezoid rule where the slip reverses inside a step; asserted ≤ 1e-3) and rises after it, to
/// 0.971 of the boundary elements' (asserted within 5 %).
#[test]
fn unloading_a_slipping_layer_sticks_first_and_dissipates() {
    let (kappa_over_g, law) = (9.667, (MU, TAU_CAP));
    let fe = fe_loop(kappa_over_g, law, 32);
    let loaded = fe.points.last().unwrap().friction_work_over_estar_lambda2;
    let mut work = loaded;
    for p in &fe.unloading {
        let w = p.friction_work_over_estar_lambda2;
        assert!(
            w >= work - 1e-3 * loaded,
            "face work falls to {w:e} from {work:e}"
        );
        work = w;
    }
    let bem = bem_along(kappa_over_g, law, &fe, 2048);
    let ratio = work / bem.face_dissipation_over_estar_lambda2();
    eprintln!("loop's face work FE / BEM = {ratio}");
    assert!((ratio - 1.0).abs() < 0.05, "FE / BEM face work {ratio}");
}
