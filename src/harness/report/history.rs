//! Nightly history: headline figures of a report appended to a JSON-lines file and compared with
//! the previous run. An accuracy worse than its tolerance or a time more than 1.5x the previous
//! run's is a regression.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::harness::report::table::{Cell, Column, Format, Table};
use ringcontact::error::{Error, Result};

/// Time ratio over the previous run that counts as a regression.
pub(crate) const SLOWDOWN: f64 = 1.5;
/// Times shorter than this are not compared (timer noise).
pub(crate) const MIN_TIME: f64 = 0.02;

/// Headline figures of one run.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Headline {
    pub date: String,
    pub failures: usize,
    pub stability_wrong_numbers: usize,
    /// Accuracy figures with their tolerances: name -> (value, tolerance).
    pub accuracy: BTreeMap<String, (f64, f64)>,
    /// Wall times in seconds: name -> time.
    pub times: BTreeMap<String, f64>,
    /// `fresh` or `stored` for the external codes.
    pub fenicsx: String,
    pub peers: String,
}

fn get<'a>(v: &'a serde_json::Value, path: &[&str]) -> Option<&'a serde_json::Value> {
    path.iter().try_fold(v, |acc, k| acc.get(*k))
}

/// Headline figures from a report directory (`report.json`, optional `stability.json`).
pub fn headline(dir: &Path, date: &str, fenicsx: &str, peers: &str) -> Result<Headline> {
    let path = dir.join("report.json");
    let report = read_json(&path)?;
    check_report_sections(&report, &path)?;
    let accuracy = accuracy_figures(&report);
    let failures = failure_count(&report);
    let times = timing_figures(&report);
    let stability_wrong_numbers = stability_wrong_numbers(dir)?;
    Ok(Headline {
        date: date.into(),
        failures,
        stability_wrong_numbers,
        accuracy,
        times,
        fenicsx: fenicsx.into(),
        peers: peers.into(),
    })
}

/// A JSON file, read and parsed.
fn read_json(path: &Path) -> Result<serde_json::Value> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::file("read", path, e))?;
    serde_json::from_str(&text).map_err(|e| Error::file("parse the report", path, e))
}

/// A report of `verify compare` has these sections; anything else (`{}`, another JSON file) is
/// an error, never "no failures".
fn check_report_sections(report: &serde_json::Value, path: &Path) -> Result<()> {
    for section in [
        &["comparison", "rows"][..],
        &["comparison", "fem"],
        &["comparison", "identities"],
        &["fenicsx"],
        &["peers"],
    ] {
        if !get(report, section).is_some_and(|v| v.is_array()) {
            return Err(Error::file(
                "take the headline figures of",
                path,
                format!(
                    "it has no `{}` list: not a report written by `verify compare`",
                    section.join(".")
                ),
            ));
        }
    }
    Ok(())
}

/// The worst relative differences (FEM against the ring BEM, FEniCSx against the FEM, peers
/// against the grid BEM) and identity residuals, each with its tolerance.
fn accuracy_figures(report: &serde_json::Value) -> BTreeMap<String, (f64, f64)> {
    let max_abs = |items: Option<&serde_json::Value>, key: &str| -> f64 {
        items.and_then(|v| v.as_array()).map_or(0.0, |a| {
            a.iter()
                .filter_map(|x| x.get(key).and_then(|d| d.as_f64()))
                .map(f64::abs)
                .fold(0.0, f64::max)
        })
    };
    let mut accuracy = BTreeMap::new();
    accuracy.insert(
        "fem_vs_ring_bem".into(),
        (
            max_abs(get(report, &["comparison", "fem"]), "relative_difference"),
            1e-3,
        ),
    );
    accuracy.insert(
        "fem_vs_ring_bem_eps".into(),
        (
            max_abs(get(report, &["comparison", "fem"]), "eps_difference"),
            1e-3,
        ),
    );
    accuracy.insert(
        "fenicsx_vs_fem".into(),
        (max_abs(report.get("fenicsx"), "relative_difference"), 1e-8),
    );
    accuracy.insert(
        "peers_vs_grid_bem".into(),
        (max_abs(report.get("peers"), "relative_difference"), 1e-6),
    );
    let identities = get(report, &["comparison", "identities"])
        .and_then(|v| v.as_array())
        .cloned()
        .unwrap_or_default();
    let worst_identity = identities
        .iter()
        .filter_map(|i| Some(i.get("relative_residual")?.as_f64()? / i.get("tolerance")?.as_f64()?))
        .fold(0.0, f64::max);
    accuracy.insert(
        "identities_residual_over_tolerance".into(),
        (worst_identity, 1.0),
    );
    accuracy
}

