//! The work of a report as independent parts: each [`Part`] is one job of a plan
//! ([`crate::harness::plan`]), runs on its own (`verify part ID`, printing a [`JobRecord`]) and
//! needs no other part's result. [`assemble`] joins the results, in the plan's order, into the
//! [`ReportInputs`] the report is written from, so one process ([`compute_all`]) and a sharded run
//! merged from files build their report from the same pieces by the same code.
//!
//! A part's id names everything it computes: `kind[:argument][:key=value]...`, e.g.
//! `comparison:tol=1e-6`, `speed:PROBLEM:fem-tol=1e-8`,
//! `convergence:PUNCH:fem:eps=0:depth=1.5:level=2:of=3`, `pulloff:PUNCH:d0h=10`.

use std::collections::HashMap;
use std::sync::{Condvar, Mutex};
use std::time::Instant;

use ringcontact::choice::Choice;
use serde::{Deserialize, Serialize};

use crate::harness::cases;
use crate::harness::records::adhesion_peers::{self, AdhesionPeerComparison};
use crate::harness::records::fenicsx::{self, FenicsxComparison};
use crate::harness::records::operator::{self, OperatorStatus};
use crate::harness::records::peers::{self, PeerComparison};
use crate::harness::records::pulloff::{self, PulloffRecord};
use crate::harness::report::document::{self, Findings, PulloffPoint, ReportExtras, ReportInputs};
use crate::harness::studies::comparison::{self, ComparisonReport};
use crate::harness::studies::convergence::{self, ComputedLevel, StudyCase};
use crate::harness::studies::speed_accuracy::{self, BasePoints, CostPoint, Problem};
use crate::harness::studies::stability::{self, Probe};
use crate::harness::studies::{claims, figures};
use ringcontact::cohesive::study::{self, LiveSimulation};
use ringcontact::error::{Error, Result};
use ringcontact::methods::Method;
use ringcontact::methods::RingBem;
use ringcontact::punch::{Contact, PunchKind};

/// Grid size up to which the stored peer results are compared (as `verify compare`).
pub(crate) const PEER_MAX_GRID: usize = 256;

/// One independent piece of work.
#[derive(Clone, Debug, PartialEq)]
pub enum Part {
    /// The ring BEM against the references, the identities, the FEM cross-checks.
    Comparison { tolerance: f64 },
    /// The stored FEniCSx results against this build.
    Fenicsx,
    /// The stored peer (Tamaas, ContactMechanics) results against this build's grid BEM.
    Peers,
    /// The stored FEniCSx operator comparisons.
    Operators,
    /// A speed-accuracy problem's yardstick and base points.
    SpeedBase(Problem),
    /// The FEM's full solve at one tolerance on a speed-accuracy problem.
    SpeedFem { problem: Problem, tolerance: f64 },
    /// One level of a convergence study.
    ConvergenceLevel {
        punch: PunchKind,
        method: Method,
        eps: f64,
        depth: f64,
        level: usize,
        levels: usize,
    },
    /// Pull-off against `d0/h` by the JKR routes, one concave punch.
    Adhesion(PunchKind),
    /// The report's single live pull-off simulation.
    PulloffLive,
    /// Our pull-off simulations against the stored Tamaas ones.
    AdhesionPeers,
    /// One pull-off simulation of `verify pulloff` (nightly).
    PulloffSimulation {
        punch: PunchKind,
        eps: f64,
        d0_over_h: f64,
    },
    /// The stability probes of `verify stability` (nightly).
    Stability,
}

/// What a part computed.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(tag = "part", content = "value", rename_all = "snake_case")]
#[allow(clippy::large_enum_variant)]
pub enum PartResult {
    Comparison(ComparisonReport),
    Fenicsx(Vec<FenicsxComparison>),
    Peers(Vec<PeerComparison>),
    Operators(Vec<OperatorStatus>),
    SpeedBase(BasePoints),
    SpeedFem(Option<CostPoint>),
    ConvergenceLevel(ComputedLevel),
    Adhesion(Vec<PulloffPoint>),
    PulloffLive(std::result::Result<LiveSimulation, String>),
    AdhesionPeers(Vec<AdhesionPeerComparison>),
    PulloffSimulation(PulloffRecord),
    Stability(Vec<Probe>),
}

