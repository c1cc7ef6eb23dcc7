//! The ParaView series of a solve (`wavy::vtk`): the files read back with vtkio's reader (the
//! `.vtu`) and quick-xml (the `.pvd`), their face pressures integrate to the curve's `p̄/E*`,
//! a loading–unloading run writes both branches in order, and a folder that cannot be written
//! is an error naming it with nothing left behind. Coarse mesh (16 × 8): a few seconds.

use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use quick_xml::events::Event;
use vtkio::model::{Attribute, CellType, DataSet, UnstructuredGridPiece, VertexNumbers, Vtk};
use wavy::fe::contact::indenter::Indenter;
use wavy::fe::{
    solve_curve, solve_cycle, solve_with_states, Curve, Interface, LayerProblem, LoadDirection,
    MeshLevel, SolveOptions,
};
use wavy::vtk::{series_times, step_file_name, write_series, VtkStep, COLLECTION_FILE};

const ASPECT_RATIO: f64 = 0.3;

/// Largest relative difference between `p̄/E*` of a point and the integral of its face
/// tractions read back from the file. The two sum the same nodal forces, the file's after a
/// division by and a multiplication with the tributary length and the slope's `w`: round-off
/// (the measured value, and the margin this bound leaves, are in docs/verification.md).
const PRESSURE_INTEGRAL_RTOL: f64 = 1e-14;

fn problem() -> LayerProblem {
    LayerProblem {
        interface: Interface::coulomb_orowan(1.0, 0.05, 0.005),
        ..wavy::defaults::layer_problem(ASPECT_RATIO)
    }
}

fn options() -> SolveOptions {
    SolveOptions {
        mesh: MeshLevel::along_face(16),
        until_a_over_lambda: 0.3,
        ..Default::default()
    }
}

/// The curve and the steps of a frictional solve, with unloading or without.
fn solve(unload: bool) -> (Curve, Vec<VtkStep>) {
    let mut steps = Vec::new();
    let curve = solve_with_states(&problem(), &options(), unload, &mut |direction, p, st| {
        steps.push(VtkStep {
            direction,
            point: *p,
            state: st.clone(),
        });
        ControlFlow::Continue(())
    })
    .expect("curve");
    (curve, steps)
}

fn loading() -> &'static (Curve, Vec<VtkStep>) {
    static LOADING: OnceLock<(Curve, Vec<VtkStep>)> = OnceLock::new();
    LOADING.get_or_init(|| solve(false))
}

/// `(file, timestep, group)` of every data set of a `.pvd`, in order.
fn collection_entries(pvd: &Path) -> Vec<(String, String, String)> {
    let text = std::fs::read_to_string(pvd).unwrap();
    let mut reader = quick_xml::Reader::from_str(&text);
    let mut found = Vec::new();
    loop {
        match reader.read_event().expect("well-formed .pvd") {
            Event::Eof => break,
            Event::Empty(e) | Event::Start(e) if e.name().as_ref() == b"DataSet" => {
                let attr = |key: &[u8]| {
                    let a = e.try_get_attribute(key).unwrap().expect("attribute");
                    a.unescape_value().unwrap().into_owned()
                };
                found.push((attr(b"file"), attr(b"timestep"), attr(b"group")));
            }
            _ => {}
        }
    }
    found
}

/// The piece of a `.vtu` read with vtkio.
fn read_piece(path: &Path) -> UnstructuredGridPiece {
    let vtk = Vtk::import(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("{} is not an unstructured grid", path.display());
    };
    assert_eq!(pieces.len(), 1);
    pieces[0].load_piece_data(None).unwrap()
}

/// The values and number of components of a named array.
fn array(attrs: &[Attribute], name: &str) -> (Vec<f64>, usize) {
    for a in attrs {
        if let Attribute::DataArray(d) = a {
            if d.name == name {
                return (
                    d.data.cast_into::<f64>().unwrap(),
                    d.elem.num_comp() as usize,
                );
            }
        }
    }
    panic!("no array {name}");
}

#[test]
fn solving_with_states_gives_the_same_curve() {
    let (with_states, steps) = loading();
    let plain = solve_curve(&problem(), &options(), &mut |_| ControlFlow::Continue(())).unwrap();
    assert_eq!(with_states, &plain);
    let points: Vec<_> = steps.iter().map(|s| s.point).collect();
    assert_eq!(points, plain.points);
    assert_eq!(steps.last().unwrap().state.deformed, plain.final_state);
}

