//! Discrete model: mesh, material, boundary conditions, contact by elimination and the
//! friction history: what a solve reads and does not change (the mutable side is
//! [`crate::fe::newton::assembly::Assembly`]).
//!
//! Unknowns are current node positions. Each node owns two equation slots; a slot is
//! either free, with a coefficient vector `c = ∂(x, y)/∂q` mapping the slot's unknown
//! `q` to the node's position, or constrained (identity row) ([`Model::slot_map`]).
//!
//! Boundary conditions (units of λ, `h` the thickness, `d` the slab displacement, `d_x`
//! its horizontal shift, 0 in the wavy problem):
//! * bonded face `Y = h`: `x = X + d_x`, `y = h − d` (moves with the rigid slab);
//! * lateral faces `X = 0`, `X = ½`: `x = X` (symmetry, [`Lateral::Symmetric`]), `y`
//!   free; or traction-free ([`Lateral::Free`], the block of the friction test);
//! * contact face `Y = 0`: free, or active (on the indenter, see [`crate::fe::contact::indenter`]),
//!   with the friction force of [`Interface::CoulombOrowan`] on active sliding nodes.
//!
//! Loading is by the slab displacement `d` (displacement control). For monotonic,
//! frictionless (path-independent) loading the equilibrium states are the same as under
//! the corresponding force control, and displacement control avoids the limit-point
//! and rigid-body issues of force control.

pub mod element;
pub mod material;
pub mod mesh;
pub mod mixed_pressure;

use crate::fe::contact::friction::{
    FrictionEval, FrictionLaw, Interface, NormalForce, SlipHistory,
};
use crate::fe::contact::indenter::Indenter;
use crate::fe::model::element::QuadRef;
use crate::fe::model::material::NeoHooke;
use crate::fe::model::mesh::Mesh;
use crate::fe::Kinematics;

/// Iteration cap of the closest-point projection ([`Model::project_closest`]). Newton on
/// the closest-point equation converges quadratically from a node within an element of
/// the surface; the cap is a safeguard.
const PROJECTION_MAX_ITERATIONS: usize = 20;

/// The closest-point projection stops once its correction is below this (units of λ):
/// about ten ulps of a position `x ≤ ½` (one ulp is 1.1·10⁻¹⁶), i.e. at round-off.
const PROJECTION_STEP_TOL: f64 = 1e-15;

/// Boundary condition of the lateral faces `X = 0` and `X = ½`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Lateral {
    /// `x = X`: symmetry planes of the periodic wavy problem (docs/replication.md R1).
    #[default]
    Symmetric,
    /// Traction-free: a finite block.
    Free,
}

/// What constrains a node's two slots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::fe) enum Role {
    Interior,
    Top,
    Side,
    Bottom,
    BottomCorner,
}

/// Mutable solution state.
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// Current node positions.
    pub x: Vec<[f64; 2]>,
    /// Active flag per contact-face node (same order as `Mesh::bottom`).
    pub active: Vec<bool>,
    /// Slab displacement `d/λ` (positive pressing the layer onto the indenter).
    pub d: f64,
    /// Horizontal slab shift `d_x/λ` (0 in the wavy problem).
    pub dx: f64,
    /// Friction history per contact-face node (empty without friction).
    pub slip: Vec<SlipHistory>,
    /// Work of friction at the contact face along the path up to the last commit of the slip
    /// history ([`Model::commit_slip`]), over the modelled half wavelength (units `G λ²` per
    /// unit depth; 0 without friction): what the face has dissipated, and under the penalty law
    /// the work its elastic slips hold.
    pub friction_work: f64,
    /// Mean pressure of each element (units `G`) that the tangent's geometric volumetric term
    /// uses, carried through a Newton solve as the mixed (Q1/P0) method's pressure iterate
    /// ([`Model::carry_pressure`]); `None` at converged states, where each element's own
    /// `κ (v/V − 1)` is used.
    pub pressure: Option<Vec<f64>>,
}

