//! The report directory of a `verify` run: Markdown for people, JSON for scripts, SVG charts.
//!
//! Charts: the dimensionless functions against `eps` by every method and reference; error
//! against wall time per problem (log-log, Pareto front marked); convergence of the grid BEM and
//! the FEM; pressure profiles of one state; pull-off against `d0/h`.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

pub use crate::harness::studies::speed_accuracy::{
    CostPoint, SpeedAccuracy, DEFAULT_FEM_TOLERANCES,
};

use crate::harness::cases::REPORT_TABLE_SAMPLES;
use crate::harness::records::fenicsx::FenicsxComparison;
use crate::harness::records::operator::OperatorStatus;
use crate::harness::records::peers::PeerComparison;
pub use crate::harness::report::contents::{
    Headline, PulloffPoint, ReportExtras, Verdict, ADHESION_PEER_CHART, PULLOFF_ANNULAR_CHART,
    PULLOFF_BRANCHES_CHART, PULLOFF_CURVE_CHART,
};
use crate::harness::report::svg::{linear_chart, log_log_chart, Series};
use crate::harness::report::tables::{report_tables, ReportTable};
use crate::harness::studies::comparison::ComparisonReport;
use crate::harness::studies::convergence;
use crate::harness::studies::figures::{
    concave_ratios, flat_ratios, ConcaveCurves, FunctionCurves, Points, PressureProfiles,
};
use ringcontact::error::{Error, Result};
use ringcontact::punch::{Contact, PunchKind};

/// Where each range's pull of `record` ended, against the range: on the closed hole's branch
/// (the rim's pull-off, extrapolated to zero range beside the JKR route's full-contact value),
/// or earlier where the hole reopened (the left-out ranges). Compression positive.
fn pulloff_branches_chart(record: &crate::harness::records::pulloff::PulloffRecord) -> String {
    let Some(s) = &record.result else {
        return String::new();
    };
    let d0 = s.d0_over_h.unwrap_or(1.0);
    let on_branch: Vec<(f64, f64)> = s
        .sequence
        .iter()
        .map(|e| (e.range_over_a / d0, -e.pulloff_over_f0))
        .collect();
    let left: Vec<(f64, f64)> = s
        .excluded
        .iter()
        .map(|x| {
            let e = &x.entry;
            let force = e.hole_reopened_at.map_or(-e.pulloff_over_f0, |(_, f)| f);
            (e.range_over_a / d0, force)
        })
        .collect();
    let widest = on_branch
        .iter()
        .chain(&left)
        .map(|p| p.0)
        .fold(0.0, f64::max);
    let mut series = vec![
        Series {
            name: "rim let go (on the branch)".into(),
            points: on_branch,
            bars: Vec::new(),
        },
        Series {
            name: "hole reopened first".into(),
            points: left,
            bars: Vec::new(),
        },
    ];
    if let (Some(x), Some(bar)) = (s.extrapolated_over_f0, s.error_bar) {
        series.push(Series {
            name: "extrapolate".into(),
            points: vec![(0.0, -x)],
            bars: vec![Some((-x - bar, -x + bar))],
        });
    }
    if let Some(j) = s.jkr_reference() {
        series.push(Series {
            name: "JKR, full contact".into(),
            points: vec![(0.0, -j), (widest, -j)],
            bars: Vec::new(),
        });
    }
    crate::harness::report::svg::linear_chart_with_markers(
        &format!(
            "{}: force where the pull left the preload's branch, by range",
            record.file.trim_end_matches(".json")
        ),
        "range rho/d0",
        "F/F0 (compression positive)",
        &series,
    )
}