/// The file a job writes: its id, its command, its wall time and its result or its error.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct JobRecord {
    pub id: String,
    pub command: String,
    pub wall_s: f64,
    /// The result, absent when the job failed.
    #[serde(default)]
    pub result: Option<PartResult>,
    /// Why the job failed (the error, or the exit status and the end of standard error).
    #[serde(default)]
    pub error: Option<String>,
}

fn fmt_sci(x: f64) -> String {
    format!("{x:e}")
}

impl Part {
    /// The id: the part's kind and every parameter (see the module's documentation).
    pub fn id(&self) -> String {
        match self {
            Part::Comparison { tolerance } => format!("comparison:tol={}", fmt_sci(*tolerance)),
            Part::Fenicsx => "fenicsx".into(),
            Part::Peers => "peers".into(),
            Part::Operators => "operators".into(),
            Part::SpeedBase(p) => format!("speed:{}", p.slug()),
            Part::SpeedFem { problem, tolerance } => {
                format!("speed:{}:fem-tol={}", problem.slug(), fmt_sci(*tolerance))
            }
            Part::ConvergenceLevel {
                punch,
                method,
                eps,
                depth,
                level,
                levels,
            } => format!(
                "convergence:{}:{}:eps={eps}:depth={depth}:level={level}:of={levels}",
                punch.label(),
                method.name()
            ),
            Part::Adhesion(kind) => format!("adhesion:{}", kind.label()),
            Part::PulloffLive => "pulloff-live".into(),
            Part::AdhesionPeers => "adhesion-peers".into(),
            Part::PulloffSimulation {
                punch,
                eps,
                d0_over_h,
            } => match punch {
                p if p.has_fixed_hole() => format!("pulloff:{}:eps={eps}", punch.name()),
                p if p.is_concave() => format!("pulloff:{}:d0h={d0_over_h}", punch.label()),
                p => format!("pulloff:{}", p.name()),
            },
            Part::Stability => "stability".into(),
        }
    }

    /// The part an id names; an error says what is wrong with it.
    pub fn from_id(id: &str) -> Result<Part> {
        let job = JobId::parse(id)?;
        let part = match job.kind {
            "comparison" => Part::Comparison {
                tolerance: job.number("tol")?,
            },
            "fenicsx" => Part::Fenicsx,
            "peers" => Part::Peers,
            "operators" => Part::Operators,
            "pulloff-live" => Part::PulloffLive,
            "adhesion-peers" => Part::AdhesionPeers,
            "stability" => Part::Stability,
            "speed" => job.speed_part()?,
            "convergence" => {
                let method = job.positional(1).ok_or_else(|| job.bad("needs a method"))?;
                Part::ConvergenceLevel {
                    punch: job.punch()?,
                    method: Method::named(method)
                        .ok_or_else(|| job.bad(&format!("no method `{method}`")))?,
                    eps: job.number("eps")?,
                    depth: job.number("depth")?,
                    level: job.count("level")?,
                    levels: job.count("of")?,
                }
            }
            "adhesion" => Part::Adhesion(job.punch()?),
            "pulloff" => {
                let punch = job.punch()?;
                Part::PulloffSimulation {
                    punch: punch.clone(),
                    eps: if punch.has_fixed_hole() {
                        job.number("eps")?
                    } else {
                        0.0
                    },
                    d0_over_h: if punch.is_concave() {
                        job.number("d0h")?
                    } else {
                        0.0
                    },
                }
            }
            _ => return Err(job.bad("unknown kind of job")),
        };
        // Only the canonical spelling is accepted, so that an id names one file.
        if part.id() != id {
            return Err(job.bad(&format!("write it as `{}`", part.id())));
        }
        Ok(part)
    }

    /// The `verify` command that runs this part and prints its [`JobRecord`].
    pub fn command(&self) -> String {
        format!("verify part {}", self.id())
    }

    /// The file of its record in a results directory.
    pub fn output_file(&self) -> String {
        format!("{}.json", self.id().replace(':', "_"))
    }

