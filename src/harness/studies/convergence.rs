//! Mesh-convergence studies (solution verification, `docs/methods.md`).
//!
//! For a sequence of refinements of one method: size `h`, unknowns, value, error against the
//! yardstick (the ring BEM at 1e-11), the observed order from each consecutive triple,
//! `p = |ln|ε32/ε21| + q(p)| / ln r21`, `q(p) = ln((r21^p - s)/(r32^p - s))`, `s = sign(ε32/ε21)`
//! (Celik et al. 2008, solved by fixed-point iteration; for a constant ratio this is
//! `ln((f3 - f2)/(f2 - f1)) / ln r`), the Richardson extrapolate of the three finest,
//! `f_ext = f1 + (f1 - f2)/(r21^p - 1)`, the fine-grid convergence index
//! `GCI = 1.25 |(f1 - f2)/f1| / (r21^p - 1)` and the asymptotic-range check: the order of the
//! finest triple divided by the order of the previous one (close to 1 in the asymptotic range;
//! needs four levels; with `p` from the same three solutions the textbook ratio
//! `GCI_23 / (r^p GCI_12)` would be 1 by construction).

use std::time::Instant;

use serde::Serialize;

use ringcontact::bem::grid::GridLoad;
use ringcontact::bem::grid_contact;
use ringcontact::bem::ring::{ContactRegion, RingSystem};
use ringcontact::bem::ring_contact::RingBemSolver;
use ringcontact::error::{Error, Result};
use ringcontact::fem::{self as fem_solver, FemLoad, FemOptions};
use ringcontact::mesh::provider;
use ringcontact::mesh::triangulation::Degree;
use ringcontact::methods::Method;
use ringcontact::numerics::richardson::observed_order;
use ringcontact::numerics::tanh_sinh::TanhSinhRule;
use ringcontact::punch::PunchKind;

use crate::harness::report::svg;
use crate::harness::report::table::{Column, Format, Table};

/// One refinement level.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Level {
    pub label: String,
    /// Representative size: cell side (grid BEM), `1/sqrt(dofs)` (FEM), `1/N` (ring BEM).
    pub size: f64,
    pub unknowns: usize,
    /// `γ` (flat punches) or `γ2` (concave punches, depth control).
    pub value: f64,
    pub error: f64,
    pub wall_s: f64,
    /// Observed order from this level and the two coarser ones.
    pub observed_order: Option<f64>,
}

/// A convergence study.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Study {
    #[serde(flatten)]
    pub punch: PunchKind,
    pub method: String,
    pub quantity: String,
    pub yardstick: f64,
    pub levels: Vec<Level>,
    pub richardson: Option<f64>,
    pub richardson_error: Option<f64>,
    /// The error bar of the finest level ([`error_bar`]), never below `error_floor`.
    pub gci_fine: Option<f64>,
    /// How that bar was made (the GCI's safety factor and order, or the oscillation's spread).
    #[serde(default)]
    pub bar_method: Option<String>,
    /// Whether the bar bounds the finest level's actual error against the yardstick (`false` is
    /// a failed check of the report and of `verify convergence`).
    #[serde(default)]
    pub bar_bounds_error: Option<bool>,
    /// Observed order of the finest triple over that of the previous triple.
    pub asymptotic_ratio: Option<f64>,
    /// Why the study stopped before its last level (the levels before it are kept), if it did.
    #[serde(default)]
    pub stopped: Option<String>,
    /// FEM: the unresolved error component of its finest model
    /// ([`fem_solver::UNRESOLVED_COMPONENT`]), which refinement does not reduce and a GCI from
    /// level differences cannot see.
    pub error_floor: Option<f64>,
}

/// `(f_ext, GCI_fine, asymptotic ratio)` from the three finest levels (finest first).
fn richardson(f1: f64, f2: f64, f3: f64, r21: f64, r32: f64) -> Option<(f64, f64, f64)> {
    let p = observed_order(f1, f2, f3, r21, r32)?;
    let extrapolate = f1 + (f1 - f2) / (r21.powf(p) - 1.0);
    let gci12 = 1.25 * ((f1 - f2) / f1).abs() / (r21.powf(p) - 1.0);
    let gci23 = 1.25 * ((f2 - f3) / f2).abs() / (r32.powf(p) - 1.0);
    Some((extrapolate, gci12, gci23 / (r21.powf(p) * gci12)))
}

