//! `wavy._wavy`: the Python extension over the wavy library. It converts arguments and results
//! and adds no physics: every check, message and value comes from `wavy::runner`
//! (`eval_request`, `solve_request`, `input`) and `wavy::runner::run_spec_file`, the functions
//! `wavy eval`, `wavy solve` and `wavy run` call. The Python API (`python/wavy/__init__.py`)
//! wraps these functions; docs/python.md describes it.

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::{PyMemoryError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::str::FromStr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::Duration;
use wavy::fe::{Kinematics, LoadDirection};
use wavy::models::{CoefficientSet, FitDomain, ModelKind, Reading};
use wavy::runner::requests::eval_request::LawRequest;
use wavy::runner::requests::input_checks::{self, out_of_range, InputError};
use wavy::runner::requests::request_error::{full_message, RequestError};
use wavy::runner::requests::solve_outcome::{Column, ExtraColumn, SolveOutcome};
use wavy::runner::requests::solve_request::{self, SolveRequest};
use wavy::runner::requests::solver::Solver;
use wavy::runner::requests::tolerance_choice;

/// A message of the library in Python's words: every command-line flag `--some-name` becomes
/// the keyword argument `some_name` (the bindings' arguments are the flags' names in
/// snake_case, docs/python.md), so that a message names what the Python caller wrote.
fn in_python_words(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(i) = rest.find("--") {
        out.push_str(&rest[..i]);
        let after = &rest[i + 2..];
        let len = after
            .find(|c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'))
            .unwrap_or(after.len());
        let name = &after[..len];
        if name.starts_with(|c: char| c.is_ascii_lowercase()) {
            out.push_str(&name.replace('-', "_"));
        } else {
            out.push_str("--");
            out.push_str(name);
        }
        rest = &after[len..];
    }
    out.push_str(rest);
    out
}

/// An input error as `ValueError`, any other failure as `RuntimeError`, with the command
/// line's message (what `wavy` prints after `error: `) in Python's words.
fn to_py_err(e: RequestError) -> PyErr {
    let message = in_python_words(&full_message(&e));
    match (&e, e.is_input()) {
        (RequestError::Memory(_), _) => PyMemoryError::new_err(message),
        (_, true) => PyValueError::new_err(message),
        (_, false) => PyRuntimeError::new_err(message),
    }
}

fn input_err(e: InputError) -> PyErr {
    PyValueError::new_err(in_python_words(&e.to_string()))
}

/// A name among a type's names, or a `ValueError` naming the argument and the allowed names.
fn parse_name<T: FromStr>(flag: &str, value: &str, names: &[&str]) -> PyResult<T> {
    value
        .parse::<T>()
        .map_err(|_| input_err(out_of_range(flag, value, names.join(", "))))
}

fn law_request(
    model: &str,
    ar: f64,
    tau_max_mpa: f64,
    reading: &str,
    coefficients: &str,
) -> PyResult<LawRequest> {
    Ok(LawRequest {
        model: parse_name("--model", model, &ModelKind::ALL.map(ModelKind::key))?,
        ar,
        tau_max_mpa,
        reading: parse_name("--reading", reading, &Reading::ALL.map(Reading::name))?,
        coefficients: parse_name(
            "--coefficients",
            coefficients,
            &CoefficientSet::ALL.map(CoefficientSet::name),
        )?,
    })
}

/// (a/λ, p̄/E*, extrapolated) arrays, one entry per evaluated point.
type LawArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
);

/// `wavy eval --model MODEL …` at `values`: with `inverse` false they are a/λ
/// (`--a-over-lambda XS`), with `inverse` true p̄/E* (`--p-over-estar PS`); the rows as
/// [`LawArrays`].
#[pyfunction]
#[pyo3(signature = (model, ar, tau_max_mpa, reading, coefficients, values, inverse))]
#[allow(clippy::too_many_arguments)] // one argument per `wavy eval` flag, as Python passes them
fn law<'py>(
    py: Python<'py>,
    model: &str,
    ar: f64,
    tau_max_mpa: f64,
    reading: &str,
    coefficients: &str,
    values: PyReadonlyArray1<'py, f64>,
    inverse: bool,
) -> PyResult<LawArrays<'py>> {
    let request = law_request(model, ar, tau_max_mpa, reading, coefficients)?;
    let values = values.as_slice()?;
    let rows = match inverse {
        false => request.forward(values),
        true => request.inverse(values),
    }
    .map_err(to_py_err)?;
    Ok((
        PyArray1::from_iter(py, rows.iter().map(|r| r.a_over_lambda)),
        PyArray1::from_iter(py, rows.iter().map(|r| r.p_over_estar)),
        PyArray1::from_iter(py, rows.iter().map(|r| r.extrapolated)),
    ))
}

