//! Richardson's observed order of convergence from three levels of a discretisation.

/// Observed order of three solutions `f1` (finest), `f2`, `f3` with refinement ratios
/// `r21 = h2/h1`, `r32 = h3/h2` (Celik et al. 2008). `None` when the differences vanish or the
/// iteration does not settle.
pub fn observed_order(f1: f64, f2: f64, f3: f64, r21: f64, r32: f64) -> Option<f64> {
    let (e21, e32) = (f2 - f1, f3 - f2);
    // Differences at rounding level carry no order (the sequence has converged).
    let floor = 1e-13 * f1.abs().max(f64::MIN_POSITIVE);
    if e21.abs() <= floor || e32.abs() <= floor {
        return None;
    }
    let s = (e32 / e21).signum();
    let mut p = ((e32 / e21).abs().ln() / r21.ln()).abs();
    for _ in 0..200 {
        let q = ((r21.powf(p) - s) / (r32.powf(p) - s)).ln();
        let next = ((e32 / e21).abs().ln() + q).abs() / r21.ln();
        if !next.is_finite() {
            return None;
        }
        if (next - p).abs() < 1e-12 {
            return Some(next);
        }
        p = next;
    }
    None
}
