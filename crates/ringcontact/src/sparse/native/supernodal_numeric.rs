//! Numeric supernodal Cholesky factorisation `A = L Lᵀ` on `faer`'s symbolic analysis, left-looking
//! with linked lists of descendants (the scheme of CHOLMOD's supernodal factorisation).
//!
//! Supernode `s` (columns `s_start..s_end`; rows: its own, then its pattern's) is formed as
//!
//! ```text
//!     P_s = A_s − Σ_d L_d,below L_d,midᵀ,   L_s,top = chol(P_s,top),   L_s,bot = P_s,bot L_s,top⁻ᵀ
//! ```
//!
//! over the descendants `d` whose pattern has rows in `s_start..s_end` (`mid`: those rows;
//! `below`: those and every later row of `d`'s pattern). Each descendant waits in the list of the
//! next supernode its pattern reaches, with the position in its pattern where that supernode's
//! rows begin, so that position is never searched for (only the count of those rows, by
//! bisection of the rest). An update is one dense product `L_d,below L_d,midᵀ`
//! (`faer`'s matrix kernels) into a scratch block, then subtracted through a map of its rows to
//! the panel's. A panel at most [`SMALL_WIDTH`] columns wide is factorised column by column in
//! plain loops, a wider one by `faer`'s dense Cholesky and triangular solve. The values are laid
//! out as `faer`'s, so `faer`'s `SupernodalLltRef` and this crate's substitutions read them; the
//! part above the diagonal of a supernode's diagonal block is not part of `L` and no solve reads
//! it (zero after the plain loops; `faer`'s kernels may leave values there, as `faer`'s own
//! numeric factorisation does).
//!
//! Each supernode's values are zeroed just before they are formed, while they are about to be
//! used, instead of in a pass over the whole factor first (the only `unsafe` here: the factor's
//! buffer is read as `f64` only where it has been written).
//!
//! `faer::sparse::linalg::cholesky::supernodal::factorize_supernodal_numeric_llt` computes the
//! same factor up to rounding (the test compares them), but it takes a zeroed buffer and zeroes
//! it again, searches each descendant's pattern twice per update, builds two index arrays and
//! dispatches a generic scatter-product per update: costs that weigh on the many small
//! supernodes of 2-D finite-element matrices.

use std::mem::MaybeUninit;

use faer::dyn_stack::MemStack;
use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch, LltError};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::SymbolicSparseColMatRef;
use faer::{Accum, MatMut, MatRef, Par};

use crate::sparse::native::dense::zeroed_scratch;

/// A pivot `≤ 0` (or not a number) met: the matrix is not positive definite.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct NonPositivePivot {
    /// The column (in elimination order) whose pivot it was.
    pub column: usize,
}

/// End of a descendant list.
const NONE: usize = usize::MAX;

/// Panels at most this many columns wide are factorised in plain loops, wider ones by `faer`'s
/// blocked kernels (8 and 32 are no faster).
const SMALL_WIDTH: usize = 16;