/// The fit domain of a coefficient set, `(AR min, AR max, τ_max min, τ_max max in MPa)`: outside
/// it a WNL value is extrapolated (the `extrapolated` flag of [`law`]).
#[pyfunction]
fn fit_domain(coefficients: &str) -> PyResult<(f64, f64, f64, f64)> {
    let set: CoefficientSet = parse_name(
        "--coefficients",
        coefficients,
        &CoefficientSet::ALL.map(CoefficientSet::name),
    )?;
    let d = set.coefficients().domain;
    Ok((
        d.aspect_ratio_min,
        d.aspect_ratio_max,
        d.tau_max_mpa_min,
        d.tau_max_mpa_max,
    ))
}

/// The columns and metadata of an outcome, as a dict (`wavy.Result` wraps it).
fn outcome_dict<'py>(py: Python<'py>, o: &SolveOutcome) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, column) in o.columns() {
        match column {
            Column::Real(v) => d.set_item(name, PyArray1::from_vec(py, v))?,
            Column::Count(v) => d.set_item(
                name,
                PyArray1::from_iter(py, v.into_iter().map(|c| c as i64)),
            )?,
            Column::Name(v) => d.set_item(name, v)?,
        }
    }
    d.set_item("mesh", o.mesh.map(|m| m.counts()))?;
    d.set_item("grid_points", o.grid_points)?;
    d.set_item("unknowns", o.unknowns)?;
    d.set_item(
        "cycle_work_over_estar_lambda2",
        o.cycle_energy.map(|e| e.cycle_work_over_estar_lambda2),
    )?;
    d.set_item(
        "face_dissipation_over_estar_lambda2",
        o.cycle_energy
            .map(|e| e.face_dissipation_over_estar_lambda2),
    )?;
    d.set_item("load_steps", o.load_steps())?;
    d.set_item("newton_iterations_total", o.newton_iterations())?;
    d.set_item("tangent_assemblies", o.work.tangent_assemblies)?;
    d.set_item("factorisations", o.work.factorisations)?;
    Ok(d)
}

/// How often the waiting Python thread runs the signal handlers during a solve.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// `request` solved on a thread of its own while this one, the GIL released, waits for it and
/// runs Python's signal handlers every [`SIGNAL_POLL`]. A signal handler that raises (Ctrl-C:
/// `KeyboardInterrupt`) sets the solve's interrupt flag ([`wavy::fe::interrupt`]), which the
/// solver reads at every Newton iteration, and raises at once: the caller gets the exception
/// within one poll, whatever the mesh, and the solve thread ends at its next iteration.
fn solve_on_thread(
    py: Python<'_>,
    request: SolveRequest,
    vtk: Option<PathBuf>,
) -> PyResult<Result<wavy::runner::requests::solve_outcome::SolveOutcome, RequestError>> {
    let flag = Arc::new(AtomicBool::new(false));
    let (sender, receiver) = mpsc::channel();
    let watched = Arc::clone(&flag);
    std::thread::Builder::new()
        .name("wavy-solve".into())
        .spawn(move || {
            let solved = wavy::fe::interrupt::watching(watched, || {
                solve_request::solve(&request, vtk.as_deref(), &mut |_| ControlFlow::Continue(()))
            });
            // the receiver is gone when the caller was interrupted: nobody waits for this
            let _ = sender.send(solved);
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the solve's thread: {e}")))?;
    let mut receiver = receiver;
    loop {
        // the receiver is moved into the GIL-free wait and back (it is `Send`, not `Sync`)
        let (received, back) = py.detach(move || (receiver.recv_timeout(SIGNAL_POLL), receiver));
        receiver = back;
        match received {
            Ok(solved) => return Ok(solved),
            Err(mpsc::RecvTimeoutError::Timeout) => {
                if let Err(raised) = py.check_signals() {
                    flag.store(true, Ordering::Relaxed);
                    return Err(raised);
                }
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return Err(PyRuntimeError::new_err(
                    "the solve's thread ended without an answer (a bug in wavy: please report it)",
                ))
            }
        }
    }
}

/// `wavy solve` with the same options, the GIL released during the solve. Returns the outcome
/// as a dict, with `stopped` = None, or, when the solver stopped, the converged part and
/// `stopped` = (message, reason), and `notes` (what the command line tells on stderr) and
/// `extrapolated` (outside the WNL fit domain); raises `ValueError` for bad input, `MemoryError`
/// when the solve's estimated memory is above `max_memory` or what is available,
/// `KeyboardInterrupt` on Ctrl-C ([`solve_on_thread`]). With `vtk`, the curve's ParaView time
/// series is written into that folder, as `wavy solve --vtk` does.
#[pyfunction]
#[pyo3(signature = (*, ar, tau_max_mpa, mu, elastic_slip_over_element, estar_mpa, kappa_over_g, thickness_over_lambda,
    kinematics, mesh, tolerance, error_estimate, until_a_over_lambda, until_p_over_estar, unload,
    unloading_substeps, vtk, profile, until_contact_fraction, max_memory, solver, grid_points, points, half_plane, coarsen_at_aspect))]
