//! Displacement control along a loading-unloading path: press to a preload, then pull until the
//! branch the preload is on ends (a jump) or the punch is free.
//!
//! Each step starts from the previous equilibrium. A step whose Newton iteration needed a shifted
//! Hessian (it left the basin of the branch) or whose force changed by more than
//! [`JUMP_FORCE`]` F0` is halved; when the step is below `min_step` and still does so, the branch
//! has ended: the jump and the state it lands on are recorded (what fixed grips see). With
//! [`PathOptions::hop_force`] set, a shifted step whose force changes by less than that is the
//! crack front hopping a node and continues the branch (the annular branch's inner edge); with
//! [`PathOptions::hop_band`] only hops that start and land with the front in the refined band at
//! the rim do (the closed branch). The pull-off, [`Curve::pulloff`], is the most tensile state of
//! that branch, in the band where there is one (refined by a golden-section search where it is a
//! smooth maximum).

use serde::Serialize;

use crate::cohesive::equilibrium::{CohesiveSurface, Equilibrium};
use crate::error::{Error, Result};

/// Largest force change per accepted step, in units of Kendall's `F0`.
const JUMP_FORCE: f64 = 0.05;

/// Separations up to this many ranges count as the cohesive zone (tension above `e^-3 σ0`).
const ZONE_RANGES: f64 = 3.0;

/// The path: where to press to, how far to pull, the step sizes (units of `a`).
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct PathOptions {
    /// Depth of the preload (positive: pressed in).
    pub preload: f64,
    /// Stop pulling at this depth if the punch is still attached (negative).
    pub pull_to: f64,
    /// Largest depth step on the way out.
    pub max_step: f64,
    /// Largest depth step on the way in (0: `max_step`).
    #[serde(default)]
    pub max_press_step: f64,
    /// Smallest depth step before a failing step is declared a jump.
    pub min_step: f64,
    /// Concave punches: where the hole is still open at `preload`, press on in steps of
    /// `preload` until it is closed (the centre within the law's range), down to this depth at
    /// most; `None` stops at `preload` whatever the hole does.
    #[serde(default)]
    pub press_until_closed: Option<f64>,
    /// Largest force change, in units of `F0`, of a step whose state needed a shifted Hessian
    /// that still counts as the same branch: the crack front hopping a node (lattice trapping,
    /// an artefact of the nodes) rather than the branch ending. 0 (the default): every shifted
    /// step is halved down to `min_step` and then is the end of the branch.
    #[serde(default)]
    pub hop_force: f64,
    /// Radius from which outward the mesh resolves the cohesive zone (a refined band at the
    /// rim): hops are accepted only while the outermost contact node lies there, and the
    /// pull-off is the most tensile state of the branch there. `None`: hops everywhere.
    #[serde(default)]
    pub hop_band: Option<f64>,
}

/// One point of the force-displacement curve.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct CurvePoint {
    pub depth: f64,
    /// Compression positive (units `E* a²`).
    pub force: f64,
    /// Innermost and outermost contact node (`x = 0`), if any.
    pub contact: Option<(f64, f64)>,
    /// Innermost and outermost node of the cohesive zone (`0 < x <= 3 ρ`), if any.
    pub zone: Option<(f64, f64)>,
    /// Outermost node separated by more than the zone (`x > 3 ρ`), if any: the edge of an open
    /// hole of a concave punch (or of the detached part).
    pub open_to: Option<f64>,
    /// The two innermost nodes (the centre and the next, for a disk) are separated beyond the
    /// zone while some node is in contact: an open hole. (A linear gap's apex alone may stay open
    /// by less than its first element's slope: a hole the mesh does not resolve, not counted.)
    pub centre_open: bool,
    /// Branch number: 0 from the start, one more after every jump.
    pub branch: usize,
    /// On the way out (after the preload).
    pub unloading: bool,
}

/// The end of a branch.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Jump {
    pub depth: f64,
    pub force_before: f64,
    /// `None` where the state it lands on was not found ([`Curve::unresolved_landing`]).
    pub force_after: Option<f64>,
    pub unloading: bool,
}

