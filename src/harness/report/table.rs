//! One table type for every output: a study fills a [`Table`] once and renders it to the
//! terminal, Markdown, CSV (the `csv` crate), JSON or HTML.
//!
//! Cells keep their numbers: CSV and JSON get full precision (`f64`'s shortest round-trip form),
//! the terminal, Markdown and HTML the column's display precision.

use std::fmt::Write as _;

use serde_json::{Map, Value};

use ringcontact::error::{Error, Result};

/// How a numeric column is shown to people (CSV and JSON always carry full precision).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Format {
    /// Fixed point with this many decimals.
    Fixed(usize),
    /// Scientific with this many decimals of the mantissa.
    Scientific(usize),
    /// Scientific with an explicit sign (differences).
    SignedScientific(usize),
}

/// One column: its key (CSV header and JSON key), what people read, its unit.
#[derive(Clone, Debug)]
pub struct Column {
    pub key: String,
    pub label: String,
    pub unit: Option<String>,
    pub format: Format,
}

impl Column {
    /// A numeric column shown with `format`.
    pub fn number(key: &str, label: &str, format: Format) -> Self {
        Self {
            key: key.to_string(),
            label: label.to_string(),
            unit: None,
            format,
        }
    }

    /// A column of text (its format applies only if a number lands in it).
    pub fn text(key: &str, label: &str) -> Self {
        Self::number(key, label, Format::Fixed(0))
    }

    /// The same column with a unit (shown in the header as `label [unit]`).
    pub(crate) fn with_unit(mut self, unit: &str) -> Self {
        self.unit = Some(unit.to_string());
        self
    }

    fn header(&self) -> String {
        match &self.unit {
            Some(u) => format!("{} [{u}]", self.label),
            None => self.label.clone(),
        }
    }
}

/// One cell.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    Number(f64),
    Text(String),
    /// No value (shown `-`, empty in CSV, `null` in JSON).
    Missing,
    /// A text that must catch the eye (a failed verdict): bold in Markdown and HTML.
    Flag(String),
}

/// `x` for people at any magnitude: fixed point with `decimals` decimals where that shows
/// `decimals + 1` significant digits or fewer than 9 before the point (`1e-3 <= |x| < 1e8`, or
/// zero), scientific with the same decimals of the mantissa elsewhere; non-finite values as Rust
/// writes them. A depth of `1e300` in fixed point would print 301 digits, of which all past the
/// 17th are the binary expansion's noise.
pub fn readable(x: f64, decimals: usize) -> String {
    let magnitude = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-3..1e8).contains(&magnitude) {
        format!("{x:.decimals$}")
    } else {
        format!("{x:.decimals$e}")
    }
}

/// Whether `x` is a whole number that JSON and CSV write without a fraction (`16`, not `16.0`).
fn is_count(x: f64) -> bool {
    x.fract() == 0.0 && x.abs() < 9.0e15
}

/// `x` in the shortest form that reads back to the same `f64`: whole numbers without a
/// fraction, the exponent form for small and large magnitudes (`1e-13`, never 13 zeros).
fn shortest(x: f64) -> String {
    if is_count(x) {
        format!("{}", x as i64)
    } else {
        format!("{x:?}")
    }
}

/// A verdict cell: `ok` when `passed`, else the flagged `failure` text.
pub(crate) fn verdict(passed: bool, failure: &str) -> Cell {
    if passed {
        Cell::Text("ok".into())
    } else {
        Cell::Flag(failure.into())
    }
}

impl From<f64> for Cell {
    fn from(v: f64) -> Self {
        Cell::Number(v)
    }
}

impl From<Option<f64>> for Cell {
    fn from(v: Option<f64>) -> Self {
        v.map_or(Cell::Missing, Cell::Number)
    }
}

impl From<&str> for Cell {
    fn from(v: &str) -> Self {
        Cell::Text(v.to_string())
    }
}

impl From<String> for Cell {
    fn from(v: String) -> Self {
        Cell::Text(v)
    }
}

/// A titled table of rows.
#[derive(Clone, Debug)]
pub struct Table {
    pub title: String,
    pub columns: Vec<Column>,
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// An empty table with these columns.
    pub fn new(title: &str, columns: Vec<Column>) -> Self {
        Self {
            title: title.to_string(),
            columns,
            rows: Vec::new(),
        }
    }

    /// Append a row (one cell per column).
    pub fn push(&mut self, row: Vec<Cell>) {
        debug_assert_eq!(row.len(), self.columns.len(), "one cell per column");
        self.rows.push(row);
    }

    fn shown(&self, column: usize, cell: &Cell) -> String {
        match cell {
            Cell::Number(v) if !v.is_finite() => v.to_string(),
            Cell::Number(v) => match self.columns[column].format {
                Format::Fixed(d) => format!("{v:.d$}"),
                Format::Scientific(d) => format!("{v:.d$e}"),
                Format::SignedScientific(d) => format!("{v:+.d$e}"),
            },
            Cell::Text(t) | Cell::Flag(t) => t.clone(),
            Cell::Missing => "-".to_string(),
        }
    }

