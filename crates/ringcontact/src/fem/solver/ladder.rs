//! The mesh ladder as a driver of named phases: each rung decides its mesh
//! ([`Ladder::next_rung`]), prepares and assembles the model ([`Ladder::prepare`]), solves its
//! contact problem ([`Ladder::solve_contact`]), estimates its error against the rung below
//! ([`Ladder::estimate`]) and decides whether to stop there or which mesh comes next
//! ([`Ladder::decide`]).

use super::*;

/// Climb the mesh ladder for `problem` until a model's estimate meets the tolerance of
/// `options` (`start`: when the solve began, for its wall time).
pub(super) fn climb(problem: Problem, options: &FemOptions, start: Instant) -> Result<FemState> {
    let mut ladder = Ladder::new(problem, options, start);
    while let Some(rung) = ladder.next_rung() {
        let mut model = ladder.prepare(&rung)?;
        let mut solved = ladder.solve_contact(&mut model, &rung)?;
        let Some(previous) = ladder.previous.take().filter(|p| !p.locator) else {
            ladder.climb_without_estimate(&rung, solved.level);
            continue;
        };
        let estimate = ladder.estimate(&model, &mut solved, &previous);
        match ladder.decide(&model, solved, &estimate, &rung)? {
            Decision::Accept(state) => return Ok(*state),
            Decision::Refine(current) => ladder.previous = Some(current),
        }
    }
    Err(ladder.exhausted())
}

/// The scene a ladder solves.
#[derive(Clone, Debug)]
pub(super) struct Problem {
    pub(super) kind: PunchKind,
    pub(super) eps: f64,
    pub(super) load: FemLoad,
}

/// One model of the ladder: its mesh request, its adapted level (`None` for a committed mesh)
/// and whether it only locates the free edge for the next mesh ([`edge_locator`]).
struct Rung {
    request: MeshRequest,
    level: Option<i32>,
    locator: bool,
}

/// A rung's model solved: the contact solution, its depth-like and force-like values
/// (`solve_model`'s `x`, `y`), its outputs and what the next rung needs of it.
struct SolvedRung {
    solution: ContactSolution,
    x: f64,
    state: StateValues,
    level: LevelResult,
}

/// A rung's error estimate against the rung below.
#[derive(Clone, Copy, Debug)]
struct Estimate {
    /// The force-like outputs' discretisation error (Richardson over the grading step, or the
    /// change).
    force: f64,
    /// The components finer models do not reduce: truncation, unresolved edges.
    floor: f64,
    /// The edge's shift caused by the field's error (`κ` times a share of the force error).
    edge_from_field: f64,
    /// The edge's conditioning `κ = |db/dd| d`.
    conditioning: f64,
    /// The whole estimate: `max(force, eps error) + floor`.
    total: f64,
}

/// What a rung's estimate decides.
enum Decision {
    /// The estimate meets the tolerance: the answer.
    Accept(Box<FemState>),
    /// Climb on; the rung's result is the next one's `previous`.
    Refine(LevelResult),
}

/// The margins of full contact that the model's own error could open: `(opening margin, depth
/// error)`, see [`crate::fem::contact::Conditioning::opening_margin`].
#[derive(Clone, Copy, Debug)]
struct UnresolvedClosure {
    opening_margin: f64,
    depth_error: f64,
}

/// How the grading steps of the adapted family have converged so far.
#[derive(Clone, Copy, Debug, Default)]
struct GradingHistory {
    /// The grading part of the force estimate on the current adapted level (Richardson from the
    /// level below), kept when the level is repeated for the free edge.
    level_force_estimate: Option<f64>,
    /// The force change of the last grading step, for the observed ratio of the next.
    last_change: Option<f64>,
    /// Whether the last grading step converged more slowly than the known order (the current
    /// level's force estimate is then the observed ratio's).
    pre_asymptotic: bool,
}

/// The mesh ladder's state between rungs.
struct Ladder<'o> {
    problem: Problem,
    options: &'o FemOptions,
    start: Instant,
    /// A long ladder says which step it is at every 10 s; a short one writes nothing.
    progress: Heartbeat,
    /// The scene, for the error when gmsh is needed and missing.
    why: String,
    start_line: f64,
    target: SizeTarget,
    /// A concave punch's first model only locates its free edge.
    locating: bool,
    committed: std::vec::IntoIter<MeshRequest>,
    next_level: i32,
    previous: Option<LevelResult>,
    grading: GradingHistory,
    /// Refinements at the free edge on the current level.
    repeats: usize,
    last_estimate: f64,
    iterations: usize,
    last_mesh: String,
    closure_unresolved: Option<UnresolvedClosure>,
}

