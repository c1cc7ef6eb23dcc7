//! Friction verification (issue #4, 2 (i)): a block pressed onto a flat rigid surface and
//! then sheared slides when the mean shear reaches min(μ p̄, τ_max) and not before
//! (`wavy::fe::shear_test`). Reference: the Coulomb–Orowan law itself (R3): the total
//! friction force of a sliding face is Σ min(μ N_i, τ_max ℓ_i), which is μ p̄ W when
//! Coulomb governs everywhere and τ_max × (deformed face length) when Orowan does.
use crate::curve_pairs::{coarse_steps_to_0_4, coarse_to_0_4, largest_relative_difference};
use std::ops::ControlFlow;
use wavy::fe::shear_test::{press_and_shear, ShearPoint, ShearTest};
use wavy::fe::CoulombOrowan;

fn run(mu: f64, tau_max_over_estar: f64) -> Vec<ShearPoint> {
    run_with_band(mu, tau_max_over_estar, 0.005)
}

fn run_with_band(
    mu: f64,
    tau_max_over_estar: f64,
    elastic_slip_over_element: f64,
) -> Vec<ShearPoint> {
    let test = ShearTest {
        kappa_over_g: 2.0 / 3.0, // ν = 0: uniform pressure, friction idle while pressing
        friction: CoulombOrowan {
            friction_coefficient: mu,
            tau_max_over_estar,
            elastic_slip_over_element,
        },
        elements: (16, 8),
        height_over_width: 0.5,
        press_over_height: 0.02,
        shift_over_height: 0.03,
        steps: (2, 30),
    };
    press_and_shear(&test).expect("press and shear")
}

fn check(points: &[ShearPoint], expected_limit: impl Fn(&ShearPoint) -> f64, what: &str) {
    let sliding = points
        .iter()
        .position(|p| p.slipping_nodes == p.nodes)
        .unwrap_or_else(|| panic!("{what}: the block never slides"));
    assert!(
        sliding > 3 && sliding + 5 < points.len(),
        "{what}: sliding starts at step {sliding} of {}",
        points.len()
    );
    for (i, p) in points.iter().enumerate() {
        let limit = expected_limit(p);
        // the threshold sum is the law's limit (exact identity of the nodal sums)
        assert!(
            (p.threshold_over_estar / limit - 1.0).abs() <= 1e-9,
            "{what} step {i}: Σ thresholds {} vs limit {limit}",
            p.threshold_over_estar
        );
        // never above the limit (Newton residual ≤ 1e-10 of the nodal forces)
        assert!(
            p.mean_shear_over_estar <= limit * (1.0 + 1e-8),
            "{what} step {i}: shear {} above the limit {limit}",
            p.mean_shear_over_estar
        );
        if i < sliding {
            // not before: some node sticks, the face has not slid, the shear is below
            assert!(p.min_face_displacement_over_elastic_slip <= 1.0 + 1e-9);
            assert!(
                p.mean_shear_over_estar < limit * (1.0 - 1e-6),
                "{what} step {i}: at the limit {limit} before sliding"
            );
        } else {
            // sliding: the shear sits on the limit and the whole face moves on
            assert!(
                (p.mean_shear_over_estar / limit - 1.0).abs() <= 1e-8,
                "{what} step {i}: shear {} vs limit {limit}",
                p.mean_shear_over_estar
            );
        }
    }
    let last = points.last().unwrap();
    assert!(
        last.min_face_displacement_over_elastic_slip > 10.0,
        "{what}: face moved only {} e_c",
        last.min_face_displacement_over_elastic_slip
    );
    // the shear rises until sliding
    for w in points[..=sliding].windows(2) {
        assert!(w[1].mean_shear_over_estar > w[0].mean_shear_over_estar);
    }
}

#[test]
fn block_slides_at_mu_p_when_coulomb_governs() {
    let mu = 0.3;
    let pts = run(mu, 10.0);
    // p̄/E* ≈ the pressing strain 0.02 (ν = 0, E* = E)
    let p = pts[0].mean_pressure_over_estar;
    assert!((p / 0.02 - 1.0).abs() < 0.02, "p̄/E* = {p}");
    check(&pts, |pt| mu * pt.mean_pressure_over_estar, "Coulomb");
}

