//! Surface deflection of a uniform pressure on a disk or an annulus: the cohesive zones' load,
//! in closed form.

use std::f64::consts::PI;

use crate::numerics::elliptic::{complete_e, complete_k};

/// Deflection `w(r)` (positive into the solid, `E* = 1`) of a unit pressure on the disk
/// `s <= c` (Johnson, *Contact Mechanics*, 1985, §3.4): `w = (4/π) c E(r²/c²)` for `r <= c`,
/// `w = (4/π) r [E(c²/r²) - (1 - c²/r²) K(c²/r²)]` beyond (parameters `m = k²`).
pub fn disk_deflection(c: f64, r: f64) -> f64 {
    if c <= 0.0 {
        return 0.0;
    }
    if r <= c {
        let k = r / c;
        let m1 = (c - r) * (c + r) / (c * c);
        4.0 / PI * c * complete_e(k * k, m1)
    } else {
        let k = c / r;
        let m1 = (r - c) * (r + c) / (r * r);
        let elliptic_k = if m1 > 0.0 { complete_k(k * k) } else { 0.0 };
        4.0 / PI * r * (complete_e(k * k, m1) - m1 * elliptic_k)
    }
}

/// Deflection of a unit pressure on the annulus `inner <= s <= outer` (`inner = 0`: a disk).
pub fn annulus_deflection(inner: f64, outer: f64, r: f64) -> f64 {
    disk_deflection(outer, r) - disk_deflection(inner, r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::tanh_sinh::TanhSinhRule;

    /// `(4/π) ∫_lo^hi s K(4rs/(r+s)²)/(r+s) ds` by tanh-sinh on panels split at `r` (the ring
    /// kernel integrated directly: independent of the closed form).
    fn by_quadrature(lo: f64, hi: f64, r: f64) -> f64 {
        let rule = TanhSinhRule::new(1.0 / 64.0);
        let mut cuts = vec![lo];
        if r > lo && r < hi {
            cuts.push(r);
        }
        cuts.push(hi);
        let mut total = 0.0;
        for pair in cuts.windows(2) {
            for node in rule.panel(pair[0], pair[1]) {
                let s = node.position;
                let distance = if pair[0] == r {
                    node.from_lo
                } else if pair[1] == r {
                    node.from_hi
                } else {
                    (s - r).abs()
                };
                let kp = distance / (s + r);
                total +=
                    node.weight * s * crate::numerics::elliptic::complete_k_from_complementary(kp)
                        / (r + s);
            }
        }
        4.0 / PI * total
    }

    #[test]
    fn the_closed_form_matches_the_ring_kernel_integrated() {
        for &(lo, hi) in &[(0.0, 1.0), (0.3, 0.8), (0.95, 1.0)] {
            for &r in &[0.0, 0.2, 0.5, 0.9, 0.97, 1.0, 1.3, 3.0] {
                let exact = annulus_deflection(lo, hi, r);
                let numeric = by_quadrature(lo, hi, r);
                assert!(
                    (exact - numeric).abs() < 1e-10,
                    "[{lo}, {hi}] at r = {r}: {exact} vs {numeric}"
                );
            }
        }
        // Johnson's centre and rim values: 2c and 4c/π.
        assert!((disk_deflection(0.5, 0.0) - 1.0).abs() < 1e-15);
        assert!((disk_deflection(0.5, 0.5) - 2.0 / PI).abs() < 1e-15);
    }
}
