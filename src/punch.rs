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
//! | power-law concave, exponent `n > 0` | `h (1 - (r/a)^n)` | `[b(d), a]` |
//! | torus (parabolic section), tube radius `ρ` | `(r - a)²/(2ρ) = h (1 - r/a)²`, `h = a²/(2ρ)` | `[b(d), c(d)]` |
//! | table (a measured profile) | `h ĝ(r/a)`, `ĝ` interpolated from `(r/a, g/h)` points | `[b(d), a]` |
//!
//! Every concave punch has a sharp rim at `r = a` (fixed edge, pressure singular) and a free
//! inner edge `b` found by the solution (pressure zero there without adhesion). The power law
//! holds the cone (`n = 1`) and the sphere (`n = 2`) as special cases; `cone` and `sphere` keep
//! their own names and evaluate the same gap. The torus has no rim: both edges of its contact
//! are free, and its gap is defined on both sides of the ring radius `a`. Written as
//! `h (1 - r/a)²` it is one dimensionless shape for every tube radius (the tube radius only sets
//! the depth scale `h`), so it shares the concave punches' `γ1 = d/h` and `γ2 = F/(2 E* h a)`.
//! The table punch is a concave punch whose profile is read from a file ([`table`]).

pub mod table;

use std::hash::{Hash, Hasher};
use std::path::Path;

pub use table::TableProfile;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// The names of the punch shapes, as written on the command line (`--punch`), in scene files
/// (`punch.shape`) and in JSON (`"punch"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum PunchName {
    /// Flat circular punch (Boussinesq): contact is the full disk.
    Flat,
    /// Flat annular punch: contact is the fixed annulus `b <= r <= a` (give `--eps b/a`).
    FlatAnnulus,
    /// Conical concave punch, gap `h (1 - r/a)`.
    Cone,
    /// Spherical (parabolic) concave punch, gap `h (1 - r²/a²)`.
    Sphere,
    /// Power-law concave punch, gap `h (1 - (r/a)^n)` (give `--exponent n`, any `n > 0`).
    Power,
    /// Torus: a convex ring of radius `a` with parabolic section, gap `(r - a)²/(2ρ)`, both
    /// contact edges free (`verify solve` and `verify table` take `--tube-radius ρ`; the other
    /// commands work in units of `h = a²/(2ρ)` and need none).
    Torus,
    /// Concave punch of a measured profile: `(r/a, g/h)` points from a CSV file, rim at the
    /// last point `r = a`, inner edge free (give `--profile FILE`).
    Table,
}

impl PunchName {
    /// Name used on the command line and in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            PunchName::Flat => "flat",
            PunchName::FlatAnnulus => "flat-annulus",
            PunchName::Cone => "cone",
            PunchName::Sphere => "sphere",
            PunchName::Power => "power",
            PunchName::Torus => "torus",
            PunchName::Table => "table",
        }
    }

    /// The punch of this name; `exponent` is the power law's `n` and is refused for every other
    /// shape; the table punch needs [`with_parameters`](Self::with_parameters).
    pub fn with_exponent(self, exponent: Option<f64>) -> Result<PunchKind> {
        self.with_parameters(exponent, None)
    }

    /// The punch of this name with its parameters: `exponent` the power law's `n`, `profile`
    /// the table punch's file; each refused for every other shape.
    pub fn with_parameters(
        self,
        exponent: Option<f64>,
        profile: Option<&Path>,
    ) -> Result<PunchKind> {
        match (self, profile) {
            (PunchName::Table, Some(path)) if exponent.is_none() => {
                return Ok(PunchKind::Table(TableRef(TableProfile::load(path)?)));
            }
            (PunchName::Table, None) => {
                return Err(Error::InvalidScene {
                    field: "profile".into(),
                    rule: "the table punch needs its profile, a CSV file of (r/a, g/h) points \
                           (--profile FILE, or punch.profile in a scene file)"
                        .into(),
                })
            }
            (PunchName::Table, Some(_)) => {}
            (_, Some(_)) => {
                return Err(Error::InvalidScene {
                    field: "profile".into(),
                    rule: format!("applies only to shape = table, not {}", self.as_str()),
                })
            }
            (_, None) => {}
        }
        match (self, exponent) {
            (PunchName::Power, Some(n)) => Ok(PunchKind::Power(Exponent::new(n)?)),
            (PunchName::Power, None) => Err(Error::InvalidScene {
                field: "exponent".into(),
                rule: "the power-law punch needs its exponent n > 0 (--exponent N, or \
                          punch.exponent in a scene file); n = 1 is the cone, n = 2 the sphere"
                    .into(),
            }),
            (_, Some(_)) => Err(Error::InvalidScene {
                field: "exponent".into(),
                rule: format!(
                    "applies only to shape = power, not {} (the cone is n = 1 and the sphere \
                     n = 2 by definition)",
                    self.as_str()
                ),
            }),
            (PunchName::Flat, None) => Ok(PunchKind::Flat),
            (PunchName::FlatAnnulus, None) => Ok(PunchKind::FlatAnnulus),
            (PunchName::Cone, None) => Ok(PunchKind::Cone),
            (PunchName::Sphere, None) => Ok(PunchKind::Sphere),
            (PunchName::Torus, None) => Ok(PunchKind::Torus),
            (PunchName::Table, None) => unreachable!("the table punch returned above"),
        }
    }
}