/// The annular branch of each stored `--branch annular` study: the pull of its smallest range
/// (force against depth, compression positive) and the JKR route's adhesive annular branch
/// ([`crate::harness::studies::figures::annular_jkr_branch`], one for each record), which ends
/// at its fixed-load pull-off.
fn pulloff_annular_chart(
    records: &[crate::harness::records::pulloff::PulloffRecord],
    jkr_branches: &[Option<Points>],
) -> String {
    let mut series = Vec::new();
    for (record, jkr) in records.iter().zip(jkr_branches) {
        let Some(s) = &record.result else { continue };
        let Some(x) = s.d0_over_h else { continue };
        let case = format!("{} {x}", s.punch);
        if let Some(curve) = s.curves.iter().rev().find(|c| !c.left_the_branch) {
            series.push(Series {
                name: format!("{case}: simulation, λ {:.0}", curve.tabor),
                points: curve
                    .points
                    .iter()
                    .filter(|p| p.2)
                    .map(|p| (p.0, p.1))
                    .collect(),
                bars: Vec::new(),
            });
        }
        series.push(Series {
            name: format!("{case}: JKR route"),
            points: jkr.clone().unwrap_or_default(),
            bars: Vec::new(),
        });
    }
    crate::harness::report::svg::linear_chart(
        "Annular branch (punch d0/h): touched with the hole open, then pulled",
        "d/d0",
        "F/F0 (compression positive)",
        &series,
    )
}

/// Our force-displacement curves (pulling) against Tamaas's, one pair per stored case.
fn adhesion_peer_chart(
    rows: &[crate::harness::records::adhesion_peers::AdhesionPeerComparison],
) -> String {
    let mut series = Vec::new();
    for r in rows {
        let case = match r.d0_over_h {
            Some(x) => format!("{} d0/h = {x}", r.punch),
            None => r.punch.to_string(),
        };
        series.push(Series {
            name: format!("ours, {case}"),
            points: r
                .our_curve
                .iter()
                .filter(|p| p.2)
                .map(|p| (p.0, p.1))
                .collect(),
            bars: Vec::new(),
        });
        series.push(Series {
            name: format!("Tamaas, {case}"),
            points: r.tamaas_curve.iter().map(|p| (p[0], p[1])).collect(),
            bars: Vec::new(),
        });
    }
    linear_chart(
        "Pulling: force against approach, ours and Tamaas's (same law and range)",
        "d/d0",
        "F/F0 (compression positive)",
        &series,
    )
}

/// The live simulation's force-displacement curve: pressing, pulling, the pull-off marked.
fn pulloff_curve_chart(live: &ringcontact::cohesive::study::LiveSimulation) -> String {
    let part = |unloading: bool| -> Vec<(f64, f64)> {
        live.curve
            .iter()
            .filter(|p| p.2 == unloading)
            .map(|p| (p.0, p.1))
            .collect()
    };
    let series = [
        Series {
            name: "pressing".into(),
            points: part(false),
            bars: Vec::new(),
        },
        Series {
            name: "pulling".into(),
            points: part(true),
            bars: Vec::new(),
        },
        Series {
            name: "pull-off".into(),
            points: vec![(
                live.entry.pulloff_depth_over_d0,
                -live.entry.pulloff_over_f0,
            )],
            bars: Vec::new(),
        },
    ];
    crate::harness::report::svg::linear_chart_with_markers(
        &format!(
            "{} d0/h = {}, Tabor {:.0}: force against depth (direct simulation)",
            live.punch,
            live.d0_over_h.map_or("-".into(), |x| x.to_string()),
            live.entry.tabor
        ),
        "d/d0",
        "F/F0 (compression positive)",
        &series,
    )
}

fn speed_chart(sa: &SpeedAccuracy) -> String {
    let mut methods: Vec<String> = sa.points.iter().map(|p| p.method.clone()).collect();
    methods.dedup();
    let mut series: Vec<Series> = methods
        .iter()
        .map(|m| {
            // Joined in order of wall time, so that a line reads as "more time, this error".
            let mut of_method: Vec<&CostPoint> =
                sa.points.iter().filter(|p| &p.method == m).collect();
            of_method.sort_by(|a, b| a.wall_s.total_cmp(&b.wall_s));
            Series {
                name: m.clone(),
                points: of_method.iter().map(|p| (p.wall_s, p.error)).collect(),
                // From the actual error up to the method's own estimate.
                bars: of_method
                    .iter()
                    .map(|p| p.estimate.map(|e| (p.error.min(e), e.max(p.error))))
                    .collect(),
            }
        })
        .collect();
    let mut front: Vec<(f64, f64)> = sa
        .points
        .iter()
        .filter(|p| p.on_pareto_front)
        .map(|p| (p.wall_s, p.error))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    series.push(Series {
        name: "Pareto front".into(),
        points: front,
        bars: Vec::new(),
    });
    log_log_chart(
        &format!("{}: error against wall time", sa.problem),
        "wall time [s]",
        "relative error (bar: up to the method's own estimate)",
        &series,
    )
}