    /// Expected wall time in seconds on the 2-core development machine with gmsh and a warm
    /// mesh cache (from the records of `verify run` on the nightly plan; the README's cost
    /// table). Only the balance of the shards depends on it.
    pub fn expected_s(&self) -> f64 {
        match self {
            Part::Comparison { .. } => 1.0,
            Part::Fenicsx => 9.0,
            Part::Peers => 7.7,
            Part::Operators => 0.1,
            Part::SpeedBase(p) => p.expected_s(),
            Part::SpeedFem { tolerance, .. } => {
                if *tolerance >= 1e-3 {
                    0.1
                } else if *tolerance >= 1e-4 {
                    0.2
                } else if *tolerance >= 1e-6 {
                    0.6
                } else {
                    // 4.8 (fixed annulus 0.5) to 12.8 s (parabolic gap).
                    9.0
                }
            }
            // Grid BEM: 64² .. ; the FEM's level k also solves the coarser ones for their free
            // edges (concave punches).
            Part::ConvergenceLevel { method, level, .. } => match method {
                Method::GridBem => 0.03 * 6f64.powi(*level as i32),
                Method::Fem => 0.08 * 2.3f64.powi(*level as i32),
                _ => 0.01,
            },
            // Alone on 2 cores: the concave punches 0.9-1.2 s (one branch for every
            // d0/h), the report's table 2.7 s, a free band 3.7 s; the live simulation 9.5 s (one
            // core), the Tamaas cases 15 s.
            Part::Adhesion(p) if p.is_free_band() => 3.7,
            Part::Adhesion(p) if p.piecewise().is_some() => 2.7,
            Part::Adhesion(_) => 1.2,
            Part::PulloffLive => 9.5,
            Part::AdhesionPeers => 15.0,
            // Small d0/h: pressed deeper until the hole closes, and ranges where it reopens
            // replaced by smaller ones (alone on 2 cores: linear gap 0.3 224 s, parabolic gap 0.3
            // 155 s, linear gap and parabolic gap 1 45-48 s).
            Part::PulloffSimulation {
                punch, d0_over_h, ..
            } => match punch.contact() {
                Contact::Disk => 15.0,
                Contact::FixedAnnulus => 50.0,
                _ if punch.power_law_exponent() == Some(1.0) && *d0_over_h <= 0.5 => 225.0,
                _ if *d0_over_h <= 0.5 => 155.0,
                _ if *d0_over_h <= 1.0 => 47.0,
                _ => 13.0,
            },
            Part::Stability => 3.5,
        }
    }

    /// Whether the part's wall times are among its results (speed-accuracy points, the
    /// convergence levels' costs, our time over FEniCSx's): [`compute_all`] runs these alone,
    /// the others side by side (the stored peers' comparison reports forces; its times are
    /// records only).
    pub(crate) fn is_timed(&self) -> bool {
        matches!(
            self,
            Part::Comparison { .. }
                | Part::Fenicsx
                | Part::SpeedBase(_)
                | Part::SpeedFem { .. }
                | Part::ConvergenceLevel { .. }
        )
    }

    /// Whether the part keeps every core busy itself (the cohesive simulations run side by
    /// side, the stability probes): [`compute_all`] runs no two of these side by side. The live
    /// pull-off is one simulation on one thread.
    pub(crate) fn uses_every_core(&self) -> bool {
        matches!(
            self,
            Part::AdhesionPeers | Part::PulloffSimulation { .. } | Part::Stability
        )
    }

    /// Run the part in this process (`edges` carries the free edges of convergence levels
    /// already computed here, so that one process does not solve a coarser level twice).
    pub(crate) fn compute(&self, edges: &mut EdgeMemo) -> Result<PartResult> {
        let ring = RingBem::new();
        Ok(match self.clone() {
            Part::Comparison { tolerance } => PartResult::Comparison(comparison::run(tolerance)?),
            Part::Fenicsx => PartResult::Fenicsx(fenicsx::run()?),
            Part::Peers => PartResult::Peers(peers::run(PEER_MAX_GRID)?),
            Part::Operators => PartResult::Operators(operator::load_records()?),
            Part::SpeedBase(problem) => {
                PartResult::SpeedBase(speed_accuracy::base_points(&ring, problem)?)
            }
            Part::SpeedFem { problem, tolerance } => {
                let yardstick = problem.yardstick(&ring)?;
                PartResult::SpeedFem(speed_accuracy::ladder_point(problem, yardstick, tolerance))
            }
            Part::ConvergenceLevel {
                punch,
                method,
                eps,
                depth,
                level,
                levels,
            } => {
                let case = StudyCase { punch, eps, depth };
                let key = (self.study_key(), level);
                let known = level
                    .checked_sub(1)
                    .and_then(|k| edges.get(&(key.0.clone(), k)).copied());
                let computed = match known {
                    Some(edge) => convergence::level_after(case, method, level, levels, edge)?,
                    None => convergence::level(case, method, level, levels)?,
                };
                edges.insert(key, computed.free_edge);
                PartResult::ConvergenceLevel(computed)
            }
            Part::Adhesion(kind) => PartResult::Adhesion(claims::pulloff_points(&ring, kind)?),
            Part::PulloffLive => {
                PartResult::PulloffLive(claims::live_pulloff().map_err(|e| e.to_string()))
            }
            Part::AdhesionPeers => PartResult::AdhesionPeers(adhesion_peers::run()?),
            Part::PulloffSimulation {
                punch,
                eps,
                d0_over_h,
            } => PartResult::PulloffSimulation(pulloff_simulation(punch, eps, d0_over_h)),
            Part::Stability => PartResult::Stability(stability::run(|_| {})),
        })
    }

