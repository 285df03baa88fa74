//! The Dugdale adhesion law and its Tabor parameter, in the units of `verify jkr`.
//!
//! Dimensionless throughout: `a = 1`, `E* = 1`, and the work of adhesion `Δw = 1/(2π)`, so that
//! `d0 = sqrt(2π a Δw / E*) = 1` and Kendall's force `F0 = sqrt(8π E* Δw a³) = 2`. A depth is then
//! already in units of `d0`, a force `F / (E* a²)` is `2 F/F0`.

use serde::Serialize;

use crate::error::{show, Error, Result};

/// The work of adhesion `Δw / (E* a)` that makes `d0 = a`.
pub const WORK: f64 = 1.0 / (2.0 * std::f64::consts::PI);

/// Kendall's force `F0 = sqrt(8π E* Δw a³)` in units of `E* a²` (with [`WORK`]).
pub const KENDALL_FORCE: f64 = 2.0;

/// The Dugdale law: tension `σ0` wherever the gap `g` between the punch and the surface is in
/// `(0, δc]`, `δc = Δw/σ0`, none beyond; contact where the gap closes.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct DugdaleLaw {
    /// Tabor parameter `λ = 2 σ0 sqrt(a / (π E* Δw))`.
    pub tabor: f64,
}

impl DugdaleLaw {
    /// The law at Tabor parameter `tabor`: an error naming `tabor` unless it is finite and
    /// positive.
    pub fn new(tabor: f64) -> Result<Self> {
        if !(tabor.is_finite() && tabor > 0.0) {
            return Err(Error::invalid(
                "tabor",
                format!(
                    "must be a finite number > 0 (the Tabor parameter 2 sigma0 sqrt(a/(pi E* \
                     dw))); got {}",
                    show(tabor)
                ),
            ));
        }
        Ok(Self { tabor })
    }

    /// Tension `σ0 / E* = λ sqrt(π Δw / (4 E* a))`, from `λ = 2 σ0 sqrt(a / (π E* Δw))`.
    pub fn tension(&self) -> f64 {
        self.tabor * (std::f64::consts::PI * WORK / 4.0).sqrt()
    }

    /// Range `δc / a = Δw / σ0`: the gap beyond which the surfaces no longer attract.
    pub fn range(&self) -> f64 {
        WORK / self.tension()
    }

    /// Length of the cohesive zone at a crack tip in the JKR limit, `ℓ = π E* Δw / (4 σ0²)`,
    /// in units of `a`: `1/λ²`.
    pub fn zone_length(&self) -> f64 {
        1.0 / (self.tabor * self.tabor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tabor_parameter_round_trips() {
        let law = DugdaleLaw::new(2.5).unwrap();
        let lambda = 2.0 * law.tension() * (1.0 / (std::f64::consts::PI * WORK)).sqrt();
        assert!((lambda - 2.5).abs() < 1e-14);
        assert!((law.range() * law.tension() - WORK).abs() < 1e-16);
    }

    #[test]
    fn a_tabor_parameter_that_is_not_positive_is_refused() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let message = DugdaleLaw::new(bad).unwrap_err().to_string();
            assert!(message.contains("tabor"), "{message}");
        }
    }
}
