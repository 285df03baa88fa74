//! The plan commands: `plan` (the suite as independent jobs), `run` (one shard of them),
//! `merge` (the report from their result files) and `part` (one job).

use std::fmt::Write as _;

use super::{message, to_json, Reply};
use crate::cli::args::{MergeArgs, PartArgs, PlanArgs, RunArgs};
use crate::cli::studies::{compare_reply, study_case, CompareInputs};
use crate::harness::plan::{self, Plan};
use crate::harness::progress::Progress;
use crate::harness::report::document;
use crate::harness::report_jobs::{self, Assembled, EdgeMemo, Part};
use crate::harness::studies::convergence;
use crate::harness::studies::stability;

/// FEM tolerances of the nightly suite's speed-accuracy jobs.
const NIGHTLY_FEM_TOLERANCES: [f64; 4] = [1e-3, 1e-4, 1e-6, 1e-8];

/// `verify plan`: the default report, the nightly suite or a convergence study as a plan.
pub fn plan(args: PlanArgs) -> Result<Reply, String> {
    if !(args.tol.is_finite() && args.tol > 0.0 && args.tol < 1.0) {
        return Err(format!("--tol {}: need 0 < tol < 1", args.tol));
    }
    let floor = ringcontact::methods::Fem::MIN_TOLERANCE;
    if let Some(t) = args
        .fem_tolerances
        .iter()
        .flatten()
        .find(|&&t| !(t >= floor && t < 1.0))
    {
        return Err(format!(
            "--fem-tolerances: {t} is outside [{floor:e}, 1), the FEM's tolerance range"
        ));
    }
    let the_plan = if args.convergence {
        let (Some(name), Some(method)) = (args.punch, args.method) else {
            return Err("--convergence needs --punch and --method".into());
        };
        let punch = super::punch_kind(name, args.exponent)?;
        // A flat-faced punch's study does not depend on --depth: the plan names one value.
        let depth = if punch.is_concave() { args.depth } else { 1.5 };
        let case = study_case(punch.clone(), args.eps, depth)?;
        let levels = args.levels as usize;
        // Refuse a study that cannot run before anything is submitted.
        convergence::check_levels(&case, method, levels).map_err(message)?;
        Plan::new(
            &format!(
                "verify plan --convergence --punch {punch} --method {} --levels {levels} --eps {} --depth {}",
                method.name(),
                case.eps,
                case.depth
            ),
            report_jobs::convergence_parts(case, method, levels),
        )
    } else if args.nightly {
        let tolerances = args
            .fem_tolerances
            .unwrap_or(NIGHTLY_FEM_TOLERANCES.to_vec());
        Plan::new(
            &format!(
                "verify plan --nightly --tol {:e} --fem-tolerances {}",
                args.tol,
                list(&tolerances)
            ),
            report_jobs::nightly_parts(args.tol, &tolerances),
        )
    } else {
        let tolerances = args
            .fem_tolerances
            .unwrap_or(document::DEFAULT_FEM_TOLERANCES.to_vec());
        Plan::new(
            &format!(
                "verify plan --tol {:e} --fem-tolerances {}",
                args.tol,
                list(&tolerances)
            ),
            report_jobs::report_parts(args.tol, &tolerances),
        )
    };
    let text = the_plan.to_text();
    match args.out {
        Some(path) => {
            std::fs::write(&path, &text)
                .map_err(|e| format!("cannot write the plan to {}: {e}", path.display()))?;
            Ok(Reply::ok(format!(
                "wrote {} ({} jobs)\n",
                path.display(),
                the_plan.jobs.len()
            )))
        }
        None => Ok(Reply::ok(text)),
    }
}

fn list(values: &[f64]) -> String {
    values
        .iter()
        .map(|t| format!("{t:e}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// `verify run`: one shard of a plan, each job in its own process.
pub fn run(args: RunArgs) -> Result<Reply, String> {
    let the_plan = Plan::read(&args.plan).map_err(message)?;
    let (index, count) = args.shard;
    let executable = std::env::current_exe()
        .map_err(|e| format!("cannot find this program's own path to run the jobs: {e}"))?;
    // One line per job on standard error (the shard's log under Slurm): which job, whether it
    // succeeded, how long it took.
    let done = plan::run_shard(
        &the_plan,
        index,
        count,
        &args.results,
        &executable,
        |line| eprintln!("{line}"),
    )
    .map_err(message)?;
    let mut text = format!(
        "shard {index}/{count} of {}: {} jobs in {:.1} s, results in {}\n",
        args.plan.display(),
        done.ran,
        done.wall_s,
        args.results.display()
    );
    for id in &done.failed {
        let _ = writeln!(text, "FAILED: {id} (its file holds the error)");
    }
    Ok(Reply::verdict(text, done.failed.is_empty()))
}

/// `verify merge`: the report (or convergence studies) from a plan's result files.
pub fn merge(args: MergeArgs) -> Result<Reply, String> {
    let the_plan = Plan::read(&args.plan).map_err(message)?;
    let results = plan::load_results(&the_plan, &args.results).map_err(message)?;
    match report_jobs::assemble(results).map_err(message)? {
        Assembled::Report { inputs, stability } => {
            let mut bar = Progress::new("merge", crate::harness::report_jobs::REPORT_STAGES);
            let extras =
                crate::harness::report_jobs::write_report(&args.report, &inputs, |stage| {
                    bar.tick(stage)
                })
                .map_err(message)?;
            let mut reply = compare_reply(
                &CompareInputs::of(&inputs),
                Some(&args.report),
                Some(&extras),
                args.json,
            )?;
            if let Some(probes) = stability {
                let path = args.report.join("stability.json");
                std::fs::write(&path, to_json(&probes)?)
                    .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
                let wrong = stability::wrong_numbers(&probes);
                if !args.json {
                    let _ = writeln!(
                        reply.text,
                        "Stability: {} probes, {wrong} wrong numbers ({})",
                        probes.len(),
                        path.display()
                    );
                }
                reply.success &= wrong == 0;
            }
            Ok(reply)
        }
        Assembled::Convergence(studies) => {
            let mut text = String::new();
            for study in &studies {
                let [csv_path, svg_path] =
                    convergence::write_files(study, &args.report).map_err(message)?;
                let _ = writeln!(
                    text,
                    "{}  wrote {} and {}",
                    convergence::render(study),
                    csv_path.display(),
                    svg_path.display()
                );
            }
            if args.json {
                return Ok(Reply::ok(to_json(&studies)?));
            }
            Ok(Reply::ok(text))
        }
    }
}

/// `verify part`: one job, its record printed as JSON (exit status 1 when it failed; the
/// record then holds the error).
pub fn part(args: PartArgs) -> Result<Reply, String> {
    let part = Part::from_id(&args.id).map_err(message)?;
    let record = part.record(&mut EdgeMemo::new());
    let success = record.error.is_none();
    if let Some(e) = &record.error {
        eprintln!("error: job {}: {e}", record.id);
    }
    Ok(Reply::verdict(to_json(&record)?, success))
}
