//! The energy audit of a frictional loop: the work the load does, `∫ p̄ dd`, is the elastic energy
//! the layer stores plus the work of friction at the face, at every point of loading and
//! unloading (`CurvePoint::friction_work_over_estar_lambda2`, `StepState`'s elastic energy), and
//! on a closed loop, where the elastic energy is back to zero, the face's work is the loop's
//! dissipation. Each side is computed its own way: the load's work by the trapezoid rule on the
//! converged points, the elastic energy from the state, the face's work node by node from the
//! friction forces and slips. A friction law that stored or lost energy, or a slip history
//! carried wrongly from step to step, would open a gap here.
use std::ops::ControlFlow;
use wavy::fe::{
    solve_with_states, Interface, Kinematics, LayerProblem, LoadDirection, MeshLevel, SolveOptions,
    StepOptions,
};

/// The AR 0.3 sinusoid on the nearly incompressible layer, μ 1, `τ_max/E*` as given, exact
/// stick.
fn problem(tau_max_over_estar: f64) -> LayerProblem {
    LayerProblem {
        aspect_ratio: 0.3,
        finer_harmonics: wavy::profile::FinerHarmonics::NONE,
        thickness_over_lambda: 1.0,
        kappa_over_g: 1000.0,
        kinematics: Kinematics::Finite,
        interface: match tau_max_over_estar > 0.0 {
            true => Interface::coulomb_orowan(1.0, tau_max_over_estar, 0.0),
            false => Interface::Frictionless,
        },
    }
}

/// One converged point of the audit, over E* λ².
#[derive(Clone, Copy, Debug)]
struct Audit {
    branch: LoadDirection,
    /// The slab displacement `d/λ` and `p̄/E*` of the point.
    at: (f64, f64),
    /// `∫ p̄ dd` from the undeformed state to here (trapezoid rule on the converged points).
    load_work: f64,
    elastic_energy: f64,
    friction_work: f64,
}

impl Audit {
    /// What the load did that the layer neither stores nor the face dissipated.
    fn gap(&self) -> f64 {
        self.load_work - self.elastic_energy - self.friction_work
    }
}

/// The loop on 32 face elements loaded to a/λ 0.4, unloading each loading interval in
/// `unloading_substeps` steps, audited at every point.
fn audited_loop(p: &LayerProblem, unloading_substeps: usize) -> Vec<Audit> {
    let opts = SolveOptions {
        mesh: MeshLevel::along_face(32),
        until_a_over_lambda: 0.4,
        steps: StepOptions {
            unloading_substeps,
            ..StepOptions::default()
        },
        ..SolveOptions::default()
    };
    let mut audits: Vec<Audit> = vec![];
    let mut last = (0.0, 0.0);
    solve_with_states(p, &opts, true, &mut |branch, point, state| {
        let (d, pressure) = (point.slab_displacement_over_lambda, point.p_over_estar);
        let before = audits.last().map_or(0.0, |a| a.load_work);
        audits.push(Audit {
            branch,
            at: (d, pressure),
            load_work: before + 0.5 * (pressure + last.1) * (d - last.0),
            elastic_energy: state.elastic_energy_over_estar_lambda2,
            friction_work: point.friction_work_over_estar_lambda2,
        });
        last = (d, pressure);
        ControlFlow::Continue(())
    })
    .unwrap_or_else(|f| panic!("{p:?}, {unloading_substeps} unloading substeps: {f}"));
    audits
}

/// The largest gap of one branch, over the loop's dissipation (its last point's load work).
fn largest_gap(audits: &[Audit], branch: LoadDirection) -> f64 {
    let dissipation = audits.last().expect("a point").load_work;
    audits
        .iter()
        .filter(|a| a.branch == branch)
        .map(|a| a.gap().abs() / dissipation)
        .fold(0.0, f64::max)
}