impl<'o> Ladder<'o> {
    /// The committed levels for this contact line (or the edge locator), then the adapted family
    /// from the first level that can meet the tolerance.
    fn new(problem: Problem, options: &'o FemOptions, start: Instant) -> Self {
        let Problem { kind, eps, .. } = problem.clone();
        let ladder = committed_ladder(&options.data, kind.clone(), eps, options.tolerance);
        let next_level = if ladder.is_empty() {
            first_adapted_level(options.degree, options.tolerance)
        } else {
            provider::COMMITTED_MAX_LEVEL as i32 + 1
        };
        let locating = ladder.is_empty() && kind.is_concave();
        let committed = if locating {
            edge_locator(&options.data, kind.clone(), eps)
        } else {
            ladder
        };
        Self {
            problem,
            options,
            start,
            progress: Heartbeat::start("fem", options.progress),
            why: format!(
                "the FEM for the {kind} at tolerance {:e}",
                options.tolerance
            ),
            start_line: contact_start(&kind, eps),
            target: SizeTarget {
                tolerance: options.tolerance,
                degree: options.degree as usize,
            },
            locating,
            committed: committed.into_iter(),
            next_level,
            previous: None,
            grading: GradingHistory::default(),
            repeats: 0,
            last_estimate: f64::INFINITY,
            iterations: 0,
            last_mesh: String::new(),
            closure_unresolved: None,
        }
    }

    /// Decide the next mesh: the next committed one, else the next adapted level, refined (for
    /// a concave punch) around the free edge the previous model located; `None` past the
    /// finest level.
    fn next_rung(&mut self) -> Option<Rung> {
        if let Some(request) = self.committed.next() {
            return Some(Rung {
                request,
                level: None,
                locator: self.locating,
            });
        }
        if self.next_level > provider::ADAPTED_MAX_LEVEL {
            return None;
        }
        // Concave punches: refine around the free edge located on the previous solve.
        let edge = self
            .previous
            .as_ref()
            .filter(|_| self.problem.kind.is_concave());
        // A hole inside the first node off the axis: refine around the middle of that node's
        // radius, to a quarter of it (no finer than gmsh makes at the axis, else around the
        // axis point itself).
        let hidden_hole = edge
            .filter(|p| p.axis == AxisContact::HoleInsideFirstNode)
            .map(|p| 0.5 * p.spacing)
            .filter(|&b| 0.25 * b >= provider::AXIS_MIN_ELEMENT_SIZE);
        let request = MeshRequest::Adapted {
            contact_start: self.start_line,
            level: self.next_level,
            // Full contact located: refine around the axis (r = 0), where a hole opens.
            free_edge: hidden_hole.or(edge
                .map(|p| p.values.eps)
                .filter(|&b| b > 0.0 || edge.is_some_and(|p| p.axis != AxisContact::Open))),
            edge_uncertainty: hidden_hole.or(edge.map(|p| p.eps_error)).unwrap_or(0.0),
            target: Some(self.target),
        };
        Some(Rung {
            request,
            level: Some(self.next_level),
            locator: false,
        })
    }

    /// Provide the rung's mesh (committed, cache or gmsh), read it and assemble its model.
    fn prepare(&mut self, rung: &Rung) -> Result<PreparedModel> {
        self.progress.set(match rung.level {
            Some(k) => format!("level {k}: making its mesh (gmsh, or the cache)"),
            None => "a committed mesh".to_string(),
        });
        let provided = provider::provide(&self.options.data, &rung.request, &self.why)?;
        // The edge locator only places the next mesh's refinement, and its domain need not meet
        // the tolerance: quadratic at the loose tolerances, the solve's degree below 1e-4, whose
        // closer edge gives the next mesh a narrower window.
        let options = self.options;
        let locator_options = FemOptions {
            degree: if options.tolerance >= CUBIC_BELOW_TOLERANCE {
                Degree::Quadratic
            } else {
                options.degree
            },
            ..options.clone()
        };
        let (model_options, domain_tolerance) = if rung.locator {
            (&locator_options, DEFAULT_TOLERANCE.max(options.tolerance))
        } else {
            (options, options.tolerance)
        };
        self.progress.set(format!(
            "reading and assembling {}",
            provided.path.display()
        ));
        let model = prepare_checked(&provided, model_options, self.start_line, domain_tolerance)?;
        self.last_mesh = model.path.clone();
        Ok(model)
    }

