//! The deformed states of a solve as a ParaView time series: one VTK XML UnstructuredGrid file
//! (`.vtu`) per converged point and one collection (`.pvd`) that lists them with their time.
//!
//! The `.vtu` files are encoded by `vtkio` (binary, base64, uncompressed, little endian); the
//! `.pvd` by `quick-xml`. Every file is written whole through [`crate::atomic_write`] or not at
//! all (the temporaries that killed runs left in the folder are removed first), and a series
//! that fails part-way removes the files it had written.

use std::path::{Path, PathBuf};

use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, Event};
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};

use crate::atomic_write::{remove_own_temporaries, remove_stale_temporaries, write_atomic};
use crate::fe::{CurvePoint, LoadDirection, StepState};

/// Name of the collection file in the series folder.
pub const COLLECTION_FILE: &str = "series.pvd";

/// One converged point of a solve and its deformed state, as
/// [`crate::fe::solve_with_states`] hands them out.
#[derive(Clone, Debug, PartialEq)]
pub struct VtkStep {
    /// The branch of the point.
    pub direction: LoadDirection,
    /// The point (its slab displacement is the time of the series).
    pub point: CurvePoint,
    /// Its deformed state.
    pub state: StepState,
}

/// Why a series could not be written; each names the file or folder.
#[derive(Debug, thiserror::Error)]
pub enum VtkError {
    /// The series folder does not exist and cannot be made (e.g. a file is in its place).
    #[error("cannot create the VTK folder {}: {source}", dir.display())]
    Folder {
        /// The folder.
        dir: PathBuf,
        /// The file-system error.
        source: std::io::Error,
    },
    /// A step's data could not be encoded as VTK XML.
    #[error("cannot encode {}: {reason}", path.display())]
    Encode {
        /// The file it was meant for.
        path: PathBuf,
        /// The encoder's message.
        reason: String,
    },
    /// A file could not be written.
    #[error("{reason}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The message, naming the file and its cause.
        reason: String,
    },
}

/// The name of the `.vtu` file of step `index` (in order of the series).
pub fn step_file_name(index: usize) -> String {
    format!("step_{index:04}.vtu")
}

/// The time of each step in the collection: the slab travel, `d/λ` on loading and
/// `2 d_max/λ − d/λ` on unloading (`d_max` the last loading point's slab displacement), which
/// keeps growing when the slab retracts. A loading series's time is its slab displacement.
pub fn series_times(steps: &[VtkStep]) -> Vec<f64> {
    let d_max = steps
        .iter()
        .rev()
        .find(|s| s.direction == LoadDirection::Loading)
        .map_or(0.0, |s| s.point.slab_displacement_over_lambda);
    steps
        .iter()
        .map(|s| {
            let d = s.point.slab_displacement_over_lambda;
            match s.direction {
                LoadDirection::Loading => d,
                LoadDirection::Unloading => 2.0 * d_max - d,
            }
        })
        .collect()
}

/// Writes the deformed states of a solve into `dir` (created if missing) as a ParaView time
/// series, and returns the paths written, the collection last.
///
/// Opening `series.pvd` in ParaView shows the deformed layer (the points are the current
/// positions, in units of λ, the z coordinate 0) at every converged point, loading then
/// unloading, with the slab displacement `d/λ` as time (on unloading the slab travel
/// `2 d_max/λ − d/λ`, [`series_times`]). Point data: `displacement_over_lambda` (current −
/// reference position, 3 components, z = 0), `reference_position_over_lambda` (3 components),
/// and on the contact face (0 elsewhere) `in_contact` (0/1), `in_stick` (0/1: 1 where the face
/// sticks to the indenter, [`crate::fe::DeformedState::in_stick`]; a node in contact and not
/// sticking slips), `contact_pressure_over_estar` and
/// `contact_shear_over_estar` (nodal force over tributary length of the deformed face, over
/// E*; shear along the indenter's tangent, 0 on the symmetry lines), `slip_over_lambda` (slip
/// since touching, [`StepState::face_slip_over_lambda`]); cell data `J` (current over reference
/// area of each quad, the mean dilatation of the Q1/P0 element). Files of an earlier series in
/// `dir` that this one does not overwrite stay, unlisted.
pub fn write_series(dir: &Path, steps: &[VtkStep]) -> Result<Vec<PathBuf>, VtkError> {
    write_series_as(dir, steps, None)
}

/// [`write_series`] for a solve that stopped short: its converged states, and a collection
/// that says so. The `Collection` element carries `status="incomplete"` and the reason
/// (`reason="…"`, the solver's message), and an XML comment repeats both for a reader of the
/// file; ParaView ignores both and opens the converged states.
pub fn write_incomplete_series(
    dir: &Path,
    steps: &[VtkStep],
    reason: &str,
) -> Result<Vec<PathBuf>, VtkError> {
    write_series_as(dir, steps, Some(reason))
}

/// The series, complete (`incomplete` = `None`) or not.
fn write_series_as(
    dir: &Path,
    steps: &[VtkStep],
    incomplete: Option<&str>,
) -> Result<Vec<PathBuf>, VtkError> {
    std::fs::create_dir_all(dir).map_err(|source| VtkError::Folder {
        dir: dir.to_path_buf(),
        source,
    })?;
    remove_stale_temporaries(dir).map_err(|e| VtkError::Write {
        path: dir.to_path_buf(),
        reason: format!("{e:#}"),
    })?;
    let mut written = Vec::with_capacity(steps.len() + 1);
    let result = write_files(dir, steps, incomplete, &mut written);
    if result.is_err() {
        for path in &written {
            let _ = std::fs::remove_file(path);
        }
        written.clear();
    }
    remove_own_temporaries(dir);
    result.map(|()| written)
}