/// What to study.
#[derive(Clone, Debug)]
pub struct StudyCase {
    pub punch: PunchKind,
    /// `b/a` of the flat annulus.
    pub eps: f64,
    /// `d/h` of a concave punch.
    pub depth: f64,
}

/// Finest adapted mesh level a FEM convergence study runs with quadratic elements (about 1.7 M
/// unknowns).
const STUDY_MAX_ADAPTED_LEVEL: usize = 5;
/// Finest adapted level with cubic elements (level 3: about 0.6 M unknowns, force error near
/// 2e-9).
const STUDY_MAX_CUBIC_LEVEL: i32 = 3;

/// The FEM study's meshes and degree: with gmsh, the adapted family from its coarsest level
/// (`g = 0.89`) with cubic elements (errors from about 5e-4 down to a few 1e-9 in six
/// levels); without, the committed levels with quadratic elements.
fn fem_study_ladder(case: &StudyCase) -> (Vec<provider::MeshRequest>, Degree) {
    if fem_solver::gmsh_found(&crate::harness::settings::data_paths()) {
        let start = fem_solver::contact_start(&case.punch, case.eps);
        let ladder = (provider::ADAPTED_MIN_LEVEL..=STUDY_MAX_CUBIC_LEVEL)
            .map(|level| provider::MeshRequest::Adapted {
                contact_start: start,
                level,
                free_edge: None,
                edge_uncertainty: 0.0,
                target: None,
            })
            .collect();
        return (ladder, Degree::Cubic);
    }
    let ladder = fem_solver::mesh_sequence(
        &crate::harness::settings::data_paths(),
        case.punch.clone(),
        case.eps,
        1e-3,
    )
    .into_iter()
    .filter(|r| match r {
        provider::MeshRequest::Adapted { level, .. } => *level <= STUDY_MAX_ADAPTED_LEVEL as i32,
        _ => true,
    })
    .collect();
    (ladder, Degree::Quadratic)
}

/// The FEM study's mesh levels for a punch with two free edges (a free band): the free-edges
/// family from its coarsest level to [`STUDY_MAX_ADAPTED_LEVEL`], quadratic elements (gmsh
/// needed: the contact line is scaled to the load).
fn free_edges_study_levels() -> Vec<i32> {
    (provider::ADAPTED_MIN_LEVEL..=STUDY_MAX_ADAPTED_LEVEL as i32).collect()
}

/// Refuse a study whose finest level cannot be run, before running the coarser ones.
pub(crate) fn check_levels(case: &StudyCase, method: Method, levels: usize) -> Result<()> {
    if method == Method::GridBem && (64usize << (levels.max(1) - 1)) > grid_contact::MAX_GRID {
        return Err(Error::OutOfRange {
            method: "grid-bem".into(),
            reason: format!(
                "{levels} levels would end at a {0} x {0} grid; at most {1} levels (64 .. {2})",
                64usize << (levels - 1),
                (grid_contact::MAX_GRID / 64).trailing_zeros() + 1,
                grid_contact::MAX_GRID
            ),
        });
    }
    if method == Method::Fem {
        // Levels past adapted level 5 (P2, about 1.7 M unknowns) or 3 (P3, 0.6 M) take more
        // than minutes and tens of GB; the study stops there.
        let available = if case.punch.has_rim() {
            fem_study_ladder(case).0.len()
        } else {
            free_edges_study_levels().len()
        };
        if levels > available {
            return Err(Error::OutOfRange {
                method: "fem".into(),
                reason: format!(
                    "the FEM study has {available} mesh levels here (up to adapted level \
                     {STUDY_MAX_ADAPTED_LEVEL} with P2, about 1.7 M unknowns, or \
                     {STUDY_MAX_CUBIC_LEVEL} with P3, 0.6 M); asked for {levels}"
                ),
            });
        }
    }
    Ok(())
}

