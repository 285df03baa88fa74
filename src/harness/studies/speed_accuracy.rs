//! Speed against accuracy: error against wall time of every method on the problems of
//! [`cases::speed_problems`].
//!
//! Each problem's points come from independent pieces, so that a run can be split into jobs
//! ([`crate::harness::report_jobs`]): the base points ([`base_points`]: ring BEM, FEM on the committed levels,
//! grid BEM), one point per FEM tolerance ([`ladder_point`]), and the stored FEniCSx results;
//! [`assemble`] joins them and marks the Pareto front.

use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::harness::cases::{self, RingPoints, SpeedProblem};

use super::UnitLoad;
use crate::harness::records::fenicsx::FenicsxComparison;
use ringcontact::error::Result;
use ringcontact::methods::Degree;
use ringcontact::methods::FarField;
use ringcontact::methods::{self, GridBem, Method, MethodOptions, RingBem};
use ringcontact::punch::PunchKind;

/// One (time, error) point of a method on a problem.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CostPoint {
    pub method: String,
    pub resolution: String,
    /// Median wall time of up to [`TIMING_RUNS`] runs in this process (fewer for a slow point:
    /// [`TIMING_BUDGET_S`]; a stored peer's: see `resolution`), seconds.
    pub wall_s: f64,
    /// Shortest and longest of those runs (`None` for a single stored time).
    #[serde(default)]
    pub wall_s_range: Option<(f64, f64)>,
    /// How many runs the time is the median of.
    #[serde(default = "one")]
    pub runs: usize,
    /// `|value - yardstick| / |yardstick|`, floored at 1e-16.
    pub error: f64,
    /// The method's own estimate of that error, where it makes one (drawn as an error bar from
    /// the actual error up to the estimate: the point must lie below the bar's top).
    pub estimate: Option<f64>,
    pub on_pareto_front: bool,
}

/// Speed against accuracy on one problem.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SpeedAccuracy {
    pub problem: String,
    pub yardstick: f64,
    pub points: Vec<CostPoint>,
}

/// Tolerances of the FEM's full solve (meshes made for the scene) in the speed-accuracy study
/// of the default run; the nightly run adds 1e-8 (`verify compare --fem-tolerances`).
pub const DEFAULT_FEM_TOLERANCES: [f64; 3] = [1e-3, 1e-4, 1e-6];

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

fn one() -> usize {
    1
}

/// Most runs of each timed point: its time is their median, shown with their range.
const TIMING_RUNS: usize = 3;

/// A point stops repeating once its runs have taken this long together (seconds): a run of a
/// second or more is timed once, of half a second twice. The longer the run, the smaller its
/// relative spread; the budget keeps the default report's timings within its minute.
const TIMING_BUDGET_S: f64 = 1.0;

/// The median wall time of a point's runs, and their range.
#[derive(Clone, Copy, Debug)]
struct Timing {
    median: f64,
    range: (f64, f64),
    runs: usize,
}