/// The dimensionless functions against eps: ring BEM curves, the paper's fits, other methods'
/// points.
fn function_charts(
    curves: &FunctionCurves,
    comparison: &ComparisonReport,
    dir: &Path,
) -> Result<()> {
    let series = |name: &str, points: Points| Series {
        name: name.into(),
        points,
        bars: Vec::new(),
    };
    let fem_points: Points = comparison
        .fem
        .iter()
        .filter(|c| !c.punch.is_concave())
        .map(|c| (c.fem_eps, c.fem_value))
        .collect();
    for annulus in PunchKind::built_in(Contact::FixedAnnulus) {
        let annulus_fit = ringcontact::reference::fit_of(&annulus, 0);
        let fit: Points = flat_ratios()
            .into_iter()
            .filter_map(|e| Some((e, (annulus_fit?.eval)(e).value)))
            .collect();
        let chart = linear_chart(
            &format!(
                "{}: gamma = F/(2 E* d a) against b/a",
                annulus.name().replace('-', " ")
            ),
            "eps = b/a",
            "gamma",
            &[
                series("ring BEM", curves.flat_ring_bem.clone()),
                series("paper fit (3)", fit),
                series("FEM P2 (points)", fem_points.clone()),
                series("grid BEM 128² (points)", curves.flat_grid_bem.clone()),
            ],
        );
        write(dir, &format!("gamma-{}.svg", annulus.label()), &chart)?;
    }
    for c in &curves.concave {
        let kind = c.punch.clone();
        if !kind.has_rim() {
            write(
                dir,
                &format!("gammas-{}.svg", kind.label()),
                &band_chart(c, &curves.band_grid_bem),
            )?;
            continue;
        }
        let fem: Points = comparison
            .fem
            .iter()
            .filter(|f| f.punch == kind && f.fem_eps > 0.0)
            .map(|f| (f.fem_eps, f.fem_value))
            .collect();
        // The report's table samples another punch's profile: that punch's curves under its
        // own (drawn first, so that the table's stay visible where they coincide).
        let mut lines = Vec::new();
        if kind.piecewise().is_some() {
            let sampled = REPORT_TABLE_SAMPLES;
            if let Some(s) = curves.concave.iter().find(|s| s.punch == sampled) {
                lines.push(series(&format!("gamma1 {sampled}"), s.gamma1.clone()));
                lines.push(series(&format!("gamma2 {sampled}"), s.gamma2.clone()));
            }
            write(
                dir,
                &format!("gammas-{}-difference.svg", kind.label()),
                &table_difference_chart(c),
            )?;
        }
        lines.push(series("gamma1 ring BEM", c.gamma1.clone()));
        lines.push(series("gamma2 ring BEM", c.gamma2.clone()));
        // The paper's fits, for the punches it fitted.
        for function in [1, 2] {
            if let Some(fit) = ringcontact::reference::fit_of(&kind, function) {
                let points = concave_ratios()
                    .into_iter()
                    .filter_map(|e| Some((e, fit.evaluate(e)?.value)))
                    .collect();
                lines.push(series(&format!("gamma{function} paper fit"), points));
            }
        }
        lines.push(series("gamma2 FEM P2", fem));
        // Markers: the FEM's one or two states stay visible.
        let chart = crate::harness::report::svg::linear_chart_with_markers(
            &format!(
                "{}: gamma1 = d/h and gamma2 = F/(2 E* h a) against b/a",
                chart_name(kind.clone())
            ),
            "eps = b/a",
            "gamma1, gamma2",
            &lines,
        );
        write(dir, &format!("gammas-{}.svg", kind.label()), &chart)?;
    }
    Ok(())
}

/// A punch as a chart's title names it: a table by its file's name (its path is in the text).
fn chart_name(kind: PunchKind) -> String {
    match kind.record().profile_file {
        Some(file) => format!(
            "{} {}",
            kind.name(),
            Path::new(&file)
                .file_name()
                .map_or_else(|| file.clone(), |n| n.to_string_lossy().into_owned())
        ),
        None => kind.to_string(),
    }
}

