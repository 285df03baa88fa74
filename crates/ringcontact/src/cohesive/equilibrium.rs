//! Equilibrium of the punch and the half-space under the adhesion law at one depth: a local
//! minimum of the total energy over the contact line's separations.
//!
//! With `w` the surface deflection into the solid at the contact-line nodes, `S = C⁻¹` the
//! condensed stiffness ([`crate::fem::surface_response`]), the punch face at depth
//! `c_i = d - g(r_i)` (`g` the recess of the face) and the separation `x = w - c >= 0`:
//!
//! `Π(x) = ½ (x + c)ᵀ S (x + c) + Σ_i A_i φ(x_i)`,   `x >= 0`,
//!
//! whose stationarity with the bound is the contact problem: the nodal force on the solid
//! `f = S w = λ - A φ'(x)` is a contact reaction `λ >= 0` (where `x = 0`) minus the adhesive
//! tension. A projected Newton method (Bertsekas 1982) with an Armijo search on `Π` finds the
//! minimum; where the Hessian `S + diag(A φ''(x))` is not positive definite on the free set (a
//! branch has ended), it is shifted, and the shift is reported: the state then found may lie on
//! another branch.

use faer::Mat;

use crate::cohesive::law::ExponentialLaw;
use crate::error::{Error, Result};
use crate::fem::surface_response::SurfaceResponse;
use crate::sparse::native::dense::{zero_padded, DenseCholesky};

/// Most Newton iterations per state.
const MAX_ITERATIONS: usize = 300;

/// The contact line with its stiffness, the face's recess and the adhesion law.
pub struct CohesiveSurface {
    pub radii: Vec<f64>,
    pub weights: Vec<f64>,
    /// `S = C⁻¹` (units `E* a`).
    stiffness: Mat<f64>,
    /// Recess `g(r_i) >= 0` of the punch face below its rim plane (units `a`).
    pub recess: Vec<f64>,
    pub law: ExponentialLaw,
    /// Stationarity tolerance on the projected gradient (a nodal force).
    tolerance: f64,
}

/// One equilibrium.
#[derive(Clone, Debug)]
pub struct Equilibrium {
    pub depth: f64,
    /// Separations `x_i >= 0` at the nodes.
    pub separation: Vec<f64>,
    /// Total force on the solid, compression positive (`Σ (S w)_i`).
    pub force: f64,
    pub iterations: usize,
    /// The Hessian needed a shift on the way: the start was not in the basin of a minimum of
    /// this branch.
    pub shifted: bool,
}

fn no_convergence(reason: String) -> Error {
    Error::NoConvergence {
        method: "cohesive-fem".into(),
        reason,
    }
}

impl CohesiveSurface {
    /// The surface of `response` under `law`, with the face's recess at its nodes.
    pub fn new(response: &SurfaceResponse, recess: Vec<f64>, law: ExponentialLaw) -> Result<Self> {
        let n = response.radii.len();
        if recess.len() != n || n == 0 {
            return Err(no_convergence(format!(
                "internal: {} recess values for {n} contact nodes",
                recess.len()
            )));
        }
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !(positive(law.work) && positive(law.range)) {
            return Err(Error::invalid(
                "adhesion law",
                format!(
                    "need a positive finite work of adhesion and range (got work {}, range {})",
                    law.work, law.range
                ),
            ));
        }
        // Zero-padded storage (`DenseCholesky`): `faer`'s kernels compute on a column's padding
        // rows, where leftover bytes can be slow subnormal numbers.
        let llt = DenseCholesky::of_lower(n, |i, j| response.compliance[(i, j)]).map_err(|_| {
            no_convergence("the contact line's compliance is not positive definite".into())
        })?;
        let mut stiffness = zero_padded(n, n);
        for i in 0..n {
            stiffness[(i, i)] = 1.0;
        }
        llt.solve_in_place(stiffness.as_mut());
        let stiffness = Mat::from_fn(n, n, |i, j| 0.5 * (stiffness[(i, j)] + stiffness[(j, i)]));
        // Kendall's F0 = sqrt(8 π Δw) (E* = a = 1), or the force of a unit depth, sets the
        // force scale.
        let f0 = (8.0 * std::f64::consts::PI * law.work).sqrt().max(1.0);
        Ok(Self {
            radii: response.radii.clone(),
            weights: response.weights.clone(),
            stiffness,
            recess,
            law,
            tolerance: 1e-11 * f0,
        })
    }

    /// Number of contact-line nodes.
    pub fn len(&self) -> usize {
        self.radii.len()
    }

    /// Whether there are no nodes (never, once built).
    pub fn is_empty(&self) -> bool {
        self.radii.is_empty()
    }

    fn face(&self, depth: f64) -> Vec<f64> {
        self.recess.iter().map(|g| depth - g).collect()
    }

    fn deflection(&self, face: &[f64], x: &[f64]) -> Vec<f64> {
        face.iter().zip(x).map(|(c, x)| c + x).collect()
    }

    /// `S w`: the nodal forces on the solid, as the sum of columns `Σ_j S_:j w_j` with `j` in
    /// order: each entry adds its row's products in the row's own order (the same bits as a
    /// row-by-row sum), while the inner loop runs down one contiguous column (vectorised).
    fn forces(&self, w: &[f64]) -> Vec<f64> {
        // `-0.0`: the start of `Iterator::sum` for floats.
        let mut sw = vec![-0.0; w.len()];
        for (j, &wj) in w.iter().enumerate() {
            for (acc, s) in sw.iter_mut().zip(self.stiffness.col_as_slice(j)) {
                *acc += s * wj;
            }
        }
        sw
    }

