//! `verify adhesion --sweep`: the Maugis-Dugdale pull-off against the Tabor parameter under both
//! controls, beside the JKR limit; a table, a CSV and a chart.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use rayon::prelude::*;

use serde::Serialize;

use crate::harness::report::svg;
use crate::harness::report::table::{Cell, Column, Format, Table};
use ringcontact::dugdale::{Control, DugdaleLaw, DugdaleSolver, FaceParameters};
use ringcontact::error::{Error, Result};
use ringcontact::punch::PunchKind;

/// Tabor parameters of the sweep: 40 points, evenly spaced in `ln λ` from 0.05 to 100.
pub(crate) fn tabor_parameters() -> Vec<f64> {
    let (lo, hi) = (0.05f64.ln(), 100f64.ln());
    (0..40)
        .map(|k| (lo + (hi - lo) * k as f64 / 39.0).exp())
        .collect()
}

/// One Tabor parameter's pull-off under one control, or why it has none.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct SweepPoint {
    pub tabor: f64,
    pub control: Control,
    /// `F/F0` (negative: tensile).
    pub pulloff_force: Option<f64>,
    pub pulloff_force_error: Option<f64>,
    pub pulloff_depth: Option<f64>,
    /// The edge that lets go (`inner`, `outer`, `both`).
    pub detaching_edge: Option<&'static str>,
    /// The reason a state was declined.
    pub declined: Option<String>,
}

impl SweepPoint {
    /// A Tabor parameter the solver declined, with its reason.
    fn declined(tabor: f64, control: Control, reason: String) -> Self {
        Self {
            tabor,
            control,
            pulloff_force: None,
            pulloff_force_error: None,
            pulloff_depth: None,
            detaching_edge: None,
            declined: Some(reason),
        }
    }
}

/// The sweep's rows, table and files.
pub(crate) struct DugdaleSweep {
    pub rows: Vec<SweepPoint>,
    pub table: Table,
    pub files: Vec<PathBuf>,
}

/// The JKR limit's pull-off `F/F0` under fixed load and fixed grips (in [`Control::ALL`]'s
/// order; `None` where `verify jkr` has none).
pub(crate) type JkrForces = [Option<f64>; 2];

/// Sweep `kind` (with its `parameters`) over [`tabor_parameters`] under both controls to
/// `tolerance`; write `dugdale-LABEL[-EPS|-d0hS].{csv,svg}` into `out`, the JKR limit
/// `jkr_force` drawn beside. `progress` is called after each Tabor parameter.
pub(crate) fn sweep(
    solver: &DugdaleSolver,
    kind: &PunchKind,
    parameters: FaceParameters,
    tolerance: f64,
    jkr_force: JkrForces,
    out: &Path,
    progress: impl FnMut(&str) + Send,
) -> Result<DugdaleSweep> {
    // The Tabor parameters are independent: solved in parallel, kept in their order.
    let progress = Mutex::new(progress);
    let per_tabor: Vec<Vec<SweepPoint>> = tabor_parameters()
        .into_par_iter()
        .map(|tabor| {
            let points = both_controls(solver, kind, parameters, tabor, tolerance)?;
            if let Ok(mut progress) = progress.lock() {
                progress(&format!("lambda = {tabor:.3}"));
            }
            Ok(points)
        })
        .collect::<Result<_>>()?;
    let rows: Vec<SweepPoint> = per_tabor.into_iter().flatten().collect();
    let table = table(kind, jkr_force, &rows);
    let chart = chart(kind, jkr_force, &rows);
    std::fs::create_dir_all(out).map_err(|e| Error::file("create the directory", out, e))?;
    let [csv, svg] = file_names(out, kind, parameters);
    let mut files = Vec::new();
    for (path, text) in [(csv, table.to_csv()?), (svg, chart)] {
        std::fs::write(&path, text).map_err(|e| Error::file("write", &path, e))?;
        files.push(path);
    }
    Ok(DugdaleSweep { rows, table, files })
}

/// The sweep's CSV and SVG files in `out`: `dugdale-LABEL[-EPS|-d0hS].{csv,svg}` (the
/// extension appended: `EPS` and `S` may have a dot of their own).
fn file_names(out: &Path, kind: &PunchKind, parameters: FaceParameters) -> [PathBuf; 2] {
    let stem = match parameters {
        FaceParameters { eps: Some(eps), .. } => format!("dugdale-{}-{eps}", kind.label()),
        FaceParameters {
            d0_over_h: Some(s), ..
        } => format!("dugdale-{}-d0h{s}", kind.label()),
        _ => format!("dugdale-{}", kind.label()),
    };
    ["csv", "svg"].map(|extension| out.join(format!("{stem}.{extension}")))
}