#[test]
fn block_slides_at_tau_max_when_orowan_governs() {
    let tau = 0.004; // below μ p̄ = 0.02 with μ = 1
    let pts = run(1.0, tau);
    check(&pts, |pt| tau * pt.contact_length_over_width, "Orowan");
    // the deformed face is as long as the undeformed one to O(strain²)
    let l = pts.last().unwrap().contact_length_over_width;
    assert!((l - 1.0).abs() < 1e-3, "face length / width = {l}");
}

use wavy::fe::{
    solve_curve, Curve, Interface, LayerProblem, MeshLevel, SlipFront, SolveOptions, TouchedNodes,
};

fn wavy_curve(ar: f64, tau_max_over_estar: f64, mesh: MeshLevel) -> Curve {
    let opts = SolveOptions {
        mesh,
        ..Default::default()
    };
    curve_with(ar, tau_max_over_estar, &opts)
}

fn curve_with(ar: f64, tau_max_over_estar: f64, opts: &SolveOptions) -> Curve {
    curve_with_band(ar, tau_max_over_estar, 0.005, opts)
}

fn curve_with_band(
    ar: f64,
    tau_max_over_estar: f64,
    elastic_slip_over_element: f64,
    opts: &SolveOptions,
) -> Curve {
    let pb = LayerProblem {
        interface: Interface::coulomb_orowan(1.0, tau_max_over_estar, elastic_slip_over_element),
        ..wavy::defaults::layer_problem(ar)
    };
    solve_curve(&pb, opts, &mut |_| ControlFlow::Continue(())).expect("curve")
}

/// The semismooth choice of the friction branches in the Newton step
/// (`NewtonOptions::semismooth_friction`, on by default) changes the path to each
/// equilibrium, not the equilibrium: at AR 0.3, τ_max/E* 0.2 (coarse mesh, to a/λ 0.4)
/// every point of the curve with it matches the curve without it to 10⁻⁸ relative (the
/// Newton tolerance is 10⁻¹⁰ of the nodal forces; this test prints the largest difference),
/// and it needs fewer Newton iterations and tangent assemblies (counted, deterministic; the
/// counts it prints are recorded in docs/performance.md).
#[test]
fn semismooth_branch_choice_changes_the_path_not_the_curve() {
    let opts = |semismooth_friction| coarse_to_0_4(|n| n.semismooth_friction = semismooth_friction);
    let (with, without) = (
        curve_with(0.3, 0.2, &opts(true)),
        curve_with(0.3, 0.2, &opts(false)),
    );
    let largest = largest_relative_difference(&with, &without);
    eprintln!("largest relative difference with/without: {largest:.2e}");
    assert!(largest <= 1e-8, "with and without differ by {largest:e}");
    let iterations = |c: &Curve| c.points.iter().map(|p| p.newton_iterations).sum::<usize>();
    eprintln!(
        "Newton iterations {} with, {} without; tangent assemblies {} with, {} without",
        iterations(&with),
        iterations(&without),
        with.work.tangent_assemblies,
        without.work.tangent_assemblies
    );
    assert!(iterations(&with) < iterations(&without));
    assert!(with.work.tangent_assemblies < without.work.tangent_assemblies);
    // every friction row and the columns it touches lie on the contact face and the layer
    // of nodes above it, which the factorisation orders last: the Woodbury solve reads S⁻¹
    // there from the factor's trailing block, never by unit-vector solves (`fe::linsys`)
    assert_eq!(with.work.woodbury_unit_solves, 0);
    assert_eq!(without.work.woodbury_unit_solves, 0);
}

