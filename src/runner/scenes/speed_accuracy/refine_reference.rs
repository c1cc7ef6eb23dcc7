//! `wavy refine-reference`: the limit of every case of a speed_accuracy spec on its
//! `reference_meshes`, written by the CLI to the file `crate::runner::scenes::speed_accuracy::reference_curves` describes.

use crate::accuracy::extrapolation::mesh_limit_with_spread;
use crate::fe::{convergence, Kinematics};
use crate::runner::scenes::speed_accuracy::reference_curves::{ReferenceCurves, ReferencePoint};
use crate::runner::scenes::speed_accuracy::SpeedAccuracyScene;
use crate::runner::sweep::fe_cases::{FeCase, SolvedCases};
use crate::runner::RunOptions;
use anyhow::{bail, Context, Result};

/// Computes the reference of every case of `scene` on its `reference_meshes` (curves from the
/// cache or solved on all threads, as a run does). Fails, naming the case and the mesh, when a
/// curve stops short of the grid or the fit has no finite limit.
pub fn compute(scene: &SpeedAccuracyScene, opts: &RunOptions) -> Result<ReferenceCurves> {
    let meshes = &scene.reference_meshes;
    let xs = scene.a_over_lambda.values();
    let physics = scene.physics();
    let ars = scene.ars();
    let cases: Vec<(f64, f64)> = scene
        .taus()
        .into_iter()
        .flat_map(|tau| ars.iter().map(move |&ar| (ar, tau)))
        .collect();
    let fe_cases: Vec<FeCase> = cases
        .iter()
        .flat_map(|&(ar, tau)| {
            meshes
                .iter()
                .map(move |&nx| scene.case(Kinematics::Finite, nx, ar, tau))
        })
        .collect();
    let solved = SolvedCases::solve(fe_cases, opts)?;
    let mut points = vec![];
    for &(ar, tau) in &cases {
        let at = format!("AR = {ar}, τ_max = {tau} MPa");
        let mut curves = vec![];
        for &nx in meshes {
            let o = solved
                .outcome(&scene.case(Kinematics::Finite, nx, ar, tau))
                .expect("every reference curve was solved");
            if let Some(f) = &o.failure {
                bail!("{at}: the reference curve on mesh {nx} stopped: {f}");
            }
            curves.push(&o.points);
        }
        for &x in &xs {
            let values: Vec<f64> = curves
                .iter()
                .zip(meshes)
                .map(|(c, nx)| {
                    convergence::p_at(c, x).with_context(|| {
                        format!("{at}: the curve on mesh {nx} does not reach a/λ = {x}")
                    })
                })
                .collect::<Result<_>>()?;
            let (p0, spread) = mesh_limit_with_spread(meshes, &values)
                .filter(|(p0, s)| p0.is_finite() && *p0 > 0.0 && s.is_finite())
                .with_context(|| {
                    format!("{at}, a/λ = {x}: no finite positive limit of {values:?}")
                })?;
            points.push(ReferencePoint {
                aspect_ratio: ar,
                tau_max_mpa: tau,
                physics,
                a_over_lambda: x,
                p_over_estar: p0,
                spread,
            });
        }
    }
    let mesh_list: Vec<String> = meshes.iter().map(|n| n.to_string()).collect();
    Ok(ReferenceCurves {
        provenance: vec![
            (
                "computed_by".into(),
                "wavy refine-reference (make reference)".into(),
            ),
            ("meshes".into(), mesh_list.join(" ")),
            (
                "fit".into(),
                "p(n) = p0 + c1/n + c2/n^2 per a/λ, least squares over the meshes (n elements along the face)".into(),
            ),
        ],
        points,
    })
}