/// The discrete model.
#[derive(Clone, Debug)]
pub struct Model {
    /// Mesh.
    pub mesh: Mesh,
    /// Material (`G = 1`).
    pub mat: NeoHooke,
    /// Kinematics.
    pub kin: Kinematics,
    /// Indenter.
    pub indenter: Indenter,
    /// Lateral faces.
    pub lateral: Lateral,
    /// The friction law in solver units (`None` without friction).
    pub(in crate::fe) friction: Option<FrictionLaw>,
    /// Reference geometry of each element.
    pub(in crate::fe) refs: Vec<QuadRef>,
    /// Element stiffness matrices of linear kinematics (empty for finite kinematics).
    pub(in crate::fe) k_lin: Vec<[[f64; 8]; 8]>,
    /// Boundary role of each node.
    pub(in crate::fe) role: Vec<Role>,
}

pub(in crate::fe) type SlotMap = Vec<[Option<[f64; 2]>; 2]>;

impl Model {
    /// Build the model. The interface's `τ_max/E*` is converted to solver units (`G = 1`)
    /// with the material's `E*/G`, and its elastic slip to a length with the mean face
    /// element size.
    pub fn new(
        mesh: Mesh,
        mat: NeoHooke,
        kin: Kinematics,
        indenter: Indenter,
        interface: Interface,
        lateral: Lateral,
    ) -> Self {
        let friction = match interface {
            Interface::Frictionless => None,
            Interface::CoulombOrowan(f) => {
                let width = mesh.nodes[*mesh.bottom.last().expect("contact face")][0]
                    - mesh.nodes[mesh.bottom[0]][0];
                Some(FrictionLaw::in_solver_units(&f, &mat, width, mesh.nx))
            }
        };
        let refs: Vec<QuadRef> = mesh
            .quads
            .iter()
            .map(|q| {
                QuadRef::new(&[
                    mesh.nodes[q[0]],
                    mesh.nodes[q[1]],
                    mesh.nodes[q[2]],
                    mesh.nodes[q[3]],
                ])
            })
            .collect();
        let k_lin = match kin {
            Kinematics::Linear => mesh
                .quads
                .iter()
                .zip(&refs)
                .map(|(q, r)| {
                    let xr = [
                        mesh.nodes[q[0]],
                        mesh.nodes[q[1]],
                        mesh.nodes[q[2]],
                        mesh.nodes[q[3]],
                    ];
                    element::tangent(r, &mat, &xr, None)
                        .expect("reference element is valid")
                        .hess
                })
                .collect(),
            Kinematics::Finite => Vec::new(),
        };
        let mut role = vec![Role::Interior; mesh.nodes.len()];
        if lateral == Lateral::Symmetric {
            for &n in mesh.sides.iter().flatten() {
                role[n] = Role::Side;
            }
        }
        for &b in &mesh.bottom {
            role[b] = Role::Bottom;
        }
        if lateral == Lateral::Symmetric {
            role[mesh.bottom[0]] = Role::BottomCorner;
            role[mesh.bottom[mesh.nx]] = Role::BottomCorner;
        }
        for &t in &mesh.top {
            role[t] = Role::Top;
        }
        Self {
            mesh,
            mat,
            kin,
            indenter,
            lateral,
            friction,
            refs,
            k_lin,
            role,
        }
    }

    /// Undeformed state with only the peak node in contact.
    pub fn initial_state(&self) -> State {
        let mut active = vec![false; self.mesh.bottom.len()];
        active[0] = true;
        let slip = if self.friction.is_some() {
            self.mesh
                .bottom
                .iter()
                .map(|&n| SlipHistory::fresh(self.mesh.nodes[n][0]))
                .collect()
        } else {
            Vec::new()
        };
        State {
            x: self.mesh.nodes.clone(),
            active,
            d: 0.0,
            dx: 0.0,
            slip,
            friction_work: 0.0,
            pressure: None,
        }
    }

