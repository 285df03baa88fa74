//! The stored pull-off simulations (`verify/pulloff/*.json`, written by
//! `scripts/pulloff/run_all.py --out verify/pulloff`; the nightly run writes fresh ones into its report): each holds the result of
//! `verify pulloff --json` (or the reason it declined), its date and its command. They are too
//! slow for the default run (12-60 s each), so the report shows the stored ones.

use serde::{Deserialize, Serialize};

use crate::harness::report::table::{verdict, Cell, Column, Format, Table};
use ringcontact::cohesive::study::PulloffStudy;
use ringcontact::error::{Error, Result};

/// One stored simulation.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PulloffRecord {
    #[serde(default)]
    pub file: String,
    pub date: String,
    pub command: String,
    #[serde(default)]
    pub result: Option<PulloffStudy>,
    /// Why the simulation declined the case, if it did.
    #[serde(default)]
    pub declined: Option<String>,
}

/// Sort key of a record's file: the name up to its trailing number, then that number
/// (`punch-d0h3` before `punch-d0h10`).
fn natural_key(name: &str) -> (String, f64) {
    let stem = name.trim_end_matches(".json");
    let split = stem
        .rfind(|c: char| !(c.is_ascii_digit() || c == '.'))
        .map_or(0, |i| i + 1);
    let value = stem[split..].parse::<f64>().unwrap_or(0.0);
    (stem[..split].to_string(), value)
}

/// Every stored record, in the natural order of the file names (none when the directory is
/// absent).
pub fn load() -> Result<Vec<PulloffRecord>> {
    let dir = crate::harness::settings::project_root().join("verify/pulloff");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Ok(Vec::new());
    };
    let mut files: Vec<_> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort_by(|a, b| {
        let key = |p: &std::path::PathBuf| {
            natural_key(
                &p.file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default(),
            )
        };
        let (ka, kb) = (key(a), key(b));
        ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
    });
    files
        .iter()
        .map(|path| {
            let text = std::fs::read_to_string(path).map_err(|e| Error::file("read", path, e))?;
            let mut record: PulloffRecord =
                serde_json::from_str(&text).map_err(|e| Error::File {
                    action: "parse".into(),
                    path: path.display().to_string(),
                    message: e.to_string(),
                })?;
            record.file = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            Ok(record)
        })
        .collect()
}

/// A Tabor number for a table: whole where it is (9, 18, 36), else to one decimal (4.5, 6.4).
fn tabor_label(tabor: f64) -> String {
    if (tabor - tabor.round()).abs() < 0.05 {
        format!("{tabor:.0}")
    } else {
        format!("{tabor:.1}")
    }
}

/// A row of [`table`] with no simulation result: the case, the date and the verdict cell.
pub(crate) fn row_without_result(case: String, date: &str, verdict: Cell) -> Vec<Cell> {
    let mut row = vec![case.into()];
    row.extend(std::iter::repeat_n(Cell::Missing, 7));
    row.push(date.into());
    row.push(verdict);
    row
}

/// The records as a table: the sequence, the extrapolate, the JKR route and the paper's route.
pub fn table(records: &[PulloffRecord]) -> Table {
    let mut t = Table::new(
        "Pull-off by direct simulation (stored; cohesive zone on the FE model)",
        vec![
            Column::text("case", "case"),
            Column::text("sequence", "F/F0 at Tabor (λ: F/F0)"),
            Column::text("left_out", "left out (another branch)"),
            Column::number("extrapolated_over_f0", "extrapolate", Format::Fixed(4)),
            Column::number("error_bar", "error bar", Format::Scientific(1)),
            Column::number("jkr_over_f0", "JKR route", Format::Fixed(4)),
            Column::number("paper_route_over_f0", "paper's route", Format::Fixed(4)),
            Column::number("wall_s", "time (one run)", Format::Fixed(1)).with_unit("s"),
            Column::text("date", "date"),
            Column::text("verdict", "verdict"),
        ],
    );
    for r in records {
        let case = r.file.trim_end_matches(".json").to_string();
        match &r.result {
            Some(s) => {
                let sequence: Vec<String> = s
                    .sequence
                    .iter()
                    .map(|e| format!("{}: {:.4}", tabor_label(e.tabor), e.pulloff_over_f0))
                    .collect();
                let left_out: Vec<String> = s
                    .excluded
                    .iter()
                    .map(|x| {
                        let how = match x.entry.hole_reopened_at {
                            None if x.entry.hole_closed_at.is_some() => {
                                let (d, f) = x.entry.hole_closed_at.unwrap_or_default();
                                format!("hole closed at F/F0 = {f:.2}, d/d0 = {d:.2}")
                            }
                            Some((d, f)) => {
                                format!("hole reopened at F/F0 = {f:.2}, d/d0 = {d:.2}")
                            }
                            None if x.entry.hole_closed_at_preload == Some(false) => {
                                "hole open at the deepest preload".to_string()
                            }
                            None => format!(
                                "branch ended at F/F0 = {:.2}, landing not found",
                                -x.entry.pulloff_over_f0
                            ),
                        };
                        format!("λ {}: {how}", tabor_label(x.entry.tabor))
                    })
                    .collect();
                t.push(vec![
                    case.into(),
                    sequence.join(", ").into(),
                    if left_out.is_empty() {
                        "-".to_string()
                    } else {
                        left_out.join("; ")
                    }
                    .into(),
                    s.extrapolated_over_f0.into(),
                    s.error_bar.into(),
                    s.jkr_reference().into(),
                    s.paper_route_over_f0.into(),
                    s.wall_s.into(),
                    r.date.clone().into(),
                    match s.agrees_with_jkr() {
                        Some(ok) => verdict(ok, "OUTSIDE THE ERROR BAR"),
                        None => Cell::Missing,
                    },
                ]);
            }
            None => t.push(row_without_result(
                case,
                &r.date,
                match r.declined.as_deref() {
                    Some(reason) if reason.contains("hole is open") => {
                        "declined: the hole is open (its moving edge is not resolved)".into()
                    }
                    Some(reason) => format!("declined: {reason}").into(),
                    None => "no result".into(),
                },
            )),
        }
    }
    t
}

