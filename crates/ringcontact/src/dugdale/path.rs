//! An equilibrium path and its pull-off: the first extremum of the force (fixed load) or of the
//! depth (fixed grips) met as the punch is pulled, sampled and then refined by golden section.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::numerics::brent::brent_minimum;

use super::configuration::Configuration;
use super::METHOD;

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

    /// The held quantity's name.
    pub(crate) fn quantity(self) -> &'static str {
        match self {
            Control::Load => "force",
            Control::Grips => "depth",
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
    /// Whether the contact is pressed from the rim inward before it is pulled (a recess:
    /// pressing stops where [`pressing_stops`] says, and the pull-off is the lowest held value
    /// after it); else the path starts where pressing left it.
    fn pressed_from_rim(&self) -> bool {
        false
    }
    /// States past the contact's `last` one, in the order they are met ([`Beyond`]): reached
    /// when `ceased` is false at the narrowest contact sampled, else where the family's states
    /// ceased; none by default.
    fn beyond_contact(&self, last: &PathPoint, ceased: bool) -> Beyond {
        let _ = (last, ceased);
        Beyond::none()
    }
    /// Spacing of the samples of the states beyond the contact, in their parameter.
    fn beyond_step(&self) -> f64 {
        0.0
    }
}

/// Parameters at and above this one belong to the states with no contact left that
/// [`Family::at`] refines (`BEYOND_CONTACT` plus their own parameter); a family's contact
/// states lie well below it (within ±20), and the parameters' rounding stays near 1e-14.
pub(crate) const BEYOND_CONTACT: f64 = 100.0;

/// The states past a family's contact states: each with its parameter (at or above
/// [`BEYOND_CONTACT`], or infinite for a state exact as it is, not refined), and why they end
/// short of the surface letting go, if they do.
pub(crate) struct Beyond {
    pub states: Vec<(f64, PathPoint)>,
    pub cut_short: Option<String>,
}

impl Beyond {
    /// No states past the contact.
    pub fn none() -> Self {
        Self {
            states: Vec::new(),
            cut_short: None,
        }
    }

    /// States exact as they are (the whole face in tension), after the narrowest contact
    /// sampled only (`ceased` false).
    pub fn exact(states: Vec<PathPoint>, ceased: bool) -> Self {
        Self {
            states: if ceased {
                Vec::new()
            } else {
                states.into_iter().map(|p| (f64::INFINITY, p)).collect()
            },
            cut_short: None,
        }
    }
}

/// A path as the punch is pulled: its states, each with its parameter (infinite for the states
/// beyond the contact), and why it ends.
pub(crate) struct Path {
    pub samples: Vec<(f64, PathPoint)>,
    /// Why the samples end where the held quantity may still fall: the narrowest contact
    /// sampled, or the family's states ceasing; `None` where they run on beyond the contact.
    pub cut_short: Option<String>,
}

/// The path of `family`. Where the family has no state ([`Error::OutOfRange`]) the path is the
/// last run of states without a gap (pressing from the rim enters it and cannot cross a gap;
/// pulling ends where the run ends); an error where it has no state at all.
pub(crate) fn path(family: &dyn Family) -> Result<Path> {
    let (first, last) = family.parameter_range();
    let step = (last - first) / (PATH_SAMPLES - 1) as f64;
    let mut states = Vec::with_capacity(PATH_SAMPLES);
    for k in 0..PATH_SAMPLES {
        let t = first + step * k as f64;
        match family.at(t) {
            Ok(point) => states.push(Ok((t, point))),
            Err(e @ Error::OutOfRange { .. }) => states.push(Err(e)),
            Err(e) => return Err(e),
        }
    }
    let end = states.iter().rposition(|s| s.is_ok());
    let Some(end) = end else {
        return Err(states
            .pop()
            .and_then(|s| s.err())
            .unwrap_or(Error::OutOfRange {
                method: super::METHOD.into(),
                reason: "no state on the path".into(),
            }));
    };
    let start = states[..end]
        .iter()
        .rposition(|s| s.is_err())
        .map_or(0, |k| k + 1);
    let cut_short = match states.get(end + 1) {
        Some(Err(reason)) => Some(format!(
            "the states end there ({})",
            reason.to_string().trim_end_matches('.')
        )),
        _ => None,
    };
    let mut samples: Vec<(f64, PathPoint)> =
        states.drain(start..=end).filter_map(|s| s.ok()).collect();
    let last = samples[samples.len() - 1].1;
    let beyond = family.beyond_contact(&last, cut_short.is_some());
    let cut_short = if beyond.states.is_empty() {
        cut_short.or_else(|| Some("at the narrowest contact sampled".into()))
    } else {
        beyond.cut_short
    };
    samples.extend(beyond.states);
    Ok(Path { samples, cut_short })
}

