//! Discrete model: mesh, material, boundary conditions, contact elimination and
//! assembly of the reduced residual and tangent.
//!
//! Unknowns are current node positions. Each node owns two equation slots; a slot is
//! either free, with a coefficient vector `c = ∂(x, y)/∂q` mapping the slot's unknown
//! `q` to the node's position, or constrained (identity row). The reduced residual and
//! tangent are `r_s = c_sᵀ g_node` and `K_st = c_sᵀ H c_t` (+ the contact curvature term
//! `y_s'' ∂Π/∂y` on sliding nodes), where `g = ∂Π/∂x` and `H = ∂²Π/∂x²` are assembled
//! from the elements.
//!
//! Boundary conditions (units of λ, `h` the thickness, `d` the slab displacement, `d_x`
//! its horizontal shift, 0 in the wavy problem):
//! * bonded face `Y = h`: `x = X + d_x`, `y = h − d` (moves with the rigid slab);
//! * lateral faces `X = 0`, `X = ½`: `x = X` (symmetry, [`Lateral::Symmetric`]), `y`
//!   free; or traction-free ([`Lateral::Free`], the block of the friction test);
//! * contact face `Y = 0`: free, or active (on the indenter, see [`super::contact`]),
//!   with the friction force of [`Interface::CoulombOrowan`] on active sliding nodes.
//!
//! Loading is by the slab displacement `d` (displacement control). For monotonic,
//! frictionless (path-independent) loading the equilibrium states are the same as under
//! the corresponding force control, and displacement control avoids the limit-point
//! and rigid-body issues of force control.

use super::contact::Indenter;
use super::element::{self, QuadRef};
use super::friction::{
    Branch, BranchChoice, FrictionEval, FrictionLaw, FrictionRow, Interface, LawBranch, RegimeRow,
    SlipHistory,
};
use super::linsys::{LinSolveError, RowChange, SparseSystem};
use super::material::NeoHooke;
use super::mesh::Mesh;
use super::Kinematics;

/// Iteration cap of the closest-point projection ([`Model::project_closest`]). Newton on
/// the closest-point equation converges quadratically from a node within an element of
/// the surface; the cap is a safeguard.
const PROJECTION_MAX_ITERATIONS: usize = 20;

/// The closest-point projection stops once its correction is below this (units of λ):
/// about ten ulps of a position `x ≤ ½` (one ulp is 1.1·10⁻¹⁶), i.e. at round-off.
const PROJECTION_STEP_TOL: f64 = 1e-15;

/// Most changed solves per Newton step in the semismooth choice of the friction branches
/// ([`Model::solve_newton`]). The choice settles in one or two changes where it settles;
/// a cap, not tuned: beyond it the assembled step is taken.
const MAX_BRANCH_SWITCHES: usize = 8;

/// Boundary condition of the lateral faces `X = 0` and `X = ½`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Lateral {
    /// `x = X`: symmetry planes of the periodic wavy problem (docs/replication.md R1).
    #[default]
    Symmetric,
    /// Traction-free: a finite block.
    Free,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
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
}

/// Assembled energy and forces.
#[derive(Clone, Debug)]
pub struct Forces {
    /// Total potential energy `Π` (units `G λ²` per unit depth).
    pub energy: f64,
    /// Full gradient `∂Π/∂x` (2 per node).
    pub grad: Vec<f64>,
    /// Reduced residual per slot (0 on constrained slots).
    pub resid: Vec<f64>,
    /// Derivative of the reduced residual with respect to the slab displacement `d`
    /// (filled only when the matrix is assembled): `−Σ_top c_sᵀ H[·, y_top]`.
    pub dresid_dd: Vec<f64>,
    /// Largest element-level nodal force component (the round-off scale of the
    /// assembled residual).
    pub force_scale: f64,
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
    friction: Option<FrictionLaw>,
    refs: Vec<QuadRef>,
    k_lin: Vec<[[f64; 8]; 8]>,
    role: Vec<Role>,
    /// Sparse tangent.
    pub sys: SparseSystem,
    /// The last state assembled and its forces: an assembly without the matrix of the
    /// same state returns them (Newton's convergence check after a line search, the
    /// active-set check after a converged solve, the measurement).
    cache: Option<(State, Forces)>,
    /// Tangent assemblies so far ([`super::SolveWork`]).
    tangent_assemblies: usize,
    /// The friction rows of the last assembled tangent, one per active sliding node (open
    /// ones included; empty without friction).
    friction_rows: Vec<FrictionRow>,
}