/// Failed checks: the report's own count (error bars and fresh baselines included) where it
/// has one, else the failed comparisons, identities, FEM checks, FEniCSx and peer results.
fn failure_count(report: &serde_json::Value) -> usize {
    let identities = get(report, &["comparison", "identities"])
        .and_then(|v| v.as_array())
        .cloned()
        .unwrap_or_default();
    let failures = [
        get(report, &["comparison", "rows"])
            .and_then(|v| v.as_array())
            .map_or(0, |rows| {
                rows.iter()
                    .flat_map(|r| {
                        r.get("comparisons")
                            .and_then(|c| c.as_array())
                            .cloned()
                            .unwrap_or_default()
                    })
                    .filter(|c| c.get("agrees") == Some(&serde_json::Value::Bool(false)))
                    .count()
            }),
        identities
            .iter()
            .filter(|i| i.get("passed") == Some(&serde_json::Value::Bool(false)))
            .count(),
        get(report, &["comparison", "fem"])
            .and_then(|v| v.as_array())
            .map_or(0, |a| {
                a.iter()
                    .filter(|c| c.get("agrees") == Some(&serde_json::Value::Bool(false)))
                    .count()
            }),
        report
            .get("fenicsx")
            .and_then(|v| v.as_array())
            .map_or(0, |a| {
                a.iter()
                    .filter(|c| {
                        c.get("status").and_then(|s| s.as_str()) == Some("current")
                            && c.get("passed") == Some(&serde_json::Value::Bool(false))
                    })
                    .count()
            }),
        report
            .get("peers")
            .and_then(|v| v.as_array())
            .map_or(0, |a| {
                a.iter()
                    .filter(|c| c.get("passed") == Some(&serde_json::Value::Bool(false)))
                    .count()
            }),
    ]
    .iter()
    .sum::<usize>();
    // The report's own count (error bars and fresh baselines included) where it has one.
    let failures = get(report, &["extras", "headline", "failed"])
        .and_then(|v| v.as_u64())
        .map_or(failures, |n| n as usize);
    failures
}

/// Wall time of each speed-accuracy point and of the report's extras, seconds.
fn timing_figures(report: &serde_json::Value) -> BTreeMap<String, f64> {
    let mut times = BTreeMap::new();
    if let Some(problems) = get(report, &["extras", "speed_accuracy"]).and_then(|v| v.as_array()) {
        for (k, problem) in problems.iter().enumerate() {
            for p in problem
                .get("points")
                .and_then(|v| v.as_array())
                .cloned()
                .unwrap_or_default()
            {
                let name = format!(
                    "problem{k} {} {}",
                    p.get("method").and_then(|v| v.as_str()).unwrap_or("?"),
                    p.get("resolution").and_then(|v| v.as_str()).unwrap_or("?")
                );
                if let Some(t) = p.get("wall_s").and_then(|v| v.as_f64()) {
                    times.insert(name, t);
                }
            }
        }
    }
    if let Some(t) = get(report, &["extras", "wall_s"]).and_then(|v| v.as_f64()) {
        times.insert("report extras total".into(), t);
    }
    times
}

/// Wrong numbers among the stability probes: `stability.json` is optional (a run without
/// `verify stability`); if present it must be the probe list that command writes, every probe
/// with an outcome.
fn stability_wrong_numbers(dir: &Path) -> Result<usize> {
    let path = dir.join("stability.json");
    if !path.exists() {
        return Ok(0);
    }
    let probes = read_json(&path)?;
    let outcomes: Option<Vec<&str>> = probes.as_array().and_then(|a| {
        a.iter()
            .map(|p| p.get("outcome").and_then(|o| o.as_str()))
            .collect()
    });
    match outcomes {
        Some(list) if !list.is_empty() => Ok(list.iter().filter(|&&o| o == "WRONG").count()),
        _ => Err(Error::file(
            "count the wrong numbers of",
            &path,
            "not a list of probes with an `outcome` each (as `verify stability --json` writes)",
        )),
    }
}

