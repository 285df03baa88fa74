//! The FEM's ladder for a contact with two free edges (a free band): the annulus `b <= r <= c`
//! has no rim, both edges are found by the solution.
//!
//! **The model.** The committed and adapted meshes have a contact line `[0, 1]` in their own
//! length unit. A band's contact can reach beyond `r = a`, so its model takes the mesh's unit
//! as `frame a` ([`ContactModel::with_free_edges`]): the line is `[0, frame a]`, with `frame`
//! 1.5 times the rigid profile's outer intersection with the surface (which the contact never
//! passes) and doubled when the located contact reaches the line's end.
//!
//! **The ladder**, through the same phases as the one-edge ladder (mesh, model, contact,
//! estimate, decision): a first model on the adapted level that can meet the tolerance locates
//! both edges ([`MeshRequest::FreeEdges`], refined around the rigid intersection); then the
//! same level refined around the located edges, and one level finer at a time, each refined
//! around the edges of the model below it, within their estimated errors. Each rung's estimate
//! against the one below:
//!
//! - the force-like outputs (`γ2` under depth control, `γ1` and `γ2` under force control): the
//!   grading step's Richardson estimate ([`grading_step_estimate`]), the same as for one edge;
//! - each edge: its change between the rungs over the spacing's ratio less one (first order in
//!   the node spacing there), never below [`INNER_RADIUS_BOUND`] of the spacing, and never below
//!   the force estimate (the field's error moves an edge as a depth error would, by `κ` times
//!   it, `κ = |db/dd| d`, 0.005-0.19 for the inner edge at `d/h` = 1e-3 ... 10);
//! - the components finer models do not reduce: the domain's truncation and
//!   [`UNRESOLVED_COMPONENT`].
//!
//! The answer is the first rung whose largest estimate meets the tolerance.

use std::time::Instant;

use super::{
    fem_error, finish, first_adapted_level, grading_step_estimate, prepare_checked, solve_model,
    FemLoad, FemOptions, FemState, PreparedModel, INNER_RADIUS_BOUND, MAX_LADDER_UNKNOWNS, METHOD,
    UNRESOLVED_COMPONENT,
};
use crate::error::{Error, Result};
use crate::fem::contact::ContactSolution;
use crate::heartbeat::Heartbeat;
use crate::mesh::provider::{self, MeshRequest, SizeTarget};
use crate::mesh::triangulation::Degree;
use crate::punch::PunchKind;

/// Times the contact line is doubled when the located contact reaches its end.
const MAX_LINE_WIDENINGS: usize = 3;

/// Where the band first touches, `r0/a`
/// ([`Profile::first_touch`](crate::punch::Profile::first_touch)), `1` if the profile does not
/// say.
fn first_touch(kind: &PunchKind) -> f64 {
    kind.first_touch().map_or(1.0, |(r0, _)| r0)
}

/// The depth `d/h` the first model starts from: the scene's under depth control; under force
/// control `8 γ2 / (π² r0)`, the depth whose rigid intersection is twice the half-width
/// `w = √(4 γ2/(π² κ r0))` of the narrow band's plane-strain Hertz contact at its first touch
/// `r0` (`F/(2π r0) = π E* w²/(4ρ)`, `ρ = a²/(κ h)`), which the contact is narrower than.
fn depth_guess(kind: &PunchKind, load: FemLoad) -> f64 {
    match load {
        FemLoad::ConcaveForce(gamma2) => {
            8.0 * gamma2.max(0.0) / (std::f64::consts::PI.powi(2) * first_touch(kind))
        }
        FemLoad::ConcaveDepth(depth) => depth.max(0.0),
        FemLoad::Flat => 0.0,
    }
}

/// The mesh's unit `frame a` for a load: 1.5 times the radius where the rigid profile at the
/// [`depth_guess`] meets the surface outside the band (the contact lies inside), at least 2 (the
/// line is widened if the contact reaches its end).
fn initial_frame(kind: &PunchKind, load: FemLoad) -> f64 {
    let (_, outer) = kind.rigid_half_widths(depth_guess(kind, load));
    (1.5 * (first_touch(kind) + outer)).max(2.0)
}