/// A pull-off located on its path: its parameter and state, and how far the depth and the force
/// may differ at the extremum itself (`[depth, force]`: the steepest slope to the nearest
/// states evaluated on either side times the farther one's distance; 0 for a state exact as it
/// is), which a kink in the held quantity (the zone's end leaving the rim) makes linear in the
/// search's width.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Located {
    pub parameter: f64,
    pub point: PathPoint,
    pub spread: [f64; 2],
}

impl Located {
    fn new((parameter, point): (f64, PathPoint), spread: [f64; 2]) -> Self {
        Self {
            parameter,
            point,
            spread,
        }
    }
}

/// The pull-off of `family` under `control` and its parameter, located to a thousandth of
/// `tolerance` ([`parameter_width`]): refined by Brent's search within two sample spacings of
/// `near` (a coarser node count's), else found along the whole path.
pub(crate) fn pulloff(
    family: &dyn Family,
    control: Control,
    near: Option<f64>,
    tolerance: f64,
) -> Result<Located> {
    let width = parameter_width(tolerance);
    let held = |p: &PathPoint| control.held(p);
    let (first, last) = family.parameter_range();
    let step = (last - first) / (PATH_SAMPLES - 1) as f64;
    let step_at = |t: f64| {
        if t >= BEYOND_CONTACT {
            family.beyond_step()
        } else {
            step
        }
    };
    let inside_path = |&(t, step): &(f64, f64)| {
        let (lo, hi) = (t - 2.0 * step, t + 2.0 * step);
        step > 0.0
            && segment(lo) == segment(t)
            && (t >= BEYOND_CONTACT || lo >= first && hi <= last)
    };
    let near = near.filter(|t| t.is_finite()).map(|t| (t, step_at(t)));
    if let Some((t, step)) = near.filter(inside_path) {
        let bracket: Result<Vec<(f64, PathPoint)>> = [t - 2.0 * step, t, t + 2.0 * step]
            .into_iter()
            .map(|t| family.at(t).map(|p| (t, p)))
            .collect();
        // A bracket reaching past the family's states falls back on the whole path.
        let bracket = match bracket {
            Err(Error::OutOfRange { .. }) => Vec::new(),
            other => other?,
        };
        if bracket.len() == 3 && held(&bracket[1].1) < held(&bracket[0].1).min(held(&bracket[2].1))
        {
            let bracket = Path {
                samples: bracket,
                cut_short: None,
            };
            return first_minimum(&bracket, control, false, width, |t| family.at(t));
        }
    }
    first_minimum(
        &path(family)?,
        control,
        family.pressed_from_rim(),
        width,
        |t| family.at(t),
    )
}

/// Where pressing from the rim stops on a path ordered as the punch is pulled: from the last
/// contact state inward, past the states where the held quantity falls inward (met unstably
/// on touching) and up the states where it rises (pressing) to its first maximum; the widest
/// state where it rises all the way (pressed further, the hole snaps shut).
fn pressing_stops(samples: &[(f64, PathPoint)], held: &dyn Fn(&PathPoint) -> f64) -> usize {
    let value = |k: usize| held(&samples[k].1);
    let mut k = samples
        .iter()
        .rposition(|(t, _)| t.is_finite())
        .unwrap_or(0);
    while k > 0 && value(k - 1) < value(k) {
        k -= 1;
    }
    while k > 0 && value(k - 1) >= value(k) {
        k -= 1;
    }
    k
}

/// The part of a path a sample's parameter belongs to: the contact's states, the states
/// beyond the contact that are refined, or those exact as they are.
fn segment(t: f64) -> u8 {
    if t.is_infinite() {
        2
    } else if t >= BEYOND_CONTACT {
        1
    } else {
        0
    }
}

/// The interval around `samples[index]` searched for the extremum: between its neighbours on
/// its own segment of the path ([`segment`]); at the contact's last state, as far again past
/// it (where the contact's states may end); at the first state beyond the contact, from it.
/// `None` for a state exact as it is.
fn bracket_in_segment(samples: &[(f64, PathPoint)], index: usize) -> Option<(f64, f64)> {
    let t = samples[index].0;
    let own = segment(t);
    let (before, after) = (samples[index - 1].0, samples[index + 1].0);
    let lo = if segment(before) == own { before } else { t };
    let hi = if segment(after) == own {
        after
    } else if own == 0 {
        t + (t - lo)
    } else {
        t
    };
    (own != 2 && hi > lo).then_some((lo, hi))
}

/// Width of the path parameter within which Brent's search locates the pull-off, for a
/// pull-off wanted to `tolerance`: a thousandth of it (the depth or force not held moves about
/// linearly with the parameter there, the held one quadratically), between the rounding floor of
/// a quadratic minimum's location and 1e-6.
fn parameter_width(tolerance: f64) -> f64 {
    (1e-3 * tolerance).clamp(1e-11, 1e-6)
}

