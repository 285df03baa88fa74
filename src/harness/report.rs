//! The report directory of a `verify` run: Markdown for people, JSON for scripts, SVG charts.
//!
//! Charts: the dimensionless functions against `eps` by every method and reference; error
//! against wall time per problem (log-log, Pareto front marked); convergence of the grid BEM and
//! the FEM; pressure profiles of one state; pull-off against `d0/h`.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use serde::Serialize;

use super::comparison::ComparisonReport;
use super::convergence::{self, StudyCase};
use super::fenicsx::FenicsxComparison;
use super::operator::OperatorStatus;
use super::peers::PeerComparison;
use super::report_tables::{report_tables, ReportTable};
use super::svg::{linear_chart, log_log_chart, Series};
use crate::adhesion;
use crate::bem::grid::{solve_contact, GridLoad, GridOperator};
use crate::bem::grid_contact::{self, cell_centre, discretise};
use crate::bem::ring::{ContactRegion, RingBemSettings, RingSystem};
use crate::bem::ring_contact::RingBemSolver;
use crate::error::{Error, Result};
use crate::fem::mesh::Degree;
use crate::fem::solver::{self as fem_solver, FemLoad, FemOptions};
use crate::methods::Method;
use crate::numerics::tanh_sinh::TanhSinhRule;
use crate::punch::PunchKind;
use crate::reference::paper_fits;

/// One (time, error) point of a method on a problem.
#[derive(Clone, Debug, Serialize)]
pub struct CostPoint {
    pub method: String,
    pub resolution: String,
    pub wall_s: f64,
    /// `|value - yardstick| / |yardstick|`, floored at 1e-16.
    pub error: f64,
    /// The method's own estimate of that error, where it makes one (drawn as an error bar from
    /// the actual error up to the estimate: the point must lie below the bar's top).
    pub estimate: Option<f64>,
    pub on_pareto_front: bool,
}

/// Speed against accuracy on one problem.
#[derive(Clone, Debug, Serialize)]
pub struct SpeedAccuracy {
    pub problem: String,
    pub yardstick: f64,
    pub points: Vec<CostPoint>,
}

/// Pull-off force `-F/F0` of a concave punch at one `d0/h` by each route.
#[derive(Clone, Debug, Serialize)]
pub struct PulloffPoint {
    pub punch: String,
    pub d0_over_h: f64,
    /// Converged solutions, annular branch, fixed load (absent: no stable annular state).
    pub fixed_load: Option<f64>,
    /// The paper's route on the paper's fitted formulas.
    pub paper_fits: Option<f64>,
    /// From full contact (rim criterion).
    pub full_contact: f64,
}

/// Everything the report holds beyond the comparison tables.
#[derive(Clone, Debug, Serialize)]
pub struct ReportExtras {
    pub speed_accuracy: Vec<SpeedAccuracy>,
    pub convergence: Vec<convergence::Study>,
    pub pulloff: Vec<PulloffPoint>,
    /// The paper's claims checked by this run.
    pub verdicts: Vec<Verdict>,
    /// The stored pull-off simulations (`verify/pulloff/`).
    pub pulloff_simulations: Vec<super::pulloff_records::PulloffRecord>,
    /// This run's single pull-off simulation (cone, `d0/h = 10`, the smallest default range), or
    /// why it failed.
    pub pulloff_live: std::result::Result<crate::cohesive::study::LiveSimulation, String>,
    pub wall_s: f64,
}

/// One claim of the paper, the numbers of this run, and the verdict.
#[derive(Clone, Debug, Serialize)]
pub struct Verdict {
    pub claim: String,
    pub numbers: String,
    pub verdict: String,
}