impl std::fmt::Display for PunchName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Exponent `n` of the power-law concave punch, gap `h (1 - (r/a)^n)`: finite and positive.
/// Compared and hashed by its bits, so that punches can be keys.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exponent(f64);

impl Exponent {
    /// Largest exponent accepted: beyond it `(r/a)^n` is a wall at the rim whose contact ring is
    /// narrower than any method here resolves (`1 - (1 - 1e-4)^n` stays below 1 % of `h`).
    pub const MAX: f64 = 100.0;

    /// A checked exponent: finite, `0 < n <= MAX`.
    pub fn new(n: f64) -> Result<Self> {
        if !(n.is_finite() && n > 0.0 && n <= Self::MAX) {
            return Err(Error::InvalidScene {
                field: "exponent".into(),
                rule: format!(
                    "must be finite with 0 < n <= {} (got {})",
                    Self::MAX,
                    crate::error::show(n)
                ),
            });
        }
        Ok(Self(n))
    }

    /// The value `n`.
    pub fn value(self) -> f64 {
        self.0
    }
}

impl Eq for Exponent {}

impl Hash for Exponent {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.0.to_bits().hash(state);
    }
}

/// A table punch's profile as a punch holds it: read once per process, compared and hashed by
/// the SHA-256 of its file.
#[derive(Clone, Copy, Debug)]
pub struct TableRef(&'static TableProfile);

impl TableRef {
    /// The profile.
    pub fn profile(self) -> &'static TableProfile {
        self.0
    }
}

impl PartialEq for TableRef {
    fn eq(&self, other: &Self) -> bool {
        self.0 == other.0
    }
}

impl Eq for TableRef {}

impl Hash for TableRef {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.0.sha256().hash(state);
    }
}

/// A punch shape with its dimensionless parameters. Written in JSON as the keys `punch` (its
/// [`PunchName`]), for the power law `exponent`, for the table `profile_file` and
/// `profile_sha256` (`profile` is taken: peer records describe their grid with it); structs
/// holding one flatten it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(into = "PunchRecord", try_from = "PunchRecord")]
pub enum PunchKind {
    /// Flat circular punch (Boussinesq): contact is the full disk.
    Flat,
    /// Flat annular punch: contact is the fixed annulus `b <= r <= a`.
    FlatAnnulus,
    /// Conical concave punch, gap `h (1 - r/a)`.
    Cone,
    /// Spherical (parabolic) concave punch, gap `h (1 - r²/a²)`.
    Sphere,
    /// Power-law concave punch, gap `h (1 - (r/a)^n)`.
    Power(Exponent),
    /// Torus of ring radius `a`, parabolic section: gap `h (1 - r/a)²` with `h = a²/(2ρ)`,
    /// defined on both sides of `a`; both contact edges free.
    Torus,
    /// Concave punch of a tabulated profile `h ĝ(r/a)`, rim at `r = a`, inner edge free.
    Table(TableRef),
}