/// Run a study of `levels` refinements with `method`; `progress` is called after each level. A
/// level that fails ends the study there: the levels before it are kept and the reason is in
/// [`Study::stopped`] (an error only when the first level fails).
pub fn run(
    case: StudyCase,
    method: Method,
    levels: usize,
    mut progress: impl FnMut(&Level),
) -> Result<Study> {
    check_levels(&case, method, levels)?;
    let yardstick = yardstick(&case)?;
    let mut out: Vec<Level> = Vec::new();
    let mut located = LocatedEdges::default();
    let mut stopped = None;
    let quiet_terminal = std::io::IsTerminal::is_terminal(&std::io::stderr());
    for k in 0..levels {
        if !quiet_terminal && k >= 3 {
            // Off a terminal, say which level is running before the long ones (no bar there).
            eprintln!(
                "convergence: {} level {} of {levels} ...",
                method.name(),
                k + 1
            );
        }
        let computed = match compute_level(&case, method, k, located, yardstick) {
            Ok(computed) => computed,
            Err(e) if k > 0 => {
                stopped = Some(format!("level {} of {levels} failed: {e}", k + 1));
                break;
            }
            Err(e) => return Err(e),
        };
        located = LocatedEdges::of(&computed);
        out.push(computed.level);
        set_observed_orders(&mut out);
        progress(&out[out.len() - 1]);
    }
    Ok(Study {
        stopped,
        ..assemble(&case, method, yardstick, out)
    })
}

/// The ring BEM's value the study measures against (tolerance 1e-11): `γ2` at the depth of a
/// concave punch, `γ` of a flat one.
pub(crate) fn yardstick(case: &StudyCase) -> Result<f64> {
    let ring = RingBemSolver::new();
    Ok(if case.punch.is_concave() {
        ring.concave_at_depth(&case.punch, case.depth, 1e-11)?
            .gamma2
            .unwrap_or(f64::NAN)
    } else {
        ring.flat(case.eps, 1e-11)?.gamma.unwrap_or(f64::NAN)
    })
}

/// One level of a study and, for the FEM on a concave punch, the free edge `b/a` it located (the
/// next level refines around it).
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct ComputedLevel {
    pub level: Level,
    pub free_edge: Option<f64>,
    /// A free band's outer free edge `c/a` (the FEM's next level refines around both).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_free_edge: Option<f64>,
}

/// Level `k` (from 0) of a study on its own, as a job of a plan: the FEM on a concave punch
/// first solves the coarser levels for the free edge each refines around (as [`run`] does),
/// so the level is the same as in one process.
pub fn level(case: StudyCase, method: Method, k: usize, levels: usize) -> Result<ComputedLevel> {
    check_levels(&case, method, levels)?;
    if k >= levels {
        return Err(Error::OutOfRange {
            method: method.name().into(),
            reason: format!("level {k} of a study of {levels} levels (levels count from 0)"),
        });
    }
    let yardstick = yardstick(&case)?;
    let mut located = LocatedEdges::default();
    if method == Method::Fem && case.punch.is_concave() {
        for coarser in 0..k {
            located = LocatedEdges::of(&compute_level(&case, method, coarser, located, yardstick)?);
        }
    }
    compute_level(&case, method, k, located, yardstick)
}

/// Level `k` of a study when level `k - 1` located the free edge `previous_edge` (the FEM on a
/// concave punch refines around it; other methods ignore it). Plans, which call it, hold one
/// edge: they refuse a free band, whose levels refine around two ([`level`] runs those).
pub(crate) fn level_after(
    case: StudyCase,
    method: Method,
    k: usize,
    levels: usize,
    previous_edge: Option<f64>,
) -> Result<ComputedLevel> {
    check_levels(&case, method, levels)?;
    let located = LocatedEdges {
        inner: previous_edge,
        outer: None,
    };
    compute_level(&case, method, k, located, yardstick(&case)?)
}

/// One level's solve: its label, size `h`, unknowns and value, and (FEM, concave punches) the
/// free edge found.
struct Sized {
    label: String,
    size: f64,
    unknowns: usize,
    value: f64,
    free_edge: Option<f64>,
    outer_edge: Option<f64>,
}

/// The free edges a FEM level located (`b/a`, and a free band's `c/a`), around which the next
/// level is refined; none before the first level and for the other methods.
#[derive(Clone, Copy, Debug, Default)]
struct LocatedEdges {
    inner: Option<f64>,
    outer: Option<f64>,
}

impl LocatedEdges {
    fn of(level: &ComputedLevel) -> Self {
        Self {
            inner: level.free_edge,
            outer: level.outer_free_edge,
        }
    }
}