/// Check the paper's claims with this run's converged solutions.
fn verdicts(
    ring: &RingBemSolver,
    pulloff: &[PulloffPoint],
    simulations: &[super::pulloff_records::PulloffRecord],
) -> Result<Vec<Verdict>> {
    let mut out = Vec::new();
    // Section 2: the fits.
    let fits = crate::fit::run(ring)?;
    let worst: Vec<String> = fits
        .iter()
        .map(|f| {
            format!(
                "{} {:.1e} (best new form {:.1e})",
                f.name, f.paper_max_rel_err, f.best_max_rel_err
            )
        })
        .collect();
    out.push(Verdict {
        claim: "the fitted formulas (3), (8), (10) approximate the BEM data well".into(),
        numbers: format!("max relative errors on 0.05..0.99: {}", worst.join(", ")),
        verdict: if fits.iter().all(|f| f.paper_max_rel_err < 1e-2) {
            "agree".into()
        } else {
            "disagree near eps -> 1".into()
        },
    });
    // Section 3: the flat annulus detaches at the outer edge.
    let ratios = [0.05, 0.2, 0.4, 0.6, 0.8, 0.9, 0.95, 0.99];
    let mut outer = 0;
    for &e in &ratios {
        if adhesion::flat_annulus(ring, e)?.governing_edge == "outer" {
            outer += 1;
        }
    }
    out.push(Verdict {
        claim: "the annular flat punch always starts to detach at the outer boundary".into(),
        numbers: format!(
            "outer edge governs at {outer} of {} ratios in 0.05..0.99",
            ratios.len()
        ),
        verdict: if outer == ratios.len() {
            "agree".into()
        } else {
            "disagree".into()
        },
    });
    // Regime independence at d0/h = 1.
    let mut spreads = Vec::new();
    for kind in [PunchKind::Cone, PunchKind::Sphere] {
        let r = adhesion::concave(ring, kind, 1.0)?;
        if let (Some(l), Some(g)) = (r.fixed_load, r.fixed_grips) {
            spreads.push(format!(
                "{kind} {:.0} %",
                100.0 * (l.force - g.force).abs() / l.force.abs()
            ));
        }
    }
    out.push(Verdict {
        claim: "pull-off almost independent of fixed grips / fixed load".into(),
        numbers: format!("difference at d0/h = 1: {}", spreads.join(", ")),
        verdict: "holds roughly (where a stable annular state exists)".into(),
    });
    // +50 % / +60 % for d0 >> h.
    let strongest: Vec<String> = pulloff
        .iter()
        .filter(|p| p.d0_over_h >= 99.0)
        .map(|p| {
            format!(
                "{}: paper's route on its fits {}, converged annular {}, full contact {:.3} F0",
                p.punch,
                p.paper_fits.map_or("-".into(), |v| format!("{v:.3} F0")),
                p.fixed_load
                    .map_or("no stable state".into(), |v| format!("{v:.3} F0")),
                p.full_contact
            )
        })
        .collect();
    // The direct simulation (a second route, no JKR theory) at the largest d0/h stored.
    let direct: Vec<&crate::cohesive::study::PulloffStudy> = simulations
        .iter()
        .filter_map(|r| r.result.as_ref())
        .filter(|s| s.punch.is_concave() && s.d0_over_h.is_some_and(|x| x >= 10.0))
        .collect();
    let direct_numbers: Vec<String> = direct
        .iter()
        .filter_map(|s| {
            Some(format!(
                "{} d0/h = {}: direct simulation {:.3} +- {:.3} F0 (full contact {:.3}, paper's \
                 route {})",
                s.punch,
                s.d0_over_h?,
                s.extrapolated_over_f0?,
                s.error_bar?,
                s.full_contact_over_f0?,
                s.paper_route_over_f0
                    .map_or("-".into(), |v| format!("{v:.3}"))
            ))
        })
        .collect();
    let direct_refutes = !direct.is_empty()
        && direct.iter().all(|s| {
            s.agrees_with_jkr() == Some(true)
                && match (s.extrapolated_over_f0, s.error_bar, s.paper_route_over_f0) {
                    (Some(x), Some(bar), Some(p)) => (x - p).abs() > 3.0 * bar,
                    _ => false,
                }
        });
    out.push(Verdict {
        claim: "pull-off up to +50 % (cone) and +60 % (sphere) above F0 for d0 >> h".into(),
        numbers: if direct_numbers.is_empty() {
            format!("at d0/h = 100: {}", strongest.join("; "))
        } else {
            format!(
                "at d0/h = 100: {}; stored direct simulations: {}",
                strongest.join("; "),
                direct_numbers.join("; ")
            )
        },
        verdict: if direct_refutes {
            "disagree: reproduced only with the fitted formulas; the direct simulation (cohesive \
             zone, extrapolated to the JKR limit) lets go at the full-contact value, not the \
             paper's"
                .into()
        } else {
            "disagree: reproduced only with the fitted formulas".into()
        },
    });
    Ok(out)
}