/// The most tensile state of the unloading branch the preload is on.
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct Pulloff {
    pub depth: f64,
    /// Negative (tensile).
    pub force: f64,
    /// `true` where the maximum is smooth (`dF/dd = 0`), `false` where it is the end of the
    /// branch (the grips and the load let go together).
    pub smooth: bool,
    /// With [`PathOptions::hop_band`]: the most tensile state is the last one whose crack front
    /// lies in the band, and the branch went on outside it (the maximum is not resolved: the
    /// force is a lower bound).
    #[serde(default)]
    pub at_band_edge: bool,
}

/// The force-displacement curve with its jumps and pull-off.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Curve {
    pub points: Vec<CurvePoint>,
    pub jumps: Vec<Jump>,
    pub pulloff: Pulloff,
    /// Newton iterations in all.
    pub iterations: usize,
    /// Steps accepted as node hops of the crack front ([`PathOptions::hop_force`]).
    #[serde(default)]
    pub hops: usize,
    /// Where the unloading branch ended and no state after the jump was found: why (the walk
    /// stopped there; the pull-off of the branch is still its most tensile state).
    #[serde(default)]
    pub unresolved_landing: Option<String>,
}

fn describe(
    surface: &CohesiveSurface,
    e: &Equilibrium,
    branch: usize,
    unloading: bool,
) -> CurvePoint {
    let range = surface.law.range;
    let extent = |pick: &dyn Fn(f64) -> bool| extent(surface, &e.separation, pick);
    CurvePoint {
        depth: e.depth,
        force: e.force,
        contact: extent(&|x| x <= 0.0),
        zone: extent(&|x| x > 0.0 && x <= ZONE_RANGES * range),
        open_to: extent(&|x| x > ZONE_RANGES * range).map(|(_, hi)| hi),
        centre_open: e.separation.len() >= 2
            && e.separation[..2].iter().all(|&x| x > ZONE_RANGES * range)
            && e.separation.iter().any(|&x| x <= 0.0),
        branch,
        unloading,
    }
}

/// Innermost and outermost node radius whose separation `pick` chooses, if any.
fn extent(
    surface: &CohesiveSurface,
    separation: &[f64],
    pick: &dyn Fn(f64) -> bool,
) -> Option<(f64, f64)> {
    let mut chosen = surface
        .radii
        .iter()
        .zip(separation)
        .filter(|(_, &x)| pick(x))
        .map(|(&r, _)| r);
    let first = chosen.next()?;
    Some((first, chosen.last().unwrap_or(first)))
}

/// Kendall's `F0 = sqrt(8 π Δw)` (`E* = a = 1`).
fn kendall(surface: &CohesiveSurface) -> f64 {
    (8.0 * std::f64::consts::PI * surface.law.work).sqrt()
}

/// Whether the punch has let go: no contact and every separation beyond 30 ranges.
fn detached(surface: &CohesiveSurface, e: &Equilibrium) -> bool {
    e.separation.iter().all(|&x| x > 30.0 * surface.law.range)
}

struct Walker<'s> {
    surface: &'s CohesiveSurface,
    options: PathOptions,
    curve: Vec<CurvePoint>,
    jumps: Vec<Jump>,
    states: Vec<Equilibrium>,
    branch: usize,
    iterations: usize,
    hops: usize,
    unresolved_landing: Option<String>,
}