/// Level `k` of a study, the FEM refining around the edges the level below `located`
/// (concave punches and free bands).
fn compute_level(
    case: &StudyCase,
    method: Method,
    k: usize,
    located: LocatedEdges,
    yardstick: f64,
) -> Result<ComputedLevel> {
    let start = Instant::now();
    let solved = match method {
        Method::GridBem => grid_bem_level(case, k)?,
        Method::Fem if !case.punch.has_rim() => free_edges_fem_level(case, k, located)?,
        Method::Fem => fem_level(case, k, located.inner)?,
        Method::RingBem => ring_bem_level(case, k)?,
        Method::Reference | Method::Auto => {
            return Err(Error::Unsupported {
                method: method.name().into(),
                reason: "convergence studies refine one method: choose ring-bem, fem or grid-bem"
                    .into(),
            })
        }
    };
    let Sized {
        label,
        size,
        unknowns,
        value,
        free_edge,
        outer_edge,
    } = solved;
    let level = Level {
        label,
        size,
        unknowns,
        value,
        error: (value - yardstick) / yardstick,
        wall_s: start.elapsed().as_secs_f64(),
        observed_order: None,
    };
    Ok(ComputedLevel {
        level,
        free_edge,
        outer_free_edge: outer_edge,
    })
}

/// The grid BEM on `(64 · 2^k)²` cells, on the square `[-a, a]²` (a free band: one square for
/// every level, [`grid_contact::band_square`] from a 32² solve).
fn grid_bem_level(case: &StudyCase, k: usize) -> Result<Sized> {
    let concave = case.punch.is_concave();
    let n = 64usize << k;
    let load = GridLoad::Depth(if concave { case.depth } else { 1.0 });
    let (s, half_size) = if case.punch.has_rim() {
        (
            grid_contact::solve(case.punch.clone(), case.eps, n, load, 1e-10)?,
            1.0,
        )
    } else {
        let half_size = grid_contact::band_square(&case.punch, 32, load, 1e-10)?;
        let s = grid_contact::solve_band_on_square(&case.punch, n, half_size, load, 1e-10)?;
        (s, half_size)
    };
    let value = s.gamma.or(s.gamma2).unwrap_or(f64::NAN);
    Ok(Sized {
        label: format!("{n}x{n}"),
        size: 2.0 * half_size / n as f64,
        unknowns: n * n,
        value,
        free_edge: None,
        outer_edge: None,
    })
}

/// The FEM options of a study's levels: elements of `degree`, `ν = 0`, Boussinesq's far
/// field, the solve's own tolerance 1e-3 (each level is one model, its estimate unused).
fn study_options(degree: Degree) -> FemOptions {
    FemOptions {
        linear_solver: crate::harness::settings::linear_solver(),
        trace: crate::harness::settings::trace(),
        data: crate::harness::settings::data_paths(),
        progress: crate::harness::progress::fem_progress(),
        degree,
        tolerance: 1e-3,
        mesh: None,
        poisson_ratio: 0.0,
        far_field: ringcontact::discretisation::far_field::FarField::Boussinesq,
    }
}

/// The FEM on level `k` of its study ladder, refined around `previous_edge` (concave punches).
fn fem_level(case: &StudyCase, k: usize, previous_edge: Option<f64>) -> Result<Sized> {
    let concave = case.punch.is_concave();
    let (sequence, degree) = fem_study_ladder(case);
    let Some(request) = sequence.get(k).cloned() else {
        return Err(Error::OutOfRange {
            method: "fem".into(),
            reason: format!("the FEM has {} mesh levels", sequence.len()),
        });
    };
    // Concave punches: refine around the free edge of the previous level's solve.
    let request = request.with_free_edge(previous_edge, 0.0);
    let label = request.label();
    let provided = provider::provide(
        &crate::harness::settings::data_paths(),
        &request,
        "the FEM convergence study",
    )?;
    let load = if concave {
        FemLoad::ConcaveDepth(case.depth)
    } else {
        FemLoad::Flat
    };
    let options = study_options(degree);
    let s = fem_solver::solve_on_mesh(case.punch.clone(), case.eps, load, &provided, &options)?;
    let value = s.gamma.or(s.gamma2).unwrap_or(f64::NAN);
    Ok(Sized {
        label: format!("{label} P{}", degree as u8),
        size: 1.0 / (s.dofs as f64).sqrt(),
        unknowns: s.dofs,
        value,
        free_edge: concave.then_some(s.eps),
        outer_edge: None,
    })
}

