//! Reading another code's results for `verify grade`: CSV with a header row, or JSON (an array
//! of objects, or an object whose `rows` is one, as `verify table --json` writes). Every error
//! names the line (CSV) or row (JSON) and the column.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use ringcontact::punch::{Contact, PunchName};

/// A quantity a row may give: a state (`eps`, `depth`, `force`) or a graded value.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "lowercase")]
pub enum Quantity {
    /// Contact ratio `b/a` (the fixed annulus's hole; a concave punch's or a free band's inner
    /// edge).
    Eps,
    /// Indentation depth `d` of the rim.
    Depth,
    /// Normal force `F`, compression positive.
    Force,
    /// `γ = F/(2 E* d a)` of the flat punches.
    Gamma,
    /// `γ1 = d/h` of the concave punches and the free bands.
    Gamma1,
    /// `γ2 = F/(2 E* h a)` of the concave punches and the free bands.
    Gamma2,
}

impl Quantity {
    /// Every quantity, in column order.
    pub const ALL: [Quantity; 6] = [
        Quantity::Eps,
        Quantity::Depth,
        Quantity::Force,
        Quantity::Gamma,
        Quantity::Gamma1,
        Quantity::Gamma2,
    ];

    /// The column name.
    pub fn key(self) -> &'static str {
        match self {
            Quantity::Eps => "eps",
            Quantity::Depth => "depth",
            Quantity::Force => "force",
            Quantity::Gamma => "gamma",
            Quantity::Gamma1 => "gamma1",
            Quantity::Gamma2 => "gamma2",
        }
    }
}

/// One row of results to grade.
#[derive(Clone, Debug)]
pub struct ResultRow {
    /// Where the row is: `line 7` (CSV, counting the header as line 1) or `row 3` (JSON).
    pub place: String,
    /// The punch (`punch` column) and its parameters (`exponent`, `tube_radius`, `profile`).
    pub punch: PunchName,
    pub exponent: Option<f64>,
    pub tube_radius: Option<f64>,
    pub profile: Option<PathBuf>,
    /// The fixed annulus's `b/a` (its geometry, from `eps`).
    pub hole_ratio: Option<f64>,
    /// What fixes the state, and its value (dimensionless or in the row's units).
    pub state: Option<(Quantity, f64)>,
    /// The values to grade, in column order.
    pub values: Vec<(Quantity, f64)>,
    /// Units of the row: `E_star`, `a`, `h` (1 when absent).
    pub effective_modulus: Option<f64>,
    pub rim_radius: Option<f64>,
    pub hole_depth: Option<f64>,
    /// The error the other code claims for the row (`error_estimate` column, as `verify solve`
    /// writes it: relative for depth, force and the `γ`s, absolute for `eps`).
    pub claimed_error: Option<f64>,
}

/// A row of the file before it is read: its place and its cells by column name.
type Record = (String, BTreeMap<String, String>);

/// The columns that have a meaning; any other column is kept in the file and ignored.
const KNOWN: [&str; 15] = [
    "punch",
    "state",
    "eps",
    "depth",
    "force",
    "gamma",
    "gamma1",
    "gamma2",
    "E_star",
    "a",
    "h",
    "exponent",
    "tube_radius",
    "profile",
    "error_estimate",
];

/// Read the results file `path` (JSON when it ends in `.json` or starts with `[` or `{`,
/// else CSV); a relative `profile` column is read beside the file.
pub fn read(path: &Path) -> Result<Vec<ResultRow>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    let json = path.extension().is_some_and(|x| x == "json");
    parse(&text, &path.display().to_string(), json, path.parent())
}

/// The rows of results `text` (JSON when `json` or when it starts with `[` or `{`, else CSV),
/// named `origin` in errors; a relative `profile` column is read from `base`.
pub fn parse(
    text: &str,
    origin: &str,
    json: bool,
    base: Option<&Path>,
) -> Result<Vec<ResultRow>, String> {
    if text
        .lines()
        .all(|l| l.trim().is_empty() || l.trim_start().starts_with('#'))
    {
        return Err(format!(
            "{origin}: the file is empty (a header row and at least one row of results)"
        ));
    }
    let first = text.trim_start().chars().next();
    let records = if json || matches!(first, Some('[' | '{')) {
        json_records(text, origin)?
    } else {
        csv_records(text, origin)?
    };
    if records.is_empty() {
        return Err(format!(
            "{origin}: no results (a header and at least one row)"
        ));
    }
    records
        .into_iter()
        .map(|(place, cells)| row(&place, &cells, base))
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{origin}: {e}"))
}

