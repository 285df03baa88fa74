//! 3-D FFT boundary-element method on a square grid (the paper's method: Pohrt and Li 2014).
//!
//! The surface is an `N x N` grid of square cells of side `Δ` carrying piecewise-constant pressure.
//! The deflection at a cell centre due to unit pressure on a cell whose centre is offset by
//! `(x, y)` is Love's (1929) closed form for a uniformly loaded rectangle,
//!
//! ```text
//! K(x, y) = 1/(π E*) [G(x + Δ/2, y + Δ/2) - G(x + Δ/2, y - Δ/2) - G(x - Δ/2, y + Δ/2) + G(x - Δ/2, y - Δ/2)],
//! G(X, Y) = X asinh(Y/X) + Y asinh(X/Y)     (= ∫_0^X ∫_0^Y dx dy / sqrt(x² + y²)),
//! ```
//!
//! and the non-periodic convolution `u = K * p` is computed by FFT on a `2N x 2N` zero-padded
//! grid (Liu, Wang and Liu 2000), the kernel spectrum computed once. Unilateral contact is solved by
//! the constrained conjugate-gradient method of Polonsky and Keer (1999), under depth control
//! (the rigid approach `d` is given: a bound-constrained quadratic programme) or force control
//! (the original algorithm with the mean-gap correction and the load constraint). It stops when
//! the complementarity residual is below the tolerance; hitting the iteration cap is an error.
//!
//! Dimensionless: `E* = 1`; lengths in any unit (the grid's).

use std::sync::Arc;

use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use crate::error::{Error, Result};

/// Name of the method.
pub const METHOD: &str = "grid-bem";

/// Love's primitive `G(X, Y) = ∫_0^X ∫_0^Y dx dy / sqrt(x² + y²)`: for `X, Y > 0` it is
/// `X asinh(Y/X) + Y asinh(X/Y)`; it is odd in each argument and 0 on the axes.
fn love_primitive(x: f64, y: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    if ax == 0.0 || ay == 0.0 {
        return 0.0;
    }
    let positive = ax * (ay / ax).asinh() + ay * (ax / ay).asinh();
    positive * x.signum() * y.signum()
}

/// Deflection at offset `(x, y)` from the centre of a uniformly loaded square cell of side `cell`
/// (unit pressure, `E* = 1`).
pub fn love_influence(x: f64, y: f64, cell: f64) -> f64 {
    let h = 0.5 * cell;
    (love_primitive(x + h, y + h) - love_primitive(x + h, y - h) - love_primitive(x - h, y + h)
        + love_primitive(x - h, y - h))
        / std::f64::consts::PI
}

/// The FFT convolution operator of one grid.
pub struct GridOperator {
    n: usize,
    padded: usize,
    /// Cell side `Δ`.
    pub cell: f64,
    spectrum: Vec<Complex<f64>>,
    row_forward: Arc<dyn RealToComplex<f64>>,
    row_inverse: Arc<dyn ComplexToReal<f64>>,
    column_forward: Arc<dyn Fft<f64>>,
    column_inverse: Arc<dyn Fft<f64>>,
}

impl GridOperator {
    /// Operator of an `n x n` grid of cells of side `cell`.
    pub fn new(n: usize, cell: f64) -> Self {
        let padded = 2 * n;
        let mut real_planner = RealFftPlanner::<f64>::new();
        let mut planner = FftPlanner::<f64>::new();
        let mut op = Self {
            n,
            padded,
            cell,
            spectrum: Vec::new(),
            row_forward: real_planner.plan_fft_forward(padded),
            row_inverse: real_planner.plan_fft_inverse(padded),
            column_forward: planner.plan_fft_forward(padded),
            column_inverse: planner.plan_fft_inverse(padded),
        };
        // Kernel on the padded grid: offsets 0..n-1 and -(n-1)..-1 wrapped; the row n is unused
        // (set to 0), which makes the circular convolution equal the linear one on the grid.
        let mut kernel = vec![0.0; padded * padded];
        for i in 0..padded {
            let di = if i < n {
                i as f64
            } else if i > n {
                i as f64 - padded as f64
            } else {
                continue;
            };
            for j in 0..padded {
                let dj = if j < n {
                    j as f64
                } else if j > n {
                    j as f64 - padded as f64
                } else {
                    continue;
                };
                kernel[i * padded + j] = love_influence(di * cell, dj * cell, cell);
            }
        }
        op.spectrum = op.forward(&mut kernel);
        let scale = 1.0 / (padded * padded) as f64;
        op.spectrum.iter_mut().for_each(|c| *c *= scale);
        op
    }

