//! Sparse Cholesky factorisation (`faer`'s symbolic analysis, the numeric factorisation of
//! [`crate::sparse::native::supernodal_numeric`]) with its fill-reducing ordering computed on the node graph
//! instead of the dof graph.
//!
//! The stiffness matrix has two dofs per node (`2i`, `2i + 1`), coupled to the same neighbours:
//! the minimum-degree ordering of the node graph (a quarter of the entries) expanded to the dofs,
//! `P = [2 π(0), 2 π(0) + 1, 2 π(1), ...]`, gives the factor the same fill as AMD on the dofs
//! at less cost (the node graph itself is built by merging each node's sorted columns, without
//! a sort). A
//! trailing odd dof (the far-field amplitude) is a node of its own. Any permutation gives the
//! same factorisation up to rounding, so this only changes time.
//!
//! The solver's models know their mesh and use a cheaper and better order instead
//! ([`SymbolicFactor::with_node_order`] with [`crate::discretisation::vertex_ordering::vertex_led_node_order`]:
//! AMD on the vertices only, 11-25 % fewer factorisation operations); the node-graph ordering
//! serves a bare pattern ([`SymbolicFactor::new`], [`SymbolicFactor::of_pattern`]).

use std::sync::Arc;

use faer::dyn_stack::MemStack;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

use crate::error::{Error, Result};
use crate::sparse::native::dense::zeroed_scratch;
use crate::sparse::native::permuted_lower::PermutedLower;
use crate::sparse::native::supernodal_numeric;
use crate::sparse::{minimum_degree_order, DofOrder};

fn solver_error(message: String) -> Error {
    Error::NoConvergence {
        method: "fem".into(),
        reason: message,
    }
}

/// Node of dof `d` for `n` dofs: `d / 2`, the trailing odd dof its own node.
fn node_of(d: usize, n: usize) -> usize {
    if d < n - n % 2 {
        d / 2
    } else {
        n / 2
    }
}

/// Append the union of two sorted lists without repeats to `out`.
fn merge_sorted(a: &[usize], b: &[usize], out: &mut Vec<usize>) {
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        let next = match (a.get(i), b.get(j)) {
            (Some(&x), Some(&y)) if x == y => {
                i += 1;
                j += 1;
                x
            }
            (Some(&x), Some(&y)) if x < y => {
                i += 1;
                x
            }
            (Some(&x), None) => {
                i += 1;
                x
            }
            (_, Some(&y)) => {
                j += 1;
                y
            }
            (None, None) => break,
        };
        out.push(next);
    }
}

/// The node graph of a dof pattern, `(offsets, rows)` in compressed sparse column form: node `m`
/// is a neighbour of node `k` when any dof of `m` couples to any dof of `k`.
fn node_graph(pattern: SymbolicSparseColMatRef<'_, usize>) -> (Vec<usize>, Vec<usize>) {
    let n = pattern.nrows();
    let nodes = n / 2 + n % 2;
    // A column's rows are sorted and `node_of` is monotone, so each column maps to a sorted node
    // list by dropping repeats; a node's columns (one or two) are merged without sorting.
    let column_nodes = |col: usize, out: &mut Vec<usize>| {
        out.clear();
        for row in pattern.row_idx_of_col(col) {
            let node = node_of(row, n);
            if out.last() != Some(&node) {
                out.push(node);
            }
        }
    };
    let mut offsets = Vec::with_capacity(nodes + 1);
    offsets.push(0);
    let mut rows = Vec::with_capacity(pattern.compute_nnz() / 4 + nodes);
    let (mut first, mut second) = (Vec::new(), Vec::new());
    for node in 0..nodes {
        let cols = if 2 * node + 1 < n - n % 2 {
            2 * node..2 * node + 2
        } else {
            n - 1..n
        };
        column_nodes(cols.start, &mut first);
        if cols.len() == 1 {
            rows.extend_from_slice(&first);
        } else {
            column_nodes(cols.start + 1, &mut second);
            merge_sorted(&first, &second, &mut rows);
        }
        offsets.push(rows.len());
    }
    (offsets, rows)
}

