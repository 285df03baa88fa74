//! The study commands: `compare` (the default job), `convergence`, `stability`, `history`, `fit`
//! and `references`.

use std::fmt::Write as _;

use super::{message, to_json, Reply};
use crate::cli::args::{CompareArgs, ConvergenceArgs, HistoryArgs, JsonArgs};
use crate::harness::progress::Progress;
use crate::harness::records::baselines;
use crate::harness::records::fenicsx;
use crate::harness::records::operator;
use crate::harness::records::peers;
use crate::harness::report::document;
use crate::harness::report::history;
use crate::harness::report::html;
use crate::harness::report::table::{Column, Format, Table};
use crate::harness::report_jobs;
use crate::harness::studies::comparison;
use crate::harness::studies::convergence;
use crate::harness::studies::stability;
use ringcontact::methods::RingBem;
use ringcontact::punch::PunchKind;
use ringcontact::punch::PunchName;
use ringcontact::reference;

/// `verify compare`: the ring BEM against the references, the FEM against the ring BEM, the
/// stored FEniCSx and peer results, and the report directory (unless `--no-report`).
pub fn compare(args: CompareArgs) -> Result<Reply, String> {
    let floor = ringcontact::methods::Fem::MIN_TOLERANCE;
    if let Some(t) = args
        .fem_tolerances
        .iter()
        .find(|&&t| !(t >= floor && t < 1.0))
    {
        return Err(format!(
            "--fem-tolerances: {t} is outside [{floor:e}, 1), the FEM's tolerance range"
        ));
    }
    if args.fresh.is_some() && args.no_report {
        return Err(
            "--fresh compares fresh results in the report: drop --no-report (or --fresh)".into(),
        );
    }
    if let Some(fresh) = &args.fresh {
        if !fresh.is_dir() {
            return Err(format!(
                "--fresh {}: not a directory (the fresh results laid out as verify/: fenicsx/, \
                 peers/, pulloff/)",
                fresh.display()
            ));
        }
    }
    if args.no_report {
        let inputs = CompareInputs {
            comparison: comparison::run(args.tol).map_err(message)?,
            fenicsx: fenicsx::run().map_err(message)?,
            peers: peers::run(report_jobs::PEER_MAX_GRID).map_err(message)?,
            operators: operator::load_records().map_err(message)?,
            adhesion_peers: Vec::new(),
        };
        return compare_reply(&inputs, None, None, args.json);
    }
    let report_dir = crate::cli::output_directory(args.report.as_deref(), "reports/latest");
    eprintln!(
        "verify: writing the report into {} (every method against the references; about a \
         minute)",
        absolute(&report_dir)
    );
    let plan = report_jobs::report_parts(args.tol, &args.fem_tolerances);
    let mut bar = Progress::new(
        "report",
        plan.len() + crate::harness::report_jobs::REPORT_STAGES,
    );
    let assembled = report_jobs::compute_all(&plan, |id| bar.tick(id)).map_err(message)?;
    let report_jobs::Assembled::Report { mut inputs, .. } = assembled else {
        return Err("the report's parts did not make a report".into());
    };
    if let Some(fresh) = &args.fresh {
        let committed = crate::harness::settings::project_root().join("verify");
        inputs.baselines = baselines::compare(fresh, &committed).map_err(message)?;
    }
    let extras =
        crate::harness::report_jobs::write_report(&report_dir, &inputs, |stage| bar.tick(stage))
            .map_err(message)?;
    compare_reply(
        &CompareInputs::of(&inputs),
        Some(&report_dir),
        Some(&extras),
        args.json,
    )
}

/// What `verify compare` prints: the comparison and the stored external results.
pub(super) struct CompareInputs {
    pub comparison: comparison::ComparisonReport,
    pub fenicsx: Vec<fenicsx::FenicsxComparison>,
    pub peers: Vec<peers::PeerComparison>,
    pub operators: Vec<operator::OperatorStatus>,
    /// The stored Tamaas pull-offs against our simulations (with a report only).
    pub adhesion_peers: Vec<crate::harness::records::adhesion_peers::AdhesionPeerComparison>,
}

