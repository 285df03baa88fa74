//! `verify grade`: another code's results against the converged references.

use super::{to_json, Reply};
use crate::cli::args::GradeArgs;
use crate::harness::grade::{self, Grading};
use crate::harness::report::table::{readable, verdict, Cell, Column, Format, Table};
use crate::heartbeat::Heartbeat;
use crate::provenance::Provenance;

/// `verify grade --results FILE`: grade every value, print the rows and the summary (or JSON),
/// write the chart with `--svg`; fails (exit status 1) when a value is beyond `--tol`.
pub fn grade(args: GradeArgs) -> Result<Reply, String> {
    let rows = grade::input::read(&args.results)?;
    let heartbeat = Heartbeat::start("verify grade");
    let grading = grade::grade(&rows, args.tol, &|k, n| {
        heartbeat.set(format!("row {} of {n}", k + 1))
    })?;
    drop(heartbeat);
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
        let object = serde_json::json!({
            "results": args.results.display().to_string(),
            "provenance": Provenance::of_this_process(),
            "tolerance": grading.tolerance,
            "max_relative_error": grading.max_relative_error,
            "beyond": grading.beyond,
            "unresolved": grading.unresolved,
            "claims_broken": grading.claims_broken,
            "rows": grading.rows,
            "summary": grading.summary,
        });
        to_json(&object)?
    } else {
        terminal(&grading)
    };
    Ok(Reply::verdict(text, success))
}

/// The rows, the summary and the verdict as text.
fn terminal(g: &Grading) -> String {
    let mut rows = Table::new(
        "Each value against the reference at its state",
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
    let mut text = rows.to_terminal();
    text.push('\n');
    text.push_str(&summary.to_terminal());
    text.push_str(&format!(
        "\n{} values graded at T = {:.1e}: {} beyond, largest relative error {:.2e}",
        g.rows.len(),
        g.tolerance,
        g.beyond,
        g.max_relative_error
    ));
    if g.unresolved > 0 {
        text.push_str(&format!(
            "; {} closer to the reference than {} times its error bound (agree to the \
             reference's accuracy, the difference not resolved)",
            g.unresolved,
            grade::RESOLUTION
        ));
    }
    if g.rows.iter().any(|r| r.claimed_error.is_some()) {
        text.push_str(&format!(
            "; {} values beyond the error their results claim",
            g.claims_broken
        ));
    }
    text.push('\n');
    text
}