/// The FEM on level `k` of the free-edges family (a free band, quadratic elements): the first
/// level refined where the rigid profile meets the surface, each further one around both edges
/// the level below located.
fn free_edges_fem_level(case: &StudyCase, k: usize, located: LocatedEdges) -> Result<Sized> {
    let levels = free_edges_study_levels();
    let Some(&level) = levels.get(k) else {
        return Err(Error::OutOfRange {
            method: "fem".into(),
            reason: format!(
                "the FEM has {} mesh levels for the {}",
                levels.len(),
                case.punch
            ),
        });
    };
    let edges = match (located.inner, located.outer) {
        (Some(inner), Some(outer)) => Some([(inner, 0.0), (outer, 0.0)]),
        _ => None,
    };
    let options = study_options(Degree::Quadratic);
    let load = FemLoad::ConcaveDepth(case.depth);
    let s =
        fem_solver::solve_free_edges_on_level(case.punch.clone(), load, level, edges, &options)?;
    Ok(Sized {
        label: format!("free-edges-L{level} P2"),
        size: 1.0 / (s.dofs as f64).sqrt(),
        unknowns: s.dofs,
        value: s.gamma2.unwrap_or(f64::NAN),
        free_edge: Some(s.eps),
        outer_edge: s.outer_edge,
    })
}

/// The ring BEM with `6 + 2k` nodes (flat punches).
fn ring_bem_level(case: &StudyCase, k: usize) -> Result<Sized> {
    let concave = case.punch.is_concave();
    let n = 6 + 2 * k;
    let rule = TanhSinhRule::new(1.0 / 16.0);
    let region = if case.eps > 0.0 {
        ContactRegion::Annulus { eps: case.eps }
    } else {
        ContactRegion::Disk
    };
    if concave {
        return Err(Error::Unsupported {
            method: "ring-bem".into(),
            reason: "convergence studies of the ring BEM cover the flat punches (its concave states are certified by the node ladder)".into(),
        });
    }
    let system = RingSystem::assemble(region, n, &rule);
    let field = system
        .solve(&vec![1.0; n])
        .ok_or_else(|| Error::NoConvergence {
            method: "ring-bem".into(),
            reason: "singular system".into(),
        })?;
    Ok(Sized {
        label: format!("N = {n}"),
        size: 1.0 / n as f64,
        unknowns: n,
        value: 0.5 * field.force,
        free_edge: None,
        outer_edge: None,
    })
}

/// The observed order of the last level from it and the two coarser ones.
fn set_observed_orders(out: &mut [Level]) {
    let m = out.len();
    if m >= 3 {
        let (f1, f2, f3) = (out[m - 1].value, out[m - 2].value, out[m - 3].value);
        let (r21, r32) = (
            out[m - 2].size / out[m - 1].size,
            out[m - 3].size / out[m - 2].size,
        );
        out[m - 1].observed_order = observed_order(f1, f2, f3, r21, r32);
    }
}

