//! Assembly of the reduced residual and tangent of a [`Model`] state.
//!
//! Unknowns are current node positions. Each node owns two equation slots; a slot is
//! either free, with a coefficient vector `c = ∂(x, y)/∂q` mapping the slot's unknown
//! `q` to the node's position, or constrained (identity row). The reduced residual and
//! tangent are `r_s = c_sᵀ g_node` and `K_st = c_sᵀ H c_t` (+ the contact curvature term
//! `y_s'' ∂Π/∂y` on sliding nodes), where `g = ∂Π/∂x` and `H = ∂²Π/∂x²` are assembled
//! from the elements; with friction, each active sliding node adds its friction force to
//! its residual and its friction row to the tangent (formulas in [`crate::fe::contact::friction`]).
//!
//! [`Assembly`] is the mutable side of a solve: the sparse tangent assembled into, the
//! forces of the last state assembled, the friction rows of the last tangent (read by the
//! semismooth step, [`crate::fe::newton::friction_step`]) and the work counters. The [`Model`] it
//! assembles is not changed by a solve.

use crate::fe::linsys::SparseSystem;
use crate::fe::model::element;
use crate::fe::model::mesh::Mesh;
use crate::fe::model::{Model, Role, SlotMap, State};
use crate::fe::newton::friction_rows::{add_friction, FrictionRow, FrictionSinks, NormalForceRow};
use crate::fe::Kinematics;

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
    /// How far the state is from the exact-stick friction law, as a force (units `G λ`; 0
    /// without friction and under the penalty law): Newton converges where this and the
    /// residual are within its tolerance.
    pub friction_complementarity: f64,
}

/// The mutable state of the Newton solves of one model.
#[derive(Clone, Debug)]
pub struct Assembly {
    /// Sparse tangent of the last assembly with the matrix.
    pub sys: SparseSystem,
    /// The last state assembled and its forces: an assembly without the matrix of the
    /// same state returns them (Newton's convergence check after a line search, the
    /// active-set check after a converged solve, the measurement).
    cache: Option<(State, Forces)>,
    /// Tangent assemblies so far ([`crate::fe::SolveWork`]).
    tangent_assemblies: usize,
    /// The friction rows of the last assembled tangent, one per active sliding node (open
    /// ones included; empty without friction).
    pub(in crate::fe) friction_rows: Vec<FrictionRow>,
    /// With friction, the equation slot of the largest residual entry at the last assembled
    /// tangent's state, where [`Self::friction_rows`] were assembled: where a failed solve
    /// looks for the friction law's crossover (`newton::at_crossover`).
    pub(in crate::fe) tangent_largest_residual: Option<usize>,
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

impl Assembly {
    /// The sparsity pattern of `model` (every element couples its eight slots), with the
    /// friction block ordered last when the model has friction.
    pub fn new(model: &Model) -> Self {
        let mesh = &model.mesh;
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
        if !model.is_potential() {
            sys.order_last(&friction_block(mesh));
        }
        Self {
            sys,
            cache: None,
            tangent_assemblies: 0,
            friction_rows: Vec::new(),
            tangent_largest_residual: None,
        }
    }

    /// Commit the friction history of the converged state `st` ([`Model::commit_slip`]) with
    /// its forces (cached from the convergence check that accepted it). No-op without
    /// friction.
    pub(crate) fn commit_slip(&mut self, model: &Model, st: &mut State) {
        if !model.is_potential() {
            let f = self
                .assemble(model, st, false)
                .expect("a converged state is not inverted");
            model.commit_slip(st, &f.grad);
        }
    }

