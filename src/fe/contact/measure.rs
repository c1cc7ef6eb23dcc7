//! What a converged state is worth on the curve: its point (contact half-width, contact
//! fraction and patches, mean pressure from the contact forces and from the slab reaction, slab
//! displacement) and its
//! deformed state with the contact tractions.

use crate::fe::contact::edge_rule::{edge_position, loaded_edge_node};
use crate::fe::contact::patch_edge::TravellingEdge;
use crate::fe::contact::patches::{contact_fraction, contact_patches};
use crate::fe::contact::stick_zone::{stick_nodes, stick_runs, stick_zone};
use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Assembly;
use crate::fe::{CurvePoint, DeformedState, SolveOptions};

/// The modelled width, half a wavelength (units of λ): the mean pressure is a force over it.
pub(crate) const HALF_WAVELENGTH: f64 = 0.5;

/// `p̄/E*` from the contact tractions: the vertical components of the contact forces, which
/// at equilibrium are the internal forces `∂Π/∂y` of the active nodes, over half a wavelength.
pub(crate) fn mean_pressure_over_estar(model: &Model, st: &State, grad: &[f64], estar: f64) -> f64 {
    model.multipliers(st, grad).iter().sum::<f64>() / HALF_WAVELENGTH / estar
}

/// Where a measured point's contact half-width `a/λ` lies.
#[derive(Clone, Copy, Debug)]
pub(crate) enum EdgeAt {
    /// In the element before this contact-face node (the node an edge event brought onto the
    /// indenter, touching with zero force, or the one after the last loaded node;
    /// [`edge_position`]).
    Node(usize),
    /// At the outer edge of the outermost contact patch ([`contact_patches`]): the extent of
    /// the contact of a profile, whose patches need not reach from the peak. With the node of
    /// the event that brought it onto the indenter (touching with zero force), if any.
    OutermostPatch(Option<usize>),
}

/// What [`measure`] finds in a converged state.
pub(crate) struct Measured {
    /// Its point on the curve.
    pub(crate) point: CurvePoint,
    /// Its internal forces `∂Π/∂x`.
    pub(crate) grad: Vec<f64>,
    /// Its contact patches ([`contact_patches`]), which the point counts and sums.
    pub(crate) patches: Vec<[f64; 2]>,
    /// Those of a profile's patch edges that travel between their own events.
    pub(crate) travelling: Vec<TravellingEdge>,
    /// Its stick intervals before they are cut to the patches ([`stick_runs`]).
    pub(crate) stick_runs: Vec<[f64; 2]>,
}

/// The point of a converged state with its contact half-width where `edge` says, its internal
/// forces and its contact patches.
pub(crate) fn measure(
    model: &Model,
    asm: &mut Assembly,
    st: &State,
    estar: f64,
    edge: EdgeAt,
    opts: &SolveOptions,
) -> Measured {
    let f = asm
        .assemble(model, st, false)
        .expect("converged state is not inverted");
    let p_tr = mean_pressure_over_estar(model, st, &f.grad, estar);
    let p_re = model.slab_reaction(&f.grad) / HALF_WAVELENGTH / estar;
    let event = match edge {
        EdgeAt::Node(k) => Some(k),
        EdgeAt::OutermostPatch(event) => event,
    };
    let (patches, travelling) = contact_patches(model, st, &f, opts, event);
    let stick_runs = stick_runs(model, st, &f.grad);
    let stick = stick_zone(&stick_runs, &patches, peak_x(model, st));
    let a_over_lambda = match edge {
        EdgeAt::Node(k) => edge_position(model, st, k, opts.contact.edge_rule),
        EdgeAt::OutermostPatch(_) => patches.last().map_or(0.0, |p| p[1]),
    };
    Measured {
        point: CurvePoint {
            a_over_lambda,
            p_over_estar: p_tr,
            p_over_estar_reaction: p_re,
            slab_displacement_over_lambda: st.d,
            newton_iterations: 0,
            active_nodes: st.active.iter().filter(|&&b| b).count(),
            contact_fraction: contact_fraction(&patches),
            patches: patches.len(),
            stick_fraction: stick.fraction,
            stick_half_width_over_lambda: stick.central_half_width,
            friction_work_over_estar_lambda2: st.friction_work / HALF_WAVELENGTH / estar,
        },
        grad: f.grad,
        patches,
        travelling,
        stick_runs,
    }
}

/// The current `x` of the peak node (units of λ).
pub(crate) fn peak_x(model: &Model, st: &State) -> f64 {
    st.x[model.mesh.bottom[0]][0]
}

/// [`measure`] for a converged state that is not an edge event: the edge in the last loaded
/// element ([`loaded_edge_node`]) for a sinusoid, of the outermost patch for a profile.
pub(crate) fn measure_between_events(
    model: &Model,
    asm: &mut Assembly,
    st: &State,
    estar: f64,
    opts: &SolveOptions,
) -> Measured {
    let f = asm
        .assemble(model, st, false)
        .expect("converged state is not inverted");
    let edge = if model.indenter.profile.is_sinusoid() {
        EdgeAt::Node(loaded_edge_node(model, st, &f, opts))
    } else {
        EdgeAt::OutermostPatch(None)
    };
    measure(model, asm, st, estar, edge, opts)
}

/// The deformed state and its contact tractions: normal and tangential nodal contact
/// forces ([`Model::normal_forces`], [`Model::tangential_forces`]) over each node's
/// tributary length on the deformed face.
pub(crate) fn deformed_state(model: &Model, st: &State, grad: &[f64], estar: f64) -> DeformedState {
    let normal = model.normal_forces(st, grad);
    let tangential = model.tangential_forces(st, grad);
    let b = &model.mesh.bottom;
    let n = b.len();
    let pos = |k: usize| st.x[b[k]];
    let seg = |k: usize| {
        let (p, q) = (pos(k), pos(k + 1));
        ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt()
    };
    let trib = |k: usize| {
        0.5 * (if k > 0 { seg(k - 1) } else { 0.0 } + if k + 1 < n { seg(k) } else { 0.0 })
    };
    DeformedState {
        nodes: st.x.clone(),
        quads: model.mesh.quads.clone(),
        bottom: b.clone(),
        in_contact: st.active.clone(),
        in_stick: stick_nodes(model, st, grad),
        contact_pressure_over_estar: (0..n).map(|k| normal[k] / trib(k) / estar).collect(),
        contact_shear_over_estar: (0..n).map(|k| tangential[k] / trib(k) / estar).collect(),
    }
}