/// Edges `(radius, uncertainty)` of the first model, in units of `a`: the rigid profile's
/// intersections with the surface at the [`depth_guess`]
/// ([`Profile::rigid_half_widths`](crate::punch::Profile::rigid_half_widths)), each known to
/// within half its distance from the first touch.
fn rigid_edges(kind: &PunchKind, load: FemLoad) -> [(f64, f64); 2] {
    let r0 = first_touch(kind);
    let (inner, outer) = kind.rigid_half_widths(depth_guess(kind, load));
    [
        ((r0 - inner).max(0.0), 0.5 * inner),
        (r0 + outer, 0.5 * outer),
    ]
}

/// Error of a located edge that changed by `change` from a model whose node spacing there was
/// `previous_spacing` to one with `spacing`: first order in the spacing, `|Δ| / (q - 1)` for a
/// ratio `q > 1.5`, else `|Δ|`, never below [`INNER_RADIUS_BOUND`] of the spacing.
pub(super) fn edge_error(change: f64, previous_spacing: f64, spacing: f64) -> f64 {
    let ratio = previous_spacing / spacing;
    let bound = INNER_RADIUS_BOUND * spacing;
    if spacing > 0.0 && ratio > 1.5 {
        (change.abs() / (ratio - 1.0)).max(bound)
    } else {
        change.abs().max(bound)
    }
}

/// What one model found, in units of `a`.
#[derive(Clone, Copy, Debug)]
struct Rung {
    level: i32,
    gamma1: f64,
    gamma2: f64,
    edges: [f64; 2],
    spacings: [f64; 2],
    /// Estimated errors of the edges (for the next mesh's refinement).
    edge_errors: [f64; 2],
    /// Only located the edges for the next mesh (no estimate against it).
    locator: bool,
}

impl Rung {
    /// This rung's force estimate against the rung `below`, and its edges' errors: a level's
    /// step is the grading's Richardson estimate ([`grading_step_estimate`]; `last_change` and
    /// `level_force` carry it between levels), a refinement of the same level at its edges is
    /// that level's grading error plus the change; an edge's error is its change over the
    /// spacings' ratio ([`edge_error`]), never below the force estimate.
    fn estimate_against(
        &mut self,
        below: &Rung,
        degree: Degree,
        last_change: &mut Option<f64>,
        level_force: &mut Option<f64>,
    ) -> f64 {
        let relative = |x: f64, y: f64| (x - y).abs() / x.abs();
        let change = relative(self.gamma1, below.gamma1).max(relative(self.gamma2, below.gamma2));
        let force = if self.level == below.level + 1 {
            let estimate = grading_step_estimate(degree, change, *last_change);
            *last_change = Some(change);
            *level_force = Some(estimate);
            estimate
        } else {
            // The same level refined at the edges: its grading error, plus the change.
            level_force.unwrap_or(change) + change
        };
        for k in 0..2 {
            self.edge_errors[k] = edge_error(
                self.edges[k] - below.edges[k],
                below.spacings[k],
                self.spacings[k],
            )
            .max(force);
        }
        force
    }
}

/// One level of the climb: its mesh (gmsh or the cache) refined around `request`'s edges, the
/// model prepared on the contact line `[0, frame a]` and solved, warm from the rung below.
fn solve_level(
    kind: &PunchKind,
    load: FemLoad,
    options: &FemOptions,
    frame: f64,
    request: &MeshRequest,
    previous: Option<Rung>,
    progress: &Heartbeat,
) -> Result<(PreparedModel, ContactSolution, f64, f64)> {
    let tolerance = options.tolerance;
    let why = format!("the FEM for the {kind} at tolerance {tolerance:e}");
    let level = request_level(request);
    progress.set(format!(
        "level {level}: making its mesh (gmsh, or the cache)"
    ));
    let provided = provider::provide(&options.data, request, &why)?;
    let mut model = prepare_checked(&provided, options, 0.0, tolerance)?;
    model.spec.frame = frame;
    progress.set(format!(
        "solving {} unknowns on {}",
        model.stiffness.nrows(),
        model.path
    ));
    let depth_guess = Some(previous.map_or(depth_guess(kind, load), |p| p.gamma1));
    // The model below's band starts the active-set iteration.
    let warm = previous.map(|p| super::WarmStart {
        inner_radius: p.edges[0],
        band: p.edge_errors[0],
        outer_radius: p.edges[1],
    });
    let (s, gamma1, gamma2) = solve_model(
        &mut model,
        kind.clone(),
        0.0,
        load,
        warm,
        depth_guess,
        tolerance,
    )?;
    if model.spec.trace {
        super::trace_level(&model, &s);
        eprintln!(
            "fem: level {level}: c/a = {:.10} (node spacing there {:.2e}), frame {frame}",
            s.outer_radius, s.outer_node_spacing
        );
    }
    Ok((model, s, gamma1, gamma2))
}