/// Approximate-minimum-degree ordering of the node graph of `pattern`, expanded to the dofs:
/// `(perm, perm_inverse)`.
fn node_graph_ordering(
    pattern: SymbolicSparseColMatRef<'_, usize>,
) -> Result<(Vec<usize>, Vec<usize>)> {
    let n = pattern.nrows();
    let (offsets, rows) = node_graph(pattern);
    let order = DofOrder::of_node_order(&minimum_degree_order(n / 2 + n % 2, &offsets, &rows), n)?;
    Ok((order.perm, order.inverse))
}

/// The pattern given as compressed columns (`col_offsets`, sorted `row_indices`) as a view.
fn checked_pattern<'p>(
    col_offsets: &'p [usize],
    row_indices: &'p [usize],
) -> Result<SymbolicSparseColMatRef<'p, usize>> {
    let n = col_offsets.len().saturating_sub(1);
    if col_offsets.last() != Some(&row_indices.len()) {
        return Err(solver_error(
            "internal: the pattern's offsets do not end at its entry count".into(),
        ));
    }
    Ok(SymbolicSparseColMatRef::new_checked(
        n,
        n,
        col_offsets,
        None,
        row_indices,
    ))
}

/// Symbolic Cholesky analysis of a symmetric pattern, ordered on its node graph
/// ([`Self::new`], [`Self::of_pattern`]) or in a given node order ([`Self::with_node_order`]).
#[derive(Clone, Debug)]
pub struct SymbolicFactor {
    inner: Arc<SymbolicCholesky<usize>>,
    /// The permuted lower triangle the numeric factorisation reads, laid out for this order.
    lower: Arc<PermutedLower>,
    /// Size and number of entries of the analysed pattern (both triangles).
    shape: (usize, usize),
}

impl SymbolicFactor {
    /// The numeric factorisation's multiply-adds ([`factorisation_work`]).
    pub fn work(&self) -> f64 {
        factorisation_work(supernodal_of(&self.inner))
    }

    /// Analyse the pattern given as compressed columns (`col_offsets`, sorted `row_indices`).
    pub(crate) fn of_pattern(col_offsets: &[usize], row_indices: &[usize]) -> Result<Self> {
        Self::new(checked_pattern(col_offsets, row_indices)?)
    }

    /// Whether this analysis is of a pattern of `n` rows and `nnz` entries.
    pub fn fits(&self, n: usize, nnz: usize) -> bool {
        self.shape == (n, nnz)
    }

    /// The layout of the permuted lower triangle that [`NumericFactor::new`] factorises.
    pub fn lower(&self) -> &PermutedLower {
        &self.lower
    }

    /// Analyse `pattern` (both triangles stored; the lower one is read).
    pub fn new(pattern: SymbolicSparseColMatRef<'_, usize>) -> Result<Self> {
        let (perm, perm_inverse) = node_graph_ordering(pattern)?;
        Self::with_dof_order(pattern, &perm, &perm_inverse)
    }

    /// Analyse the pattern (compressed columns, as [`Self::of_pattern`]) with the nodes eliminated
    /// in `node_order` (each of the `n / 2` nodes once, for example
    /// [`crate::discretisation::vertex_ordering::vertex_led_node_order`]); a trailing odd dof (the far-field
    /// amplitude) goes last.
    pub(crate) fn with_node_order(
        col_offsets: &[usize],
        row_indices: &[usize],
        node_order: &[usize],
    ) -> Result<Self> {
        let pattern = checked_pattern(col_offsets, row_indices)?;
        let n = pattern.nrows();
        let order = DofOrder::of_nodes(node_order, n)?;
        Self::with_dof_order(pattern, &order.perm, &order.inverse)
    }

    /// Analyse `pattern` with the dofs eliminated in the order `perm` (`perm_inverse` its
    /// inverse, both checked to be a permutation by the caller).
    fn with_dof_order(
        pattern: SymbolicSparseColMatRef<'_, usize>,
        perm: &[usize],
        perm_inverse: &[usize],
    ) -> Result<Self> {
        let n = pattern.nrows();
        let inner = supernodal_analysis(pattern, perm, perm_inverse)?;
        let lower = PermutedLower::new(pattern.col_ptr(), pattern.row_idx(), perm)?;
        Ok(Self {
            inner: Arc::new(inner),
            lower: Arc::new(lower),
            shape: (n, pattern.compute_nnz()),
        })
    }
}

