//! The sparse symmetric positive definite (SPD) solver layer: the one seam between the finite
//! elements and the linear algebra.
//!
//! The FE code asks this layer for four things, on a matrix `K` stored as compressed columns
//! with both triangles ([`Pattern`]):
//!
//! - [`analyse`]`(pattern, ordering, backend)`: the symbolic Cholesky analysis of `K`'s pattern
//!   in the elimination order the mesh gives ([`NodeOrdering`]; done once per model);
//! - [`Analysis::factorise`]`(pattern, values, constrained)`: the numeric factorisation
//!   `P K_C Pᵀ = L Lᵀ` of `K` with the rows and columns of the constrained dofs reduced to their
//!   diagonal (`K_C`; the pattern, hence the analysis, is the same for every constraint set);
//! - [`Factor::solve`] and [`Factor::solve_many`]: `x = K_C⁻¹ b` for one or many `b`.
//!
//! [`constrained::ConstrainedCholesky`] builds the FEM's solves on them (prescribed values,
//! iterative refinement, unit responses). Two backends implement the seam, chosen at run time
//! ([`Backend`], `verify --linear-solver`): `faer`'s public sparse Cholesky ([`faer_llt`]) and
//! this crate's own factorisation on `faer`'s supernodal layout ([`native`], split over two cores
//! where the model admits a separator). The native one is the default, 1.3-2.2x faster on the
//! user's paths (`benches/records/linear-solver.md`,
//! `docs/decisions.md`); `tests/suite/linear_solver_contract.rs` runs the FE suite on both. Only
//! [`native`] reads `faer`'s internal layouts or holds `unsafe` code.

pub mod constrained;
pub mod faer_llt;
pub mod native;

use std::str::FromStr;
use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMatRef;
use faer::MatMut;

use self::faer_llt::{FaerAnalysis, FaerFactor};
use self::native::split::{SplitAnalysis, SplitFactor};
use self::native::whole::{NumericFactor, SymbolicFactor};

use crate::error::{Error, Result};

/// Which implementation of the seam factorises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// `faer`'s public sparse Cholesky ([`faer_llt`]), in one thread.
    Faer,
    /// This crate's supernodal factorisation on `faer`'s symbolic layout, split over two cores
    /// where the model admits a separator and has at least `split_min_dofs` unknowns
    /// ([`native`]; [`SPLIT_MIN_DOFS`] by default).
    Native { split_min_dofs: usize },
}

impl Default for Backend {
    /// [`Backend::BUILT_IN`]: a model uses another only where its options name one.
    fn default() -> Self {
        Self::BUILT_IN
    }
}

impl Backend {
    /// The names the command line takes.
    pub const NAMES: [&'static str; 2] = ["faer", "native"];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Faer => "faer",
            Backend::Native { .. } => "native",
        }
    }

    /// Fewest unknowns for which a model's factorisation is split over two cores; `None` for a
    /// backend that never splits.
    pub fn split_min_dofs(self) -> Option<usize> {
        match self {
            Backend::Faer => None,
            Backend::Native { split_min_dofs } => Some(split_min_dofs),
        }
    }

    /// The backend a model gets unless its options name another: 1.3-2.2x faster than
    /// [`Backend::Faer`] on the FEM's targets (docs/decisions.md, `benches/records/linear-solver.md`).
    pub const BUILT_IN: Backend = Backend::Native {
        split_min_dofs: SPLIT_MIN_DOFS,
    };
}

impl FromStr for Backend {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "faer" => Ok(Backend::Faer),
            "native" => Ok(Backend::BUILT_IN),
            other => Err(format!(
                "unknown linear solver '{other}': use one of {}",
                Backend::NAMES.join(", ")
            )),
        }
    }
}

/// The environment variable a program reads for its backend (`verify`, the tests); the library
/// reads none: a model's backend is its options' `linear_solver`.
pub const ENVIRONMENT_VARIABLE: &str = "RINGCONTACT_LINEAR_SOLVER";

/// The symbolic analysis of one pattern on one backend ([`analyse`], [`analyse_bare`]): what
/// every numeric factorisation of that pattern reuses.
#[derive(Clone, Debug)]
pub struct Analysis {
    kind: AnalysisKind,
    /// Rows and stored entries of the analysed pattern.
    shape: (usize, usize),
}

#[derive(Clone, Debug)]
enum AnalysisKind {
    Faer(FaerAnalysis),
    NativeWhole(SymbolicFactor),
    NativeSplit(Arc<SplitAnalysis>),
}

