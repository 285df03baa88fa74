//! The paper's 3-D FFT BEM on a square grid (Polonsky-Keer) as a [`Solver`], with its error
//! estimate from the same problem on coarser grids over the same square.

use std::time::Instant;

use super::ladder::{Ladder, LocatedEdges, Rung, StudyCase};
use super::units::base;
use super::Solver;
use crate::bem::grid::GridLoad;
pub use crate::bem::grid_contact::GridState;
use crate::bem::{grid_contact, grid_estimate};
use crate::error::{Error, Result};
use crate::punch::Contact;
use crate::scene::{Load, Scene};
use crate::solution::{GridBemPart, Solution};

/// Default cells per side of the grid BEM.
pub const DEFAULT_GRID: usize = 256;

/// The grid BEM and its own options.
#[derive(Clone, Debug)]
pub struct GridBem {
    /// Cells per side (default [`DEFAULT_GRID`]).
    pub cells: usize,
    /// A free band's square half-size `L` in units of `a` (default: sized from a coarse solve;
    /// a punch with a rim covers its own `[-a, a]²`).
    pub extent: Option<f64>,
    /// Solve the coarser levels of the error estimate too (default); `false` solves the
    /// requested grid alone (the paper's method as the peer codes run it).
    pub with_estimate: bool,
    /// Polonsky-Keer's iteration cap, past which the solve is an error (default
    /// [`grid_contact::default_iteration_cap`], `50 + 20 N`); a punch with a rim only.
    pub max_iterations: Option<usize>,
}

impl GridBem {
    /// The fewest cells per side the grid BEM takes.
    pub const MIN_CELLS: usize = grid_contact::MIN_GRID;
    /// The most cells per side the grid BEM takes.
    pub const MAX_CELLS: usize = grid_contact::MAX_GRID;

    /// The requested grid's own state at `scene` (its cell pressures among it), without the
    /// coarser levels of the error estimate.
    pub fn state(&self, scene: &Scene) -> Result<GridState> {
        let load = grid_load(scene)?;
        self.state_under(scene, load, scene_tolerance(scene))
    }

    /// The state on `self.cells` cells per side under `load` at `tolerance`.
    fn state_under(&self, scene: &Scene, load: GridLoad, tolerance: f64) -> Result<GridState> {
        let kind = scene.punch.kind.clone();
        if self.extent.is_some() && !kind.is_free_band() {
            return Err(Error::Unsupported {
                method: self.name().into(),
                reason: EXTENT_ONLY_FOR_A_BAND.into(),
            });
        }
        let eps = scene.punch.inner_ratio();
        match (self.extent, self.max_iterations) {
            (Some(half_size), None) => {
                grid_contact::solve_band_on_square(&kind, self.cells, half_size, load, tolerance)
            }
            (None, Some(cap)) => {
                grid_contact::solve_capped(kind, eps, self.cells, load, tolerance, cap)
            }
            (None, None) => grid_contact::solve(kind, eps, self.cells, load, tolerance),
            (Some(_), Some(_)) => Err(Error::Unsupported {
                method: self.name().into(),
                reason: "an iteration cap applies to a punch with a rim, a grid extent to a \
                         free band: not both"
                    .into(),
            }),
        }
    }
}

/// The grid BEM's convergence criterion: the complementarity residual 1e-10, or the scene's
/// tolerance if tighter.
fn scene_tolerance(scene: &Scene) -> f64 {
    scene.tolerance.unwrap_or(1e-10).min(1e-10)
}

/// The grid's load of `scene`: unit depth (flat-faced), `d/h` or `F/(2 E* h a)` (concave).
fn grid_load(scene: &Scene) -> Result<GridLoad> {
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    let h = scene.punch.hole_depth;
    match (scene.punch.kind.is_concave(), scene.load) {
        (false, _) => Ok(GridLoad::Depth(1.0)),
        (_, Load::Depth(d)) => Ok(GridLoad::Depth(d / h)),
        (_, Load::Force(f)) => Ok(GridLoad::Force(f / (2.0 * es * h * a))),
        (_, Load::ContactRatio(_)) => Err(Error::Unsupported {
            method: crate::bem::grid::METHOD.into(),
            reason: "the grid BEM takes a depth or a force (use the ring BEM for --eps)".into(),
        }),
    }
}

impl Default for GridBem {
    fn default() -> Self {
        GridBem {
            cells: DEFAULT_GRID,
            extent: None,
            with_estimate: true,
            max_iterations: None,
        }
    }
}

/// The grid BEM's ladder: `(64 · 2^k)²` cells on the square `[-a, a]²` (a free band: one
/// square for every level, [`grid_contact::band_square`] from a 32² solve); first order in the
/// cell size.
impl Ladder for GridBem {
    fn check_levels(&self, _case: &StudyCase, levels: usize) -> Result<()> {
        if (64usize << (levels.max(1) - 1)) > grid_contact::MAX_GRID {
            return Err(Error::OutOfRange {
                method: "grid-bem".into(),
                reason: format!(
                    "{levels} levels would end at a {0} x {0} grid; at most {1} levels (64 .. {2})",
                    64usize << (levels - 1),
                    (grid_contact::MAX_GRID / 64).trailing_zeros() + 1,
                    grid_contact::MAX_GRID
                ),
            });
        }
        Ok(())
    }

