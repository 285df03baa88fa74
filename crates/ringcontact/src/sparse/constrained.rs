//! Sparse Cholesky solves of `K u = f` with Dirichlet constraints, on a fixed sparsity pattern.
//!
//! A constrained dof `i` keeps its row and column in the pattern, with every off-diagonal entry
//! set to zero and the diagonal kept (`K_ii u_i = K_ii ū_i`); the known values move to the right
//! side. The pattern is therefore the same for every constraint set, and the symbolic analysis
//! ([`crate::sparse::analyse`]) is computed once and reused for each new active set of the
//! contact iteration: only the numeric factorisation ([`crate::sparse::Analysis::factorise`]) is
//! repeated. Everything here goes through the seam of [`crate::sparse`], on either backend.

use std::borrow::Cow;

use faer::Mat;
use nalgebra_sparse::CscMatrix;
use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::sparse::{analyse_bare, Analysis, Backend, Factor, Pattern};

/// Rows of the refinement's residual computed per parallel task.
const RESIDUAL_ROWS_PER_TASK: usize = 4096;

/// Cholesky solver bound to one stiffness matrix.
pub struct ConstrainedCholesky<'a> {
    matrix: &'a CscMatrix<f64>,
    analysis: Analysis,
    /// Where each column's diagonal entry is among `matrix`'s entries.
    diagonal: Cow<'a, [usize]>,
    /// The last numeric factorisation and the constraint set it belongs to: a solve with the same
    /// set (other prescribed values or forces) is a back-substitution only.
    last: Option<(Vec<bool>, Factor)>,
    /// Number of numeric factorisations done.
    pub factorisations: usize,
    /// Wall time spent in numeric factorisations (seconds).
    pub factorisation_seconds: f64,
    /// Whether [`Self::solve`] takes its step of iterative refinement
    /// ([`Self::refine_solutions`]).
    refine: bool,
}

fn solver_error(message: String) -> Error {
    Error::NoConvergence {
        method: "fem".into(),
        reason: message,
    }
}

fn finite(u: Vec<f64>) -> Result<Vec<f64>> {
    if u.iter().any(|v| !v.is_finite()) {
        return Err(solver_error(
            "the linear solve produced non-finite values".into(),
        ));
    }
    Ok(u)
}

impl<'a> ConstrainedCholesky<'a> {
    /// Symbolic analysis of the pattern of `matrix` (done once), on [`Backend::BUILT_IN`].
    ///
    /// Both backends factorise in one thread: on the 2-core machine the numeric factorisation
    /// took 0.044 s sequential against 0.080 s parallel at 38 k unknowns, 1.47 s against 2.16 s
    /// at 706 k, and blocked solves of 64 right-hand sides 0.087 s against 0.153 s (the two
    /// cores are better used by the parallel element assembly, the native split and independent
    /// states).
    pub fn new(matrix: &'a CscMatrix<f64>) -> Result<Self> {
        Self::with_backend(matrix, Backend::default())
    }

    /// [`Self::new`] on the given backend (a bare pattern: ordered on its node graph by the
    /// native backend, by `faer`'s AMD by the other).
    pub fn with_backend(matrix: &'a CscMatrix<f64>, backend: Backend) -> Result<Self> {
        let pattern = Pattern::new(matrix.col_offsets(), matrix.row_indices());
        Self::with_symbolic(matrix, analyse_bare(pattern, backend)?)
    }

    /// [`Self::new`] with the symbolic analysis of `matrix`'s pattern already done (for example
    /// while the matrix was assembled); an analysis of another pattern is an error.
    fn with_symbolic(matrix: &'a CscMatrix<f64>, analysis: Analysis) -> Result<Self> {
        let n = matrix.nrows();
        let mut diagonal = vec![usize::MAX; n];
        for (col, slot) in diagonal.iter_mut().enumerate() {
            let range = matrix.col_offsets()[col]..matrix.col_offsets()[col + 1];
            if let Some(k) = matrix.row_indices()[range.clone()]
                .iter()
                .position(|&row| row == col)
            {
                *slot = range.start + k;
            }
        }
        Self::with_diagonal(matrix, analysis, Cow::Owned(diagonal))
    }