    /// Assemble energy, gradient, reduced residual and (if `with_matrix`) the reduced
    /// tangent into [`Assembly::sys`]. `None` if any element is inverted. With friction,
    /// `energy` is the elastic energy only (the problem is no longer a minimisation).
    pub fn assemble(&mut self, model: &Model, st: &State, with_matrix: bool) -> Option<Forces> {
        if !with_matrix {
            if let Some((c, f)) = &self.cache {
                if c.same_forces(st) {
                    return Some(f.clone());
                }
            }
        }
        let nn = model.mesh.nodes.len();
        let map = model.slot_map(st);
        if with_matrix {
            self.sys.clear();
            self.friction_rows.clear();
            self.tangent_assemblies += 1;
        }
        let ElementSums {
            energy,
            grad,
            force_scale,
            mut dresid_dd,
            normal_rows,
            ..
        } = self.add_elements(model, st, &map, with_matrix)?;
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
            if model.kin == Kinematics::Finite {
                for (k, &n) in model.mesh.bottom.iter().enumerate() {
                    if st.active[k] && map[n][0].is_some() {
                        self.sys.values[self.sys.diag_pos[2 * n]] +=
                            grad[2 * n + 1] * model.indenter.curvature(st.x[n][0]);
                    }
                }
            }
        }
        let mut friction_complementarity = 0.0;
        if let Some(law) = model.friction {
            let sinks = FrictionSinks {
                resid: &mut resid,
                dresid_dd: &mut dresid_dd,
                tangent: with_matrix.then_some((&mut self.sys, &mut self.friction_rows)),
            };
            friction_complementarity =
                add_friction(model, st, &map, &law, (&grad, &normal_rows), sinks);
            if with_matrix {
                self.tangent_largest_residual = (resid.iter().enumerate())
                    .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
                    .map(|(slot, _)| slot);
            }
        }
        let forces = Forces {
            energy,
            grad,
            resid,
            dresid_dd,
            force_scale,
            friction_complementarity,
        };
        self.cache = Some((st.clone(), forces.clone()));
        Some(forces)
    }

    /// The element loop: energy, gradient and force scale of every element and, with the
    /// matrix, its tangent scattered into [`Assembly::sys`] ([`Self::scatter_element`]).
    /// `None` if an element is inverted.
    fn add_elements(
        &mut self,
        model: &Model,
        st: &State,
        map: &SlotMap,
        with_matrix: bool,
    ) -> Option<ElementSums> {
        let nn = model.mesh.nodes.len();
        // the contact-face index of each active sliding node, whose normal-force row the
        // Coulomb regime's threshold μN needs (see `friction`)
        let sliding_face_index: Vec<Option<usize>> = match model.friction {
            Some(_) if with_matrix => {
                let mut f = vec![None; nn];
                for (k, &n) in model.mesh.bottom.iter().enumerate() {
                    if st.active[k] && map[n][0].is_some() {
                        f[n] = Some(k);
                    }
                }
                f
            }
            _ => Vec::new(),
        };
        let normal_rows = if sliding_face_index.is_empty() {
            Vec::new()
        } else {
            vec![NormalForceRow::default(); model.mesh.bottom.len()]
        };
        let mut sums = ElementSums {
            energy: 0.0,
            grad: vec![0.0; 2 * nn],
            force_scale: 0.0,
            dresid_dd: vec![0.0; if with_matrix { 2 * nn } else { 0 }],
            sliding_face_index,
            normal_rows,
        };
        for e in 0..model.mesh.quads.len() {
            let q = model.mesh.quads[e];
            let (en, g, hess) = match model.kin {
                Kinematics::Finite if !with_matrix => {
                    let (en, g) =
                        element::gradient(&model.refs[e], &model.mat, &model.elem_x(st, e))?;
                    (en, g, [[0.0; 8]; 8])
                }
                Kinematics::Finite => {
                    let pressure = st.pressure.as_ref().map(|p| p[e]);
                    let x = model.elem_x(st, e);
                    let t = element::tangent(&model.refs[e], &model.mat, &x, pressure)?;
                    (t.energy, t.grad, t.hess)
                }
                Kinematics::Linear => {
                    let (en, g) = model.linear_elem(st, e);
                    (en, g, model.k_lin[e])
                }
            };
            sums.energy += en;
            sums.force_scale = g.iter().fold(sums.force_scale, |m, v| m.max(v.abs()));
            for a in 0..4 {
                sums.grad[2 * q[a]] += g[2 * a];
                sums.grad[2 * q[a] + 1] += g[2 * a + 1];
            }
            if with_matrix {
                self.scatter_element(model, st, map, e, &hess, &mut sums);
            }
        }
        Some(sums)
    }

