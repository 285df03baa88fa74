//! The [`Profile`] trait: what every solver, check and report asks of an axisymmetric punch.
//!
//! A profile is dimensionless: radii in units of the rim (or ring) radius `a`, gaps in units of
//! the depth scale `h`, so that `g(r) = h ĝ(r/a)`. A built-in punch is one implementation in its
//! own file; a user's own punch is another, written outside the crate and handed to the solvers
//! as [`PunchKind::new`](super::PunchKind::new).

use super::{PunchName, PunchRecord};

/// Where a punch's contact lies and which of its edges are free (found by the solution, the
/// pressure zero there without adhesion) or fixed (a sharp edge, the pressure singular).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contact {
    /// The whole flat face `r <= a` (Boussinesq's punch): one fixed edge, the rim.
    Disk,
    /// The fixed annulus `b <= r <= a`, `b` a parameter of the punch: two fixed edges.
    FixedAnnulus,
    /// `[b(d), a]`: a sharp rim at `r = a` and a free inner edge (the concave punches).
    RimAndFreeInner,
    /// `[b(d), c(d)]` around `r = a`: two free edges and no rim.
    FreeBand,
}

/// A dimensionless gap `ĝ(ρ)` that is smooth between known break points (a profile given by
/// points and interpolated): what the ring BEM and the MDR need to integrate it piece by piece.
pub trait PiecewiseProfile: Send + Sync {
    /// `ĝ(ρ)`.
    fn value(&self, rho: f64) -> f64;
    /// `ĝ(ρ + offset) - ĝ(ρ)`, precise relative to itself as `offset -> 0`.
    fn increment(&self, rho: f64, offset: f64) -> f64;
    /// `dĝ/dρ`.
    fn slope(&self, rho: f64) -> f64;
    /// `d²ĝ/dρ²`.
    fn curvature(&self, rho: f64) -> f64;
    /// The break points in `[0, 1]` (ascending), where derivatives of the gap may jump.
    fn break_points(&self) -> &[f64];
    /// A name of the pieces' content (a digest): values computed from them are kept under it.
    fn content_key(&self) -> &str;
}

/// One axisymmetric rigid punch, dimensionless: the gap `ĝ(ρ) = g/h` at `ρ = r/a` and what the
/// solvers may rely on. Only [`name`](Self::name), [`contact`](Self::contact),
/// [`gap`](Self::gap) and [`slope`](Self::slope) are required; every other answer has a safe
/// default (no closed form, no closure, the floor of the hole probed).
pub trait Profile: Send + Sync + std::fmt::Debug {
    /// Name on the command line and in JSON (a built-in's, or a user's own).
    fn name(&self) -> &str;

    /// Where the contact lies and which edges are free ([`Contact`]).
    fn contact(&self) -> Contact;

    /// Dimensionless gap `ĝ(ρ) = g(r)/h` at `ρ = r/a`: `ĝ(1) = 0` at a rim, `ĝ(0) = 1` for a
    /// concave punch; 0 for the flat punches.
    fn gap(&self, rho: f64) -> f64;

    /// Slope `dĝ/dρ` of the gap.
    fn slope(&self, rho: f64) -> f64;

    /// The closed forms, series, asymptotes and fits that hold for this punch (none by
    /// default): the analytic references solve with them and the harness grades against them.
    fn references(&self) -> Vec<super::Reference> {
        Vec::new()
    }

    /// A name unique to the profile and its parameters, for file names, labels and cache keys
    /// (`power-n2.5`); two profiles with one label are taken to be the same punch.
    fn label(&self) -> String {
        self.name().to_string()
    }

    /// The command-line flags that name this punch (`--punch power --exponent 2.5`).
    fn flags(&self) -> String {
        format!("--punch {}", self.name())
    }

    /// How the punch reads in a sentence (`power (n = 2.5)`).
    fn describe(&self) -> String {
        self.name().to_string()
    }

    /// The built-in name, if the punch is one of the built-in shapes.
    fn builtin(&self) -> Option<PunchName> {
        None
    }

    /// How the punch is written in JSON (its name and parameters).
    fn record(&self) -> PunchRecord {
        PunchRecord {
            punch: self.name().to_string(),
            exponent: None,
            profile_file: None,
            profile_sha256: None,
        }
    }

    /// The exponent `n` when the gap is `1 - ρ^n`,
    /// which the closed-form references of [`crate::reference::power_law`] and the paper's fits
    /// hold for.
    fn power_law_exponent(&self) -> Option<f64> {
        None
    }