/// The cells of each CSV row by column name, with the row's place.
fn csv_records(text: &str, origin: &str) -> Result<Vec<Record>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| format!("{origin}: the header row: {e}"))?
        .iter()
        .map(String::from)
        .collect();
    check_header(&header, origin)?;
    let mut out = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| format!("{origin}: {e}"))?;
        let line = record.position().map_or(0, |p| p.line());
        let cells = header
            .iter()
            .cloned()
            .zip(record.iter().map(String::from))
            .collect();
        out.push((format!("line {line}"), cells));
    }
    Ok(out)
}

/// The cells of each JSON row by key (numbers as their text), with the row's place.
fn json_records(text: &str, origin: &str) -> Result<Vec<Record>, String> {
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| format!("{origin}: not JSON: {e}"))?;
    let rows = match &value {
        serde_json::Value::Array(rows) => rows,
        serde_json::Value::Object(o) => match o.get("rows") {
            Some(serde_json::Value::Array(rows)) => rows,
            _ => {
                return Err(format!(
                    "{origin}: a JSON file of results is an array of objects, or an object \
                     whose `rows` is one"
                ))
            }
        },
        _ => {
            return Err(format!(
                "{origin}: a JSON file of results is an array of objects"
            ))
        }
    };
    if rows.is_empty() {
        return Err(format!(
            "{origin}: no results (at least one row of results)"
        ));
    }
    let mut out = Vec::new();
    let mut keys = std::collections::BTreeSet::new();
    for (i, row) in rows.iter().enumerate() {
        let place = format!("row {}", i + 1);
        let serde_json::Value::Object(object) = row else {
            return Err(format!("{origin}: {place} is not an object"));
        };
        let cells = object
            .iter()
            .map(|(k, v)| {
                let text = match v {
                    serde_json::Value::Null => String::new(),
                    serde_json::Value::String(s) => s.clone(),
                    other => other.to_string(),
                };
                keys.insert(k.clone());
                (k.clone(), text)
            })
            .collect();
        out.push((place, cells));
    }
    check_header(&keys.into_iter().collect::<Vec<_>>(), origin)?;
    Ok(out)
}

/// The columns every file needs: `punch`, a state and a value to grade.
fn check_header(header: &[String], origin: &str) -> Result<(), String> {
    let has = |k: &str| header.iter().any(|h| h == k);
    if !has("punch") {
        return Err(format!(
            "{origin}: missing column `punch` (one of {}); the columns are {}",
            PunchName::names(None, ", "),
            header.join(", ")
        ));
    }
    if !Quantity::ALL.iter().any(|q| has(q.key())) {
        return Err(format!(
            "{origin}: no column to grade or to set the state: give some of eps, depth, force, \
             gamma, gamma1, gamma2 (the columns are {})",
            header.join(", ")
        ));
    }
    let wrong: Vec<&String> = header
        .iter()
        .filter(|h| KNOWN.iter().any(|k| k.eq_ignore_ascii_case(h) && k != h))
        .collect();
    if !wrong.is_empty() {
        return Err(format!(
            "{origin}: column names are case-sensitive: {wrong:?} (write {})",
            KNOWN.join(", ")
        ));
    }
    Ok(())
}