/// The study from its levels (coarsest first): observed orders, Richardson extrapolate, GCI of
/// the finest level (never below the FEM's unresolved component).
pub fn assemble(case: &StudyCase, method: Method, yardstick: f64, levels: Vec<Level>) -> Study {
    let concave = case.punch.is_concave();
    let mut out: Vec<Level> = Vec::new();
    for level in levels {
        out.push(Level {
            observed_order: None,
            ..level
        });
        set_observed_orders(&mut out);
    }
    let m = out.len();
    let ratio = match (m >= 4).then(|| (out[m - 1].observed_order, out[m - 2].observed_order)) {
        Some((Some(p1), Some(p2))) => Some(p1 / p2),
        _ => None,
    };
    let expected = expected_order(case, method);
    let (richardson, bar) = if m >= 3 {
        let (f1, f2, f3) = (out[m - 1].value, out[m - 2].value, out[m - 3].value);
        let (r21, r32) = (
            out[m - 2].size / out[m - 1].size,
            out[m - 3].size / out[m - 2].size,
        );
        let extrapolate = richardson(f1, f2, f3, r21, r32).map(|(e, _, _)| e);
        (
            extrapolate,
            error_bar([f1, f2, f3], r21, r32, expected, ratio),
        )
    } else {
        (None, None)
    };
    let error_floor = (method == Method::Fem).then_some(fem_solver::UNRESOLVED_COMPONENT);
    let gci = bar
        .as_ref()
        .map(|b| b.value.max(error_floor.unwrap_or(0.0)));
    let bar_bounds_error = match (gci, out.last()) {
        (Some(g), Some(finest)) => Some(finest.error.abs() <= g),
        _ => None,
    };
    Study {
        punch: case.punch.clone(),
        method: method.name().to_string(),
        quantity: if concave {
            format!("gamma2 at d/h = {}", case.depth)
        } else {
            format!("gamma at b/a = {}", case.eps)
        },
        yardstick,
        richardson_error: richardson.map(|e| (e - yardstick) / yardstick),
        levels: out,
        richardson,
        gci_fine: gci,
        bar_method: bar.map(|b| b.method),
        bar_bounds_error,
        asymptotic_ratio: ratio,
        stopped: None,
        error_floor,
    }
}

/// The order at which a method's value converges under refinement, where one is known: the
/// grid BEM's piecewise-constant pressure 1 (observed nearer 0.7 with the staircase edge), the
/// FEM's force, a functional of the solution, `2p` for elements of degree `p` on meshes graded
/// toward the singular edges. The ring BEM converges faster than any power (none).
fn expected_order(case: &StudyCase, method: Method) -> Option<f64> {
    match method {
        Method::GridBem => Some(1.0),
        Method::Fem if !case.punch.has_rim() => Some(2.0 * Degree::Quadratic as u8 as f64),
        Method::Fem => Some(2.0 * fem_study_ladder(case).1 as u8 as f64),
        _ => None,
    }
}

/// The finest level's error bar and how it was made.
#[derive(Clone, Debug)]
pub struct ErrorBar {
    pub value: f64,
    pub method: String,
}

/// The error bar of the finest of three levels `f = [f1, f2, f3]` (finest first) with
/// refinement ratios `r21`, `r32` (Roache; Celik et al. 2008):
/// - oscillatory convergence (`f2 - f1` and `f3 - f2` of opposite signs): no order exists; the
///   bar is 3 times the spread of the three values, relative to `f1`;
/// - in the asymptotic range (the last two triples' orders within 10 % of each other, or, with
///   three levels, the observed order within 10 % of the `expected` one): the GCI
///   `1.25 |f1 - f2| / |f1| / (r21^p - 1)` with the observed order `p`;
/// - otherwise the GCI with the safety factor 3 and the order `min(p, expected)`: an order
///   above the method's, which a lucky cancellation between levels gives, shrinks the bar.
pub fn error_bar(
    f: [f64; 3],
    r21: f64,
    r32: f64,
    expected: Option<f64>,
    order_ratio: Option<f64>,
) -> Option<ErrorBar> {
    let [f1, f2, f3] = f;
    let (e21, e32) = (f2 - f1, f3 - f2);
    if e21 * e32 < 0.0 {
        let spread = f.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
            - f.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        return Some(ErrorBar {
            value: 3.0 * spread / f1.abs(),
            method: "oscillatory convergence: 3 x the spread of the three finest levels".into(),
        });
    }
    let p = observed_order(f1, f2, f3, r21, r32)?;
    let asymptotic = match (order_ratio, expected) {
        (Some(r), _) => (r - 1.0).abs() < 0.1,
        (None, Some(q)) => (p / q - 1.0).abs() < 0.1,
        (None, None) => false,
    };
    let (safety, order, how) = if asymptotic {
        (1.25, p, format!("GCI, Fs = 1.25, observed order {p:.2}"))
    } else {
        let order = expected.map_or(p, |q| p.min(q));
        (
            3.0,
            order,
            format!(
                "GCI, Fs = 3 (not shown to be in the asymptotic range), order {order:.2} \
                 (observed {p:.2}{})",
                expected.map_or(String::new(), |q| format!(", expected {q:.1}"))
            ),
        )
    };
    Some(ErrorBar {
        value: safety * (e21 / f1).abs() / (r21.powf(order) - 1.0),
        method: how,
    })
}