#[test]
fn series_reads_back_with_vtkio() {
    let (_, steps) = loading();
    let dir = tempfile::tempdir().unwrap();
    let written = write_series(dir.path(), steps).unwrap();
    assert_eq!(written.len(), steps.len() + 1);
    assert_eq!(written.last().unwrap(), &dir.path().join(COLLECTION_FILE));
    for (i, (path, step)) in written.iter().zip(steps).enumerate() {
        assert_eq!(path, &dir.path().join(step_file_name(i)));
        let st = &step.state;
        let piece = read_piece(path);
        let (points, quads) = (st.deformed.nodes.len(), st.deformed.quads.len());
        assert_eq!(piece.num_points(), points);
        assert_eq!(piece.cells.types, vec![CellType::Quad; quads]);
        let VertexNumbers::XML { connectivity, .. } = &piece.cells.cell_verts else {
            panic!("XML cells expected");
        };
        let quad_nodes: Vec<u64> = st
            .deformed
            .quads
            .iter()
            .flatten()
            .map(|&n| n as u64)
            .collect();
        assert_eq!(connectivity, &quad_nodes);
        let xyz = piece.points.cast_into::<f64>().unwrap();
        for (n, x) in st.deformed.nodes.iter().enumerate() {
            assert_eq!(&xyz[3 * n..3 * n + 3], &[x[0], x[1], 0.0]);
        }
        for (name, comps) in [
            ("displacement_over_lambda", 3),
            ("reference_position_over_lambda", 3),
            ("in_contact", 1),
            ("in_stick", 1),
            ("contact_pressure_over_estar", 1),
            ("contact_shear_over_estar", 1),
            ("slip_over_lambda", 1),
        ] {
            let (values, c) = array(&piece.data.point, name);
            assert_eq!((values.len(), c), (comps * points, comps), "{name}");
        }
        let (j, _) = array(&piece.data.cell, "J");
        assert_eq!(j, st.element_dilatation);
        assert!(j.iter().all(|&j| j > 0.0));
        // displacement = current − reference, exactly as written
        let (u, _) = array(&piece.data.point, "displacement_over_lambda");
        let (r, _) = array(&piece.data.point, "reference_position_over_lambda");
        for n in 0..points {
            for c in 0..2 {
                assert_eq!(u[3 * n + c], xyz[3 * n + c] - r[3 * n + c]);
            }
        }
        // the face values at the face nodes, 0 elsewhere
        let (slip, _) = array(&piece.data.point, "slip_over_lambda");
        let (contact, _) = array(&piece.data.point, "in_contact");
        let (stick, _) = array(&piece.data.point, "in_stick");
        for (k, &n) in st.deformed.bottom.iter().enumerate() {
            assert_eq!(slip[n], st.face_slip_over_lambda[k]);
            assert_eq!(contact[n], f64::from(u8::from(st.deformed.in_contact[k])));
            assert_eq!(stick[n], f64::from(u8::from(st.deformed.in_stick[k])));
            assert!(
                contact[n] == 1.0 || stick[n] == 0.0,
                "a free node does not stick"
            );
            if !st.deformed.in_contact[k] {
                assert_eq!(slip[n], 0.0);
            }
        }
        let interior = (0..points).filter(|n| !st.deformed.bottom.contains(n));
        assert!(interior
            .into_iter()
            .all(|n| slip[n] == 0.0 && contact[n] == 0.0 && stick[n] == 0.0));
    }
    // the collection lists every step, its time the CSV's slab displacement
    let entries = collection_entries(written.last().unwrap());
    assert_eq!(entries.len(), steps.len());
    for (i, ((file, time, group), step)) in entries.iter().zip(steps).enumerate() {
        assert_eq!(file, &step_file_name(i));
        let csv_d = step.point.csv_row().split(',').nth(3).unwrap().to_string();
        assert_eq!(time, &csv_d);
        assert_eq!(group, "loading");
    }
    let times: Vec<f64> = entries.iter().map(|e| e.1.parse().unwrap()).collect();
    assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
    // the slip is that of a contact that grows outward with friction: some node has slid
    let last = &steps.last().unwrap().state;
    assert!(last.face_slip_over_lambda.iter().any(|&s| s != 0.0));
}