    /// Grid size `N`.
    pub fn size(&self) -> usize {
        self.n
    }

    /// 2-D real-to-complex transform of a `padded x padded` array (rows, then columns).
    fn forward(&self, data: &mut [f64]) -> Vec<Complex<f64>> {
        let m = self.padded;
        let half = m / 2 + 1;
        let mut out = vec![Complex::new(0.0, 0.0); m * half];
        let mut scratch = self.row_forward.make_scratch_vec();
        for (row, out_row) in data.chunks_mut(m).zip(out.chunks_mut(half)) {
            self.row_forward
                .process_with_scratch(row, out_row, &mut scratch)
                .expect("row FFT sizes");
        }
        let mut column = vec![Complex::new(0.0, 0.0); m];
        let mut col_scratch =
            vec![Complex::new(0.0, 0.0); self.column_forward.get_inplace_scratch_len()];
        for k in 0..half {
            for i in 0..m {
                column[i] = out[i * half + k];
            }
            self.column_forward
                .process_with_scratch(&mut column, &mut col_scratch);
            for i in 0..m {
                out[i * half + k] = column[i];
            }
        }
        out
    }

    /// Inverse of [`Self::forward`] (unnormalised), written into `data`.
    fn inverse(&self, spectrum: &mut [Complex<f64>], data: &mut [f64]) {
        let m = self.padded;
        let half = m / 2 + 1;
        let mut column = vec![Complex::new(0.0, 0.0); m];
        let mut col_scratch =
            vec![Complex::new(0.0, 0.0); self.column_inverse.get_inplace_scratch_len()];
        for k in 0..half {
            for i in 0..m {
                column[i] = spectrum[i * half + k];
            }
            self.column_inverse
                .process_with_scratch(&mut column, &mut col_scratch);
            for i in 0..m {
                spectrum[i * half + k] = column[i];
            }
        }
        let mut scratch = self.row_inverse.make_scratch_vec();
        for (row_spec, row) in spectrum.chunks_mut(half).zip(data.chunks_mut(m)) {
            // The imaginary parts of the DC and Nyquist bins are rounding noise: clear them.
            row_spec[0].im = 0.0;
            row_spec[half - 1].im = 0.0;
            self.row_inverse
                .process_with_scratch(row_spec, row, &mut scratch)
                .expect("row FFT sizes");
        }
    }

    /// `u = K * p` on the `N x N` grid (row-major), `E* = 1`.
    pub fn apply(&self, pressure: &[f64], deflection: &mut [f64]) {
        let (n, m) = (self.n, self.padded);
        let mut padded = vec![0.0; m * m];
        for i in 0..n {
            padded[i * m..i * m + n].copy_from_slice(&pressure[i * n..(i + 1) * n]);
        }
        let mut spectrum = self.forward(&mut padded);
        for (s, k) in spectrum.iter_mut().zip(&self.spectrum) {
            *s *= k;
        }
        self.inverse(&mut spectrum, &mut padded);
        for i in 0..n {
            deflection[i * n..(i + 1) * n].copy_from_slice(&padded[i * m..i * m + n]);
        }
    }
}

/// What is prescribed in a grid contact solve.
#[derive(Clone, Copy, Debug)]
pub enum GridLoad {
    /// Rigid approach `d`.
    Depth(f64),
    /// Total force `F` (`E* = 1`).
    Force(f64),
}

/// A solved grid contact.
#[derive(Clone, Debug)]
pub struct GridContact {
    /// Cell pressures (row-major, `N x N`).
    pub pressure: Vec<f64>,
    /// Total force `Δ² Σ p`.
    pub force: f64,
    /// Rigid approach `d` (given, or found under force control).
    pub depth: f64,
    /// Cells in contact (`p > 0`).
    pub contact_cells: usize,
    /// CG iterations.
    pub iterations: usize,
    /// Final complementarity residual.
    pub residual: f64,
}

