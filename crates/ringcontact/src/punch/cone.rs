//! The conical concave punch, gap `h (1 - r/a)`: `h (1 - (r/a)^n)` with `n = 1`.

use super::{Contact, Profile, PunchName, Quantity, Reference, ReferenceKind, ReferenceValue};

/// `γ1 = d/h` of this punch.
pub const GAMMA1: Quantity = Quantity::new("cone_gamma1", "gamma1 (cone)", 1);
/// `γ2 = F/(2 E* h a)` of this punch.
pub const GAMMA2: Quantity = Quantity::new("cone_gamma2", "gamma2 (cone)", 2);

/// Conical concave punch: its apex (a kink) keeps a hole open at every depth.
#[derive(Clone, Copy, Debug, Default)]
pub struct Cone;

impl Profile for Cone {
    fn name(&self) -> &str {
        "cone"
    }
    fn builtin(&self) -> Option<PunchName> {
        Some(PunchName::Cone)
    }
    fn contact(&self) -> Contact {
        Contact::RimAndFreeInner
    }
    fn gap(&self, rho: f64) -> f64 {
        1.0 - rho
    }
    fn slope(&self, _rho: f64) -> f64 {
        -1.0
    }
    fn power_law_exponent(&self) -> Option<f64> {
        Some(1.0)
    }
    fn smooth_at_axis(&self) -> bool {
        false
    }
    fn may_meet_hole_floor(&self) -> bool {
        false
    }
    fn hole_lower_bound(&self, depth_over_hole: f64) -> Option<f64> {
        Some(cone_hole_lower_bound(depth_over_hole))
    }
    fn references(&self) -> Vec<Reference> {
        // The open interval the paper plotted: the forms diverge at eps = 0.
        let open = (1e-12, 1.0 - 1e-12);
        vec![
            Reference {
                name: "paper-fit",
                source: "paper eq. (8)-(9)",
                quantity: GAMMA1,
                eps_range: open,
                kind: ReferenceKind::Fit,
                eval: |e| ReferenceValue::unbounded(paper_fit(1, e)),
            },
            Reference {
                name: "paper-fit",
                source: "paper eq. (8)-(9)",
                quantity: GAMMA2,
                eps_range: open,
                kind: ReferenceKind::Fit,
                eval: |e| ReferenceValue::unbounded(paper_fit(2, e)),
            },
        ]
    }
}

/// The paper's fit, eq. (8)-(9): `γ_i ≈ (-ln eps)^n_i (a_i + b_i eps + c_i eps²)`.
pub fn paper_fit(i: usize, eps: f64) -> f64 {
    let (n, a, b, c) = if i == 1 {
        (0.874, 2.09, 0.54, 0.15)
    } else {
        (0.945, 1.85, 0.45, 0.12)
    };
    (-eps.ln()).powf(n) * (a + b * eps + c * eps * eps)
}

/// The conical punch's hole `b/a` at depth `d/h` (`γ1(b/a) = d/h`), ascending in depth: the ring
/// BEM (`verify solve --punch cone --eps B --method ring-bem`, its error estimates 1e-13 to
/// 1e-9). They follow `d/h ≈ (π/2) ln(a/b) + 1` (docs/conventions.md fact 5).
const CONE_HOLE_BY_DEPTH: [(f64, f64); 16] = [
    (1.789611, 0.5),
    (2.761971, 0.3),
    (3.462597, 0.2),
    (4.596961, 0.1),
    (5.699800, 0.05),
    (6.505729, 0.03),
    (7.143858, 0.02),
    (8.233465, 0.01),
    (9.322488, 5e-3),
    (10.124946, 3e-3),
    (10.761867, 2e-3),
    (11.850672, 1e-3),
    (12.939468, 5e-4),
    (13.741872, 3e-4),
    (14.378776, 2e-4),
    (15.467569, 1e-4),
];

/// Share of the interpolated hole that [`cone_hole_lower_bound`] keeps: `ln(a/b)` is nearly
/// linear in `d/h` (slope `2/π`), and interpolating it between the rows of
/// [`CONE_HOLE_BY_DEPTH`] gave 0.991-1.000 of the ring BEM's hole at 15 depths between them
/// (2 to 15 h).
const CONE_HOLE_BOUND_SHARE: f64 = 0.9;