    /// Whether the reduced problem is an energy minimisation with a symmetric tangent
    /// (frictionless), or not (friction).
    pub fn is_potential(&self) -> bool {
        self.friction.is_none()
    }

    fn bottom_slot(&self) -> Vec<Option<usize>> {
        let mut b = vec![None; self.mesh.nodes.len()];
        for (k, &n) in self.mesh.bottom.iter().enumerate() {
            b[n] = Some(k);
        }
        b
    }

    pub(in crate::fe) fn slot_map(&self, st: &State) -> SlotMap {
        let bidx = self.bottom_slot();
        (0..self.mesh.nodes.len())
            .map(|n| match self.role[n] {
                Role::Interior => [Some([1.0, 0.0]), Some([0.0, 1.0])],
                Role::Top => [None, None],
                Role::Side => [None, Some([0.0, 1.0])],
                Role::BottomCorner => {
                    if st.active[bidx[n].expect("bottom node")] {
                        [None, None]
                    } else {
                        [None, Some([0.0, 1.0])]
                    }
                }
                Role::Bottom => {
                    if st.active[bidx[n].expect("bottom node")] {
                        let s = match self.kin {
                            Kinematics::Finite => self.indenter.slope(st.x[n][0]),
                            Kinematics::Linear => 0.0,
                        };
                        [Some([1.0, s]), None]
                    } else {
                        [Some([1.0, 0.0]), Some([0.0, 1.0])]
                    }
                }
            })
            .collect()
    }

    /// Enforce the prescribed and contact constraints on `st` (top at `h − d`, lateral
    /// `x = X`, active nodes on the indenter).
    pub fn enforce_constraints(&self, st: &mut State) {
        let h = self.mesh.thickness;
        for (n, r) in self.role.iter().enumerate() {
            let xr = self.mesh.nodes[n];
            match r {
                Role::Top => st.x[n] = [xr[0] + st.dx, h - st.d],
                Role::Side | Role::BottomCorner => st.x[n][0] = xr[0],
                _ => {}
            }
        }
        for (k, &n) in self.mesh.bottom.iter().enumerate() {
            if st.active[k] {
                st.x[n][1] = self.surface_y(st, n);
            }
        }
    }

    fn surface_y(&self, st: &State, n: usize) -> f64 {
        match self.kin {
            Kinematics::Finite => self.indenter.y(st.x[n][0]),
            Kinematics::Linear => self.indenter.y(self.mesh.nodes[n][0]),
        }
    }

    /// Gap of each contact-face node (`y − y_s(x)`, at the reference `X` for linear
    /// kinematics).
    pub fn gaps(&self, st: &State) -> Vec<f64> {
        self.mesh
            .bottom
            .iter()
            .map(|&n| st.x[n][1] - self.surface_y(st, n))
            .collect()
    }

    pub(in crate::fe) fn elem_x(&self, st: &State, e: usize) -> [[f64; 2]; 4] {
        let q = self.mesh.quads[e];
        [st.x[q[0]], st.x[q[1]], st.x[q[2]], st.x[q[3]]]
    }

    pub(in crate::fe) fn linear_elem(&self, st: &State, e: usize) -> (f64, [f64; 8]) {
        let q = self.mesh.quads[e];
        let mut u = [0.0; 8];
        for a in 0..4 {
            for i in 0..2 {
                u[2 * a + i] = st.x[q[a]][i] - self.mesh.nodes[q[a]][i];
            }
        }
        let k = &self.k_lin[e];
        let mut g = [0.0; 8];
        let mut en = 0.0;
        for a in 0..8 {
            g[a] = (0..8).map(|b| k[a][b] * u[b]).sum();
            en += 0.5 * u[a] * g[a];
        }
        (en, g)
    }

