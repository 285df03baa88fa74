//! Sparse Cholesky solves of `K u = f` with Dirichlet constraints, on a fixed sparsity pattern.
//!
//! A constrained dof `i` keeps its row and column in the pattern, with every off-diagonal entry
//! set to zero and the diagonal kept (`K_ii u_i = K_ii ū_i`); the known values move to the right
//! side. The pattern is therefore the same for every constraint set, and the symbolic analysis
//! (node-graph AMD ordering, supernodal structure: [`super::node_ordered_cholesky`]) is computed
//! once and reused for each new active set of the contact iteration: only the numeric
//! factorisation is repeated, on the permuted lower triangle gathered from `K` without copying it
//! ([`super::permuted_lower`]). A large model's matrix is split in two parts and a separator
//! and factorised on two cores ([`super::split_cholesky`]).

use std::borrow::Cow;
use std::sync::Arc;

use faer::MatMut;
use nalgebra_sparse::CscMatrix;
use rayon::prelude::*;

use super::dense_cholesky::zero_padded;
use super::mesh::Mesh;
use super::node_ordered_cholesky::{NumericFactor, SymbolicFactor};
use super::separator::{split_nodes_of, NodeSplit, Side};
use super::split_cholesky::{SplitAnalysis, SplitFactor};
use super::vertex_ordering::{vertex_graph, vertex_led_node_order_of, vertex_order, VertexCells};
use crate::error::{Error, Result};
use crate::sparse::faer_llt::{FaerAnalysis, FaerFactor};
use crate::sparse::{Backend, DofOrder, Pattern};

/// The symbolic analysis a [`ConstrainedCholesky`] factorises on: of the whole matrix, or of its
/// two parts and their separator.
#[derive(Clone, Debug)]
pub enum Analysis {
    Whole(SymbolicFactor),
    Split(Arc<SplitAnalysis>),
    Faer(FaerAnalysis, (usize, usize)),
}

/// Fewest unknowns for which a model's factorisation is split over two cores.
/// Measured in the FEniCSx comparison (medians of five runs): at 8 008 unknowns 12.8 ms split
/// against 17.0 ms whole, at 3 700 (P1, and the linear edge locators of P2 models) 8-15 ms
/// against 9-21 ms.
pub const SPLIT_MIN_DOFS: usize = 3_000;

/// [`SPLIT_MIN_DOFS`], or the environment's `RINGCONTACT_SPLIT_MIN_DOFS` (to compare the split
/// factorisation with the whole one on the same model).
fn split_min_dofs() -> usize {
    std::env::var("RINGCONTACT_SPLIT_MIN_DOFS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(SPLIT_MIN_DOFS)
}

/// Rows of the refinement's residual computed per parallel task.
const RESIDUAL_ROWS_PER_TASK: usize = 4096;

/// Most separator unknowns a split may have (its Schur complement is dense).
pub const SPLIT_MAX_SEPARATOR_DOFS: usize = 2_000;

/// What a model's [`Analysis`] needs from its mesh alone: the vertex-led node order
/// ([`super::vertex_ordering`]) and, for a model of at least [`SPLIT_MIN_DOFS`] unknowns, a
/// split by a separator read off that order's elimination tree or a ring of the mesh, whichever
/// promises the shorter factorisation ([`super::separator`]). Needs no pattern, so it is
/// computed while the pattern is built.
pub struct MeshOrdering {
    order: Vec<usize>,
    split: Option<NodeSplit>,
    /// The backend the analysis is for (only [`Backend::Native`] uses the split).
    backend: Backend,
}

impl MeshOrdering {
    /// The ordering of `mesh`'s nodes (one vertex graph and one minimum-degree order of it for
    /// the node order and the split, which are then found side by side).
    pub fn of_mesh(mesh: &Mesh, backend: Backend) -> Self {
        Self::of_raised(mesh, backend, || mesh)
    }

    /// The ordering of the mesh `raised` gives, `vertex_mesh` with its degree raised: the vertex
    /// graph and its minimum-degree order, which need only the cells' vertices, are found on
    /// `vertex_mesh` before `raised` is called, so that the raising can run beside them. If the
    /// raised mesh's cells do not have `vertex_mesh`'s vertices (in the same order), they are
    /// found again on the raised mesh.
    pub fn of_raised<'m>(
        vertex_mesh: &Mesh,
        backend: Backend,
        raised: impl FnOnce() -> &'m Mesh,
    ) -> Self {
        let incidence = VertexCells::new(vertex_mesh);
        let graph = vertex_graph(vertex_mesh, &incidence);
        let vertices = vertex_order(&graph);
        let mesh = raised();
        if !same_vertices(vertex_mesh, mesh) {
            return Self::of_mesh(mesh, backend);
        }
        let wants_split =
            backend == Backend::Native && 2 * mesh.nodes.len() >= split_min_dofs();
        let (order, split) = rayon::join(
            || vertex_led_node_order_of(mesh, &incidence, &graph, &vertices),
            || {
                wants_split
                    .then(|| split_nodes_of(mesh, &graph, &vertices))
                    .flatten()
            },
        );
        Self {
            order,
            split,
            backend,
        }
    }
}

