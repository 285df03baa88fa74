//! The power-law concave punch, gap `h (1 - (r/a)^n)` for any `0 < n <= 100`.

use std::hash::{Hash, Hasher};

use super::power_law;
use super::{Contact, Profile, PunchName, PunchRecord};
use crate::error::{Error, Result};

/// Exponent `n` of the power-law concave punch: finite and positive. Compared and hashed by its
/// bits, so that punches can be keys.
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

/// Power-law concave punch `1 - ρ^n`: closes at a finite depth for `n > 1`
/// ([`power_law::closure_depth`]), from a disk and an annulus for `n > 2`.
#[derive(Clone, Copy, Debug)]
pub struct Power(pub Exponent);

impl Power {
    fn n(&self) -> f64 {
        self.0.value()
    }
}

impl Profile for Power {
    fn name(&self) -> &str {
        "power"
    }
    fn builtin(&self) -> Option<PunchName> {
        Some(PunchName::Power)
    }
    fn contact(&self) -> Contact {
        Contact::RimAndFreeInner
    }
    fn gap(&self, rho: f64) -> f64 {
        1.0 - rho.powf(self.n())
    }
    fn slope(&self, rho: f64) -> f64 {
        -self.n() * rho.powf(self.n() - 1.0)
    }
    fn label(&self) -> String {
        format!("power-n{}", self.n())
    }
    fn flags(&self) -> String {
        format!("--punch power --exponent {}", self.n())
    }
    fn describe(&self) -> String {
        format!("power (n = {})", self.n())
    }
    fn record(&self) -> PunchRecord {
        PunchRecord {
            exponent: Some(self.n()),
            ..PunchRecord::named(self.name())
        }
    }
    fn power_law_exponent(&self) -> Option<f64> {
        Some(self.n())
    }
    fn exponent_parameter(&self) -> Option<f64> {
        Some(self.n())
    }
    fn closure(&self) -> Option<(f64, f64)> {
        let depth = power_law::closure_depth(self.n())?;
        Some((depth, power_law::full_contact_gamma2(self.n(), depth)?))
    }
    fn smooth_at_axis(&self) -> bool {
        self.n() > 1.0
    }
    fn may_meet_hole_floor(&self) -> bool {
        self.n() > 2.0
    }
    fn flatter_than_the_sphere(&self) -> bool {
        self.n() > 2.0
    }
    fn rim_slope(&self) -> f64 {
        self.n()
    }
}

/// What `verify references` says of this punch.
pub(crate) const SUMMARY: super::profile::Summary = super::profile::Summary {
    description: "Power-law concave punch, gap `h (1 - (r/a)^n)` (give `--exponent n`, any `n > \
                  0`)",
    flags: "--punch power --exponent N",
    gap: "h (1 - (r/a)^n), n > 0",
    edges: "rim at a, free inner edge",
    closed_forms: "full contact (n > 1) by the MDR, `verify solve --method reference`",
};