/// A numeric factorisation `P K_C Pᵀ = L Lᵀ` ([`Analysis::factorise`]).
pub struct Factor {
    kind: FactorKind,
}

enum FactorKind {
    Faer(FaerFactor),
    NativeWhole(NumericFactor),
    NativeSplit(SplitFactor),
}

/// [`analyse`] with `beside` run on the other core meanwhile (the FEM assembles the values
/// there): returns both results.
///
/// The native backend splits the model in two parts by `ordering`'s separator when it has at
/// least [`Backend::split_min_dofs`] unknowns, the separator at most
/// [`SPLIT_MAX_SEPARATOR_DOFS`] and no entry of `K` couples the parts; otherwise it factorises
/// the whole matrix.
pub fn analyse_beside<R: Send>(
    pattern: Pattern<'_>,
    ordering: &NodeOrdering,
    backend: Backend,
    beside: impl FnOnce() -> R + Send,
) -> (Result<Analysis>, R) {
    let (col_offsets, row_indices) = (pattern.col_offsets, pattern.row_indices);
    let shape = (pattern.n(), pattern.nnz());
    let dofs = pattern.n();
    let order = &ordering.order;
    let done = |kind: Result<AnalysisKind>| kind.map(|kind| Analysis { kind, shape });
    if backend == Backend::Faer {
        let analyse = || {
            let order = DofOrder::of_nodes(order, dofs)?;
            FaerAnalysis::new(&pattern, &order).map(AnalysisKind::Faer)
        };
        let (kind, result) = rayon::join(analyse, beside);
        return (done(kind), result);
    }
    let whole = || {
        SymbolicFactor::with_node_order(col_offsets, row_indices, order)
            .map(AnalysisKind::NativeWhole)
    };
    let split = ordering.split.as_ref().filter(|split| {
        backend.split_min_dofs().is_some_and(|least| dofs >= least)
            && 2 * split.count(Side::Separator) + dofs % 2 <= SPLIT_MAX_SEPARATOR_DOFS
    });
    let Some(split) = split else {
        let (kind, result) = rayon::join(whole, beside);
        return (done(kind), result);
    };
    match SplitAnalysis::new_beside(col_offsets, row_indices, order, split, beside) {
        (Ok(Some(analysis)), result) => (
            done(Ok(AnalysisKind::NativeSplit(Arc::new(analysis)))),
            result,
        ),
        (Ok(None), result) => (done(whole()), result),
        (Err(e), result) => (Err(e), result),
    }
}

/// The symbolic analysis of `pattern` (both triangles stored, sorted rows; two dofs per node of
/// `ordering`'s mesh and an optional trailing dof) eliminated in `ordering` on `backend`.
pub fn analyse(
    pattern: Pattern<'_>,
    ordering: &NodeOrdering,
    backend: Backend,
) -> Result<Analysis> {
    analyse_beside(pattern, ordering, backend, || ()).0
}

/// The analysis of a pattern that comes without a mesh: ordered on its node graph by the native
/// backend, by `faer`'s AMD by the other.
pub fn analyse_bare(pattern: Pattern<'_>, backend: Backend) -> Result<Analysis> {
    let shape = (pattern.n(), pattern.nnz());
    let kind = match backend {
        Backend::Native { .. } => AnalysisKind::NativeWhole(SymbolicFactor::of_pattern(
            pattern.col_offsets,
            pattern.row_indices,
        )?),
        Backend::Faer => AnalysisKind::Faer(FaerAnalysis::with_amd(&pattern)?),
    };
    Ok(Analysis { kind, shape })
}

impl Analysis {
    /// Whether this analysis is of a pattern of `n` rows and `nnz` entries.
    pub fn fits(&self, n: usize, nnz: usize) -> bool {
        self.shape == (n, nnz)
    }

    /// One phrase for traces: the backend, whole or split (the parts' and the separator's
    /// unknowns), and the factor's size or work.
    pub fn describe(&self) -> String {
        match &self.kind {
            AnalysisKind::Faer(analysis) => format!("faer, nnz(L) {}", analysis.factor_len()),
            AnalysisKind::NativeWhole(symbolic) => {
                format!("whole, work {:.3e}", symbolic.work())
            }
            AnalysisKind::NativeSplit(split) => {
                let [first, second] = split.part_sizes();
                let [first_work, second_work] = split.part_work();
                format!(
                    "split {first} + {second}, separator {}, work {first_work:.3e} + \
                     {second_work:.3e}",
                    split.separator_len()
                )
            }
        }
    }