    /// Total energy, `None` if any element is inverted.
    pub fn energy(&self, st: &State) -> Option<f64> {
        let mut e = 0.0;
        for k in 0..self.mesh.quads.len() {
            e += match self.kin {
                Kinematics::Finite => {
                    element::energy(&self.refs[k], &self.mat, &self.elem_x(st, k))?
                }
                Kinematics::Linear => self.linear_elem(st, k).0,
            };
        }
        Some(e)
    }

    /// Slope `y_s'` of the indenter under contact-face node `n` as the contact law sees
    /// it (0 for linear kinematics).
    pub(in crate::fe) fn contact_slope(&self, st: &State, n: usize) -> f64 {
        match self.kin {
            Kinematics::Finite => self.indenter.slope(st.x[n][0]),
            Kinematics::Linear => 0.0,
        }
    }

    /// Arc length along the indenter from `x0` to `x1` as the contact law sees it.
    pub(in crate::fe) fn contact_arc(&self, x0: f64, x1: f64) -> f64 {
        match self.kin {
            Kinematics::Finite => self.indenter.arc_length(x0, x1),
            Kinematics::Linear => x1 - x0,
        }
    }

    /// Trial elastic slip `e*` of active contact-face node `k`
    /// ([`SlipHistory::trial_elastic_slip`]).
    fn trial_elastic_slip(&self, st: &State, k: usize) -> f64 {
        let n = self.mesh.bottom[k];
        let h = st.slip[k];
        h.trial_elastic_slip(self.contact_arc(h.anchor_x, st.x[n][0]))
    }

    /// Friction force of active contact-face node `k` ([`FrictionLaw::eval`]), given the
    /// internal forces `grad` of the residual and, where `st` has a pressure iterate, those of
    /// the iterate ([`Self::iterate_forces`], `None` otherwise): the regime is the iterate's
    /// ([`NormalForce`]).
    pub(in crate::fe) fn friction_eval(
        &self,
        st: &State,
        k: usize,
        (grad, iterate): (&[f64], Option<&[f64]>),
        law: &FrictionLaw,
    ) -> FrictionEval {
        let b = &self.mesh.bottom;
        let n = b[k];
        let curvature = match self.kin {
            Kinematics::Finite => self.indenter.curvature(st.x[n][0]),
            Kinematics::Linear => 0.0,
        };
        let neighbours = [k.wrapping_sub(1), k + 1].map(|m| b.get(m).map(|&nm| st.x[nm]));
        let [residual, _] = self.node_contact_force(st, grad, n);
        let normal = match iterate {
            Some(g) => NormalForce {
                residual,
                iterate: self.node_contact_force(st, g, n)[0],
            },
            None => NormalForce::converged(residual),
        };
        law.eval(
            (self.contact_slope(st, n), curvature),
            (&st.slip[k], self.trial_elastic_slip(st, k)),
            st.x[n],
            neighbours,
            normal,
        )
    }

    /// Commit the friction history of a converged load step on every contact-face node:
    /// `e_{n+1} = e_c φ`, `S_{n+1} = S(x)` and the tangential force on active nodes, reset on
    /// free ones, and add the step's work of friction to the state's
    /// ([`crate::fe::contact::friction::FrictionLaw::commit`]). `grad` is the converged
    /// state's `∂Π/∂x`, from which the forces follow. No-op without friction.
    pub fn commit_slip(&self, st: &mut State, grad: &[f64]) {
        let Some(law) = self.friction else { return };
        let tangential = self.tangential_forces(st, grad);
        for (k, &n) in self.mesh.bottom.iter().enumerate() {
            let step = st.active[k].then(|| (self.trial_elastic_slip(st, k), tangential[k]));
            let (committed, work) = law.commit(step, st.x[n][0], &st.slip[k]);
            st.slip[k] = committed;
            st.friction_work += work;
        }
    }