/// One row from its cells.
fn row(
    place: &str,
    cells: &BTreeMap<String, String>,
    base: Option<&Path>,
) -> Result<ResultRow, String> {
    let text = |key: &str| cells.get(key).map(|s| s.trim()).filter(|s| !s.is_empty());
    let number = |key: &str| -> Result<Option<f64>, String> {
        match text(key) {
            None => Ok(None),
            Some(t) => match t.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(Some(x)),
                _ => Err(format!(
                    "{place}, column {key}: {t:?} is not a finite number"
                )),
            },
        }
    };
    let name = text("punch").ok_or_else(|| format!("{place}, column punch: empty"))?;
    let punch = PunchName::parse(name).ok_or_else(|| {
        format!(
            "{place}, column punch: unknown punch {name:?} (one of {})",
            PunchName::names(None, ", ")
        )
    })?;
    let flat = matches!(punch.contact(), Contact::Disk | Contact::FixedAnnulus);
    let given: Vec<(Quantity, f64)> = Quantity::ALL
        .iter()
        .map(|&q| number(q.key()).map(|v| v.map(|v| (q, v))))
        .collect::<Result<Vec<_>, _>>()?
        .into_iter()
        .flatten()
        .collect();
    for (q, _) in &given {
        let wrong = match (flat, q) {
            (true, Quantity::Gamma1 | Quantity::Gamma2) => Some("the flat punches' function is gamma = F/(2 E* d a)"),
            (false, Quantity::Gamma) => Some("a concave punch's (and a free band's) functions are gamma1 = d/h and gamma2 = F/(2 E* h a)"),
            (true, Quantity::Eps) if punch.contact() == Contact::Disk => Some("its contact is the whole disk: it has no hole"),
            _ => None,
        };
        if let Some(why) = wrong {
            return Err(format!(
                "{place}, column {}: does not apply to the {}: {why}",
                q.key(),
                punch.as_str()
            ));
        }
    }
    let mut hole_ratio = None;
    let mut rest = given.clone();
    if punch.contact() == Contact::FixedAnnulus {
        let eps = given
            .iter()
            .find(|(q, _)| *q == Quantity::Eps)
            .map(|p| p.1)
            .ok_or_else(|| format!("{place}, column eps: the {} needs its b/a", punch.as_str()))?;
        hole_ratio = Some(eps);
        rest.retain(|(q, _)| *q != Quantity::Eps);
    }
    let state = state_of(place, text("state"), flat, &rest)?;
    // The state is not graded, nor its restatement as a function (gamma1 = d/h at a given
    // depth, gamma2 = F/(2 E* h a) at a given force).
    let restated = match state.map(|s| s.0) {
        Some(Quantity::Depth) if !flat => Some(Quantity::Gamma1),
        Some(Quantity::Force) if !flat => Some(Quantity::Gamma2),
        _ => None,
    };
    let values: Vec<(Quantity, f64)> = rest
        .into_iter()
        .filter(|(q, _)| Some(*q) != state.map(|s| s.0) && Some(*q) != restated)
        .collect();
    if values.is_empty() {
        return Err(format!(
            "{place}: nothing to grade (give a value of gamma, gamma1, gamma2, or of eps, depth, \
             force beside the one that sets the state)"
        ));
    }
    let profile = text("profile").map(|p| {
        let p = PathBuf::from(p);
        match base {
            Some(dir) if p.is_relative() => dir.join(p),
            _ => p,
        }
    });
    Ok(ResultRow {
        place: place.to_string(),
        punch,
        exponent: number("exponent")?,
        tube_radius: number("tube_radius")?,
        profile,
        hole_ratio,
        state,
        values,
        effective_modulus: number("E_star")?,
        rim_radius: number("a")?,
        hole_depth: number("h")?,
        claimed_error: number("error_estimate")?,
    })
}

/// The state of a row: the `state` column's quantity, else the first of depth, force, eps
/// given (a code is given a depth or a force and finds the contact; results given as the
/// paper's functions of eps have no depth or force column). A flat-faced punch without depth or
/// force is at unit depth (`None`: its `gamma` does not depend on it).
fn state_of(
    place: &str,
    named: Option<&str>,
    flat: bool,
    given: &[(Quantity, f64)],
) -> Result<Option<(Quantity, f64)>, String> {
    let states = [Quantity::Depth, Quantity::Force, Quantity::Eps];
    if let Some(name) = named {
        let q = states
            .iter()
            .find(|q| q.key() == name)
            .ok_or_else(|| format!("{place}, column state: {name:?} is not eps, depth or force"))?;
        return given
            .iter()
            .find(|(g, _)| g == q)
            .copied()
            .map(Some)
            .ok_or_else(|| {
                format!("{place}, column {name}: empty, but the state column names it")
            });
    }
    let first = states
        .iter()
        .find_map(|q| given.iter().find(|(g, _)| g == q).copied());
    match first {
        Some(s) => Ok(Some(s)),
        None if flat => Ok(None),
        None => Err(format!(
            "{place}: no state: give eps, depth or force (the columns the state is read from)"
        )),
    }
}