#[allow(clippy::too_many_arguments)]
fn solve<'py>(
    py: Python<'py>,
    ar: f64,
    tau_max_mpa: f64,
    mu: f64,
    elastic_slip_over_element: f64,
    estar_mpa: f64,
    kappa_over_g: f64,
    thickness_over_lambda: f64,
    kinematics: Option<&str>,
    mesh: Option<&str>,
    tolerance: Option<f64>,
    error_estimate: bool,
    until_a_over_lambda: f64,
    until_p_over_estar: Option<f64>,
    unload: bool,
    unloading_substeps: Option<usize>,
    vtk: Option<PathBuf>,
    profile: Option<&str>,
    until_contact_fraction: Option<f64>,
    max_memory: Option<u64>,
    solver: &str,
    grid_points: Option<usize>,
    points: Option<usize>,
    half_plane: bool,
    coarsen_at_aspect: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let solver = parse_name::<Solver>("--solver", solver, &Solver::ALL.map(Solver::name))?;
    // the command line's default: finite strain, but linear for the boundary-element solver
    let kinematics = match kinematics {
        Some(name) => {
            parse_name::<Kinematics>("--kinematics", name, &Kinematics::ALL.map(Kinematics::name))?
        }
        None if solver == Solver::BoundaryElement => Kinematics::Linear,
        None => Kinematics::Finite,
    };
    // `profile` (the command line's --profile) instead of `ar` (its shorthand --ar)
    let (ar, finer_harmonics) = match profile {
        Some(text) => {
            let p = input_checks::profile(text).map_err(input_err)?;
            (p.aspect_ratio, p.finer)
        }
        None => (ar, wavy::profile::FinerHarmonics::NONE),
    };
    let request = SolveRequest {
        tau_max_mpa,
        mu,
        elastic_slip_over_element,
        estar_mpa,
        kappa_over_g,
        thickness_over_lambda,
        kinematics,
        mesh: mesh
            .map(input_checks::mesh)
            .transpose()
            .map_err(input_err)?,
        tolerance,
        error_estimate,
        until_a_over_lambda,
        until_p_over_estar,
        until_contact_fraction,
        unload,
        unloading_substeps,
        max_memory,
        finer_harmonics,
        solver,
        grid_points,
        points,
        half_plane,
        coarsen_at_aspect,
        ..SolveRequest::new(ar)
    };
    // the notes the command line gives on stderr, for the result's metadata
    let mut notes: Vec<String> = vec![];
    if solver == Solver::BoundaryElement {
        request.prepare_bem().map_err(to_py_err)?;
    } else {
        let prepared = request.prepare().map_err(to_py_err)?;
        if let (Some(choice), Some(t)) = (&prepared.tolerance_choice, tolerance) {
            notes.push(tolerance_choice::announcement(choice, t));
        }
        notes.extend(prepared.notes.iter().cloned());
    }
    let notes: Vec<String> = notes.iter().map(|n| in_python_words(n)).collect();
    let extrapolated = !FitDomain::PAPER.contains(request.ar, request.tau_max_mpa);
    let with_metadata = |d: Bound<'py, PyDict>| -> PyResult<Bound<'py, PyDict>> {
        d.set_item("notes", notes.clone())?;
        d.set_item("extrapolated", extrapolated)?;
        Ok(d)
    };
    match solve_on_thread(py, request, vtk)? {
        Ok(outcome) => {
            let d = with_metadata(outcome_dict(py, &outcome)?)?;
            d.set_item("stopped", py.None())?;
            Ok(d)
        }
        Err(RequestError::Stopped { error, partial }) => {
            let d = with_metadata(outcome_dict(py, &partial)?)?;
            let message = full_message(&RequestError::Stopped {
                error: error.clone(),
                partial: partial.clone(),
            });
            d.set_item(
                "stopped",
                (
                    in_python_words(&message),
                    in_python_words(&error.to_string()),
                ),
            )?;
            Ok(d)
        }
        Err(RequestError::Interrupted { .. }) => Err(
            pyo3::exceptions::PyKeyboardInterrupt::new_err("the solve was interrupted"),
        ),
        Err(other) => Err(to_py_err(other)),
    }
}