/// The report's table against the punch it samples at the same depth (log-log): `|Δgamma2|`
/// against `d/h`, under its bound, the largest difference of the two gaps `g/h` (the contact
/// problem is monotone in the gap, `figures::largest_gap_difference`).
fn table_difference_chart(c: &ConcaveCurves) -> String {
    let sampled = REPORT_TABLE_SAMPLES;
    let difference: Points = c
        .gamma2
        .iter()
        .zip(&c.sampled_at_depth)
        .map(|(&(_, table), &(depth, reference))| (depth, (table - reference).abs()))
        .collect();
    let depths = || difference.iter().map(|p| p.0);
    let (low, high) = (
        depths().fold(f64::INFINITY, f64::min),
        depths().fold(0.0, f64::max),
    );
    let mut lines = vec![Series {
        name: format!("|gamma2 - {sampled}'s|"),
        points: difference,
        bars: Vec::new(),
    }];
    if let Some(bound) = c.gap_difference {
        lines.push(Series {
            name: "bound: max |Δg|/h".into(),
            points: vec![(low, bound), (high, bound)],
            bars: Vec::new(),
        });
    }
    log_log_chart(
        &format!(
            "{} against the {sampled} it samples, at the same depth",
            chart_name(c.punch.clone())
        ),
        "d/h",
        "|gamma2 difference|",
        &lines,
    )
}

/// A free band against its depth `d/h` (log-log): the force `gamma2 = F/(2 E* h a)` by the ring
/// BEM and the grid BEM, and both free edges `b/a`, `c/a`.
fn band_chart(c: &ConcaveCurves, grid_bem: &Points) -> String {
    let against_depth = |values: &Points| -> Points {
        c.gamma1
            .iter()
            .zip(values)
            .map(|(&(_, depth), &(_, value))| (depth, value))
            .collect()
    };
    let series = |name: &str, points: Points| Series {
        name: name.into(),
        points,
        bars: Vec::new(),
    };
    log_log_chart(
        &format!(
            "{}: gamma2 = F/(2 E* h a) and the edges b/a, c/a against d/h",
            c.punch
        ),
        "gamma1 = d/h",
        "gamma2, b/a, c/a",
        &[
            series("gamma2 ring BEM", against_depth(&c.gamma2)),
            series("gamma2 grid BEM 128²", grid_bem.clone()),
            series(
                "b/a ring BEM",
                c.gamma1.iter().map(|&(b, depth)| (depth, b)).collect(),
            ),
            series("c/a ring BEM", against_depth(&c.outer)),
        ],
    )
}

/// Pressure profiles of the parabolic gap at `d = 1.5 h`: ring BEM, azimuthally averaged grid BEM,
/// FEM.
fn pressure_chart(profiles: &PressureProfiles, dir: &Path) -> Result<()> {
    let clip = |v: &Points| -> Points { v.iter().copied().filter(|&(r, _)| r < 0.99).collect() };
    let series = |name: &str, points: Points| Series {
        name: name.into(),
        points,
        bars: Vec::new(),
    };
    let (kind, depth) = crate::harness::cases::PRESSURE_PROFILE;
    let chart = linear_chart(
        &format!("{kind} d/h = {depth}: contact pressure p/(E* h/a) against r/a (r < 0.99 a)"),
        "r/a",
        "p a / (E* h)",
        &[
            series("ring BEM (nodes)", clip(&profiles.ring_bem)),
            series("grid BEM 256², averaged", clip(&profiles.grid_bem)),
            series("FEM P2 (nodal)", profiles.fem.clone()),
        ],
    );
    write(dir, &pressure_chart_file(), &chart)
}

/// The pressure chart's file name, `pressure-LABEL.svg`.
fn pressure_chart_file() -> String {
    format!(
        "pressure-{}.svg",
        crate::harness::cases::PRESSURE_PROFILE.0.label()
    )
}

/// The committed reference dataset (`verify/dataset/`, `verify dataset --small`), copied into
/// `dir/dataset/` so that the report links it wherever the report is; nothing where the project
/// has none.
fn copy_dataset(dir: &Path) -> Result<()> {
    let Ok(root) = crate::harness::settings::find_data().map(|data| data.root) else {
        return Ok(());
    };
    let source = root.join(DATASET_DIRECTORY);
    let Ok(entries) = std::fs::read_dir(&source) else {
        return Ok(());
    };
    let target = dir.join("dataset");
    std::fs::create_dir_all(&target)
        .map_err(|e| Error::file("create the directory", &target, e))?;
    for entry in entries.filter_map(|e| e.ok()) {
        let from = entry.path();
        if from.is_file() {
            let to = target.join(entry.file_name());
            std::fs::copy(&from, &to).map_err(|e| Error::file("copy", &from, e))?;
        }
    }
    Ok(())
}