/// Factorise `A = L Lᵀ` (module documentation) and return `L`'s values (`symbolic.len_val()` of
/// them, in `faer`'s layout); `a_lower` and `a_values` hold `A`'s lower triangle in elimination
/// order (rows in any order; entries above the diagonal are skipped). Fails at the first pivot
/// that is not positive.
pub(crate) fn factorise(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    a_lower: SymbolicSparseColMatRef<'_, usize>,
    a_values: &[f64],
) -> Result<Vec<f64>, NonPositivePivot> {
    let n = symbolic.nrows();
    let n_super = symbolic.n_supernodes();
    let len = symbolic.len_val();
    let val_ptr = symbolic.col_ptr_for_val();
    assert!(
        a_lower.nrows() == n && a_lower.ncols() == n && val_ptr[n_super] == len,
        "internal: the matrix's size or the factor's layout is not the analysis's"
    );
    let begin = symbolic.supernode_begin();
    let end = symbolic.supernode_end();
    // A supernode's rows below its diagonal block, in increasing order.
    let pattern_of = |s: usize| symbolic.supernode(s).pattern();
    let Extents {
        super_of,
        widest,
        tallest,
    } = Extents::of(symbolic);
    let mut lists = DescendantLists::new(n_super);
    // The current panel's row of each global row (its own columns, then its pattern), or NONE.
    let mut local = vec![NONE; n];
    let mut row_map = vec![0usize; tallest];
    let mut update = vec![0.0; tallest * widest.max(1)];
    // Zeroed, as every scratch handed to `faer`'s dense kernels here ([`zeroed_scratch`]).
    let mut memory = zeroed_scratch(cholesky_in_place_scratch::<f64>(
        widest,
        Par::Seq,
        Default::default(),
    ));
    // The factor's values, each panel zeroed just before it is formed (while it is about to be
    // in cache) instead of in a pass over the whole factor first.
    let mut values: Vec<f64> = Vec::with_capacity(len);
    let base = values.as_mut_ptr();
    for s in 0..n_super {
        let (s_start, s_end) = (begin[s], end[s]);
        let width = s_end - s_start;
        let pattern = pattern_of(s);
        let rows = width + pattern.len();
        // Every row of the panel by its global index: its own columns first, then its pattern.
        set_local_rows(&mut local, s_start..s_end, pattern);
        let (panel_start, panel_end) = (val_ptr[s], val_ptr[s + 1]);
        // SAFETY: `values` has room for `len ≥ panel_end` values, so the panel's range lies in
        // its allocation; zero bytes are the value +0.0.
        unsafe { std::ptr::write_bytes(base.add(panel_start), 0, panel_end - panel_start) };
        // SAFETY: every value before `panel_end` is written (the earlier panels when they were
        // formed, this one just now), and no other reference to the buffer exists meanwhile.
        let written = unsafe { std::slice::from_raw_parts_mut(base, panel_end) };
        let (done, panel) = written.split_at_mut(panel_start);
        add_columns_of_a(panel, rows, s_start..s_end, (a_lower, a_values), &local);
        // The descendants' updates.
        let mut d = lists.take(s);
        while d != NONE {
            let following = lists.next[d];
            let d_width = end[d] - begin[d];
            let d_pattern = pattern_of(d);
            let d_rows = d_width + d_pattern.len();
            let first = lists.position[d];
            let below = &d_pattern[first..];
            let mid = below.partition_point(|&r| r < s_end);
            let d_values = &done[val_ptr[d]..val_ptr[d + 1]];
            for (slot, &r) in row_map.iter_mut().zip(below) {
                *slot = local[r];
            }
            let below_block = MatRef::from_column_major_slice_with_stride(
                &d_values[d_width + first..],
                below.len(),
                d_width,
                d_rows,
            );
            subtract_update(
                panel,
                rows,
                below_block,
                mid,
                &row_map[..below.len()],
                &mut update,
            );
            // On to the next supernode d's pattern reaches.
            let after = first + mid;
            if after < d_pattern.len() {
                lists.link(d, after, super_of[d_pattern[after]]);
            }
            d = following;
        }
        factor_panel(panel, rows, width, s_start, &mut memory)?;
        clear_local_rows(&mut local, s_start..s_end, pattern);
        if let Some(&row) = pattern.first() {
            lists.link(s, 0, super_of[row]);
        }
    }
    // SAFETY: the panels cover `0..len` (`val_ptr` runs from 0 to `len`), each written above.
    unsafe { values.set_len(len) };
    Ok(values)
}

/// Each column's supernode, and the widest and the tallest panel (columns, rows).
struct Extents {
    super_of: Vec<usize>,
    widest: usize,
    tallest: usize,
}

impl Extents {
    fn of(symbolic: &SymbolicSupernodalCholesky<usize>) -> Self {
        let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
        let mut super_of = vec![0usize; symbolic.nrows()];
        let (mut widest, mut tallest) = (0, 0);
        for s in 0..symbolic.n_supernodes() {
            super_of[begin[s]..end[s]].fill(s);
            widest = widest.max(end[s] - begin[s]);
            tallest = tallest.max(end[s] - begin[s] + symbolic.supernode(s).pattern().len());
        }
        Extents {
            super_of,
            widest,
            tallest,
        }
    }
}