impl CompareInputs {
    /// The parts of a report's inputs `verify compare` prints.
    pub fn of(inputs: &document::ReportInputs) -> Self {
        Self {
            comparison: inputs.comparison.clone(),
            fenicsx: inputs.fenicsx.clone(),
            peers: inputs.peers.clone(),
            operators: inputs.operators.clone(),
            adhesion_peers: inputs.adhesion_peers.clone(),
        }
    }

    /// Checks that failed.
    pub fn failures(&self) -> usize {
        self.comparison.failures()
            + fenicsx::failures(&self.fenicsx)
            + operator::failures(&self.operators)
            + peers::failures(&self.peers)
            + crate::harness::records::adhesion_peers::failures(&self.adhesion_peers)
    }
}

/// The reply of `verify compare` (and `verify merge` of a report plan): tables or JSON, the
/// report's location, success when no check failed.
pub(super) fn compare_reply(
    inputs: &CompareInputs,
    report_dir: Option<&std::path::Path>,
    extras: Option<&document::ReportExtras>,
    json: bool,
) -> Result<Reply, String> {
    // With a report, its headline counts every check (error bars, fresh baselines too).
    let success = match extras {
        Some(e) => e.headline.failed == 0,
        None => inputs.failures() == 0,
    };
    let (comparison, external, operators, peer_rows) = (
        &inputs.comparison,
        &inputs.fenicsx,
        &inputs.operators,
        &inputs.peers,
    );
    if json {
        let all = serde_json::json!({
            "comparison": comparison,
            "fenicsx": external,
            "fenicsx_operators": operators,
            "peers": peer_rows,
            "adhesion_peers": inputs.adhesion_peers
        });
        return Ok(Reply::verdict(to_json(&all)?, success));
    }
    let mut text = comparison::render(comparison);
    text += &fenicsx::render(external);
    text += "\n";
    text += &operator::render_records(operators);
    text += &peers::render(peer_rows);
    if !inputs.adhesion_peers.is_empty() {
        text += "\n";
        text +=
            &crate::harness::records::adhesion_peers::table(&inputs.adhesion_peers).to_terminal();
    }
    let _ = writeln!(
        text,
        "\n{} of {} stored FEniCSx results compared, {} failed; {} peer comparisons, {} failed.",
        external.iter().filter(|r| r.status == "current").count(),
        external.len(),
        fenicsx::failures(external),
        peer_rows.len(),
        peers::failures(peer_rows)
    );
    if let Some(e) = extras {
        if !e.baselines.is_empty() {
            text += "\n";
            text += &baselines::table(&e.baselines).to_terminal();
        }
        let _ = writeln!(text, "{}", e.headline.sentence().replace("**", ""));
    }
    if let Some(dir) = report_dir {
        let _ = writeln!(
            text,
            "Report: {}/index.html (web page), report.md, report.json, SVG charts",
            absolute(dir)
        );
    }
    Ok(Reply::verdict(text, success))
}

/// `verify convergence`: one method refined level by level against the ring BEM; writes the CSV
/// and the chart into `--out`.
pub fn convergence(args: ConvergenceArgs) -> Result<Reply, String> {
    // A free band (two free edges): the FEM's free-edges family or the grid BEM, at `--depth` d/h.
    let punch = super::punch_kind_or_free_band(args.punch, args.exponent, args.profile.as_deref())?;
    let case = study_case(punch, args.eps, args.depth)?;
    let levels = args.levels as usize;
    let mut bar = Progress::new("convergence", levels);
    let study = convergence::run(case, args.method, levels, |level| {
        bar.tick(&format!(
            "{}: {} unknowns, {:.2} s",
            level.label, level.unknowns, level.wall_s
        ))
    })
    .map_err(message)?;
    let out = crate::cli::output_directory(args.out.as_deref(), "reports/convergence");
    let [csv_path, svg_path] = convergence::write_files(&study, &out).map_err(message)?;
    // A bar that does not bound the actual error, or a study cut short, is not a success.
    let success = convergence::failures(&study) == 0 && study.stopped.is_none();
    if args.json {
        return Ok(Reply::verdict(to_json(&study)?, success));
    }
    Ok(Reply::verdict(
        format!(
            "{}  wrote {} and {}\n",
            convergence::render(&study),
            absolute(&csv_path),
            absolute(&svg_path)
        ),
        success,
    ))
}