/// Where the committed small copy of the reference dataset lives, relative to the project.
const DATASET_DIRECTORY: &str = "verify/dataset";

fn write(dir: &Path, name: &str, text: &str) -> Result<()> {
    std::fs::write(dir.join(name), text).map_err(|e| Error::file("write", &dir.join(name), e))
}

/// Everything a report is made of: computed in one process
/// ([`crate::harness::report_jobs::compute_all`]) or read from the result files of a plan's jobs
/// ([`crate::harness::plan::load_results`]), both joined by
/// [`crate::harness::report_jobs::assemble`].
#[derive(Clone, Debug)]
pub struct ReportInputs {
    pub comparison: ComparisonReport,
    pub fenicsx: Vec<FenicsxComparison>,
    pub operators: Vec<OperatorStatus>,
    pub peers: Vec<PeerComparison>,
    pub speed_accuracy: Vec<SpeedAccuracy>,
    /// The grid BEM's and the FEM's studies of the parabolic gap at `d = 1.5 h`.
    pub convergence: Vec<convergence::Study>,
    /// Pull-off by the JKR routes against `d0/h`, linear gap then parabolic gap.
    pub pulloff: Vec<PulloffPoint>,
    /// The pull-off simulations shown (the stored ones, or this run's).
    pub pulloff_simulations: Vec<crate::harness::records::pulloff::PulloffRecord>,
    /// This run's single pull-off simulation, or why it failed.
    pub pulloff_live: std::result::Result<ringcontact::cohesive::study::LiveSimulation, String>,
    /// The stored Tamaas pull-offs against this run's simulations.
    pub adhesion_peers: Vec<crate::harness::records::adhesion_peers::AdhesionPeerComparison>,
    /// Fresh peer and pull-off results against the committed baselines (none without
    /// `--fresh`).
    pub baselines: Vec<crate::harness::records::baselines::BaselineCheck>,
    /// Wall time of the computations (their sum when merged from jobs), seconds.
    pub wall_s: f64,
}

/// The chart of one punch's pull-off against `d0/h` by each route.
fn pulloff_chart(kind: PunchKind, points: &[PulloffPoint]) -> String {
    let mine: Vec<&PulloffPoint> = points.iter().filter(|p| p.punch == kind.label()).collect();
    let series = [
        Series {
            name: "fixed load".into(),
            points: mine
                .iter()
                .filter_map(|p| p.fixed_load.map(|v| (p.d0_over_h, v)))
                .collect(),
            bars: Vec::new(),
        },
        Series {
            name: "paper fits".into(),
            points: mine
                .iter()
                .filter_map(|p| p.paper_fits.map(|v| (p.d0_over_h, v)))
                .collect(),
            bars: Vec::new(),
        },
        Series {
            name: "full contact".into(),
            points: mine
                .iter()
                .filter_map(|p| p.full_contact.map(|v| (p.d0_over_h, v)))
                .collect(),
            bars: Vec::new(),
        },
        Series {
            name: "fixed grips".into(),
            points: mine
                .iter()
                .filter_map(|p| p.fixed_grips.map(|v| (p.d0_over_h, v)))
                .collect(),
            bars: Vec::new(),
        },
        Series {
            name: "plane-strain JKR cylinder".into(),
            points: mine
                .iter()
                .filter_map(|p| p.plane_strain.map(|v| (p.d0_over_h, v)))
                .collect(),
            bars: Vec::new(),
        },
    ];
    // The paper fitted the linear gap and the parabolic gap only, a free band has no full contact
    // and only a free band shows fixed grips and its narrow-band asymptote: no empty legend
    // entries.
    let mut series: Vec<Series> = series
        .into_iter()
        .filter(|s| !s.points.is_empty())
        .collect();
    // The report's table samples another punch's profile: that punch's fixed-load pull-off,
    // drawn first (the table's stays visible where they coincide).
    if kind.piecewise().is_some() {
        let sampled = REPORT_TABLE_SAMPLES;
        series.insert(
            0,
            Series {
                name: format!("{sampled}, fixed load"),
                points: points
                    .iter()
                    .filter(|p| p.punch == sampled.label())
                    .filter_map(|p| p.fixed_load.map(|v| (p.d0_over_h, v)))
                    .collect(),
                bars: Vec::new(),
            },
        );
    }
    log_log_chart(
        &format!("{}: pull-off / F0 against d0/h", chart_name(kind)),
        "d0/h",
        "-F/F0",
        &series,
    )
}

