//! An equilibrium path and its pull-off: the first extremum of the force (fixed load) or of the
//! depth (fixed grips) met as the punch is pulled, sampled and then refined by golden section.

use serde::Serialize;

use crate::error::Result;

use super::configuration::Configuration;

/// One equilibrium: the contact, the loaded region, depth `d/a` and force `F/(E* a²)`.
#[derive(Clone, Copy, Debug)]
pub struct PathPoint {
    /// Contact and loaded region.
    pub configuration: Configuration,
    /// Depth `d/a`, positive into the solid.
    pub depth: f64,
    /// Force `F/(E* a²)`, positive in compression.
    pub force: f64,
    /// The gap at the face's inner and outer edge over the range `δc` (0 where the face has no
    /// inner edge): an edge whose gap has reached `δc` has let go of the surface.
    pub edge_gaps: [f64; 2],
}

impl PathPoint {
    pub(crate) fn new(
        configuration: Configuration,
        depth: f64,
        force: f64,
        edge_gaps: [f64; 2],
    ) -> Self {
        Self {
            configuration,
            depth,
            force,
            edge_gaps,
        }
    }
}

/// How the punch is pulled: the force or the depth is what the machine holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Control {
    /// Fixed load: the pull-off is the most tensile force along the path.
    Load,
    /// Fixed grips: the pull-off is the most negative depth along the path.
    Grips,
}

impl Control {
    /// Both controls.
    pub const ALL: [Control; 2] = [Control::Load, Control::Grips];

    /// The name on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Control::Load => "load",
            Control::Grips => "grips",
        }
    }

    /// The quantity whose first minimum along the path is the pull-off.
    pub(crate) fn held(self, point: &PathPoint) -> f64 {
        match self {
            Control::Load => point.force,
            Control::Grips => point.depth,
        }
    }
}

/// Samples along a path.
const PATH_SAMPLES: usize = 40;

/// A family of equilibria along one path parameter `t`, growing as the punch is pulled.
pub(crate) trait Family {
    /// The first and last `t` sampled.
    fn parameter_range(&self) -> (f64, f64);
    /// The equilibrium at `t`.
    fn at(&self, t: f64) -> Result<PathPoint>;
    /// States past the last `t` that the parameter does not reach (the whole face in tension
    /// with no contact left), in the order they are met; none by default.
    fn beyond_contact(&self) -> Vec<PathPoint> {
        Vec::new()
    }
}

/// The path of `family` as the punch is pulled, each state with its parameter (infinite for
/// the states beyond the contact).
pub(crate) fn path(family: &dyn Family) -> Result<Vec<(f64, PathPoint)>> {
    let (first, last) = family.parameter_range();
    let step = (last - first) / (PATH_SAMPLES - 1) as f64;
    let mut samples = Vec::with_capacity(PATH_SAMPLES + 2);
    for k in 0..PATH_SAMPLES {
        let t = first + step * k as f64;
        samples.push((t, family.at(t)?));
    }
    for point in family.beyond_contact() {
        samples.push((f64::INFINITY, point));
    }
    Ok(samples)
}

/// The pull-off of `family` under `control` and its parameter: refined by golden section
/// within two sample spacings of `near` (a coarser node count's), else found along the whole
/// path.
pub(crate) fn pulloff(
    family: &dyn Family,
    control: Control,
    near: Option<f64>,
) -> Result<(f64, PathPoint)> {
    let held = |p: &PathPoint| control.held(p);
    let (first, last) = family.parameter_range();
    let step = (last - first) / (PATH_SAMPLES - 1) as f64;
    let inside_path =
        |t: &f64| t.is_finite() && *t - 2.0 * step >= first && *t + 2.0 * step <= last;
    if let Some(t) = near.filter(inside_path) {
        let bracket: Vec<(f64, PathPoint)> = [t - 2.0 * step, t, t + 2.0 * step]
            .into_iter()
            .map(|t| family.at(t).map(|p| (t, p)))
            .collect::<Result<_>>()?;
        if held(&bracket[1].1) < held(&bracket[0].1).min(held(&bracket[2].1)) {
            return first_minimum(&bracket, held, |t| family.at(t));
        }
    }
    first_minimum(&path(family)?, held, |t| family.at(t))
}

/// Golden-section width of the path parameter at the pull-off.
const PARAMETER_WIDTH: f64 = 1e-11;

/// The first local minimum of `held` along the `samples` of `state(t)` (ordered as the punch is
/// pulled), refined by golden section between its neighbours; the last sample when `held`
/// falls all the way.
fn first_minimum(
    samples: &[(f64, PathPoint)],
    held: impl Fn(&PathPoint) -> f64,
    state: impl Fn(f64) -> Result<PathPoint>,
) -> Result<(f64, PathPoint)> {
    let index = (1..samples.len())
        .find(|&k| held(&samples[k].1) >= held(&samples[k - 1].1))
        .map(|k| k - 1)
        .unwrap_or(samples.len() - 1);
    if index == 0 || index + 1 == samples.len() {
        return Ok(samples[index]);
    }
    let (mut lo, mut hi) = (samples[index - 1].0, samples[index + 1].0);
    if !(lo.is_finite() && hi.is_finite()) {
        // A state off the parameterised path (the whole face in tension) is exact as it is.
        return Ok(samples[index]);
    }
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    let mut best = samples[index];
    let mut x1 = hi - golden * (hi - lo);
    let mut x2 = lo + golden * (hi - lo);
    let (mut p1, mut p2) = (state(x1)?, state(x2)?);
    while (hi - lo).abs() > PARAMETER_WIDTH {
        if held(&p1) < held(&p2) {
            hi = x2;
            (x2, p2) = (x1, p1);
            x1 = hi - golden * (hi - lo);
            p1 = state(x1)?;
        } else {
            lo = x1;
            (x1, p1) = (x2, p2);
            x2 = lo + golden * (hi - lo);
            p2 = state(x2)?;
        }
        for candidate in [(x1, p1), (x2, p2)] {
            if held(&candidate.1) < held(&best.1) {
                best = candidate;
            }
        }
    }
    Ok(best)
}