/// The cone's hole deeper than [`CONE_HOLE_BY_DEPTH`] (where the ring BEM stops at `b/a =
/// 1e-4`): docs/conventions.md fact 5, `d/h = (π/2) ln(a/b) + c`, with `c = 1`. The table's `c` rises
/// toward it from below and has settled at 0.9998-1.0002 from `b/a = 1e-2` down, so
/// `b/a = exp(-2 (d/h - 1)/π)` is within 0.02 % of the hole at the table's end.
fn cone_hole_asymptote(depth: f64) -> f64 {
    (-2.0 * (depth - 1.0) / std::f64::consts::PI).exp()
}

/// A lower bound of the conical punch's hole `b/a` at depth `d/h`: `ln(b/a)` interpolated
/// linearly in `d/h` between the rows of [`CONE_HOLE_BY_DEPTH`], times
/// [`CONE_HOLE_BOUND_SHARE`]. Shallower than the first row, that row's hole times the share (the
/// hole shrinks as the punch presses deeper, so it is wider there); deeper than the last, the
/// asymptote ([`cone_hole_asymptote`]) times the share.
fn cone_hole_lower_bound(depth: f64) -> f64 {
    let rows = &CONE_HOLE_BY_DEPTH;
    if depth.is_nan() || depth <= rows[0].0 {
        // Shallower than the first row (or not a number): at least its hole.
        return CONE_HOLE_BOUND_SHARE * rows[0].1;
    }
    rows.windows(2).find(|pair| depth <= pair[1].0).map_or(
        CONE_HOLE_BOUND_SHARE * cone_hole_asymptote(depth),
        |pair| {
            let ((d0, b0), (d1, b1)) = (pair[0], pair[1]);
            let t = (depth - d0) / (d1 - d0);
            CONE_HOLE_BOUND_SHARE * (b0.ln() + t * (b1.ln() - b0.ln())).exp()
        },
    )
}

/// What `verify references` says of this punch.
pub(crate) const SUMMARY: super::profile::Summary = super::profile::Summary {
    description: "Conical concave punch, gap `h (1 - r/a)`",
    flags: "--punch cone",
    gap: "h (1 - r/a)",
    edges: "rim at a, free inner edge",
    closed_forms: "none in partial contact; never closes",
};

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/conventions.md fact 5: `γ1` grows like `(π/2) ln(1/eps)`; with the constant 1 it holds
    /// to 0.03 from `eps = 0.1` down (independent of the ring BEM that made the table). Before
    /// the table the bound is the first row's, beyond it the asymptote's.
    #[test]
    fn the_cone_hole_table_follows_the_asymptote() {
        for &(depth, hole) in &CONE_HOLE_BY_DEPTH {
            let asymptote = std::f64::consts::FRAC_PI_2 * (1.0 / hole).ln() + 1.0;
            if hole <= 0.1 {
                assert!(
                    (depth - asymptote).abs() < 0.03,
                    "{hole}: {depth} against {asymptote}"
                );
            }
        }
        for pair in CONE_HOLE_BY_DEPTH.windows(2) {
            assert!(pair[1].0 > pair[0].0 && pair[1].1 < pair[0].1);
        }
        assert_eq!(cone_hole_lower_bound(1.0), 0.9 * 0.5);
        assert_eq!(cone_hole_lower_bound(f64::NAN), 0.9 * 0.5);
        // Beyond it, the asymptote (c = 1): at the table's end within 0.02 % of the ring BEM's
        // hole, then 0.9 of it, falling by e^{-2/π} per h.
        let last = CONE_HOLE_BY_DEPTH[CONE_HOLE_BY_DEPTH.len() - 1];
        assert!((cone_hole_asymptote(last.0) / last.1 - 1.0).abs() < 2e-4);
        for depth in [16.0, 20.0, 60.0] {
            let bound = cone_hole_lower_bound(depth);
            assert_eq!(bound, 0.9 * cone_hole_asymptote(depth));
            assert!(bound > 0.0 && bound < last.1);
        }
    }
}
