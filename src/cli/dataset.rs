//! `verify dataset`: the converged reference values as CSV and JSON with a datapackage.json.

use super::{message, output_directory, to_json, Reply};
use crate::cli::args::DatasetArgs;
use crate::harness::dataset::{self, Size};
use crate::harness::report::table::{Column, Format, Table};
use ringcontact::heartbeat::Heartbeat;
use ringcontact::provenance::Provenance;

/// What [`write`] wrote: the tables, the files and the provenance they carry.
pub(super) struct Written {
    resources: Vec<dataset::Resource>,
    files: Vec<std::path::PathBuf>,
    provenance: Provenance,
}

/// Compute the tables (`small`: the coarse copy) and write them, with `datapackage.json`, into
/// `out`, with progress on standard error.
pub(super) fn write(out: &std::path::Path, small: bool) -> Result<Written, String> {
    let size = if small { Size::Small } else { Size::Full };
    let heartbeat = Heartbeat::start("verify dataset", crate::harness::progress::fem_progress());
    let resources =
        dataset::build(size, &|step| heartbeat.set(step.to_string())).map_err(message)?;
    drop(heartbeat);
    let provenance = Provenance::of_this_process();
    let files = dataset::write(out, &resources, &provenance, size).map_err(message)?;
    Ok(Written {
        resources,
        files,
        provenance,
    })
}

/// What `verify dataset --json` prints: the directory, the provenance, each table's name, rows
/// and interpolation error, and the files.
pub(super) fn summary_json(out: &std::path::Path, written: &Written) -> Result<String, String> {
    let summary: Vec<serde_json::Value> = written
        .resources
        .iter()
        .map(|r| {
            serde_json::json!({
                "name": r.name,
                "rows": r.table.rows.len(),
                "interpolation_error": r.interpolation_error,
            })
        })
        .collect();
    to_json(&serde_json::json!({
        "out": out.display().to_string(),
        "provenance": written.provenance,
        "resources": summary,
        "files": written.files,
    }))
}

/// `verify dataset [--out DIR] [--small]`: compute and write the tables, print what was written.
pub fn dataset(args: DatasetArgs) -> Result<Reply, String> {
    let out = output_directory(args.out.as_deref(), "reports/dataset");
    let written = write(&out, args.small)?;
    if args.json {
        return Ok(Reply::ok(summary_json(&out, &written)?));
    }
    let resources = &written.resources;
    let mut table = Table::new(
        &format!("Dataset written to {}", out.display()),
        vec![
            Column::text("name", "table (.csv and .json)"),
            Column::number("rows", "rows", Format::Fixed(0)),
            Column::text("interpolation", "interpolation error (measured)"),
            Column::text("title", "contents"),
        ],
    );
    for r in resources {
        let interpolation_errors: Vec<String> = r
            .interpolation_error
            .iter()
            .map(|(n, e)| format!("{n} {e:.1e}"))
            .collect();
        table.push(vec![
            r.name.clone().into(),
            (r.table.rows.len() as f64).into(),
            interpolation_errors.join(", ").into(),
            r.title.clone().into(),
        ]);
    }
    Ok(Reply::ok(format!(
        "{}\ndatapackage.json describes every column (name, type, unit, description) and the \
         provenance.\n",
        table.to_terminal()
    )))
}
