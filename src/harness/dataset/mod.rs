//! `verify dataset`: converged reference values to download. The non-adhesive functions of the
//! built-in punches with their error bounds and the error of interpolating them
//! ([`functions`]), the JKR critical states and pull-off forces, and the fitted formulas with
//! their largest errors ([`adhesive`]); each table as CSV (one header row) and JSON, described by
//! a `datapackage.json` (Frictionless Data tabular data package: names, types, units,
//! descriptions) with the provenance (version, commit, command).

pub mod adhesive;
pub mod functions;

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

use crate::harness::cases;
use crate::harness::report::table::{Column, Format, Table};
use ringcontact::error::{Error, Result};
use ringcontact::methods::RingBem;
use ringcontact::provenance::Provenance;

/// One column of a table: its name, unit and meaning (a Frictionless table-schema field).
#[derive(Clone, Debug)]
pub struct Field {
    pub name: String,
    /// `number` or `string`.
    pub kind: &'static str,
    /// The unit (`1` for dimensionless), `None` for text.
    pub unit: Option<String>,
    pub description: String,
}

impl Field {
    /// A numeric field in `unit`.
    pub fn number(name: &str, unit: &str, description: &str) -> Self {
        Self {
            name: name.into(),
            kind: "number",
            unit: Some(unit.into()),
            description: description.into(),
        }
    }

    /// A text field.
    pub fn text(name: &str, description: &str) -> Self {
        Self {
            name: name.into(),
            kind: "string",
            unit: None,
            description: description.into(),
        }
    }

    /// The column of a [`Table`] holding the field.
    pub fn column(&self) -> Column {
        Column::number(&self.name, &self.name, Format::Scientific(10))
    }

    fn schema(&self) -> Value {
        let mut field = json!({
            "name": self.name,
            "type": self.kind,
            "description": self.description,
        });
        if let Some(unit) = &self.unit {
            field["unit"] = json!(unit);
        }
        field
    }
}

/// One table of the dataset.
pub struct Resource {
    /// File stem (`functions-LABEL` gives `functions-LABEL.csv` and `.json`).
    pub name: String,
    pub title: String,
    pub description: String,
    pub fields: Vec<Field>,
    pub table: Table,
    /// The largest relative error of interpolating each function column, against fresh solves.
    pub interpolation_error: Vec<(String, f64)>,
}

/// How large a dataset to make.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Size {
    /// The full grids (interpolation to about 1e-8).
    Full,
    /// The committed copy: coarser grids, fewer adhesion states.
    Small,
}

impl Size {
    fn intervals(self) -> usize {
        match self {
            Size::Full => 800,
            Size::Small => 48,
        }
    }

    fn annulus_ratios(self) -> Vec<f64> {
        let count = match self {
            Size::Full => 40,
            Size::Small => 8,
        };
        functions::grid(count)
            .into_iter()
            .filter(|e| (1e-3..=0.999).contains(e))
            .collect()
    }

    /// `d0/h` from 0.1 to 100 evenly in the logarithm, rounded to 12 significant digits.
    fn adhesion_scales(self) -> Vec<f64> {
        let steps = match self {
            Size::Full => 24,
            Size::Small => 4,
        };
        crate::harness::studies::sweeps::pulloff_scales(steps)
            .into_iter()
            .map(|s| format!("{s:.11e}").parse().unwrap_or(s))
            .collect()
    }

    /// A free band's `d0/h`, from 1e-3 to 1 evenly in the logarithm (its JKR analysis is
    /// checked up to `d0/h = 1`; at 1e-3 it is within 3e-5 of the plane-strain cylinder).
    fn band_scales(self) -> Vec<f64> {
        self.adhesion_scales()
            .into_iter()
            .map(|s| format!("{:.11e}", s / 100.0).parse().unwrap_or(s / 100.0))
            .collect()
    }
}

