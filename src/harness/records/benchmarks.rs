//! The benchmark records (`benches/records/*.json`, written by the benchmark scripts): speed
//! figures measured interleaved with their spread, the machine and the commit, read here so
//! that the report and `verify fenicsx` quote them instead of single runs.
//!
//! - `fenicsx-speed.json` (`scripts/fenicsx/speed.py`): our FEM and FEniCSx in several
//!   configurations on the same discrete problems, time from the mesh file to the force.
//! - `tamaas-speed.json` (`scripts/peers/speed.py`): our grid BEM and Tamaas at 512².

use std::collections::BTreeMap;
use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use crate::harness::report::table::{Column, Format, Table};
use ringcontact::error::{Error, Result};

/// Median, range and count of a timed quantity's runs (seconds, or a ratio).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct Spread {
    pub median: f64,
    pub min: f64,
    pub max: f64,
    #[serde(default)]
    pub runs: Vec<f64>,
}

impl Spread {
    /// `median (min-max)` with `digits` decimals.
    pub(crate) fn describe(&self, digits: usize) -> String {
        format!(
            "{:.digits$} ({:.digits$}-{:.digits$})",
            self.median, self.min, self.max
        )
    }
}

/// The machine a record was measured on.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct Machine {
    pub description: String,
}

/// One row of the FEniCSx record: a stored result's problem, both codes' times.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct FenicsxSpeedRow {
    pub row: String,
    pub unknowns: usize,
    pub ours: Spread,
    pub fenicsx: BTreeMap<String, Spread>,
    /// The fastest FEniCSx configuration on this row (`solver:processes`).
    pub fastest: String,
    /// Our time over the fastest configuration's, per round.
    pub ratio: Spread,
}

/// What every record states about how it was measured.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct Provenance {
    /// The command that wrote the record.
    pub command: String,
    pub date: String,
    pub commit: String,
    pub machine: Machine,
    /// Interleaved rounds: each time is the median of this many runs.
    pub rounds: usize,
    /// What the timed region holds, the same on both sides.
    pub timed_region: String,
}

/// The FEniCSx speed record.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct FenicsxSpeed {
    #[serde(flatten)]
    pub provenance: Provenance,
    pub configs: Vec<String>,
    pub rows: Vec<FenicsxSpeedRow>,
}

/// A FEniCSx row's time as the speed-accuracy chart quotes it.
pub(crate) struct RowTime {
    pub median: f64,
    pub min: f64,
    pub max: f64,
    pub runs: usize,
    pub configuration: String,
}

/// The records' directory, `benches/records/` of the project.
pub(crate) fn records_directory() -> PathBuf {
    crate::harness::settings::project_root()
        .join("benches")
        .join("records")
}

fn load<T: serde::de::DeserializeOwned>(name: &str) -> Result<T> {
    let path = records_directory().join(name);
    let text = std::fs::read_to_string(&path).map_err(|e| Error::file("read", &path, e))?;
    serde_json::from_str(&text).map_err(|e| Error::file("parse", &path, e))
}

impl FenicsxSpeed {
    /// The stored record (`benches/records/fenicsx-speed.json`).
    pub fn load() -> Result<Self> {
        load("fenicsx-speed.json")
    }

    /// The fastest FEniCSx configuration's time on the row named `name`, if the record has it.
    pub fn row(&self, name: &str) -> Option<RowTime> {
        let row = self.rows.iter().find(|r| r.row == name)?;
        let time = row.fenicsx.get(&row.fastest)?;
        Some(RowTime {
            median: time.median,
            min: time.min,
            max: time.max,
            runs: time.runs.len().max(1),
            configuration: format!("FEniCSx {}", row.fastest),
        })
    }

    /// Our time over the fastest FEniCSx configuration's: the row medians' range.
    pub(crate) fn ratio_range(&self) -> (f64, f64) {
        self.rows
            .iter()
            .map(|r| r.ratio.median)
            .fold((f64::INFINITY, 0.0), |(lo, hi), x| (lo.min(x), hi.max(x)))
    }