    /// Scatter the Hessian `hess` of element `e` into the reduced tangent `c_sᵀ H c_t`, its
    /// bonded-face columns into `∂r/∂d`, and the normal-force rows of its active sliding
    /// nodes into `sums`.
    fn scatter_element(
        &mut self,
        model: &Model,
        st: &State,
        map: &SlotMap,
        e: usize,
        hess: &[[f64; 8]; 8],
        sums: &mut ElementSums,
    ) {
        let q = model.mesh.quads[e];
        for b in 0..4 {
            if model.role[q[b]] != Role::Top {
                continue;
            }
            for a in 0..4 {
                for s in 0..2 {
                    if let Some(ca) = map[q[a]][s] {
                        sums.dresid_dd[2 * q[a] + s] -=
                            ca[0] * hess[2 * a][2 * b + 1] + ca[1] * hess[2 * a + 1][2 * b + 1];
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
            if let Some(k) = sums.sliding_face_index.get(q[a]).copied().flatten() {
                let sl = model.contact_slope(st, q[a]);
                let normal = &mut sums.normal_rows[k];
                for b in 0..4 {
                    let nrow = |col: usize| -sl * hess[2 * a][col] + hess[2 * a + 1][col];
                    if model.role[q[b]] == Role::Top {
                        normal.dd -= nrow(2 * b + 1);
                    }
                    for t in 0..2 {
                        let Some(cb) = map[q[b]][t] else { continue };
                        let v = nrow(2 * b) * cb[0] + nrow(2 * b + 1) * cb[1];
                        normal.entries.push((2 * q[b] + t, v));
                    }
                }
            }
        }
    }

    /// The work done so far: tangent assemblies and factorisations.
    pub fn work(&self) -> crate::fe::SolveWork {
        crate::fe::SolveWork {
            tangent_assemblies: self.tangent_assemblies,
            factorisations: self.sys.factorisations(),
            woodbury_unit_solves: self.sys.woodbury_unit_solves(),
        }
    }
}

/// What the element loop of one assembly accumulates.
struct ElementSums {
    /// Total elastic energy `Π`.
    energy: f64,
    /// `∂Π/∂x` (2 per node).
    grad: Vec<f64>,
    /// Largest element-level nodal force component.
    force_scale: f64,
    /// `∂r/∂d` of the reduced residual (with the matrix only).
    dresid_dd: Vec<f64>,
    /// The contact-face index of each node that is active and sliding (with friction and
    /// the matrix only).
    sliding_face_index: Vec<Option<usize>>,
    /// Per contact-face node, its normal-force row (with friction and the matrix only).
    normal_rows: Vec<NormalForceRow>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::contact::friction::{Branch, Regime};
    use crate::fe::newton::friction_rows::LawPiece;
    use crate::fe::test_problems::coarse_sinusoid;
    use crate::fe::{build_model, Interface};

    /// A pressed, sheared state of the coarse AR 0.3 model under friction coefficient `mu`
    /// and stick regularisation `elastic_slip_over_element` (τ_max/E* = 0.1): the layer
    /// moved down by 0.01 λ, the contact-face nodes that the indenter then pushes up in
    /// contact, moved along it beyond their stick band.
    fn sheared(mu: f64, elastic_slip_over_element: f64) -> (Model, Assembly, State) {
        let interface = Interface::coulomb_orowan(mu, 0.1, elastic_slip_over_element);
        let (problem, opts) = coarse_sinusoid(0.3, interface);
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
        let asm = Assembly::new(&model);
        (model, asm, st)
    }

    /// Model `to`'s tangent row, residual and `∂r/∂d` on each friction node, against model
    /// `from`'s switched to `to`'s piece of the law ([`FrictionRow::switched`], with `to`'s
    /// elastic-slip limit, and without the hold that returns a node beyond its band to it)
    /// where `selected` picks the pair; returns how many were compared.
    fn compare_switched(
        from: &mut (Model, Assembly, State),
        to: &mut (Model, Assembly, State),
        st: &State,
        selected: impl Fn(LawPiece, LawPiece) -> bool,
    ) -> usize {
        let (from_model, from, _) = from;
        let (to_model, to, _) = to;
        let ff = from.assemble(from_model, st, true).expect("not inverted");
        let ft = to.assemble(to_model, st, true).expect("not inverted");
        let slip_c = to_model.elastic_slip_limit().expect("friction");
        let n = from.sys.size();
        let mut compared = 0;
        for (rf, rt) in from.friction_rows.iter().zip(&to.friction_rows) {
            assert_eq!(rf.row, rt.row);
            if !selected(rf.at, rt.at) {
                continue;
            }
            compared += 1;
            let (entries, d_resid, d_resid_dd) = rf.without_hold().switched(rt.at, slip_c);
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

    /// Under the penalty law a sliding node beyond its stick band, switched to stick, is held
    /// at its band's middle: its switched row is `k e_x` alone, its switched residual `k (x −
    /// x_m)`, and at `x_m` its trial elastic slip vanishes to within 10⁻³ e_c (measured
    /// 7.9·10⁻⁴ e_c, with committed elastic slips of half the band either way). Every sliding
    /// node of the sheared state beyond its band has the hold, and no node of the wide band does.
    #[test]
    fn a_node_beyond_its_band_switched_to_stick_is_held_at_the_band_middle() {
        let (model, mut asm, mut st) = sheared(50.0, 0.005);
        let slip_c = model.elastic_slip_limit().expect("friction");
        // a committed elastic slip, half the band either way, moves the middle off the anchor
        for (k, h) in st.slip.iter_mut().enumerate() {
            h.elastic = if k % 2 == 0 { 0.5 } else { -0.5 } * slip_c;
        }
        let forces = asm.assemble(&model, &st, true).expect("not inverted");
        let law = model.friction.expect("friction");
        let k = law.hold_stiffness;
        let n = asm.sys.size();
        let (mut held, mut largest) = (0, 0.0_f64);
        for r in &asm.friction_rows {
            let beyond = r.at.slip != Branch::Stick && r.trial_slip.abs() > slip_c;
            assert_eq!(r.held.is_some(), beyond, "face node {}", r.face);
            let Some(hold) = &r.held else { continue };
            held += 1;
            let to = LawPiece {
                slip: Branch::Stick,
                ..r.at
            };
            let (entries, d_resid, _) = r.switched(to, slip_c);
            let scale = (0..n).fold(k, |m, c| m.max(asm.sys.get(r.row, c).abs()));
            for c in 0..n {
                let extra: f64 = entries.iter().filter(|e| e.0 == c).map(|e| e.1).sum();
                let switched = asm.sys.get(r.row, c) + extra;
                let expected = if c == r.row { k } else { 0.0 };
                assert!(
                    (switched - expected).abs() <= 1e-12 * scale,
                    "row {}, column {c}: {switched} against {expected}",
                    r.row
                );
            }
            let resid = forces.resid[r.row] + d_resid;
            assert!((resid - k * hold.offset).abs() <= 1e-12 * scale * slip_c);
            let mut middle = st.clone();
            middle.x[model.mesh.bottom[r.face]][0] -= hold.offset;
            model.enforce_constraints(&mut middle);
            let at_middle =
                (model.friction_eval(&middle, r.face, (&forces.grad, None), &law)).trial_slip;
            // `x_m` takes the arc's slope `w` where the node is, not over the band: exact to
            // first order in `e_n` times the change of slope over the node's motion
            largest = largest.max(at_middle.abs() / slip_c);
            assert!(
                at_middle.abs() <= 1e-3 * slip_c,
                "face node {}: e* {at_middle:.3e} at the middle",
                r.face
            );
        }
        eprintln!("{held} nodes held, |e*| at the middle at most {largest:.2e} e_c");
        assert!(held >= 3, "only {held} nodes beyond their band");
        let (wide_model, mut wide, _) = sheared(50.0, 100.0);
        wide.assemble(&wide_model, &st, true).expect("not inverted");
        assert!(wide.friction_rows.iter().all(|r| r.held.is_none()));
    }

    /// The semismooth step's switches are exact. Regime: on every node that the Coulomb law
    /// (μ = 10⁻⁴) puts in the Coulomb regime and the Orowan law (μ = 50, same τ_max) in the
    /// Orowan regime, the Coulomb model's tangent row, residual and `∂r/∂d` switched to the
    /// Orowan regime are the Orowan model's assembled ones (the Orowan row does not depend
    /// on μ). Branch: a sliding node switched to the band's spring with the limit `e_c` of a
    /// model whose wide band (100 element lengths) holds it stuck has that model's row (the
    /// slip row does not depend on `e_c`). The assembled tangents are checked against central
    /// differences in `tests/solver/fe_tangent.rs`.
    #[test]
    fn switched_rows_are_the_other_pieces_assembled_rows() {
        let mut coulomb = sheared(1e-4, 0.005);
        let mut orowan = sheared(50.0, 0.005);
        let mut stuck = sheared(50.0, 100.0);
        let st = coulomb.2.clone();
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