/// A range's end as people read it: `1e-12`, `0.3`, `1 - 1e-12`.
fn readable_bound(x: f64) -> String {
    if x > 0.0 && x < 1e-4 {
        format!("{x:.0e}")
    } else if x < 1.0 && 1.0 - x < 1e-4 {
        format!("1 - {:.0e}", 1.0 - x)
    } else {
        format!("{x}")
    }
}

/// `path` made absolute against the current directory, so that a message says where a file
/// went wherever the command ran.
pub(super) fn absolute(path: &std::path::Path) -> String {
    std::path::absolute(path)
        .unwrap_or_else(|_| path.to_path_buf())
        .display()
        .to_string()
}

/// The case of a convergence study from `--punch`, `--eps` (a fixed annulus only) and `--depth`,
/// checked.
pub(super) fn study_case(
    punch: PunchKind,
    eps: f64,
    depth: f64,
) -> Result<convergence::StudyCase, String> {
    let eps = if punch.has_fixed_hole() { eps } else { 0.0 };
    if !(0.0..1.0).contains(&eps) {
        return Err(format!("--eps {eps}: need 0 <= b/a < 1"));
    }
    if !(depth.is_finite() && depth > 0.0) {
        return Err(format!("--depth {depth}: need a positive d/h"));
    }
    Ok(convergence::StudyCase { punch, eps, depth })
}

/// `verify stability`: every method toward its limits; fails if any returned a wrong number
/// without an error.
pub fn stability(args: JsonArgs) -> Result<Reply, String> {
    let mut bar = Progress::new("stability", stability::PROBES);
    let probes = stability::run(|p| bar.tick(&format!("{} {}", p.method, p.probe)));
    let success = stability::wrong_numbers(&probes) == 0;
    let text = if args.json {
        to_json(&probes)?
    } else {
        stability::render(&probes)
    };
    Ok(Reply::verdict(text, success))
}

/// `verify history`: append the report's headline figures to the history, write the trend and
/// the web page with trend charts; fails on a regression.
pub fn history(args: HistoryArgs) -> Result<Reply, String> {
    let date = args.date.clone().unwrap_or_else(|| {
        args.report
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "run".into())
    });
    let current =
        history::headline(&args.report, &date, &args.fenicsx, &args.peers).map_err(message)?;
    let previous = history::append(&args.history, &current).map_err(message)?;
    let found = history::regressions(&current, previous.as_ref());
    let trend_path = args.report.join("trend.md");
    std::fs::write(
        &trend_path,
        history::trend(&args.history, 30).map_err(message)?,
    )
    .map_err(|e| format!("cannot write {}: {e}", trend_path.display()))?;
    let recorded = history::read_history(&args.history).map_err(message)?;
    let trend_csv = args.report.join("table-trend.csv");
    std::fs::write(
        &trend_csv,
        history::trend_table(&recorded, recorded.len())
            .to_csv()
            .map_err(message)?,
    )
    .map_err(|e| format!("cannot write {}: {e}", trend_csv.display()))?;
    let page = html::write_index(&args.report, Some(&recorded)).map_err(message)?;
    let mut text = format!("web page with trend charts: {}\n", page.display());
    let _ = writeln!(
        text,
        "history: {} ({} runs recorded); FEniCSx {}, peers {}",
        args.history.display(),
        recorded.len(),
        current.fenicsx,
        current.peers
    );
    if found.is_empty() {
        let _ = writeln!(
            text,
            "no regression against the tolerances{}",
            if previous.is_some() {
                " or the previous run"
            } else {
                " (first run)"
            }
        );
    }
    for r in &found {
        let _ = writeln!(text, "REGRESSION: {r}");
    }
    Ok(Reply::verdict(text, found.is_empty()))
}