    /// Solve the model's contact problem, warm-started from the previous rung, and read off what
    /// the next rung needs: the outputs, the edge's node spacing and error, full contact.
    fn solve_contact(&mut self, model: &mut PreparedModel, rung: &Rung) -> Result<SolvedRung> {
        let Problem { kind, eps, load } = self.problem.clone();
        self.progress.set(format!(
            "solving {} unknowns on {}",
            model.stiffness.nrows(),
            self.last_mesh
        ));
        // The previous model's contact radius (and depth) start the iterations.
        let guess = self.previous.as_ref().map(|p| WarmStart {
            inner_radius: p.values.eps,
            band: p.eps_error,
            outer_radius: f64::INFINITY,
        });
        let depth_guess = self.previous.as_ref().map(|p| p.values.primary);
        let (s, x, y) = solve_model(
            model,
            kind.clone(),
            eps,
            load,
            guess,
            depth_guess,
            self.options.tolerance,
        )?;
        self.iterations += s.iterations;
        if model.spec.trace {
            trace_level(model, &s);
        }
        let state = state_of(load, eps, &s, x, y);
        let (eps_out, gamma, gamma1, gamma2) = state;
        let mut level = LevelResult {
            values: LevelValues {
                primary: gamma.or(gamma1).unwrap_or(f64::NAN),
                gamma2: gamma2.unwrap_or(f64::NAN),
                eps: eps_out,
            },
            spacing: s.inner_node_spacing,
            eps_error: INNER_RADIUS_BOUND * s.inner_node_spacing,
            level: rung.level,
            locator: rung.locator,
            axis: AxisContact::Open,
            edge_bound: INNER_RADIUS_BOUND,
        };
        let concave = kind.is_concave();
        let free_nodes = s.reactions.len() - s.active_radii.len();
        if let Some(first_off_axis) = full_contact_spacing(&s).filter(|_| concave) {
            // The next mesh refines around r = 0 to find the hole, if any.
            level.spacing = first_off_axis;
            level.eps_error = first_off_axis;
            level.axis = AxisContact::Full;
            level.edge_bound = 1.0;
        } else if concave && free_nodes < MIN_FREE_NODES {
            // Too few free nodes in the hole for the edge's extrapolation: bound it by two
            // spacings (the edge lies between the last free node and the first in contact).
            level.edge_bound = 2.0;
            level.eps_error = 2.0 * s.inner_node_spacing;
        }
        Ok(SolvedRung {
            solution: s,
            x,
            state,
            level,
        })
    }

    /// A rung with nothing below to estimate against (the first, or the one after the edge
    /// locator): climb to the next level.
    fn climb_without_estimate(&mut self, rung: &Rung, result: LevelResult) {
        if let Some(level) = rung.level {
            self.next_level = level + 1;
        }
        self.previous = Some(result);
    }