/// Holding a sliding node that lies beyond its stick band at the band's middle when the Newton
/// step puts it on stick (`NewtonOptions::return_into_band`, on by default), instead of
/// linearising it on the band's spring continued out to where it is, changes the path to each
/// equilibrium, not the equilibrium: at AR 0.3, τ_max/E* 0.1 and 0.2 (coarse mesh, loaded to a/λ
/// 0.4 and unloaded) every point with it matches the loop without it to 10⁻⁸ relative (this test
/// prints the largest difference). Its saving is the unloading's: over the two loops it takes
/// fewer Newton iterations (counted, deterministic; printed; measured 298 and 253 against 295 and
/// 278, the first loop's loading 111 against 98: with the node that has just touched held in the
/// load tangent, few loading steps still put a node beyond its band).
#[test]
fn returning_into_the_band_changes_the_path_not_the_curve() {
    let opts = |return_into_band| coarse_to_0_4(|n| n.return_into_band = return_into_band);
    let [with, without] = same_loops(
        &[0.1, 0.2],
        [("with", &opts(true)), ("without", &opts(false))],
        Branches::Both,
    );
    assert!(with < without, "{with} against {without}");
}

/// Which branches of a loop [`same_loops`] counts the Newton iterations of.
#[derive(Clone, Copy)]
enum Branches {
    Both,
    Unloading,
}

/// The AR 0.3 loops ([`loop_with`]) at each τ_max/E* of `taus` solved with two named option sets,
/// asserted the same curve ([`assert_same_curve`]); returns the Newton iterations each took over
/// all the loops, on `branches`.
fn same_loops(taus: &[f64], solves: [(&str, &SolveOptions); 2], branches: Branches) -> [usize; 2] {
    let iterations = |c: &Curve| {
        let loading = match branches {
            Branches::Both => c.points.as_slice(),
            Branches::Unloading => &[],
        };
        (loading.iter().chain(&c.unloading))
            .map(|p| p.newton_iterations)
            .sum::<usize>()
    };
    let [(a, opts_a), (b, opts_b)] = solves;
    let mut totals = [0, 0];
    for &tau_max_over_estar in taus {
        let first = loop_with(0.3, tau_max_over_estar, opts_a);
        let second = loop_with(0.3, tau_max_over_estar, opts_b);
        let largest = largest_relative_difference(&first, &second)
            .max(largest_unloading_difference(&first, &second));
        let counts = [(a, iterations(&first)), (b, iterations(&second))];
        assert_same_curve(tau_max_over_estar, largest, counts);
        totals[0] += counts[0].1;
        totals[1] += counts[1].1;
    }
    totals
}

/// Prints how far two solves of one case lie apart (`largest`, relative) and the Newton
/// iterations of each, named; asserts they are the same curve to 10⁻⁸.
fn assert_same_curve(tau_max_over_estar: f64, largest: f64, counts: [(&str, usize); 2]) {
    let [(a, na), (b, nb)] = counts;
    eprintln!(
        "τ_max/E* {tau_max_over_estar}: largest relative difference {largest:.2e}, Newton \
         iterations {na} {a}, {nb} {b}"
    );
    assert!(largest <= 1e-8, "{a} and {b} differ by {largest:e}");
}

/// The loading–unloading loop of [`curve_with`]'s problem.
fn loop_with(ar: f64, tau_max_over_estar: f64, opts: &SolveOptions) -> Curve {
    let pb = LayerProblem {
        interface: Interface::coulomb_orowan(1.0, tau_max_over_estar, 0.005),
        ..wavy::defaults::layer_problem(ar)
    };
    wavy::fe::solve_cycle(&pb, opts, &mut |_, _| ControlFlow::Continue(()))
        .unwrap_or_else(|e| panic!("AR {ar}, τ_max/E* {tau_max_over_estar}: {e}"))
}

/// The largest relative difference of p̄/E* between the unloading points of `a` and `b`, which
/// must have the same points (asserted); each relative to `b`'s p̄/E*, at least 10⁻¹² (a loop
/// ends at zero load).
fn largest_unloading_difference(a: &Curve, b: &Curve) -> f64 {
    assert_eq!(a.unloading.len(), b.unloading.len(), "the unloading points");
    (a.unloading.iter().zip(&b.unloading))
        .map(|(p, q)| (p.p_over_estar - q.p_over_estar).abs() / q.p_over_estar.abs().max(1e-12))
        .fold(0.0, f64::max)
}