    fn level(&self, case: &StudyCase, k: usize, _located: LocatedEdges) -> Result<Rung> {
        let concave = case.punch.is_concave();
        let n = 64usize << k;
        let load = GridLoad::Depth(if concave { case.depth } else { 1.0 });
        let (s, half_size) = if case.punch.has_rim() {
            (
                grid_contact::solve(case.punch.clone(), case.eps, n, load, 1e-10)?,
                1.0,
            )
        } else {
            let half_size = grid_contact::band_square(&case.punch, 32, load, 1e-10)?;
            let s = grid_contact::solve_band_on_square(&case.punch, n, half_size, load, 1e-10)?;
            (s, half_size)
        };
        let value = s.gamma.or(s.gamma2).unwrap_or(f64::NAN);
        Ok(Rung {
            label: format!("{n}x{n}"),
            size: 2.0 * half_size / n as f64,
            unknowns: n * n,
            value,
            free_edge: None,
            outer_edge: None,
        })
    }

    fn expected_order(&self, _case: &StudyCase) -> Option<f64> {
        Some(1.0)
    }
}

impl Solver for GridBem {
    fn name(&self) -> &'static str {
        crate::bem::grid::METHOD
    }

    fn compute(&self, scene: &Scene) -> Result<Solution> {
        solve_grid_bem(scene, self)
    }
}

/// Why `--grid-extent` is refused where it does not apply.
pub(super) const EXTENT_ONLY_FOR_A_BAND: &str =
    "--grid-extent sets the square of a free band's grid (a punch whose contact edges are both \
     free) with --method grid-bem (the other punches' grid covers their own [-a, a]²)";

/// Solve with the square-grid FFT BEM on `n x n` cells (`grid.cells`); a free band's square
/// half-size `L/a` is `grid.extent` if given. Its convergence criterion is the complementarity
/// residual (tolerance 1e-10, or the scene's if tighter); its discretisation error is estimated
/// from the same problem on `n/2` and `n/4` cells over the same square
/// ([`crate::bem::grid_estimate`]); where a coarser level cannot be solved (a ring too narrow
/// for it, `n/4 < 8`) the solution has no estimate and says why. `grid.with_estimate: false`
/// skips the coarser levels.
fn solve_grid_bem(scene: &Scene, grid: &GridBem) -> Result<Solution> {
    let kind = scene.punch.kind.clone();
    let a = scene.punch.rim_radius;
    let n = grid.cells;
    let load = grid_load(scene)?;
    let tolerance = scene_tolerance(scene);
    let start = Instant::now();
    let state = grid.state_under(scene, load, tolerance)?;
    let free_edges: &[fn(&grid_contact::GridState) -> f64] = match kind.contact() {
        Contact::FreeBand => &[grid_estimate::inner_edge, grid_estimate::outer_edge],
        Contact::RimAndFreeInner => &[grid_estimate::inner_edge],
        Contact::Disk | Contact::FixedAnnulus => &[],
    };
    // The coarser levels on the same square (a free band's as solved), without an iteration cap.
    let coarser = |cells: usize| GridBem {
        cells,
        extent: kind.is_free_band().then_some(state.square_half_size),
        with_estimate: false,
        max_iterations: None,
    };
    let estimate = grid.with_estimate.then(|| {
        grid_estimate::estimate(&state, free_edges, |m| {
            coarser(m).state_under(scene, load, tolerance)
        })
    });
    let estimate_note = match &estimate {
        None => "no error estimate (--no-grid-estimate: the requested grid alone)".to_string(),
        Some(Ok(_)) => format!(
            "error estimate from {} and {} cells per side on the same square (first order, \
             safety factor {})",
            n / grid_estimate::COARSENING[0],
            n / grid_estimate::COARSENING[1],
            grid_estimate::SAFETY
        ),
        Some(Err(e)) => format!("no error estimate ({e})"),
    };
    Ok(Solution {
        outer_radius: state.outer_edge * a,
        unknowns: n * n,
        iterations: state.iterations,
        complementarity_residual: Some(state.residual),
        grid_bem: Some(GridBemPart {
            cells: n,
            grid_extent: Some(state.square_half_size * a),
        }),
        error_estimate: estimate.and_then(Result::ok),
        provenance: format!(
            "square-grid FFT BEM (Love kernel, 2N zero padding, Polonsky-Keer CG), {n} x {n} cells on \
             [-L, L]^2 with L = {} a, {} contact cells, {} iterations, complementarity residual {:.1e}; \
             {estimate_note}",
            crate::error::show(state.square_half_size), state.contact_cells, state.iterations, state.residual
        ),
        ..base(
            scene,
            crate::bem::grid::METHOD,
            state.eps,
            (state.gamma, state.gamma1, state.gamma2),
            start.elapsed().as_secs_f64(),
        )?
    })
}
