//! `verify grade`: another code's results against the converged reference at the same state.
//!
//! Each row of the results ([`input`]) is re-solved by the ring BEM at a tolerance of 1e-12
//! (where it declines, by `--method auto` at a hundredth of the grading tolerance), and each
//! graded value `v` is set beside the reference `r` with its bound `δ` (relative):
//! `relative_error = |v - r| / |r|` (`|v|` where `r = 0`), `within = relative_error <= T`.
//! A reference is trusted to judge a difference only when `100 δ <= relative_error`; a value
//! closer to the reference than that is said to be so (`note`), never graded silently.

pub mod input;

use serde::{Deserialize, Serialize};

pub use input::{Quantity, ResultRow};

use crate::harness::records::peers::PeerResult;
use crate::harness::report::table::{readable, verdict, Cell, Column, Format, Table};
use ringcontact::error::Error;
use ringcontact::methods::{self, Method};
use ringcontact::scene::{Scene, SceneSpec};
use ringcontact::solution::Solution;

/// The ring BEM's tolerance for the references.
pub const REFERENCE_TOLERANCE: f64 = 1e-12;

/// The tolerance the report grades the stored peer results at: their square grids (64 to 256
/// cells per side) resolve the force to a few parts in 1e3 on these states, a staircase error of
/// the first order in the cell size.
pub const PEER_TOLERANCE: f64 = 1e-2;

/// How much smaller than the difference it judges a reference's error bound must be.
pub const RESOLUTION: f64 = 100.0;

/// One graded value.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct GradedValue {
    /// Where the row is in the results file (`line 7`, `row 3`).
    pub place: String,
    /// Punch name (with `exponent` where the shape takes one).
    pub punch: String,
    /// What sets the state and its value (`eps`, `depth`, `force`; the fixed annulus's `eps`).
    pub state: String,
    pub state_value: f64,
    /// The graded quantity (`eps`, `depth`, `force`, `gamma`, `gamma1`, `gamma2`).
    pub quantity: Quantity,
    /// The value in the results file.
    pub value: f64,
    /// The reference value at the same state.
    pub reference: f64,
    /// The reference's relative error bound.
    pub reference_error: f64,
    /// `|value - reference| / |reference|` (`|value|` where the reference is 0).
    pub relative_error: f64,
    /// `relative_error <= tolerance`.
    pub within: bool,
    /// Whether the reference resolves the difference (`100 reference_error <= relative_error`).
    pub resolved: bool,
    /// The error the results claim for this value (`error_estimate` column), if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub claimed_error: Option<f64>,
    /// Whether the actual error is within the claimed one (allowing the reference's own bound).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub claim_holds: Option<bool>,
    /// Method of the reference.
    pub reference_method: String,
    /// Said when the difference is not resolved by the reference.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// The largest and the RMS relative error of one quantity of one punch.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Summary {
    pub punch: String,
    pub quantity: Quantity,
    pub count: usize,
    pub max_relative_error: f64,
    pub rms_relative_error: f64,
    /// How many are within the tolerance.
    pub within: usize,
}

/// A grading of a results file.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Grading {
    /// The tolerance `T` every relative error is held to.
    pub tolerance: f64,
    /// The largest relative error of all graded values.
    pub max_relative_error: f64,
    /// Every graded value, in the file's order.
    pub rows: Vec<GradedValue>,
    /// Per punch and quantity.
    pub summary: Vec<Summary>,
    /// Values beyond the tolerance.
    pub beyond: usize,
    /// Values the reference does not resolve (closer to it than 100 times its bound).
    pub unresolved: usize,
    /// Values whose actual error exceeds the error their results claim.
    pub claims_broken: usize,
}

/// A grading as `verify grade --json` prints it (and the Python package returns it): the
/// grading's keys, what was graded and the provenance.
#[derive(Serialize)]
pub struct GradeReport<'a> {
    /// The results graded: a file's path, or what the caller names them.
    pub results: String,
    pub provenance: ringcontact::provenance::Provenance,
    #[serde(flatten)]
    pub grading: &'a Grading,
}

