//! Complete elliptic integrals of the first kind, `K(m) = ∫_0^{π/2} dθ / sqrt(1 - m sin²θ)`,
//! and of the second kind, `E(m) = ∫_0^{π/2} sqrt(1 - m sin²θ) dθ`.
//!
//! Computed by the arithmetic-geometric mean, `K(m) = π / (2 AGM(1, k'))` with the complementary
//! modulus `k' = sqrt(1 - m)` passed in directly. Near the logarithmic singularity `m -> 1` the
//! caller forms `k'` without cancellation (for the ring kernel `k' = |r - s| / (r + s)`), so the
//! result keeps full relative precision for every `k'` in `(0, 1]`.

use std::f64::consts::PI;

/// `K` as a function of the complementary modulus `k' = sqrt(1 - m)`, `0 < k' <= 1`.
///
/// Relative accuracy is a few ulps: the AGM converges quadratically and is stopped once the two
/// means agree to `4 ε`. `k' = 0` (the singular point) returns `+inf`.
pub(crate) fn complete_k_from_complementary(k_prime: f64) -> f64 {
    debug_assert!((0.0..=1.0).contains(&k_prime));
    if k_prime == 0.0 {
        return f64::INFINITY;
    }
    let (mut arith, mut geom) = (1.0_f64, k_prime);
    // Quadratic convergence: even k' = 1e-300 needs fewer than 15 steps.
    for _ in 0..40 {
        if (arith - geom).abs() <= 4.0 * f64::EPSILON * arith {
            break;
        }
        let next = 0.5 * (arith + geom);
        geom = (arith * geom).sqrt();
        arith = next;
    }
    PI / (arith + geom)
}

/// `K(m)` for a parameter `0 <= m < 1` (convenience wrapper; loses precision as `m -> 1`).
pub fn complete_k(m: f64) -> f64 {
    complete_k_from_complementary((1.0 - m).sqrt())
}

/// `E(m)` given both `m = k²` and `m1 = 1 - m` (each formed by the caller without
/// cancellation), `0 <= m, m1 <= 1`: Carlson's `E = R_F(0, m1, 1) - (m/3) R_D(0, m1, 1)`
/// (DLMF 19.25.1), relative accuracy about 1e-15 for every `m` including `m -> 1` (`E(1) = 1`),
/// where the AGM's `K (1 - Σ 2^{n-1} c_n²)` would cancel.
pub fn complete_e(m: f64, m1: f64) -> f64 {
    debug_assert!((0.0..=1.0).contains(&m) && (0.0..=1.0).contains(&m1));
    if m1 == 0.0 {
        return 1.0;
    }
    carlson_rf(0.0, m1, 1.0) - m / 3.0 * carlson_rd(0.0, m1, 1.0)
}

/// Largest relative spread of the duplication's arguments before the series ends it: the
/// neglected terms are of order `SPREAD⁶` (below 1e-20).
const CARLSON_SPREAD: f64 = 1e-4;

/// Carlson's `R_F(x, y, z) = ½ ∫_0^∞ dt / sqrt((t + x)(t + y)(t + z))` by duplication
/// (Carlson 1995, *Numer. Algorithms* 10, 13-26), at most one argument zero. Each step cuts
/// the spread fourfold: 600 steps reach the series from any spread a double can hold.
fn carlson_rf(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    for _ in 0..600 {
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        let mean = (x + y + z) / 3.0;
        let (dx, dy, dz) = ((mean - x) / mean, (mean - y) / mean, (mean - z) / mean);
        if dx.abs().max(dy.abs()).max(dz.abs()) < CARLSON_SPREAD {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 + (e2 / 24.0 - 0.1 - 3.0 / 44.0 * e3) * e2 + e3 / 14.0) / mean.sqrt();
        }
    }
    f64::INFINITY
}

/// Carlson's `R_D(x, y, z) = (3/2) ∫_0^∞ dt / ((t + z) sqrt((t + x)(t + y)(t + z)))` by
/// duplication (Carlson 1995), `x + y > 0`, `z > 0`.
fn carlson_rd(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    let (mut sum, mut factor) = (0.0, 1.0);
    for _ in 0..600 {
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        sum += factor / (sz * (z + lambda));
        factor *= 0.25;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        let mean = 0.2 * (x + y + 3.0 * z);
        let (dx, dy, dz) = ((mean - x) / mean, (mean - y) / mean, (mean - z) / mean);
        if dx.abs().max(dy.abs()).max(dz.abs()) < CARLSON_SPREAD {
            let ea = dx * dy;
            let eb = dz * dz;
            let ec = ea - eb;
            let ed = ea - 6.0 * eb;
            let ee = ed + ec + ec;
            let c3 = 9.0 / 22.0;
            let c4 = 3.0 / 26.0;
            let series = 1.0
                + ed * (-3.0 / 14.0 + 0.25 * c3 * ed - 1.5 * c4 * dz * ee)
                + dz * (ee / 6.0 + dz * (-c3 * ec + dz * c4 * ea));
            return 3.0 * sum + factor * series / (mean * mean.sqrt());
        }
    }
    f64::INFINITY
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_known_values() {
        // K(0) = π/2 exactly.
        assert!((complete_k(0.0) - PI / 2.0).abs() < 1e-15);
        // K(1/2) = Γ(1/4)² / (4 sqrt(π)) (lemniscatic case), Γ(1/4) = 3.625609908221908...
        let gamma_quarter = 3.625_609_908_221_908_f64;
        let exact = gamma_quarter * gamma_quarter / (4.0 * PI.sqrt());
        assert!((complete_k(0.5) - exact).abs() < 1e-14 * exact);
    }

    #[test]
    fn log_singularity_has_the_asymptotic_form() {
        // K ~ ln(4/k') + (k'^2/4)(ln(4/k') - 1) as k' -> 0 (DLMF 19.12.1, two terms).
        for &kp in &[1e-4_f64, 1e-8, 1e-12, 1e-100] {
            let l = (4.0 / kp).ln();
            let asym = l + 0.25 * kp * kp * (l - 1.0);
            let k = complete_k_from_complementary(kp);
            assert!((k - asym).abs() < 1e-13 * asym, "k'={kp}: {k} vs {asym}");
        }
    }
    #[test]
    fn second_kind_matches_known_values_and_legendre() {
        // E(0) = π/2, E(1) = 1 exactly; E(1/2) = 1.3506438810476755 (DLMF 19.20, tabulated).
        assert!((complete_e(0.0, 1.0) - PI / 2.0).abs() < 1e-15);
        assert!((complete_e(1.0, 0.0) - 1.0).abs() < 1e-15);
        assert!((complete_e(0.5, 0.5) - 1.350_643_881_047_675_5).abs() < 2e-15);
        // Legendre's relation E K' + E' K - K K' = π/2 (DLMF 19.7.1), with K from the AGM.
        for &m in &[1e-6, 0.1, 0.3, 0.7, 0.999_999] {
            let m1 = 1.0 - m;
            let (k, k1) = (complete_k(m), complete_k(m1));
            let (e, e1) = (complete_e(m, m1), complete_e(m1, m));
            let legendre = e * k1 + e1 * k - k * k1;
            assert!((legendre - PI / 2.0).abs() < 1e-13, "m = {m}: {legendre}");
        }
    }
}