/// Holding the contact-face node that has just touched where it touched in the load tangent
/// (`StepOptions::touched_nodes`, held by default), instead of letting it slide freely as the
/// consistent tangent does at zero normal force, changes the predictor of each event, not the
/// equilibrium: at AR 0.3, τ_max/E* 0.1 and 0.2 (coarse mesh, to a/λ 0.4) every point with it
/// matches the curve without it to 10⁻⁸ relative (measured 1.7e-9; this test prints the largest
/// difference), in fewer Newton iterations (counted, deterministic; printed; measured 111 and 92
/// against 159 and 161).
#[test]
fn holding_the_touched_node_in_the_tangent_changes_the_path_not_the_curve() {
    let opts = |touched| coarse_steps_to_0_4(|s| s.touched_nodes = touched);
    let iterations = |c: &Curve| c.points.iter().map(|p| p.newton_iterations).sum::<usize>();
    for tau_max_over_estar in [0.1, 0.2] {
        let held = curve_with(0.3, tau_max_over_estar, &opts(TouchedNodes::Held));
        let free = curve_with(0.3, tau_max_over_estar, &opts(TouchedNodes::Free));
        let largest = largest_relative_difference(&held, &free);
        let counts = [("held", iterations(&held)), ("free", iterations(&free))];
        assert_same_curve(tau_max_over_estar, largest, counts);
        assert!(iterations(&held) < iterations(&free));
    }
}

/// Following an unloading step's slip front in its prediction (`StepOptions::slip_front`,
/// followed by default: the stuck nodes that start to slide in the step put on slip where they
/// reach their band's edge) instead of holding them stuck as the load tangent does changes the
/// predictor of each unloading step, not the equilibrium: at AR 0.3, τ_max/E* 0.02 and 0.05
/// (coarse mesh, loaded to a/λ 0.4 and unloaded), every point with it matches the loop without
/// it to 10⁻⁸ relative (measured 1.3e-10; this test prints the largest difference), in fewer
/// Newton iterations over the two loops' unloading (counted, deterministic; printed; measured 117
/// and 151 against 120 and 202).
#[test]
fn following_the_slip_front_changes_the_path_not_the_curve() {
    let opts = |slip_front| coarse_steps_to_0_4(|s| s.slip_front = slip_front);
    let [followed, held] = same_loops(
        &[0.02, 0.05],
        [
            ("followed", &opts(SlipFront::Followed)),
            ("held", &opts(SlipFront::Held)),
        ],
        Branches::Unloading,
    );
    assert!(followed < held, "{followed} against {held}");
}

/// A Newton pass from the predictor's pressure iterate accepting a line-search trial where either
/// residual falls enough, the displacement method's or the mixed method's
/// (`NewtonOptions::either_residual_merit`, on by default), instead of the displacement method's
/// alone, changes the path to each equilibrium, not the equilibrium: at AR 0.3, τ_max/E* 0.02
/// and 0.05 (coarse mesh, loaded to a/λ 0.4 and unloaded), every point with it matches the loop
/// without it to 10⁻⁸ relative (measured 2.6·10⁻¹¹; this test prints the largest difference), in
/// fewer Newton iterations over the two loops' unloading (counted, deterministic; printed;
/// measured 111 and 138 against 117 and 151).
#[test]
fn either_residual_changes_the_path_not_the_curve() {
    let opts = |either| coarse_to_0_4(|n| n.either_residual_merit = either);
    let [either, displacement] = same_loops(
        &[0.02, 0.05],
        [
            ("either residual", &opts(true)),
            ("displacement residual", &opts(false)),
        ],
        Branches::Unloading,
    );
    assert!(either < displacement, "{either} against {displacement}");
}

