//! Every table of the verification report as a [`Table`]: the Markdown report, its web page and
//! the CSV file behind each table (`table-<slug>.csv`, linked under it) come from the same rows.

use crate::harness::records::fenicsx::FenicsxComparison;
use crate::harness::records::operator::OperatorStatus;
use crate::harness::records::peers::PeerComparison;
use crate::harness::report::contents::ReportExtras;
use crate::harness::report::table::{verdict, Cell, Column, Format, Table};
use crate::harness::studies::comparison::{self, ComparisonReport};

/// One table of the report: the section it opens (if any), a sentence above it, the table, a
/// chart shown above it, and the file stem of its CSV.
pub(crate) struct ReportTable {
    pub section: Option<String>,
    pub intro: Option<String>,
    pub chart: Option<String>,
    pub slug: String,
    pub table: Table,
}

fn text(key: &str, label: &str) -> Column {
    Column::text(key, label)
}

fn entry(section: Option<&str>, slug: &str, table: Table) -> ReportTable {
    ReportTable {
        section: section.map(str::to_string),
        intro: None,
        chart: None,
        slug: slug.to_string(),
        table,
    }
}

/// The paper's claims and this run's verdicts.
fn claims(extras: &ReportExtras) -> Table {
    let mut t = Table::new(
        "The paper's claims against this run",
        vec![
            text("claim", "claim"),
            text("this_run", "this run"),
            text("verdict", "verdict"),
        ],
    );
    for v in &extras.verdicts {
        t.push(vec![
            v.claim.clone().into(),
            v.numbers.clone().into(),
            v.verdict.clone().into(),
        ]);
    }
    t
}

fn external(fenicsx: &[FenicsxComparison], peers: &[PeerComparison]) -> Table {
    let mut t = Table::new(
        "Stored results of external codes against ours",
        vec![
            text("result", "result"),
            Column::number(
                "relative_difference",
                "rel. diff to ours",
                Format::SignedScientific(1),
            ),
            text("verdict", "verdict"),
        ],
    );
    for r in fenicsx {
        t.push(vec![
            format!("FEniCSx {} ({})", r.file, r.status).into(),
            r.relative_difference.into(),
            if r.passed {
                "ok".into()
            } else if r.status == "current" {
                Cell::Flag("FAIL".into())
            } else {
                "stale, not used".into()
            },
        ]);
    }
    for r in peers {
        t.push(vec![
            r.file.clone().into(),
            r.relative_difference.into(),
            verdict(r.passed, "FAIL"),
        ]);
    }
    t
}

fn operators(rows: &[OperatorStatus]) -> Table {
    let mut t = Table::new(
        "Assembled operator against FEniCSx's (stored comparisons)",
        vec![
            text("mesh", "mesh"),
            text("degree", "degree"),
            Column::number("dofs", "dofs", Format::Fixed(0)),
            Column::number("nnz", "nnz", Format::Fixed(0)),
            Column::number(
                "stiffness_difference",
                "K difference",
                Format::Scientific(1),
            ),
            Column::number("load_difference", "load difference", Format::Scientific(1)),
            text("fenicsx", "FEniCSx"),
            text("date", "date"),
            text("status", "mesh"),
            text("verdict", "verdict"),
        ],
    );
    for r in rows {
        let c = &r.record.comparison;
        t.push(vec![
            c.mesh.clone().into(),
            format!("P{}", c.degree).into(),
            (c.dofs as f64).into(),
            (c.nnz_ours as f64).into(),
            c.stiffness_difference.into(),
            c.load_difference.into(),
            format!("dolfinx {}", r.record.dolfinx_version).into(),
            r.record.date.clone().into(),
            r.status.clone().into(),
            verdict(c.meets_goal(), "ABOVE GOAL"),
        ]);
    }
    t
}

/// Every table of the report, in the report's order (charts of the speed-accuracy study above
/// their tables).
pub(crate) fn report_tables(
    comparison: &ComparisonReport,
    fenicsx: &[FenicsxComparison],
    operator_rows: &[OperatorStatus],
    peers: &[PeerComparison],
    extras: &ReportExtras,
) -> Vec<ReportTable> {
    let mut out = vec![
        entry(Some("The paper's claims"), "claims", claims(extras)),
        entry(
            Some("Methods and references"),
            "references",
            comparison::reference_table(comparison),
        ),
        entry(
            Some("Consistency checks"),
            "identities",
            comparison::identity_table(comparison),
        ),
        entry(
            Some("FEM against the ring BEM (default tolerance)"),
            "fem",
            comparison::fem_table(comparison),
        ),
        entry(
            Some("External codes (stored results)"),
            "external",
            external(fenicsx, peers),
        ),
    ];
    if let Some(g) = &extras.peer_grading {
        out.push(ReportTable {
            section: None,
            intro: Some(format!(
                "The same stored results graded against the converged references by the code \
                 of `verify grade` (`verify grade --results verify/grade/tamaas.csv` grades \
                 Tamaas's as a user would): the peers' square grids are held to {:.0e}. {}.",
                g.tolerance,
                crate::harness::grade::verdict_sentence(g)
            )),
            chart: Some(crate::harness::grade::PEER_CHART.to_string()),
            slug: "peer-grading".into(),
            table: crate::harness::grade::rows_table(
                g,
                "Stored peer results against the converged references",
            ),
        });
    }
    out.extend(baseline_and_speed_tables(extras));
    out.push(operator_table(operator_rows));
    out.extend(pulloff_tables(extras));
    out.extend(speed_accuracy_tables(extras));
    out
}

