//! The default backend of the SPD seam: `faer`'s public sparse Cholesky (`LLᵀ`) with the
//! caller's elimination order passed as a custom ordering.
//!
//! [`FaerAnalysis::new`] is `faer::sparse::linalg::cholesky::factorize_symbolic_cholesky` with
//! `SymmetricOrdering::Custom(P)`; [`FaerFactor::new`] is `SymbolicCholesky::factorize_numeric_llt`
//! of the matrix whose constrained rows and columns are reduced to their diagonal, read from the
//! lower triangle; solves are `LltRef::solve_in_place_with_conj`. Nothing here reaches into
//! `faer`'s internal layouts.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

use super::{solver_error, DofOrder, Pattern};
use crate::error::Result;

/// Symbolic analysis of one pattern in one elimination order.
#[derive(Clone, Debug)]
pub(crate) struct FaerAnalysis {
    symbolic: Arc<SymbolicCholesky<usize>>,
}

impl FaerAnalysis {
    /// Analyse `pattern` (both triangles stored; the lower one is read) eliminated in `order`.
    pub fn new(pattern: &Pattern<'_>, order: &DofOrder) -> Result<Self> {
        let perm = PermRef::new_checked(&order.perm, &order.inverse, pattern.n());
        Self::ordered(pattern, SymmetricOrdering::Custom(perm))
    }

    /// Analyse `pattern` in `faer`'s own approximate-minimum-degree order (for a pattern that
    /// comes without a mesh).
    pub(crate) fn with_amd(pattern: &Pattern<'_>) -> Result<Self> {
        Self::ordered(pattern, SymmetricOrdering::Amd)
    }

    fn ordered(pattern: &Pattern<'_>, ordering: SymmetricOrdering<'_, usize>) -> Result<Self> {
        let symbolic =
            factorize_symbolic_cholesky(view(pattern)?, Side::Lower, ordering, Default::default())
                .map_err(|e| solver_error(format!("symbolic Cholesky analysis failed: {e:?}")))?;
        Ok(Self {
            symbolic: Arc::new(symbolic),
        })
    }

    /// Nonzeros of the factor `L`.
    pub(crate) fn factor_len(&self) -> usize {
        self.symbolic.len_val()
    }
}

/// A numeric factor `P K_C Pᵀ = L Lᵀ` on a [`FaerAnalysis`].
pub(crate) struct FaerFactor {
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
}

impl FaerFactor {
    /// Factorise the matrix with `pattern` and `values` whose rows and columns `constrained`
    /// keep only their diagonal (`K_C`); fails if `K_C` is not positive definite.
    pub fn new(
        analysis: &FaerAnalysis,
        pattern: &Pattern<'_>,
        values: &[f64],
        constrained: &[bool],
    ) -> Result<Self> {
        let reduced = pattern.reduced_lower_values(values, constrained);
        let view = view(pattern)?;
        let matrix = SparseColMatRef::new(view, &reduced);
        let symbolic = &analysis.symbolic;
        let par = Par::Seq;
        let mut memory = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|_| solver_error("out of memory for the Cholesky factorisation".into()))?;
        let mut factor = vec![0.0; symbolic.len_val()];
        symbolic
            .factorize_numeric_llt(
                &mut factor,
                matrix,
                Side::Lower,
                LltRegularization::default(),
                par,
                MemStack::new(&mut memory),
                Default::default(),
            )
            .map_err(|_| crate::sparse::not_positive_definite())?;
        Ok(Self {
            symbolic: Arc::clone(symbolic),
            values: factor,
        })
    }

    /// Overwrite `rhs` (one or more columns) with `K_C⁻¹ rhs`.
    pub(crate) fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let par = Par::Seq;
        let mut memory = MemBuffer::new(
            self.symbolic
                .solve_in_place_scratch::<f64>(rhs.ncols(), par),
        );
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            par,
            MemStack::new(&mut memory),
        );
    }
}

/// `pattern` as `faer`'s view.
fn view<'p>(pattern: &'p Pattern<'_>) -> Result<SymbolicSparseColMatRef<'p, usize>> {
    pattern.check()?;
    Ok(SymbolicSparseColMatRef::new_checked(
        pattern.n(),
        pattern.n(),
        pattern.col_offsets,
        None,
        pattern.row_indices,
    ))
}
