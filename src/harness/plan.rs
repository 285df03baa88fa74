//! A plan of independent jobs, run in shards and merged: the engine a Slurm job array drives.
//!
//! `verify plan` writes the suite as a [`Plan`]: one line per job, tab-separated, `id`,
//! `expected_s`, `output` (its file in a results directory) and `command` (the exact `verify`
//! command; it prints the job's [`JobRecord`] on standard output). The plan depends only on its
//! arguments, so it is the same from run to run. `verify run --shard I/N` runs the jobs of shard
//! `I` ([`Plan::shard`]: longest expected time first, each to the least-loaded shard, ties to the
//! lower index), each in its own process, writing one file per job (an error record when the job
//! fails, never nothing). `verify merge` reads every job's file ([`load_results`]) and builds the
//! report with the code a single-process run uses ([`crate::harness::report_jobs::assemble`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use crate::harness::report_jobs::{JobRecord, Part, PartResult};
use ringcontact::error::{Error, Result};

/// The first line of every plan file.
const MAGIC: &str = "# ringcontact plan v1";
/// The column header line.
const COLUMNS: &str = "id\texpected_s\toutput\tcommand";

/// One job of a plan.
#[derive(Clone, Debug, PartialEq)]
pub struct Job {
    pub part: Part,
    /// Expected wall time, seconds (the balance of the shards).
    pub expected_s: f64,
    /// File of its record in the results directory.
    pub output: String,
    /// The `verify` command that runs it.
    pub command: String,
}

/// A suite as a list of independent jobs.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// What the plan computes (the `verify plan` arguments that made it).
    pub title: String,
    pub jobs: Vec<Job>,
}

impl Plan {
    /// The plan of `parts`, in their order.
    pub fn new(title: &str, parts: Vec<Part>) -> Plan {
        Plan {
            title: title.to_string(),
            jobs: parts
                .into_iter()
                .map(|part| Job {
                    expected_s: part.expected_s(),
                    output: part.output_file(),
                    command: part.command(),
                    part,
                })
                .collect(),
        }
    }

    /// The plan file: two comment lines, the column header, one tab-separated line per job.
    pub fn to_text(&self) -> String {
        let mut text = format!("{MAGIC}: {}\n", self.title);
        let total: f64 = self.jobs.iter().map(|j| j.expected_s).sum();
        let _ = writeln!(
            text,
            "# {} jobs, about {total:.0} s on one core; run with `verify run --plan FILE --shard I/N --results DIR`, then `verify merge`",
            self.jobs.len()
        );
        text += COLUMNS;
        text.push('\n');
        for j in &self.jobs {
            let _ = writeln!(
                text,
                "{}\t{}\t{}\t{}",
                j.part.id(),
                j.expected_s,
                j.output,
                j.command
            );
        }
        text
    }