/// Whether `raised` has the cells of `vertex_mesh`, in the same order, with the same vertex
/// nodes (each cell's first three), and keeps `vertex_mesh`'s nodes' numbers (or is the same
/// mesh, as in [`MeshOrdering::of_mesh`]): then both have the same vertex graph.
fn same_vertices(vertex_mesh: &Mesh, raised: &Mesh) -> bool {
    std::ptr::eq(vertex_mesh, raised)
        || vertex_mesh.cell_count() == raised.cell_count()
            && raised.nodes.len() >= vertex_mesh.nodes.len()
            && (0..vertex_mesh.cell_count())
                .all(|c| vertex_mesh.cell(c)[..3] == raised.cell(c)[..3])
}

impl Analysis {
    /// The analysis of a model's stiffness pattern (compressed columns, both triangles, two dofs
    /// per node of the mesh `ordering` belongs to and an optional trailing dof), in its
    /// vertex-led order: split in two parts by its separator when the model has at least
    /// [`SPLIT_MIN_DOFS`] unknowns, the separator at most [`SPLIT_MAX_SEPARATOR_DOFS`] unknowns
    /// and no entry of `K` couples the two parts; whole otherwise. `beside` runs on the two cores beside
    /// the analysis (for a split, beside the second part's: [`SplitAnalysis::new_beside`]).
    pub fn of_ordering_beside<R: Send>(
        ordering: &MeshOrdering,
        col_offsets: &[usize],
        row_indices: &[usize],
        beside: impl FnOnce() -> R + Send,
    ) -> (Result<Self>, R) {
        let order = &ordering.order;
        let dofs = col_offsets.len().saturating_sub(1);
        if ordering.backend == Backend::Faer {
            let pattern = Pattern::new(col_offsets, row_indices);
            let analyse = || {
                let order = DofOrder::of_nodes(order, dofs)?;
                FaerAnalysis::new(&pattern, &order)
                    .map(|a| Analysis::Faer(a, (dofs, row_indices.len())))
            };
            return rayon::join(analyse, beside);
        }
        let whole = || SymbolicFactor::with_node_order(col_offsets, row_indices, order);
        let split = ordering.split.as_ref().filter(|split| {
            dofs >= split_min_dofs()
                && 2 * split.count(Side::Separator) + dofs % 2 <= SPLIT_MAX_SEPARATOR_DOFS
        });
        let Some(split) = split else {
            let (analysis, result) = rayon::join(whole, beside);
            return (analysis.map(Analysis::Whole), result);
        };
        match SplitAnalysis::new_beside(col_offsets, row_indices, order, split, beside) {
            (Ok(Some(analysis)), result) => (Ok(Analysis::Split(Arc::new(analysis))), result),
            (Ok(None), result) => (whole().map(Analysis::Whole), result),
            (Err(e), result) => (Err(e), result),
        }
    }