/// The fresh-against-baseline table (when the run made fresh results) and the
/// interleaved speed records against the peers (when stored).
fn baseline_and_speed_tables(extras: &ReportExtras) -> Vec<ReportTable> {
    let mut out = Vec::new();
    if !extras.baselines.is_empty() {
        out.push(ReportTable {
            intro: Some(
                "This run's fresh peer and pull-off results (in the report directory, `fresh/`) \
                 against the committed baselines in `verify/`: a difference beyond the \
                 tolerance is a regression. Baselines change only by a reviewed commit."
                    .into(),
            ),
            ..entry(
                Some("Fresh runs against the committed baselines"),
                "baselines",
                crate::harness::records::baselines::table(&extras.baselines),
            )
        });
    }
    if let Ok(record) = crate::harness::records::benchmarks::FenicsxSpeed::load() {
        out.push(ReportTable {
            intro: Some(record.summary()),
            ..entry(
                Some("Cost against the peers (interleaved benchmark records)"),
                "speed-fenicsx",
                record.table(),
            )
        });
    }
    if let Ok(record) = crate::harness::records::benchmarks::TamaasSpeed::load() {
        out.push(ReportTable {
            intro: Some(format!(
                "Timed region: {}; reproduce: `{}`.",
                record.provenance.timed_region, record.provenance.command
            )),
            ..entry(None, "speed-tamaas", record.table())
        });
    }
    out
}

/// Our assembled operator against FEniCSx's on the same mesh and degree.
fn operator_table(operator_rows: &[OperatorStatus]) -> ReportTable {
    ReportTable {
        intro: Some(
            "Our stiffness matrix and unit-pressure load vector against FEniCSx's on the same \
                 mesh and degree, dofs matched by position (`scripts/fenicsx/operators.py`); \
                 goal: largest entry-wise difference over the largest entry <= 1e-12."
                .into(),
        ),
        ..entry(
            Some("Assembled operator against FEniCSx (stored comparisons)"),
            "operators",
            operators(operator_rows),
        )
    }
}

/// The direct pull-off simulations: the stored sequences with this run's live
/// point, the branches a concave punch's hole takes, the annular route, Tamaas.
fn pulloff_tables(extras: &ReportExtras) -> Vec<ReportTable> {
    let mut out = Vec::new();
    out.push(pulloff_simulation_table(extras));
    if let Some(record) =
        crate::harness::records::pulloff::with_branches(&extras.pulloff_simulations)
    {
        out.push(ReportTable {
            intro: Some(format!(
                "What the formula route does not see: at small Tabor numbers the closed hole of \
                 a concave punch reopens on the way out (the apex keeps a pinhole of the law's \
                 range, a flaw the JKR route, with no flaw at the centre, does not have), so \
                 those ranges end on the annular branch and are left out of the extrapolation; \
                 from larger Tabor numbers on the hole holds until the rim lets go. Force \
                 compression positive. The chart: {}, the force at which each range's pull \
                 left the preload's branch against the range (the rim's pull-off, or the hole \
                 reopening first), the extrapolate and the JKR route.",
                record.file.trim_end_matches(".json")
            )),
            chart: Some(crate::harness::report::contents::PULLOFF_BRANCHES_CHART.to_string()),
            ..entry(
                None,
                "pulloff-branches",
                crate::harness::records::pulloff::branches_table(&extras.pulloff_simulations),
            )
        });
    }
    let annular = crate::harness::records::pulloff::annular(&extras.pulloff_simulations);
    if !annular.is_empty() {
        out.push(ReportTable {
            intro: Some(
                "The paper's own route, simulated: the punch touched with its hole open (the \
                 rim plane at the surface), then pulled; the inner edge moves outward until the \
                 annulus lets go (`verify pulloff --branch annular`; the contact line meshed \
                 uniformly at a third of the zone per range). JKR route: the fixed-load \
                 pull-off of the annular contact from converged ring-BEM solutions. The chart: \
                 the pull at the smallest range against the JKR route's adhesive annular branch \
                 (compression positive)."
                    .into(),
            ),
            chart: Some(crate::harness::report::contents::PULLOFF_ANNULAR_CHART.to_string()),
            ..entry(
                None,
                "pulloff-annular",
                crate::harness::records::pulloff::table(&annular),
            )
        });
    }
    if !extras.adhesion_peers.is_empty() {
        out.push(ReportTable {
            intro: Some(
                "The same law and range on Tamaas's grid BEM with its exponential adhesion \
                 functional (`scripts/peers/run_adhesion.py`, stored in `verify/peers/adhesion/`; \
                 a periodic cell, corrected for its images): agreement within Tamaas's \
                 uncertainty (images and grid) plus our mesh change. The chart: the pulling \
                 curves, Tamaas's in its largest cell (L = 6a, not corrected for the images: \
                 its maximum sits about 1 % above the extrapolate) with its approach converted \
                 to the isolated half-space."
                    .into(),
            ),
            chart: Some(crate::harness::report::contents::ADHESION_PEER_CHART.to_string()),
            ..entry(
                None,
                "pulloff-tamaas",
                crate::harness::records::adhesion_peers::table(&extras.adhesion_peers),
            )
        });
    }
    out
}

