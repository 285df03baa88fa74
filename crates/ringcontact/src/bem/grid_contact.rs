//! The punch problems on the square-grid BEM ([`crate::bem::grid`]), dimensionless (`a = 1`,
//! `E* = 1`, `d = 1` or `h = 1`).
//!
//! The grid spans the punch's bounding square `[-a, a]²` with `N x N` cells; a cell belongs to the
//! punch when its centre lies in `b <= r <= a` (fixed annulus) or `r <= a` (the others), which is
//! the staircase approximation of the edges that limits the method's convergence. The concave
//! punches' contact ratio is read off the contact area:
//! `eps = sqrt(1 - (cells in contact)/(cells under the punch))`.

use std::time::Instant;

use crate::bem::grid::{solve_contact, GridLoad, GridOperator};
use crate::error::{Error, Result};
use crate::punch::PunchKind;

/// Fewest cells across the contact ring for a result (fewer: an error, not a number).
const MIN_CELLS_ACROSS: f64 = 2.0;

/// Largest grid accepted: memory about 100 N² bytes (0.4 GB at 2048), time growing like
/// `N² log N` per iteration times an iteration count that grows with `N` (seconds at 512 on
/// 2 cores; 2048 takes some minutes and reports progress). 4096 would take hours.
pub const MAX_GRID: usize = 2048;

/// Smallest grid accepted (cells per side).
pub const MIN_GRID: usize = 8;

/// A grid solve of a punch state.
#[derive(Clone, Debug)]
pub struct GridState {
    pub grid: usize,
    pub eps: f64,
    /// Outer contact edge `c/a` (1, the rim, for every punch but a free band).
    pub outer_edge: f64,
    /// Half-size `L/a` of the square `[-L, L]²` the grid covers (1 but for a free band).
    pub square_half_size: f64,
    pub gamma: Option<f64>,
    pub gamma1: Option<f64>,
    pub gamma2: Option<f64>,
    pub force: f64,
    pub depth: f64,
    pub iterations: usize,
    pub residual: f64,
    pub contact_cells: usize,
    pub wall_s: f64,
    /// The cells' pressures, row by row over the square `[-L, L]²` (`n²` values, units of the
    /// solve: `E* d / a` for a flat-faced punch, `E* h / a` for a concave one).
    pub pressure: Vec<f64>,
}

impl GridState {
    /// The cells' pressures averaged over `bins` rings of equal width inside `r < a`, as
    /// `(r/a, p)` at the rings' mid-radii (rings holding no cell centre left out).
    pub fn ring_averaged_pressure(&self, bins: usize) -> Vec<(f64, f64)> {
        let n = self.grid;
        let mut sum = vec![0.0; bins];
        let mut count = vec![0usize; bins];
        for i in 0..n {
            for j in 0..n {
                let r = self.square_half_size * cell_centre(n, i).hypot(cell_centre(n, j));
                if r < 1.0 {
                    let b = ((r * bins as f64) as usize).min(bins - 1);
                    sum[b] += self.pressure[i * n + j];
                    count[b] += 1;
                }
            }
        }
        (0..bins)
            .filter(|&b| count[b] > 0)
            .map(|b| ((b as f64 + 0.5) / bins as f64, sum[b] / count[b] as f64))
            .collect()
    }
}

/// The discretised punch: which cells it covers and its gap there.
pub struct GridPunch {
    pub allowed: Vec<bool>,
    pub profile: Vec<f64>,
    pub disk_cells: usize,
}

/// Cell-centre coordinates of an `n x n` grid on `[-1, 1]²`.
pub fn cell_centre(n: usize, index: usize) -> f64 {
    let cell = 2.0 / n as f64;
    (index as f64 + 0.5) * cell - 1.0
}

/// Discretise an axisymmetric punch on an `n x n` grid.
pub fn discretise(kind: PunchKind, eps: f64, n: usize) -> GridPunch {
    let mut allowed = vec![false; n * n];
    let mut profile = vec![0.0; n * n];
    let mut disk_cells = 0;
    for i in 0..n {
        for j in 0..n {
            let r = cell_centre(n, i).hypot(cell_centre(n, j));
            if r <= 1.0 {
                disk_cells += 1;
                let inside = !kind.has_fixed_hole() || r >= eps;
                allowed[i * n + j] = inside;
                profile[i * n + j] = kind.gap_shape(r);
            }
        }
    }
    GridPunch {
        allowed,
        profile,
        disk_cells,
    }
}