    /// The convergence study a level belongs to (the levels of one study share it).
    fn study_key(&self) -> String {
        match self {
            Part::ConvergenceLevel {
                punch,
                method,
                eps,
                depth,
                levels,
                ..
            } => format!("{}:{}:{eps}:{depth}:{levels}", punch.label(), method.name()),
            _ => self.id(),
        }
    }

    /// Run the part and wrap its result (or its error) with its id, command and time.
    pub fn record(&self, edges: &mut EdgeMemo) -> JobRecord {
        let start = Instant::now();
        let outcome = self.compute(edges);
        let wall_s = start.elapsed().as_secs_f64();
        let (result, error) = match outcome {
            Ok(r) => (Some(r), None),
            Err(e) => (None, Some(e.to_string())),
        };
        JobRecord {
            id: self.id(),
            command: self.command(),
            wall_s,
            result,
            error,
        }
    }
}

/// Free edges found by convergence levels run in this process: (study, level) -> edge.
pub(crate) type EdgeMemo = HashMap<(String, usize), Option<f64>>;

/// A pull-off simulation as `verify pulloff --json` runs it (the study meshes, the default
/// ranges), recorded like `scripts/pulloff/run_all.py` records it: its result, or the reason it
/// declined the case.
fn pulloff_simulation(punch: PunchKind, eps: f64, d0_over_h: f64) -> PulloffRecord {
    let mut command = format!("verify pulloff {}", punch.flags());
    if punch.has_fixed_hole() {
        command += &format!(" --eps {eps}");
    }
    if punch.is_concave() {
        command += &format!(" --d0h {d0_over_h}");
    }
    command += " --json";
    let case = study::Case {
        punch: punch.clone(),
        eps,
        d0_over_h,
        linear_solver: crate::harness::settings::linear_solver(),
        data: crate::harness::settings::data_paths(),
    };
    let outcome = study::run_on_study_meshes(
        case,
        &study::default_ranges(&crate::harness::settings::data_paths()),
        |_| {},
    );
    let file = match &punch {
        p if p.has_fixed_hole() => format!("{}-{eps}.json", p.name()),
        p if p.is_concave() => format!("{}-d0h{d0_over_h}.json", p.label()),
        p => format!("{}.json", p.name()),
    };
    let (result, declined) = match outcome {
        Ok(r) => (Some(r), None),
        Err(e) => (None, Some(format!("error: {e}"))),
    };
    PulloffRecord {
        file,
        date: crate::harness::report::html::utc_now_iso(),
        command,
        result,
        declined,
    }
}

/// The parts of the default report (`verify compare --report`): the comparison at `tolerance`,
/// the stored external results, each speed-accuracy problem's base and FEM points at
/// `fem_tolerances`, the grid BEM's and the FEM's three-level studies of the parabolic gap at
/// `d = 1.5 h`, the JKR pull-off routes and one live pull-off simulation.
pub(crate) fn report_parts(tolerance: f64, fem_tolerances: &[f64]) -> Vec<Part> {
    let mut parts = vec![
        Part::Comparison { tolerance },
        Part::Fenicsx,
        Part::Peers,
        Part::Operators,
    ];
    for problem in Problem::all() {
        parts.push(Part::SpeedBase(problem));
        for &tolerance in fem_tolerances {
            parts.push(Part::SpeedFem { problem, tolerance });
        }
    }
    for method in [Method::GridBem, Method::Fem] {
        parts.extend(convergence_parts(
            cases::REPORT_STUDY,
            method,
            REPORT_STUDY_LEVELS,
        ));
    }
    for punch in cases::report_profile_punches() {
        parts.push(Part::Adhesion(punch));
    }
    parts.push(Part::PulloffLive);
    parts.push(Part::AdhesionPeers);
    parts
}

