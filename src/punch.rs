//! Punch shapes and their gap functions.
//!
//! The gap `g(r)` is the distance from the punch face up to the plane of the sharp rim, for
//! `0 <= r <= a` (see `docs/conventions.md`). Non-penetration reads `w(r) >= d - g(r)`.
//!
//! | shape | gap `g(r)` | contact |
//! |---|---|---|
//! | flat circular | `0` | `[0, a]` |
//! | flat annular | hole for `r < b`, `0` on `[b, a]` | `[b, a]`, fixed |
//! | conical concave | `h (1 - r/a)` | `[b(d), a]` |
//! | spherical (parabolic) concave | `h (1 - r²/a²)` | `[b(d), a]` |

use serde::{Deserialize, Serialize};

/// The four punch shapes the project verifies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum PunchKind {
    /// Flat circular punch (Boussinesq): contact is the full disk.
    Flat,
    /// Flat annular punch: contact is the fixed annulus `b <= r <= a`.
    FlatAnnulus,
    /// Conical concave punch, gap `h (1 - r/a)`.
    Cone,
    /// Spherical (parabolic) concave punch, gap `h (1 - r²/a²)`.
    Sphere,
}

impl PunchKind {
    /// Name used on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            PunchKind::Flat => "flat",
            PunchKind::FlatAnnulus => "flat-annulus",
            PunchKind::Cone => "cone",
            PunchKind::Sphere => "sphere",
        }
    }

    /// Whether the inner contact radius is found by the solver (concave punches).
    pub fn is_concave(self) -> bool {
        matches!(self, PunchKind::Cone | PunchKind::Sphere)
    }

    /// Whether the concave profile is smooth at the axis (`g(r)` even and analytic there: the
    /// sphere), so that the full-contact pressure is smooth there and the contact can close.
    /// The cone's apex (`g = h (1 - r/a)`, a kink) makes the pressure there log-singular: a
    /// hole stays open at every depth.
    pub fn profile_smooth_at_axis(self) -> bool {
        matches!(self, PunchKind::Sphere)
    }

    /// Dimensionless gap `g(r)/h` of a concave punch at `rho = r/a` (0 for flat punches).
    pub fn gap_shape(self, rho: f64) -> f64 {
        match self {
            PunchKind::Flat | PunchKind::FlatAnnulus => 0.0,
            PunchKind::Cone => 1.0 - rho,
            PunchKind::Sphere => 1.0 - rho * rho,
        }
    }
}

impl std::fmt::Display for PunchKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Punch geometry in physical units (any consistent length unit).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Punch {
    pub kind: PunchKind,
    /// Outer contact radius `a` = the sharp rim.
    pub rim_radius: f64,
    /// Inner radius `b` of the flat annulus (`0 <= b < a`; `b = 0` is the flat circular punch).
    pub inner_radius: f64,
    /// Depth `h` of the concave hole at `r = 0` (concave punches only; 0 otherwise).
    pub hole_depth: f64,
}

impl Punch {
    /// Gap `g(r)` in length units, `0 <= r <= a`.
    pub fn gap(&self, r: f64) -> f64 {
        self.hole_depth * self.kind.gap_shape(r / self.rim_radius)
    }

    /// `b/a` of a flat annulus (0 for the other shapes).
    pub fn inner_ratio(&self) -> f64 {
        self.inner_radius / self.rim_radius
    }
}