/// How a [`PunchKind`] is written in JSON.
#[derive(Serialize, Deserialize)]
struct PunchRecord {
    punch: PunchName,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    exponent: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    profile_file: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    profile_sha256: Option<String>,
}

impl From<PunchKind> for PunchRecord {
    fn from(kind: PunchKind) -> Self {
        PunchRecord {
            punch: kind.shape_name(),
            exponent: kind.exponent(),
            profile_file: kind.table().map(|t| t.source().to_string()),
            profile_sha256: kind.table().map(|t| t.sha256().to_string()),
        }
    }
}

impl TryFrom<PunchRecord> for PunchKind {
    type Error = Error;
    fn try_from(record: PunchRecord) -> Result<Self> {
        let kind = record.punch.with_parameters(
            record.exponent,
            record.profile_file.as_deref().map(Path::new),
        )?;
        if let (Some(table), Some(recorded)) = (kind.table(), &record.profile_sha256) {
            if table.sha256() != recorded {
                return Err(Error::invalid(
                    "profile_sha256",
                    format!(
                        "the profile `{}` has changed since the record was written (SHA-256 {} \
                         now, {recorded} recorded)",
                        table.source(),
                        table.sha256()
                    ),
                ));
            }
        }
        Ok(kind)
    }
}

impl PunchKind {
    /// The shape's name ([`PunchName`]).
    pub fn shape_name(self) -> PunchName {
        match self {
            PunchKind::Flat => PunchName::Flat,
            PunchKind::FlatAnnulus => PunchName::FlatAnnulus,
            PunchKind::Cone => PunchName::Cone,
            PunchKind::Sphere => PunchName::Sphere,
            PunchKind::Power(_) => PunchName::Power,
            PunchKind::Torus => PunchName::Torus,
            PunchKind::Table(_) => PunchName::Table,
        }
    }