    /// The exponent `n` of `1 - ρ^n` when it is a parameter of the punch (a punch whose exponent
    /// is fixed by its definition has none).
    fn exponent_parameter(&self) -> Option<f64> {
        None
    }

    /// The gap as pieces smooth between break points, if it is only piecewise smooth: the ring
    /// BEM then integrates it piece by piece (kinks and all) and its full contact comes from
    /// the MDR's quadratures over the pieces.
    fn piecewise(&self) -> Option<&dyn PiecewiseProfile> {
        None
    }

    /// Where the contact closes to a disk, `(d/h, F/(2 E* h a))`, if it does; `None` for a hole
    /// that stays open at every depth (and, by default, for a profile that does not say).
    fn closure(&self) -> Option<(f64, f64)> {
        None
    }

    /// Whether the profile is flat at the axis (`ĝ'(0) = 0`), so that the full-contact pressure
    /// is bounded there and the contact can close at a finite depth.
    fn smooth_at_axis(&self) -> bool {
        self.slope(0.0) == 0.0
    }

    /// Whether the surface inside a free inner edge can meet the floor of the hole before the
    /// hole closes, so that its states must be probed there (by default: yes, probe).
    fn may_meet_hole_floor(&self) -> bool {
        true
    }

    /// A lower bound of the hole `b/a` at depth `d/h` of a profile whose hole never closes: a
    /// method may then report full contact only with an error estimate at least this wide.
    /// `None` (the default) where no such bound is known: full contact is then checked against
    /// [`Profile::closure`].
    fn hole_lower_bound(&self, depth_over_hole: f64) -> Option<f64> {
        let _ = depth_over_hole;
        None
    }

    /// Whether the contact closes from a disk and an annulus rather than by a shrinking hole
    /// (a profile flatter than the parabolic gap at the axis); the ring BEM's single annulus stops
    /// short of it.
    fn flatter_than_the_sphere(&self) -> bool {
        false
    }

    /// An approximation of `γ1 = d/h` (`depth_controlled`) or `γ2 = F/(2 E* h a)` at the inner
    /// edge `b/a = eps`, decreasing in `eps`, that starts the ring BEM's inverse search; `None`
    /// (the default): the solver's own start (the paper's fits scaled by the rim slope).
    fn approximate_gamma(&self, eps: f64, depth_controlled: bool) -> Option<f64> {
        let _ = (eps, depth_controlled);
        None
    }

    /// Where a free band first touches, `r0/a`, and the gap's curvature there, `a² g''(r0)/h`:
    /// the narrow band's plane-strain limit. `None` (the default): not known.
    fn first_touch(&self) -> Option<(f64, f64)> {
        None
    }

    /// How far the rigid profile pressed to `d/h = depth` past its first touch reaches on each
    /// side of it: `(inner, outer)` half-widths in units of `a`, where
    /// `ĝ(r) = ĝ(r0) + d/h` ([`Profile::first_touch`]'s `r0`, `1` if it says none); the inner
    /// one stops at the axis. By default found by bisection on the gap.
    fn rigid_half_widths(&self, depth: f64) -> (f64, f64) {
        let r0 = self.first_touch().map_or(1.0, |(r0, _)| r0);
        let above = |r: f64| self.gap(r) - self.gap(r0) - depth > 0.0;
        let bisect = |mut below: f64, mut over: f64| {
            for _ in 0..100 {
                let mid = 0.5 * (below + over);
                if above(mid) {
                    over = mid;
                } else {
                    below = mid;
                }
            }
            0.5 * (below + over)
        };
        let inner = if above(0.0) { r0 - bisect(r0, 0.0) } else { r0 };
        let mut far = 2.0 * r0.max(1.0);
        for _ in 0..60 {
            if above(far) {
                break;
            }
            far *= 2.0;
        }
        (inner, bisect(r0, far) - r0)
    }

    /// The slope `-ĝ'(1)` at the rim, which scales the paper's fits into a first guess.
    fn rim_slope(&self) -> f64 {
        -self.slope(1.0)
    }
}

/// What the command line and `verify references` say of a built-in punch: one line on what it
/// is, the flags that name it, its gap, its edges and its closed forms.
#[derive(Clone, Copy, Debug)]
pub struct Summary {
    pub description: &'static str,
    pub flags: &'static str,
    pub gap: &'static str,
    pub edges: &'static str,
    pub closed_forms: &'static str,
}
