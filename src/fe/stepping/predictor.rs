//! The start of a load step: the load tangent `∂q/∂d`, the predicted state at a new slab
//! displacement, and the displacement-controlled step that predicts and equilibrates.

use crate::fe::error::StepFail;
use crate::fe::model::{Model, State};
use crate::fe::newton::active_set::{equilibrate, Hold};
use crate::fe::newton::assembly::Assembly;
use crate::fe::SolveOptions;

/// `∂q/∂d` at a converged state: `K ∂q/∂d = −∂r/∂d` (the tangent is positive definite
/// there); `None` if the state is inverted or the solve fails.
pub(crate) fn load_tangent(model: &Model, asm: &mut Assembly, st: &State) -> Option<Vec<f64>> {
    let f = asm.assemble(model, st, true)?;
    let mut rhs = [f.dresid_dd.iter().map(|v| -v).collect::<Vec<f64>>()];
    asm.sys.solve(&mut rhs).ok()?;
    let [z] = rhs;
    Some(z)
}

/// The load tangent of `st` for the predictor if [`StepOptions::tangent_predictor`] is on
/// ([`load_tangent`]).
pub(crate) fn tangent_at(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    st: &State,
) -> Option<Vec<f64>> {
    opts.steps
        .tangent_predictor
        .then(|| load_tangent(model, asm, st))
        .flatten()
}

/// Predictor for the slab displacement `cur.d + dd`: the tangent (Euler) predictor
/// `q + dd · ∂q/∂d` along the load tangent `tangent` of the converged state, else
/// linear extrapolation of the last increment, else a uniform vertical compression.
/// The first that has no inverted element is used.
pub(crate) fn predictor(
    model: &Model,
    cur: &State,
    prev: Option<&State>,
    dd: f64,
    tangent: Option<&[f64]>,
) -> Option<State> {
    let h = model.mesh.thickness;
    let mut tries: Vec<State> = Vec::new();
    if let Some(z) = tangent {
        let mut st = cur.clone();
        st.d = cur.d + dd;
        model.enforce_constraints(&mut st);
        tries.push(model.updated(&st, z, dd));
    }
    if let Some(p) = prev {
        let ddp = cur.d - p.d;
        if ddp > 0.0 {
            let s = dd / ddp;
            let mut st = cur.clone();
            for (xn, (xc, xp)) in st.x.iter_mut().zip(cur.x.iter().zip(&p.x)) {
                xn[0] = xc[0] + s * (xc[0] - xp[0]);
                xn[1] = xc[1] + s * (xc[1] - xp[1]);
            }
            st.d = cur.d + dd;
            tries.push(st);
        }
    }
    let mut st = cur.clone();
    for (xn, xr) in st.x.iter_mut().zip(&model.mesh.nodes) {
        xn[1] -= dd * xr[1] / h;
    }
    st.d = cur.d + dd;
    tries.push(st);
    for mut t in tries {
        model.enforce_constraints(&mut t);
        if model.energy(&t).is_some() {
            return Some(t);
        }
    }
    None
}

/// A displacement-controlled step from the converged state `from` to the slab displacement
/// `d` (exactly: `from.d + (d − from.d)` may differ from `d` in the last bit): predicted along
/// the load tangent of `from`, then equilibrated with its active set, the nodes of `hold` kept
/// as they are. Returns the state (slip not committed) and the Newton iterations.
pub(crate) fn displacement_step(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    from: &State,
    d: f64,
    hold: Hold,
) -> Result<(State, usize), StepFail> {
    let tangent = tangent_at(model, asm, opts, from);
    let mut st =
        predictor(model, from, None, d - from.d, tangent.as_deref()).ok_or(StepFail::Inverted {
            iteration: 0,
            residual: f64::NAN,
        })?;
    st.d = d;
    model.enforce_constraints(&mut st);
    let iters = equilibrate(model, asm, &mut st, opts, hold)?;
    Ok((st, iters))
}