/// The pull-off at one Tabor parameter under each control, or why it has none.
fn both_controls(
    solver: &DugdaleSolver,
    kind: &PunchKind,
    parameters: FaceParameters,
    tabor: f64,
    tolerance: f64,
) -> Result<Vec<SweepPoint>> {
    let law = DugdaleLaw::new(tabor)?;
    Control::ALL
        .into_iter()
        .map(
            |control| match solver.pulloff(kind, parameters, law, control, tolerance) {
                Ok(p) => Ok(SweepPoint {
                    tabor,
                    control,
                    pulloff_force: Some(p.pulloff_force),
                    pulloff_force_error: Some(p.pulloff_force_error),
                    pulloff_depth: Some(p.pulloff_depth),
                    detaching_edge: Some(p.detaching_edge.name()),
                    declined: None,
                }),
                Err(e @ (Error::NoConvergence { .. } | Error::OutOfRange { .. })) => {
                    Ok(SweepPoint::declined(tabor, control, e.to_string()))
                }
                Err(e) => Err(e),
            },
        )
        .collect()
}

/// The sweep's rows as a table (terminal and CSV).
fn table(kind: &PunchKind, jkr_force: JkrForces, rows: &[SweepPoint]) -> Table {
    let [load, grips] = jkr_force.map(|f| f.map_or("none".into(), |f| format!("{f:.6}")));
    let mut table = Table::new(
        &format!(
            "{}: Maugis-Dugdale pull-off F/F0 against the Tabor parameter (JKR limit {load} \
             fixed load, {grips} fixed grips; F0 = sqrt(8 pi E* dw a^3), \
             d0 = sqrt(2 pi a dw / E*))",
            kind.describe()
        ),
        vec![
            Column::number("tabor", "lambda", Format::Scientific(3)),
            Column::text("control", "control"),
            Column::number("pulloff_force", "F/F0", Format::Fixed(8)),
            Column::number("pulloff_force_error", "error bound", Format::Scientific(1)),
            Column::number("pulloff_depth", "d/d0", Format::Fixed(8)),
            Column::text("detaching_edge", "edge"),
            Column::text("declined", "declined"),
        ],
    );
    for r in rows {
        table.push(vec![
            r.tabor.into(),
            r.control.name().into(),
            r.pulloff_force.into(),
            r.pulloff_force_error.into(),
            r.pulloff_depth.into(),
            Cell::from(r.detaching_edge.unwrap_or_default()),
            Cell::from(r.declined.clone().unwrap_or_default()),
        ]);
    }
    table
}

/// The chart of the tensile pull-off against `log10 λ`, one curve per control, the JKR limit
/// beside: the force on a linear axis, as a punch that comes away gradually has none.
fn chart(kind: &PunchKind, jkr_force: JkrForces, rows: &[SweepPoint]) -> String {
    let curve = |control: Control| svg::Series {
        name: format!("fixed {}", control.name()),
        points: rows
            .iter()
            .filter(|r| r.control == control)
            .filter_map(|r| r.pulloff_force.map(|f| (r.tabor.log10(), -f)))
            .collect(),
        bars: Vec::new(),
    };
    let parameters = tabor_parameters();
    let (lo, hi) = (parameters[0].log10(), parameters[39].log10());
    let jkr_line = |name: &str, force: f64| svg::Series {
        name: name.into(),
        points: vec![(lo, -force), (hi, -force)],
        bars: Vec::new(),
    };
    let mut series = vec![curve(Control::Load), curve(Control::Grips)];
    match jkr_force {
        [Some(load), Some(grips)] if load == grips => series.push(jkr_line("JKR limit", load)),
        [load, grips] => {
            series.extend(load.map(|f| jkr_line("JKR limit, fixed load", f)));
            series.extend(grips.map(|f| jkr_line("JKR limit, fixed grips", f)));
        }
    }
    svg::linear_chart_with_markers(
        &format!(
            "{}: Dugdale pull-off against the Tabor parameter",
            kind.describe()
        ),
        "log10 of the Tabor parameter lambda",
        "-F_pulloff / F0",
        &series,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use ringcontact::punch::Contact;

    /// Sweeps of one punch at different `b/a` or `d0/h` write different files (a dot in the
    /// value once cut the name at it: `b/a` = 0.5 and 0.9 both wrote `...-0.csv`).
    #[test]
    fn each_face_parameter_has_its_own_files() {
        let out = Path::new("out");
        let names = |contact, eps, d0_over_h| {
            let kind = PunchKind::built_in(contact).remove(0);
            let files = file_names(out, &kind, FaceParameters { eps, d0_over_h })
                .map(|p| p.file_name().unwrap().to_string_lossy().into_owned());
            (kind.label().to_string(), files)
        };
        let (label, files) = names(Contact::FixedAnnulus, Some(0.5), None);
        assert_eq!(
            files,
            [
                format!("dugdale-{label}-0.5.csv"),
                format!("dugdale-{label}-0.5.svg")
            ]
        );
        assert_ne!(files, names(Contact::FixedAnnulus, Some(0.9), None).1);
        let (label, files) = names(Contact::RimAndFreeInner, None, Some(0.1));
        assert_eq!(
            files,
            [
                format!("dugdale-{label}-d0h0.1.csv"),
                format!("dugdale-{label}-d0h0.1.svg")
            ]
        );
    }
}