/// Compute every table of the dataset.
pub fn build(size: Size, progress: &dyn Fn(&str)) -> Result<Vec<Resource>> {
    let solver = RingBem::new();
    let mut resources = Vec::new();
    for kind in cases::dataset_function_punches() {
        resources.push(functions::resource(
            &solver,
            kind,
            size.intervals(),
            progress,
        )?);
    }
    resources.push(adhesive::fixed_annulus(
        &solver,
        &size.annulus_ratios(),
        progress,
    )?);
    for kind in cases::dataset_recessed_jkr_punches() {
        resources.push(adhesive::concave(
            &solver,
            kind,
            &size.adhesion_scales(),
            progress,
        )?);
    }
    for band in cases::free_bands() {
        resources.push(adhesive::free_band(
            &solver,
            &band,
            &size.band_scales(),
            progress,
        )?);
    }
    progress("fits");
    resources.push(adhesive::fits(&solver)?);
    Ok(resources)
}

/// Write each resource as `NAME.csv` and `NAME.json` into `out`, and `datapackage.json`;
/// returns the files written.
pub fn write(
    out: &Path,
    resources: &[Resource],
    provenance: &Provenance,
    size: Size,
) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(out).map_err(|e| Error::file("create the directory", out, e))?;
    let mut files = Vec::new();
    let mut described = Vec::new();
    for r in resources {
        let csv_path = out.join(format!("{}.csv", r.name));
        put(&csv_path, &r.table.to_csv()?, &mut files)?;
        let schema: Vec<Value> = r.fields.iter().map(Field::schema).collect();
        let interpolation: serde_json::Map<String, Value> = r
            .interpolation_error
            .iter()
            .map(|(k, v)| (k.clone(), json!(v)))
            .collect();
        let document = json!({
            "name": r.name,
            "title": r.title,
            "description": r.description,
            "provenance": provenance,
            "fields": schema,
            "interpolation_error": interpolation,
            "rows": r.table.to_json(),
        });
        let json_path = out.join(format!("{}.json", r.name));
        put(&json_path, &pretty(&document)?, &mut files)?;
        let mut resource = json!({
            "name": r.name,
            "path": format!("{}.csv", r.name),
            "profile": "tabular-data-resource",
            "format": "csv",
            "mediatype": "text/csv",
            "encoding": "utf-8",
            "title": r.title,
            "description": r.description,
            "schema": { "fields": schema, "missingValues": [""] },
            "json_copy": format!("{}.json", r.name),
        });
        if !interpolation.is_empty() {
            resource["interpolation_error"] = Value::Object(interpolation);
        }
        described.push(resource);
    }
    let package = json!({
        "profile": "tabular-data-package",
        "name": "ringcontact-reference-dataset",
        "title": "Converged reference values for rigid punches with ring-shaped contact",
        "description": format!(
            "Frictionless normal contact of rigid axisymmetric punches ({}) with an elastic \
             half-space, without and with JKR adhesion, computed by the ring-element BEM of \
             ringcontact. Dimensionless: a = h = E* = 1 (a punch whose contact is fixed, \
             F = 2 E* d a gamma; a punch whose contact edges are found, h its gap at the axis, \
             d = h gamma1, F = 2 E* h a gamma2). \
             Every table is given as CSV (the resource's path) and as JSON (json_copy). {}",
            cases::dataset_function_punches()
                .iter()
                .map(|kind| kind.label())
                .collect::<Vec<_>>()
                .join(", "),
            match size {
                Size::Full => "Full grids.",
                Size::Small => "The small copy: coarser grids (`verify dataset --small`); \
                                `verify dataset` writes the full grids.",
            }
        ),
        "version": provenance.ringcontact_version,
        "licenses": [ { "name": "MIT" }, { "name": "Apache-2.0" } ],
        "sources": [ {
            "title": format!(
                "ringcontact {} (commit {})",
                provenance.ringcontact_version, provenance.commit
            )
        } ],
        "provenance": provenance,
        "resources": described,
    });
    put(
        &out.join("datapackage.json"),
        &pretty(&package)?,
        &mut files,
    )?;
    Ok(files)
}

fn pretty(value: &Value) -> Result<String> {
    serde_json::to_string_pretty(value)
        .map(|s| s + "\n")
        .map_err(|e| Error::File {
            action: "write as JSON".into(),
            path: "dataset".into(),
            message: e.to_string(),
        })
}

fn put(path: &Path, text: &str, files: &mut Vec<PathBuf>) -> Result<()> {
    std::fs::write(path, text).map_err(|e| Error::file("write", path, e))?;
    files.push(path.to_path_buf());
    Ok(())
}
