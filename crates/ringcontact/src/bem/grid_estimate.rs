//! The grid BEM's error estimate on the grid a user asks for.
//!
//! The method is first order in the cell size `h` (piecewise-constant pressure, staircase edges),
//! but its error coefficient wanders from grid to grid: the cells whose centres fall inside a
//! circle follow no smooth law in `h` (the flat-faced punch's relative error times `N` wanders from
//! 0.09 to 0.24 between 32² and 1024², with 128² and 256² almost equal). A Richardson estimate from
//! two levels can therefore see no change where the error is large, so the estimate takes the
//! steepest of the three level pairs: the same problem is solved on `N/2` and `N/4` cells over the
//! same square (about a fifth more work), and for each output `f`
//!
//! `bar = 3 h1 max_{i<j} |f_i - f_j| / |h_i - h_j|`,
//!
//! and, where the three converge monotonically but slower than first order, the GCI with its
//! observed order ([`three_level_bar`]); relative for the `γ`s, absolute (units of `a`) for the
//! free edges, which the staircase cannot place to better than about a cell (the bar is never
//! below one cell `h1` there). Over 192 states of every punch on 64², 128² and 256² (the
//! narrowest bands, the deepest loads, holes a few cells wide near full contact) the actual
//! error stays below 0.78 of the bar; the hardest is the parabolic gap's small hole near full
//! contact, whose edge follows the depth's error amplified by the closing hole
//! (`tests/suite/grid_estimate.rs` keeps a sample with it).

use crate::bem::grid_contact::{GridState, MIN_GRID};
use crate::error::{Error, Result};
use crate::numerics::richardson::observed_order;

/// The coarser levels' cells per side are the grid's divided by these.
pub const COARSENING: [usize; 2] = [2, 4];

/// The free edges' bar is never below this many cells.
pub const EDGE_FLOOR_CELLS: f64 = 1.0;

/// Safety factor on the steepest pair's first-order extrapolation.
pub const SAFETY: f64 = 3.0;

/// The bar of the finest of three values `f` on cells `h` (finest first) of a first-order method
/// whose error coefficient wanders and whose free edges may converge slower: the larger of
/// - `SAFETY h1 max_{i<j} |f_i - f_j| / |h_i - h_j|`, the steepest level pair's first-order
///   extrapolation (robust where two levels agree by chance), and
/// - where the three converge monotonically, the GCI with the safety factor 3 and the order
///   `min(p, 1)` of the observed order `p` (Roache): `3 |f1 - f2| / (r21^min(p,1) - 1)`, which
///   follows levels that converge slower than first order; `p` is taken no lower than
///   [`LOWEST_ORDER`].
pub fn three_level_bar(f: [f64; 3], h: [f64; 3]) -> f64 {
    let mut steepest = 0.0f64;
    for i in 0..3 {
        for j in i + 1..3 {
            steepest = steepest.max((f[i] - f[j]).abs() / (h[i] - h[j]).abs());
        }
    }
    let pairs = SAFETY * h[0] * steepest;
    let (r21, r32) = (h[1] / h[0], h[2] / h[1]);
    let monotone = (f[1] - f[0]) * (f[2] - f[1]) > 0.0;
    let gci = match observed_order(f[0], f[1], f[2], r21, r32) {
        Some(p) if monotone => {
            SAFETY * (f[1] - f[0]).abs() / (r21.powf(p.clamp(LOWEST_ORDER, 1.0)) - 1.0)
        }
        _ => 0.0,
    };
    pairs.max(gci)
}

/// The lowest order the GCI term assumes: three levels of the staircase can show almost equal
/// changes by chance (an observed order near 0, a bar of 40 times the last change where the
/// actual error was 1/20 of it); at 1/2 the bar is at most 7 times the last change.
pub const LOWEST_ORDER: f64 = 0.5;

/// The contact's inner edge `b/a` of a grid state.
pub fn inner_edge(s: &GridState) -> f64 {
    s.eps
}