/// The adapted level a free-edges mesh request asks for (the only kind this ladder makes).
fn request_level(request: &MeshRequest) -> i32 {
    match request {
        MeshRequest::FreeEdges { level, .. } => *level,
        _ => 0,
    }
}

/// How one climb ended.
enum Climb {
    Solved(Box<FemState>),
    /// The located contact reached the end of the mesh's contact line: widen it.
    LineTooShort,
}

/// Solve a punch whose contact has two free edges (a free band) with the FEM (module
/// documentation).
pub(super) fn solve(kind: PunchKind, load: FemLoad, options: &FemOptions) -> Result<FemState> {
    let start = Instant::now();
    if options.mesh.is_some() {
        return Err(Error::Unsupported {
            method: METHOD.into(),
            reason: format!(
                "the {kind}'s meshes are made for the scene (their contact line is scaled to the \
                 load): --mesh applies to the punches with a rim"
            ),
        });
    }
    if matches!(load, FemLoad::Flat) {
        return Err(fem_error(format!("the {kind} is not a flat-faced punch")));
    }
    options.data.check()?;
    let progress = Heartbeat::start("fem", options.progress);
    let mut frame = initial_frame(&kind, load);
    for _ in 0..=MAX_LINE_WIDENINGS {
        match climb(kind.clone(), load, options, frame, start, &progress)? {
            Climb::Solved(state) => return Ok(*state),
            Climb::LineTooShort => frame *= 2.0,
        }
    }
    Err(fem_error(format!(
        "the {kind}'s contact reached the end of a contact line {} a long, widened \
         {MAX_LINE_WIDENINGS} times",
        crate::error::show(frame / 2.0)
    )))
}

/// One model of the ladder on its own, for a mesh-convergence study: level `level` of the
/// free-edges family on the contact line `[0, frame a]` ([`initial_frame`] of the load), its
/// sizes made for `options.tolerance`, refined around `edges` (`(radius, uncertainty)` in units
/// of `a`; `None`: the rigid profile's intersection, [`rigid_edges`]). No estimate (the study
/// makes its own); the inner edge in `eps`, the outer in `outer_edge`.
pub(super) fn solve_on_level(
    kind: PunchKind,
    load: FemLoad,
    level: i32,
    edges: Option<[(f64, f64); 2]>,
    options: &FemOptions,
) -> Result<FemState> {
    let start = Instant::now();
    if matches!(load, FemLoad::Flat) {
        return Err(fem_error(format!("the {kind} is not a flat-faced punch")));
    }
    options.data.check()?;
    let frame = initial_frame(&kind, load);
    let tolerance = options.tolerance;
    let edges = edges.unwrap_or_else(|| rigid_edges(&kind, load));
    let request = MeshRequest::FreeEdges {
        level,
        edges: edges.map(|(r, uncertainty)| (r / frame, uncertainty / frame)),
        target: SizeTarget {
            tolerance: tolerance / frame,
            degree: options.degree as usize,
        },
        ring_scale: provider::ring_width_scale(edges[1].0 - edges[0].0),
    };
    let why = format!("the FEM convergence study of the {kind}");
    let provided = provider::provide(&options.data, &request, &why)?;
    let mut model = prepare_checked(&provided, options, 0.0, tolerance)?;
    model.spec.frame = frame;
    let (s, gamma1, gamma2) = solve_model(
        &mut model,
        kind.clone(),
        0.0,
        load,
        None,
        Some(depth_guess(&kind, load)),
        tolerance,
    )?;
    if s.outer_node_spacing == 0.0 {
        return Err(fem_error(format!(
            "the {kind}'s contact reached the end of the contact line {} a long on {}",
            crate::error::show(frame),
            model.path
        )));
    }
    check_open(kind, &s, &model.path)?;
    let iterations = s.iterations;
    let outer = s.outer_radius;
    let state = (s.inner_radius, None, Some(gamma1), Some(gamma2));
    let mut state = finish(&model, s, state, None, iterations, options.degree, start);
    state.outer_edge = Some(outer);
    Ok(state)
}