/// Cells between the innermost cell in contact and the ring's inner edge read off the contact
/// area (`eps`) beyond which the contact holds cells inside the ring's hole: on a single ring the
/// innermost contact cell lies within 0.2 cells of `eps`, past a floor touch many cells inside it.
const HOLE_CONTACT_CELLS: f64 = 3.0;

/// A concave punch's contact on the grid must be one ring `[b, a]`, the contact the harness
/// compares (its `eps` is read off the contact area): cells in contact more than
/// [`HOLE_CONTACT_CELLS`] inside `eps` mean the punch touches the floor of its hole (a gap
/// `1 - ρ^n` with `n > 2` before its ring closes), a disk or a ring and the annulus.
fn check_one_ring(
    kind: PunchKind,
    n: usize,
    pressure: &[f64],
    eps: f64,
    gamma2: f64,
) -> Result<()> {
    let cell = 2.0 / n as f64;
    let innermost = (0..n * n)
        .filter(|&k| pressure[k] > 0.0)
        .map(|k| cell_centre(n, k / n).hypot(cell_centre(n, k % n)))
        .fold(f64::INFINITY, f64::min);
    if innermost < eps - HOLE_CONTACT_CELLS * cell {
        return Err(Error::OutOfRange {
            method: crate::bem::grid::METHOD.into(),
            reason: format!(
                "the {kind}'s contact on the {n} x {n} grid is not one ring: cells from r/a = \
                 {innermost:.4} are in contact inside the ring's hole (b/a = {eps:.4} by the \
                 contact area), so the punch touches the floor of its hole and the contact is a \
                 disk or a ring and the annulus, whose edges the harness does not compare (its \
                 force on this grid: F/(2 E* h a) = {gamma2:.6})"
            ),
        });
    }
    Ok(())
}

/// The grid sizes accepted, `MIN_GRID..=MAX_GRID` cells per side.
fn check_grid(n: usize) -> Result<()> {
    if !(MIN_GRID..=MAX_GRID).contains(&n) {
        Err(Error::OutOfRange {
            method: crate::bem::grid::METHOD.into(),
            reason: format!(
                "grid {n} outside {MIN_GRID}..={MAX_GRID} cells per side (a {n} x {n} grid needs about \
                 {:.1} GB and far longer than minutes on this kind of machine)",
                100.0 * (n as f64).powi(2) / 1e9
            ),
        })
    } else {
        Ok(())
    }
}

/// Solve a punch state on an `n x n` grid. `load`: depth `d` (flat: 1; concave: `d/h`) or force
/// `F/(2 E* h a)` for concave punches.
pub fn solve(
    kind: PunchKind,
    eps: f64,
    n: usize,
    load: GridLoad,
    tolerance: f64,
) -> Result<GridState> {
    if kind.is_free_band() {
        return solve_band(&kind, n, load, tolerance);
    }
    solve_capped(kind, eps, n, load, tolerance, default_iteration_cap(n))
}

/// Polonsky-Keer's default iteration cap on an `n x n` grid, `50 + 20 n`.
pub fn default_iteration_cap(n: usize) -> usize {
    50 + 20 * n
}