/// The `.vtu` of every step, then the collection; each path is pushed once written.
fn write_files(
    dir: &Path,
    steps: &[VtkStep],
    incomplete: Option<&str>,
    written: &mut Vec<PathBuf>,
) -> Result<(), VtkError> {
    let mut names = Vec::with_capacity(steps.len());
    for (index, step) in steps.iter().enumerate() {
        let name = step_file_name(index);
        let path = dir.join(&name);
        let bytes = unstructured_grid(&step.state).map_err(|e| VtkError::Encode {
            path: path.clone(),
            reason: e.to_string(),
        })?;
        write(&path, &bytes)?;
        written.push(path);
        names.push(name);
    }
    let path = dir.join(COLLECTION_FILE);
    let bytes = collection(steps, &names, incomplete).map_err(|e| VtkError::Encode {
        path: path.clone(),
        reason: e.to_string(),
    })?;
    write(&path, &bytes)?;
    written.push(path);
    Ok(())
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), VtkError> {
    write_atomic(path, bytes).map_err(|e| VtkError::Write {
        path: path.to_path_buf(),
        reason: format!("{e:#}"),
    })
}

/// A point's 2-D vector as a VTK 3-component one (z = 0).
fn in_plane(v: [f64; 2]) -> [f64; 3] {
    [v[0], v[1], 0.0]
}

/// The `.vtu` bytes of one deformed state.
fn unstructured_grid(st: &StepState) -> Result<Vec<u8>, vtkio::Error> {
    let d = &st.deformed;
    let num_points = d.nodes.len();
    let points: Vec<f64> = d.nodes.iter().flat_map(|&x| in_plane(x)).collect();
    let displacement: Vec<f64> = d
        .nodes
        .iter()
        .zip(&st.reference_nodes)
        .flat_map(|(x, r)| in_plane([x[0] - r[0], x[1] - r[1]]))
        .collect();
    let reference: Vec<f64> = st
        .reference_nodes
        .iter()
        .flat_map(|&r| in_plane(r))
        .collect();
    // face values at their nodes, 0 elsewhere
    let on_face = |values: &[f64]| {
        let mut all = vec![0.0; num_points];
        for (&n, &v) in d.bottom.iter().zip(values) {
            all[n] = v;
        }
        all
    };
    let mut in_contact = vec![0u8; num_points];
    for (&n, &c) in d.bottom.iter().zip(&d.in_contact) {
        in_contact[n] = u8::from(c);
    }
    let mut in_stick = vec![0u8; num_points];
    for (&n, &s) in d.bottom.iter().zip(&d.in_stick) {
        in_stick[n] = u8::from(s);
    }
    let connectivity: Vec<u64> = d.quads.iter().flatten().map(|&n| n as u64).collect();
    let offsets: Vec<u64> = (1..=d.quads.len() as u64).map(|c| 4 * c).collect();
    let piece = UnstructuredGridPiece {
        points: points.into(),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity,
                offsets,
            },
            types: vec![CellType::Quad; d.quads.len()],
        },
        data: Attributes {
            point: vec![
                Attribute::vectors("displacement_over_lambda").with_data(displacement),
                Attribute::vectors("reference_position_over_lambda").with_data(reference),
                Attribute::scalars("in_contact", 1).with_data(in_contact),
                Attribute::scalars("in_stick", 1).with_data(in_stick),
                Attribute::scalars("contact_pressure_over_estar", 1)
                    .with_data(on_face(&d.contact_pressure_over_estar)),
                Attribute::scalars("contact_shear_over_estar", 1)
                    .with_data(on_face(&d.contact_shear_over_estar)),
                Attribute::scalars("slip_over_lambda", 1)
                    .with_data(on_face(&st.face_slip_over_lambda)),
            ],
            cell: vec![Attribute::scalars("J", 1).with_data(st.element_dilatation.clone())],
        },
    };
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        data: DataSet::inline(piece),
        file_path: None,
    };
    let mut bytes = Vec::new();
    vtk.write_xml(&mut bytes)?;
    Ok(bytes)
}

/// The `.pvd` bytes: one `DataSet` per step, its time ([`series_times`]), its branch as the
/// group, and its file relative to the collection; for an incomplete series the status and
/// reason ([`write_incomplete_series`]).
fn collection(
    steps: &[VtkStep],
    names: &[String],
    incomplete: Option<&str>,
) -> Result<Vec<u8>, quick_xml::Error> {
    let mut w = quick_xml::Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", None, None)))?;
    let file = BytesStart::new("VTKFile").with_attributes([
        ("type", "Collection"),
        ("version", "0.1"),
        ("byte_order", "LittleEndian"),
    ]);
    w.write_event(Event::Start(file))?;
    let mut collection = BytesStart::new("Collection");
    if let Some(reason) = incomplete {
        let note = format!(
            " INCOMPLETE: the solve stopped short after {} converged points: {} ",
            steps.len(),
            reason.replace("--", "- -")
        );
        w.write_event(Event::Comment(quick_xml::events::BytesText::from_escaped(
            note,
        )))?;
        collection.push_attribute(("status", "incomplete"));
        collection.push_attribute(("reason", reason));
    }
    w.write_event(Event::Start(collection))?;
    for ((step, name), time) in steps.iter().zip(names).zip(series_times(steps)) {
        let time = time.to_string();
        let data_set = BytesStart::new("DataSet").with_attributes([
            ("timestep", time.as_str()),
            ("group", step.direction.name()),
            ("part", "0"),
            ("file", name.as_str()),
        ]);
        w.write_event(Event::Empty(data_set))?;
    }
    w.write_event(Event::End(BytesEnd::new("Collection")))?;
    w.write_event(Event::End(BytesEnd::new("VTKFile")))?;
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    Ok(bytes)
}
