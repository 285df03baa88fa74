//! `verify grade`: another code's results against the converged references.

use super::{to_json, Reply};
use crate::cli::args::GradeArgs;
use crate::harness::grade::{self, GradeReport, Grading};
use ringcontact::heartbeat::Heartbeat;
use ringcontact::provenance::Provenance;

/// `verify grade --results FILE`: grade every value, print the rows and the summary (or JSON),
/// write the chart with `--svg`; fails (exit status 1) when a value is beyond `--tol`.
pub fn grade(args: GradeArgs) -> Result<Reply, String> {
    let rows = grade::input::read(&args.results)?;
    let grading = grade_rows(&rows, args.tol, "verify grade")?;
    if let Some(path) = &args.svg {
        let title = format!(
            "{}: relative error against the reference",
            args.results
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
        );
        std::fs::write(path, grade::chart(&grading, &title))
            .map_err(|e| format!("--svg {}: cannot write: {e}", path.display()))?;
    }
    let success = grading.beyond == 0;
    let text = if args.json {
        to_json(&GradeReport {
            results: args.results.display().to_string(),
            provenance: Provenance::of_this_process(),
            grading: &grading,
        })?
    } else {
        terminal(&grading)
    };
    Ok(Reply::verdict(text, success))
}

/// The rows, the summary and the verdict as text.
fn terminal(g: &Grading) -> String {
    format!(
        "{}\n{}\n{}\n",
        grade::rows_table(g, "Each value against the reference at its state").to_terminal(),
        grade::summary_table(g).to_terminal(),
        grade::verdict_sentence(g)
    )
}

/// Grade `rows` at tolerance `tol` with progress on standard error under `label` (the command
/// line and the Python package's `grade`).
pub(super) fn grade_rows(
    rows: &[grade::input::ResultRow],
    tol: f64,
    label: &str,
) -> Result<Grading, String> {
    let heartbeat = Heartbeat::start(label, crate::harness::progress::fem_progress());
    grade::grade(rows, tol, &|k, n| {
        heartbeat.set(format!("row {} of {n}", k + 1))
    })
}