    /// Total energy `Π(x)` at `depth`.
    pub fn energy(&self, depth: f64, x: &[f64]) -> f64 {
        let w = self.deflection(&self.face(depth), x);
        let sw = self.forces(&w);
        let elastic: f64 = 0.5 * w.iter().zip(&sw).map(|(a, b)| a * b).sum::<f64>();
        let adhesive: f64 = self
            .weights
            .iter()
            .zip(x)
            .map(|(a, &s)| a * self.law.energy(s))
            .sum();
        elastic + adhesive
    }

    /// The equilibrium at `depth` reached from the separations `start` (a local minimum of
    /// `Π`).
    pub fn equilibrium(&self, depth: f64, start: &[f64]) -> Result<Equilibrium> {
        let n = self.len();
        if start.len() != n || !depth.is_finite() || start.iter().any(|v| !v.is_finite()) {
            return Err(Error::invalid(
                "equilibrium start",
                format!(
                    "need {n} finite separations and a finite depth (got {} values, depth {depth})",
                    start.len()
                ),
            ));
        }
        let face = self.face(depth);
        let mut x: Vec<f64> = start.iter().map(|v| v.max(0.0)).collect();
        let mut shifted = false;
        for iteration in 0..MAX_ITERATIONS {
            let w = self.deflection(&face, &x);
            let sw = self.forces(&w);
            let gradient: Vec<f64> = (0..n)
                .map(|i| sw[i] + self.weights[i] * self.law.tension(x[i]))
                .collect();
            let projected = (0..n)
                .map(|i| {
                    if x[i] <= 0.0 {
                        gradient[i].min(0.0)
                    } else {
                        gradient[i]
                    }
                })
                .fold(0.0f64, |m, g| m.max(g.abs()));
            if !projected.is_finite() {
                return Err(no_convergence(format!(
                    "non-finite gradient at depth {depth:e}"
                )));
            }
            if projected <= self.tolerance {
                return Ok(Equilibrium {
                    depth,
                    force: sw.iter().sum(),
                    separation: x,
                    iterations: iteration,
                    shifted,
                });
            }
            // Binding set: at the bound and pushed into it.
            let binding_width = projected.min(1e-3) * self.law.range;
            let binding: Vec<bool> = (0..n)
                .map(|i| x[i] <= binding_width && gradient[i] > 0.0)
                .collect();
            let free: Vec<usize> = (0..n).filter(|&i| !binding[i]).collect();
            let mut step = vec![0.0; n];
            for i in 0..n {
                if binding[i] {
                    // A scaled gradient step toward the bound.
                    step[i] = -gradient[i] / self.stiffness[(i, i)];
                }
            }
            if !free.is_empty() {
                let (direction, needed_shift) = self.newton_direction(&x, &gradient, &free)?;
                shifted |= needed_shift;
                for (k, &i) in free.iter().enumerate() {
                    step[i] = direction[k];
                }
            }
            x = self.search(depth, &x, &gradient, &step)?;
        }
        Err(no_convergence(format!(
            "no equilibrium at depth {depth:e} after {MAX_ITERATIONS} Newton iterations"
        )))
    }

    /// Solve `(H_FF + μ I) p = -g_F` with the smallest shift `μ >= 0` (from 0, then growing
    /// tenfold) that makes the matrix positive definite.
    fn newton_direction(
        &self,
        x: &[f64],
        gradient: &[f64],
        free: &[usize],
    ) -> Result<(Vec<f64>, bool)> {
        let m = free.len();
        let scale = free
            .iter()
            .map(|&i| self.stiffness[(i, i)])
            .fold(0.0f64, f64::max);
        let mut shift = 0.0;
        for _ in 0..40 {
            let hessian = DenseCholesky::of_lower(m, |a, b| {
                let (i, j) = (free[a], free[b]);
                let mut h = self.stiffness[(i, j)];
                if i == j {
                    h += self.weights[i] * self.law.curvature(x[i]) + shift;
                }
                h
            });
            if let Ok(llt) = hessian {
                let mut p = zero_padded(m, 1);
                for a in 0..m {
                    p[(a, 0)] = -gradient[free[a]];
                }
                llt.solve_in_place(p.as_mut());
                return Ok(((0..m).map(|a| p[(a, 0)]).collect(), shift > 0.0));
            }
            shift = if shift == 0.0 {
                1e-8 * scale
            } else {
                10.0 * shift
            };
        }
        Err(no_convergence(
            "the Hessian stays indefinite under every shift".into(),
        ))
    }

    /// Armijo search along the projected path `max(0, x + α p)`.
    fn search(&self, depth: f64, x: &[f64], gradient: &[f64], step: &[f64]) -> Result<Vec<f64>> {
        let current = self.energy(depth, x);
        let mut alpha = 1.0;
        for _ in 0..60 {
            let trial: Vec<f64> = x
                .iter()
                .zip(step)
                .map(|(x, p)| (x + alpha * p).max(0.0))
                .collect();
            let decrease: f64 = gradient
                .iter()
                .zip(trial.iter().zip(x))
                .map(|(g, (t, x))| g * (t - x))
                .sum();
            let energy = self.energy(depth, &trial);
            // Sufficient decrease, or no increase beyond the rounding of `Π` (near the minimum
            // the decrease of a Newton step is below it).
            let rounding = 1e-13 * current.abs().max(self.tolerance * self.law.range);
            if energy <= current + 1e-4 * decrease || energy <= current + rounding {
                return Ok(trial);
            }
            alpha *= 0.5;
        }
        Err(no_convergence(format!(
            "the line search found no decrease of the energy at depth {depth:e}"
        )))
    }
}