    /// [`Self::with_symbolic`] with the position of each column's diagonal entry among
    /// `matrix`'s entries given (`usize::MAX` for a column without one), as the assembly knows
    /// it ([`crate::discretisation::assembly::StiffnessPattern::into_matrix_and_diagonal`]): the search for
    /// them reads every entry of `matrix` (2.2 ms at 92 528 unknowns, on one core), and so
    /// does a check of the positions given (1.3 ms: one entry per column, no longer in cache).
    /// The positions are trusted: the assembly writes each with its column's rows, and the
    /// test `assembled_diagonal_positions_are_the_diagonal` compares them with the search on
    /// every kind of pattern; debug builds check them here as well.
    pub(crate) fn with_symbolic_and_diagonal(
        matrix: &'a CscMatrix<f64>,
        analysis: Analysis,
        diagonal: &'a [usize],
    ) -> Result<Self> {
        let (offsets, rows) = (matrix.col_offsets(), matrix.row_indices());
        debug_assert!(diagonal.iter().enumerate().all(|(col, &d)| {
            d == usize::MAX || ((offsets[col]..offsets[col + 1]).contains(&d) && rows[d] == col)
        }));
        if diagonal.len() != matrix.ncols() {
            return Err(solver_error(
                "internal: the diagonal positions given belong to another matrix".into(),
            ));
        }
        Self::with_diagonal(matrix, analysis, Cow::Borrowed(diagonal))
    }

    fn with_diagonal(
        matrix: &'a CscMatrix<f64>,
        analysis: Analysis,
        diagonal: Cow<'a, [usize]>,
    ) -> Result<Self> {
        if !analysis.fits(matrix.nrows(), matrix.nnz()) {
            return Err(solver_error(
                "internal: the symbolic analysis belongs to another pattern".into(),
            ));
        }
        if let Some(col) = diagonal.iter().position(|&d| d == usize::MAX) {
            return Err(solver_error(format!(
                "dof {col} has no diagonal entry (a node outside every element)"
            )));
        }
        Ok(Self {
            matrix,
            analysis,
            diagonal,
            last: None,
            factorisations: 0,
            factorisation_seconds: 0.0,
            refine: true,
        })
    }

    /// Whether [`Self::solve`] refines its solution (one step of iterative refinement, on by
    /// default): worth its second triangular solve only where the answer is asked to within a
    /// few orders of magnitude of rounding (see [`Self::solve`]).
    pub(crate) fn refine_solutions(&mut self, refine: bool) {
        self.refine = refine;
    }

    /// Solve `K u = f` with `u_i = prescribed[i]` wherever `constrained[i]`.
    pub fn solve(
        &mut self,
        force: &[f64],
        constrained: &[bool],
        prescribed: &[f64],
    ) -> Result<Vec<f64>> {
        self.solve_with(force, constrained, prescribed, true)
    }

    /// [`Self::solve`] without its step of iterative refinement: for intermediate solutions that
    /// a later refinement corrects (half the triangular solves).
    pub(crate) fn solve_unrefined(
        &mut self,
        force: &[f64],
        constrained: &[bool],
        prescribed: &[f64],
    ) -> Result<Vec<f64>> {
        self.solve_with(force, constrained, prescribed, false)
    }