/// `wavy run SPEC --out OUT [--cache CACHE]`: the written paths (the GIL released meanwhile).
/// A spec error is a `ValueError`; a failed run, or figures resting on curves that stopped
/// short (written, marked INCOMPLETE, as the command line does), a `RuntimeError`.
#[pyfunction]
#[pyo3(signature = (spec, out, cache=None))]
fn run(
    py: Python<'_>,
    spec: PathBuf,
    out: PathBuf,
    cache: Option<PathBuf>,
) -> PyResult<Vec<String>> {
    let mut options = wavy::runner::RunOptions::default();
    if let Some(c) = cache {
        options.sweep.cache_dir = c;
    }
    let ran = py.detach(|| -> anyhow::Result<(Vec<PathBuf>, Option<String>)> {
        let output = wavy::runner::run_spec_file(&spec, &options)?;
        let written = wavy::runner::write_outputs(&output, &out)?;
        Ok((
            written,
            wavy::runner::incomplete_message(std::slice::from_ref(&output)),
        ))
    });
    match ran {
        Ok((_, Some(incomplete))) => Err(PyRuntimeError::new_err(incomplete)),
        Ok((written, None)) => Ok(written.iter().map(|p| p.display().to_string()).collect()),
        Err(e)
            if e.chain()
                .any(|c| c.is::<wavy::spec::SpecError>() || c.is::<InputError>()) =>
        {
            Err(PyValueError::new_err(in_python_words(&format!("{e:#}"))))
        }
        Err(e) => Err(PyRuntimeError::new_err(in_python_words(&format!("{e:#}")))),
    }
}

/// The names of the load branches (`branch` column).
fn branch_names() -> [&'static str; 2] {
    [
        LoadDirection::Loading.name(),
        LoadDirection::Unloading.name(),
    ]
}

#[pymodule]
fn _wavy(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(law, m)?)?;
    m.add_function(wrap_pyfunction!(fit_domain, m)?)?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add("BRANCHES", branch_names())?;
    // the columns of a result, in the order `wavy solve` prints them (the one list of them:
    // `SolveOutcome::columns`), without the optional `error_estimate`
    let empty = SolveOutcome {
        mesh: None,
        grid_points: None,
        unknowns: 0,
        extra: ExtraColumn::None,
        rows: vec![],
        work: wavy::fe::SolveWork::default(),
        cycle_energy: None,
    };
    let columns: Vec<&str> = empty.columns().iter().map(|(name, _)| *name).collect();
    m.add("COLUMNS", columns)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    let defaults = SolveRequest::new(f64::NAN);
    let d = PyDict::new(m.py());
    d.set_item("mu", defaults.mu)?;
    d.set_item(
        "elastic_slip_over_element",
        defaults.elastic_slip_over_element,
    )?;
    d.set_item("estar_mpa", defaults.estar_mpa)?;
    d.set_item("kappa_over_g", defaults.kappa_over_g)?;
    d.set_item("thickness_over_lambda", defaults.thickness_over_lambda)?;
    d.set_item("until_a_over_lambda", defaults.until_a_over_lambda)?;
    m.add("SOLVE_DEFAULTS", d)?;
    Ok(())
}