/// File of the live simulation's force-displacement chart.
pub const PULLOFF_CURVE_CHART: &str = "pulloff-curve.svg";

/// The live simulation's force-displacement curve: pressing, pulling, the pull-off marked.
fn pulloff_curve_chart(live: &crate::cohesive::study::LiveSimulation) -> String {
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
    super::svg::linear_chart_with_markers(
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

/// The cone at `d0/h = 10` (hole closed) at the smallest default range (Tabor 36), on the study
/// mesh (level 3 of the adapted family; the committed disk level 2 without gmsh).
fn live_pulloff() -> Result<crate::cohesive::study::LiveSimulation> {
    use crate::cohesive::study;
    let case = study::Case {
        punch: PunchKind::Cone,
        eps: 0.0,
        d0_over_h: 10.0,
    };
    let mesh = study::study_mesh(0.0, study::STUDY_LEVEL)?;
    let smallest = study::DEFAULT_RANGES[study::DEFAULT_RANGES.len() - 1];
    study::simulate_once(case, smallest, &mesh)
}

fn floor(e: f64) -> f64 {
    e.abs().max(1e-16)
}

fn mark_pareto(points: &mut [CostPoint]) {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].wall_s.total_cmp(&points[b].wall_s));
    let mut best = f64::INFINITY;
    for i in order {
        if points[i].error < best {
            best = points[i].error;
            points[i].on_pareto_front = true;
        }
    }
}

fn timed<T>(f: impl FnOnce() -> Result<T>) -> Result<(T, f64)> {
    let start = Instant::now();
    let v = f()?;
    Ok((v, start.elapsed().as_secs_f64()))
}

fn point(method: &str, resolution: String, wall_s: f64, value: f64, yardstick: f64) -> CostPoint {
    CostPoint {
        method: method.into(),
        resolution,
        wall_s,
        error: floor((value - yardstick) / yardstick),
        estimate: None,
        on_pareto_front: false,
    }
}

/// [`point`] with the method's own error estimate.
fn estimated_point(
    method: &str,
    resolution: String,
    wall_s: f64,
    value: f64,
    yardstick: f64,
    estimate: Option<f64>,
) -> CostPoint {
    CostPoint {
        estimate,
        ..point(method, resolution, wall_s, value, yardstick)
    }
}

/// Tolerances of the FEM's full solve (meshes made for the scene) in the speed-accuracy study
/// of the default run; the nightly run adds 1e-8 (`verify compare --fem-tolerances`).
pub const DEFAULT_FEM_TOLERANCES: [f64; 3] = [1e-3, 1e-4, 1e-6];

