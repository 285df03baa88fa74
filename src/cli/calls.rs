//! The library calls behind the Python package (`python/`): the same work as the subcommands,
//! with a scene given as keywords and every answer as JSON text, so that the binding only
//! converts and releases the interpreter lock. Nothing here computes anything the subcommands
//! do not.

use ringcontact::choice::Choice;

use super::{message, refuse_non_finite};
use crate::harness::grade::{self, GradeReport};
use ringcontact::heartbeat::Heartbeat;
use ringcontact::methods::Degree;
use ringcontact::methods::{self, Method, MethodOptions};
use ringcontact::provenance::Provenance;
use ringcontact::scene::SceneSpec;

/// The method options a keyword solve takes besides the scene (as `verify solve`'s flags).
#[derive(Clone, Debug, Default)]
pub struct SolveOptions {
    /// `--grid N`: grid BEM cells per side.
    pub grid: Option<usize>,
    /// `--grid-extent L`: grid BEM half-size for a free band, in units of `a`.
    pub grid_extent: Option<f64>,
    /// `--degree D`: FEM element degree 1, 2 or 3.
    pub degree: Option<u8>,
}

/// Solve each scene of `scenes_json` (a JSON array of objects of scene keywords,
/// [`SceneSpec::from_keywords`]) by the method named `method`, as `verify solve --json` does;
/// a relative `profile` is read from `base`. Every scene is validated before the first is
/// solved; an error names the scene (`state 3 of 10`) when there are several. Returns the JSON
/// array of the solutions, in order.
pub fn solve_keyword_scenes(
    scenes_json: &str,
    method: &str,
    options: &SolveOptions,
    base: Option<&std::path::Path>,
) -> Result<String, String> {
    let method = Method::named(method).ok_or_else(|| {
        format!(
            "method {method:?} is not one of {}",
            Method::names_joined(", ")
        )
    })?;
    let degree = match options.degree {
        None => None,
        Some(n) => Some(
            Degree::from_number(n)
                .ok_or_else(|| format!("degree {n}: the FEM's elements are of degree 1, 2 or 3"))?,
        ),
    };
    // The grid's range is the grid BEM's own to check (`grid_contact::check_grid`).
    let options = MethodOptions {
        degree,
        grid: options.grid,
        grid_extent: options.grid_extent,
        ..crate::harness::settings::method_options()
    };
    let values: Vec<serde_json::Value> = serde_json::from_str(scenes_json)
        .map_err(|e| format!("the scenes are not a JSON array: {e}"))?;
    let count = values.len();
    // Where the error is: the state among several (a single scene's error speaks for itself).
    let name = |k: usize| format!("state {} of {count}", k + 1);
    let named = |k: usize, e: String| {
        if count == 1 {
            e
        } else {
            format!("{}: {e}", name(k))
        }
    };
    let scenes = values
        .into_iter()
        .enumerate()
        .map(|(k, value)| {
            let serde_json::Value::Object(object) = value else {
                return Err(named(k, "a scene is an object of keywords".into()));
            };
            let given: Vec<String> = object.keys().cloned().collect();
            SceneSpec::from_keywords(object, &name(k), base)
                .and_then(SceneSpec::validate)
                .map_err(|e| named(k, ringcontact::scene::in_keywords(e, &given).to_string()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let heartbeat = Heartbeat::start(
        "ringcontact.solve",
        crate::harness::progress::fem_progress(),
    );
    let mut solutions = Vec::with_capacity(count);
    for (k, scene) in scenes.iter().enumerate() {
        heartbeat.set(name(k));
        let solution =
            methods::solve_with(scene, method, &options).map_err(|e| named(k, e.to_string()))?;
        refuse_non_finite(&format!("the solve of {}", name(k)), &solution)?;
        solutions.push(solution);
    }
    serde_json::to_string(&solutions).map_err(message)
}

/// Grade the results `text` (CSV, or JSON when `json` or when it starts with `[` or `{`),
/// named `origin` in messages and in the report, at tolerance `tol`, as `verify grade --json`
/// does. Returns the report's JSON and whether every value is within `tol`.
pub fn grade_text(
    text: &str,
    origin: &str,
    json: bool,
    tol: f64,
) -> Result<(String, bool), String> {
    let rows = grade::input::parse(text, origin, json, None)?;
    let grading = super::grade::grade_rows(&rows, tol, "ringcontact.grade")
        .map_err(|e| format!("{origin}: {e}"))?;
    let report = GradeReport {
        results: origin.to_string(),
        provenance: Provenance::of_this_process(),
        grading: &grading,
    };
    let text = serde_json::to_string(&report).map_err(message)?;
    Ok((text, grading.beyond == 0))
}

/// Grade the results file `path` (CSV, or JSON) at tolerance `tol`, as `verify grade --results
/// PATH --json` does. Returns the report's JSON and whether every value is within `tol`.
pub fn grade_file(path: &std::path::Path, tol: f64) -> Result<(String, bool), String> {
    let rows = grade::input::read(path)?;
    let grading = super::grade::grade_rows(&rows, tol, "ringcontact.grade")?;
    let report = GradeReport {
        results: path.display().to_string(),
        provenance: Provenance::of_this_process(),
        grading: &grading,
    };
    let text = serde_json::to_string(&report).map_err(message)?;
    Ok((text, grading.beyond == 0))
}

/// Write the dataset (`small`: the coarse copy) into `out`, as `verify dataset --out OUT --json`
/// does, and return what that prints.
pub fn dataset(out: &std::path::Path, small: bool) -> Result<String, String> {
    let written = super::dataset::write(out, small)?;
    super::dataset::summary_json(out, &written)
}

/// The JKR sweep of `punch` (a fixed annulus over `b/a`, a punch with a rim over `d0/h`) written
/// into `out` (default `reports/jkr`), as `verify jkr --sweep --json` does: the rows' JSON.
/// A sweep takes neither `eps` nor `d0h`; the one that belongs to the other family is refused by
/// its keyword ([`ringcontact::adhesion::refuse_other_family`]).
pub fn jkr_sweep(
    punch: &ringcontact::punch::PunchKind,
    eps: Option<f64>,
    d0h: Option<f64>,
    out: Option<&std::path::Path>,
) -> Result<String, String> {
    ringcontact::adhesion::refuse_other_family(punch, eps, d0h).map_err(message)?;
    let out = super::output_directory(out, "reports/jkr");
    super::jkr::sweep(punch, &ringcontact::methods::RingBem::new(), &out, true)
}
