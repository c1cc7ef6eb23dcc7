//! Consistent tangent vs central finite differences (element level and global, with the
//! contact elimination terms). Reference: the derivatives of the code's own energy and
//! residual, differenced numerically; tolerances are relative to the largest entry.
use wavy::fe::model::element::{self, QuadRef};
use wavy::fe::model::material::NeoHooke;
use wavy::fe::newton::assembly;
use wavy::fe::*;

/// The largest magnitude among `values`.
fn largest_entry<'a>(values: impl IntoIterator<Item = &'a f64>) -> f64 {
    values.into_iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

fn distorted() -> ([[f64; 2]; 4], [[f64; 2]; 4]) {
    let xr = [[0.0, 0.0], [0.1, 0.0], [0.12, 0.09], [-0.01, 0.1]];
    let x = [[0.003, -0.01], [0.13, 0.004], [0.125, 0.085], [0.01, 0.11]];
    (xr, x)
}

#[test]
fn element_gradient_and_hessian_match_central_differences() {
    for kappa in [10.0, 1000.0] {
        let mat = NeoHooke { g: 1.0, kappa };
        let (xr, x) = distorted();
        let q = QuadRef::new(&xr);
        let t = element::tangent(&q, &mat, &x, None).expect("valid element");
        let h = 1e-6;
        let gmax = largest_entry(&t.grad);
        let hmax = largest_entry(t.hess.iter().flatten());
        for a in 0..8 {
            let mut xp = x;
            let mut xm = x;
            xp[a / 2][a % 2] += h;
            xm[a / 2][a % 2] -= h;
            let ep = element::energy(&q, &mat, &xp).unwrap();
            let em = element::energy(&q, &mat, &xm).unwrap();
            let fd = (ep - em) / (2.0 * h);
            assert!(
                (fd - t.grad[a]).abs() <= 1e-6 * gmax,
                "grad[{a}] {fd} vs {}",
                t.grad[a]
            );
            let tp = element::tangent(&q, &mat, &xp, None).unwrap();
            let tm = element::tangent(&q, &mat, &xm, None).unwrap();
            for b in 0..8 {
                let fd = (tp.grad[b] - tm.grad[b]) / (2.0 * h);
                assert!(
                    (fd - t.hess[b][a]).abs() <= 1e-6 * hmax,
                    "kappa {kappa} hess[{b}][{a}] fd {fd} vs {}",
                    t.hess[b][a]
                );
            }
        }
    }
}

/// A geometric pressure given to the tangent (the mixed method's pressure iterate) replaces
/// `κ (v/V − 1)` in the volumetric term `p ∇²v` alone: given that very value the tangent is the
/// condensed one, and given another it differs by `(p − κ (v/V − 1)) ∇²v`, whose only entries
/// are `±½` of the difference between the x of a corner and the y of its two neighbours (the
/// shoelace area's second derivatives); energy and gradient do not change.
#[test]
fn a_geometric_pressure_changes_the_volumetric_geometric_term_alone() {
    let mat = NeoHooke {
        g: 1.0,
        kappa: 1000.0,
    };
    let (xr, x) = distorted();
    let q = QuadRef::new(&xr);
    let condensed = element::tangent(&q, &mat, &x, None).unwrap();
    let own = mat.kappa * (element::shoelace(&x) / q.area - 1.0);
    let same = element::tangent(&q, &mat, &x, Some(own)).unwrap();
    let shift = 2.5;
    let other = element::tangent(&q, &mat, &x, Some(own + shift)).unwrap();
    let hmax = largest_entry(condensed.hess.iter().flatten());
    for r in 0..8 {
        for c in 0..8 {
            let (k, l) = (r / 2, c / 2);
            let second = match (r % 2, c % 2) {
                (0, 1) if l == (k + 1) % 4 => 0.5,
                (0, 1) if l == (k + 3) % 4 => -0.5,
                (1, 0) if k == (l + 1) % 4 => 0.5,
                (1, 0) if k == (l + 3) % 4 => -0.5,
                _ => 0.0,
            };
            assert!((same.hess[r][c] - condensed.hess[r][c]).abs() <= 1e-13 * hmax);
            let moved = other.hess[r][c] - condensed.hess[r][c];
            assert!(
                (moved - shift * second).abs() <= 1e-12 * hmax,
                "hess[{r}][{c}]: moved {moved}, expected {}",
                shift * second
            );
        }
    }
    assert_eq!(other.energy, condensed.energy);
    assert_eq!(other.grad, condensed.grad);
}

/// The gradient-only path (`element::gradient`, used when no matrix is assembled) and
/// the tangent path agree to round-off (relative 1e-13 of the largest entry), and both
/// agree with the pointwise generic tangent `NeoHooke::iso_response` contracted with
/// the shape-function gradients. (Index loops mirror the tensor index notation.)
#[test]
#[allow(clippy::needless_range_loop)]
fn gradient_path_and_generic_material_tangent_agree() {
    let mat = NeoHooke {
        g: 1.0,
        kappa: 1000.0,
    };
    let (xr, x) = distorted();
    let q = QuadRef::new(&xr);
    let t = element::tangent(&q, &mat, &x, None).unwrap();
    let (e, g) = element::gradient(&q, &mat, &x).unwrap();
    let gmax = largest_entry(&t.grad);
    assert!((e - t.energy).abs() <= 1e-13 * t.energy.abs());
    for a in 0..8 {
        assert!((g[a] - t.grad[a]).abs() <= 1e-13 * gmax, "grad[{a}]");
    }
    // isochoric Hessian from the generic 4-index tangent
    let mut h = [[0.0; 8]; 8];
    for gp in 0..4 {
        let mut f = [[0.0; 2]; 2];
        for a in 0..4 {
            for i in 0..2 {
                for j in 0..2 {
                    f[i][j] += x[a][i] * q.dn[gp][a][j];
                }
            }
        }
        let r = mat.iso_response(&f, true).unwrap();
        for a in 0..4 {
            for i in 0..2 {
                for b in 0..4 {
                    for k in 0..2 {
                        let mut v = 0.0;
                        for jj in 0..2 {
                            for l in 0..2 {
                                v += q.dn[gp][a][jj] * r.a[i][jj][k][l] * q.dn[gp][b][l];
                            }
                        }
                        h[2 * a + i][2 * b + k] += q.wdet[gp] * v;
                    }
                }
            }
        }
    }
    // volumetric part: the tangent of the zero-κ material differs by exactly that
    let iso = NeoHooke { g: 1.0, kappa: 0.0 };
    let ti = element::tangent(&q, &iso, &x, None).unwrap();
    let hmax = largest_entry(ti.hess.iter().flatten());
    for a in 0..8 {
        for b in 0..8 {
            assert!(
                (h[a][b] - ti.hess[a][b]).abs() <= 1e-12 * hmax,
                "hess[{a}][{b}] {} vs {}",
                h[a][b],
                ti.hess[a][b]
            );
        }
    }
}

#[test]
fn inverted_element_is_rejected() {
    let mat = NeoHooke {
        g: 1.0,
        kappa: 100.0,
    };
    let (xr, _) = distorted();
    let q = QuadRef::new(&xr);
    // fold corner 2 across the diagonal: one corner Jacobian negative
    let x = [[0.0, 0.0], [0.1, 0.0], [0.02, 0.02], [0.0, 0.1]];
    assert!(element::energy(&q, &mat, &x).is_none());
    assert!(element::tangent(&q, &mat, &x, None).is_none());
}

/// Global reduced residual and tangent, including sliding contact nodes (chain rule
/// and `y_s''` term) and the derivative with respect to the slab displacement.
#[test]
fn global_tangent_with_contact_elimination_matches_central_differences() {
    for kin in [Kinematics::Finite, Kinematics::Linear] {
        let pb = LayerProblem {
            kappa_over_g: 50.0,
            kinematics: kin,
            ..wavy::defaults::layer_problem(0.2)
        };
        let opts = SolveOptions {
            mesh: MeshLevel::Elements { nx: 5, ny: 3 },
            ..Default::default()
        };
        let m = build_model(&pb, &opts);
        let mut asm = assembly::Assembly::new(&m);
        let mut st = m.initial_state();
        st.d = 0.03;
        // deform smoothly, put the first three contact-face nodes on the indenter
        for (i, x) in st.x.iter_mut().enumerate() {
            let r = m.mesh.nodes[i];
            x[0] += 0.01 * (3.0 * r[0]).sin() * (1.0 + r[1]);
            x[1] += 0.02 * (5.0 * r[0] + 1.0).cos() * (1.0 - r[1]);
        }
        for k in 0..3 {
            st.active[k] = true;
        }
        m.enforce_constraints(&mut st);
        let f = assert_tangent_matches_central_differences(
            &m,
            &mut asm,
            &st,
            1e-6,
            &format!("{kin:?}"),
        );
        // the residual is the energy's gradient (frictionless: a minimisation)
        let (n, h) = (2 * m.num_nodes(), 1e-6);
        for c in (0..n).filter(|&c| f.resid[c] != 0.0 || asm.sys.get(c, c) != 1.0) {
            let mut e = vec![0.0; n];
            e[c] = 1.0;
            let ep = m.energy(&m.updated(&st, &e, h)).unwrap();
            let em = m.energy(&m.updated(&st, &e, -h)).unwrap();
            let fd_e = (ep - em) / (2.0 * h);
            assert!(
                (fd_e - f.resid[c]).abs() <= 1e-6 * (1.0 + f.resid[c].abs()),
                "{kin:?} slot {c}: dΠ/dq {fd_e} vs r {}",
                f.resid[c]
            );
        }
    }
}

/// The assembled reduced tangent `K` (every free slot) and `∂r/∂d` against central
/// differences of the reduced residual with step `h`; tolerance 1e-6 of the largest
/// diagonal entry. Returns the forces at `st` (assembled with the matrix).
fn assert_tangent_matches_central_differences(
    m: &model::Model,
    asm: &mut assembly::Assembly,
    st: &model::State,
    h: f64,
    label: &str,
) -> assembly::Forces {
    let f = asm.assemble(m, st, true).expect("valid state");
    let k_at = asm.sys.clone();
    let n = 2 * m.num_nodes();
    let kmax = (0..n).map(|i| k_at.get(i, i).abs()).fold(0.0, f64::max);
    let free = |r: usize| f.resid[r] != 0.0 || k_at.get(r, r) != 1.0;
    for c in (0..n).filter(|&c| free(c)) {
        let mut e = vec![0.0; n];
        e[c] = 1.0;
        let fp = asm.assemble(m, &m.updated(st, &e, h), false).unwrap();
        let fm = asm.assemble(m, &m.updated(st, &e, -h), false).unwrap();
        for r in (0..n).filter(|&r| free(r)) {
            let fd = (fp.resid[r] - fm.resid[r]) / (2.0 * h);
            let k = k_at.get(r, c);
            assert!(
                (fd - k).abs() <= 1e-6 * kmax,
                "{label}: K[{r}][{c}] fd {fd} vs {k}"
            );
        }
    }
    let shifted = |dd: f64| {
        let mut s = st.clone();
        s.d += dd;
        m.enforce_constraints(&mut s);
        s
    };
    let (sp, sm) = (shifted(h), shifted(-h));
    let fp = asm.assemble(m, &sp, false).unwrap();
    let fm = asm.assemble(m, &sm, false).unwrap();
    for r in 0..n {
        let fd = (fp.resid[r] - fm.resid[r]) / (2.0 * h);
        assert!(
            (fd - f.dresid_dd[r]).abs() <= 1e-6 * kmax,
            "{label}: dr/dd[{r}] fd {fd} vs {}",
            f.dresid_dd[r]
        );
    }
    f
}

/// The friction tangent tests' state of the AR 0.2 model `m`: the layer conformed to the
/// indenter and compressed (compressive contact forces), its first four face nodes active.
fn pressed_face(m: &model::Model) -> model::State {
    let mut st = m.initial_state();
    st.d = 0.06;
    for (i, x) in st.x.iter_mut().enumerate() {
        let r = m.mesh.nodes[i];
        let ys = -0.2 * (1.0 - (std::f64::consts::TAU * r[0]).cos());
        x[0] += 0.01 * (3.0 * r[0]).sin() * (1.0 + r[1]);
        x[1] += (1.0 - r[1]) * (ys - 0.05) - 0.06 * r[1]
            + 0.002 * (5.0 * r[0] + 1.0).cos() * (1.0 - r[1]);
    }
    for k in 0..4 {
        st.active[k] = true;
    }
    m.enforce_constraints(&mut st);
    st
}

/// Friction rows (regularised Coulomb–Orowan, `src/fe/contact/indenter.rs`): the non-symmetric
/// tangent against central differences of the reduced residual, with nodes in stick and
/// in slip, in the Coulomb regime (`τ_max` large) and in the Orowan regime (`μ` large),
/// finite and linear kinematics. The history is placed so that no node is within the
/// difference step of a stick/slip or regime switch.
#[test]
fn friction_tangent_matches_central_differences() {
    let regimes = [("coulomb", 0.4, 50.0), ("orowan", 50.0, 0.05)];
    for kin in [Kinematics::Finite, Kinematics::Linear] {
        for (name, mu, tau) in regimes {
            let pb = LayerProblem {
                kappa_over_g: 50.0,
                kinematics: kin,
                interface: Interface::coulomb_orowan(mu, tau, 0.005),
                ..wavy::defaults::layer_problem(0.2)
            };
            let frictionless = LayerProblem {
                interface: Interface::Frictionless,
                ..pb
            };
            let opts = SolveOptions {
                mesh: MeshLevel::Elements { nx: 5, ny: 3 },
                ..Default::default()
            };
            let m = build_model(&pb, &opts);
            let m0 = build_model(&frictionless, &opts);
            let mut asm = assembly::Assembly::new(&m);
            let mut asm0 = assembly::Assembly::new(&m0);
            let mut st = pressed_face(&m);
            let e_c = m.elastic_slip_limit().expect("friction is built");
            assert!(m0.elastic_slip_limit().is_none());
            // node 1 sticks (|e*| = 0.4 e_c), nodes 2 and 3 slip in opposite directions
            for (k, offset) in [(1, 0.4 * e_c), (2, 3.0 * e_c), (3, -5.0 * e_c)] {
                let n = m.mesh.bottom[k];
                st.slip[k].elastic = 0.0;
                st.slip[k].anchor_x = st.x[n][0] - offset;
            }
            let f = asm.assemble(&m, &st, true).expect("valid state");
            let f0 = asm0.assemble(&m0, &st, false).expect("valid state");
            // every sliding node is pressed and in the intended regime
            let normal = m.normal_forces(&st, &f.grad);
            let limit = m.friction_thresholds(&st, &f.grad);
            for k in 1..4 {
                assert!(
                    normal[k] > 0.0,
                    "{kin:?} {name}: node {k} N = {}",
                    normal[k]
                );
                let coulomb = limit[k] == mu * normal[k];
                assert_eq!(coulomb, name == "coulomb", "{kin:?} {name}: node {k}");
            }
            for k in 1..4 {
                let n = m.mesh.bottom[k];
                assert!(
                    (f.resid[2 * n] - f0.resid[2 * n]).abs() > 1e-3 * f0.force_scale,
                    "{kin:?} {name}: node {k} carries no friction force"
                );
            }
            assert_tangent_matches_central_differences(
                &m,
                &mut asm,
                &st,
                1e-7,
                &format!("{kin:?} {name}"),
            );
        }
    }
}

/// Exact stick (`elastic_slip_over_element = 0`): a held node's row is its constraint
/// `k (x − x_anchor)`, a sliding node's `c·g ± w L`; the tangent with these rows against
/// central differences of the reduced residual, in either regime and kinematics.
#[test]
fn exact_stick_tangent_matches_central_differences() {
    use wavy::fe::Branch;
    let regimes = [("coulomb", 0.4, 50.0), ("orowan", 50.0, 0.05)];
    for kin in [Kinematics::Finite, Kinematics::Linear] {
        for (name, mu, tau) in regimes {
            let pb = LayerProblem {
                kappa_over_g: 50.0,
                kinematics: kin,
                interface: Interface::coulomb_orowan(mu, tau, 0.0),
                ..wavy::defaults::layer_problem(0.2)
            };
            let opts = SolveOptions {
                mesh: MeshLevel::Elements { nx: 5, ny: 3 },
                ..Default::default()
            };
            let m = build_model(&pb, &opts);
            let mut asm = assembly::Assembly::new(&m);
            let mut st = pressed_face(&m);
            // node 1 held off its anchor, nodes 2 and 3 sliding in opposite directions
            for (k, offset, held) in [
                (1, 1e-3, Branch::Stick),
                (2, 3e-3, Branch::SlipForward),
                (3, -5e-3, Branch::SlipBackward),
            ] {
                let n = m.mesh.bottom[k];
                st.slip[k].anchor_x = st.x[n][0] - offset;
                st.slip[k].held = held;
            }
            assert_tangent_matches_central_differences(
                &m,
                &mut asm,
                &st,
                1e-7,
                &format!("exact stick, {kin:?} {name}"),
            );
        }
    }
}