/// The supernodes whose updates each supernode still awaits, as linked lists: `head[s]`, then
/// `next[d]`; `position[d]` is where in `d`'s pattern the rows of the supernode whose list `d`
/// is in begin.
struct DescendantLists {
    head: Vec<usize>,
    next: Vec<usize>,
    position: Vec<usize>,
}

impl DescendantLists {
    fn new(supernodes: usize) -> Self {
        DescendantLists {
            head: vec![NONE; supernodes],
            next: vec![NONE; supernodes],
            position: vec![0; supernodes],
        }
    }

    /// The first of `s`'s list, the list emptied.
    #[inline]
    fn take(&mut self, s: usize) -> usize {
        std::mem::replace(&mut self.head[s], NONE)
    }

    /// Put `d` on the list of supernode `t`, whose rows begin at `position` in `d`'s pattern.
    #[inline]
    fn link(&mut self, d: usize, position: usize, t: usize) {
        self.position[d] = position;
        self.next[d] = self.head[t];
        self.head[t] = d;
    }
}

/// The panel's row of each global row: its own `columns` first, then its `pattern`.
#[inline]
fn set_local_rows(local: &mut [usize], columns: std::ops::Range<usize>, pattern: &[usize]) {
    let width = columns.len();
    for (i, slot) in local[columns].iter_mut().enumerate() {
        *slot = i;
    }
    for (i, &row) in pattern.iter().enumerate() {
        local[row] = width + i;
    }
}