/// The stored pull-off sequences with this run's live point (or why it failed).
fn pulloff_simulation_table(extras: &ReportExtras) -> ReportTable {
    let mut table = crate::harness::records::pulloff::table(&extras.pulloff_simulations);
    let (live_punch, live_d0h) = crate::harness::cases::live_pulloff();
    let live_case = format!("{}-d0h{live_d0h}", live_punch.label());
    match &extras.pulloff_live {
        Ok(live) => table.push(vec![
            format!(
                "{live_case}, this run (Tabor {:.0} only; {} contact nodes, {})",
                live.entry.tabor, live.contact_nodes, live.mesh
            )
            .into(),
            format!("{:.0}: {:.4}", live.entry.tabor, live.entry.pulloff_over_f0).into(),
            Cell::Missing,
            Cell::Missing,
            Cell::Missing,
            Cell::Missing,
            Cell::Missing,
            live.wall_s.into(),
            "this run".into(),
            Cell::Missing,
        ]),
        Err(why) => table.push(crate::harness::records::pulloff::row_without_result(
            format!("{live_case}, this run"),
            "this run",
            Cell::Flag(format!("FAILED: {why}")),
        )),
    }
    ReportTable {
        intro: Some(
            "A second route to the pull-off, with no JKR energy balance: an exponential \
             adhesion law on the FE model's contact line, pressed and pulled under \
             displacement control at ranges spanning a factor 10 in the Tabor parameter \
             (the closed branch: each on its own mesh, a band at the rim refined to the \
             cohesive zone), extrapolated to zero range (`verify pulloff`; stored by \
             `scripts/pulloff/run_all.py --out verify/pulloff`; the nightly run compares fresh runs with them). JKR route: fixed-load pull-off (flat punches), from full contact \
             (concave punches, pressed until their hole closes: 3h, or deeper for small \
             d0/h), and for the `-annular` cases the fixed-load pull-off of the annular \
             contact (touched with the hole open, then pulled); for a free band's cases \
             (touched at the lowest circle, then pulled, a cohesive zone at both free edges) \
             the two-edge JKR solution's fixed-load pull-off. A range at which the closed \
             hole reopens on the way out is on another branch: it is left out (named) and a \
             smaller range replaces it."
                .into(),
        ),
        chart: extras
            .pulloff_live
            .is_ok()
            .then(|| crate::harness::report::contents::PULLOFF_CURVE_CHART.to_string()),
        ..entry(
            Some("Pull-off by direct simulation"),
            "pulloff-simulation",
            table,
        )
    }
}

/// One table (and chart) per speed-against-accuracy problem.
fn speed_accuracy_tables(extras: &ReportExtras) -> Vec<ReportTable> {
    let mut out = Vec::new();
    for (k, sa) in extras.speed_accuracy.iter().enumerate() {
        let mut t = Table::new(
            &sa.problem,
            vec![
                text("method", "method"),
                text("resolution", "resolution"),
                Column::number("wall_s", "wall time (median)", Format::Fixed(4)).with_unit("s"),
                text("wall_s_range", "range [s]"),
                Column::number("runs", "runs", Format::Fixed(0)),
                Column::number("error", "rel. error", Format::Scientific(1)),
                Column::number("estimate", "own estimate", Format::Scientific(1)),
                text("bounds", "estimate bounds error"),
                text("pareto", "Pareto"),
            ],
        );
        for p in &sa.points {
            t.push(vec![
                p.method.clone().into(),
                p.resolution.clone().into(),
                p.wall_s.into(),
                p.wall_s_range
                    .map_or("-".to_string(), |(lo, hi)| format!("{lo:.4}-{hi:.4}"))
                    .into(),
                (p.runs as f64).into(),
                p.error.into(),
                p.estimate.into(),
                match p.estimate_bounds_error() {
                    Some(true) => "yes".into(),
                    Some(false) => Cell::Flag("NO (a failed check)".into()),
                    None => "".into(),
                },
                if p.on_pareto_front { "yes" } else { "" }.into(),
            ]);
        }
        out.push(ReportTable {
            chart: Some(format!("speed-accuracy-{k}.svg")),
            ..entry(
                (k == 0).then_some("Speed against accuracy"),
                &format!("speed-accuracy-{k}"),
                t,
            )
        });
    }
    out
}