/// Levels of the report's convergence studies.
const REPORT_STUDY_LEVELS: usize = 3;

/// The levels of one convergence study, one part each.
pub(crate) fn convergence_parts(case: StudyCase, method: Method, levels: usize) -> Vec<Part> {
    (0..levels)
        .map(|level| Part::ConvergenceLevel {
            punch: case.punch.clone(),
            method,
            eps: case.eps,
            depth: case.depth,
            level,
            levels,
        })
        .collect()
}

/// The pull-off simulations of the nightly run (`scripts/pulloff/run_all.py`'s cases).
fn pulloff_parts() -> Vec<Part> {
    cases::pulloff_simulations()
        .into_iter()
        .map(|(punch, eps, d0_over_h)| Part::PulloffSimulation {
            punch,
            eps,
            d0_over_h,
        })
        .collect()
}

/// The nightly suite: the report's parts with the FEM down to `fem_tolerances` (1e-8), the
/// pull-off simulations and the stability probes.
pub fn nightly_parts(tolerance: f64, fem_tolerances: &[f64]) -> Vec<Part> {
    let mut parts = report_parts(tolerance, fem_tolerances);
    parts.extend(pulloff_parts());
    parts.push(Part::Stability);
    parts
}

/// What a plan's results make: a report (with, in the nightly suite, the stability probes), or
/// convergence studies.
#[allow(clippy::large_enum_variant)]
pub enum Assembled {
    Report {
        inputs: ReportInputs,
        stability: Option<Vec<Probe>>,
    },
    Convergence(Vec<convergence::Study>),
}

fn need<T>(value: Option<T>, what: &str) -> Result<T> {
    value.ok_or_else(|| {
        Error::Plan(format!(
            "the plan has no {what} job: a report needs it (make the plan with `verify plan`)"
        ))
    })
}

/// Join parts' results, in the plan's order, into a report's inputs or convergence studies.
/// Every part must have a result; a report needs the comparison, the stored external results,
/// the JKR routes and the live simulation.
pub fn assemble(results: Vec<(Part, PartResult, f64)>) -> Result<Assembled> {
    let wall_s: f64 = results.iter().map(|r| r.2).sum();
    let mut comparison = None;
    let (mut fenicsx, mut peers, mut operators) = (None, None, None);
    let mut bases: Vec<BasePoints> = Vec::new();
    let mut ladders: HashMap<&'static str, Vec<Option<CostPoint>>> = HashMap::new();
    let mut studies: Vec<StudyLevels> = Vec::new();
    let mut pulloff = Vec::new();
    let mut live = None;
    let mut adhesion = None;
    let mut simulations = Vec::new();
    let mut stability = None;
    let mut report_parts = 0usize;
    for (part, result, _) in results {
        let mismatch = || {
            Error::Plan(format!(
                "the result of job `{}` is not what that job computes",
                part.id()
            ))
        };
        if !matches!(part, Part::ConvergenceLevel { .. }) {
            report_parts += 1;
        }
        match (&part, result) {
            (Part::Comparison { .. }, PartResult::Comparison(c)) => comparison = Some(c),
            (Part::Fenicsx, PartResult::Fenicsx(f)) => fenicsx = Some(f),
            (Part::Peers, PartResult::Peers(p)) => peers = Some(p),
            (Part::Operators, PartResult::Operators(o)) => operators = Some(o),
            (Part::SpeedBase(_), PartResult::SpeedBase(b)) => bases.push(b),
            (Part::SpeedFem { problem, .. }, PartResult::SpeedFem(p)) => {
                ladders.entry(problem.slug()).or_default().push(p)
            }
            (
                Part::ConvergenceLevel {
                    punch,
                    method,
                    eps,
                    depth,
                    levels,
                    ..
                },
                PartResult::ConvergenceLevel(l),
            ) => {
                let case = StudyCase {
                    punch: punch.clone(),
                    eps: *eps,
                    depth: *depth,
                };
                add_level(&mut studies, case, *method, *levels, l);
            }
            (Part::Adhesion(_), PartResult::Adhesion(p)) => pulloff.extend(p),
            (Part::PulloffLive, PartResult::PulloffLive(l)) => live = Some(l),
            (Part::AdhesionPeers, PartResult::AdhesionPeers(a)) => adhesion = Some(a),
            (Part::PulloffSimulation { .. }, PartResult::PulloffSimulation(r)) => {
                simulations.push(r)
            }
            (Part::Stability, PartResult::Stability(p)) => stability = Some(p),
            _ => return Err(mismatch()),
        }
    }
    let assembled_studies = assemble_studies(studies)?;
    if report_parts == 0 {
        return Ok(Assembled::Convergence(assembled_studies));
    }
    let fenicsx = need(fenicsx, "fenicsx")?;
    let speed_accuracy = bases
        .iter()
        .map(|b| {
            let ladder = ladders.remove(b.problem.slug()).unwrap_or_default();
            speed_accuracy::assemble(b, &ladder, &fenicsx)
        })
        .collect();
    if simulations.is_empty() {
        simulations = pulloff::load()?;
    }
    Ok(Assembled::Report {
        inputs: ReportInputs {
            comparison: need(comparison, "comparison")?,
            fenicsx,
            operators: need(operators, "operators")?,
            peers: need(peers, "peers")?,
            speed_accuracy,
            convergence: assembled_studies,
            pulloff: need((!pulloff.is_empty()).then_some(pulloff), "adhesion")?,
            pulloff_simulations: simulations,
            pulloff_live: need(live, "pulloff-live")?,
            adhesion_peers: need(adhesion, "adhesion-peers")?,
            baselines: Vec::new(),
            wall_s,
        },
        stability,
    })
}