    /// Parse a plan file's text (`origin` names it in errors). Every line must be a job this
    /// build knows, with the output file and command its id implies, each id once.
    pub fn parse(text: &str, origin: &str) -> Result<Plan> {
        let bad = |line: usize, why: String| Error::Plan(format!("{origin}, line {line}: {why}"));
        let mut lines = text.lines().enumerate();
        let title = match lines.next() {
            Some((_, first)) if first.starts_with(MAGIC) => first[MAGIC.len()..]
                .trim_start_matches(':')
                .trim()
                .to_string(),
            _ => {
                return Err(Error::Plan(format!(
                    "{origin} is not a plan file (its first line is not `{MAGIC}: ...`; make one with `verify plan`)"
                )))
            }
        };
        let mut jobs: Vec<Job> = Vec::new();
        for (k, line) in lines {
            let n = k + 1;
            if line.starts_with('#') || line.trim().is_empty() || line == COLUMNS {
                continue;
            }
            let cols: Vec<&str> = line.split('\t').collect();
            let [id, expected, output, command] = cols[..] else {
                return Err(bad(
                    n,
                    format!("{} columns, expected 4 ({COLUMNS})", cols.len()),
                ));
            };
            let part = Part::from_id(id).map_err(|e| bad(n, e.to_string()))?;
            let expected_s = expected
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x >= 0.0)
                .ok_or_else(|| bad(n, format!("expected_s `{expected}` is not a time")))?;
            if output != part.output_file() || command != part.command() {
                return Err(bad(
                    n,
                    format!(
                        "job `{id}` must write `{}` with `{}`",
                        part.output_file(),
                        part.command()
                    ),
                ));
            }
            if jobs.iter().any(|j| j.part == part) {
                return Err(bad(n, format!("job `{id}` appears twice")));
            }
            jobs.push(Job {
                part,
                expected_s,
                output: output.to_string(),
                command: command.to_string(),
            });
        }
        if jobs.is_empty() {
            return Err(Error::Plan(format!("{origin} has no jobs")));
        }
        Ok(Plan { title, jobs })
    }

    /// Read and parse a plan file.
    pub fn read(path: &Path) -> Result<Plan> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::file("read", path, e))?;
        Plan::parse(&text, &path.display().to_string())
    }

    /// The jobs of shard `index` of `count` (from 1), in plan order. Jobs go, longest expected
    /// time first (ties in plan order), each to the shard with the least expected time so far
    /// (ties to the lower index): deterministic, and within the longest job of balanced.
    pub fn shard(&self, index: usize, count: usize) -> Result<Vec<&Job>> {
        if count == 0 || index == 0 || index > count {
            return Err(Error::Plan(format!(
                "shard {index}/{count}: need 1 <= I <= N"
            )));
        }
        let mut order: Vec<usize> = (0..self.jobs.len()).collect();
        order.sort_by(|&a, &b| {
            self.jobs[b]
                .expected_s
                .total_cmp(&self.jobs[a].expected_s)
                .then(a.cmp(&b))
        });
        let mut load = vec![0.0f64; count];
        let mut owner = vec![0usize; self.jobs.len()];
        for j in order {
            let lightest = (0..count)
                .min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b)))
                .unwrap_or(0);
            load[lightest] += self.jobs[j].expected_s;
            owner[j] = lightest;
        }
        Ok(self
            .jobs
            .iter()
            .zip(owner)
            .filter(|(_, o)| *o == index - 1)
            .map(|(j, _)| j)
            .collect())
    }
}

/// `I/N` of `--shard` as (I, N).
pub(crate) fn parse_shard(text: &str) -> std::result::Result<(usize, usize), String> {
    let (i, n) = text
        .split_once('/')
        .ok_or_else(|| format!("`{text}`: write the shard as I/N, e.g. 2/3"))?;
    let parse = |s: &str| {
        s.trim()
            .parse::<usize>()
            .map_err(|_| format!("`{text}`: `{s}` is not a whole number"))
    };
    let (i, n) = (parse(i)?, parse(n)?);
    if n == 0 || i == 0 || i > n {
        return Err(format!("`{text}`: need 1 <= I <= N"));
    }
    Ok((i, n))
}

/// What a shard's run did.
#[derive(Debug, Default)]
pub struct ShardRun {
    pub ran: usize,
    /// Ids of the jobs that failed (their files hold error records).
    pub failed: Vec<String>,
    pub wall_s: f64,
}