    /// Factorise `K_C`: the matrix of the analysed `pattern` with `values`, its rows and columns
    /// `constrained` reduced to their diagonal (`K_C`'s off-diagonal entries there are zero, so
    /// the constraint set never changes the pattern). Fails if `K_C` is not positive definite.
    pub fn factorise(
        &self,
        pattern: Pattern<'_>,
        values: &[f64],
        constrained: &[bool],
    ) -> Result<Factor> {
        if !self.fits(pattern.n(), pattern.nnz())
            || values.len() != pattern.nnz()
            || constrained.len() != pattern.n()
        {
            return Err(solver_error(
                "internal: the values or constraints do not fit the analysed pattern".into(),
            ));
        }
        let kind = match &self.kind {
            AnalysisKind::Faer(analysis) => {
                FactorKind::Faer(FaerFactor::new(analysis, &pattern, values, constrained)?)
            }
            AnalysisKind::NativeWhole(symbolic) => {
                let lower = symbolic.lower().gathered(values, constrained);
                FactorKind::NativeWhole(NumericFactor::new(symbolic, &lower)?)
            }
            AnalysisKind::NativeSplit(split) => {
                FactorKind::NativeSplit(SplitFactor::new(split, values, constrained)?)
            }
        };
        Ok(Factor { kind })
    }
}

impl Factor {
    /// Overwrite `rhs` with `K_C⁻¹ rhs`.
    pub fn solve(&self, rhs: &mut [f64]) {
        let n = rhs.len();
        self.solve_many(MatMut::from_column_major_slice_mut(rhs, n, 1));
    }

    /// Overwrite each column of `rhs` with `K_C⁻¹` times it (one blocked solve).
    pub fn solve_many(&self, rhs: MatMut<'_, f64>) {
        match &self.kind {
            FactorKind::Faer(factor) => factor.solve_in_place(rhs),
            FactorKind::NativeWhole(factor) => factor.solve_in_place(rhs),
            FactorKind::NativeSplit(factor) => factor.solve_in_place(rhs),
        }
    }
}

/// A symmetric sparsity pattern as compressed columns: `col_offsets` (`n + 1` entries) and the
/// sorted `row_indices` of each column, both triangles stored.
#[derive(Clone, Copy, Debug)]
pub struct Pattern<'a> {
    pub col_offsets: &'a [usize],
    pub row_indices: &'a [usize],
}

impl<'a> Pattern<'a> {
    /// The pattern of the given compressed columns.
    pub fn new(col_offsets: &'a [usize], row_indices: &'a [usize]) -> Self {
        Self {
            col_offsets,
            row_indices,
        }
    }

    /// Rows (and columns).
    pub fn n(&self) -> usize {
        self.col_offsets.len().saturating_sub(1)
    }

    /// Stored entries.
    pub fn nnz(&self) -> usize {
        self.row_indices.len()
    }

    /// That the offsets end at the entry count (the rest `faer` checks).
    fn check(&self) -> Result<()> {
        if self.col_offsets.last() != Some(&self.row_indices.len()) {
            return Err(solver_error(
                "internal: the pattern's offsets do not end at its entry count".into(),
            ));
        }
        Ok(())
    }

    /// The values of `K_C`: `values` with every off-diagonal entry in a constrained row or
    /// column set to zero.
    fn reduced_lower_values(&self, values: &[f64], constrained: &[bool]) -> Vec<f64> {
        let mut reduced = values.to_vec();
        for col in 0..self.n() {
            let entries = self.col_offsets[col]..self.col_offsets[col + 1];
            for (value, &row) in reduced[entries.clone()]
                .iter_mut()
                .zip(&self.row_indices[entries])
            {
                if row != col && (constrained[row] || constrained[col]) {
                    *value = 0.0;
                }
            }
        }
        reduced
    }
}

/// Which part of the split a node belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    First,
    Second,
    Separator,
}

/// The side of every node of a mesh: the two parts a split factorisation
/// ([`native::split`]) factorises on two cores, and their separator.
#[derive(Clone, Debug)]
pub struct NodeSplit {
    pub sides: Vec<Side>,
}