/// The levels of one convergence study, as its jobs computed them.
type StudyLevels = (StudyCase, Method, usize, Vec<ComputedLevel>);

/// Add level `l` to its study (the same case, method and level count), or start that study.
fn add_level(
    studies: &mut Vec<StudyLevels>,
    case: StudyCase,
    method: Method,
    levels: usize,
    l: ComputedLevel,
) {
    let same = |s: &&mut StudyLevels| {
        s.0.punch == case.punch
            && s.0.eps == case.eps
            && s.0.depth == case.depth
            && s.1 == method
            && s.2 == levels
    };
    match studies.iter_mut().find(|s| same(s)) {
        Some(s) => s.3.push(l),
        None => studies.push((case, method, levels, vec![l])),
    }
}

/// Each study from its levels (every one present) against the ring BEM's yardstick.
fn assemble_studies(studies: Vec<StudyLevels>) -> Result<Vec<convergence::Study>> {
    let mut assembled = Vec::new();
    for (case, method, levels, computed) in studies {
        if computed.len() != levels {
            return Err(Error::Plan(format!(
                "the {} study of {} has {} of its {levels} levels",
                method.name(),
                case.punch,
                computed.len()
            )));
        }
        let yardstick = convergence::yardstick(&case)?;
        let levels = computed.into_iter().map(|c| c.level).collect();
        assembled.push(convergence::assemble(&case, method, yardstick, levels));
    }
    Ok(assembled)
}

