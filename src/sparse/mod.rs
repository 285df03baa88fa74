//! The sparse symmetric positive definite (SPD) solver layer: the one seam between the finite
//! elements and the linear algebra.
//!
//! The FE code asks this layer for four things, on a matrix `K` stored as compressed columns
//! with both triangles:
//!
//! - [`analyse`]`(pattern, ordering)`: the symbolic Cholesky analysis of `K`'s pattern in a
//!   given elimination order (done once per model);
//! - [`SpdAnalysis::factorise`]`(values, constrained)`: the numeric factorisation
//!   `P K_C Pᵀ = L Lᵀ` of `K` with the rows and columns of the constrained dofs reduced to their
//!   diagonal (`K_C`; the pattern, hence the analysis, is the same for every constraint set);
//! - [`SpdFactor::solve`] and [`SpdFactor::solve_many`]: `x = K_C⁻¹ b` for one or many `b`.
//!
//! Two backends implement it, chosen at run time ([`Backend`]): `faer`'s public sparse Cholesky
//! ([`faer_llt`], the default) and this crate's own factorisation on `faer`'s supernodal layout
//! ([`native`]), kept where it was measured faster on a user's path (docs/decisions.md).

pub mod faer_llt;

use std::str::FromStr;
use std::sync::OnceLock;

use crate::error::{Error, Result};

/// Which implementation of the seam factorises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// `faer`'s public sparse Cholesky ([`faer_llt`]), in one thread.
    Faer,
    /// This crate's supernodal factorisation on `faer`'s symbolic layout, split over two cores
    /// where the model admits a separator ([`native`]).
    Native,
}

impl Default for Backend {
    /// The backend of this process ([`Backend::of_process`]).
    fn default() -> Self {
        Self::of_process()
    }
}

impl Backend {
    /// The names the command line takes.
    pub const NAMES: [&'static str; 2] = ["faer", "native"];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Faer => "faer",
            Backend::Native => "native",
        }
    }

    /// The backend a model gets unless its options name another: measured 1.2-2x faster than
    /// [`Backend::Faer`] on the FEM's targets (docs/decisions.md, `benches/records/linear-solver.md`).
    pub const BUILT_IN: Backend = Backend::Native;

    /// The backend of this process: the one [`set_process_backend`] chose (the `verify`
    /// binary's `--linear-solver`), else the environment's `RINGCONTACT_LINEAR_SOLVER` (read,
    /// never set; an unknown name is ignored here and refused by the binary), else
    /// [`Backend::BUILT_IN`].
    pub fn of_process() -> Self {
        *PROCESS_BACKEND.get_or_init(|| {
            std::env::var(ENVIRONMENT_VARIABLE)
                .ok()
                .and_then(|v| v.parse().ok())
                .unwrap_or(Self::BUILT_IN)
        })
    }
}

impl FromStr for Backend {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "faer" => Ok(Backend::Faer),
            "native" => Ok(Backend::Native),
            other => Err(format!(
                "unknown linear solver '{other}': use one of {}",
                Backend::NAMES.join(", ")
            )),
        }
    }
}

static PROCESS_BACKEND: OnceLock<Backend> = OnceLock::new();

/// The environment variable naming the process's backend ([`Backend::of_process`]).
pub const ENVIRONMENT_VARIABLE: &str = "RINGCONTACT_LINEAR_SOLVER";

/// Choose the backend of every model this process builds without naming one (the `verify`
/// binary's `--linear-solver`); only the first call counts. Returns whether it was taken.
pub fn set_process_backend(backend: Backend) -> bool {
    PROCESS_BACKEND.set(backend).is_ok() || PROCESS_BACKEND.get() == Some(&backend)
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
            for k in self.col_offsets[col]..self.col_offsets[col + 1] {
                let row = self.row_indices[k];
                if row != col && (constrained[row] || constrained[col]) {
                    reduced[k] = 0.0;
                }
            }
        }
        reduced
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
        let pairs = n / 2;
        let mut perm = Vec::with_capacity(n);
        for &node in node_order {
            if node >= pairs {
                return Err(solver_error(format!(
                    "internal: node {node} of the elimination order is not one of the {pairs} nodes"
                )));
            }
            perm.extend([2 * node, 2 * node + 1]);
        }
        if n % 2 == 1 {
            perm.push(n - 1);
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
                "internal: the elimination order holds {} of the {pairs} nodes",
                node_order.len()
            )));
        }
        Ok(Self { perm, inverse })
    }
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