/// Supernodal symbolic analysis of the lower triangle of `pattern` eliminated in the order
/// `perm` (`perm_inverse` its inverse).
fn supernodal_analysis(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    perm: &[usize],
    perm_inverse: &[usize],
) -> Result<SymbolicCholesky<usize>> {
    let ordering = PermRef::new_checked(perm, perm_inverse, pattern.nrows());
    let inner = factorize_symbolic_cholesky(
        pattern,
        Side::Lower,
        SymmetricOrdering::Custom(ordering),
        CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        },
    )
    .map_err(|e| solver_error(format!("symbolic Cholesky analysis failed: {e:?}")))?;
    if !matches!(inner.raw(), SymbolicCholeskyRaw::Supernodal(_)) || inner.perm().is_none() {
        return Err(solver_error(
            "internal: the symbolic analysis is not supernodal with the given order".into(),
        ));
    }
    Ok(inner)
}

/// The supernodal part of an analysis made by [`supernodal_analysis`] (which checks that it is
/// supernodal).
fn supernodal_of(analysis: &SymbolicCholesky<usize>) -> &SymbolicSupernodalCholesky<usize> {
    match analysis.raw() {
        SymbolicCholeskyRaw::Supernodal(supernodal) => supernodal,
        SymbolicCholeskyRaw::Simplicial(_) => unreachable!("checked by supernodal_analysis"),
    }
}

/// The numeric factorisation's work on a supernodal analysis, `Σ_j c_j²` multiply-adds over
/// the factor's columns `j` (`c_j` the entries of column `j` on and below the diagonal, the
/// supernodes' dense blocks counted whole, with the zeros `faer`'s relaxed supernodes carry: a
/// tridiagonal matrix of 10 rows in its own order, 37 without them, counts 385, one dense
/// supernode), for traces and comparisons of orderings.
pub(crate) fn factorisation_work(supernodal: &SymbolicSupernodalCholesky<usize>) -> f64 {
    let (begin, end) = (supernodal.supernode_begin(), supernodal.supernode_end());
    let rows = supernodal.col_ptr_for_row_idx();
    (0..supernodal.n_supernodes())
        .map(|s| {
            let below = (rows[s + 1] - rows[s]) as f64;
            let columns = end[s] - begin[s];
            (0..columns)
                .map(|j| {
                    let c = (columns - j) as f64 + below;
                    c * c
                })
                .sum::<f64>()
        })
        .sum()
}

/// The supernodal factor `L` of the matrix whose lower triangle (in the analysis's elimination
/// order) is `lower` with `lower_values`: `L`'s values in `faer`'s layout, supernode by
/// supernode ([`supernodal_numeric::factorise`], which zeroes each supernode's values just
/// before it forms them). Fails if the matrix is not positive definite.
pub(crate) fn factorise_supernodal(
    supernodal: &SymbolicSupernodalCholesky<usize>,
    lower: &SymbolicSparseColMat<usize>,
    lower_values: &[f64],
) -> Result<Vec<f64>> {
    if lower_values.len() != lower.compute_nnz() || lower.nrows() != supernodal.nrows() {
        return Err(solver_error(
            "internal: the values do not fit the permuted lower triangle".into(),
        ));
    }
    supernodal_numeric::factorise(supernodal, lower.as_ref(), lower_values).map_err(|e| {
        solver_error(format!(
            "the stiffness matrix is not positive definite (pivot {}): is the body held against \
             rigid motion?",
            e.column
        ))
    })
}

/// Numeric Cholesky factor `A = L Lᵀ` on a [`SymbolicFactor`].
#[derive(Clone, Debug)]
pub(crate) struct NumericFactor {
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
}

impl NumericFactor {
    /// Factorise `P A Pᵀ = L Lᵀ`, given the values of its lower triangle in the layout of
    /// [`SymbolicFactor::lower`] (gathered by [`PermutedLower::gather`]); fails if `A` is not
    /// positive definite ([`factorise_supernodal`]).
    pub fn new(symbolic: &SymbolicFactor, lower_values: &[f64]) -> Result<Self> {
        let inner = &symbolic.inner;
        let values =
            factorise_supernodal(supernodal_of(inner), symbolic.lower.pattern(), lower_values)?;
        Ok(Self {
            symbolic: Arc::clone(inner),
            values,
        })
    }