impl NodeSplit {
    /// Number of nodes on `side`.
    pub fn count(&self, side: Side) -> usize {
        self.sides.iter().filter(|&&s| s == side).count()
    }
}

/// An elimination order of the dofs: `perm[i]` is the dof eliminated `i`-th, `inverse` its
/// inverse.
#[derive(Clone, Debug)]
pub struct DofOrder {
    pub perm: Vec<usize>,
    pub inverse: Vec<usize>,
}

impl DofOrder {
    /// Expand an elimination order of the nodes to the `n` dofs: node `m` is dofs `2m`, `2m + 1`;
    /// for odd `n` a trailing dof `n - 1` (the far-field amplitude) goes last. An order that is
    /// not a permutation of the `n / 2` nodes is an error.
    pub fn of_nodes(node_order: &[usize], n: usize) -> Result<Self> {
        if n.is_multiple_of(2) {
            return Self::of_node_order(node_order, n);
        }
        let mut nodes = Vec::with_capacity(node_order.len() + 1);
        nodes.extend_from_slice(node_order);
        nodes.push(n / 2);
        Self::of_node_order(&nodes, n)
    }

    /// [`Self::of_nodes`] with the trailing dof of an odd `n` given its place in `node_order`
    /// as node `n / 2` (a minimum-degree order of the node graph puts it where it falls).
    pub fn of_node_order(node_order: &[usize], n: usize) -> Result<Self> {
        let (pairs, nodes) = (n / 2, n / 2 + n % 2);
        let mut perm = Vec::with_capacity(n);
        for &node in node_order {
            match node {
                m if m < pairs => perm.extend([2 * m, 2 * m + 1]),
                m if m < nodes => perm.push(n - 1),
                m => {
                    return Err(solver_error(format!(
                        "internal: node {m} of the elimination order is not one of the {nodes} \
                         nodes"
                    )))
                }
            }
        }
        let mut inverse = vec![usize::MAX; n];
        for (i, &d) in perm.iter().enumerate() {
            if inverse[d] != usize::MAX {
                return Err(solver_error(format!(
                    "internal: node {} appears twice in the elimination order",
                    d / 2
                )));
            }
            inverse[d] = i;
        }
        if perm.len() != n {
            return Err(solver_error(format!(
                "internal: the elimination order holds {} of the {nodes} nodes",
                node_order.len()
            )));
        }
        Ok(Self { perm, inverse })
    }
}

/// What the analysis needs to know of the mesh, computed by the discretisation
/// (`crate::discretisation::node_ordering::node_ordering`): the order in which to eliminate the nodes
/// (two dofs each) and, for the native backend, a split of the nodes in two parts and a
/// separator.
#[derive(Clone, Debug)]
pub struct NodeOrdering {
    pub order: Vec<usize>,
    pub split: Option<NodeSplit>,
}

/// Fewest unknowns for which a model's factorisation is split over two cores: below it the
/// split gains nothing (docs/decisions.md, "Where the constants come from").
pub const SPLIT_MIN_DOFS: usize = 3_000;

/// Most separator unknowns a split may have (its Schur complement is dense).
pub const SPLIT_MAX_SEPARATOR_DOFS: usize = 2_000;

/// Approximate-minimum-degree order (`faer`'s AMD) of a graph of `count` vertices given as
/// compressed columns (`offsets`, sorted `rows`, each vertex its own neighbour): the vertices in
/// the order to eliminate them.
pub fn minimum_degree_order(count: usize, offsets: &[usize], rows: &[usize]) -> Vec<usize> {
    let graph = SymbolicSparseColMatRef::new_checked(count, count, offsets, None, rows);
    let (mut perm, mut perm_inverse) = (vec![0usize; count], vec![0usize; count]);
    let mut memory = MemBuffer::new(amd::order_scratch::<usize>(count, graph.compute_nnz()));
    let ordered = amd::order(
        &mut perm,
        &mut perm_inverse,
        graph.as_ref(),
        Default::default(),
        MemStack::new(&mut memory),
    );
    if ordered.is_err() {
        // AMD only fails on allocation; the identity is still a valid (slower) ordering.
        perm = (0..count).collect();
    }
    perm
}

pub(crate) fn solver_error(message: String) -> Error {
    Error::NoConvergence {
        method: "fem".into(),
        reason: message,
    }
}

pub(crate) fn not_positive_definite() -> Error {
    solver_error(
        "the stiffness matrix is not positive definite: is the body held against rigid motion?"
            .into(),
    )
}