/// What the report draws and states beyond its inputs, computed by the methods before it is
/// written ([`crate::harness::report_jobs::write_report`]).
#[derive(Clone, Debug)]
pub(crate) struct Findings {
    /// The dimensionless functions against `eps`.
    pub functions: FunctionCurves,
    /// The parabolic gap's pressure profiles at `d = 1.5 h`.
    pub pressure: PressureProfiles,
    /// The JKR route's annular branch for each stored annular study (in the order of
    /// [`crate::harness::records::pulloff::annular`]; none where a record has no result).
    pub annular_jkr: Vec<Option<Points>>,
    /// The paper's claims with this run's numbers.
    pub verdicts: Vec<Verdict>,
    /// The stored peer results graded against the references (`verify grade`'s code path).
    pub peer_grading: Option<crate::harness::grade::Grading>,
    /// Wall time of computing these, seconds.
    pub wall_s: f64,
}

/// Write the report directory (charts, tables, Markdown, JSON, HTML) from its inputs and
/// findings; returns the extras (also in report.json). Draws and formats only.
pub(crate) fn write_files(
    dir: &Path,
    inputs: &ReportInputs,
    findings: &Findings,
) -> Result<ReportExtras> {
    let start = Instant::now();
    std::fs::create_dir_all(dir).map_err(|e| Error::file("create the directory", dir, e))?;
    let comparison = &inputs.comparison;
    let (fenicsx, operators, peers) = (&inputs.fenicsx, &inputs.operators, &inputs.peers);
    function_charts(&findings.functions, comparison, dir)?;
    for (k, sa) in inputs.speed_accuracy.iter().enumerate() {
        write(dir, &format!("speed-accuracy-{k}.svg"), &speed_chart(sa))?;
    }
    for study in &inputs.convergence {
        write(
            dir,
            &format!("convergence-{}.svg", study.method),
            &convergence::chart(study),
        )?;
        write(
            dir,
            &format!("table-convergence-{}.csv", study.method),
            &convergence::csv(study)?,
        )?;
    }
    pressure_chart(&findings.pressure, dir)?;
    adhesion_charts(dir, inputs, findings)?;
    copy_dataset(dir)?;
    if let Some(g) = &findings.peer_grading {
        let title = "Stored peer results: relative error of the force against the references";
        write(
            dir,
            crate::harness::grade::PEER_CHART,
            &crate::harness::grade::chart(g, title),
        )?;
    }
    let simulations = inputs.pulloff_simulations.clone();
    let mut extras = ReportExtras {
        baselines: inputs.baselines.clone(),
        peer_grading: findings.peer_grading.clone(),
        headline: Headline::default(),
        verdicts: findings.verdicts.clone(),
        pulloff_simulations: simulations,
        pulloff_live: inputs.pulloff_live.clone(),
        adhesion_peers: inputs.adhesion_peers.clone(),
        speed_accuracy: inputs.speed_accuracy.clone(),
        convergence: inputs.convergence.clone(),
        pulloff: inputs.pulloff.clone(),
        wall_s: inputs.wall_s + findings.wall_s + start.elapsed().as_secs_f64(),
    };
    extras.headline = headline(comparison, fenicsx, operators, peers, &extras);
    let json = serde_json::json!({
        "comparison": comparison,
        "fenicsx": fenicsx,
        "fenicsx_operators": operators,
        "peers": peers,
        "extras": extras
    });
    write(
        dir,
        "report.json",
        &serde_json::to_string_pretty(&json).unwrap_or_default(),
    )?;
    let tables = report_tables(comparison, fenicsx, operators, peers, &extras);
    for t in &tables {
        write(dir, &format!("table-{}.csv", t.slug), &t.table.to_csv()?)?;
    }
    write(
        dir,
        "report.md",
        &markdown(comparison, fenicsx, operators, peers, &extras, &tables),
    )?;
    crate::harness::report::html::write_index(dir, None)?;
    Ok(extras)
}