/// The face shear is a friction traction: at most τ_max on every face node (the slip threshold
/// `min(μ N, τ_max ℓ)` over the same tributary length ℓ), and zero on the symmetry lines, where
/// the node's tangential force is the symmetry plane's reaction and no friction.
#[test]
fn face_shear_is_bounded_by_the_shear_strength_and_zero_on_symmetry_lines() {
    let (_, steps) = loading();
    let Interface::CoulombOrowan(law) = problem().interface else {
        panic!("a frictional problem");
    };
    let mut largest: f64 = 0.0;
    for step in steps {
        let tau = &step.state.deformed.contact_shear_over_estar;
        assert_eq!((tau[0], tau[tau.len() - 1]), (0.0, 0.0));
        largest = largest.max(tau.iter().fold(0.0, |m, t| m.max(t.abs())));
    }
    println!(
        "largest |τ|/E* on the face {largest:e}, τ_max/E* {}",
        law.tau_max_over_estar
    );
    // the shear is the node's tangential reaction over ℓ, the friction force to the residual
    // Newton stops at (`residual_rtol` 1e-10 of the largest element nodal force): measured
    // 1.03e-8 of τ_max above it on this mesh
    assert!(
        largest <= law.tau_max_over_estar * (1.0 + 5e-8),
        "{largest:e}"
    );
    assert!(
        largest >= 0.5 * law.tau_max_over_estar,
        "{largest:e}: friction acts"
    );
}

/// The face tractions read back from each `.vtu` integrate to the point's `p̄/E*`: the vertical
/// component of the traction `(p + y_s' τ)/w` (normal `(−y_s', 1)/w`, tangent `(1, y_s')/w`)
/// times each face node's tributary length on the deformed face (half of each adjacent chord,
/// as the solver divided the nodal forces), over half a wavelength.
#[test]
fn face_pressures_integrate_to_the_mean_pressure() {
    let (_, steps) = loading();
    let dir = tempfile::tempdir().unwrap();
    let written = write_series(dir.path(), steps).unwrap();
    let indenter = Indenter::sinusoid(ASPECT_RATIO);
    let mut worst: f64 = 0.0;
    for (path, step) in written.iter().zip(steps) {
        let piece = read_piece(path);
        let xyz = piece.points.cast_into::<f64>().unwrap();
        let (r, _) = array(&piece.data.point, "reference_position_over_lambda");
        let (p, _) = array(&piece.data.point, "contact_pressure_over_estar");
        let (tau, _) = array(&piece.data.point, "contact_shear_over_estar");
        // the face: reference Y = 0, in order of reference X
        let mut face: Vec<usize> = (0..piece.num_points())
            .filter(|&n| r[3 * n + 1] == 0.0)
            .collect();
        face.sort_by(|&a, &b| r[3 * a].total_cmp(&r[3 * b]));
        let pos = |k: usize| [xyz[3 * face[k]], xyz[3 * face[k] + 1]];
        let chord = |k: usize| {
            let (a, b) = (pos(k), pos(k + 1));
            ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
        };
        let m = face.len();
        let mut force = 0.0;
        for k in 0..m {
            let left = if k > 0 { chord(k - 1) } else { 0.0 };
            let right = if k + 1 < m { chord(k) } else { 0.0 };
            let tributary = 0.5 * (left + right);
            let s = indenter.slope(pos(k)[0]);
            let w = (1.0 + s * s).sqrt();
            force += tributary * (p[face[k]] + s * tau[face[k]]) / w;
        }
        let mean = force / 0.5;
        let expected = step.point.p_over_estar;
        worst = worst.max((mean - expected).abs() / expected);
    }
    println!("largest relative difference of the pressure integral: {worst:e}");
    assert!(worst <= PRESSURE_INTEGRAL_RTOL, "{worst:e}");
}