    /// Whether this analysis is of a pattern of `n` rows and `nnz` entries.
    pub fn fits(&self, n: usize, nnz: usize) -> bool {
        match self {
            Analysis::Whole(symbolic) => symbolic.fits(n, nnz),
            Analysis::Split(split) => split.fits(n, nnz),
            Analysis::Faer(_, shape) => *shape == (n, nnz),
        }
    }

    /// One phrase for traces: `whole`, or the parts' and the separator's unknowns, with the
    /// numeric factorisation's multiply-adds ([`super::node_ordered_cholesky::factorisation_work`]).
    pub fn describe(&self) -> String {
        match self {
            Analysis::Whole(symbolic) => format!("whole, work {:.3e}", symbolic.work()),
            Analysis::Faer(analysis, _) => format!("faer, nnz(L) {}", analysis.factor_len()),
            Analysis::Split(split) => {
                let [first, second] = split.part_sizes();
                let [first_work, second_work] = split.part_work();
                format!(
                    "split {first} + {second}, separator {}, work {first_work:.3e} + {second_work:.3e}",
                    split.separator_len()
                )
            }
        }
    }
}

/// A numeric factorisation on an [`Analysis`].
enum Factor {
    Whole(NumericFactor),
    Split(SplitFactor),
    Faer(FaerFactor),
}

impl Factor {
    /// Overwrite `rhs` (one or more columns) with `A⁻¹ rhs`.
    fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        match self {
            Factor::Whole(factor) => factor.solve_in_place(rhs),
            Factor::Split(factor) => factor.solve_in_place(rhs),
            Factor::Faer(factor) => factor.solve_in_place(rhs),
        }
    }
}