/// The pull-off charts: the JKR routes against `d0/h`, this run's simulation, the stored
/// studies' branches, the annular route, Tamaas's curves.
fn adhesion_charts(dir: &Path, inputs: &ReportInputs, findings: &Findings) -> Result<()> {
    for kind in crate::harness::cases::report_profile_punches() {
        write(
            dir,
            &format!("pulloff-{}.svg", kind.label()),
            &pulloff_chart(kind, &inputs.pulloff),
        )?;
    }
    if let Ok(l) = &inputs.pulloff_live {
        write(dir, PULLOFF_CURVE_CHART, &pulloff_curve_chart(l))?;
    }
    if let Some(record) =
        crate::harness::records::pulloff::with_branches(&inputs.pulloff_simulations)
    {
        write(dir, PULLOFF_BRANCHES_CHART, &pulloff_branches_chart(record))?;
    }
    let annular = crate::harness::records::pulloff::annular(&inputs.pulloff_simulations);
    if !annular.is_empty() {
        write(
            dir,
            PULLOFF_ANNULAR_CHART,
            &pulloff_annular_chart(&annular, &findings.annular_jkr),
        )?;
    }
    if !inputs.adhesion_peers.is_empty() {
        write(
            dir,
            ADHESION_PEER_CHART,
            &adhesion_peer_chart(&inputs.adhesion_peers),
        )?;
    }
    Ok(())
}

/// Count every check of a report: one per bounded reference, identity, FEM comparison, stored
/// external result compared, fresh result against its baseline, convergence study's error bar
/// and speed-accuracy point with its own estimate; results that could not be compared here are
/// counted apart, with the reason.
pub fn headline(
    comparison: &ComparisonReport,
    fenicsx: &[FenicsxComparison],
    operators: &[OperatorStatus],
    peers: &[PeerComparison],
    extras: &ReportExtras,
) -> Headline {
    let bounded = comparison
        .rows
        .iter()
        .flat_map(|r| &r.comparisons)
        .filter(|c| c.agrees.is_some())
        .count();
    let fenicsx_compared = fenicsx.iter().filter(|r| r.status != "needs-gmsh").count();
    let operators_compared = operators
        .iter()
        .filter(|r| r.status != "mesh absent")
        .count();
    let bars = extras
        .convergence
        .iter()
        .filter(|s| s.bar_bounds_error.is_some())
        .count();
    let estimates = extras
        .speed_accuracy
        .iter()
        .flat_map(|s| &s.points)
        .filter(|p| p.estimate_bounds_error().is_some())
        .count();
    let groups = vec![
        ("ring BEM against bounded references".to_string(), bounded),
        ("consistency identities".into(), comparison.identities.len()),
        ("FEM against the ring BEM".into(), comparison.fem.len()),
        ("stored FEniCSx results".into(), fenicsx_compared),
        (
            "stored FEniCSx operator comparisons".into(),
            operators_compared,
        ),
        ("stored peer results".into(), peers.len()),
        (
            "stored peer results graded against the references".into(),
            extras.peer_grading.as_ref().map_or(0, |g| g.rows.len()),
        ),
        (
            "stored Tamaas pull-offs".into(),
            extras.adhesion_peers.len(),
        ),
        (
            "fresh results against their baselines".into(),
            extras.baselines.len(),
        ),
        (
            "convergence error bars against the actual error".into(),
            bars,
        ),
        (
            "speed-accuracy estimates against the actual error".into(),
            estimates,
        ),
    ];
    let failed = comparison.failures()
        + crate::harness::records::fenicsx::failures(fenicsx)
        + crate::harness::records::operator::failures(operators)
        + crate::harness::records::peers::failures(peers)
        + extras.peer_grading.as_ref().map_or(0, |g| g.beyond)
        + crate::harness::records::adhesion_peers::failures(&extras.adhesion_peers)
        + crate::harness::records::baselines::failures(&extras.baselines)
        + extras
            .convergence
            .iter()
            .map(convergence::failures)
            .sum::<usize>()
        + crate::harness::studies::speed_accuracy::unbounded_estimates(&extras.speed_accuracy);
    let mut not_run = Vec::new();
    // An operator comparison whose generated mesh could not be found or made is not run: for
    // want of gmsh, or (with gmsh) because its record names no parameters or gmsh failed.
    let operators_absent = operators.len() - operators_compared;
    let gmsh = ringcontact::mesh::provider::gmsh_available(&crate::harness::settings::data_paths());
    let need_gmsh = fenicsx.len() - fenicsx_compared
        + comparison.fem_not_run
        + if gmsh { 0 } else { operators_absent };
    if need_gmsh > 0 {
        not_run.push((need_gmsh, "need gmsh (bash scripts/install_gmsh.sh)".into()));
    }
    if gmsh && operators_absent > 0 {
        not_run.push((
            operators_absent,
            "operator comparisons whose mesh is neither at its stored path nor made from its \
             record's `reproduce` parameters"
                .into(),
        ));
    }
    Headline {
        checks: groups.iter().map(|(_, n)| n).sum(),
        failed,
        not_run,
        groups,
    }
}