    /// Put contact-face node `k` in contact: mark it active, move it to its closest point
    /// on the indenter, and start its friction history there with no elastic slip, unless it
    /// was in contact at the last converged step (released and put back within one load step,
    /// [`SlipHistory::in_contact`]), which keeps its committed history: a step's converged state
    /// does not depend on the order in which the active-set passes changed its contact set.
    pub fn activate(&self, st: &mut State, k: usize) {
        st.active[k] = true;
        self.project_closest(st, k);
        if self.friction.is_some() && !st.slip[k].in_contact {
            st.slip[k] = SlipHistory::fresh(st.x[self.mesh.bottom[k]][0]);
        }
    }

    /// Contact force of every contact-face node in the indenter's frame, `[N, T]` (0 on free
    /// nodes; per unit depth, units `G λ`): the normal force `N = (g_y − y_s' g_x)/w` and the
    /// tangential force `T = (g_x + y_s' g_y)/w` along `(1, y_s')/w`, the friction force at
    /// equilibrium.
    fn contact_forces(&self, st: &State, grad: &[f64]) -> Vec<[f64; 2]> {
        self.mesh
            .bottom
            .iter()
            .enumerate()
            .map(|(k, &n)| {
                if !st.active[k] {
                    return [0.0; 2];
                }
                self.node_contact_force(st, grad, n)
            })
            .collect()
    }

    /// `[N, T]` of contact-face node `n` as if it were in contact ([`Self::contact_forces`]).
    fn node_contact_force(&self, st: &State, grad: &[f64], n: usize) -> [f64; 2] {
        let s = self.contact_slope(st, n);
        let w = (1.0 + s * s).sqrt();
        let (gx, gy) = (grad[2 * n], grad[2 * n + 1]);
        [(gy - s * gx) / w, (gx + s * gy) / w]
    }

    /// Normal contact force `N` of every contact-face node (`Self::contact_forces`).
    pub fn normal_forces(&self, st: &State, grad: &[f64]) -> Vec<f64> {
        self.contact_forces(st, grad).iter().map(|f| f[0]).collect()
    }

    /// Tangential contact force `T` of every contact-face node (`Self::contact_forces`); 0 on
    /// a symmetry line, where the friction traction is antisymmetric and the node's tangential
    /// force is the reaction of the symmetry plane (`x = X`) instead.
    pub fn tangential_forces(&self, st: &State, grad: &[f64]) -> Vec<f64> {
        self.contact_forces(st, grad)
            .iter()
            .zip(&self.mesh.bottom)
            .map(|(f, &n)| match self.role[n] {
                Role::BottomCorner => 0.0,
                _ => f[1],
            })
            .collect()
    }

    /// Friction threshold `L = min(μ N, τ_max ℓ)` of every active contact-face node (units
    /// `G λ`; empty without friction).
    pub fn friction_thresholds(&self, st: &State, grad: &[f64]) -> Vec<f64> {
        let Some(law) = self.friction else {
            return Vec::new();
        };
        (0..self.mesh.bottom.len())
            .map(|k| {
                if !st.active[k] {
                    return 0.0;
                }
                self.friction_eval(st, k, (grad, None), &law).limit
            })
            .collect()
    }

    /// Elastic slip `e_c` at which the friction threshold is mobilised (units of λ;
    /// `None` without friction).
    pub fn elastic_slip_limit(&self) -> Option<f64> {
        self.friction.map(|f| f.slip_c)
    }

    /// Horizontal force transmitted by the slab, `Σ_top ∂Π/∂x` (per unit depth, units `G λ`).
    pub fn slab_shear(&self, grad: &[f64]) -> f64 {
        self.mesh.top.iter().map(|&n| grad[2 * n]).sum::<f64>()
    }

    /// Apply the Newton update `α δ` (slot-wise) to `base`. Sliding nodes move in `x`
    /// and are put back on the indenter exactly (`y = y_s(x)`).
    pub fn updated(&self, base: &State, dq: &[f64], alpha: f64) -> State {
        let mut st = base.clone();
        let map = self.slot_map(base);
        for n in 0..self.mesh.nodes.len() {
            for s in 0..2 {
                if map[n][s].is_some() {
                    st.x[n][s] += alpha * dq[2 * n + s];
                }
            }
        }
        self.enforce_constraints(&mut st);
        st
    }