/// The first local minimum of `held` after its first maximum along the `samples` of `state(t)`
/// (ordered as the punch is pulled; states before the maximum are not reached by pressing;
/// when `pressed_from_rim`, the lowest value after where pressing stops, [`pressing_stops`]),
/// refined by Brent's search on its segment of the path ([`bracket_in_segment`]) to `width`;
/// the last sample when `held` falls all the way into the states beyond the contact, an error
/// when it still falls where the path is cut short.
fn first_minimum(
    path: &Path,
    control: Control,
    pressed_from_rim: bool,
    width: f64,
    state: impl Fn(f64) -> Result<PathPoint>,
) -> Result<Located> {
    let samples = &path.samples;
    let held = |p: &PathPoint| control.held(p);
    let falls = |k: usize| held(&samples[k].1) < held(&samples[k - 1].1);
    let top = if pressed_from_rim {
        pressing_stops(samples, &held)
    } else {
        (1..samples.len()).find(|&k| falls(k)).map_or(0, |k| k - 1)
    };
    let index = if pressed_from_rim {
        // Past a local minimum the contact jumps to a later state of the same held value: the
        // pull-off is the lowest value after the maximum.
        (top..samples.len()).fold(top, |m, k| {
            if held(&samples[k].1) < held(&samples[m].1) {
                k
            } else {
                m
            }
        })
    } else {
        (top + 1..samples.len())
            .find(|&k| !falls(k))
            .map_or(samples.len() - 1, |k| k - 1)
    };
    if let Some(end) = path
        .cut_short
        .as_ref()
        .filter(|_| index + 1 == samples.len())
    {
        return Err(Error::OutOfRange {
            method: METHOD.into(),
            reason: format!(
                "no pull-off on the path: the {} still falls where the path ends, {end} \
                 (fixed {})",
                control.quantity(),
                control.name()
            ),
        });
    }
    if index == 0 || index + 1 == samples.len() {
        return Ok(Located::new(samples[index], [0.0; 2]));
    }
    let Some((lo, hi)) = bracket_in_segment(samples, index) else {
        // A state off the parameterised path (the whole face in tension) is exact as it is.
        return Ok(Located::new(samples[index], [0.0; 2]));
    };
    let mut best = samples[index];
    let mut evaluated: Vec<(f64, PathPoint)> = [index - 1, index + 1]
        .into_iter()
        .map(|k| samples[k])
        .filter(|(t, _)| (lo..=hi).contains(t))
        .collect();
    // Where the family has no state (past the end of the contact's states) the held quantity
    // counts as infinite: the search keeps to the states that exist.
    let mut ceased: Vec<f64> = Vec::new();
    let mut visit = |t: f64| -> Result<f64> {
        let point = match state(t) {
            Ok(point) => point,
            Err(Error::OutOfRange { .. }) => {
                ceased.push(t);
                return Ok(f64::INFINITY);
            }
            Err(e) => return Err(e),
        };
        evaluated.push((t, point));
        if held(&point) < held(&best.1) {
            best = (t, point);
        }
        Ok(held(&point))
    };
    brent_minimum(&mut visit, lo, hi, 0.25 * width)?;
    let spread = spread_around(best, &evaluated, &ceased);
    Ok(Located::new(best, spread))
}

/// How far the depth and the force may differ at the extremum from the `best` state found:
/// the extremum lies between the nearest `evaluated` states on either side (or the nearest
/// parameter with no state, `ceased`, when that is nearer), so each quantity can differ by its
/// steepest slope toward them times the farthest distance.
fn spread_around(
    best: (f64, PathPoint),
    evaluated: &[(f64, PathPoint)],
    ceased: &[f64],
) -> [f64; 2] {
    let nearest = |side: f64| {
        evaluated
            .iter()
            .filter(|(t, _)| (t - best.0) * side > 0.0)
            .min_by(|a, b| (a.0 - best.0).abs().total_cmp(&(b.0 - best.0).abs()))
    };
    let neighbours: Vec<&(f64, PathPoint)> = [nearest(-1.0), nearest(1.0)]
        .into_iter()
        .flatten()
        .collect();
    let nearest_on = |side: f64| {
        let state = nearest(side).map(|(t, _)| *t);
        let no_state = ceased.iter().copied().filter(|t| (t - best.0) * side > 0.0);
        state
            .into_iter()
            .chain(no_state)
            .map(|t| (t - best.0).abs())
            .reduce(f64::min)
    };
    let reach = [-1.0, 1.0]
        .into_iter()
        .filter_map(nearest_on)
        .fold(0.0, f64::max);
    let steepest = |quantity: fn(&PathPoint) -> f64| {
        neighbours
            .iter()
            .map(|(t, p)| (quantity(p) - quantity(&best.1)).abs() / (t - best.0).abs())
            .fold(0.0, f64::max)
    };
    [steepest(|p| p.depth) * reach, steepest(|p| p.force) * reach]
}