/// [`solve`] for a punch with a rim, stopping with an error after `max_iterations` iterations of
/// Polonsky-Keer.
pub fn solve_capped(
    kind: PunchKind,
    eps: f64,
    n: usize,
    load: GridLoad,
    tolerance: f64,
    max_iterations: usize,
) -> Result<GridState> {
    if kind.is_free_band() {
        return Err(Error::Unsupported {
            method: crate::bem::grid::METHOD.into(),
            reason: format!(
                "an iteration cap applies to a punch with a rim; the {} is a free band",
                kind.name()
            ),
        });
    }
    check_grid(n)?;
    // A ring narrower than two cells is not resolved: the staircase would carry most of the error
    // and the number would look plausible. Refuse it instead.
    let cell = 2.0 / n as f64;
    if kind.has_fixed_hole() && (1.0 - eps) < MIN_CELLS_ACROSS * cell {
        return Err(Error::OutOfRange {
            method: crate::bem::grid::METHOD.into(),
            reason: format!(
                "the ring b/a = {} is {:.2} cells wide on a {n} x {n} grid; at least {MIN_CELLS_ACROSS} cells are needed \
                 (use --grid {} or more, or the ring BEM)",
                crate::error::show(eps),
                (1.0 - eps) / cell,
                (2.0 * MIN_CELLS_ACROSS / (1.0 - eps)).ceil() as usize
            ),
        });
    }
    let start = Instant::now();
    let op = GridOperator::new(n, cell);
    let punch = discretise(kind.clone(), eps, n);
    let load = match load {
        GridLoad::Force(f) => GridLoad::Force(2.0 * f),
        other => other,
    };
    let c = solve_contact(
        &op,
        &punch.allowed,
        &punch.profile,
        load,
        tolerance,
        max_iterations,
    )?;
    let wall_s = start.elapsed().as_secs_f64();
    let concave = kind.is_concave();
    let eps_out = if concave {
        (1.0 - c.contact_cells as f64 / punch.disk_cells as f64)
            .max(0.0)
            .sqrt()
    } else {
        eps
    };
    if concave {
        check_one_ring(kind, n, &c.pressure, eps_out, 0.5 * c.force)?;
    }
    if concave && (1.0 - eps_out) < MIN_CELLS_ACROSS * cell {
        return Err(Error::OutOfRange {
            method: crate::bem::grid::METHOD.into(),
            reason: format!(
                "the contact ring (b/a = {eps_out:.4}) is {:.2} cells wide on a {n} x {n} grid; at least \
                 {MIN_CELLS_ACROSS} cells are needed (refine the grid or use the ring BEM)",
                (1.0 - eps_out) / cell
            ),
        });
    }
    Ok(GridState {
        grid: n,
        eps: eps_out,
        outer_edge: 1.0,
        square_half_size: 1.0,
        gamma: (!concave).then(|| c.force / (2.0 * c.depth)),
        gamma1: concave.then_some(c.depth),
        gamma2: concave.then_some(0.5 * c.force),
        force: c.force,
        depth: c.depth,
        iterations: c.iterations,
        residual: c.residual,
        contact_cells: c.contact_cells,
        wall_s,
        pressure: c.pressure,
    })
}

/// Half-size of the first (coarse) square a free band is located on, in units of `a`: it holds
/// a contact up to `c = 2.9 a`.
const BAND_FIRST_HALF_SIZE: f64 = 3.0;

/// A punch whose contact is a free band (both edges free, its gap defined on both sides of the
/// ring radius `a`, `h = 1`) on an `n x n` grid over `[-L, L]²`: every cell of the inscribed disk
/// may touch. Its contact band is found by the complementarity iteration, both
/// edges at once; the edges are read off the contact cells as the smallest and largest centre
/// radius in contact (staircase, `O(cell)`). The square is sized in two passes: a grid of
/// `n/4` cells on `[-3a, 3a]²` finds the band, and the final grid spans the band's outer edge
/// plus a quarter of its width (at least four coarse cells); a contact reaching within two cells
/// of the square's edge is refused.
pub fn solve_band(kind: &PunchKind, n: usize, load: GridLoad, tolerance: f64) -> Result<GridState> {
    check_grid(n)?;
    let start = Instant::now();
    let half_size = band_square(kind, n / 4, load, tolerance)?;
    let fine = solve_band_on_square(kind, n, half_size, load, tolerance)?;
    Ok(GridState {
        wall_s: start.elapsed().as_secs_f64(),
        ..fine
    })
}

/// The half-size `L/a` of a free band's square for a load: a solve on `max(coarse, 32)²` cells
/// of the square `[-1.6 a, 1.6 a]²` locates the band `[b, c]`; the square reaches a quarter of
/// its width (at least four of those cells) beyond `c`. A study refining the grid on a fixed
/// square takes it from the same `coarse` at every level.
pub fn band_square(kind: &PunchKind, coarse: usize, load: GridLoad, tolerance: f64) -> Result<f64> {
    let coarse_n = coarse.max(32);
    let located = band_on_square(kind, coarse_n, BAND_FIRST_HALF_SIZE, load, tolerance)?;
    let coarse_cell = 2.0 * BAND_FIRST_HALF_SIZE / coarse_n as f64;
    Ok(located.outer + (0.25 * (located.outer - located.inner)).max(4.0 * coarse_cell))
}