    /// `st` carried along the load path's direction `rate` (slot-wise, per unit slab
    /// displacement) to the slab displacement `st.d + dd`: the slab moved, then [`Self::updated`].
    pub fn along(&self, st: &State, rate: &[f64], dd: f64) -> State {
        let mut moved = st.clone();
        moved.d = st.d + dd;
        self.enforce_constraints(&mut moved);
        self.updated(&moved, rate, dd)
    }

    /// Move contact-face node `k` (about to be activated) to the closest point of the
    /// indenter (finite kinematics; a few Newton steps on
    /// `(x − x₀) + (y_s(x) − y₀) y_s'(x) = 0`). A vertical projection would distort the
    /// adjacent elements strongly where the indenter is steep.
    pub fn project_closest(&self, st: &mut State, k: usize) {
        if self.kin != Kinematics::Finite {
            return;
        }
        let n = self.mesh.bottom[k];
        if self.role[n] == Role::BottomCorner {
            return;
        }
        let [x0, y0] = st.x[n];
        let mut x = x0;
        for _ in 0..PROJECTION_MAX_ITERATIONS {
            let (ys, s, c) = (
                self.indenter.y(x),
                self.indenter.slope(x),
                self.indenter.curvature(x),
            );
            let f = (x - x0) + (ys - y0) * s;
            let df = 1.0 + s * s + (ys - y0) * c;
            if df <= 0.0 {
                break;
            }
            let dx = f / df;
            x -= dx;
            if dx.abs() < PROJECTION_STEP_TOL {
                break;
            }
        }
        if x.is_finite() {
            // the half period X ∈ [0, ½] of the mesh
            st.x[n][0] = x.clamp(0.0, 0.5);
        }
    }

    /// Edge constraint on contact-face node `k` (held free): its gap `c = y − y_s(x)`
    /// (at the reference `X` for linear kinematics) and `∂c/∂(x, y)`.
    pub fn edge_constraint(&self, st: &State, k: usize) -> (f64, [f64; 2]) {
        let n = self.mesh.bottom[k];
        let c = st.x[n][1] - self.surface_y(st, n);
        let dc = match self.kin {
            Kinematics::Finite => [-self.indenter.slope(st.x[n][0]), 1.0],
            Kinematics::Linear => [0.0, 1.0],
        };
        (c, dc)
    }

    /// The change `∇c·z` of the gap `c` of free contact-face node `k` along a slot vector
    /// `z` ([`Self::edge_constraint`]), as a function of `z`: with the load tangent `z`
    /// ([`crate::fe::stepping::predictor::load_tangent`]) the rate `∂g_k/∂d` at which the gap closes.
    pub fn gap_rate_along(&self, st: &State, k: usize) -> impl Fn(&[f64]) -> f64 {
        let node = self.mesh.bottom[k];
        let (_, dc) = self.edge_constraint(st, k);
        move |z: &[f64]| dc[0] * z[2 * node] + dc[1] * z[2 * node + 1]
    }

    /// Multipliers `λ_i = ∂Π/∂y_i` of the contact-face nodes (0 on free nodes).
    pub fn multipliers(&self, st: &State, grad: &[f64]) -> Vec<f64> {
        self.mesh
            .bottom
            .iter()
            .enumerate()
            .map(|(k, &n)| if st.active[k] { grad[2 * n + 1] } else { 0.0 })
            .collect()
    }

    /// Vertical force transmitted by the slab, `−Σ_top ∂Π/∂y` (per unit depth, units
    /// `G λ`).
    pub fn slab_reaction(&self, grad: &[f64]) -> f64 {
        -self.mesh.top.iter().map(|&n| grad[2 * n + 1]).sum::<f64>()
    }

    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.mesh.nodes.len()
    }
}