/// Solve the unilateral contact of a rigid punch: `allowed[i]` marks cells the punch covers,
/// `target[i] = d - g_i` is the deflection the punch imposes where it touches (for depth control
/// pass the gap profile `g_i` as `profile` and the depth in `load`).
pub fn solve_contact(
    op: &GridOperator,
    allowed: &[bool],
    profile: &[f64],
    load: GridLoad,
    tolerance: f64,
    max_iterations: usize,
) -> Result<GridContact> {
    let n = op.size();
    let cells = n * n;
    let area = op.cell * op.cell;
    let force_control = matches!(load, GridLoad::Force(_));
    let (mut depth, force_target) = match load {
        GridLoad::Depth(d) => (d, f64::NAN),
        GridLoad::Force(f) => (f64::NAN, f),
    };
    let allowed_count = allowed.iter().filter(|&&a| a).count();
    if allowed_count == 0 {
        return Err(Error::Unsupported {
            method: METHOD.into(),
            reason: "no grid cell lies under the punch: the grid is coarser than the punch".into(),
        });
    }
    let mut p = initial_pressure(allowed, allowed_count, area, load);
    let mut u = vec![0.0; cells];
    let mut gap = vec![0.0; cells];
    let mut t = vec![0.0; cells];
    let mut r = vec![0.0; cells];
    let (mut delta, mut g_old) = (0.0_f64, 1.0_f64);
    let mut residual = f64::INFINITY;
    // Long solves (large grids) say where they are on standard error every 10 s.
    let mut report = IterationReport::start(n);
    for iteration in 1..=max_iterations {
        report.every_ten_seconds(iteration, residual);
        op.apply(&p, &mut u);
        let (contact, mean) = fill_gap(&mut gap, &u, profile, allowed, &p);
        if contact == 0 {
            return Err(Error::NoConvergence {
                method: METHOD.into(),
                reason: format!("the contact set emptied at iteration {iteration}"),
            });
        }
        if force_control {
            // Under force control d is eliminated by the mean over the contact set.
            depth = mean;
        }
        for i in 0..cells {
            if allowed[i] {
                gap[i] -= depth;
            }
        }
        // Convergence: complementarity (Σ p |gap| relative to F d) and penetration of free cells.
        let total: f64 = p.iter().sum();
        residual = complementarity_residual(&p, &gap, allowed, depth, total);
        if residual <= tolerance && iteration > 1 {
            return Ok(GridContact {
                force: area * total,
                pressure: p,
                depth,
                contact_cells: contact,
                iterations: iteration,
                residual,
            });
        }
        let entered = conjugate_step(
            op,
            ConjugateVectors {
                p: &mut p,
                gap: &gap,
                t: &mut t,
                r: &mut r,
            },
            allowed,
            &mut g_old,
            delta,
            force_control.then_some(contact),
        );
        delta = if entered { 0.0 } else { 1.0 };
        if force_control {
            let total: f64 = p.iter().sum::<f64>() * area;
            if total > 0.0 {
                let s = force_target / total;
                p.iter_mut().for_each(|v| *v *= s);
            }
        }
    }
    Err(Error::NoConvergence {
        method: METHOD.into(),
        reason: format!(
            "Polonsky-Keer stopped at the cap of {max_iterations} iterations with complementarity residual {residual:.2e} (tolerance {tolerance:.1e})"
        ),
    })
}

/// `gap = u + g` on the allowed cells (the depth not yet subtracted); the number of cells in
/// contact (`p > 0`) and their mean of it.
fn fill_gap(
    gap: &mut [f64],
    u: &[f64],
    profile: &[f64],
    allowed: &[bool],
    p: &[f64],
) -> (usize, f64) {
    let mut contact = 0usize;
    let mut sum = 0.0;
    for i in 0..gap.len() {
        if allowed[i] {
            gap[i] = u[i] + profile[i];
            if p[i] > 0.0 {
                sum += gap[i];
                contact += 1;
            }
        }
    }
    (contact, sum / contact as f64)
}

/// The start of the iteration: uniform pressure on the `allowed_count` allowed cells carrying a
/// plausible load (the force, or `2 d sqrt(A/π)` of the covered area `A` under depth control).
fn initial_pressure(allowed: &[bool], allowed_count: usize, area: f64, load: GridLoad) -> Vec<f64> {
    let start_load = match load {
        GridLoad::Force(force) => force,
        GridLoad::Depth(depth) => {
            2.0 * depth * (allowed_count as f64 * area / std::f64::consts::PI).sqrt()
        }
    };
    allowed
        .iter()
        .map(|&a| {
            if a {
                start_load / (allowed_count as f64 * area)
            } else {
                0.0
            }
        })
        .collect()
}