/// Grade `rows` against the references at tolerance `tolerance`; `progress` is told each row.
pub fn grade(
    rows: &[ResultRow],
    tolerance: f64,
    progress: &dyn Fn(usize, usize),
) -> Result<Grading, String> {
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(format!(
            "--tol is a relative error: 0 < T < 1 (got {tolerance})"
        ));
    }
    let mut graded = Vec::new();
    for (k, row) in rows.iter().enumerate() {
        progress(k, rows.len());
        let scene = scene_of(row)?;
        let reference = reference_solution(&scene, tolerance)
            .map_err(|e| format!("{}: no reference at this state: {e}", row.place))?;
        let (state, state_value) = match (row.state, row.hole_ratio) {
            (Some((q, v)), None) => (q.key().to_string(), v),
            (_, Some(eps)) => ("eps".to_string(), eps),
            (None, None) => ("depth".to_string(), 1.0),
        };
        for &(quantity, value) in &row.values {
            let (reference_value, bound) = reference_of(&reference, quantity)
                .ok_or_else(|| format!("{}: the reference has no {}", row.place, quantity.key()))?;
            let difference = (value - reference_value).abs();
            let relative_error = if reference_value == 0.0 {
                difference
            } else {
                difference / reference_value.abs()
            };
            let resolved = RESOLUTION * bound <= relative_error;
            // A claimed error is relative, but absolute for eps (as `verify solve` writes it).
            let claim_holds = row.claimed_error.map(|claimed| match quantity {
                Quantity::Eps => difference <= claimed + bound * reference_value.abs(),
                _ => relative_error <= claimed + bound,
            });
            graded.push(GradedValue {
                place: row.place.clone(),
                punch: reference.punch.label(),
                state: state.clone(),
                state_value,
                quantity,
                value,
                reference: reference_value,
                reference_error: bound,
                relative_error,
                within: relative_error <= tolerance,
                resolved,
                claimed_error: row.claimed_error,
                claim_holds,
                reference_method: reference.method.clone(),
                note: (!resolved).then(|| {
                    format!(
                        "closer to the reference than {RESOLUTION} times its error bound \
                         ({bound:.1e}): agrees to the reference's accuracy, the difference is \
                         not resolved"
                    )
                }),
            });
        }
    }
    let summary = summarise(&graded);
    Ok(Grading {
        tolerance,
        max_relative_error: graded.iter().map(|g| g.relative_error).fold(0.0, f64::max),
        beyond: graded.iter().filter(|g| !g.within).count(),
        unresolved: graded.iter().filter(|g| !g.resolved).count(),
        claims_broken: graded
            .iter()
            .filter(|g| g.claim_holds == Some(false))
            .count(),
        rows: graded,
        summary,
    })
}

/// The scene of a row: its punch and units, the state as its load, the reference tolerance.
fn scene_of(row: &ResultRow) -> Result<Scene, String> {
    let mut spec = SceneSpec::default().shape_named(Some(row.punch), row.exponent);
    if let Some(rho) = row.tube_radius {
        spec = spec.tube_radius(rho);
    }
    if let Some(path) = &row.profile {
        spec = spec.profile(path);
    }
    if let Some(a) = row.rim_radius {
        spec = spec.rim_radius(a);
    }
    if let Some(h) = row.hole_depth {
        spec = spec.hole_depth(h);
    }
    if let Some(e) = row.effective_modulus {
        spec = spec.effective_modulus(e);
    }
    if let Some(eps) = row.hole_ratio {
        spec = spec.inner_ratio(eps);
    }
    spec = match row.state {
        Some((Quantity::Eps, v)) => spec.contact_ratio(v),
        Some((Quantity::Force, v)) => spec.force(v),
        Some((_, v)) => spec.depth(v),
        None => spec.depth(1.0),
    };
    spec.tolerance(REFERENCE_TOLERANCE)
        .validate()
        .map_err(|e| format!("{}, column {}", row.place, column_of(&e)))
}

/// The message of a scene error with the results file's column first (`eps: must satisfy ...`).
fn column_of(error: &Error) -> String {
    let Error::InvalidScene { field, rule } = error else {
        return format!("punch: {error}");
    };
    let column = match field.as_str() {
        "load.contact_ratio" | "eps" | "punch.inner_radius" => "eps",
        "load.depth" => "depth",
        "load.force" => "force",
        "material.effective_modulus" => "E_star",
        "punch.rim_radius" => "a",
        "punch.hole_depth" => "h",
        "punch.exponent" => "exponent",
        "punch.tube_radius" => "tube_radius",
        "punch.profile" => "profile",
        other => other,
    };
    format!("{column}: {rule}")
}

/// The reference at `scene`: the ring BEM at [`REFERENCE_TOLERANCE`], else the cheapest method
/// meeting a hundredth of the grading tolerance.
fn reference_solution(scene: &Scene, tolerance: f64) -> Result<Solution, String> {
    match methods::solve(scene, Method::RingBem) {
        Ok(s) if s.error_estimate.is_some() => Ok(s),
        first => {
            let fallback = (Scene {
                tolerance: Some((tolerance / RESOLUTION).max(1e-9)),
                ..scene.clone()
            })
            .clone()
            .clone()
            .clone()
            .clone()
            .clone()
            .clone();
            methods::solve(&fallback, Method::Auto).map_err(|e| {
                let ring = match first {
                    Err(r) => format!("ring BEM: {r}; "),
                    Ok(_) => String::new(),
                };
                format!("{ring}auto: {e}")
            })
        }
    }
}