    /// Name used on the command line and in JSON.
    pub fn name(self) -> &'static str {
        self.shape_name().as_str()
    }

    /// A name unique to the shape and its parameters, for file names and labels: the name, and
    /// for the power law `power-n<n>` (`power-n2.5`).
    pub fn label(self) -> String {
        match self {
            PunchKind::Power(n) => format!("power-n{}", n.value()),
            PunchKind::Table(t) => format!("table-{}", &t.profile().sha256()[..12]),
            _ => self.name().to_string(),
        }
    }

    /// The punch of a [`label`](Self::label) (`cone`, `power-n2.5`), if it names one. A table
    /// punch's label (`table-` and the first 12 hex digits of its file's SHA-256) names it only
    /// once this process has loaded that table ([`TableProfile::loaded`]).
    pub fn from_label(label: &str) -> Option<PunchKind> {
        if let Some(n) = label.strip_prefix("power-n") {
            return Exponent::new(n.parse().ok()?).ok().map(PunchKind::Power);
        }
        if let Some(prefix) = label.strip_prefix("table-") {
            return TableProfile::loaded(prefix).map(PunchKind::from_table);
        }
        let name = <PunchName as clap::ValueEnum>::from_str(label, false).ok()?;
        name.with_exponent(None).ok()
    }

    /// The command-line flags that name this punch: `--punch cone`, `--punch power --exponent
    /// 2.5`.
    pub fn flags(self) -> String {
        match self {
            PunchKind::Power(n) => format!("--punch power --exponent {}", n.value()),
            PunchKind::Table(t) => format!("--punch table --profile {}", t.profile().source()),
            _ => format!("--punch {}", self.name()),
        }
    }

    /// The power law's exponent `n` (`None` for the other shapes, even the cone and sphere).
    pub fn exponent(self) -> Option<f64> {
        match self {
            PunchKind::Power(n) => Some(n.value()),
            _ => None,
        }
    }

    /// The table punch of a loaded profile.
    pub fn from_table(profile: &'static TableProfile) -> PunchKind {
        PunchKind::Table(TableRef(profile))
    }

    /// The table punch's profile (`None` for the other shapes).
    pub fn table(self) -> Option<&'static TableProfile> {
        match self {
            PunchKind::Table(t) => Some(t.profile()),
            _ => None,
        }
    }

    /// The exponent `n` of the concave profile `h (1 - (r/a)^n)`: 1 for the cone, 2 for the
    /// sphere, `n` for the power law; `None` for the flat punches.
    pub fn concave_exponent(self) -> Option<f64> {
        match self {
            PunchKind::Cone => Some(1.0),
            PunchKind::Sphere => Some(2.0),
            PunchKind::Power(n) => Some(n.value()),
            PunchKind::Flat | PunchKind::FlatAnnulus | PunchKind::Torus | PunchKind::Table(_) => {
                None
            }
        }
    }

    /// Whether the inner contact radius is found by the solver, with the depth scale `h` and
    /// the functions `γ1 = d/h`, `γ2 = F/(2 E* h a)`: the concave punches and the torus.
    pub fn is_concave(self) -> bool {
        self.concave_exponent().is_some() || matches!(self, PunchKind::Torus | PunchKind::Table(_))
    }

    /// Whether the contact's outer edge is a sharp rim at `r = a` (every punch but the torus,
    /// whose outer edge is free).
    pub fn has_rim(self) -> bool {
        self != PunchKind::Torus
    }

    /// Whether the concave profile is flat at the axis (`g'(0) = 0`: the sphere, the power law
    /// with `n > 1`), so that the full-contact pressure is bounded there and the contact can
    /// close at a finite depth ([`crate::reference::power_law`]). The cone's apex
    /// (`g = h (1 - r/a)`, a kink) and every `n <= 1` make the pressure there singular and
    /// tensile: a hole stays open at every depth.
    pub fn profile_smooth_at_axis(self) -> bool {
        match self {
            PunchKind::Table(t) => t.profile().slope(0.0) == 0.0,
            _ => self.concave_exponent().is_some_and(|n| n > 1.0),
        }
    }

    /// Whether a ring with a free inner edge can meet the floor of its hole before the hole
    /// closes, so that its states must be probed there: the power law flatter than the sphere
    /// at the axis (`n > 2`) and any table. The cone, the sphere and every `n <= 2` clear the
    /// floor at every contact ratio (their holes close at full contact; measured in
    /// `tests/adhesion.rs`), and so do their adhesive states, which add the flat annulus's lag.
    pub fn may_meet_hole_floor(self) -> bool {
        match self {
            PunchKind::Table(_) => true,
            _ => self.concave_exponent().is_some_and(|n| n > 2.0),
        }
    }

    /// Dimensionless gap `g(r)/h` of a concave punch or the torus at `rho = r/a` (0 for flat
    /// punches).
    pub fn gap_shape(self, rho: f64) -> f64 {
        match self {
            PunchKind::Flat | PunchKind::FlatAnnulus => 0.0,
            PunchKind::Torus => (1.0 - rho) * (1.0 - rho),
            PunchKind::Cone => 1.0 - rho,
            PunchKind::Sphere => 1.0 - rho * rho,
            PunchKind::Power(n) => 1.0 - rho.powf(n.value()),
            PunchKind::Table(t) => t.profile().value(rho),
        }
    }
}

impl std::fmt::Display for PunchKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PunchKind::Power(n) => write!(f, "power (n = {})", n.value()),
            PunchKind::Table(t) => write!(f, "table ({})", t.profile().source()),
            _ => f.write_str(self.name()),
        }
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
    /// Depth `h` of the concave hole at `r = 0` (concave punches only; 0 otherwise). For the
    /// torus the gap at the axis, `h = a²/(2ρ)`.
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

    /// The torus's tube radius `ρ = a²/(2h)` (`None` for the other shapes).
    pub fn tube_radius(&self) -> Option<f64> {
        (self.kind == PunchKind::Torus)
            .then(|| self.rim_radius * self.rim_radius / (2.0 * self.hole_depth))
    }
}