impl Walker<'_> {
    /// Walk from the last state to `target` (stopping early once detached when unloading).
    fn walk(&mut self, target: f64, unloading: bool) -> Result<()> {
        let f0 = kendall(self.surface);
        let largest = if unloading || self.options.max_press_step <= 0.0 {
            self.options.max_step
        } else {
            self.options.max_press_step.max(self.options.min_step)
        };
        let mut step = largest;
        loop {
            let last = self.states.last().expect("a start state").clone();
            if (last.depth - target).abs() <= 1e-15
                || (unloading && (detached(self.surface, &last) || self.jumped_while_unloading()))
            {
                return Ok(());
            }
            let direction = (target - last.depth).signum();
            let depth = if (target - last.depth).abs() <= step {
                target
            } else {
                last.depth + direction * step
            };
            let attempt = self.surface.equilibrium(depth, &last.separation);
            let mut hop = false;
            let continuous = match &attempt {
                Ok(next) => {
                    self.iterations += next.iterations;
                    let change = (next.force - last.force).abs();
                    // A hop starts and lands in the band: a front that jumps out of it ran
                    // (the coarser mesh beyond only arrests it).
                    hop = next.shifted
                        && change <= self.options.hop_force * f0
                        && self.in_band(&last)
                        && self.in_band(next);
                    (!next.shifted || hop) && change <= JUMP_FORCE * f0
                }
                Err(_) => false,
            };
            if continuous && hop {
                self.hops += 1;
            }
            if !continuous && step > self.options.min_step {
                step *= 0.5;
                continue;
            }
            let next = if continuous {
                attempt?
            } else {
                match self.landing(depth, attempt) {
                    Ok(state) => state,
                    // The unloading branch has ended (its pull-off is behind) but the state it
                    // jumps to was not found: the walk stops there, and says so.
                    Err(e) if unloading => {
                        self.jumps.push(Jump {
                            depth: last.depth,
                            force_before: last.force,
                            force_after: None,
                            unloading,
                        });
                        self.unresolved_landing = Some(e.to_string());
                        return Ok(());
                    }
                    Err(e) => return Err(e),
                }
            };
            if !continuous {
                self.jumps.push(Jump {
                    depth: last.depth,
                    force_before: last.force,
                    force_after: Some(next.force),
                    unloading,
                });
                self.branch += 1;
            }
            self.curve
                .push(describe(self.surface, &next, self.branch, unloading));
            self.states.push(next);
            step = (1.5 * step).min(largest);
        }
    }
}

impl Walker<'_> {
    /// Whether the crack front (the outermost node in contact) of `state` lies in
    /// [`PathOptions::hop_band`] (always, without one).
    fn in_band(&self, state: &Equilibrium) -> bool {
        match self.options.hop_band {
            None => true,
            Some(band) => front_in_band(self.surface, &state.separation, band),
        }
    }

    /// The unloading path has left the preload's branch: the pull-off is behind.
    fn jumped_while_unloading(&self) -> bool {
        self.jumps.iter().any(|j| j.unloading)
    }

    /// Where a branch that ended at `depth` lands: the equilibrium the Newton iteration from the
    /// end of the branch reached (energy descent from it, as the grips would let it go), else,
    /// when that found none, the free surface (every separation beyond 30 ranges).
    fn landing(&mut self, depth: f64, from_branch: Result<Equilibrium>) -> Result<Equilibrium> {
        let error = match from_branch {
            Ok(state) => return Ok(state),
            Err(e) => e,
        };
        let surface = self.surface;
        let free_start: Vec<f64> = surface.recess.iter().map(|g| g - depth).collect();
        if free_start.iter().all(|&x| x > 30.0 * surface.law.range) {
            if let Ok(free) = surface.equilibrium(depth, &free_start) {
                if detached(surface, &free) {
                    self.iterations += free.iterations;
                    return Ok(free);
                }
            }
        }
        Err(error)
    }
}

/// Whether the outermost node in contact (zero separation, [`CurvePoint::contact`]) lies at
/// radius `band` or beyond.
fn front_in_band(surface: &CohesiveSurface, separation: &[f64], band: f64) -> bool {
    extent(surface, separation, &|x| x <= 0.0).is_some_and(|(_, outer)| outer >= band)
}