/// Error against wall time for the flat annulus (`eps = 0.5`, `γ`), the sphere (`d = 1.5 h`,
/// `γ2`), the cone (`d = 2h`, `γ2`) and the flat annulus `eps = 0.3`: ring BEM at several node
/// counts or tolerances, FEM at the committed levels (P1, P2) where they exist, the FEM's full
/// solve at each of `fem_tolerances` (with gmsh), grid BEM at 64-256 cells per side, and the
/// stored FEniCSx results on the same state (their wall time and force, as stored).
pub fn speed_accuracy(
    ring: &RingBemSolver,
    fenicsx: &[FenicsxComparison],
    fem_tolerances: &[f64],
) -> Result<Vec<SpeedAccuracy>> {
    let rule = TanhSinhRule::new(1.0 / 16.0);
    // Flat annulus: the ring BEM at a few node counts (it converges geometrically).
    let yardstick = ring.flat(0.5, 1e-12)?.gamma.unwrap_or(f64::NAN);
    let mut points = Vec::new();
    for n in [3usize, 4, 5, 6, 8] {
        let (g, t) = timed(|| {
            let region = ContactRegion::Annulus { eps: 0.5 };
            let settings = RingBemSettings {
                nodes: n,
                quadrature_step: 1.0 / 16.0,
            };
            RingSystem::assemble(region, settings, &rule)
                .solve(&vec![1.0; n])
                .map(|f| 0.5 * f.force)
                .ok_or_else(|| Error::NoConvergence {
                    method: "ring-bem".into(),
                    reason: "singular".into(),
                })
        })?;
        points.push(point("ring-bem", format!("N = {n}"), t, g, yardstick));
    }
    let flat = CostProblem {
        kind: PunchKind::FlatAnnulus,
        eps: 0.5,
        family: Some("annulus-0.5"),
        load: FemLoad::Flat,
    };
    points.extend(fem_and_grid_points(&flat, yardstick)?);
    points.extend(fem_ladder_points(&flat, yardstick, fem_tolerances));
    points.extend(fenicsx_points(&flat, yardstick, fenicsx));
    mark_pareto(&mut points);
    let mut out = vec![SpeedAccuracy {
        problem: "flat annulus b/a = 0.5, gamma".into(),
        yardstick,
        points,
    }];
    // Sphere under depth control: the ring BEM at a few tolerances.
    let yardstick = ring
        .concave_at_depth(PunchKind::Sphere, 1.5, 1e-11)?
        .gamma2
        .unwrap_or(f64::NAN);
    let mut points = Vec::new();
    for tol in [1e-2, 1e-4, 1e-6, 1e-9] {
        let (s, t) = timed(|| ring.concave_at_depth(PunchKind::Sphere, 1.5, tol))?;
        points.push(estimated_point(
            "ring-bem",
            format!("tol {tol:.0e}"),
            t,
            s.gamma2.unwrap_or(f64::NAN),
            yardstick,
            Some(s.error_estimate),
        ));
    }
    let sphere = CostProblem {
        kind: PunchKind::Sphere,
        eps: 0.0,
        family: Some("disk"),
        load: FemLoad::ConcaveDepth(1.5),
    };
    points.extend(fem_and_grid_points(&sphere, yardstick)?);
    points.extend(fem_ladder_points(&sphere, yardstick, fem_tolerances));
    points.extend(fenicsx_points(&sphere, yardstick, fenicsx));
    mark_pareto(&mut points);
    out.push(SpeedAccuracy {
        problem: "sphere d/h = 1.5, gamma2".into(),
        yardstick,
        points,
    });
    // The cone and the flat annulus 0.3: the FEM's full solve against FEniCSx on the meshes the
    // FEM makes (and the committed ones), with the ring BEM and the grid BEM.
    let cone = CostProblem {
        kind: PunchKind::Cone,
        eps: 0.0,
        family: None,
        load: FemLoad::ConcaveDepth(2.0),
    };
    let thick = CostProblem {
        kind: PunchKind::FlatAnnulus,
        eps: 0.3,
        family: None,
        load: FemLoad::Flat,
    };
    for (problem, name) in [
        (cone, "cone d/h = 2, gamma2"),
        (thick, "flat annulus b/a = 0.3, gamma"),
    ] {
        let yardstick = problem.value_of_ring_bem(ring, 1e-11)?;
        let mut points = Vec::new();
        for tol in [1e-2, 1e-4, 1e-6, 1e-9] {
            let (value, t) = timed(|| problem.value_of_ring_bem(ring, tol))?;
            points.push(point(
                "ring-bem",
                format!("tol {tol:.0e}"),
                t,
                value,
                yardstick,
            ));
        }
        points.extend(fem_and_grid_points(&problem, yardstick)?);
        points.extend(fem_ladder_points(&problem, yardstick, fem_tolerances));
        points.extend(fenicsx_points(&problem, yardstick, fenicsx));
        mark_pareto(&mut points);
        out.push(SpeedAccuracy {
            problem: name.into(),
            yardstick,
            points,
        });
    }
    Ok(out)
}

/// The FEM's full solve (`--method fem --tol X`, default degree, meshes made for the scene) at
/// each tolerance, when gmsh is there; a tolerance it cannot meet is left out with a note on
/// standard error.
fn fem_ladder_points(problem: &CostProblem, yardstick: f64, tolerances: &[f64]) -> Vec<CostPoint> {
    if !fem_solver::gmsh_found() {
        return Vec::new();
    }
    let mut points = Vec::new();
    for &tolerance in tolerances {
        let degree = fem_solver::default_degree(tolerance);
        let options = FemOptions {
            degree,
            tolerance,
            mesh: None,
            poisson_ratio: 0.0,
            far_field: crate::fem::far_field::FarField::Boussinesq,
        };
        match timed(|| fem_solver::solve(problem.kind, problem.eps, problem.load, &options)) {
            Ok((s, t)) => points.push(estimated_point(
                "fem --tol",
                format!("tol {tolerance:.0e}, P{}", degree as u8),
                t,
                s.gamma.or(s.gamma2).unwrap_or(f64::NAN),
                yardstick,
                s.error_estimate,
            )),
            Err(e) => eprintln!("speed-accuracy: fem at tolerance {tolerance:e} left out: {e}"),
        }
    }
    points
}