/// The equations that the friction rows and the columns they touch can occupy: the contact
/// face and the nodes of its elements (the layer above it), ordered last in the
/// factorisation so that the Woodbury solve reads `S⁻¹` on them from the factor's trailing
/// block (`linsys`). The face nodes' sliding slots, the rows that carry the updates, come
/// last of all: the trailing block's forward solve starts at the first of them.
fn friction_block(mesh: &Mesh) -> Vec<usize> {
    let face: std::collections::BTreeSet<usize> = mesh.bottom.iter().copied().collect();
    let near_face: std::collections::BTreeSet<usize> = mesh
        .quads
        .iter()
        .filter(|q| q.iter().any(|n| face.contains(n)))
        .flatten()
        .copied()
        .collect();
    let mut dofs = Vec::new();
    for &n in &near_face {
        if !face.contains(&n) {
            dofs.push(2 * n);
        }
        dofs.push(2 * n + 1);
    }
    // the face nodes' sliding slots (slot 2n) last of all
    dofs.extend(mesh.bottom.iter().map(|&n| 2 * n));
    dofs
}

type SlotMap = Vec<[Option<[f64; 2]>; 2]>;

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
                    element::tangent(r, &mat, &xr)
                        .expect("reference element is valid")
                        .hess
                })
                .collect(),
            Kinematics::Finite => Vec::new(),
        };
        let mut role = vec![Role::Interior; mesh.nodes.len()];
        if lateral == Lateral::Symmetric {
            for j in 0..=mesh.ny {
                role[mesh.id(0, j)] = Role::Side;
                role[mesh.id(mesh.nx, j)] = Role::Side;
            }
        }
        for &b in &mesh.bottom {
            role[b] = Role::Bottom;
        }
        if lateral == Lateral::Symmetric {
            role[mesh.id(0, 0)] = Role::BottomCorner;
            role[mesh.id(mesh.nx, 0)] = Role::BottomCorner;
        }
        for &t in &mesh.top {
            role[t] = Role::Top;
        }
        let elem_dofs: Vec<[usize; 8]> = mesh
            .quads
            .iter()
            .map(|q| {
                let mut d = [0; 8];
                for a in 0..4 {
                    d[2 * a] = 2 * q[a];
                    d[2 * a + 1] = 2 * q[a] + 1;
                }
                d
            })
            .collect();
        let mut sys = SparseSystem::new(2 * mesh.nodes.len(), &elem_dofs);
        if friction.is_some() {
            sys.order_last(&friction_block(&mesh));
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
            sys,
            cache: None,
            tangent_assemblies: 0,
            friction_rows: Vec::new(),
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

    fn slot_map(&self, st: &State) -> SlotMap {
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

    fn elem_x(&self, st: &State, e: usize) -> [[f64; 2]; 4] {
        let q = self.mesh.quads[e];
        [st.x[q[0]], st.x[q[1]], st.x[q[2]], st.x[q[3]]]
    }

    fn linear_elem(&self, st: &State, e: usize) -> (f64, [f64; 8]) {
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

    /// Assemble energy, gradient, reduced residual and (if `with_matrix`) the reduced
    /// tangent into `self.sys`. `None` if any element is inverted. With friction, `energy`
    /// is the elastic energy only (the problem is no longer a minimisation).
    pub fn assemble(&mut self, st: &State, with_matrix: bool) -> Option<Forces> {
        if !with_matrix {
            if let Some((c, f)) = &self.cache {
                if c == st {
                    return Some(f.clone());
                }
            }
        }
        let nn = self.mesh.nodes.len();
        let map = self.slot_map(st);
        let mut grad = vec![0.0; 2 * nn];
        let mut energy = 0.0;
        let mut force_scale = 0.0_f64;
        let mut dresid_dd = vec![0.0; if with_matrix { 2 * nn } else { 0 }];
        // Friction: active sliding nodes (contact-face index per node) and, per such node,
        // the rows (−y_s', 1)ᵀ H[node, ·] mapped to slots (column, value) and their
        // derivative with respect to d (the Coulomb regime needs them, see `friction`).
        let fric_of: Vec<Option<usize>> = match self.friction {
            Some(_) if with_matrix => {
                let mut f = vec![None; nn];
                for (k, &n) in self.mesh.bottom.iter().enumerate() {
                    if st.active[k] && map[n][0].is_some() {
                        f[n] = Some(k);
                    }
                }
                f
            }
            _ => Vec::new(),
        };
        let n_fric = if fric_of.is_empty() {
            0
        } else {
            self.mesh.bottom.len()
        };
        let mut fric_rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n_fric];
        let mut fric_dd = vec![0.0; n_fric];
        if with_matrix {
            self.sys.clear();
            self.friction_rows.clear();
            self.tangent_assemblies += 1;
        }
        for e in 0..self.mesh.quads.len() {
            let q = self.mesh.quads[e];
            let (en, g, hess) = match self.kin {
                Kinematics::Finite if !with_matrix => {
                    let (en, g) = element::gradient(&self.refs[e], &self.mat, &self.elem_x(st, e))?;
                    (en, g, [[0.0; 8]; 8])
                }
                Kinematics::Finite => {
                    let t = element::tangent(&self.refs[e], &self.mat, &self.elem_x(st, e))?;
                    (t.energy, t.grad, t.hess)
                }
                Kinematics::Linear => {
                    let (en, g) = self.linear_elem(st, e);
                    (en, g, self.k_lin[e])
                }
            };
            energy += en;
            force_scale = g.iter().fold(force_scale, |m, v| m.max(v.abs()));
            for a in 0..4 {
                grad[2 * q[a]] += g[2 * a];
                grad[2 * q[a] + 1] += g[2 * a + 1];
            }
            if with_matrix {
                for b in 0..4 {
                    if self.role[q[b]] != Role::Top {
                        continue;
                    }
                    for a in 0..4 {
                        for s in 0..2 {
                            if let Some(ca) = map[q[a]][s] {
                                dresid_dd[2 * q[a] + s] -= ca[0] * hess[2 * a][2 * b + 1]
                                    + ca[1] * hess[2 * a + 1][2 * b + 1];
                            }
                        }
                    }
                }
                let pos = &self.sys.elem_pos[e];
                for a in 0..4 {
                    for s in 0..2 {
                        let Some(ca) = map[q[a]][s] else { continue };
                        // row vector caᵀ H[a, ·]
                        let mut row = [0.0; 8];
                        for (col, rv) in row.iter_mut().enumerate() {
                            *rv = ca[0] * hess[2 * a][col] + ca[1] * hess[2 * a + 1][col];
                        }
                        for b in 0..4 {
                            for t in 0..2 {
                                let Some(cb) = map[q[b]][t] else { continue };
                                let v = row[2 * b] * cb[0] + row[2 * b + 1] * cb[1];
                                self.sys.values[pos[8 * (2 * a + s) + 2 * b + t]] += v;
                            }
                        }
                    }
                    if let Some(k) = fric_of.get(q[a]).copied().flatten() {
                        let sl = self.contact_slope(st, q[a]);
                        for b in 0..4 {
                            let nrow = |col: usize| -sl * hess[2 * a][col] + hess[2 * a + 1][col];
                            if self.role[q[b]] == Role::Top {
                                fric_dd[k] -= nrow(2 * b + 1);
                            }
                            for t in 0..2 {
                                let Some(cb) = map[q[b]][t] else { continue };
                                let v = nrow(2 * b) * cb[0] + nrow(2 * b + 1) * cb[1];
                                fric_rows[k].push((2 * q[b] + t, v));
                            }
                        }
                    }
                }
            }
        }
        let mut resid = vec![0.0; 2 * nn];
        for n in 0..nn {
            for s in 0..2 {
                if let Some(c) = map[n][s] {
                    resid[2 * n + s] = c[0] * grad[2 * n] + c[1] * grad[2 * n + 1];
                }
            }
        }
        if with_matrix {
            for n in 0..nn {
                for s in 0..2 {
                    if map[n][s].is_none() {
                        self.sys.values[self.sys.diag_pos[2 * n + s]] = 1.0;
                    }
                }
            }
            if self.kin == Kinematics::Finite {
                for (k, &n) in self.mesh.bottom.iter().enumerate() {
                    if st.active[k] && map[n][0].is_some() {
                        self.sys.values[self.sys.diag_pos[2 * n]] +=
                            grad[2 * n + 1] * self.indenter.curvature(st.x[n][0]);
                    }
                }
            }
        }
        if let Some(law) = self.friction {
            for (k, &n) in self.mesh.bottom.iter().enumerate() {
                if !st.active[k] || map[n][0].is_none() {
                    continue;
                }
                let f = self.friction_eval(st, k, &grad, &law);
                resid[2 * n] += f.force;
                if !with_matrix {
                    continue;
                }
                // the friction row of the tangent (formulas in `friction`) under either
                // regime, kept for the semismooth step (`friction_rows`); the assembled
                // regime's row goes in: its own entry into the symmetric values, the rest
                // as a row update (see `linsys`), every friction row an update row so that
                // a switch of the semismooth step changes updates only
                let (own_phi, own_dphi) = f.coulomb_own(&law, [grad[2 * n], grad[2 * n + 1]]);
                let mut coulomb_phi = vec![(2 * n, own_phi)];
                coulomb_phi.extend(fric_rows[k].iter().map(|&(c, v)| (c, law.mu * v)));
                let coulomb = RegimeRow {
                    per_phi: coulomb_phi,
                    w_limit: own_dphi,
                    per_phi_dd: law.mu * fric_dd[k],
                };
                let cn = map[n][0].expect("sliding slot");
                let (own_phi, own_dphi) = f.orowan_own(&law, cn);
                let mut orowan_phi = vec![(2 * n, own_phi)];
                for (side, m) in [k.wrapping_sub(1), k + 1].into_iter().enumerate() {
                    let Some(&nm) = self.mesh.bottom.get(m) else {
                        continue;
                    };
                    for t in 0..2 {
                        let Some(cm) = map[nm][t] else { continue };
                        orowan_phi.push((2 * nm + t, f.orowan_neighbour(&law, side, cm)));
                    }
                }
                let orowan = RegimeRow {
                    per_phi: orowan_phi,
                    w_limit: own_dphi,
                    per_phi_dd: 0.0,
                };
                let row = f.row(2 * n, coulomb, orowan);
                let assembled = row.law_row(row.at, law.slip_c);
                self.sys.values[self.sys.diag_pos[2 * n]] += assembled.own;
                self.sys.add_to_row(2 * n, 2 * n, 0.0);
                for (col, v) in assembled.others {
                    self.sys.add_to_row(2 * n, col, v);
                }
                dresid_dd[2 * n] += assembled.force_dd;
                self.friction_rows.push(row);
            }
        }
        let forces = Forces {
            energy,
            grad,
            resid,
            dresid_dd,
            force_scale,
        };
        self.cache = Some((st.clone(), forces.clone()));
        Some(forces)
    }

    /// Solve the Newton system of the last assembled tangent, `rhs[0] = −r` and, if
    /// present, `rhs[1] = −∂r/∂d`; `direction` maps the solutions to the step `δq` (for
    /// the bordered solve, a combination of the two).
    ///
    /// With friction and `semismooth`, the step is a semismooth Newton step of the
    /// piecewise-smooth friction law: each node's piece of the law (threshold regime and
    /// return-mapping branch) is the one its linearised state after the step lies on, not
    /// the one of the current state. A sliding node whose trial slip after the step,
    /// `e* + w δx`, leaves its slip branch (lands in the stick band or beyond it, on the
    /// other side) is put on the stick branch, and back on its slip branch for good if its
    /// stick step lands there ([`BranchChoice::after_step`]); a node whose linearised
    /// thresholds cross takes the smaller one, Coulomb or Orowan
    /// ([`FrictionRow::regime_after`]). The rows and residuals of the new pieces replace the
    /// assembled ones ([`FrictionRow::switched`], exact inside the band: unit test; beyond
    /// it the threshold's sensitivity keeps the band's factor, [`FrictionRow::law_row`]) and
    /// the system is solved again by Woodbury with the same factorisation, until the pieces
    /// agree with the step; if they have not within [`MAX_BRANCH_SWITCHES`], the assembled
    /// step is taken.
    ///
    /// Why: the slip tangent is flat, so a node whose solution lies in the narrow stick band
    /// is thrown from slip one way to slip the other and back (Newton's cycle on a
    /// saturating law), and a node near the Coulomb–Orowan crossover flips between the two
    /// thresholds; the line search then crawls through either with steps of 1/32–1/4. Both
    /// switches change the path to each equilibrium, not the equilibrium (every p̄/E* of the
    /// 18 Fig. 3 curves within 8·10⁻⁹ of the plain step's; test
    /// `semismooth_branch_choice_changes_the_path_not_the_curve` in `tests/fe_friction.rs`).
    /// Measured (`cargo run --release --example fig3_work`): 6863 tangent assemblies over the
    /// 18 Fig. 3 curves against 11847 without the switches (README, "Frictional speed").
    /// Tried and left out: letting stick nodes slide when
    /// their step leaves the band, or any node take whatever branch its step lands on (the
    /// switches cycled or cost more iterations), switching into and out of the open regime
    /// ([`FrictionRow::regime_after`]), and the switch in the predictor's load tangent (no
    /// gain).
    pub(crate) fn solve_newton(
        &mut self,
        rhs: &mut [Vec<f64>],
        semismooth: bool,
        direction: impl Fn(&[Vec<f64>]) -> Vec<f64>,
    ) -> Result<(), LinSolveError> {
        let law = match self.friction {
            Some(law) if semismooth => law,
            _ => return self.sys.solve(rhs),
        };
        let rows = &self.friction_rows;
        let with_load_column = rhs.len() > 1;
        let mut assumed: Vec<LawBranch> = rows.iter().map(|r| r.at).collect();
        let mut choices: Vec<BranchChoice> = rows
            .iter()
            .map(|r| BranchChoice::assembled(r.at.slip))
            .collect();
        let switching = self
            .sys
            .solve_switching_rows(rhs, MAX_BRANCH_SWITCHES, |solutions| {
                let step = direction(solutions);
                let mut landed = assumed.clone();
                for (i, r) in rows.iter().enumerate() {
                    let slip = Branch::of(r.trial_slip + r.w * step[r.row], law.slip_c);
                    choices[i] = choices[i].after_step(r.at.slip, slip);
                    landed[i] = LawBranch {
                        regime: r.regime_after(&step),
                        slip: choices[i].assumed,
                    };
                }
                if landed == assumed {
                    return None;
                }
                assumed = landed;
                let changes = rows
                    .iter()
                    .zip(&assumed)
                    .filter(|(r, &b)| r.at != b)
                    .map(|(r, &b)| {
                        let (entries, d_resid, d_resid_dd) = r.switched(b, law.slip_c);
                        let mut rhs = vec![-d_resid];
                        if with_load_column {
                            rhs.push(-d_resid_dd);
                        }
                        RowChange {
                            row: r.row,
                            entries,
                            rhs,
                        }
                    })
                    .collect();
                Some(changes)
            });
        switching.map(|_| ())
    }

    /// Slope `y_s'` of the indenter under contact-face node `n` as the contact law sees
    /// it (0 for linear kinematics).
    fn contact_slope(&self, st: &State, n: usize) -> f64 {
        match self.kin {
            Kinematics::Finite => self.indenter.slope(st.x[n][0]),
            Kinematics::Linear => 0.0,
        }
    }

    /// Arc length along the indenter from `x0` to `x1` as the contact law sees it.
    fn contact_arc(&self, x0: f64, x1: f64) -> f64 {
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

    /// Friction force of active contact-face node `k` ([`FrictionLaw::eval`]).
    fn friction_eval(&self, st: &State, k: usize, grad: &[f64], law: &FrictionLaw) -> FrictionEval {
        let b = &self.mesh.bottom;
        let n = b[k];
        let curvature = match self.kin {
            Kinematics::Finite => self.indenter.curvature(st.x[n][0]),
            Kinematics::Linear => 0.0,
        };
        let neighbours = [k.wrapping_sub(1), k + 1].map(|m| b.get(m).map(|&nm| st.x[nm]));
        let [normal, _] = self.node_contact_force(st, grad, n);
        law.eval(
            self.contact_slope(st, n),
            curvature,
            self.trial_elastic_slip(st, k),
            st.x[n],
            neighbours,
            normal,
        )
    }

    /// Commit the friction history of a converged load step on every contact-face node:
    /// `e_{n+1} = e_c φ`, `S_{n+1} = S(x)` on active nodes, reset on free ones (see
    /// [`super::friction`]). No-op without friction.
    pub fn commit_slip(&self, st: &mut State) {
        let Some(law) = self.friction else { return };
        for (k, &n) in self.mesh.bottom.iter().enumerate() {
            let trial = st.active[k].then(|| self.trial_elastic_slip(st, k));
            st.slip[k] = law.commit(trial, st.x[n][0]);
        }
    }

    /// Put contact-face node `k` in contact: mark it active, move it to its closest point
    /// on the indenter, and start its friction history there with no elastic slip.
    pub fn activate(&self, st: &mut State, k: usize) {
        st.active[k] = true;
        self.project_closest(st, k);
        if self.friction.is_some() {
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

    /// Tangential contact force `T` of every contact-face node (`Self::contact_forces`).
    pub fn tangential_forces(&self, st: &State, grad: &[f64]) -> Vec<f64> {
        self.contact_forces(st, grad).iter().map(|f| f[1]).collect()
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
                self.friction_eval(st, k, grad, &law).limit
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

    /// The work done so far: tangent assemblies and factorisations.
    pub fn work(&self) -> super::SolveWork {
        super::SolveWork {
            tangent_assemblies: self.tangent_assemblies,
            factorisations: self.sys.factorisations(),
            woodbury_unit_solves: self.sys.woodbury_unit_solves(),
        }
    }

    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.mesh.nodes.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::friction::Regime;
    use crate::fe::{build_model, Interface, LayerProblem, MeshLevel, SolveOptions};

    /// A pressed, sheared state of the coarse AR 0.3 model under friction coefficient `mu`
    /// and stick regularisation `elastic_slip_over_element` (τ_max/E* = 0.1): the layer
    /// moved down by 0.01 λ, the contact-face nodes that the indenter then pushes up in
    /// contact, moved along it beyond their stick band.
    fn sheared(mu: f64, elastic_slip_over_element: f64) -> (Model, State) {
        let problem = LayerProblem {
            aspect_ratio: 0.3,
            thickness_over_lambda: 1.0,
            kappa_over_g: 1000.0,
            kinematics: Kinematics::Finite,
            interface: Interface::coulomb_orowan(mu, 0.1, elastic_slip_over_element),
        };
        let opts = SolveOptions {
            mesh: MeshLevel::Coarse,
            ..Default::default()
        };
        let model = build_model(&problem, &opts);
        let mut st = model.initial_state();
        st.d = 0.01;
        for p in st.x.iter_mut() {
            p[1] -= st.d;
        }
        for k in 1..model.mesh.bottom.len() {
            let n = model.mesh.bottom[k];
            if model.indenter.y(st.x[n][0]) < -0.8 * st.d {
                break;
            }
            model.activate(&mut st, k);
            st.x[n][0] += 1e-4 * k as f64;
        }
        model.enforce_constraints(&mut st);
        (model, st)
    }

    /// Model `to`'s tangent row, residual and `∂r/∂d` on each friction node, against model
    /// `from`'s switched to `to`'s piece of the law ([`FrictionRow::switched`], with `to`'s
    /// elastic-slip limit) where `selected` picks the pair; returns how many were compared.
    fn compare_switched(
        from: &mut Model,
        to: &mut Model,
        st: &State,
        selected: impl Fn(LawBranch, LawBranch) -> bool,
    ) -> usize {
        let ff = from.assemble(st, true).expect("not inverted");
        let ft = to.assemble(st, true).expect("not inverted");
        let slip_c = to.elastic_slip_limit().expect("friction");
        let n = from.sys.size();
        let mut compared = 0;
        for (rf, rt) in from.friction_rows.iter().zip(&to.friction_rows) {
            assert_eq!(rf.row, rt.row);
            if !selected(rf.at, rt.at) {
                continue;
            }
            compared += 1;
            let (entries, d_resid, d_resid_dd) = rf.switched(rt.at, slip_c);
            let scale = (0..n).fold(0.0_f64, |m, c| m.max(to.sys.get(rt.row, c).abs()));
            for c in 0..n {
                let extra: f64 = entries.iter().filter(|e| e.0 == c).map(|e| e.1).sum();
                let switched = from.sys.get(rf.row, c) + extra;
                let assembled = to.sys.get(rt.row, c);
                assert!(
                    (switched - assembled).abs() <= 1e-12 * scale,
                    "row {}, column {c}: switched {switched} vs assembled {assembled}",
                    rf.row
                );
            }
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()));
            assert!(close(ff.resid[rf.row] + d_resid, ft.resid[rt.row]));
            assert!(close(
                ff.dresid_dd[rf.row] + d_resid_dd,
                ft.dresid_dd[rt.row]
            ));
        }
        compared
    }

    /// The semismooth step's switches are exact. Regime: on every node that the Coulomb law
    /// (μ = 10⁻⁴) puts in the Coulomb regime and the Orowan law (μ = 50, same τ_max) in the
    /// Orowan regime, the Coulomb model's tangent row, residual and `∂r/∂d` switched to the
    /// Orowan regime are the Orowan model's assembled ones (the Orowan row does not depend
    /// on μ). Branch: a sliding node switched to stick with the limit `e_c` of a model whose
    /// wide band (100 element lengths) holds it stuck has that model's row (the slip row does
    /// not depend on `e_c`). The assembled tangents are checked against central differences
    /// in `tests/fe_tangent.rs`.
    #[test]
    fn switched_rows_are_the_other_pieces_assembled_rows() {
        let (mut coulomb, st) = sheared(1e-4, 0.005);
        let (mut orowan, _) = sheared(50.0, 0.005);
        let (mut stuck, _) = sheared(50.0, 100.0);
        let regimes = compare_switched(&mut coulomb, &mut orowan, &st, |a, b| {
            a.regime == Regime::Coulomb && b.regime == Regime::Orowan && a.slip == b.slip
        });
        assert!(regimes >= 3, "only {regimes} nodes in both regimes");
        let branches = compare_switched(&mut orowan, &mut stuck, &st, |a, b| {
            a.regime == b.regime && a.slip != Branch::Stick && b.slip == Branch::Stick
        });
        assert!(
            branches >= 3,
            "only {branches} nodes switched from slip to stick"
        );
    }
}