/// Without friction the face does no work, and the load's work is the elastic energy at every
/// point to the trapezoid rule's error: measured at most 9.6e-4 of the largest load work
/// (the loading peak's), asserted 1.5e-3.
#[test]
fn without_friction_the_face_does_no_work() {
    let audits = audited_loop(&problem(0.0), 1);
    assert!(audits.iter().all(|a| a.friction_work == 0.0));
    let peak = audits.iter().map(|a| a.load_work).fold(0.0, f64::max);
    let gap = audits.iter().map(|a| a.gap().abs()).fold(0.0, f64::max) / peak;
    eprintln!("largest gap over the peak load work: {gap:.2e}");
    assert!(
        gap <= 1.5e-3,
        "the load's work is not the elastic energy: {gap:e}"
    );
}

/// With friction (`τ_max/E*` 0.05, exact stick) every point of the loop accounts for the load's
/// work to the quadrature's error: measured at most 7.79e-3 of the loop's dissipation along loading
/// (asserted 9e-3), 7.03e-3 along unloading with one unloading step per loading step and 1.10e-2
/// with four (asserted 8e-3 and 1.25e-2). The load's work is the trapezoid rule on the points, the
/// face's work is summed over the committed steps, the points and the sub-steps of the events whose
/// first try failed, so the gap is the two quadratures' difference and moves with the solver's
/// steps: since friction's pieces are read from the pressure iterate's forces the events that
/// committed sub-steps before converge from their first try, and the face's work is summed over
/// fewer steps (the points' p̄ are those of before to 1e-11); with those sub-steps it measured
/// 6.34e-3, 3.80e-3 and 7.86e-3, before the pressure iterate (11 committed sub-steps) 2.8e-3, 7.9e-3 and 1.9e-3
/// (docs/verification.md, "The energy audit"). The last point is the closed loop,
/// where the face's work is the dissipation. The finer steps sample the unloading branch without
/// moving it: where both runs have a point (the loading points' displacements), p̄ agrees within
/// 1.2e-7 of the peak p̄ (asserted 1e-6; Newton stops at a residual of 1e-10 of the largest nodal
/// force, `NewtonOptions::residual_rtol`): slip hardly reverses inside an interval, and one
/// return-mapping step lands where four do. A history carried wrongly from step to step would move
/// it.
#[test]
fn the_face_and_the_layer_account_for_the_work_of_the_load() {
    let p = problem(0.05);
    let coarse = audited_loop(&p, 1);
    let fine = audited_loop(&p, 4);
    let loading = largest_gap(&coarse, LoadDirection::Loading);
    let (unloading_coarse, unloading_fine) = (
        largest_gap(&coarse, LoadDirection::Unloading),
        largest_gap(&fine, LoadDirection::Unloading),
    );
    eprintln!(
        "largest gap over the dissipation: loading {loading:.2e}; unloading {unloading_coarse:.2e} (1 step per loading step), {unloading_fine:.2e} (4)"
    );
    assert!(loading <= 9e-3, "loading: {loading:e}");
    assert!(
        unloading_coarse <= 8e-3 && unloading_fine <= 1.25e-2,
        "unloading: {unloading_coarse:e} (1 step), {unloading_fine:e} (4 steps)"
    );
    let end = fine.last().expect("a point");
    assert!(end.elastic_energy.abs() <= 1e-12 * end.load_work, "{end:?}");
    let unloading = |audits: &[Audit]| -> Vec<(f64, f64)> {
        let on_branch = audits
            .iter()
            .filter(|a| a.branch == LoadDirection::Unloading);
        on_branch.map(|a| a.at).collect()
    };
    let peak = coarse.iter().map(|a| a.at.1).fold(0.0, f64::max);
    let fine_points = unloading(&fine);
    let shared: Vec<f64> = unloading(&coarse)
        .into_iter()
        .filter_map(|(d, p)| {
            let same = fine_points.iter().find(|f| f.0 == d)?;
            Some((same.1 - p).abs() / peak)
        })
        .collect();
    let moved = shared.iter().copied().fold(0.0, f64::max);
    eprintln!(
        "unloading p̄ at the {} shared displacements: within {moved:.1e} of the peak",
        shared.len()
    );
    assert!(shared.len() >= 20, "{} shared displacements", shared.len());
    assert!(
        moved <= 1e-6,
        "the unloading branch moved by {moved:e} of the peak"
    );
}