/// The stored FEniCSx results of this state (punch, `b/a` or depth), at their stored wall time
/// (dolfinx on this machine; the value is `F/2`, i.e. `γ` at unit depth or `γ2` at `h = 1`).
fn fenicsx_points(
    problem: &CostProblem,
    yardstick: f64,
    fenicsx: &[FenicsxComparison],
) -> Vec<CostPoint> {
    fenicsx
        .iter()
        .filter(|c| {
            let r = &c.stored;
            r.punch == problem.kind
                && match problem.load {
                    FemLoad::ConcaveDepth(d) => (r.depth - d).abs() < 1e-12,
                    _ => {
                        (r.eps.unwrap_or(0.0) - problem.eps).abs() < 1e-12
                            && (r.depth - 1.0).abs() < 1e-12
                    }
                }
        })
        .map(|c| {
            let r = &c.stored;
            let name = c.file.trim_end_matches(".json");
            point(
                "FEniCSx (stored)",
                format!("{name}, {} dofs", r.dofs),
                r.wall_s,
                0.5 * r.force,
                yardstick,
            )
        })
        .collect()
}

/// A problem of the speed-accuracy study, as the FEM and the grid BEM see it.
struct CostProblem {
    kind: PunchKind,
    eps: f64,
    /// Committed mesh family, if there is one for this contact line.
    family: Option<&'static str>,
    load: FemLoad,
}

impl CostProblem {
    /// `γ` (flat) or `γ2` (concave) by the ring BEM at `tolerance`.
    fn value_of_ring_bem(&self, ring: &RingBemSolver, tolerance: f64) -> Result<f64> {
        let value = match self.load {
            FemLoad::ConcaveDepth(d) => ring.concave_at_depth(self.kind, d, tolerance)?.gamma2,
            _ => ring.flat(self.eps, tolerance)?.gamma,
        };
        Ok(value.unwrap_or(f64::NAN))
    }
}

