//! Verification scene of the friction law: a block pressed onto a flat rigid surface and
//! then sheared by its slab.
//!
//! ```text
//!        d_x →  ┌──────────────┐  rigid slab (bonded), pressed down by d, shifted by d_x
//!               │              │
//!   free side   │    block     │  free side          height h, width ½ (units of λ)
//!               │              │
//!  ─────────────┴──────────────┴──────────── flat rigid surface y = 0, Coulomb–Orowan
//! ```
//!
//! With Coulomb–Orowan friction the block slides as a whole when the slab's mean shear
//! force reaches the sum of the nodal thresholds, `Σ min(μ N_i, τ_max ℓ_i)/W`, i.e.
//! `min(μ p̄, τ_max)` for a uniform pressure, and not before; `tests/solver/fe_friction.rs`
//! checks that. The same model, solver and friction code as the wavy problem are used:
//! only the indenter (amplitude 0) and the lateral faces ([`Lateral::Free`]) differ.

use super::{Kinematics, SolveError, SolveOptions};
use crate::fe::contact::friction::{CoulombOrowan, Interface};
use crate::fe::contact::indenter::Indenter;
use crate::fe::model::material::{estar_over_g, NeoHooke};
use crate::fe::model::mesh::{Grading, Mesh};
use crate::fe::model::{Lateral, Model, State};
use crate::fe::newton::active_set::{equilibrate, Hold};
use crate::fe::newton::assembly::Assembly;

/// The press-then-shear test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShearTest {
    /// Bulk over shear modulus `κ/G` (2/3 gives `ν = 0`: no lateral expansion under
    /// pressure, so the pressure is uniform and friction is idle while pressing).
    pub kappa_over_g: f64,
    /// The interface law.
    pub friction: CoulombOrowan,
    /// Elements along the width and the height.
    pub elements: (usize, usize),
    /// Block height over its width (the width is ½ in units of λ).
    pub height_over_width: f64,
    /// Slab displacement pressing the block, over its height.
    pub press_over_height: f64,
    /// Final slab shift over the height.
    pub shift_over_height: f64,
    /// Load steps of the pressing and of the shearing phase.
    pub steps: (usize, usize),
}

/// One converged state of the shearing phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShearPoint {
    /// Slab shift `d_x` over the block height.
    pub shift_over_height: f64,
    /// Horizontal slab force over the width, over `E*`.
    pub mean_shear_over_estar: f64,
    /// Vertical contact force over the width, over `E*`.
    pub mean_pressure_over_estar: f64,
    /// Sum of the nodal friction thresholds `Σ min(μ N_i, τ_max ℓ_i)` over the width,
    /// over `E*`.
    pub threshold_over_estar: f64,
    /// Deformed length of the contact face over the width.
    pub contact_length_over_width: f64,
    /// Contact-face nodes in slip (`|e| = e_c`), and all contact-face nodes.
    pub slipping_nodes: usize,
    pub nodes: usize,
    /// Smallest horizontal displacement of a contact-face node over the elastic slip
    /// `e_c`: at most 1 while any node sticks, growing once the whole face slides.
    pub min_face_displacement_over_elastic_slip: f64,
}

/// Width of the block, units of λ.
const WIDTH: f64 = 0.5;

/// Press the block, then shear it; one point per shearing step.
pub fn press_and_shear(test: &ShearTest) -> Result<Vec<ShearPoint>, SolveError> {
    let model = block_model(test);
    let h = model.mesh.thickness;
    let mut asm = Assembly::new(&model);
    let opts = SolveOptions::default();
    let mut st = model.initial_state();
    for k in 0..st.active.len() {
        model.activate(&mut st, k);
    }
    let (n_press, n_shear) = test.steps;
    let mut points = Vec::with_capacity(n_shear);
    for step in 1..=n_press + n_shear {
        if step <= n_press {
            press_predictor(
                &model,
                &mut st,
                test.press_over_height * h * step as f64 / n_press as f64,
            );
        } else {
            let shift = test.shift_over_height * h * (step - n_press) as f64 / n_shear as f64;
            shear_predictor(&model, &mut st, shift);
        }
        model.enforce_constraints(&mut st);
        equilibrate(&model, &mut asm, &mut st, &opts, Hold::NONE)
            .map_err(|f| f.into_error(step, st.d))?;
        asm.commit_slip(&model, &mut st);
        if step > n_press {
            points.push(shear_point(&model, &mut asm, &st, step)?);
        }
    }
    Ok(points)
}