/// The levels: size, unknowns, value, error against the yardstick, observed order, time.
pub fn table(study: &Study) -> Table {
    let mut t = Table::new(
        &format!(
            "{} {} convergence of {} (yardstick: ring BEM {:.12})",
            study.punch, study.method, study.quantity, study.yardstick
        ),
        vec![
            Column::text("label", "level"),
            Column::number("size", "size h", Format::Scientific(4)),
            Column::number("unknowns", "unknowns", Format::Fixed(0)),
            Column::number("value", "value", Format::Fixed(12)),
            Column::number("relative_error", "rel. error", Format::SignedScientific(3)),
            Column::number("observed_order", "order", Format::Fixed(2)),
            Column::number("wall_s", "time (one run)", Format::Fixed(3)).with_unit("s"),
        ],
    );
    for l in &study.levels {
        t.push(vec![
            l.label.clone().into(),
            l.size.into(),
            (l.unknowns as f64).into(),
            l.value.into(),
            l.error.into(),
            l.observed_order.into(),
            l.wall_s.into(),
        ]);
    }
    t
}

/// Table for the terminal: [`table`] and the [`summary`] (and why the study stopped early).
pub fn render(study: &Study) -> String {
    let stopped = study
        .stopped
        .as_ref()
        .map_or(String::new(), |why| format!("  STOPPED EARLY: {why}\n"));
    format!(
        "{}{stopped}  {}\n",
        table(study).to_terminal(),
        summary(study)
    )
}

/// One sentence: the Richardson extrapolate, its error against the yardstick, the GCI of the
/// finest level and whether the levels are in the asymptotic range (or why there is none).
pub(crate) fn summary(study: &Study) -> String {
    match (study.richardson, study.gci_fine) {
        (Some(e), Some(g)) => {
            let range = match study.asymptotic_ratio {
                Some(r) if (r - 1.0).abs() < 0.1 => {
                    format!("order ratio of the last two triples {r:.3}: in the asymptotic range")
                }
                Some(r) => format!(
                    "order ratio of the last two triples {r:.3}: NOT in the asymptotic range \
                     (hence the conservative bar)"
                ),
                None => "asymptotic range not checked (needs four levels with settled orders)"
                    .to_string(),
            };
            let floor = match study.error_floor {
                Some(f) if f >= g => {
                    " (the FEM's unresolved error component, which level differences do not see)"
                }
                _ => "",
            };
            format!(
                "Richardson extrapolate {e:.12} (error against the yardstick {:+.2e}); error \
                 bar of the finest level {g:.2e}{floor} ({}); {}; {range}",
                study.richardson_error.unwrap_or(f64::NAN),
                study.bar_method.as_deref().unwrap_or("GCI"),
                bound_sentence(study),
            )
        }
        (None, Some(g)) => format!(
            "error bar of the finest level {g:.2e} ({}); {}; no Richardson extrapolate (no \
             settled order)",
            study.bar_method.as_deref().unwrap_or("-"),
            bound_sentence(study),
        ),
        _ => "no Richardson extrapolate or error bar (fewer than three levels, differences at \
              rounding level, or no settled order)"
            .to_string(),
    }
}

/// Whether the bar bounds the finest level's actual error, in words.
fn bound_sentence(study: &Study) -> String {
    let actual = study.levels.last().map_or(f64::NAN, |l| l.error.abs());
    match study.bar_bounds_error {
        Some(true) => format!("it bounds the actual error {actual:.2e}"),
        Some(false) => format!("IT DOES NOT BOUND the actual error {actual:.2e} (a failed check)"),
        None => "not checked".into(),
    }
}

/// Failed checks of a study: an error bar that does not bound the actual error.
pub fn failures(study: &Study) -> usize {
    usize::from(study.bar_bounds_error == Some(false))
}

/// CSV of the levels ([`table`]'s columns, full precision).
pub fn csv(study: &Study) -> Result<String> {
    table(study).to_csv()
}