/// Exact stick (`elastic_slip_over_element = 0`): the decision stiffness `c_t` of the
/// active-set decision changes the Newton path, not the curve. At AR 0.3, τ_max/E* 0.1 (coarse
/// mesh, to a/λ 0.4), `c_t` = 0.1 G and 1 G (the default) give the same points to 10⁻⁸
/// (measured 5·10⁻¹¹; the test prints it). Not asserted, because it does not hold: with
/// `c_t` = 10 G the curve leaves these in a/λ 0.10–0.17 (p̄ up to 1.6 % apart at equal a/λ) and
/// rejoins them to 10⁻¹¹ beyond. Both states satisfy the law and equilibrium to the Newton
/// tolerance: on this nearly incompressible layer with μ 1 some increments have more than one
/// solution, and the decision's path picks one (docs/replication.md, R3).
#[test]
fn exact_stick_decision_stiffness_changes_the_path_not_the_curve() {
    let opts = |stick_decision_stiffness| {
        coarse_to_0_4(|n| n.stick_decision_stiffness = stick_decision_stiffness)
    };
    let soft = curve_with_band(0.3, 0.1, 0.0, &opts(0.1));
    let default = curve_with_band(0.3, 0.1, 0.0, &opts(1.0));
    assert_eq!(soft.points.len(), default.points.len());
    let mut largest = 0.0_f64;
    for (p, q) in soft.points.iter().zip(&default.points) {
        for (x, y) in [
            (p.a_over_lambda, q.a_over_lambda),
            (p.p_over_estar, q.p_over_estar),
            (p.stick_fraction, q.stick_fraction),
        ] {
            let d = (x - y).abs() / y.abs().max(1e-3);
            largest = largest.max(d);
            assert!(d <= 1e-8, "{x} with c_t 0.1 G, {y} with 1 G");
        }
    }
    eprintln!("largest relative difference between c_t 0.1 G and 1 G: {largest:.2e}");
}

/// The penalty law's curve converges to the exact-stick curve as its band closes, at first
/// order: at AR 0.3, τ_max/E* 0.1 (coarse mesh), the difference of p̄ at a/λ 0.1 and 0.4
/// shrinks by 8.6 and 9.9 (measured; 10 is first order) from e_c = 0.005 to 0.0005 element,
/// and is 1.8·10⁻³ and 1.8·10⁻⁴ at the default band (the test prints them). So exact stick is
/// the law the penalty approximates, and the default band's regularisation error is that
/// difference.
#[test]
fn penalty_stick_converges_to_exact_stick_at_first_order() {
    let opts = SolveOptions {
        mesh: MeshLevel::Coarse,
        until_a_over_lambda: 0.42,
        ..Default::default()
    };
    let exact = curve_with_band(0.3, 0.1, 0.0, &opts);
    let band = |e_c: f64| curve_with_band(0.3, 0.1, e_c, &opts);
    let (default, tenth) = (band(0.005), band(0.0005));
    for a in [0.1, 0.4] {
        let p = |c: &Curve| c.p_at(a).expect("a/λ on the curve");
        let (d0, d1) = (p(&default) - p(&exact), p(&tenth) - p(&exact));
        eprintln!(
            "a/λ {a}: p̄ − p̄_exact {:.3e} (e_c 0.005), {:.3e} (0.0005)",
            d0 / p(&exact),
            d1 / p(&exact)
        );
        assert!((d0 / p(&exact)).abs() < 2.5e-3, "default band off by {d0}");
        let ratio = d0 / d1;
        assert!((7.0..12.0).contains(&ratio), "a/λ {a}: ratio {ratio}");
    }
}

