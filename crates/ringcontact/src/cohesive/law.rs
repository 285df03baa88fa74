//! The adhesion law on the contact line.

use serde::Serialize;

/// Exponential adhesion (the law of Tamaas's `ExponentialAdhesionFunctional`): the adhesive
/// energy per unit area at separation `s >= 0` is `φ(s) = -Δw e^{-s/ρ}`, the tension
/// `σ(s) = φ'(s) = (Δw/ρ) e^{-s/ρ}` (peak `σ0 = Δw/ρ` in contact), the work of adhesion
/// `∫σ ds = Δw`. Non-penetration `s >= 0` is a separate constraint.
#[derive(Clone, Copy, Debug, Serialize, serde::Deserialize)]
pub struct ExponentialLaw {
    /// Work of adhesion `Δw` (units `E* a`).
    pub work: f64,
    /// Range `ρ` (units `a`).
    pub range: f64,
}

impl ExponentialLaw {
    /// Energy per unit area `φ(s) = -Δw e^{-s/ρ}`.
    pub fn energy(&self, s: f64) -> f64 {
        -self.work * (-s / self.range).exp()
    }

    /// `φ'(s) = (Δw/ρ) e^{-s/ρ}`: the tension pulling the surfaces together.
    pub fn tension(&self, s: f64) -> f64 {
        self.work / self.range * (-s / self.range).exp()
    }

    /// `φ''(s) = -(Δw/ρ²) e^{-s/ρ}`.
    pub(crate) fn curvature(&self, s: f64) -> f64 {
        -self.work / (self.range * self.range) * (-s / self.range).exp()
    }

    /// Peak tension `σ0 = Δw/ρ`.
    fn peak(&self) -> f64 {
        self.work / self.range
    }

    /// Length of the cohesive zone at a crack tip, `ℓ = π E* Δw / (4 σ0²)` (Dugdale's zone for the
    /// energy release rate `Δw`, `K² = 2 E* Δw`), with `E* = 1`.
    pub(crate) fn zone_length(&self) -> f64 {
        std::f64::consts::PI * self.work / (4.0 * self.peak().powi(2))
    }

    /// Tabor-like parameter `λ = sqrt(a/ℓ)` for the rim radius `a = 1`: large is the JKR limit.
    pub fn tabor(&self) -> f64 {
        (1.0 / self.zone_length()).sqrt()
    }
}