/// A quantity of the reference and its relative error bound.
fn reference_of(s: &Solution, quantity: Quantity) -> Option<(f64, f64)> {
    let estimate = s.error_estimate?;
    let value = match quantity {
        Quantity::Eps => s.eps,
        Quantity::Depth => s.depth,
        Quantity::Force => s.force,
        Quantity::Gamma => s.gamma?,
        Quantity::Gamma1 => s.gamma1?,
        Quantity::Gamma2 => s.gamma2?,
    };
    // The estimate bounds eps absolutely and the rest relatively (`Solution::error_estimate`).
    let bound = match quantity {
        Quantity::Eps if s.eps > 0.0 => estimate / s.eps,
        _ => estimate,
    };
    Some((value, bound))
}

/// Largest and RMS relative error per punch and quantity, in order of appearance.
fn summarise(graded: &[GradedValue]) -> Vec<Summary> {
    let mut out: Vec<Summary> = Vec::new();
    let mut squares: Vec<f64> = Vec::new();
    for g in graded {
        let k = match out
            .iter()
            .position(|s| s.punch == g.punch && s.quantity == g.quantity)
        {
            Some(k) => k,
            None => {
                out.push(Summary {
                    punch: g.punch.clone(),
                    quantity: g.quantity,
                    count: 0,
                    max_relative_error: 0.0,
                    rms_relative_error: 0.0,
                    within: 0,
                });
                squares.push(0.0);
                out.len() - 1
            }
        };
        out[k].count += 1;
        out[k].max_relative_error = out[k].max_relative_error.max(g.relative_error);
        out[k].within += usize::from(g.within);
        squares[k] += g.relative_error * g.relative_error;
    }
    for (s, sq) in out.iter_mut().zip(squares) {
        s.rms_relative_error = (sq / s.count as f64).sqrt();
    }
    out
}

/// The chart's axis label for the states of `rows`.
fn state_label(rows: &[GradedValue]) -> String {
    let mut states: Vec<&str> = rows.iter().map(|g| g.state.as_str()).collect();
    states.sort_unstable();
    states.dedup();
    match states.as_slice() {
        ["eps"] => "contact ratio b/a".into(),
        ["depth"] => "depth d".into(),
        ["force"] => "force F".into(),
        _ => format!("state ({})", states.join(", ")),
    }
}

/// A chart of the relative error against the state, one series per punch and quantity, and
/// the tolerance (log-log: exact agreements, which a log axis cannot show, are left out).
pub fn chart(grading: &Grading, title: &str) -> String {
    use crate::harness::report::svg::{log_log_chart, Series};
    let mut series: Vec<Series> = Vec::new();
    for s in &grading.summary {
        let points: Vec<(f64, f64)> = grading
            .rows
            .iter()
            .filter(|g| g.punch == s.punch && g.quantity == s.quantity)
            .filter(|g| g.relative_error > 0.0 && g.state_value > 0.0)
            .map(|g| (g.state_value, g.relative_error))
            .collect();
        series.push(Series {
            name: format!("{} {}", s.punch, s.quantity.key()),
            bars: vec![None; points.len()],
            points,
        });
    }
    series.push(Series {
        name: format!("tolerance {:.0e}", grading.tolerance),
        points: state_range(grading)
            .map(|(lo, hi)| vec![(lo, grading.tolerance), (hi, grading.tolerance)])
            .unwrap_or_default(),
        bars: vec![None, None],
    });
    log_log_chart(
        title,
        &state_label(&grading.rows),
        "relative error |value - reference| / |reference|",
        &series,
    )
}

/// The smallest and largest positive state value.
fn state_range(grading: &Grading) -> Option<(f64, f64)> {
    let values = grading
        .rows
        .iter()
        .map(|g| g.state_value)
        .filter(|v| *v > 0.0);
    let lo = values.clone().fold(f64::INFINITY, f64::min);
    let hi = values.fold(0.0, f64::max);
    (lo.is_finite() && hi > 0.0).then_some((lo, hi))
}