#[test]
fn a_cycle_writes_both_branches_in_order() {
    let (curve, steps) = solve(true);
    let plain = solve_cycle(
        &problem(),
        &options(),
        &mut |_, _| ControlFlow::Continue(()),
    )
    .unwrap();
    assert_eq!(curve, plain);
    assert!(!curve.unloading.is_empty());
    let branches: Vec<LoadDirection> = steps.iter().map(|s| s.direction).collect();
    let mut expected = vec![LoadDirection::Loading; curve.points.len()];
    expected.extend(vec![LoadDirection::Unloading; curve.unloading.len()]);
    assert_eq!(branches, expected);
    let dir = tempfile::tempdir().unwrap();
    let written = write_series(dir.path(), &steps).unwrap();
    assert_eq!(written.len(), steps.len() + 1);
    let entries = collection_entries(written.last().unwrap());
    let groups: Vec<&str> = entries.iter().map(|e| e.2.as_str()).collect();
    let names: Vec<&str> = expected.iter().map(|d| d.name()).collect();
    assert_eq!(groups, names);
    // time: the slab travel, the slab displacement on loading, 2 d_max − d on unloading
    let times: Vec<f64> = entries.iter().map(|e| e.1.parse().unwrap()).collect();
    assert_eq!(times, series_times(&steps));
    assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
    let d_max = curve.points.last().unwrap().slab_displacement_over_lambda;
    for (t, p) in times[curve.points.len()..].iter().zip(&curve.unloading) {
        assert_eq!(*t, 2.0 * d_max - p.slab_displacement_over_lambda);
    }
    for (file, _, _) in &entries {
        read_piece(&dir.path().join(file));
    }
}

/// Every file under `dir`, hidden ones included.
fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            out.push(p.clone());
            out.extend(files_under(&p));
        } else {
            out.push(p);
        }
    }
    out.sort();
    out
}

#[test]
fn a_folder_that_cannot_be_written_is_named_and_nothing_is_left() {
    let (_, steps) = loading();
    let steps = &steps[..3];
    let root = tempfile::tempdir().unwrap();
    // a file where the folder should be, and where a parent folder should be
    let blocker = root.path().join("blocker");
    std::fs::write(&blocker, b"not a folder").unwrap();
    for dir in [blocker.clone(), blocker.join("vtk")] {
        let e = write_series(&dir, steps).unwrap_err();
        let message = e.to_string();
        assert!(message.contains(&dir.display().to_string()), "{message}");
    }
    assert_eq!(files_under(root.path()), vec![blocker.clone()]);
    // a series that fails part-way (a folder where its second file goes) removes what it wrote
    let dir = root.path().join("series");
    let in_the_way = dir.join(step_file_name(1));
    std::fs::create_dir_all(&in_the_way).unwrap();
    let e = write_series(&dir, steps).unwrap_err();
    let message = e.to_string();
    assert!(
        message.contains(&in_the_way.display().to_string()),
        "{message}"
    );
    assert_eq!(files_under(&dir), vec![in_the_way]);
}

/// `wavy solve --vtk DIR` writes one step per CSV row and the collection, whose times are the
/// rows' slab displacements; a curve that stops short writes the series of its converged rows,
/// and the collection says it is incomplete and why.
#[test]
fn the_command_line_writes_the_series_of_its_rows() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let out = dir.path().join("series");
    let run = |extra: &[&str], vtk: &Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_wavy"))
            .args(["solve", "--ar", "0.3"])
            .args(extra)
            .arg("--vtk")
            .arg(vtk)
            .output()
            .expect("wavy runs")
    };
    let o = run(&["--mesh", "16", "--until-a-over-lambda", "0.3"], &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = String::from_utf8(o.stdout).expect("UTF-8");
    let displacements: Vec<String> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(3).expect("four columns").to_string())
        .collect();
    let entries = collection_entries(&out.join(COLLECTION_FILE));
    assert_eq!(entries.len(), displacements.len());
    for (i, ((file, time, _), d)) in entries.iter().zip(&displacements).enumerate() {
        assert_eq!(time, d, "step {i}");
        assert_eq!(file, &step_file_name(i));
        assert!(out.join(file).is_file());
    }
    let stopped = dir.path().join("stopped");
    let o = run(&["--mesh", "8", "--until-a-over-lambda", "0.45"], &stopped);
    assert_eq!(o.status.code(), Some(1));
    let rows = String::from_utf8(o.stdout).expect("UTF-8").lines().count() - 1;
    let entries = collection_entries(&stopped.join(COLLECTION_FILE));
    assert!(
        rows > 0 && entries.len() == rows,
        "{rows} rows, {entries:?}"
    );
    assert!(entries
        .iter()
        .all(|(file, _, _)| stopped.join(file).is_file()));
    let pvd = std::fs::read_to_string(stopped.join(COLLECTION_FILE)).unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    let reason = stderr.trim_end().trim_start_matches("error: ");
    assert!(
        pvd.contains("<Collection status=\"incomplete\" reason=\"") && pvd.contains("INCOMPLETE"),
        "{pvd}"
    );
    assert!(
        pvd.contains(&reason.replace('"', "&quot;")),
        "{reason}\n{pvd}"
    );
}