/// Regressions of `current` (against its tolerances and against `previous`'s times).
pub(crate) fn regressions(current: &Headline, previous: Option<&Headline>) -> Vec<String> {
    let mut out = Vec::new();
    if current.failures > 0 {
        out.push(format!("{} checks failed", current.failures));
    }
    if current.stability_wrong_numbers > 0 {
        out.push(format!(
            "{} wrong numbers without an error (verify stability)",
            current.stability_wrong_numbers
        ));
    }
    for (name, (value, tolerance)) in &current.accuracy {
        if value > tolerance {
            out.push(format!(
                "accuracy {name}: {value:.2e} exceeds its tolerance {tolerance:.0e}"
            ));
        }
    }
    if let Some(prev) = previous {
        for (name, t) in &current.times {
            if let Some(&p) = prev.times.get(name) {
                if p >= MIN_TIME && *t > SLOWDOWN * p {
                    out.push(format!(
                        "time {name}: {t:.3} s, {:.2}x the previous run's {p:.3} s",
                        t / p
                    ));
                }
            }
        }
    }
    out
}

/// Append `current` to the history file and return the previous entry.
pub fn append(history: &Path, current: &Headline) -> Result<Option<Headline>> {
    let previous = read_history(history)?.pop();
    let line = serde_json::to_string(current)
        .map_err(|e| Error::file("serialise a record for", history, e))?;
    if let Some(parent) = history.parent() {
        let _ = std::fs::create_dir_all(parent);
    }
    use std::io::Write;
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(history)
        .map_err(|e| Error::file("open for appending", history, e))?;
    writeln!(file, "{line}").map_err(|e| Error::file("append to", history, e))?;
    Ok(previous)
}

/// Every record of a history file (none if it does not exist yet). A line that is not a record
/// (a truncated write, an edit) is an error naming the line: it is never skipped.
pub(crate) fn read_history(history: &Path) -> Result<Vec<Headline>> {
    let text = match std::fs::read_to_string(history) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(Error::file("read", history, e)),
    };
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            serde_json::from_str(l).map_err(|e| {
                Error::file(
                    "read the history",
                    history,
                    format!("line {} is not a record ({e}): truncated or edited?", i + 1),
                )
            })
        })
        .collect()
}

/// Trend of the last runs as a Markdown table.
pub fn trend(history: &Path, last: usize) -> Result<String> {
    Ok(format!(
        "# Trend\n\n{}",
        trend_table(&read_history(history)?, last).to_markdown_table()
    ))
}

/// The last `last` runs: failures, wrong numbers, the headline accuracies and the time of the
/// report's extras.
pub(crate) fn trend_table(runs: &[Headline], last: usize) -> Table {
    let mut t = Table::new(
        "Trend",
        vec![
            Column::text("date", "date"),
            Column::number("failures", "failures", Format::Fixed(0)),
            Column::number("wrong_numbers", "wrong numbers", Format::Fixed(0)),
            Column::number("fem_vs_ring_bem", "FEM vs ring BEM", Format::Scientific(1)),
            Column::number("fenicsx_vs_fem", "FEniCSx vs FEM", Format::Scientific(1)),
            Column::number(
                "peers_vs_grid_bem",
                "peers vs grid BEM",
                Format::Scientific(1),
            ),
            Column::number("extras_s", "extras", Format::Fixed(1)).with_unit("s"),
            Column::text("fenicsx", "FEniCSx"),
            Column::text("peers", "peers"),
        ],
    );
    for r in runs.iter().rev().take(last).rev() {
        let accuracy = |k: &str| Cell::from(r.accuracy.get(k).map(|v| v.0));
        t.push(vec![
            r.date.clone().into(),
            (r.failures as f64).into(),
            (r.stability_wrong_numbers as f64).into(),
            accuracy("fem_vs_ring_bem"),
            accuracy("fenicsx_vs_fem"),
            accuracy("peers_vs_grid_bem"),
            r.times.get("report extras total").copied().into(),
            r.fenicsx.clone().into(),
            r.peers.clone().into(),
        ]);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(time: f64, fem: f64) -> Headline {
        Headline {
            date: "d".into(),
            failures: 0,
            stability_wrong_numbers: 0,
            accuracy: [("fem_vs_ring_bem".to_string(), (fem, 1e-3))]
                .into_iter()
                .collect(),
            times: [("solve".to_string(), time)].into_iter().collect(),
            fenicsx: "stored".into(),
            peers: "stored".into(),
        }
    }

    #[test]
    fn slowdowns_and_accuracy_losses_are_regressions() {
        assert!(regressions(&run(1.0, 1e-4), Some(&run(0.9, 1e-4))).is_empty());
        assert_eq!(regressions(&run(2.0, 1e-4), Some(&run(1.0, 1e-4))).len(), 1);
        assert_eq!(regressions(&run(1.0, 2e-3), Some(&run(1.0, 1e-4))).len(), 1);
        // Below the timer-noise floor, times are not compared.
        assert!(regressions(&run(0.01, 1e-4), Some(&run(0.001, 1e-4))).is_empty());
    }
}