    /// The rung's error estimate against `previous`: the force's (Richardson over a grading
    /// step, with the observed order where it is lower), the components finer models do not
    /// reduce, the located edge's (its change, and the shift the field's error causes), and
    /// whether full contact is closed, hides a hole inside its first node, or could open within
    /// the model's error. Updates the rung's edge error and axis contact accordingly.
    fn estimate(
        &mut self,
        model: &PreparedModel,
        solved: &mut SolvedRung,
        previous: &LevelResult,
    ) -> Estimate {
        let Problem { kind, load, .. } = self.problem.clone();
        let degree = self.options.degree;
        let s = &solved.solution;
        let current = &mut solved.level;
        let change = current.force_change(previous);
        let force = match (previous.level, current.level) {
            // A grading step of the adapted family: Richardson with the known order, or the
            // observed one where it is lower.
            (Some(p), Some(c)) if c == p + 1 => {
                let last = self.grading.last_change;
                let estimate = grading_step_estimate(degree, change, last);
                self.grading = GradingHistory {
                    level_force_estimate: Some(estimate),
                    last_change: Some(change),
                    pre_asymptotic: below_known_order(degree, change, last),
                };
                estimate
            }
            // The same level refined at the free edge: its grading error, plus the change.
            (Some(p), Some(c)) if c == p => {
                self.grading.level_force_estimate.unwrap_or(change) + change
            }
            _ => change,
        };
        let eps_out = current.values.eps;
        // The edges' component falls with finer models, but the rim sizes the targets ask for
        // keep it below 0.05 of the tolerance: it never stops the ladder below alone.
        let floor = model.truncation_bias() + UNRESOLVED_COMPONENT + model.edge_component(eps_out);
        current.eps_error = current.eps_estimate(previous);
        // The edge moves κ = |db/dd| d times a depth error; a field error acts as a share of
        // one, or as the whole of one under a prescribed force and outside the asymptotic range,
        // where it adds to the edge's own error (docs/decisions.md, "Where the constants come
        // from").
        let conditioning = s.conditioning.edge_depth_sensitivity.abs() * solved.x.abs();
        let whole_shift = self.grading.pre_asymptotic || matches!(load, FemLoad::ConcaveForce(_));
        let field_share = if whole_shift {
            EDGE_FIELD_FRACTION_WHOLE
        } else {
            EDGE_FIELD_FRACTION
        };
        // Also asked of the edge-only refinement: the field component is not reduced by
        // refining at the edge.
        let edge_from_field = field_share * conditioning * (force + floor);
        current.eps_error = if whole_shift {
            current.eps_error + edge_from_field
        } else {
            current.eps_error.max(edge_from_field)
        };
        let depth_error = force + floor;
        current.settle_axis(kind, s.conditioning.closure_margin, depth_error);
        self.closure_unresolved = (current.axis != AxisContact::Open
            && s.conditioning.opening_margin < depth_error)
            .then_some(UnresolvedClosure {
                opening_margin: s.conditioning.opening_margin,
                depth_error,
            });
        Estimate {
            force,
            floor,
            edge_from_field,
            conditioning,
            total: force.max(current.eps_error) + floor,
        }
    }

    /// Accept the rung if its estimate meets the tolerance (and no full contact could open);
    /// decline where finer models cannot help (an axis spacing gmsh does not reach, an
    /// ill-conditioned edge, a floor above half the tolerance, the largest model); else choose
    /// the next rung: the same level refined at the free edge when only the edge misses (at most
    /// [`MAX_EDGE_REPEATS`] times), the next level otherwise.
    fn decide(
        &mut self,
        model: &PreparedModel,
        solved: SolvedRung,
        estimate: &Estimate,
        rung: &Rung,
    ) -> Result<Decision> {
        let tolerance = self.options.tolerance;
        let Estimate {
            force,
            floor,
            edge_from_field,
            total,
            ..
        } = *estimate;
        if total <= tolerance && self.closure_unresolved.is_none() {
            rim_resolves_the_ring(model, self.problem.kind.clone(), &solved.solution)?;
            return Ok(Decision::Accept(Box::new(finish(
                model,
                solved.solution,
                solved.state,
                Some(total),
                self.iterations,
                self.options.degree,
                self.start,
            ))));
        }
        self.last_estimate = total;
        let current = solved.level;
        self.check_refinable(model, &current, estimate)?;
        if let Some(level) = rung.level {
            // Only the free edge misses: refine there on the same level (at most twice).
            // (Not when the edge's field component misses: only finer levels reduce it.)
            let edge_only = self.problem.kind.is_concave()
                && self.closure_unresolved.is_none()
                && self.grading.level_force_estimate.is_some()
                && force.max(edge_from_field) + floor <= tolerance
                && self.repeats < MAX_EDGE_REPEATS;
            if edge_only {
                self.repeats += 1;
            } else {
                self.next_level = level + 1;
                self.repeats = 0;
            }
        }
        Ok(Decision::Refine(current))
    }