/// `verify fit`: the paper's approximations refitted to ring-BEM data, and better forms.
pub fn fit(args: JsonArgs) -> Result<Reply, String> {
    let solver = RingBem::new();
    let reports = ringcontact::fit::run(&solver).map_err(message)?;
    if args.json {
        // One entry per function, keyed by its name.
        let map: serde_json::Map<String, serde_json::Value> = reports
            .iter()
            .map(|r| Ok((r.name.clone(), serde_json::to_value(r).map_err(message)?)))
            .collect::<Result<_, String>>()?;
        return Ok(Reply::ok(to_json(&map)?));
    }
    let mut t = Table::new(
        "Refits on ring-BEM data, 0.05 <= eps <= 0.99 (max relative error on 301 points, and where)",
        vec![
            Column::text("function", "function"),
            Column::text("variant", "variant"),
            Column::text("form", "form"),
            Column::text("params", "parameters"),
            Column::number("max_rel_err", "max rel. error", Format::Scientific(2)),
            Column::number("at_eps", "at eps", Format::Fixed(3)),
        ],
    );
    let rounded = |p: &[f64], digits: i32| -> String {
        let scale = 10f64.powi(digits);
        let shown: Vec<String> = p
            .iter()
            .map(|v| ((v * scale).round() / scale).to_string())
            .collect();
        shown.join(", ")
    };
    for r in &reports {
        let variants = [
            (
                "paper",
                &r.paper_form,
                rounded(&r.paper_params, 6),
                r.paper_max_rel_err,
                r.paper_max_rel_err_eps,
            ),
            (
                "refit",
                &r.paper_form,
                rounded(&r.params, 4),
                r.max_rel_err,
                r.max_rel_err_eps,
            ),
            (
                "best form",
                &r.best_form,
                rounded(&r.best_params, 6),
                r.best_max_rel_err,
                r.best_max_rel_err_eps,
            ),
        ];
        for (variant, form, params, err, at) in variants {
            t.push(vec![
                r.name.clone().into(),
                variant.into(),
                form.clone().into(),
                params.into(),
                err.into(),
                at.into(),
            ]);
        }
    }
    Ok(Reply::ok(t.to_terminal()))
}

/// `verify references`: the analytic references and where each is valid.
pub fn references(args: JsonArgs) -> Result<Reply, String> {
    if args.json {
        return Ok(Reply::ok(to_json(&reference::catalogue())?));
    }
    let mut t = Table::new(
        "Analytic references",
        vec![
            Column::text("name", "name"),
            Column::text("quantity", "quantity"),
            Column::text("kind", "kind"),
            Column::text("valid_eps", "valid eps"),
            Column::text("source", "source"),
        ],
    );
    for r in reference::catalogue() {
        t.push(vec![
            r.name.into(),
            r.quantity.label().into(),
            r.kind.label().into(),
            format!(
                "[{}, {}]",
                readable_bound(r.eps_range.0),
                readable_bound(r.eps_range.1)
            )
            .into(),
            r.source.into(),
        ]);
    }
    Ok(Reply::ok(format!(
        "{}\n{}",
        t.to_terminal(),
        punch_table().to_terminal()
    )))
}

/// The built-in punches: the flags that name each, its gap, its edges and its closed forms.
fn punch_table() -> Table {
    let mut t = Table::new(
        "Punches (gap g(r) at zero depth; contact b <= r <= a, or b <= r <= c for a free band)",
        vec![
            Column::text("flags", "flags"),
            Column::text("gap", "gap g(r)"),
            Column::text("edges", "edges"),
            Column::text("closed_forms", "closed forms"),
        ],
    );
    for name in PunchName::ALL {
        let row = name.summary();
        t.push(vec![
            row.flags.into(),
            row.gap.into(),
            row.edges.into(),
            row.closed_forms.into(),
        ]);
    }
    t
}