/// Whether the project holds the committed dataset (copied into every report).
fn dir_has_dataset() -> bool {
    crate::harness::settings::find_data()
        .map(|data| data.root)
        .is_ok_and(|root| {
            root.join(DATASET_DIRECTORY)
                .join("datapackage.json")
                .is_file()
        })
}

/// The units of the report's adhesive results (conventions: `docs/conventions.md`).
pub const ADHESIVE_UNITS: &str = "Units of the adhesive results (JKR, pull-off): depths in \
    d0 = sqrt(2 pi a dw / E*), forces in F0 = sqrt(8 pi E* dw a^3) (Kendall's force), dw the \
    work of adhesion, a the punch's outer radius; each column says its sign.";

fn markdown(
    comparison: &ComparisonReport,
    fenicsx: &[FenicsxComparison],
    operators: &[OperatorStatus],
    peers: &[PeerComparison],
    extras: &ReportExtras,
    tables: &[ReportTable],
) -> String {
    let mut md = String::from("# ringcontact verification report\n\n");
    let _ = writeln!(
        md,
        "{}\n",
        headline(comparison, fenicsx, operators, peers, extras).sentence()
    );
    let _ = writeln!(md, "{ADHESIVE_UNITS}\n");
    for t in tables {
        if let Some(section) = &t.section {
            let _ = writeln!(md, "## {section}\n");
        }
        if let Some(intro) = &t.intro {
            let _ = writeln!(md, "{intro}\n");
        }
        if let Some(chart) = &t.chart {
            let _ = writeln!(md, "![]({chart})\n");
        }
        let _ = writeln!(
            md,
            "**{}** ([CSV](table-{}.csv))\n\n{}",
            t.table.title,
            t.slug,
            t.table.to_markdown_table()
        );
    }
    let study = crate::harness::cases::REPORT_STUDY;
    let _ = writeln!(
        md,
        "## Convergence ({}, d/h = {})\n",
        study.punch, study.depth
    );
    for s in &extras.convergence {
        let table = convergence::table(s);
        let _ = writeln!(
            md,
            "![](convergence-{0}.svg)\n\n**{1}** ([CSV](table-convergence-{0}.csv))\n\n{2}\n{3}\n",
            s.method,
            table.title,
            table.to_markdown_table(),
            convergence::summary(s)
        );
    }
    if dir_has_dataset() {
        md += "## Reference dataset\n\nConverged values to download, each with its error bound \
               and provenance: the non-adhesive functions with their stress intensity factors, \
               the JKR critical states and pull-off forces, the fitted formulas with their \
               largest errors ([datapackage.json](dataset/datapackage.json), CSV and JSON; the \
               small copy committed in `verify/dataset/`). `verify dataset` writes the full \
               grids, which interpolate to 1e-8.\n\n";
    }
    md += "## Charts\n\n";
    for annulus in PunchKind::built_in(Contact::FixedAnnulus) {
        let _ = writeln!(md, "![](gamma-{}.svg)", annulus.label());
    }
    let punches = crate::harness::cases::report_profile_punches();
    for kind in &punches {
        let _ = writeln!(md, "![](gammas-{}.svg)", kind.label());
        if kind.piecewise().is_some() {
            let _ = writeln!(md, "![](gammas-{}-difference.svg)", kind.label());
        }
    }
    let _ = writeln!(md, "![]({})", pressure_chart_file());
    for kind in &punches {
        let _ = writeln!(md, "![](pulloff-{}.svg)", kind.label());
    }
    md
}