/// Add `A`'s `columns` (its lower triangle, rows in any order) into the panel of `rows` rows,
/// each row at its `local` place.
#[inline]
fn add_columns_of_a(
    panel: &mut [f64],
    rows: usize,
    columns: std::ops::Range<usize>,
    (a_lower, a_values): (SymbolicSparseColMatRef<'_, usize>, &[f64]),
    local: &[usize],
) {
    let (a_offsets, a_rows) = (a_lower.col_ptr(), a_lower.row_idx());
    let first = columns.start;
    for j in columns {
        let column = &mut panel[(j - first) * rows..][..rows];
        for k in a_offsets[j]..a_offsets[j + 1] {
            let i = a_rows[k];
            if i >= j {
                column[local[i]] += a_values[k];
            }
        }
    }
}

/// Undo [`set_local_rows`]: every row of the panel back to `NONE`.
#[inline]
fn clear_local_rows(local: &mut [usize], columns: std::ops::Range<usize>, pattern: &[usize]) {
    local[columns].fill(NONE);
    for &row in pattern {
        local[row] = NONE;
    }
}

/// `panel −= below · below[..mid]ᵀ`, scattered: `below` is a descendant's `L_d,below` (its
/// first `mid` rows are the panel's own columns), and its row `i` lands in the panel's row
/// `row_map[i]` (for `i < mid` that is also the panel's column of that row). Only the lower
/// trapezoid (row `i ≥` column `j`) is subtracted. `update` is scratch of at least
/// `below.nrows() · mid` values.
fn subtract_update(
    panel: &mut [f64],
    rows: usize,
    below: MatRef<'_, f64>,
    mid: usize,
    row_map: &[usize],
    update: &mut [f64],
) {
    let count = below.nrows();
    let update = &mut update[..count * mid];
    matmul(
        MatMut::from_column_major_slice_mut(update, count, mid),
        Accum::Replace,
        below,
        below.subrows(0, mid).transpose(),
        1.0,
        Par::Seq,
    );
    for (jj, column) in update.chunks_exact(count).enumerate() {
        let target = &mut panel[row_map[jj] * rows..][..rows];
        for (&row, &u) in row_map[jj..].iter().zip(&column[jj..]) {
            target[row] -= u;
        }
    }
}

/// Factorise a supernode's panel (`rows` × `width`, column-major, updates applied): the top
/// block's Cholesky factor, then the rows below it solved against it.
fn factor_panel(
    panel: &mut [f64],
    rows: usize,
    width: usize,
    s_start: usize,
    memory: &mut [MaybeUninit<u8>],
) -> Result<(), NonPositivePivot> {
    if width <= SMALL_WIDTH {
        // Column by column (left-looking within the panel): column j less Σ_{k<j} L_jk L_k,
        // then divided by its pivot's square root.
        for j in 0..width {
            let (left, right) = panel.split_at_mut(j * rows);
            let column = &mut right[j..rows];
            for k in 0..j {
                let column_k = &left[k * rows + j..(k + 1) * rows];
                let a = column_k[0];
                for (c, &l) in column.iter_mut().zip(column_k) {
                    *c -= l * a;
                }
            }
            let pivot = column[0];
            if pivot.is_nan() || pivot <= 0.0 {
                return Err(NonPositivePivot {
                    column: s_start + j,
                });
            }
            let root = pivot.sqrt();
            column[0] = root;
            let inverse = 1.0 / root;
            for c in &mut column[1..] {
                *c *= inverse;
            }
        }
        return Ok(());
    }
    let mut panel = MatMut::from_column_major_slice_mut(panel, rows, width);
    cholesky_in_place(
        panel.rb_mut().subrows_mut(0, width),
        Default::default(),
        Par::Seq,
        MemStack::new(memory),
        Default::default(),
    )
    .map_err(|LltError::NonPositivePivot { index }| NonPositivePivot {
        column: s_start + index,
    })?;
    let (top, bottom) = panel.split_at_row_mut(width);
    solve_lower_triangular_in_place(top.rb(), bottom.transpose_mut(), Par::Seq);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretisation::assembly::assemble_stiffness;
    use crate::discretisation::element::Lame;
    use crate::discretisation::quadrature::stiffness_rule;
    use crate::discretisation::vertex_ordering::vertex_led_node_order;
    use crate::mesh::triangulation::{structured_rectangle, tags, Degree};
    use crate::sparse::native::node_pair_analysis::supernodal_of_lower;
    use crate::sparse::native::permuted_lower::PermutedLower;
    use faer::dyn_stack::MemBuffer;
    use faer::sparse::linalg::cholesky::supernodal::{
        factorize_supernodal_numeric_llt, factorize_supernodal_numeric_llt_scratch,
    };
    use faer::sparse::SparseColMatRef;

    /// The permuted lower triangle of a rectangle's stiffness matrix (its diagonal raised by
    /// `shift` times its mean, which makes it positive definite: alone it has the rigid
    /// axial translation) and its supernodal analysis.
    fn rectangle_system(
        degree: Degree,
        shift: f64,
    ) -> (PermutedLower, Vec<f64>, SymbolicSupernodalCholesky<usize>) {
        let material = Lame::from_young_poisson(1.0, 0.3);
        let mesh = structured_rectangle(2.0, 1.0, 16, 8, tags::CONTACT, tags::AXIS, tags::FAR)
            .with_degree(degree);
        let k = assemble_stiffness(&mesh, &material, &stiffness_rule(degree)).unwrap();
        let order: Vec<usize> = vertex_led_node_order(&mesh)
            .into_iter()
            .flat_map(|m| [2 * m, 2 * m + 1])
            .collect();
        let mut values = k.values().to_vec();
        let diagonal: Vec<usize> = (0..k.ncols())
            .map(|col| {
                let range = k.col_offsets()[col]..k.col_offsets()[col + 1];
                range.start
                    + k.row_indices()[range]
                        .iter()
                        .position(|&r| r == col)
                        .unwrap()
            })
            .collect();
        let mean = diagonal.iter().map(|&d| values[d]).sum::<f64>() / diagonal.len() as f64;
        for &d in &diagonal {
            values[d] += shift * mean;
        }
        let lower = PermutedLower::new(k.col_offsets(), k.row_indices(), &order).unwrap();
        let lower_values = lower.gathered(&values, &vec![false; k.ncols()]);
        let symbolic = supernodal_of_lower(lower.pattern().as_ref()).unwrap();
        (lower, lower_values, symbolic)
    }

    /// `faer`'s own numeric factorisation of the same matrix on the same analysis: the
    /// independent reference.
    fn faer_factor(
        lower: &PermutedLower,
        lower_values: &[f64],
        symbolic: &SymbolicSupernodalCholesky<usize>,
    ) -> Vec<f64> {
        let mut values = vec![0.0; symbolic.len_val()];
        let mut memory = MemBuffer::new(factorize_supernodal_numeric_llt_scratch::<usize, f64>(
            symbolic,
            Par::Seq,
            Default::default(),
        ));
        factorize_supernodal_numeric_llt(
            &mut values,
            SparseColMatRef::new(lower.pattern().as_ref(), lower_values),
            Default::default(),
            symbolic,
            Par::Seq,
            MemStack::new(&mut memory),
            Default::default(),
        )
        .unwrap();
        values
    }

    #[test]
    fn the_factor_is_faers_to_rounding_on_narrow_and_wide_supernodes() {
        for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
            let (lower, lower_values, symbolic) = rectangle_system(degree, 1e-6);
            let widths: Vec<usize> = (0..symbolic.n_supernodes())
                .map(|s| symbolic.supernode_end()[s] - symbolic.supernode_begin()[s])
                .collect();
            // Both ways of factorising a supernode's panel are exercised.
            assert!(widths.iter().any(|&w| w <= SMALL_WIDTH), "{degree:?}");
            assert!(
                widths.iter().any(|&w| w > SMALL_WIDTH),
                "{degree:?}: {widths:?}"
            );
            let ours = factorise(&symbolic, lower.pattern().as_ref(), &lower_values).unwrap();
            let reference = faer_factor(&lower, &lower_values, &symbolic);
            // Entry by entry of L, relative to the largest entry of its supernode.
            let offsets = symbolic.col_ptr_for_val();
            for s in 0..symbolic.n_supernodes() {
                let range = offsets[s]..offsets[s + 1];
                let scale = reference[range.clone()]
                    .iter()
                    .fold(0.0_f64, |m, v| m.max(v.abs()));
                let w = symbolic.supernode_end()[s] - symbolic.supernode_begin()[s];
                let rows = (offsets[s + 1] - offsets[s]) / w;
                for e in range {
                    // Above the diagonal block's diagonal: not part of L (values may be left
                    // there; no solve reads them).
                    let (row, col) = ((e - offsets[s]) % rows, (e - offsets[s]) / rows);
                    if row < col {
                        continue;
                    }
                    assert!(
                        (ours[e] - reference[e]).abs() <= 1e-11 * scale,
                        "{degree:?}, supernode {s}, entry {e}: {} against {}",
                        ours[e],
                        reference[e]
                    );
                }
            }
        }
    }

    #[test]
    fn a_matrix_that_is_not_positive_definite_is_refused_with_its_pivot() {
        // Without the shift the stiffness matrix is singular (rigid axial translation): rounding
        // leaves its last pivot at about zero, of either sign. With the diagonal lowered below
        // zero, a pivot is negative.
        let (lower, mut lower_values, symbolic) = rectangle_system(Degree::Quadratic, 1e-6);
        // The diagonal entries of the permuted lower triangle: each column's entry in its own row.
        let pattern = lower.pattern();
        let n = pattern.nrows();
        for col in 0..n {
            let range = pattern.col_ptr()[col]..pattern.col_ptr()[col + 1];
            for (&row, value) in pattern.row_idx()[range.clone()]
                .iter()
                .zip(&mut lower_values[range])
            {
                if row == col {
                    *value = -*value;
                }
            }
        }
        let refused = factorise(&symbolic, pattern.as_ref(), &lower_values);
        // The first column has nothing to its left: its pivot is its own (negative) diagonal.
        assert_eq!(refused, Err(NonPositivePivot { column: 0 }));
        let mut nan_values = rectangle_system(Degree::Quadratic, 1e-6).1;
        let last = nan_values.len() - 1;
        nan_values[last] = f64::NAN;
        let refused = factorise(&symbolic, pattern.as_ref(), &nan_values);
        assert!(refused.is_err(), "a NaN pivot passed");
    }
}