/// The contact's outer edge `c/a` of a grid state.
pub fn outer_edge(s: &GridState) -> f64 {
    s.outer_edge
}

/// The estimate of `fine`, a solve on `fine.grid` cells per side over the square
/// `[-L, L]²` (`L = fine.square_half_size`), from `coarser(m)`, the same problem on `m` cells
/// over the same square: the largest of the `γ`s' relative bars and the absolute bars of the
/// `free_edges` (the edges the solution finds: [`inner_edge`] of a concave punch, both of a
/// free band; none of a flat-faced punch), see the module docs.
pub fn estimate(
    fine: &GridState,
    free_edges: &[fn(&GridState) -> f64],
    coarser: impl Fn(usize) -> Result<GridState>,
) -> Result<f64> {
    let n = fine.grid;
    if n / COARSENING[1] < MIN_GRID {
        return Err(Error::OutOfRange {
            method: crate::bem::grid::METHOD.into(),
            reason: format!(
                "{n} cells per side are too few for the estimate's coarser grids ({} and {} \
                 cells; at least {} needed for one)",
                n / COARSENING[0],
                n / COARSENING[1],
                MIN_GRID * COARSENING[1]
            ),
        });
    }
    let half = coarser(n / COARSENING[0])?;
    let quarter = coarser(n / COARSENING[1])?;
    let levels = [fine, &half, &quarter];
    let h = levels.map(|s| 2.0 * fine.square_half_size / s.grid as f64);
    let mut bar = 0.0f64;
    let outputs: [fn(&GridState) -> Option<f64>; 3] = [|s| s.gamma, |s| s.gamma1, |s| s.gamma2];
    for output in outputs {
        if let (Some(f1), Some(f2), Some(f3)) = (output(fine), output(&half), output(&quarter)) {
            bar = bar.max(three_level_bar([f1, f2, f3], h) / f1.abs());
        }
    }
    for edge in free_edges {
        bar = bar.max(three_level_bar(levels.map(edge), h).max(EDGE_FLOOR_CELLS * h[0]));
    }
    Ok(bar)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A first-order sequence `f = 1 + c h` gives three times its error (both terms agree, to
    /// the rounding of the differences).
    #[test]
    fn a_clean_first_order_sequence_gets_three_times_its_error() {
        let h = [0.01, 0.02, 0.04];
        let f = h.map(|h| 1.0 + 0.3 * h);
        let bar = three_level_bar(f, h);
        assert!((bar / (3.0 * 0.3 * 0.01) - 1.0).abs() < 1e-9, "{bar}");
    }

    /// A slower monotone sequence `f = 1 + c h^0.5` gets the GCI at its observed order 0.5,
    /// which bounds its error where the first-order pairs alone would hardly.
    #[test]
    fn a_slower_sequence_gets_the_gci_at_its_order() {
        let h = [0.01, 0.02, 0.04];
        let f = h.map(|h: f64| 1.0 + 0.3 * h.powf(0.5));
        let error = 0.3 * 0.01f64.powf(0.5);
        let bar = three_level_bar(f, h);
        assert!(bar >= 2.0 * error, "{bar} against {error}");
        let pairs_only = 3.0 * 0.01 * (f[1] - f[0]) / 0.01;
        assert!(
            pairs_only < 1.3 * error,
            "the pairs alone would be {pairs_only}"
        );
    }

    /// Two levels that agree by chance (the flat-faced punch's 128² and 256²: 0.9991035, 0.9990669,
    /// then 64²: 0.9981215; the actual error of 256² is 9.3e-4) still give a bar above it.
    #[test]
    fn levels_that_agree_by_chance_do_not_hide_the_error() {
        let f = [0.9990669113578775, 0.9991034962541707, 0.998121510680774];
        let h = [2.0 / 256.0, 2.0 / 128.0, 2.0 / 64.0];
        assert!(three_level_bar(f, h) >= 9.33e-4);
    }
}