/// The FEM (P1 and P2 on levels L0-L2) and the grid BEM (64² to 256²) on one problem; the value
/// is `γ` (flat) or `γ2` (concave).
fn fem_and_grid_points(problem: &CostProblem, yardstick: f64) -> Result<Vec<CostPoint>> {
    let mut points = Vec::new();
    for (degree, name) in [(Degree::Linear, "fem P1"), (Degree::Quadratic, "fem P2")] {
        let Some(family) = problem.family else {
            break;
        };
        for level in 0..3 {
            let mesh = fem_solver::mesh_directory().join(format!("{family}-L{level}.msh"));
            let options = FemOptions {
                degree,
                tolerance: 1e-3,
                mesh: Some(mesh),
                poisson_ratio: 0.0,
                far_field: crate::fem::far_field::FarField::Boussinesq,
            };
            let (s, t) =
                timed(|| fem_solver::solve(problem.kind, problem.eps, problem.load, &options))?;
            points.push(point(
                name,
                format!("L{level}"),
                t,
                s.gamma.or(s.gamma2).unwrap_or(f64::NAN),
                yardstick,
            ));
        }
    }
    let grid_load = match problem.load {
        FemLoad::ConcaveDepth(d) => GridLoad::Depth(d),
        _ => GridLoad::Depth(1.0),
    };
    for n in [64usize, 128, 256] {
        let (s, t) = timed(|| grid_contact::solve(problem.kind, problem.eps, n, grid_load, 1e-10))?;
        points.push(point(
            "grid-bem",
            format!("{n}²"),
            t,
            s.gamma.or(s.gamma2).unwrap_or(f64::NAN),
            yardstick,
        ));
    }
    Ok(points)
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

/// The dimensionless functions against eps: ring BEM curves, references, other methods' points.
fn function_charts(ring: &RingBemSolver, comparison: &ComparisonReport, dir: &Path) -> Result<()> {
    let ratios: Vec<f64> = (0..=60).map(|k| 0.99 * k as f64 / 60.0).collect();
    let flat: Vec<(f64, f64)> = ratios
        .iter()
        .map(|&e| Ok((e, ring.flat(e, 1e-10)?.gamma.unwrap_or(f64::NAN))))
        .collect::<Result<_>>()?;
    let fem_points: Vec<(f64, f64)> = comparison
        .fem
        .iter()
        .filter(|c| !c.punch.is_concave())
        .map(|c| (c.fem_eps, c.fem_value))
        .collect();
    let mut grid_points = Vec::new();
    for e in [0.0, 0.5, 0.9] {
        if let Ok(s) = grid_contact::solve(
            if e == 0.0 {
                PunchKind::Flat
            } else {
                PunchKind::FlatAnnulus
            },
            e,
            128,
            GridLoad::Depth(1.0),
            1e-10,
        ) {
            grid_points.push((e, s.gamma.unwrap_or(f64::NAN)));
        }
    }
    let chart = linear_chart(
        "flat annulus: gamma = F/(2 E* d a) against b/a",
        "eps = b/a",
        "gamma",
        &[
            Series {
                name: "ring BEM".into(),
                points: flat,
                bars: Vec::new(),
            },
            Series {
                name: "paper fit (3)".into(),
                points: ratios
                    .iter()
                    .map(|&e| (e, paper_fits::flat_gamma(e)))
                    .collect(),
                bars: Vec::new(),
            },
            Series {
                name: "FEM P2 (points)".into(),
                points: fem_points,
                bars: Vec::new(),
            },
            Series {
                name: "grid BEM 128² (points)".into(),
                points: grid_points,
                bars: Vec::new(),
            },
        ],
    );
    write(dir, "gamma-flat-annulus.svg", &chart)?;
    for kind in [PunchKind::Cone, PunchKind::Sphere] {
        let ratios: Vec<f64> = (1..=50).map(|k| 0.05 + 0.9 * k as f64 / 50.0).collect();
        let mut g1 = Vec::new();
        let mut g2 = Vec::new();
        for &e in &ratios {
            let s = ring.concave_at_ratio(kind, e, 1e-10)?;
            g1.push((e, s.gamma1.unwrap_or(f64::NAN)));
            g2.push((e, s.gamma2.unwrap_or(f64::NAN)));
        }
        let fit = |i: usize| -> Vec<(f64, f64)> {
            ratios
                .iter()
                .map(|&e| {
                    (
                        e,
                        if kind == PunchKind::Cone {
                            paper_fits::cone_gamma(i, e)
                        } else {
                            paper_fits::sphere_gamma(i, e)
                        },
                    )
                })
                .collect()
        };
        let fem: Vec<(f64, f64)> = comparison
            .fem
            .iter()
            .filter(|c| c.punch == kind && c.fem_eps > 0.0)
            .map(|c| (c.fem_eps, c.fem_value))
            .collect();
        let chart = linear_chart(
            &format!("{kind}: gamma1 = d/h and gamma2 = F/(2 E* h a) against b/a"),
            "eps = b/a",
            "gamma1, gamma2",
            &[
                Series {
                    name: "gamma1 ring BEM".into(),
                    points: g1,
                    bars: Vec::new(),
                },
                Series {
                    name: "gamma2 ring BEM".into(),
                    points: g2,
                    bars: Vec::new(),
                },
                Series {
                    name: "gamma1 paper fit".into(),
                    points: fit(1),
                    bars: Vec::new(),
                },
                Series {
                    name: "gamma2 paper fit".into(),
                    points: fit(2),
                    bars: Vec::new(),
                },
                Series {
                    name: "gamma2 FEM P2".into(),
                    points: fem,
                    bars: Vec::new(),
                },
            ],
        );
        write(dir, &format!("gammas-{}.svg", kind.name()), &chart)?;
    }
    Ok(())
}

/// Pressure profiles of the sphere at `d = 1.5 h`: ring BEM and azimuthally averaged grid BEM.
fn pressure_chart(ring: &RingBemSolver, dir: &Path) -> Result<()> {
    let state = ring.concave_at_depth(PunchKind::Sphere, 1.5, 1e-10)?;
    let bem: Vec<(f64, f64)> = state.pressure.iter().map(|&(r, p)| (r, p)).collect();
    let n = 256;
    let op = GridOperator::new(n, 2.0 / n as f64);
    let punch = discretise(PunchKind::Sphere, 0.0, n);
    let c = solve_contact(
        &op,
        &punch.allowed,
        &punch.profile,
        GridLoad::Depth(1.5),
        1e-10,
        10_000,
    )?;
    let bins = 64;
    let mut sum = vec![0.0; bins];
    let mut count = vec![0usize; bins];
    for i in 0..n {
        for j in 0..n {
            let r = cell_centre(n, i).hypot(cell_centre(n, j));
            if r < 1.0 {
                let b = ((r * bins as f64) as usize).min(bins - 1);
                sum[b] += c.pressure[i * n + j];
                count[b] += 1;
            }
        }
    }
    let grid: Vec<(f64, f64)> = (0..bins)
        .filter(|&b| count[b] > 0)
        .map(|b| ((b as f64 + 0.5) / bins as f64, sum[b] / count[b] as f64))
        .collect();
    let options = FemOptions {
        degree: Degree::Quadratic,
        tolerance: 1e-3,
        mesh: None,
        poisson_ratio: 0.0,
        far_field: crate::fem::far_field::FarField::Boussinesq,
    };
    let fem_state =
        fem_solver::solve(PunchKind::Sphere, 0.0, FemLoad::ConcaveDepth(1.5), &options)?;
    // Nodal estimates in the contact, clipped near the rim singularity for the chart.
    let fem: Vec<(f64, f64)> =
        crate::fem::contact::nodal_pressure(&fem_state.field.mesh, &fem_state.reactions)
            .into_iter()
            .filter(|&(r, p)| p > 0.0 && r < 0.99)
            .collect();
    let clip = |v: Vec<(f64, f64)>| -> Vec<(f64, f64)> {
        v.into_iter().filter(|&(r, _)| r < 0.99).collect()
    };
    let chart = linear_chart(
        "sphere d/h = 1.5: contact pressure p/(E* h/a) against r/a (r < 0.99 a)",
        "r/a",
        "p a / (E* h)",
        &[
            Series {
                name: "ring BEM (nodes)".into(),
                points: clip(bem),
                bars: Vec::new(),
            },
            Series {
                name: "grid BEM 256², averaged".into(),
                points: clip(grid),
                bars: Vec::new(),
            },
            Series {
                name: "FEM P2 (nodal)".into(),
                points: fem,
                bars: Vec::new(),
            },
        ],
    );
    write(dir, "pressure-sphere.svg", &chart)
}

fn write(dir: &Path, name: &str, text: &str) -> Result<()> {
    std::fs::write(dir.join(name), text).map_err(|e| Error::file("write", &dir.join(name), e))
}

/// Number of progress stages of [`write_report`].
pub const STAGES: usize = 6;

/// Write the report directory; returns the extras (also in report.json).
pub fn write_report(
    dir: &Path,
    comparison: &ComparisonReport,
    fenicsx: &[FenicsxComparison],
    operators: &[OperatorStatus],
    peers: &[PeerComparison],
    fem_tolerances: &[f64],
    mut progress: impl FnMut(&str),
) -> Result<ReportExtras> {
    let start = Instant::now();
    std::fs::create_dir_all(dir).map_err(|e| Error::file("create the directory", dir, e))?;
    let ring = RingBemSolver::new();
    progress("functions against eps");
    function_charts(&ring, comparison, dir)?;
    progress("speed against accuracy");
    let speed = speed_accuracy(&ring, fenicsx, fem_tolerances)?;
    for (k, sa) in speed.iter().enumerate() {
        write(dir, &format!("speed-accuracy-{k}.svg"), &speed_chart(sa))?;
    }
    progress("convergence studies");
    let mut studies = Vec::new();
    for (method, levels) in [(Method::GridBem, 3), (Method::Fem, 3)] {
        let study = convergence::run(
            StudyCase {
                punch: PunchKind::Sphere,
                eps: 0.0,
                depth: 1.5,
            },
            method,
            levels,
            |_| {},
        )?;
        write(
            dir,
            &format!("convergence-{}.svg", method.name()),
            &convergence::chart(&study),
        )?;
        write(
            dir,
            &format!("table-convergence-{}.csv", method.name()),
            &convergence::csv(&study)?,
        )?;
        studies.push(study);
    }
    progress("pressure profiles");
    pressure_chart(&ring, dir)?;
    progress("adhesion");
    let mut pulloff = Vec::new();
    for kind in [PunchKind::Cone, PunchKind::Sphere] {
        let mut series = vec![
            Series {
                name: "fixed load".into(),
                points: vec![],
                bars: Vec::new(),
            },
            Series {
                name: "paper fits".into(),
                points: vec![],
                bars: Vec::new(),
            },
            Series {
                name: "full contact".into(),
                points: vec![],
                bars: Vec::new(),
            },
        ];
        for k in 0..=8 {
            let s = 10f64.powf(-1.0 + 3.0 * k as f64 / 8.0);
            let r = adhesion::concave(&ring, kind, s)?;
            let fl = r.fixed_load.as_ref().map(|c| -c.force);
            let pf = r.paper_fits_fixed_load.map(|p| -p.1);
            let full = -r.full_contact.pulloff.force;
            if let Some(v) = fl {
                series[0].points.push((s, v));
            }
            if let Some(v) = pf {
                series[1].points.push((s, v));
            }
            series[2].points.push((s, full));
            pulloff.push(PulloffPoint {
                punch: kind.name().to_string(),
                d0_over_h: s,
                fixed_load: fl,
                paper_fits: pf,
                full_contact: full,
            });
        }
        write(
            dir,
            &format!("pulloff-{}.svg", kind.name()),
            &log_log_chart(
                &format!("{kind}: pull-off / F0 against d0/h"),
                "d0/h",
                "-F/F0",
                &series,
            ),
        )?;
    }
    progress("pull-off simulation");
    // A failure of this one simulation is shown in the report, not a failure of the report.
    let live = live_pulloff().map_err(|e| e.to_string());
    if let Ok(l) = &live {
        write(dir, PULLOFF_CURVE_CHART, &pulloff_curve_chart(l))?;
    }
    let simulations = super::pulloff_records::load()?;
    let verdicts = verdicts(&ring, &pulloff, &simulations)?;
    let extras = ReportExtras {
        verdicts,
        pulloff_simulations: simulations,
        pulloff_live: live,
        speed_accuracy: speed,
        convergence: studies,
        pulloff,
        wall_s: start.elapsed().as_secs_f64(),
    };
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
    super::html::write_index(dir, None)?;
    Ok(extras)
}

fn markdown(
    comparison: &ComparisonReport,
    fenicsx: &[FenicsxComparison],
    operators: &[OperatorStatus],
    peers: &[PeerComparison],
    extras: &ReportExtras,
    tables: &[ReportTable],
) -> String {
    let mut md = String::from("# ringcontact verification report\n\n");
    let bounded = comparison
        .rows
        .iter()
        .flat_map(|r| &r.comparisons)
        .filter(|c| c.agrees.is_some())
        .count();
    let failed = comparison.failures()
        + super::fenicsx::failures(fenicsx)
        + super::operator::failures(operators)
        + super::peers::failures(peers);
    let _ = writeln!(
        md,
        "**{} checks, {failed} failed.** Ring BEM against bounded references: {bounded}; consistency identities: {}; FEM against the ring BEM: {}; stored FEniCSx results: {}; stored FEniCSx operator comparisons: {}; stored peer results: {}.\n",
        bounded
            + comparison.identities.len()
            + comparison.fem.len()
            + fenicsx.len()
            + operators.len()
            + peers.len(),
        comparison.identities.len(),
        comparison.fem.len(),
        fenicsx.len(),
        operators.len(),
        peers.len()
    );
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
    md += "## Convergence (sphere, d/h = 1.5)\n\n";
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
    md += "## Charts\n\n![](gamma-flat-annulus.svg)\n![](gammas-cone.svg)\n![](gammas-sphere.svg)\n![](pressure-sphere.svg)\n![](pulloff-cone.svg)\n![](pulloff-sphere.svg)\n";
    md
}
