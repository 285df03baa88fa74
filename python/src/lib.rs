//! `ringcontact._native`: the Rust library called from Python. Each function converts its
//! arguments, releases the interpreter lock while the library works (other Python threads and a
//! notebook's kernel stay responsive), and returns JSON text that the Python package
//! (`python/ringcontact/`) turns into dicts, NumPy arrays and DataFrames. Every error is a
//! `RingContactError` carrying the message `verify` would print.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

use ringcontact::adhesion;
use ringcontact::finite_guard;
use ringcontact::methods::RingBem;
use ringcontact::provenance;
use ringcontact::punch::PunchName;
use ringcontact_verify::cli::calls::{self, SolveOptions};

create_exception!(
    ringcontact,
    RingContactError,
    PyException,
    "An input ringcontact refuses or a solve that fails; the message is the tool's own."
);

/// Solve the scenes `scenes` (a JSON array of keyword objects) by `method`; the JSON array of
/// the solutions (the objects of `verify solve --json`). `call` names the Python call in the
/// provenance.
#[pyfunction]
#[pyo3(signature = (scenes, method, call, grid=None, grid_extent=None, degree=None, base=None))]
#[allow(clippy::too_many_arguments)]
fn solve_scenes(
    py: Python<'_>,
    scenes: String,
    method: String,
    call: String,
    grid: Option<usize>,
    grid_extent: Option<f64>,
    degree: Option<u8>,
    base: Option<std::path::PathBuf>,
) -> PyResult<String> {
    let options = SolveOptions {
        grid,
        grid_extent,
        degree,
    };
    py.detach(|| {
        provenance::called_as(&call, || {
            calls::solve_keyword_scenes(&scenes, &method, &options, base.as_deref())
        })
    })
    .map_err(RingContactError::new_err)
}

/// The JKR solution of the punch named `punch` (with its `exponent` or `profile`) at `b/a = eps`
/// (the flat annulus) or at the work of adhesion `d0/h = d0h` (the others), from the library's
/// [`adhesion::jkr`]: the JSON of `verify jkr --json`. `call` names the Python call.
#[pyfunction]
#[pyo3(signature = (punch, call, exponent=None, profile=None, eps=None, d0h=None))]
fn jkr(
    py: Python<'_>,
    punch: String,
    call: String,
    exponent: Option<f64>,
    profile: Option<std::path::PathBuf>,
    eps: Option<f64>,
    d0h: Option<f64>,
) -> PyResult<String> {
    py.detach(|| {
        provenance::called_as(&call, || {
            let kind = punch_of(&punch, exponent, profile.as_deref())?;
            let solution =
                adhesion::jkr(&RingBem::new(), &kind, eps, d0h).map_err(|e| e.to_string())?;
            finite_guard::check_finite(&solution).map_err(|field| {
                format!(
                    "{call} produced a non-finite result ({field}): the input is beyond the \
                     range where the numbers are representable"
                )
            })?;
            serde_json::to_string(&solution).map_err(|e| e.to_string())
        })
    })
    .map_err(RingContactError::new_err)
}

/// The punch named `punch` with its `exponent` or `profile`; an error naming the known punches.
fn punch_of(
    punch: &str,
    exponent: Option<f64>,
    profile: Option<&std::path::Path>,
) -> Result<ringcontact::punch::PunchKind, String> {
    let name = PunchName::parse(punch).ok_or_else(|| {
        format!(
            "unknown punch {punch:?} (one of {})",
            PunchName::names(None, ", ")
        )
    })?;
    name.with_parameters(exponent, profile)
        .map_err(|e| e.to_string())
}

/// The analytic references and fits the library knows ([`ringcontact::reference::catalogue`]):
/// the JSON of `verify references --json`.
#[pyfunction]
fn references() -> PyResult<String> {
    serde_json::to_string(&ringcontact::reference::catalogue())
        .map_err(|e| RingContactError::new_err(e.to_string()))
}

/// Grade the results file `path` (CSV or JSON) at tolerance `tol`: the JSON of `verify grade
/// --json` and whether every value is within `tol`.
#[pyfunction]
fn grade_file(
    py: Python<'_>,
    path: std::path::PathBuf,
    tol: f64,
    call: String,
) -> PyResult<(String, bool)> {
    py.detach(|| provenance::called_as(&call, || calls::grade_file(&path, tol)))
        .map_err(RingContactError::new_err)
}

/// Write the dataset (`small`: the coarse copy) into `out`: the JSON of `verify dataset --json`.
#[pyfunction]
fn dataset(py: Python<'_>, out: std::path::PathBuf, small: bool, call: String) -> PyResult<String> {
    py.detach(|| provenance::called_as(&call, || calls::dataset(&out, small)))
        .map_err(RingContactError::new_err)
}

/// The JKR sweep of the punch named `punch` (with its `exponent` or `profile`), written into
/// `out`: the rows' JSON of `verify jkr --sweep --json`.
#[pyfunction]
#[pyo3(signature = (punch, call, exponent=None, profile=None, eps=None, d0h=None, out=None))]
#[allow(clippy::too_many_arguments)]
fn jkr_sweep(
    py: Python<'_>,
    punch: String,
    call: String,
    exponent: Option<f64>,
    profile: Option<std::path::PathBuf>,
    eps: Option<f64>,
    d0h: Option<f64>,
    out: Option<std::path::PathBuf>,
) -> PyResult<String> {
    py.detach(|| {
        provenance::called_as(&call, || {
            let kind = punch_of(&punch, exponent, profile.as_deref())?;
            calls::jkr_sweep(&kind, eps, d0h, out.as_deref())
        })
    })
    .map_err(RingContactError::new_err)
}

/// Grade the results `text` (CSV, or JSON when `json`), named `origin`, at tolerance `tol`:
/// the JSON of `verify grade --json` and whether every value is within `tol`.
#[pyfunction]
fn grade_text(
    py: Python<'_>,
    text: String,
    origin: String,
    json: bool,
    tol: f64,
    call: String,
) -> PyResult<(String, bool)> {
    py.detach(|| provenance::called_as(&call, || calls::grade_text(&text, &origin, json, tol)))
        .map_err(RingContactError::new_err)
}

/// The library's version and the commit it was built from.
#[pyfunction]
fn build() -> (String, String) {
    (
        provenance::VERSION.to_string(),
        provenance::COMMIT.to_string(),
    )
}

/// The keywords a scene takes (`solve(**keywords)`).
#[pyfunction]
fn scene_keywords() -> Vec<String> {
    ringcontact::scene::keyword_names()
        .into_iter()
        .map(String::from)
        .collect()
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // A malformed mesh is an error naming the file, not a panic message: silent inside the
    // mesh parser, every other panic handed to the hook that was there.
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if !ringcontact::mesh::msh::inside_mesh_parser() {
            previous(info);
        }
    }));
    m.add("RingContactError", m.py().get_type::<RingContactError>())?;
    m.add_function(wrap_pyfunction!(solve_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(grade_file, m)?)?;
    m.add_function(wrap_pyfunction!(dataset, m)?)?;
    m.add_function(wrap_pyfunction!(jkr_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(jkr, m)?)?;
    m.add_function(wrap_pyfunction!(references, m)?)?;
    m.add_function(wrap_pyfunction!(grade_text, m)?)?;
    m.add_function(wrap_pyfunction!(build, m)?)?;
    m.add_function(wrap_pyfunction!(scene_keywords, m)?)?;
    Ok(())
}