/// The first stored record with a simulation that left the closed hole's branch and its
/// curves (the one the report charts), if any.
pub(crate) fn with_branches(records: &[PulloffRecord]) -> Option<&PulloffRecord> {
    records.iter().find(|r| {
        r.result.as_ref().is_some_and(|s| {
            s.branch != Some(ringcontact::cohesive::study::Branch::Annular)
                && s.curves.iter().any(|c| c.left_the_branch)
        })
    })
}

/// The stored simulations of a concave punch's annular branch (`--branch annular`) with a
/// result (a free band, touched and pulled as well, has no hole: it is not among them).
pub fn annular(records: &[PulloffRecord]) -> Vec<PulloffRecord> {
    records
        .iter()
        .filter(|r| {
            r.result.as_ref().is_some_and(|s| {
                s.branch == Some(ringcontact::cohesive::study::Branch::Annular) && s.punch.has_rim()
            })
        })
        .cloned()
        .collect()
}

/// Where a stored simulation left the closed hole's branch: one row per left-out range (case,
/// Tabor, what happened, where), beside the pull-off the smallest range reached on the branch.
pub(crate) fn branches_table(records: &[PulloffRecord]) -> Table {
    let mut t = Table::new(
        "Where the closed hole's branch ended early (stored simulations)",
        vec![
            Column::text("case", "case"),
            Column::number("tabor", "Tabor", Format::Fixed(0)),
            Column::text("what", "what happened"),
            Column::number("depth_over_d0", "at d/d0", Format::Fixed(3)),
            Column::number("force_over_f0", "F/F0 there", Format::Fixed(3)),
            Column::number("pressed_to_over_d0", "pressed to d/d0", Format::Fixed(2)),
            Column::number(
                "on_branch_over_f0",
                "pull-off on the branch",
                Format::Fixed(4),
            ),
        ],
    );
    for r in records {
        let Some(s) = &r.result else { continue };
        if s.branch == Some(ringcontact::cohesive::study::Branch::Annular) {
            continue;
        }
        let on_branch = s.sequence.last().map(|e| e.pulloff_over_f0);
        for x in &s.excluded {
            let e = &x.entry;
            let (what, at) = match e.hole_reopened_at {
                Some(at) => ("the hole reopened on the way out", at),
                None if e.hole_closed_at_preload == Some(false) => (
                    "the hole stayed open at the deepest preload",
                    (f64::NAN, f64::NAN),
                ),
                None => (
                    "the branch ended; no landing state found",
                    (e.pulloff_depth_over_d0, -e.pulloff_over_f0),
                ),
            };
            t.push(vec![
                r.file.trim_end_matches(".json").to_string().into(),
                e.tabor.into(),
                what.into(),
                at.0.into(),
                at.1.into(),
                e.preload_over_d0.into(),
                on_branch.into(),
            ]);
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::natural_key;

    #[test]
    fn files_sort_by_their_trailing_number() {
        assert_eq!(
            natural_key("punch-d0h10.json"),
            ("punch-d0h".to_string(), 10.0)
        );
        assert_eq!(
            natural_key("punch-d0h0.3.json"),
            ("punch-d0h".to_string(), 0.3)
        );
        assert_eq!(natural_key("flat.json"), ("flat".to_string(), 0.0));
        assert_eq!(natural_key("ring-0.9.json"), ("ring-".to_string(), 0.9));
    }
}