/// Compute `parts` in this process (the single-process run) and join them in the plan's order:
/// the untimed parts side by side (one worker per core), then the timed ones ([`Part::is_timed`])
/// one after another with the machine to themselves. `progress` is called with each part's id
/// as it starts; the first failed part in the plan's order is the error.
pub(crate) fn compute_all(parts: &[Part], progress: impl FnMut(&str) + Send) -> Result<Assembled> {
    let progress = Mutex::new(progress);
    let tick = |what: &str| report_to(&progress, what);
    // Longest first ([`Part::expected_s`]), so that no worker is left with a long part at the
    // end; a part that uses every core itself never runs beside another such part.
    let mut untimed: Vec<usize> = (0..parts.len()).filter(|&i| !parts[i].is_timed()).collect();
    untimed.sort_by(|&i, &j| parts[j].expected_s().total_cmp(&parts[i].expected_s()));
    let queue = PartQueue::new(untimed, |i| parts[i].uses_every_core());
    let computed: Mutex<Vec<(usize, Result<Computed>)>> = Mutex::new(Vec::new());
    let run = |i: usize, edges: &mut EdgeMemo| {
        tick(&parts[i].id());
        let start = Instant::now();
        let result = parts[i]
            .compute(edges)
            .map(|r| (r, start.elapsed().as_secs_f64()));
        if let Ok(mut done) = computed.lock() {
            done.push((i, result));
        }
    };
    let workers = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, parts.len().max(1));
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                let mut edges = EdgeMemo::new();
                while let Some(i) = queue.take() {
                    run(i, &mut edges);
                    queue.done(i);
                }
            });
        }
    });
    // The timed parts alone, one after another: their timings are not shared with other work.
    let mut edges = EdgeMemo::new();
    for i in (0..parts.len()).filter(|&i| parts[i].is_timed()) {
        run(i, &mut edges);
    }
    let mut computed = computed
        .into_inner()
        .map_err(|_| Error::Plan("a report part's worker panicked".into()))?;
    computed.sort_by_key(|(i, _)| *i);
    let mut results = Vec::with_capacity(parts.len());
    for (i, result) in computed {
        let (value, wall_s) = result?;
        results.push((parts[i].clone(), value, wall_s));
    }
    assemble(results)
}

/// Call a progress callback shared between threads (a poisoned lock drops the report).
fn report_to(progress: &Mutex<impl FnMut(&str)>, what: &str) {
    if let Ok(mut report) = progress.lock() {
        report(what)
    }
}

/// A part's result and its wall time in seconds.
type Computed = (PartResult, f64);

/// The untimed parts waiting for a worker of [`compute_all`], in order; a part marked `heavy`
/// (it uses every core itself) is handed out only while no other heavy part runs.
struct PartQueue {
    state: Mutex<(Vec<usize>, bool)>,
    changed: Condvar,
    heavy: Vec<bool>,
}

impl PartQueue {
    fn new(order: Vec<usize>, heavy: impl Fn(usize) -> bool) -> Self {
        let size = order.iter().max().map_or(0, |&i| i + 1);
        Self {
            heavy: (0..size).map(heavy).collect(),
            state: Mutex::new((order, false)),
            changed: Condvar::new(),
        }
    }

    /// The next part this worker may run (waiting while only heavy parts are left and one
    /// runs), or `None` when the queue is empty.
    fn take(&self) -> Option<usize> {
        let mut state = self.state.lock().ok()?;
        loop {
            let (waiting, heavy_running) = &mut *state;
            if waiting.is_empty() {
                return None;
            }
            if let Some(k) = waiting
                .iter()
                .position(|&i| !(*heavy_running && self.heavy[i]))
            {
                let i = waiting.remove(k);
                *heavy_running |= self.heavy[i];
                return Some(i);
            }
            state = self.changed.wait(state).ok()?;
        }
    }

    /// Part `i` has finished.
    fn done(&self, i: usize) {
        if self.heavy[i] {
            if let Ok(mut state) = self.state.lock() {
                state.1 = false;
            }
            self.changed.notify_all();
        }
    }
}

/// Number of progress stages of [`write_report`].
pub(crate) const REPORT_STAGES: usize = 5;