/// Run `f` one time after another, [`TIMING_RUNS`] times or until the runs have taken
/// [`TIMING_BUDGET_S`]; its (last) value and the [`Timing`] (the median of an even number of
/// runs is the mean of the middle two).
fn timed<T>(mut f: impl FnMut() -> Result<T>) -> Result<(T, Timing)> {
    let mut times = Vec::with_capacity(TIMING_RUNS);
    let mut value = None;
    while times.len() < TIMING_RUNS && times.iter().sum::<f64>() < TIMING_BUDGET_S {
        let start = Instant::now();
        value = Some(f()?);
        times.push(start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    let n = times.len();
    let timing = Timing {
        median: 0.5 * (times[(n - 1) / 2] + times[n / 2]),
        range: (times[0], times[n - 1]),
        runs: n,
    };
    Ok((value.expect("at least one run"), timing))
}

fn point(method: &str, resolution: String, time: Timing, value: f64, yardstick: f64) -> CostPoint {
    CostPoint {
        method: method.into(),
        resolution,
        wall_s: time.median,
        wall_s_range: Some(time.range),
        runs: time.runs,
        error: floor((value - yardstick) / yardstick),
        estimate: None,
        on_pareto_front: false,
    }
}

/// [`point`] with the method's own error estimate.
fn estimated_point(
    method: &str,
    resolution: String,
    time: Timing,
    value: f64,
    yardstick: f64,
    estimate: Option<f64>,
) -> CostPoint {
    CostPoint {
        estimate,
        ..point(method, resolution, time, value, yardstick)
    }
}

impl CostPoint {
    /// Whether the method's own estimate bounds its actual error (`None`: no estimate).
    pub(crate) fn estimate_bounds_error(&self) -> Option<bool> {
        self.estimate
            .map(|e| self.error <= e * (1.0 + 1e-9) || self.error <= 1e-15)
    }
}

/// Points whose own estimate does not bound their actual error (failed checks of the report).
pub(crate) fn unbounded_estimates(studies: &[SpeedAccuracy]) -> usize {
    studies
        .iter()
        .flat_map(|s| &s.points)
        .filter(|p| p.estimate_bounds_error() == Some(false))
        .count()
}

/// A problem of the speed-accuracy study: an index into [`cases::speed_problems`], written in
/// JSON by its case's name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Problem(usize);

impl Problem {
    /// Every problem, in the report's order.
    pub(crate) fn all() -> Vec<Problem> {
        (0..cases::speed_problems().len()).map(Problem).collect()
    }

    /// The problem's case.
    fn case(self) -> SpeedProblem {
        cases::speed_problems().swap_remove(self.0)
    }

    /// Short name (job ids, file names).
    pub(crate) fn slug(self) -> &'static str {
        self.case().slug
    }

    /// The problem named `slug`.
    pub(crate) fn from_slug(slug: &str) -> Option<Problem> {
        Problem::all().into_iter().find(|p| p.slug() == slug)
    }

    /// The chart's title.
    pub(crate) fn title(self) -> &'static str {
        self.case().title
    }

    /// About how long its base points take, in seconds (for the balance of the report's shards).
    pub(crate) fn expected_s(self) -> f64 {
        self.case().expected_s
    }

    /// The ring BEM's value the points are compared with: `γ` at tolerance 1e-12 for the
    /// problem whose points are node counts, the others' `γ` or `γ2` at 1e-11.
    pub(crate) fn yardstick(self, ring: &RingBem) -> Result<f64> {
        let cost = self.cost_problem();
        match self.case().ring_points {
            RingPoints::NodeCounts => Ok(ring.flat(cost.eps, 1e-12)?.gamma.unwrap_or(f64::NAN)),
            _ => cost.value_of_ring_bem(ring, 1e-11),
        }
    }

    fn cost_problem(self) -> CostProblem {
        let case = self.case();
        CostProblem {
            kind: case.kind,
            eps: case.eps,
            family: case.family,
            load: UnitLoad::of_depth(case.depth),
        }
    }
}

impl Serialize for Problem {
    fn serialize<S: serde::Serializer>(
        &self,
        serializer: S,
    ) -> std::result::Result<S::Ok, S::Error> {
        serializer.serialize_str(self.case().name)
    }
}

impl<'de> Deserialize<'de> for Problem {
    fn deserialize<D: serde::Deserializer<'de>>(
        deserializer: D,
    ) -> std::result::Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        Problem::all()
            .into_iter()
            .find(|p| p.case().name == name)
            .ok_or_else(|| serde::de::Error::custom(format!("unknown problem '{name}'")))
    }
}

/// The base points of one problem and the yardstick they are compared with.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct BasePoints {
    pub problem: Problem,
    /// The ring BEM's value at tolerance 1e-11 (flat `b/a = 0.5`: 1e-12).
    pub yardstick: f64,
    pub points: Vec<CostPoint>,
}