/// Press to the preload, then pull until free (or to `pull_to`), from the undeformed surface at
/// zero depth.
pub fn follow(surface: &CohesiveSurface, options: PathOptions) -> Result<Curve> {
    if !(options.preload.is_finite()
        && options.pull_to < options.preload
        && options.min_step > 0.0
        && options.max_step >= options.min_step)
    {
        return Err(Error::OutOfRange {
            method: "cohesive-fem".into(),
            reason: format!(
                "path {options:?}: need pull_to < preload and 0 < min_step <= max_step"
            ),
        });
    }
    let start = surface.equilibrium(0.0, &surface.recess)?;
    let mut walker = Walker {
        surface,
        options,
        curve: vec![describe(surface, &start, 0, false)],
        jumps: Vec::new(),
        iterations: start.iterations,
        states: vec![start],
        branch: 0,
        hops: 0,
        unresolved_landing: None,
    };
    walker.walk(options.preload, false)?;
    if let Some(deepest) = options.press_until_closed {
        let mut depth = options.preload;
        while walker.curve.last().is_some_and(|p| p.centre_open) && depth < deepest {
            depth = (depth + options.preload.abs().max(options.max_press_step)).min(deepest);
            walker.walk(depth, false)?;
        }
    }
    let preload_index = walker.states.len() - 1;
    walker.walk(options.pull_to, true)?;
    let end = walker.states.last().expect("a state");
    if !walker.jumped_while_unloading() && !detached(surface, end) {
        return Err(Error::NoConvergence {
            method: "cohesive-fem".into(),
            reason: format!(
                "the punch is still attached at the end of the pull, d = {} (force {}): the \
                 pull-off lies deeper; pull further",
                crate::error::show(options.pull_to),
                crate::error::show(end.force)
            ),
        });
    }
    let pulloff = pulloff(&mut walker, preload_index)?;
    Ok(Curve {
        points: walker.curve,
        jumps: walker.jumps,
        pulloff,
        iterations: walker.iterations,
        hops: walker.hops,
        unresolved_landing: walker.unresolved_landing,
    })
}

/// The most tensile state of the unloading branch the preload is on (up to its first jump),
/// refined where it is a smooth maximum. Past that jump the discrete crack front advances node by
/// node and is pinned between jumps (lattice trapping: the tension can rise again, an artefact
/// of the nodes, not of the law), so the first end of the branch is the pull-off the model
/// resolves.
fn pulloff(walker: &mut Walker, preload_index: usize) -> Result<Pulloff> {
    let branch = walker.curve[preload_index].branch;
    let last_of_branch = (preload_index..walker.states.len())
        .take_while(|&k| walker.curve[k].branch == branch)
        .last()
        .unwrap_or(preload_index);
    // With a band, only the states whose front lies in it count (the mesh resolves the zone
    // there only); the front moves inward, so they come first.
    let last = (preload_index..=last_of_branch)
        .take_while(|&k| walker.in_band(&walker.states[k]))
        .last()
        .unwrap_or(preload_index);
    let at_band_edge = last < last_of_branch;
    let (best, _) = (preload_index..=last)
        .map(|k| (k, walker.states[k].force))
        .fold((preload_index, f64::INFINITY), |acc, (k, f)| {
            if f < acc.1 {
                (k, f)
            } else {
                acc
            }
        });
    let branch_ends = best == last || best == preload_index;
    let state = &walker.states[best];
    if branch_ends {
        return Ok(Pulloff {
            depth: state.depth,
            force: state.force,
            smooth: false,
            at_band_edge: at_band_edge && best == last,
        });
    }
    // A smooth maximum of the tension between its neighbours: golden-section search, each
    // trial from the nearest state of the branch.
    let (mut lo, mut hi) = (walker.states[best + 1].depth, walker.states[best - 1].depth);
    let start = walker.states[best].separation.clone();
    let surface = walker.surface;
    let force_at = |d: f64, iterations: &mut usize| -> Result<f64> {
        let e = surface.equilibrium(d, &start)?;
        *iterations += e.iterations;
        Ok(e.force)
    };
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let mut a = lo + (1.0 - ratio) * (hi - lo);
    let mut b = lo + ratio * (hi - lo);
    let mut fa = force_at(a, &mut walker.iterations)?;
    let mut fb = force_at(b, &mut walker.iterations)?;
    while hi - lo > 1e-6 * walker.options.max_step {
        if fa < fb {
            hi = b;
            b = a;
            fb = fa;
            a = lo + (1.0 - ratio) * (hi - lo);
            fa = force_at(a, &mut walker.iterations)?;
        } else {
            lo = a;
            a = b;
            fa = fb;
            b = lo + ratio * (hi - lo);
            fb = force_at(b, &mut walker.iterations)?;
        }
    }
    let (depth, force) = if fa < fb { (a, fa) } else { (b, fb) };
    Ok(Pulloff {
        depth,
        force: force.min(state.force),
        smooth: true,
        at_band_edge: false,
    })
}