/// The last `n` lines of `text`.
fn tail(text: &str, n: usize) -> String {
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

/// Write `text` to `path` through a temporary file and a rename, so that a reader never sees a
/// half-written record.
fn write_atomically(path: &Path, text: &str) -> Result<()> {
    let tmp = path.with_extension("json.part");
    std::fs::write(&tmp, text).map_err(|e| Error::file("write", &tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| Error::file("rename into place", path, e))
}

/// Run one job in its own process (`verify` is `executable`) and write its record into
/// `results`; returns whether it succeeded.
fn run_job(executable: &Path, job: &Job, results: &Path) -> Result<bool> {
    let start = Instant::now();
    let args: Vec<&str> = job.command.split_whitespace().skip(1).collect();
    // The job reads the data directory this process reads (`--data-dir` is not inherited).
    let mut command = Command::new(executable);
    if let Ok(root) = crate::harness::settings::find_data().map(|data| data.root) {
        command.env(crate::harness::settings::DATA_DIR_VARIABLE, root);
        command.env(
            ringcontact::sparse::ENVIRONMENT_VARIABLE,
            crate::harness::settings::linear_solver().name(),
        );
    }
    let output = command.args(&args).output();
    let wall_s = start.elapsed().as_secs_f64();
    let failure = |why: String| JobRecord {
        id: job.part.id(),
        command: job.command.clone(),
        wall_s,
        result: None,
        error: Some(why),
    };
    let record = match output {
        Err(e) => failure(format!("could not start {}: {e}", executable.display())),
        Ok(out) => {
            let stdout = String::from_utf8_lossy(&out.stdout);
            match serde_json::from_str::<JobRecord>(&stdout) {
                Ok(r) if r.id == job.part.id() => r,
                _ => failure(format!(
                    "exit status {}{}; standard error ends:\n{}",
                    out.status
                        .code()
                        .map_or("none (killed by a signal)".into(), |c| c.to_string()),
                    if out.status.success() {
                        ", but standard output is not the job's record"
                    } else {
                        ""
                    },
                    tail(&String::from_utf8_lossy(&out.stderr), 20)
                )),
            }
        }
    };
    let ok = record.error.is_none() && record.result.is_some();
    let text = serde_json::to_string_pretty(&record)
        .map_err(|e| Error::Plan(format!("job `{}`: {e}", job.part.id())))?;
    write_atomically(&results.join(&job.output), &(text + "\n"))?;
    Ok(ok)
}

/// Run shard `index` of `count` of `plan`, one process per job (`executable`, normally this
/// `verify`), writing each job's record into `results`; `progress` gets a line per job.
pub fn run_shard(
    plan: &Plan,
    index: usize,
    count: usize,
    results: &Path,
    executable: &Path,
    mut progress: impl FnMut(&str),
) -> Result<ShardRun> {
    let start = Instant::now();
    std::fs::create_dir_all(results).map_err(|e| Error::file("create", results, e))?;
    let jobs = plan.shard(index, count)?;
    let mut run = ShardRun::default();
    for (k, job) in jobs.iter().enumerate() {
        let job_start = Instant::now();
        let ok = run_job(executable, job, results)?;
        run.ran += 1;
        if !ok {
            run.failed.push(job.part.id());
        }
        progress(&format!(
            "shard {index}/{count}: job {} of {}: {} {} ({:.1} s)",
            k + 1,
            jobs.len(),
            job.part.id(),
            if ok { "done" } else { "FAILED" },
            job_start.elapsed().as_secs_f64()
        ));
    }
    run.wall_s = start.elapsed().as_secs_f64();
    Ok(run)
}

/// Every job's result from `results`, in plan order, with its wall time. Fails naming every
/// job whose file is missing, unreadable, for another job, or an error record.
pub fn load_results(plan: &Plan, results: &Path) -> Result<Vec<(Part, PartResult, f64)>> {
    let mut out = Vec::new();
    let mut problems = Vec::new();
    for job in &plan.jobs {
        let path: PathBuf = results.join(&job.output);
        let text = match std::fs::read_to_string(&path) {
            Ok(t) => t,
            Err(_) => {
                problems.push(format!("{}: missing ({})", job.part.id(), path.display()));
                continue;
            }
        };
        match serde_json::from_str::<JobRecord>(&text) {
            Err(e) => problems.push(format!(
                "{}: unreadable ({}: {e})",
                job.part.id(),
                path.display()
            )),
            Ok(r) if r.id != job.part.id() => problems.push(format!(
                "{}: {} holds the record of job `{}`",
                job.part.id(),
                path.display(),
                r.id
            )),
            Ok(JobRecord {
                error: Some(why), ..
            }) => problems.push(format!(
                "{}: failed: {}",
                job.part.id(),
                why.lines().next().unwrap_or_default()
            )),
            Ok(JobRecord {
                result: Some(result),
                wall_s,
                ..
            }) => out.push((job.part.clone(), result, wall_s)),
            Ok(_) => problems.push(format!("{}: the record has no result", job.part.id())),
        }
    }
    if !problems.is_empty() {
        return Err(Error::Plan(format!(
            "{} of {} jobs have no usable result in {}:\n  {}",
            problems.len(),
            plan.jobs.len(),
            results.display(),
            problems.join("\n  ")
        )));
    }
    Ok(out)
}