    fn solve_with(
        &mut self,
        force: &[f64],
        constrained: &[bool],
        prescribed: &[f64],
        refine: bool,
    ) -> Result<Vec<f64>> {
        let n = self.matrix.nrows();
        let offsets = self.matrix.col_offsets();
        let rows = self.matrix.row_indices();
        let values = self.matrix.values();
        let reuse = self.is_factorised_for(constrained);
        let mut rhs = force.to_vec();
        for col in (0..n).filter(|&col| constrained[col]) {
            for k in offsets[col]..offsets[col + 1] {
                let row = rows[k];
                if !constrained[row] {
                    rhs[row] -= values[k] * prescribed[col];
                }
            }
        }
        for i in 0..n {
            if constrained[i] {
                rhs[i] = values[self.diagonal[i]] * prescribed[i];
            }
        }
        if !reuse {
            self.factorise(constrained)?;
        }
        if let Some((mask, llt)) = &self.last {
            // One step of iterative refinement with the same factor: the graded meshes span
            // element sizes from 1e-10 a to 1e6 a, and without it rounding leaves a floor of about
            // 4e-9 in the force of 10^6-unknown models.
            let b = rhs.clone();
            llt.solve(&mut rhs);
            if !(refine && self.refine) {
                return finite(rhs);
            }
            // r = b - K_C x, K_C being K with the constrained rows and columns reduced to
            // their diagonal.
            // A free row's term is its product with the free part of x (row i read as column
            // i: K is symmetric), a constrained row's its diagonal term; the rows in parallel.
            let free_x: Vec<f64> = rhs
                .iter()
                .zip(mask)
                .map(|(&x, &held)| if held { 0.0 } else { x })
                .collect();
            let mut residual: Vec<f64> = (0..n)
                .into_par_iter()
                .with_min_len(RESIDUAL_ROWS_PER_TASK)
                .map(|i| {
                    if mask[i] {
                        b[i] - values[self.diagonal[i]] * rhs[i]
                    } else {
                        b[i] - self.column_dot(i, &free_x)
                    }
                })
                .collect();
            llt.solve(&mut residual);
            for (x, dx) in rhs.iter_mut().zip(&residual) {
                *x += dx;
            }
        }
        finite(rhs)
    }

    /// Whether the current numeric factor belongs to this constraint set.
    fn is_factorised_for(&self, constrained: &[bool]) -> bool {
        matches!(&self.last, Some((mask, _)) if mask.as_slice() == constrained)
    }

    /// Numeric factorisation of the matrix with the rows and columns of `constrained` replaced by
    /// their diagonal (the symbolic analysis is reused).
    fn factorise(&mut self, constrained: &[bool]) -> Result<()> {
        let start = std::time::Instant::now();
        let pattern = Pattern::new(self.matrix.col_offsets(), self.matrix.row_indices());
        let factor = self
            .analysis
            .factorise(pattern, self.matrix.values(), constrained)?;
        self.factorisations += 1;
        self.factorisation_seconds += start.elapsed().as_secs_f64();
        self.last = Some((constrained.to_vec(), factor));
        Ok(())
    }

    /// Columns `w_j = K_C⁻¹ e_j` of the inverse of the constrained matrix `K_C` (constraint set
    /// `constrained`) for free dofs `j`: the responses to unit forces at those dofs with the
    /// constrained dofs held at zero. One factorisation (reused if current) and one blocked
    /// triangular solve with `dofs.len()` right-hand sides.
    pub fn unit_responses(
        &mut self,
        constrained: &[bool],
        dofs: &[usize],
    ) -> Result<Vec<Vec<f64>>> {
        let n = self.matrix.nrows();
        if let Some(&j) = dofs.iter().find(|&&j| j >= n || constrained[j]) {
            return Err(solver_error(format!(
                "internal: unit response asked for dof {j}, which is constrained or out of range"
            )));
        }
        if !self.is_factorised_for(constrained) {
            self.factorise(constrained)?;
        }
        let mut block = Mat::<f64>::zeros(n, dofs.len());
        for (c, &j) in dofs.iter().enumerate() {
            block[(j, c)] = 1.0;
        }
        if let Some((_, llt)) = &self.last {
            llt.solve_many(block.as_mut());
        }
        let columns: Vec<Vec<f64>> = (0..dofs.len())
            .map(|c| (0..n).map(|i| block[(i, c)]).collect())
            .collect();
        if columns.iter().flatten().any(|v| !v.is_finite()) {
            return Err(solver_error(
                "the unit responses contain non-finite values".into(),
            ));
        }
        Ok(columns)
    }