/// A line on standard error every ten seconds of a long solve of an `n x n` grid.
struct IterationReport {
    n: usize,
    started: std::time::Instant,
    reported: std::time::Instant,
}

impl IterationReport {
    fn start(n: usize) -> Self {
        let now = std::time::Instant::now();
        IterationReport {
            n,
            started: now,
            reported: now,
        }
    }

    /// Say the iteration and the residual if ten seconds passed since the last line.
    fn every_ten_seconds(&mut self, iteration: usize, residual: f64) {
        if self.reported.elapsed().as_secs_f64() >= 10.0 {
            self.reported = std::time::Instant::now();
            let n = self.n;
            eprintln!(
                "grid-bem {n} x {n}: iteration {iteration}, residual {residual:.1e}, {:.0} s",
                self.started.elapsed().as_secs_f64()
            );
        }
    }
}

/// The Polonsky-Keer residual: complementarity `Σ p |gap| / (F d)` (`total = Σ p`) or the
/// largest penetration of a free cell over `d`, whichever is larger.
fn complementarity_residual(
    p: &[f64],
    gap: &[f64],
    allowed: &[bool],
    depth: f64,
    total: f64,
) -> f64 {
    let cells = p.len();
    let scale = depth.abs().max(f64::MIN_POSITIVE);
    let complementarity: f64 = (0..cells)
        .filter(|&i| p[i] > 0.0)
        .map(|i| p[i] * gap[i].abs())
        .sum::<f64>()
        / (total * scale);
    let penetration = (0..cells)
        .filter(|&i| allowed[i] && p[i] == 0.0)
        .map(|i| (-gap[i]).max(0.0))
        .fold(0.0, f64::max)
        / scale;
    complementarity.max(penetration)
}

/// The vectors of a Polonsky-Keer step: pressure `p` (updated), the gap on the allowed cells,
/// the conjugate direction `t` (updated) and its response `r` (work space).
struct ConjugateVectors<'a> {
    p: &'a mut [f64],
    gap: &'a [f64],
    t: &'a mut [f64],
    r: &'a mut [f64],
}

/// One Polonsky-Keer step: a conjugate direction on the contact set (restarted when `delta` is
/// 0; `g_old` the previous squared gap norm, updated), a step that keeps `p >= 0`, penetrating
/// cells entering the contact set (whether any did is returned). Under force control
/// (`contact_for_mean`: the contact cells) the response's mean over the contact is removed.
fn conjugate_step(
    op: &GridOperator,
    vectors: ConjugateVectors,
    allowed: &[bool],
    g_old: &mut f64,
    delta: f64,
    contact_for_mean: Option<usize>,
) -> bool {
    let ConjugateVectors { p, gap, t, r } = vectors;
    let cells = p.len();
    // Conjugate direction on the contact set.
    let g_norm: f64 = (0..cells)
        .filter(|&i| p[i] > 0.0)
        .map(|i| gap[i] * gap[i])
        .sum();
    for i in 0..cells {
        t[i] = if p[i] > 0.0 {
            gap[i] + delta * (g_norm / *g_old) * t[i]
        } else {
            0.0
        };
    }
    *g_old = g_norm;
    op.apply(t, r);
    if let Some(contact) = contact_for_mean {
        let mean_r = (0..cells)
            .filter(|&i| p[i] > 0.0)
            .map(|i| r[i])
            .sum::<f64>()
            / contact as f64;
        r.iter_mut().for_each(|v| *v -= mean_r);
    }
    let num: f64 = (0..cells)
        .filter(|&i| p[i] > 0.0)
        .map(|i| gap[i] * t[i])
        .sum();
    let den: f64 = (0..cells)
        .filter(|&i| p[i] > 0.0)
        .map(|i| r[i] * t[i])
        .sum();
    let tau = if den > 0.0 { num / den } else { 0.0 };
    for i in 0..cells {
        if p[i] > 0.0 {
            p[i] = (p[i] - tau * t[i]).max(0.0);
        }
    }
    // Cells that penetrate enter the contact set; the conjugacy restarts.
    let mut entered = false;
    for i in 0..cells {
        if allowed[i] && p[i] == 0.0 && gap[i] < 0.0 {
            p[i] = -tau * gap[i];
            entered = true;
        }
    }
    entered
}