    /// One row per problem: unknowns, our time, each configuration's, the ratio.
    pub fn table(&self) -> Table {
        let mut columns = vec![
            Column::text("row", "stored result"),
            Column::number("unknowns", "unknowns", Format::Fixed(0)),
            Column::text("ours_s", "ours [s]"),
        ];
        for c in &self.configs {
            columns.push(Column::text(c, &format!("FEniCSx {c} [s]")));
        }
        columns.push(Column::text("fastest", "fastest FEniCSx"));
        columns.push(Column::text("ratio", "ours / fastest"));
        let mut t = Table::new(
            &format!(
                "Our FEM against FEniCSx, interleaved ({} rounds, {}, commit {}, {}): median \
                 (range)",
                self.provenance.rounds,
                self.provenance.machine.description,
                self.provenance.commit,
                self.provenance.date
            ),
            columns,
        );
        for r in &self.rows {
            let mut cells = vec![
                r.row.clone().into(),
                (r.unknowns as f64).into(),
                r.ours.describe(3).into(),
            ];
            for c in &self.configs {
                cells.push(
                    r.fenicsx
                        .get(c)
                        .map_or("-".to_string(), |s| s.describe(3))
                        .into(),
                );
            }
            cells.push(r.fastest.clone().into());
            cells.push(r.ratio.describe(3).into());
            t.push(cells);
        }
        t
    }

    /// One paragraph: what was timed, how, and the ratio's range.
    pub(crate) fn summary(&self) -> String {
        let (lo, hi) = self.ratio_range();
        format!(
            "Timed region on both sides: {}. Each configuration is `solver:processes` of \
             scripts/fenicsx/solve.py; every force agreed with the stored one to 1e-8. Our time \
             over FEniCSx's fastest configuration: {lo:.2} to {hi:.2} (row medians; the ranges \
             over the rounds are in the table). Reproduce: `{}`.",
            self.provenance.timed_region, self.provenance.command
        )
    }
}

/// The Tamaas speed record (`benches/records/tamaas-speed.json`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct TamaasSpeed {
    #[serde(flatten)]
    pub provenance: Provenance,
    pub problem: String,
    pub tamaas_configuration: String,
    pub ours: Spread,
    pub tamaas: Spread,
    pub ratio_ours_over_tamaas: Spread,
    pub stiffness_relative_difference: f64,
}

impl TamaasSpeed {
    /// The stored record.
    pub fn load() -> Result<Self> {
        load("tamaas-speed.json")
    }

    /// Both codes' times and the ratio, one row each.
    pub fn table(&self) -> Table {
        let mut t = Table::new(
            &format!(
                "Our grid BEM against Tamaas, {} ({} interleaved rounds, {}, commit {}, {})",
                self.problem,
                self.provenance.rounds,
                self.provenance.machine.description,
                self.provenance.commit,
                self.provenance.date
            ),
            vec![
                Column::text("code", "code"),
                Column::text("time_s", "time [s], median (range)"),
            ],
        );
        t.push(vec!["ours".into(), self.ours.describe(2).into()]);
        t.push(vec![
            format!("Tamaas ({})", self.tamaas_configuration).into(),
            self.tamaas.describe(2).into(),
        ]);
        t.push(vec![
            "ours / Tamaas".into(),
            self.ratio_ours_over_tamaas.describe(2).into(),
        ]);
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed record reads, names its machine and commit, and its ratios are the
    /// quotients of its own medians' order of magnitude (a record whose ratio is not our time
    /// over the fastest configuration's would be caught).
    #[test]
    fn the_committed_fenicsx_record_is_consistent() {
        let path =
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("benches/records/fenicsx-speed.json");
        let record: FenicsxSpeed =
            serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let p = &record.provenance;
        assert!(!p.machine.description.is_empty() && !p.commit.is_empty());
        assert!(p.rounds >= 3, "a record is the median of several rounds");
        for r in &record.rows {
            let fastest = &r.fenicsx[&r.fastest];
            for (config, time) in &r.fenicsx {
                assert!(
                    time.median >= fastest.median,
                    "{}: {config} is faster",
                    r.row
                );
                assert_eq!(time.runs.len(), p.rounds, "{} {config}", r.row);
            }
            let quotient = r.ours.median / fastest.median;
            assert!(
                (r.ratio.median / quotient - 1.0).abs() < 0.5,
                "{}: ratio {} against medians' quotient {quotient}",
                r.row,
                r.ratio.median
            );
            assert!(r.ratio.min <= r.ratio.median && r.ratio.median <= r.ratio.max);
        }
    }
}