/// Climb the adapted levels on a contact line `[0, frame a]` until a rung's estimate meets the
/// tolerance.
fn climb(
    kind: PunchKind,
    load: FemLoad,
    options: &FemOptions,
    frame: f64,
    start: Instant,
    progress: &Heartbeat,
) -> Result<Climb> {
    let tolerance = options.tolerance;
    let degree = options.degree;
    let target = SizeTarget {
        tolerance: tolerance / frame,
        degree: degree as usize,
    };
    let mut level = first_adapted_level(degree, tolerance);
    let mut edges = rigid_edges(&kind, load);
    let mut previous: Option<Rung> = None;
    let mut last_change: Option<f64> = None;
    // The grading estimate of the current level, kept when the level is refined at the edges.
    let mut level_force: Option<f64> = None;
    let mut repeats = 0;
    let mut iterations = 0;
    let mut last_estimate = f64::INFINITY;
    let mut last_mesh = String::new();
    while level <= provider::ADAPTED_MAX_LEVEL {
        let locator = previous.is_none();
        let request = MeshRequest::FreeEdges {
            level,
            edges: edges.map(|(r, uncertainty)| (r / frame, uncertainty / frame)),
            target,
            ring_scale: provider::ring_width_scale(edges[1].0 - edges[0].0),
        };
        let (model, s, gamma1, gamma2) =
            solve_level(&kind, load, options, frame, &request, previous, progress)?;
        last_mesh = model.path.clone();
        iterations += s.iterations;
        if s.outer_node_spacing == 0.0 {
            return Ok(Climb::LineTooShort);
        }
        check_open(kind.clone(), &s, &last_mesh)?;
        let spacings = [s.inner_node_spacing, s.outer_node_spacing];
        let located = [s.inner_radius, s.outer_radius];
        let mut rung = Rung {
            level,
            gamma1,
            gamma2,
            edges: located,
            spacings,
            edge_errors: spacings.map(|h| 2.0 * h),
            locator,
        };
        if let Some(below) = previous.filter(|p| !p.locator) {
            let force = rung.estimate_against(&below, degree, &mut last_change, &mut level_force);
            let floor = model.truncation_bias() + UNRESOLVED_COMPONENT;
            let total = force.max(rung.edge_errors[0]).max(rung.edge_errors[1]) + floor;
            if total <= tolerance {
                let state = (located[0], None, Some(gamma1), Some(gamma2));
                let mut state = finish(&model, s, state, Some(total), iterations, degree, start);
                state.outer_edge = Some(located[1]);
                return Ok(Climb::Solved(Box::new(state)));
            }
            last_estimate = total;
            let unknowns = model.stiffness.nrows();
            if unknowns > MAX_LADDER_UNKNOWNS || floor > 0.5 * tolerance {
                return Err(fem_error(format!(
                    "the model {last_mesh} ({unknowns} unknowns) reaches an estimated error of \
                     {total:.1e}, above the tolerance {tolerance:.1e}, and finer models would be \
                     too large or cannot reduce it; loosen --tol or use the ring BEM"
                )));
            }
            progress.set(format!(
                "{unknowns} unknowns on {last_mesh} gave an estimate of {total:.1e}, above the \
                 tolerance {tolerance:.1e}: refining"
            ));
            // Only the edges miss: refine them on the same level (at most twice).
            let edges_only = level_force.is_some()
                && force + floor <= tolerance
                && repeats < super::MAX_EDGE_REPEATS;
            if edges_only {
                repeats += 1;
            } else {
                level += 1;
                repeats = 0;
            }
        } else if !locator {
            // The first model refined at the edges: nothing below to estimate against.
            level += 1;
        }
        // The locator's level is solved again, refined at the edges it found; then the ladder
        // refines at the edges or climbs a level (above).
        edges = [0, 1].map(|k| (rung.edges[k], rung.edge_errors[k]));
        previous = Some(rung);
    }
    Err(fem_error(format!(
        "the finest model ({last_mesh}) reaches an estimated error of {last_estimate:.1e}, above \
         the tolerance {:.1e}; loosen --tol or use the ring BEM",
        options.tolerance
    )))
}

/// The contact must be a ring: one that reaches the axis (a disk, a band pressed beyond its
/// closure) has one free edge, which this ladder does not treat.
fn check_open(kind: PunchKind, s: &ContactSolution, mesh: &str) -> Result<()> {
    if s.inner_radius > 0.0 {
        return Ok(());
    }
    Err(Error::OutOfRange {
        method: METHOD.into(),
        reason: format!(
            "the {kind}'s contact on {mesh} reaches the axis (a disk): the FEM locates the two \
             free edges of a ring only; use the ring BEM"
        ),
    })
}