    /// Overwrite `rhs` (one or more columns) with `A⁻¹ rhs`. The scratch is zeroed: `faer`'s
    /// dense kernels compute on its padding ([`crate::sparse::native::dense`]).
    pub(crate) fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let mut memory = zeroed_scratch(
            self.symbolic
                .solve_in_place_scratch::<f64>(rhs.ncols(), Par::Seq),
        );
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut memory),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_node_graph_is_the_union_of_each_nodes_columns() {
        // 5 nodes and a trailing dof; the two dofs of a node couple to different nodes (the far
        // field couples the trailing dof to some dofs only), so columns must be merged.
        let n = 11;
        let couples = |row: usize, col: usize| {
            let (a, b) = (node_of(row, n), node_of(col, n));
            a.abs_diff(b) <= 1
                || (row + 2 * col).is_multiple_of(7)
                || (col + 2 * row).is_multiple_of(7)
        };
        let mut offsets = vec![0];
        let mut rows = Vec::new();
        for col in 0..n {
            rows.extend((0..n).filter(|&row| couples(row, col)));
            offsets.push(rows.len());
        }
        let pattern = SymbolicSparseColMat::new_checked(n, n, offsets, None, rows);
        let (graph_offsets, graph_rows) = node_graph(pattern.as_ref());
        for node in 0..6 {
            let mut expected: Vec<usize> = (0..n)
                .filter(|&col| node_of(col, n) == node)
                .flat_map(|col| (0..n).filter(move |&row| couples(row, col)))
                .map(|row| node_of(row, n))
                .collect();
            expected.sort_unstable();
            expected.dedup();
            assert_eq!(
                &graph_rows[graph_offsets[node]..graph_offsets[node + 1]],
                expected.as_slice(),
                "node {node}"
            );
        }
    }

    #[test]
    fn the_work_of_dense_blocks_is_the_sum_of_their_squared_column_counts() {
        // A block-diagonal pattern of `blocks` dense blocks of `size` dofs: whatever the order,
        // each block's factor is dense, with column counts size, size - 1, ..., 1, so the work is
        // blocks * size (size + 1) (2 size + 1) / 6 (the sum of the first `size` squares).
        for (blocks, size) in [(1, 6), (3, 4), (5, 2)] {
            let n = blocks * size;
            let mut offsets = vec![0];
            let mut rows = Vec::new();
            for col in 0..n {
                let block = col / size;
                rows.extend(block * size..(block + 1) * size);
                offsets.push(rows.len());
            }
            let symbolic = SymbolicFactor::of_pattern(&offsets, &rows).expect("analysis");
            let expected = (blocks * size * (size + 1) * (2 * size + 1) / 6) as f64;
            assert_eq!(symbolic.work(), expected, "{blocks} blocks of {size}");
        }
    }

    #[test]
    fn the_ordering_keeps_node_pairs_together_and_the_trailing_dof_alone() {
        // Path of 3 nodes (6 dofs) plus one extra dof coupled to everything.
        let n = 7;
        let mut offsets = vec![0];
        let mut rows = Vec::new();
        for col in 0..n {
            for row in 0..n {
                let (a, b) = (node_of(row, n), node_of(col, n));
                if a.abs_diff(b) <= 1 || a == 3 || b == 3 {
                    rows.push(row);
                }
            }
            offsets.push(rows.len());
        }
        let pattern = SymbolicSparseColMat::new_checked(n, n, offsets, None, rows);
        let (perm, inverse) = node_graph_ordering(pattern.as_ref()).unwrap();
        let mut sorted = perm.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..n).collect::<Vec<_>>());
        for (i, &d) in perm.iter().enumerate() {
            assert_eq!(inverse[d], i);
        }
        for pair in perm.iter().filter(|&&d| d < 6 && d % 2 == 0) {
            assert_eq!(perm[inverse[*pair] + 1], pair + 1, "{perm:?}");
        }
    }
}