/// The yardstick and the base points of `problem`: the ring BEM (as its case's [`RingPoints`]
/// says), the FEM with P1 and P2 on the
/// committed levels L0-L2 where the problem has a committed family, and the grid BEM at 64² to
/// 256² cells.
pub(crate) fn base_points(ring: &RingBem, problem: Problem) -> Result<BasePoints> {
    let cost = problem.cost_problem();
    let yardstick = problem.yardstick(ring)?;
    let mut points = match problem.case().ring_points {
        RingPoints::NodeCounts => {
            // The ring BEM at a few node counts (it converges geometrically).
            let mut points = Vec::new();
            for n in [3usize, 4, 5, 6, 8] {
                let (g, t) = timed(|| ring.flat_on_nodes(cost.eps, n))?;
                points.push(point("ring-bem", format!("N = {n}"), t, g, yardstick));
            }
            points
        }
        RingPoints::EstimatedTolerances => {
            let depth = cost.load_depth();
            let mut points = Vec::new();
            for tol in [1e-2, 1e-4, 1e-6, 1e-9] {
                let (s, t) = timed(|| ring.concave_at_depth(&cost.kind, depth, tol))?;
                points.push(estimated_point(
                    "ring-bem",
                    format!("tol {tol:.0e}"),
                    t,
                    s.gamma2.unwrap_or(f64::NAN),
                    yardstick,
                    Some(s.error_estimate),
                ));
            }
            points
        }
        RingPoints::Tolerances => {
            let mut points = Vec::new();
            for tol in [1e-2, 1e-4, 1e-6, 1e-9] {
                let (value, t) = timed(|| cost.value_of_ring_bem(ring, tol))?;
                points.push(point(
                    "ring-bem",
                    format!("tol {tol:.0e}"),
                    t,
                    value,
                    yardstick,
                ));
            }
            points
        }
    };
    points.extend(fem_and_grid_points(&cost, yardstick)?);
    Ok(BasePoints {
        problem,
        yardstick,
        points,
    })
}

/// The FEM's full solve (`--method fem --tol X`, default degree, meshes made for the scene) at
/// `tolerance`, when gmsh is there (`None` without gmsh, and when the solve fails: the reason is
/// written to standard error and the point left out).
pub(crate) fn ladder_point(problem: Problem, yardstick: f64, tolerance: f64) -> Option<CostPoint> {
    if !ringcontact::mesh::provider::gmsh_available(&crate::harness::settings::data_paths()) {
        return None;
    }
    let cost = problem.cost_problem();
    let solve = || {
        let scene = super::unit_scene(cost.kind.clone(), cost.eps, cost.load, Some(tolerance))?;
        methods::solve_with(&scene, Method::Fem, &MethodOptions::default())
    };
    match timed(solve) {
        Ok((s, t)) => Some(estimated_point(
            "fem --tol",
            format!(
                "tol {tolerance:.0e}, P{}",
                s.fem.as_ref().map_or(0, |fem| fem.degree)
            ),
            t,
            s.gamma.or(s.gamma2).unwrap_or(f64::NAN),
            yardstick,
            s.error_estimate,
        )),
        Err(e) => {
            eprintln!("speed-accuracy: fem at tolerance {tolerance:e} left out: {e}");
            None
        }
    }
}

/// One problem's chart data: the base points, the FEM's points in the order of `ladder`, the
/// stored FEniCSx results of the same state; the Pareto front marked.
pub fn assemble(
    base: &BasePoints,
    ladder: &[Option<CostPoint>],
    fenicsx: &[FenicsxComparison],
) -> SpeedAccuracy {
    let mut points = base.points.clone();
    points.extend(ladder.iter().flatten().cloned());
    let benchmark = crate::harness::records::benchmarks::FenicsxSpeed::load().ok();
    points.extend(fenicsx_points(
        &base.problem.cost_problem(),
        base.yardstick,
        fenicsx,
        benchmark.as_ref(),
    ));
    mark_pareto(&mut points);
    SpeedAccuracy {
        problem: base.problem.title().into(),
        yardstick: base.yardstick,
        points,
    }
}

/// Error against wall time on every problem, in one process: [`base_points`], a
/// [`ladder_point`] per entry of `fem_tolerances` and the stored FEniCSx results, [`assemble`]d.
pub fn speed_accuracy(
    ring: &RingBem,
    fenicsx: &[FenicsxComparison],
    fem_tolerances: &[f64],
) -> Result<Vec<SpeedAccuracy>> {
    let mut out = Vec::new();
    for problem in Problem::all() {
        let base = base_points(ring, problem)?;
        let ladder: Vec<Option<CostPoint>> = fem_tolerances
            .iter()
            .map(|&t| ladder_point(problem, base.yardstick, t))
            .collect();
        out.push(assemble(&base, &ladder, fenicsx));
    }
    Ok(out)
}

