//! Golden-section search for the maximum of a unimodal function on an interval.

/// The abscissa in `[lo, hi]` where `f` (unimodal there) is largest, to `width` in `x`: the
/// interval shrinks by the golden ratio `(√5 - 1)/2` per evaluation.
pub fn golden_section_max(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64, width: f64) -> f64 {
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    while hi - lo > width {
        let (x1, x2) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
        if f(x1) < f(x2) {
            lo = x1;
        } else {
            hi = x2;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    #[test]
    fn finds_the_top_of_a_parabola() {
        let x = super::golden_section_max(|x| -(x - 0.3) * (x - 0.3), 0.0, 1.0, 1e-10);
        assert!((x - 0.3).abs() < 1e-9);
    }
}