    /// Aligned text for a terminal: the title, then right-aligned columns.
    pub(crate) fn to_terminal(&self) -> String {
        let cells: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|r| {
                r.iter()
                    .enumerate()
                    .map(|(c, v)| self.shown(c, v))
                    .collect()
            })
            .collect();
        let headers: Vec<String> = self.columns.iter().map(Column::header).collect();
        let widths: Vec<usize> = (0..self.columns.len())
            .map(|c| {
                cells
                    .iter()
                    .map(|r| r[c].chars().count())
                    .chain([headers[c].chars().count()])
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        // Text columns are left-aligned, numeric ones right-aligned.
        let textual: Vec<bool> = (0..self.columns.len())
            .map(|c| {
                self.rows
                    .iter()
                    .map(|r| &r[c])
                    .find(|v| !matches!(v, Cell::Missing))
                    .is_some_and(|v| matches!(v, Cell::Text(_) | Cell::Flag(_)))
            })
            .collect();
        let line = |items: &[String]| -> String {
            let parts: Vec<String> = items
                .iter()
                .zip(&widths)
                .zip(&textual)
                .map(|((s, &w), &left)| {
                    if left {
                        format!("{s:<w$}")
                    } else {
                        format!("{s:>w$}")
                    }
                })
                .collect();
            format!("  {}\n", parts.join(" ").trim_end())
        };
        let mut out = format!("{}\n", self.title);
        out.push_str(&line(&headers));
        for r in &cells {
            out.push_str(&line(r));
        }
        out
    }

    /// The Markdown table alone.
    pub(crate) fn to_markdown_table(&self) -> String {
        let mut out = String::from("|");
        for c in &self.columns {
            let _ = write!(out, " {} |", c.header());
        }
        out.push_str("\n|");
        out.push_str(&"---|".repeat(self.columns.len()));
        out.push('\n');
        for r in &self.rows {
            out.push('|');
            for (c, v) in r.iter().enumerate() {
                let text = self.shown(c, v).replace('|', "\\|");
                match v {
                    Cell::Flag(_) => {
                        let _ = write!(out, " **{text}** |");
                    }
                    _ => {
                        let _ = write!(out, " {text} |");
                    }
                }
            }
            out.push('\n');
        }
        out
    }

    /// CSV with the column keys as header and full-precision numbers.
    pub(crate) fn to_csv(&self) -> Result<String> {
        let mut writer = csv::Writer::from_writer(Vec::new());
        let fail = |e: csv::Error| self.csv_error(e);
        writer
            .write_record(self.columns.iter().map(|c| c.key.as_str()))
            .map_err(fail)?;
        for r in &self.rows {
            writer
                .write_record(r.iter().map(|v| match v {
                    Cell::Number(x) => shortest(*x),
                    Cell::Text(t) | Cell::Flag(t) => t.clone(),
                    Cell::Missing => String::new(),
                }))
                .map_err(fail)?;
        }
        let bytes = writer.into_inner().map_err(|e| self.csv_error(e))?;
        String::from_utf8(bytes).map_err(|e| self.csv_error(e))
    }

    fn csv_error(&self, e: impl std::fmt::Display) -> Error {
        Error::File {
            action: "write as CSV".into(),
            path: self.title.clone(),
            message: e.to_string(),
        }
    }

    /// A JSON array of objects keyed by the column keys (non-finite numbers as `null`).
    pub fn to_json(&self) -> Value {
        Value::Array(
            self.rows
                .iter()
                .map(|r| {
                    let mut object = Map::new();
                    for (c, v) in r.iter().enumerate() {
                        let value = match v {
                            Cell::Number(x) if is_count(*x) => Value::from(*x as i64),
                            Cell::Number(x) => {
                                serde_json::Number::from_f64(*x).map_or(Value::Null, Value::Number)
                            }
                            Cell::Text(t) | Cell::Flag(t) => Value::String(t.clone()),
                            Cell::Missing => Value::Null,
                        };
                        object.insert(self.columns[c].key.clone(), value);
                    }
                    Value::Object(object)
                })
                .collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn readable_numbers_switch_to_scientific_outside_ordinary_magnitudes() {
        assert_eq!(readable(0.5, 3), "0.500");
        assert_eq!(readable(0.0, 3), "0.000");
        assert_eq!(readable(-12345.678, 2), "-12345.68");
        assert_eq!(readable(1e300, 3), "1.000e300");
        assert_eq!(readable(-2.5e-7, 2), "-2.50e-7");
        assert_eq!(readable(f64::INFINITY, 3), "inf");
        assert!(readable(1e300, 12).len() < 20);
    }

    use super::*;

    fn sample() -> Table {
        let mut t = Table::new(
            "sample, with a comma",
            vec![
                Column::number("eps", "b/a", Format::Fixed(3)),
                Column::number("force", "F", Format::Scientific(2)).with_unit("E* a d"),
                Column::number("note", "note", Format::Fixed(0)),
            ],
        );
        t.push(vec![
            0.5.into(),
            1.9620357938451314.into(),
            "a, \"quoted\"".into(),
        ]);
        t.push(vec![0.9.into(), None.into(), Cell::Missing]);
        t
    }

    #[test]
    fn every_format_carries_the_same_rows() {
        let t = sample();
        let terminal = t.to_terminal();
        assert!(
            terminal.contains("F [E* a d]") && terminal.contains("1.96e0"),
            "{terminal}"
        );
        let md = t.to_markdown_table();
        assert!(md.contains("| 0.500 | 1.96e0 |"), "{md}");
        // CSV: quoted where needed, full precision, empty for missing.
        let csv = t.to_csv().unwrap();
        assert!(csv.starts_with("eps,force,note\n"), "{csv}");
        assert!(
            csv.contains("0.5,1.9620357938451314,\"a, \"\"quoted\"\"\""),
            "{csv}"
        );
        assert!(csv.contains("0.9,,\n"), "{csv}");
        let json = t.to_json();
        assert_eq!(json[0]["force"], 1.9620357938451314);
        assert!(json[1]["force"].is_null());
    }
}