    /// Decline a rung that missed the tolerance where finer models cannot help: full contact at
    /// an axis spacing gmsh does not reach, an edge whose field component stays above half the
    /// tolerance, full contact the error could open on the largest model, a floor above half
    /// the tolerance, or the largest model itself.
    fn check_refinable(
        &self,
        model: &PreparedModel,
        current: &LevelResult,
        estimate: &Estimate,
    ) -> Result<()> {
        let tolerance = self.options.tolerance;
        let Estimate {
            floor,
            conditioning,
            total,
            ..
        } = *estimate;
        let last_mesh = &self.last_mesh;
        // Full contact whose first node off the axis is already as close to it as gmsh's
        // elements there go: finer models cannot bound a hole inside it any better.
        let axis_spacing = provider::AXIS_MIN_ELEMENT_SIZE / f64::from(self.options.degree as u8);
        if current.axis != AxisContact::Open && current.spacing <= 2.0 * axis_spacing {
            return Err(Error::OutOfRange {
                method: METHOD.into(),
                reason: format!(
                    "{last_mesh} finds full contact: a hole, if any, lies inside its first node \
                     off the axis (r = {:.1e} a), and bounding it to the tolerance {tolerance:.1e} \
                     needs elements at the axis below {:.0e} a, which gmsh does not make in \
                     reasonable time; loosen --tol or use the ring BEM",
                    current.spacing,
                    provider::AXIS_MIN_ELEMENT_SIZE
                ),
            });
        }
        let unknowns = model.stiffness.nrows();
        self.progress.set(format!(
            "{unknowns} unknowns on {last_mesh} gave an estimate of {total:.1e}, above the \
             tolerance {tolerance:.1e}: refining"
        ));
        // The floor's share of the edge's field component is not reduced either (at the
        // asymptotic share, which finer models reach).
        let field_floor = EDGE_FIELD_FRACTION * conditioning * floor;
        if field_floor > 0.5 * tolerance {
            return Err(Error::OutOfRange {
                method: METHOD.into(),
                reason: format!(
                    "the free edge b/a = {} of {last_mesh} is ill-conditioned (a nearly closed \
                     hole): it moves κ = |db/dd| d = {conditioning:.1} times a relative change of \
                     the depth, and the part of its error that finer models do not reduce \
                     ({EDGE_FIELD_FRACTION} κ times the force floor {floor:.1e}: \
                     {field_floor:.1e}) is above half the tolerance {tolerance:.1e}; loosen --tol \
                     or use the ring BEM",
                    crate::error::show(current.values.eps),
                ),
            });
        }
        if let Some(closure) = self
            .closure_unresolved
            .filter(|_| unknowns > MAX_LADDER_UNKNOWNS)
        {
            return Err(closure_unresolved_error(last_mesh, closure));
        }
        if floor > 0.5 * tolerance || unknowns > MAX_LADDER_UNKNOWNS {
            // Finer models do not reduce the floor, and past this size the next model (about
            // 2.7x larger) would take minutes and most of the memory: stop here.
            let why = if unknowns > MAX_LADDER_UNKNOWNS {
                "the next model would have about 2 M unknowns or more".to_string()
            } else {
                format!(
                    "more than half of the tolerance is taken by the error components finer \
                     models do not reduce ({floor:.1e}; larger on narrow rings)"
                )
            };
            return Err(fem_error(format!(
                "the model {last_mesh} ({unknowns} unknowns) reaches an estimated error of \
                 {total:.1e}, above the tolerance {tolerance:.1e}, and {why}; loosen --tol or use \
                 the ring BEM"
            )));
        }
        Ok(())
    }

    /// The error when the finest level did not meet the tolerance.
    fn exhausted(&self) -> Error {
        if let Some(closure) = self.closure_unresolved {
            return closure_unresolved_error(&self.last_mesh, closure);
        }
        fem_error(format!(
            "the finest model ({}) reaches an estimated error of {:.1e}, above the tolerance \
             {:.1e}; loosen --tol or use the ring BEM",
            self.last_mesh, self.last_estimate, self.options.tolerance
        ))
    }
}

/// The ladder ended on full contact that its last model's error could open.
fn closure_unresolved_error(last_mesh: &str, closure: UnresolvedClosure) -> Error {
    let UnresolvedClosure {
        opening_margin: margin,
        depth_error,
    } = closure;
    Error::OutOfRange {
        method: METHOD.into(),
        reason: format!(
            "{last_mesh} finds full contact, but a depth {margin:.1e} smaller (relative; within \
             its estimated error {depth_error:.1e}) would open a hole: a nearly closed hole is \
             below what the finest model resolves; use cubic elements or the ring BEM"
        ),
    }
}