/// The stored FEniCSx results of this state (punch, `b/a` or depth): their time is the
/// interleaved benchmark record's median (`benches/records/fenicsx-speed.json`, fastest
/// configuration) where it has the row, else the stored single run, said so in `resolution`
/// (the value is `F/2`, i.e. `γ` at unit depth or `γ2` at `h = 1`).
fn fenicsx_points(
    problem: &CostProblem,
    yardstick: f64,
    fenicsx: &[FenicsxComparison],
    benchmark: Option<&crate::harness::records::benchmarks::FenicsxSpeed>,
) -> Vec<CostPoint> {
    fenicsx
        .iter()
        .filter(|c| {
            let r = &c.stored;
            r.punch == problem.kind
                && match problem.load {
                    UnitLoad::Depth(d) => (r.depth - d).abs() < 1e-12,
                    UnitLoad::Flat => {
                        (r.eps.unwrap_or(0.0) - problem.eps).abs() < 1e-12
                            && (r.depth - 1.0).abs() < 1e-12
                    }
                }
        })
        .map(|c| {
            let r = &c.stored;
            let name = c.file.trim_end_matches(".json");
            // The interleaved record's median where it has the row, else the stored single run.
            let (time, origin) = match benchmark.and_then(|b| b.row(name)) {
                Some(row) => (
                    Timing {
                        median: row.median,
                        range: (row.min, row.max),
                        runs: row.runs,
                    },
                    format!("{}, median of the interleaved record", row.configuration),
                ),
                None => (
                    Timing {
                        median: r.wall_s,
                        range: (r.wall_s, r.wall_s),
                        runs: 1,
                    },
                    "one stored run, not interleaved".to_string(),
                ),
            };
            CostPoint {
                wall_s_range: (time.runs > 1).then_some(time.range),
                ..point(
                    "FEniCSx (stored)",
                    format!("{name}, {} dofs; {origin}", r.dofs),
                    time,
                    0.5 * r.force,
                    yardstick,
                )
            }
        })
        .collect()
}

/// A problem of the speed-accuracy study, as the FEM and the grid BEM see it.
struct CostProblem {
    kind: PunchKind,
    eps: f64,
    /// Committed mesh family, if there is one for this contact line.
    family: Option<&'static str>,
    load: UnitLoad,
}

impl CostProblem {
    /// The depth `d/h` of a concave problem (0 for a flat one).
    fn load_depth(&self) -> f64 {
        match self.load {
            UnitLoad::Depth(d) => d,
            UnitLoad::Flat => 0.0,
        }
    }

    /// `γ` (flat) or `γ2` (concave) by the ring BEM at `tolerance`.
    fn value_of_ring_bem(&self, ring: &RingBem, tolerance: f64) -> Result<f64> {
        let value = match self.load {
            UnitLoad::Depth(d) => ring.concave_at_depth(&self.kind, d, tolerance)?.gamma2,
            UnitLoad::Flat => ring.flat(self.eps, tolerance)?.gamma,
        };
        Ok(value.unwrap_or(f64::NAN))
    }
}

/// The FEM (P1 and P2 on levels L0-L2) and the grid BEM (64² to 256²) on one problem; the value
/// is `γ` (flat) or `γ2` (concave).
fn fem_and_grid_points(problem: &CostProblem, yardstick: f64) -> Result<Vec<CostPoint>> {
    let mut points = Vec::new();
    // Each FEM point is one model on a committed level (tolerance 1e-3: its estimate unused).
    let scene = super::unit_scene(problem.kind.clone(), problem.eps, problem.load, Some(1e-3))?;
    for (degree, name) in [(Degree::Linear, "fem P1"), (Degree::Quadratic, "fem P2")] {
        let Some(family) = problem.family else {
            break;
        };
        for level in 0..3 {
            let mesh =
                crate::harness::settings::mesh_directory().join(format!("{family}-L{level}.msh"));
            let fem = methods::Fem {
                mesh: Some(mesh),
                degree: Some(degree),
                far_field: Some(FarField::Boussinesq),
                ..crate::harness::settings::fem()
            };
            let (s, t) = timed(|| fem.state(&scene))?;
            points.push(point(
                name,
                format!("L{level}"),
                t,
                s.gamma.or(s.gamma2).unwrap_or(f64::NAN),
                yardstick,
            ));
        }
    }
    // The paper's method as peers run it: the requested grid alone, residual 1e-10.
    let scene = super::unit_scene(problem.kind.clone(), problem.eps, problem.load, None)?;
    for n in [64usize, 128, 256] {
        let grid = GridBem {
            cells: n,
            with_estimate: false,
            ..GridBem::default()
        };
        let (s, t) = timed(|| grid.state(&scene))?;
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