/// The block of `test` on the flat surface: its mesh (uniform, the width [`WIDTH`]), material
/// and friction law, the lateral faces free.
fn block_model(test: &ShearTest) -> Model {
    let h = test.height_over_width * WIDTH;
    let (nx, ny) = test.elements;
    let mesh = Mesh::graded(
        nx,
        ny,
        h,
        Grading {
            peak_ratio: 1.0,
            first_layer_over_dx: h / ny as f64 * nx as f64 / WIDTH,
            coarsen_at_aspect: 0.0,
        },
    );
    let mat = NeoHooke {
        g: 1.0,
        kappa: test.kappa_over_g,
    };
    Model::new(
        mesh,
        mat,
        Kinematics::Finite,
        Indenter::sinusoid(0.0),
        Interface::CoulombOrowan(test.friction),
        Lateral::Free,
    )
}

/// A pressing step to slab displacement `d`: uniform compression as the predictor.
fn press_predictor(model: &Model, st: &mut State, d: f64) {
    let h = model.mesh.thickness;
    st.d = d;
    for (x, xr) in st.x.iter_mut().zip(&model.mesh.nodes) {
        x[1] = xr[1] * (h - d) / h;
    }
}

/// A shearing step to slab shift `shift`: simple shear of the increment as the predictor.
fn shear_predictor(model: &Model, st: &mut State, shift: f64) {
    let h = model.mesh.thickness;
    for (x, xr) in st.x.iter_mut().zip(&model.mesh.nodes) {
        x[0] += (shift - st.dx) * xr[1] / h;
    }
    st.dx = shift;
}

/// What the converged state `st` of shearing step `step` reads: forces, thresholds, contact
/// length and slip.
fn shear_point(
    model: &Model,
    asm: &mut Assembly,
    st: &State,
    step: usize,
) -> Result<ShearPoint, SolveError> {
    let h = model.mesh.thickness;
    let estar = estar_over_g(model.mat.kappa / model.mat.g);
    let e_c = model.elastic_slip_limit().expect("friction is built");
    let f = asm.assemble(model, st, false).ok_or(SolveError::Inverted {
        step,
        iteration: 0,
        residual: f64::NAN,
    })?;
    let b = &model.mesh.bottom;
    let normal: f64 = model.normal_forces(st, &f.grad).iter().sum();
    let threshold: f64 = model.friction_thresholds(st, &f.grad).iter().sum();
    let length: f64 = b
        .windows(2)
        .map(|w| {
            let (p, q) = (st.x[w[0]], st.x[w[1]]);
            (q[0] - p[0]).hypot(q[1] - p[1])
        })
        .sum();
    let min_disp = b
        .iter()
        .map(|&n| st.x[n][0] - model.mesh.nodes[n][0])
        .fold(f64::INFINITY, f64::min);
    Ok(ShearPoint {
        shift_over_height: st.dx / h,
        mean_shear_over_estar: model.slab_shear(&f.grad) / WIDTH / estar,
        mean_pressure_over_estar: normal / WIDTH / estar,
        threshold_over_estar: threshold / WIDTH / estar,
        contact_length_over_width: length / WIDTH,
        slipping_nodes: st
            .slip
            .iter()
            .filter(|s| match e_c > 0.0 {
                true => s.elastic.abs() >= e_c * (1.0 - 1e-12),
                false => s.held != crate::fe::contact::friction::Branch::Stick,
            })
            .count(),
        nodes: b.len(),
        min_face_displacement_over_elastic_slip: min_disp / e_c,
    })
}