/// Exact stick on the sheared block: the face starts held (no node slides at the first step),
/// the shear stays below the law's limit `μ p̄` until every node slides, and then sits on it.
#[test]
fn exact_stick_holds_the_block_until_it_slides_at_mu_p() {
    let mu = 0.3;
    let points = run_with_band(mu, 10.0, 0.0);
    let sliding = points
        .iter()
        .position(|p| p.slipping_nodes == p.nodes)
        .expect("the block slides");
    assert!(
        sliding > 3 && sliding + 5 < points.len(),
        "slides at step {sliding}"
    );
    for (i, p) in points.iter().enumerate() {
        let limit = mu * p.mean_pressure_over_estar;
        if i < sliding {
            assert!(
                p.mean_shear_over_estar < limit,
                "step {i}: at the limit before sliding"
            );
        } else {
            assert!(
                (p.mean_shear_over_estar / limit - 1.0).abs() <= 1e-8,
                "step {i}: shear {} vs limit {limit}",
                p.mean_shear_over_estar
            );
        }
    }
    let first = &points[0];
    assert_eq!(first.slipping_nodes, 0, "the face sticks at first");
}

fn a_values() -> Vec<f64> {
    (0..8).map(|i| 0.1 + 0.05 * i as f64).collect()
}

/// Issue #4, 2 (ii): in the linear limit (AR = 0.01, κ/G = 1000) friction changes p̄(a) by less
/// than 0.2 %: linear theory has no normal–tangential coupling for an incompressible solid on a
/// rigid indenter (R4), so the strongest friction of the sweep (μ = 1, τ_max/E* = 0.2) must be
/// nearly idle. Same mesh for both curves, so discretisation errors cancel. Measured: at most
/// 0.096 % (at a/λ = 0.1); asserted < 0.2 %, about twice that.
#[test]
fn friction_is_idle_in_the_linear_limit() {
    let free = wavy_curve(0.01, 0.0, MeshLevel::Coarse);
    let fric = wavy_curve(0.01, 0.2, MeshLevel::Coarse);
    for a in a_values() {
        let (p0, p1) = (free.p_at(a).unwrap(), fric.p_at(a).unwrap());
        let effect = p1 / p0 - 1.0;
        eprintln!("AR 0.01 a {a:.2}: friction effect {:.4} %", 100.0 * effect);
        assert!(
            effect.abs() < 0.002,
            "a {a}: friction changes p̄ by {effect}"
        );
    }
}

/// Issue #4, 2 (iii): at AR = 0.3 the effect of the shear strength on p̄(a) (τ_max/E* = 0.2
/// against frictionless, μ = 1) is resolved well above the discretisation error. The error of
/// the default (48×24) mesh is bounded by the Richardson estimate from its difference to the
/// coarse (32×16) one at order 1, which over-estimates it for any convergence order ≥ 1
/// (e₂ = |f₁ − f₂|/(ρ^q − 1), ρ = 1.5); the effect must exceed five times that bound wherever
/// friction matters (a/λ ≥ 0.2), and both numbers are printed (recorded in
/// docs/verification.md).
#[test]
fn friction_effect_at_ar_0_3_is_resolved_above_discretisation_error() {
    let curves = |mesh| (wavy_curve(0.3, 0.0, mesh), wavy_curve(0.3, 0.2, mesh));
    let (free_c, fric_c) = curves(MeshLevel::Coarse);
    let (free_d, fric_d) = curves(MeshLevel::Default);
    let mut compared = 0;
    for a in a_values() {
        // the coarse frictional curve's last event may fall just short of 0.45
        if [&free_c, &fric_c, &free_d, &fric_d]
            .iter()
            .any(|c| c.p_at(a).is_none())
        {
            continue;
        }
        compared += 1;
        let p = |c: &Curve| c.p_at(a).expect("in range");
        let effect = p(&fric_d) / p(&free_d) - 1.0;
        let error = (p(&fric_d) / p(&fric_c) - 1.0)
            .abs()
            .max((p(&free_d) / p(&free_c) - 1.0).abs())
            / (MeshLevel::REFINEMENT_RATIO - 1.0);
        eprintln!(
            "AR 0.3 a {a:.2}: friction effect {:+.2} %, default-mesh error bound {:.3} %",
            100.0 * effect,
            100.0 * error
        );
        if a >= 0.2 - 1e-9 {
            assert!(
                effect.abs() >= 5.0 * error,
                "a {a}: effect {effect} not resolved above the error bound {error}"
            );
        }
    }
    assert!(compared >= 7, "only {compared} a/λ values in every curve");
}
