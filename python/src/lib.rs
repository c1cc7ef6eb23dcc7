//! `wavy._wavy`: the Python extension over the wavy library. It converts arguments and results
//! and adds no physics: every check, message and value comes from `wavy::runner`
//! (`eval_request`, `solve_request`, `input`) and `wavy::runner::run_spec_file`, the functions
//! `wavy eval`, `wavy solve` and `wavy run` call. The Python API (`python/wavy/__init__.py`)
//! wraps these functions; docs/python.md describes it.

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::str::FromStr;
use wavy::fe::{Kinematics, LoadDirection};
use wavy::models::{CoefficientSet, ModelKind, Reading};
use wavy::runner::requests::eval_request::LawRequest;
use wavy::runner::requests::input_checks::{self, out_of_range, InputError};
use wavy::runner::requests::request_error::{full_message, RequestError};
use wavy::runner::requests::solve_outcome::{Column, SolveOutcome};
use wavy::runner::requests::solve_request::{self, SolveRequest};

/// An input error as `ValueError`, any other failure as `RuntimeError`, with the command
/// line's message (what `wavy` prints after `error: `).
fn to_py_err(e: RequestError) -> PyErr {
    let message = full_message(&e);
    match e.is_input() {
        true => PyValueError::new_err(message),
        false => PyRuntimeError::new_err(message),
    }
}

fn input_err(e: InputError) -> PyErr {
    PyValueError::new_err(e.to_string())
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
    d.set_item("mesh", o.mesh.counts())?;
    d.set_item("unknowns", o.unknowns)?;
    d.set_item("load_steps", o.load_steps())?;
    d.set_item("newton_iterations_total", o.newton_iterations())?;
    d.set_item("tangent_assemblies", o.work.tangent_assemblies)?;
    d.set_item("factorisations", o.work.factorisations)?;
    Ok(d)
}

/// The Python signal handlers run (Ctrl-C raises `KeyboardInterrupt` there); `Break` with the
/// exception kept in `raised` when one raised. Called between load steps, with the GIL
/// taken for the check only.
fn check_signals(raised: &mut Option<PyErr>) -> ControlFlow<()> {
    match Python::attach(|py| py.check_signals()) {
        Ok(()) => ControlFlow::Continue(()),
        Err(e) => {
            *raised = Some(e);
            ControlFlow::Break(())
        }
    }
}

/// `wavy solve` with the same options, the GIL released during the solve. Returns the outcome
/// as a dict, with `stopped` = None, or, when the solver stopped, the converged part and
/// `stopped` = (message, reason); raises `ValueError` for bad input, `KeyboardInterrupt` on
/// Ctrl-C (checked after every converged load step). With `vtk`, a complete curve also writes
/// its ParaView time series into that folder (as `wavy solve --vtk`).
#[pyfunction]
#[pyo3(signature = (*, ar, tau_max_mpa, mu, estar_mpa, kappa_over_g, thickness_over_lambda,
    kinematics, mesh, tolerance, error_estimate, until_a_over_lambda, until_p_over_estar, unload,
    vtk, profile, until_contact_fraction))]
#[allow(clippy::too_many_arguments)]
fn solve<'py>(
    py: Python<'py>,
    ar: f64,
    tau_max_mpa: f64,
    mu: f64,
    estar_mpa: f64,
    kappa_over_g: f64,
    thickness_over_lambda: f64,
    kinematics: &str,
    mesh: Option<&str>,
    tolerance: Option<f64>,
    error_estimate: bool,
    until_a_over_lambda: f64,
    until_p_over_estar: Option<f64>,
    unload: bool,
    vtk: Option<PathBuf>,
    profile: Option<&str>,
    until_contact_fraction: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
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
        estar_mpa,
        kappa_over_g,
        thickness_over_lambda,
        kinematics: parse_name::<Kinematics>(
            "--kinematics",
            kinematics,
            &Kinematics::ALL.map(Kinematics::name),
        )?,
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
        finer_harmonics,
        ..SolveRequest::new(ar)
    };
    let mut raised: Option<PyErr> = None;
    let solved = py.detach(|| {
        solve_request::solve(&request, vtk.as_deref(), &mut |_| {
            check_signals(&mut raised)
        })
    });
    match solved {
        Ok(outcome) => {
            let d = outcome_dict(py, &outcome)?;
            d.set_item("stopped", py.None())?;
            Ok(d)
        }
        Err(RequestError::Stopped { error, partial }) => {
            let d = outcome_dict(py, &partial)?;
            let message = full_message(&RequestError::Stopped {
                error: error.clone(),
                partial: partial.clone(),
            });
            d.set_item("stopped", (message, error.to_string()))?;
            Ok(d)
        }
        Err(RequestError::Interrupted { .. }) => {
            Err(raised.unwrap_or_else(|| PyRuntimeError::new_err("the solve was interrupted")))
        }
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
            Err(PyValueError::new_err(format!("{e:#}")))
        }
        Err(e) => Err(PyRuntimeError::new_err(format!("{e:#}"))),
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
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add("BRANCHES", branch_names())?;
    let defaults = SolveRequest::new(f64::NAN);
    let d = PyDict::new(m.py());
    d.set_item("mu", defaults.mu)?;
    d.set_item("estar_mpa", defaults.estar_mpa)?;
    d.set_item("kappa_over_g", defaults.kappa_over_g)?;
    d.set_item("thickness_over_lambda", defaults.thickness_over_lambda)?;
    d.set_item("until_a_over_lambda", defaults.until_a_over_lambda)?;
    m.add("SOLVE_DEFAULTS", d)?;
    Ok(())
}