    /// `(K u)_i` for each dof `i` of `dofs`: the reaction at a constrained dof of a solution
    /// without forces there. Read from column `i` (`K` is symmetric), so it costs the entries of
    /// those columns only, not a product with the whole matrix.
    pub(crate) fn product_at(&self, u: &[f64], dofs: &[usize]) -> Vec<f64> {
        dofs.iter().map(|&i| self.column_dot(i, u)).collect()
    }

    /// `Σ_k K_ki x_k` over column `i`'s entries: `(K x)_i`, `K` being symmetric.
    fn column_dot(&self, i: usize, x: &[f64]) -> f64 {
        let column = self.matrix.col_offsets()[i]..self.matrix.col_offsets()[i + 1];
        self.matrix.row_indices()[column.clone()]
            .iter()
            .zip(&self.matrix.values()[column])
            .map(|(&row, &k)| k * x[row])
            .sum()
    }

    /// Residual `K u - f`: the reaction forces at constrained dofs (zero elsewhere, to rounding).
    pub fn residual(&self, u: &[f64], force: &[f64]) -> Vec<f64> {
        let mut r: Vec<f64> = force.iter().map(|f| -f).collect();
        let offsets = self.matrix.col_offsets();
        let rows = self.matrix.row_indices();
        let values = self.matrix.values();
        for col in 0..self.matrix.ncols() {
            let uc = u[col];
            for k in offsets[col]..offsets[col + 1] {
                r[rows[k]] += values[k] * uc;
            }
        }
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretisation::assembly::assemble_stiffness;
    use crate::discretisation::element::Lame;
    use crate::discretisation::quadrature::stiffness_rule;
    use crate::mesh::triangulation::{structured_rectangle, Degree};

    /// `K u` by the full product over `K`'s stored entries (the definition).
    fn product(k: &CscMatrix<f64>, u: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; k.nrows()];
        for (col, column) in k.col_iter().enumerate() {
            for (&row, &v) in column.row_indices().iter().zip(column.values()) {
                y[row] += v * u[col];
            }
        }
        y
    }

    #[test]
    fn column_products_and_the_refined_solve_match_the_full_product() {
        for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
            let mesh = structured_rectangle(2.0, 1.0, 6, 4, 1, 2, 3).with_degree(degree);
            let material = Lame::from_young_poisson(1.0, 0.3);
            let k = assemble_stiffness(&mesh, &material, &stiffness_rule(degree)).unwrap();
            let n = k.nrows();
            let u: Vec<f64> = (0..n)
                .map(|i| ((i * 37 % 101) as f64 - 50.0) / 7.0)
                .collect();
            let full = product(&k, &u);
            let mut solver = ConstrainedCholesky::new(&k).unwrap();
            let dofs: Vec<usize> = (0..n).step_by(3).collect();
            for (&i, ku) in dofs.iter().zip(solver.product_at(&u, &dofs)) {
                assert!(
                    (ku - full[i]).abs() <= 1e-12 * full[i].abs().max(1.0),
                    "{degree:?}"
                );
            }
            // Bottom held, top pressed down: the solve must satisfy K u = f on the free dofs
            // and the prescribed values on the held ones.
            let bottom: Vec<usize> = mesh.boundary_nodes(3);
            let top: Vec<usize> = mesh.boundary_nodes(1);
            let mut constrained = vec![false; n];
            let mut prescribed = vec![0.0; n];
            for &m in &bottom {
                constrained[2 * m] = true;
                constrained[2 * m + 1] = true;
            }
            for &m in &top {
                constrained[2 * m + 1] = true;
                prescribed[2 * m + 1] = -0.01;
            }
            let force: Vec<f64> = (0..n)
                .map(|i| if i % 5 == 0 { 1e-3 } else { 0.0 })
                .collect();
            let x = solver.solve(&force, &constrained, &prescribed).unwrap();
            let kx = product(&k, &x);
            let scale = kx.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for i in 0..n {
                if constrained[i] {
                    assert!((x[i] - prescribed[i]).abs() < 1e-14, "{degree:?} dof {i}");
                } else {
                    assert!(
                        (kx[i] - force[i]).abs() < 1e-12 * scale,
                        "{degree:?} dof {i}"
                    );
                }
            }
        }
    }
}