/// Compute what the report draws and states beyond its inputs ([`Findings`]: the function
/// curves, the pressure profiles, the JKR annular branches, the verdicts on the paper's
/// claims), then write the report directory from both; returns the extras (also in
/// report.json). `progress` is called with each of [`REPORT_STAGES`] stages as it starts.
pub(crate) fn write_report(
    dir: &std::path::Path,
    inputs: &ReportInputs,
    progress: impl FnMut(&str) + Send,
) -> Result<ReportExtras> {
    let start = Instant::now();
    let ring = RingBem::new();
    let progress = Mutex::new(progress);
    let tick = |what: &str| report_to(&progress, what);
    // The verdicts (the longest stage) beside the rest: none of them is timed.
    let (curves, verdicts) = std::thread::scope(|scope| {
        let verdicts = scope.spawn(|| {
            tick("verdicts");
            claims::verdicts(&ring, &inputs.pulloff, &inputs.pulloff_simulations)
        });
        tick("functions against eps");
        let curves = figures::function_curves(&ring).and_then(|functions| {
            tick("pressure profiles");
            let pressure = figures::pressure_profiles(&ring)?;
            tick("adhesion");
            let annular_jkr: Vec<Option<figures::Points>> =
                pulloff::annular(&inputs.pulloff_simulations)
                    .iter()
                    .map(|record| {
                        let study = record.result.as_ref()?;
                        let d0_over_h = study.d0_over_h?;
                        Some(figures::annular_jkr_branch(
                            &ring,
                            study.punch.clone(),
                            d0_over_h,
                        ))
                    })
                    .collect();
            Ok((functions, pressure, annular_jkr))
        });
        let verdicts = verdicts
            .join()
            .unwrap_or_else(|_| Err(Error::Plan("the verdicts' worker panicked".into())));
        (curves, verdicts)
    });
    let (functions, pressure, annular_jkr) = curves?;
    let verdicts = verdicts?;
    tick("stored peer results graded");
    let peer_grading = crate::harness::grade::grade_stored_peers()?;
    let findings = Findings {
        functions,
        pressure,
        annular_jkr,
        verdicts,
        peer_grading,
        wall_s: start.elapsed().as_secs_f64(),
    };
    tick("tables and pages");
    document::write_files(dir, inputs, &findings)
}
/// A job id taken apart: `kind:positional:...:key=value:...`.
struct JobId<'a> {
    id: &'a str,
    kind: &'a str,
    positional: Vec<&'a str>,
    keys: HashMap<&'a str, &'a str>,
}

impl<'a> JobId<'a> {
    /// The fields of `id`; an error where a key is given twice.
    fn parse(id: &'a str) -> Result<Self> {
        let mut fields = id.split(':');
        let mut job = JobId {
            id,
            kind: fields.next().unwrap_or_default(),
            positional: Vec::new(),
            keys: HashMap::new(),
        };
        for f in fields {
            match f.split_once('=') {
                Some((k, v)) => {
                    if job.keys.insert(k, v).is_some() {
                        return Err(job.bad(&format!("`{k}` given twice")));
                    }
                }
                None => job.positional.push(f),
            }
        }
        Ok(job)
    }

    fn bad(&self, why: &str) -> Error {
        Error::Plan(format!("job id `{}`: {why}", self.id))
    }

    fn positional(&self, k: usize) -> Option<&'a str> {
        self.positional.get(k).copied()
    }

    fn value(&self, key: &str) -> Result<&'a str> {
        self.keys
            .get(key)
            .copied()
            .ok_or_else(|| self.bad(&format!("needs `{key}=`")))
    }

    /// The finite number under `key`.
    fn number(&self, key: &str) -> Result<f64> {
        let v = self.value(key)?;
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| self.bad(&format!("`{key}={v}` is not a number")))
    }

    /// The count under `key`.
    fn count(&self, key: &str) -> Result<usize> {
        let v = self.value(key)?;
        v.parse::<usize>()
            .map_err(|_| self.bad(&format!("`{key}={v}` is not a count")))
    }

    /// The punch the first positional field names (its label); a punch given by a file only as
    /// the report's own.
    fn punch(&self) -> Result<PunchKind> {
        let name = self
            .positional(0)
            .ok_or_else(|| self.bad("needs a punch"))?;
        if let Some(own) = cases::report_table_punch().filter(|t| t.label() == name) {
            return Ok(own);
        }
        PunchKind::from_label(name).ok_or_else(|| {
            self.bad(&format!(
                "no punch `{name}` (a job's punch given by a file must be the report's, {})",
                cases::REPORT_TABLE_FILE
            ))
        })
    }

    /// A speed-accuracy part: the problem's base points, or its FEM at `fem-tol`.
    fn speed_part(&self) -> Result<Part> {
        let slug = self
            .positional(0)
            .ok_or_else(|| self.bad("needs a problem"))?;
        let problem = Problem::from_slug(slug).ok_or_else(|| {
            self.bad(&format!(
                "no speed-accuracy problem `{slug}` (known: {})",
                Problem::all()
                    .iter()
                    .map(|p| p.slug())
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
        })?;
        Ok(if self.keys.contains_key("fem-tol") {
            Part::SpeedFem {
                problem,
                tolerance: self.number("fem-tol")?,
            }
        } else {
            Part::SpeedBase(problem)
        })
    }
}