/// Cholesky solver bound to one stiffness matrix.
pub struct ConstrainedCholesky<'a> {
    matrix: &'a CscMatrix<f64>,
    analysis: Analysis,
    /// Where each column's diagonal entry is among `matrix`'s entries.
    diagonal: Cow<'a, [usize]>,
    /// Values of the permuted lower triangle of the constrained matrix (allocated at the first
    /// factorisation, reused by the next ones).
    lower_values: Vec<f64>,
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
    /// Symbolic analysis of the pattern of `matrix` (done once).
    ///
    /// Sets `faer`'s parallelism to sequential: on the 2-core machine the numeric factorisation
    /// takes 0.044 s sequential against 0.080 s parallel at 38 k unknowns, 1.47 s against 2.16 s
    /// at 706 k, and blocked solves of 64 right-hand sides 0.087 s against 0.153 s (the two
    /// cores are better used by the parallel element assembly and by independent states).
    pub fn new(matrix: &'a CscMatrix<f64>) -> Result<Self> {
        Self::with_backend(matrix, Backend::of_process())
    }

    /// [`Self::new`] on the given backend (a bare pattern: ordered on its node graph by the
    /// native backend, by `faer`'s AMD by the other).
    pub fn with_backend(matrix: &'a CscMatrix<f64>, backend: Backend) -> Result<Self> {
        let (offsets, rows) = (matrix.col_offsets(), matrix.row_indices());
        let analysis = match backend {
            Backend::Native => Analysis::Whole(SymbolicFactor::of_pattern(offsets, rows)?),
            Backend::Faer => Analysis::Faer(
                FaerAnalysis::with_amd(&Pattern::new(offsets, rows))?,
                (matrix.nrows(), matrix.nnz()),
            ),
        };
        Self::with_symbolic(matrix, analysis)
    }

    /// [`Self::new`] with the symbolic analysis of `matrix`'s pattern already done (for example
    /// while the matrix was assembled); an analysis of another pattern is an error.
    pub fn with_symbolic(matrix: &'a CscMatrix<f64>, analysis: Analysis) -> Result<Self> {
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
    /// it ([`super::assembly::StiffnessPattern::into_matrix_and_diagonal`]): the search for
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
        faer::set_global_parallelism(faer::Par::Seq);
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
            lower_values: Vec::new(),
            last: None,
            factorisations: 0,
            factorisation_seconds: 0.0,
            refine: true,
        })
    }

    /// Whether [`Self::solve`] refines its solution (one step of iterative refinement, on by
    /// default): worth its second triangular solve only where the answer is asked to within a
    /// few orders of magnitude of rounding (see [`Self::solve`]).
    pub fn refine_solutions(&mut self, refine: bool) {
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
    pub fn solve_unrefined(
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
            // element sizes from 1e-10 a to 1e6 a, and without it rounding left a floor of about
            // 4e-9 in the force of 10^6-unknown models (measured against the ring BEM).
            let b = rhs.clone();
            llt.solve_in_place(MatMut::from_column_major_slice_mut(&mut rhs, n, 1));
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
            llt.solve_in_place(MatMut::from_column_major_slice_mut(&mut residual, n, 1));
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
        let factor = match &self.analysis {
            Analysis::Whole(symbolic) => {
                let layout = symbolic.lower();
                self.lower_values.resize(layout.len(), 0.0);
                layout.gather(self.matrix.values(), constrained, &mut self.lower_values);
                Factor::Whole(NumericFactor::new(symbolic, &self.lower_values)?)
            }
            Analysis::Split(split) => {
                Factor::Split(SplitFactor::new(split, self.matrix.values(), constrained)?)
            }
            Analysis::Faer(analysis, _) => {
                let pattern =
                    Pattern::new(self.matrix.col_offsets(), self.matrix.row_indices());
                Factor::Faer(FaerFactor::new(
                    analysis,
                    &pattern,
                    self.matrix.values(),
                    constrained,
                )?)
            }
        };
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
        let mut block = zero_padded(n, dofs.len());
        for (c, &j) in dofs.iter().enumerate() {
            block[(j, c)] = 1.0;
        }
        if let Some((_, llt)) = &self.last {
            llt.solve_in_place(block.as_mut());
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
    pub fn product_at(&self, u: &[f64], dofs: &[usize]) -> Vec<f64> {
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
    use crate::fem::assembly::assemble_stiffness;
    use crate::fem::element::Lame;
    use crate::fem::mesh::{structured_rectangle, Degree};
    use crate::fem::solver::stiffness_rule;

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

    /// The ordering found with the vertex graph of the vertex mesh, beside the raising, is the
    /// ordering of the raised mesh; a "raised" mesh with other vertices gets its own.
    #[test]
    fn the_ordering_beside_the_raising_is_the_raised_meshs_own() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes/annulus-0.5-L1.msh");
        let vertex_mesh = crate::fem::msh::read_msh(&path).unwrap();
        assert_eq!(vertex_mesh.degree, Degree::Linear);
        let same = |a: &MeshOrdering, b: &MeshOrdering| {
            a.order == b.order
                && a.split.as_ref().map(|s| &s.sides) == b.split.as_ref().map(|s| &s.sides)
        };
        for degree in [Degree::Quadratic, Degree::Cubic] {
            let raised = vertex_mesh.with_degree(degree);
            let beside = MeshOrdering::of_raised(&vertex_mesh, Backend::Native, || &raised);
            let own = MeshOrdering::of_mesh(&raised, Backend::Native);
            assert!(beside.split.is_some(), "{degree:?}: the split is exercised");
            assert!(same(&beside, &own), "{degree:?}");
        }
        let other = structured_rectangle(2.0, 1.0, 30, 20, 1, 2, 3).with_degree(Degree::Quadratic);
        let beside = MeshOrdering::of_raised(&vertex_mesh, Backend::Native, || &other);
        assert_eq!(beside.order.len(), other.nodes.len());
        assert!(same(&beside, &MeshOrdering::of_mesh(&other, Backend::Native)));
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