/// Write `<punch>-<method>.csv` and a log-log SVG chart of |error| against the size into `dir`;
/// returns the two paths.
pub(crate) fn write_files(study: &Study, dir: &std::path::Path) -> Result<[std::path::PathBuf; 2]> {
    let file_error = |path: &std::path::Path, e: std::io::Error| Error::File {
        action: "write".into(),
        path: path.display().to_string(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(|e| file_error(dir, e))?;
    let stem = format!("{}-{}", study.punch.name(), study.method);
    let csv_path = dir.join(format!("{stem}.csv"));
    let svg_path = dir.join(format!("{stem}.svg"));
    std::fs::write(&csv_path, csv(study)?).map_err(|e| file_error(&csv_path, e))?;
    std::fs::write(&svg_path, chart(study)).map_err(|e| file_error(&svg_path, e))?;
    Ok([csv_path, svg_path])
}

/// Log-log SVG chart of |relative error| against the size `h`.
pub fn chart(study: &Study) -> String {
    let series = vec![svg::Series {
        name: study.method.clone(),
        points: study
            .levels
            .iter()
            .map(|l| (l.size, l.error.abs()))
            .collect(),
        bars: Vec::new(),
    }];
    svg::log_log_chart(
        &format!(
            "{} {}: |relative error| against the ring BEM",
            study.punch.name(),
            study.quantity
        ),
        "size h",
        "|relative error|",
        &series,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_and_extrapolate_of_a_known_sequence() {
        // f(h) = 1 + 0.3 h^2 + 0.1 h^3 on h = 0.4, 0.2, 0.1 (ratio 2) and on a non-constant
        // ratio: the observed order tends to 2 and Richardson removes most of the error.
        let f = |h: f64| 1.0 + 0.3 * h * h + 0.1 * h.powi(3);
        let p = observed_order(f(0.1), f(0.2), f(0.4), 2.0, 2.0).unwrap();
        assert!((p - 2.0).abs() < 0.2, "{p}");
        let (e, gci, _) = richardson(f(0.1), f(0.2), f(0.4), 2.0, 2.0).unwrap();
        assert!((e - 1.0).abs() < 0.1 * (f(0.1) - 1.0));
        assert!(
            gci >= (f(0.1) - 1.0).abs() / f(0.1),
            "GCI {gci} must bound the error"
        );
        let p = observed_order(f(0.1), f(0.15), f(0.3), 1.5, 2.0).unwrap();
        assert!((p - 2.0).abs() < 0.3, "{p}");
        // Converged to rounding: no order.
        assert!(observed_order(1.0, 1.0 + 1e-16, 1.0 + 2e-16, 2.0, 2.0).is_none());
    }

    /// The bars of the default report's two studies (sphere, d = 1.5 h; values of a run, the
    /// actual errors against the ring BEM at 1e-11): the grid BEM's levels oscillate (the GCI
    /// from its observed order 5.1 was 2.5e-6 against an actual 2.1e-3), the FEM's order 7.2
    /// lies above the 6 of a P3 force (its GCI was 6.0e-6 against 1.7e-5). Both bars bound now.
    #[test]
    fn the_error_bars_bound_the_default_studies_actual_errors() {
        let grid = [1.2044755569212888, 1.2045553006730303, 1.2018670533540974];
        let bar = error_bar(grid, 2.0, 2.0, Some(1.0), None).unwrap();
        assert!(bar.method.starts_with("oscillatory"), "{}", bar.method);
        assert!(bar.value >= 2.0849e-3, "grid BEM bar {}", bar.value);
        let fem = [1.2070128748394542, 1.2070632570302815, 1.2076335952467923];
        let sizes = [
            0.00802908585711205,
            0.010996316850679233,
            0.015361001225823307,
        ];
        let bar = error_bar(
            fem,
            sizes[1] / sizes[0],
            sizes[2] / sizes[1],
            Some(6.0),
            None,
        )
        .unwrap();
        assert!(bar.method.contains("Fs = 3"), "{}", bar.method);
        assert!(bar.value >= 1.7302e-5, "FEM bar {}", bar.value);
        // In the asymptotic range the textbook GCI stands: f = 1 + h^2 on h = 0.4, 0.2, 0.1.
        let f = |h: f64| 1.0 + h * h;
        let bar = error_bar([f(0.1), f(0.2), f(0.4)], 2.0, 2.0, Some(2.0), None).unwrap();
        assert!(bar.method.contains("Fs = 1.25"), "{}", bar.method);
        assert!((bar.value - 1.25 * 0.03 / f(0.1) / 3.0).abs() < 1e-12);
    }
}