/// The stored peer results (`verify/peers/*.json`: the force a peer found at a given depth) as
/// rows to grade. A free band's records are in units of its `h` (its tube radius `a/2`). A
/// record is read by a built-in punch's name, so each has one.
pub fn peer_rows(records: &[(String, PeerResult)]) -> Vec<ResultRow> {
    records
        .iter()
        .filter_map(|(file, r)| Some((file, r, r.punch.shape_name()?)))
        .map(|(file, r, punch)| ResultRow {
            place: file.clone(),
            punch,
            exponent: r.punch.exponent(),
            tube_radius: r.punch.is_free_band().then_some(0.5),
            profile: r.punch.record().profile_file.map(Into::into),
            hole_ratio: r.punch.has_fixed_hole().then_some(r.eps).flatten(),
            state: Some((Quantity::Depth, r.depth)),
            values: vec![(Quantity::Force, r.force)],
            effective_modulus: None,
            rim_radius: None,
            hole_depth: None,
            claimed_error: None,
        })
        .collect()
}

/// The graded values as a table (the terminal output of `verify grade` and the report's).
pub fn rows_table(g: &Grading, title: &str) -> Table {
    let mut rows = Table::new(
        title,
        vec![
            Column::text("place", "where"),
            Column::text("punch", "punch"),
            Column::text("state", "state"),
            Column::text("quantity", "quantity"),
            Column::number("value", "value", Format::Scientific(9)),
            Column::number("reference", "reference", Format::Scientific(9)),
            Column::number("reference_error", "ref. bound", Format::Scientific(1)),
            Column::number("relative_error", "rel. error", Format::Scientific(2)),
            Column::text("within", "within T"),
            Column::text("claim", "own estimate"),
        ],
    );
    for r in &g.rows {
        rows.push(vec![
            r.place.clone().into(),
            r.punch.clone().into(),
            format!("{} = {}", r.state, readable(r.state_value, 6)).into(),
            r.quantity.key().into(),
            r.value.into(),
            r.reference.into(),
            r.reference_error.into(),
            r.relative_error.into(),
            if r.resolved {
                verdict(r.within, "beyond")
            } else {
                Cell::Text("yes (not resolved)".into())
            },
            match (r.claimed_error, r.claim_holds) {
                (Some(c), Some(true)) => format!("{c:.1e} holds").into(),
                (Some(c), _) => Cell::Flag(format!("{c:.1e} broken")),
                _ => Cell::Missing,
            },
        ]);
    }
    rows
}

/// The largest and RMS error per punch and quantity as a table.
pub fn summary_table(g: &Grading) -> Table {
    let mut summary = Table::new(
        "Per punch and quantity",
        vec![
            Column::text("punch", "punch"),
            Column::text("quantity", "quantity"),
            Column::number("count", "values", Format::Fixed(0)),
            Column::number("within", "within T", Format::Fixed(0)),
            Column::number("max", "largest rel. error", Format::Scientific(2)),
            Column::number("rms", "RMS rel. error", Format::Scientific(2)),
        ],
    );
    for s in &g.summary {
        summary.push(vec![
            s.punch.clone().into(),
            s.quantity.key().into(),
            (s.count as f64).into(),
            (s.within as f64).into(),
            s.max_relative_error.into(),
            s.rms_relative_error.into(),
        ]);
    }
    summary
}

/// One sentence: how many values, how many beyond, the largest error, the unresolved and the
/// broken claims.
pub fn verdict_sentence(g: &Grading) -> String {
    let mut text = format!(
        "{} values graded at T = {:.1e}: {} beyond, largest relative error {:.2e}",
        g.rows.len(),
        g.tolerance,
        g.beyond,
        g.max_relative_error
    );
    if g.unresolved > 0 {
        text.push_str(&format!(
            "; {} closer to the reference than {RESOLUTION} times its error bound (agree to the \
             reference's accuracy, the difference not resolved)",
            g.unresolved
        ));
    }
    if g.rows.iter().any(|r| r.claimed_error.is_some()) {
        text.push_str(&format!(
            "; {} values beyond the error their results claim",
            g.claims_broken
        ));
    }
    text
}

/// The stored peer results (`verify/peers/`) graded at [`PEER_TOLERANCE`]; `None` when none
/// are stored.
pub fn grade_stored_peers() -> ringcontact::error::Result<Option<Grading>> {
    let records = crate::harness::records::peers::load_results()?;
    if records.is_empty() {
        return Ok(None);
    }
    grade(&peer_rows(&records), PEER_TOLERANCE, &|_, _| {})
        .map(Some)
        .map_err(|e| Error::File {
            action: "grade the stored peer results".into(),
            path: crate::harness::records::peers::results_directory()
                .display()
                .to_string(),
            message: e,
        })
}

/// File of the report's chart of the graded peer results.
pub const PEER_CHART: &str = "grade-peers.svg";