/// A free band on one given square `[-L, L]²` (`half_size = L/a > 1`), `n x n` cells: what
/// [`solve_band`] does on its final square, for a grid chosen by the caller (a peer code's).
/// A band narrower than [`MIN_CELLS_ACROSS`] cells, or a contact reaching within two cells of
/// the square's edge, is refused.
pub fn solve_band_on_square(
    kind: &PunchKind,
    n: usize,
    half_size: f64,
    load: GridLoad,
    tolerance: f64,
) -> Result<GridState> {
    check_grid(n)?;
    if !(half_size.is_finite() && half_size > 1.0 && half_size <= BAND_MAX_HALF_SIZE) {
        return Err(Error::OutOfRange {
            method: crate::bem::grid::METHOD.into(),
            reason: format!(
                "the {}'s grid half-size L = {} a must lie in (1, {BAND_MAX_HALF_SIZE}] a: \
                 the square [-L, L]² must hold the ring r = a and the band around it",
                kind.name(),
                crate::error::show(half_size)
            ),
        });
    }
    let start = Instant::now();
    let fine = band_on_square(kind, n, half_size, load, tolerance)?;
    let cell = 2.0 * half_size / n as f64;
    if (fine.outer - fine.inner) < MIN_CELLS_ACROSS * cell {
        return Err(Error::OutOfRange {
            method: crate::bem::grid::METHOD.into(),
            reason: format!(
                "the {}'s contact band [{:.4}, {:.4}] a is {:.2} cells wide on a {n} x {n} grid \
                 over [-{half_size:.3}, {half_size:.3}]² a; at least {MIN_CELLS_ACROSS} cells are \
                 needed (refine the grid or use the ring BEM)",
                kind.name(),
                fine.inner,
                fine.outer,
                (fine.outer - fine.inner) / cell
            ),
        });
    }
    Ok(GridState {
        wall_s: start.elapsed().as_secs_f64(),
        ..fine.state
    })
}

/// Largest square half-size `L/a` accepted for a free band (a band up to about `c = 8 a`).
pub const BAND_MAX_HALF_SIZE: f64 = 10.0;

/// A free band's solve on one square: the state and the band read off the contact cells.
struct BandOnSquare {
    state: GridState,
    inner: f64,
    outer: f64,
}

fn band_on_square(
    kind: &PunchKind,
    n: usize,
    half_size: f64,
    load: GridLoad,
    tolerance: f64,
) -> Result<BandOnSquare> {
    let cell = 2.0 * half_size / n as f64;
    let op = GridOperator::new(n, cell);
    let mut allowed = vec![false; n * n];
    let mut profile = vec![0.0; n * n];
    let radius = |i: usize, j: usize| half_size * cell_centre(n, i).hypot(cell_centre(n, j));
    for i in 0..n {
        for j in 0..n {
            let r = radius(i, j);
            if r <= half_size {
                allowed[i * n + j] = true;
                profile[i * n + j] = kind.gap_shape(r);
            }
        }
    }
    let load = match load {
        GridLoad::Force(f) => GridLoad::Force(2.0 * f),
        other => other,
    };
    let c = solve_contact(
        &op,
        &allowed,
        &profile,
        load,
        tolerance,
        default_iteration_cap(n),
    )?;
    let (mut inner, mut outer) = (f64::INFINITY, 0.0_f64);
    for i in 0..n {
        for j in 0..n {
            if c.pressure[i * n + j] > 0.0 {
                let r = radius(i, j);
                inner = inner.min(r);
                outer = outer.max(r);
            }
        }
    }
    if outer > half_size - 2.0 * cell {
        return Err(Error::OutOfRange {
            method: crate::bem::grid::METHOD.into(),
            reason: format!(
                "the {}'s contact reaches r = {outer:.3} a, within two cells of the grid's \
                 square [-{half_size:.3}, {half_size:.3}]² a: the square must extend past the \
                 band (a larger --grid-extent, a smaller load, or the ring BEM)",
                kind.name()
            ),
        });
    }
    Ok(BandOnSquare {
        state: GridState {
            grid: n,
            eps: inner,
            outer_edge: outer,
            square_half_size: half_size,
            gamma: None,
            gamma1: Some(c.depth),
            gamma2: Some(0.5 * c.force),
            force: c.force,
            depth: c.depth,
            iterations: c.iterations,
            residual: c.residual,
            contact_cells: c.contact_cells,
            wall_s: 0.0,
            pressure: c.pressure,
        },
        inner,
        outer,
    })
}
