//! The permuted lower triangle of `K` and its supernodal symbolic analysis, worked out on the
//! node graph.
//!
//! `K` has two dofs per node (`2m`, `2m + 1`) with identical columns, each holding both dofs of
//! every coupled node, and possibly one trailing dof of its own (the far-field amplitude). When
//! the elimination order keeps each node's two dofs together (`[2m, 2m + 1, ...]`, the trailing
//! dof last), every structural quantity of the dof problem is the node problem's expanded:
//!
//! - the lower triangle of `P K Pᵀ` is laid out from one scan of each node's first column (the
//!   second, identical, is only compared): a quarter of the index lookups of a dof-by-dof scan
//!   ([`PermutedLower`]);
//! - the elimination tree and column counts of the factor come from the node graph's (a quarter
//!   of the entries and of the factor's structure to walk): for node `c` with parent `q`, dof
//!   `2c`'s parent is `2c + 1` and `2c + 1`'s is `q`'s first dof; the column counts are
//!   `2 n_c − f_c` and `2 n_c − f_c − 1`, with `n_c` the node column's count and `f_c = 1` when
//!   the column reaches the single trailing dof (a node of one dof);
//! - the supernodal structure is then `faer`'s
//!   ([`factorize_supernodal_symbolic_cholesky`]), given the upper triangle with one row per
//!   coupled node (its first dof: the second is its parent in the elimination tree, in the same
//!   supernode, so it reaches no supernode the first does not).
//!
//! The result is the analysis `faer` makes of the whole dof pattern (the tests compare the two
//! on the committed meshes, with and without the far-field dof, whole and split), at less cost:
//! at 92 528 quadratic unknowns a part's layout and analysis took 28 ms dof by dof and 18 ms
//! here (medians of 20 warm solves). The scan visits `K`'s columns in elimination order, not in
//! `K`'s: without asking for the columns a few nodes ahead it was as slow as the dof-wise layout.
//! A pattern or order not in this form is reported (`None`), and the caller analyses the dofs.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::simplicial::{
    prefactorize_symbolic_cholesky, prefactorize_symbolic_cholesky_scratch, EliminationTreeRef,
};
use faer::sparse::linalg::cholesky::supernodal::{
    factorize_supernodal_symbolic_cholesky, factorize_supernodal_symbolic_cholesky_scratch,
    SymbolicSupernodalCholesky,
};
use faer::sparse::linalg::SymbolicSupernodalParams;
use faer::sparse::{SymbolicSparseColMat, SymbolicSparseColMatRef};

use crate::error::{Error, Result};
use crate::numerics::prefetch::prefetch_range;
use crate::sparse::native::permuted_lower::PermutedLower;

fn analysis_error(message: String) -> Error {
    Error::NoConvergence {
        method: "fem".into(),
        reason: message,
    }
}

/// The layout of the permuted lower triangle, whether it couples outside the order, and its
/// supernodal symbolic analysis.
#[derive(Debug)]
pub(crate) struct NodePairAnalysis {
    /// The permuted lower triangle (as [`PermutedLower::of_part`] lays it out).
    pub lower: PermutedLower,
    /// Whether an entry of one of the first `checked` columns lies outside the order.
    pub couples: bool,
    /// The supernodal symbolic factorisation of `lower`.
    pub symbolic: SymbolicSupernodalCholesky<usize>,
}

/// A compressed-column list of indices (node indices, or dofs for [`supernodal_of_lower`]).
struct NodeColumns {
    offsets: Vec<usize>,
    rows: Vec<usize>,
}

impl NodeColumns {
    fn column(&self, c: usize) -> &[usize] {
        &self.rows[self.offsets[c]..self.offsets[c + 1]]
    }

    /// The transpose (rows sorted within each column).
    fn transposed(&self) -> Self {
        transpose(&self.offsets, &self.rows)
    }
}

/// The transpose of the square pattern with compressed columns `offsets`, `rows` (rows sorted
/// within each column of the result): a counting sort.
fn transpose(offsets: &[usize], rows: &[usize]) -> NodeColumns {
    let n = offsets.len() - 1;
    let mut counts = vec![0usize; n + 1];
    for &r in rows {
        counts[r + 1] += 1;
    }
    for i in 0..n {
        counts[i + 1] += counts[i];
    }
    let transposed_offsets = counts.clone();
    let mut next = counts;
    let mut transposed_rows = vec![0usize; rows.len()];
    for c in 0..n {
        for &r in &rows[offsets[c]..offsets[c + 1]] {
            transposed_rows[next[r]] = c;
            next[r] += 1;
        }
    }
    NodeColumns {
        offsets: transposed_offsets,
        rows: transposed_rows,
    }
}

/// Lay out and analyse the lower triangle of `P K Pᵀ` for the elimination `order` (dofs of `K`,
/// given as compressed columns with both triangles stored), as [`PermutedLower::of_part`] and
/// `faer`'s supernodal analysis would, on the node graph (see the module's documentation).
/// `Ok(None)` when the order or the pattern is not in node pairs.
pub(crate) fn analyse_node_pairs(
    col_offsets: &[usize],
    row_indices: &[usize],
    order: &[usize],
    checked: usize,
) -> Result<Option<NodePairAnalysis>> {
    let dofs = col_offsets.len().saturating_sub(1);
    PermutedLower::check_pattern(col_offsets, row_indices)?;
    let n = order.len();
    // K's own trailing dof (odd dimension), and the order's: the same dof, last, or none.
    let amplitude = (dofs % 2 == 1).then(|| dofs - 1);
    let single = n % 2 == 1;
    if single && Some(order[n - 1]) != amplitude {
        return Ok(None);
    }
    let pairs = n / 2;
    if (0..pairs).any(|c| !order[2 * c].is_multiple_of(2) || order[2 * c + 1] != order[2 * c] + 1) {
        return Ok(None);
    }
    let node_place = node_places(order, dofs)?;
    // A dof's place in the order (`usize::MAX`: not in it).
    let place_of_dof = |row: usize| match node_place[row / 2] {
        u32::MAX => usize::MAX,
        c => 2 * c as usize + row % 2,
    };

    let nodes = pairs + usize::from(single);
    let spans = node_column_spans(col_offsets, order, pairs);
    let mut layout = LowerLayout::with_capacity(n, nodes, row_indices.len());
    // (new first dof, index in K's first column, whether a node pair) of one node's column.
    let mut entries: Vec<(usize, usize, bool)> = Vec::with_capacity(64);
    for (c, &(start, end, end2)) in spans.iter().enumerate() {
        // The columns are scattered over K (the order is not K's): ask for those a few nodes
        // ahead while this one is worked on.
        if let Some(&(ahead, _, ahead_end)) = spans.get(c + PREFETCH_AHEAD) {
            prefetch_range(&row_indices[ahead..ahead_end]);
        }
        let start2 = end;
        if end2 - start2 != end - start || row_indices[start..end] != row_indices[start2..end2] {
            return Ok(None);
        }
        let interior = 2 * c < checked;
        entries.clear();
        let mut k = start;
        while k < end {
            let row = row_indices[k];
            if Some(row) == amplitude {
                match place_of_dof(row) {
                    usize::MAX => layout.outside |= interior,
                    p => entries.push((p, k, false)),
                }
                k += 1;
            } else if row.is_multiple_of(2) && k + 1 < end && row_indices[k + 1] == row + 1 {
                match place_of_dof(row) {
                    usize::MAX => layout.outside |= interior,
                    p => entries.push((p, k, true)),
                }
                k += 2;
            } else {
                return Ok(None);
            }
        }
        layout.push_node_pair(&entries, c, start2 - start, pairs);
    }
    if single {
        // The trailing dof's column: only entries at or after it (its diagonal) are kept.
        let last = order[n - 1];
        let range = col_offsets[last]..col_offsets[last + 1];
        let places = range
            .clone()
            .zip(&row_indices[range])
            .map(|(k, &row)| (k, place_of_dof(row)));
        layout.push_trailing_dof(places, n - 1, checked, pairs);
    }
    let LowerLayout {
        offsets,
        rows,
        source,
        node_lower,
        outside,
    } = layout;
    let pattern = SymbolicSparseColMat::new_unsorted_checked(n, n, offsets, None, rows);
    let node_upper = node_lower.transposed();
    drop(node_lower);
    let symbolic = supernodal_of_node_pairs(&node_upper, pairs, single)?;
    let lower = PermutedLower::from_parts(pattern, source, order.to_vec());
    Ok(Some(NodePairAnalysis {
        lower,
        couples: outside,
        symbolic,
    }))
}

/// Each node pair's two columns in K (the first's start, the second's start, which is the
/// first's end, and the second's end), gathered in one pass of independent loads.
fn node_column_spans(
    col_offsets: &[usize],
    order: &[usize],
    pairs: usize,
) -> Vec<(usize, usize, usize)> {
    (0..pairs)
        .map(|c| {
            let first = order[2 * c];
            (
                col_offsets[first],
                col_offsets[first + 1],
                col_offsets[first + 2],
            )
        })
        .collect()
}

/// Each node's place in the elimination `order` of `dofs` dofs (`u32::MAX`: not in it), a
/// quarter of a dof-wise inverse's memory: the scan's lookups stay in the core's cache. An
/// order with a dof out of range or twice is an internal error.
fn node_places(order: &[usize], dofs: usize) -> Result<Vec<u32>> {
    let absent = u32::MAX;
    let mut node_place = vec![absent; dofs.div_ceil(2)];
    for (new, &old) in order.iter().enumerate() {
        if old >= dofs {
            return Err(analysis_error(format!(
                "internal: dof {old} is out of range of the elimination order"
            )));
        }
        if new % 2 == 0 {
            if node_place[old / 2] != absent {
                return Err(analysis_error(format!(
                    "internal: dof {old} is twice in the elimination order"
                )));
            }
            node_place[old / 2] = (new / 2) as u32;
        }
    }
    Ok(node_place)
}

/// The lower triangle of `P K Pᵀ` being laid out column by column: its dof-wise pattern, each
/// entry's index in `K` (`source`), the node-wise lower pattern, and whether an interior
/// column couples to a dof outside the order.
struct LowerLayout {
    offsets: Vec<usize>,
    rows: Vec<usize>,
    source: Vec<u32>,
    node_lower: NodeColumns,
    outside: bool,
}

impl LowerLayout {
    /// Empty, with room for `n` dofs in `nodes` nodes and about half of `entries` entries.
    fn with_capacity(n: usize, nodes: usize, entries: usize) -> Self {
        let mut node_lower = NodeColumns {
            offsets: Vec::with_capacity(nodes + 1),
            rows: Vec::with_capacity(entries / 8 + nodes),
        };
        node_lower.offsets.push(0);
        let mut offsets = Vec::with_capacity(n + 1);
        offsets.push(0);
        LowerLayout {
            offsets,
            rows: Vec::with_capacity((entries + n) / 2),
            source: Vec::with_capacity((entries + n) / 2),
            node_lower,
            outside: false,
        }
    }

    /// The two columns of node pair `c` from its `entries` (new first dof, index in K's first
    /// column, whether a node pair); K's second column is `shift` entries after the first.
    #[inline]
    fn push_node_pair(
        &mut self,
        entries: &[(usize, usize, bool)],
        c: usize,
        shift: usize,
        pairs: usize,
    ) {
        let (x, z) = (2 * c, 2 * c + 1);
        let (rows, source) = (&mut self.rows, &mut self.source);
        for &(p, k, pair) in entries {
            if p >= x {
                rows.push(p);
                source.push(k as u32);
                if pair {
                    rows.push(p + 1);
                    source.push(k as u32 + 1);
                }
                self.node_lower.rows.push(if pair { p / 2 } else { pairs });
            }
        }
        self.offsets.push(rows.len());
        for &(p, k, pair) in entries {
            let k = k + shift;
            if pair && p >= x {
                if p > x {
                    rows.push(p);
                    source.push(k as u32);
                }
                rows.push(p + 1);
                source.push(k as u32 + 1);
            } else if !pair && p > z {
                rows.push(p);
                source.push(k as u32);
            }
        }
        self.offsets.push(rows.len());
        self.node_lower.offsets.push(self.node_lower.rows.len());
    }

    /// The trailing dof's column `new_col` from `(index in K, new place)` of its entries: only
    /// those at or after it (its diagonal) are kept.
    fn push_trailing_dof(
        &mut self,
        places: impl Iterator<Item = (usize, usize)>,
        new_col: usize,
        checked: usize,
        pairs: usize,
    ) {
        for (k, p) in places {
            if p == usize::MAX {
                self.outside |= new_col < checked;
            } else if p >= new_col {
                self.rows.push(p);
                self.source.push(k as u32);
                self.node_lower.rows.push(pairs);
            }
        }
        self.offsets.push(self.rows.len());
        self.node_lower.offsets.push(self.node_lower.rows.len());
    }
}

/// How many node columns ahead of the scan the prefetch asks for.
const PREFETCH_AHEAD: usize = 8;

/// The supernodal analysis of the dof pattern whose node graph's upper triangle (with its
/// diagonal) is `node_upper`: `pairs` nodes of two dofs, then, if `single`, one of one dof.
fn supernodal_of_node_pairs(
    node_upper: &NodeColumns,
    pairs: usize,
    single: bool,
) -> Result<SymbolicSupernodalCholesky<usize>> {
    let nodes = node_upper.offsets.len() - 1;
    let n = 2 * pairs + usize::from(single);
    if n == 0 {
        return Err(analysis_error("internal: nothing to analyse".into()));
    }
    let (node_parent, node_counts) = node_elimination_tree(node_upper)?;
    // Whether each node's column of the factor reaches the single node: it does where the
    // single node couples to the node or to one of its descendants.
    let mut reaches_single = vec![false; nodes];
    if single {
        for &c in node_upper.column(pairs) {
            reaches_single[c] = true;
        }
        for c in 0..pairs {
            if reaches_single[c] {
                if let Ok(q) = usize::try_from(node_parent[c]) {
                    reaches_single[q] = true;
                }
            }
        }
    }
    let first_dof = |node: usize| 2 * node;
    let mut parent = vec![-1isize; n];
    let mut counts = vec![0usize; n];
    for c in 0..pairs {
        let (x, z) = (2 * c, 2 * c + 1);
        parent[x] = z as isize;
        parent[z] = match usize::try_from(node_parent[c]) {
            Ok(q) => first_dof(q) as isize,
            Err(_) => -1,
        };
        counts[x] = 2 * node_counts[c] - usize::from(reaches_single[c]);
        counts[z] = counts[x] - 1;
    }
    if single {
        parent[n - 1] = -1;
        counts[n - 1] = node_counts[pairs];
    }
    // A tree over 0..n with each parent after its child, as faer's analysis indexes it.
    if parent
        .iter()
        .enumerate()
        .any(|(j, &p)| p != -1 && (p <= j as isize || p >= n as isize))
    {
        return Err(analysis_error(
            "internal: the expanded elimination tree is not a tree".into(),
        ));
    }
    let (dof_offsets, dof_rows) = dof_upper_pattern(node_upper, pairs);
    let dof_upper = SymbolicSparseColMatRef::new_checked(n, n, &dof_offsets, None, &dof_rows);
    let mut memory = MemBuffer::try_new(factorize_supernodal_symbolic_cholesky_scratch::<usize>(n))
        .map_err(|_| analysis_error("out of memory for the symbolic analysis".into()))?;
    // SAFETY: `parent` is the elimination tree of `dof_upper`'s pattern: the node graph's
    // (computed by faer's `prefactorize_symbolic_cholesky`) expanded to the dofs, which the
    // tests check equal to faer's own on the dof pattern; it was just checked to be a forest on
    // 0..n with every parent after its child, the property faer's analysis indexes by.
    let etree = unsafe { EliminationTreeRef::<usize>::from_inner(&parent) };
    factorize_supernodal_symbolic_cholesky(
        dof_upper,
        etree,
        &counts,
        MemStack::new(&mut memory),
        SymbolicSupernodalParams::default(),
    )
    .map_err(|e| analysis_error(format!("symbolic Cholesky analysis failed: {e:?}")))
}

/// The node graph's elimination tree (parent of each node, -1 at a root) and the factor's
/// column counts, by `faer`'s `prefactorize_symbolic_cholesky` on the upper triangle.
fn node_elimination_tree(node_upper: &NodeColumns) -> Result<(Vec<isize>, Vec<usize>)> {
    let nodes = node_upper.offsets.len() - 1;
    let upper = SymbolicSparseColMatRef::new_checked(
        nodes,
        nodes,
        &node_upper.offsets,
        None,
        &node_upper.rows,
    );
    let mut node_parent = vec![0isize; nodes];
    let mut node_counts = vec![0usize; nodes];
    {
        let mut memory = MemBuffer::try_new(prefactorize_symbolic_cholesky_scratch::<usize>(
            nodes,
            node_upper.rows.len(),
        ))
        .map_err(|_| analysis_error("out of memory for the symbolic analysis".into()))?;
        prefactorize_symbolic_cholesky(
            &mut node_parent,
            &mut node_counts,
            upper,
            MemStack::new(&mut memory),
        );
    }
    Ok((node_parent, node_counts))
}

/// The dofs' upper triangle from the nodes': one row per coupled node (its first dof), and a
/// node's first dof in its second dof's column; the first `pairs` nodes have two dofs, the rest
/// one.
fn dof_upper_pattern(node_upper: &NodeColumns, pairs: usize) -> (Vec<usize>, Vec<usize>) {
    let nodes = node_upper.offsets.len() - 1;
    let first_dof = |node: usize| 2 * node;
    let mut dof_offsets = Vec::with_capacity(2 * pairs + nodes - pairs + 1);
    let mut dof_rows = Vec::with_capacity(2 * node_upper.rows.len());
    dof_offsets.push(0);
    for c in 0..nodes {
        let earlier = node_upper.column(c).iter().filter(|&&r| r < c);
        let widths = if c < pairs { 2 } else { 1 };
        for dof in 0..widths {
            dof_rows.extend(earlier.clone().map(|&r| first_dof(r)));
            if dof == 1 {
                dof_rows.push(first_dof(c));
            }
            dof_offsets.push(dof_rows.len());
        }
    }
    (dof_offsets, dof_rows)
}

/// `faer`'s supernodal symbolic analysis of the lower triangle `lower` (compressed columns,
/// rows unsorted, already in elimination order), dof by dof: its transpose's elimination tree
/// and column counts ([`prefactorize_symbolic_cholesky`]), then the supernodes. For patterns
/// [`analyse_node_pairs`] does not take.
pub(crate) fn supernodal_of_lower(
    lower: SymbolicSparseColMatRef<'_, usize>,
) -> Result<SymbolicSupernodalCholesky<usize>> {
    let n = lower.nrows();
    // The upper triangle, diagonal included (faer's analysis reads the entries above it only).
    let NodeColumns { offsets, rows } = transpose(lower.col_ptr(), lower.row_idx());
    let upper = SymbolicSparseColMatRef::new_checked(n, n, &offsets, None, &rows);
    let mut parent = vec![0isize; n];
    let mut col_counts = vec![0usize; n];
    let req = prefactorize_symbolic_cholesky_scratch::<usize>(n, rows.len())
        .or(factorize_supernodal_symbolic_cholesky_scratch::<usize>(n));
    let mut memory = MemBuffer::try_new(req)
        .map_err(|_| analysis_error("out of memory for the symbolic analysis".into()))?;
    let etree = prefactorize_symbolic_cholesky(
        &mut parent,
        &mut col_counts,
        upper,
        MemStack::new(&mut memory),
    );
    factorize_supernodal_symbolic_cholesky(
        upper,
        etree,
        &col_counts,
        MemStack::new(&mut memory),
        SymbolicSupernodalParams::default(),
    )
    .map_err(|e| analysis_error(format!("symbolic Cholesky analysis failed: {e:?}")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretisation::assembly::StiffnessPattern;
    use crate::discretisation::element::Lame;
    use crate::discretisation::far_field::FarFieldCondition;
    use crate::discretisation::separator::{split_nodes, Side as PartSide};
    use crate::discretisation::vertex_ordering::vertex_led_node_order;
    use crate::mesh::triangulation::{tags, Degree, Mesh};
    use faer::perm::PermRef;
    use faer::sparse::linalg::cholesky::{
        factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
        SymmetricOrdering,
    };
    use faer::sparse::linalg::SupernodalThreshold;
    use faer::Side;

    /// `faer`'s own analysis of the whole dof pattern `lower` (the reference).
    fn faer_analysis(lower: &SymbolicSparseColMat<usize>) -> SymbolicCholesky<usize> {
        // The identity as a custom order: faer then reads the lower triangle (with
        // `SymmetricOrdering::Identity` it would take the pattern as the upper one).
        let identity: Vec<usize> = (0..lower.nrows()).collect();
        factorize_symbolic_cholesky(
            lower.as_ref(),
            Side::Lower,
            SymmetricOrdering::Custom(PermRef::new_checked(&identity, &identity, identity.len())),
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .unwrap()
    }

    fn supernodal(analysis: &SymbolicCholesky<usize>) -> &SymbolicSupernodalCholesky<usize> {
        match analysis.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => s,
            SymbolicCholeskyRaw::Simplicial(_) => panic!("not supernodal"),
        }
    }

    fn assert_same_analysis(
        got: &SymbolicSupernodalCholesky<usize>,
        expected: &SymbolicSupernodalCholesky<usize>,
        case: &str,
    ) {
        let same = |a: &[usize], b: &[usize], what: &str| {
            let first = a.iter().zip(b).position(|(x, y)| x != y);
            assert!(
                a.len() == b.len() && first.is_none(),
                "{case}: {what} differ (lengths {} and {}, first at {first:?})",
                a.len(),
                b.len()
            );
        };
        assert_eq!(got.nrows(), expected.nrows(), "{case}: size");
        same(
            got.supernode_begin(),
            expected.supernode_begin(),
            "supernodes",
        );
        same(
            got.col_ptr_for_row_idx(),
            expected.col_ptr_for_row_idx(),
            "row offsets",
        );
        same(
            got.col_ptr_for_val(),
            expected.col_ptr_for_val(),
            "value offsets",
        );
        same(got.row_idx(), expected.row_idx(), "rows");
    }

    /// The layouts hold the same entries of `K` in the same places.
    fn assert_same_layout(got: &PermutedLower, expected: &PermutedLower, case: &str) {
        assert_eq!(got.order(), expected.order(), "{case}: order");
        assert_eq!(
            got.pattern().col_ptr(),
            expected.pattern().col_ptr(),
            "{case}"
        );
        assert_eq!(
            got.pattern().row_idx(),
            expected.pattern().row_idx(),
            "{case}"
        );
        // Distinct values: the gathered triangles are equal only if every source is.
        let values: Vec<f64> = (0..1 << 24).map(|k| k as f64).collect();
        let dofs = got.order().iter().max().map_or(0, |&d| d + 1);
        let free = vec![false; dofs];
        let (mut a, mut b) = (vec![0.0; got.len()], vec![0.0; expected.len()]);
        got.gather(&values, &free, &mut a);
        expected.gather(&values, &free, &mut b);
        assert_eq!(a, b, "{case}: sources");
    }

    /// The orders a model's solver analyses: the whole (nodes, then the far-field amplitude)
    /// and, where the mesh splits, each part with the separator.
    fn orders_of(mesh: &Mesh, dofs: usize) -> Vec<(String, Vec<usize>, usize)> {
        let nodes = vertex_led_node_order(mesh);
        let amplitude: Vec<usize> = (dofs % 2 == 1).then(|| dofs - 1).into_iter().collect();
        let pairs = |of: &mut dyn Iterator<Item = usize>| -> Vec<usize> {
            of.flat_map(|m| [2 * m, 2 * m + 1]).collect()
        };
        let mut whole = pairs(&mut nodes.iter().copied());
        whole.extend(&amplitude);
        let mut orders = vec![("whole".to_string(), whole, 0)];
        if let Some(split) = split_nodes(mesh) {
            let sides = &split.sides;
            let of_side = |side| nodes.iter().copied().filter(move |&m| sides[m] == side);
            let mut separator = pairs(&mut of_side(PartSide::Separator));
            separator.extend(&amplitude);
            for side in [PartSide::First, PartSide::Second] {
                let mut order = pairs(&mut of_side(side));
                let interior = order.len();
                order.extend(&separator);
                orders.push((format!("{side:?}"), order, interior));
            }
        }
        orders
    }

    #[test]
    fn the_node_graph_gives_faers_own_layout_and_analysis_of_the_dofs() {
        // Committed meshes at degrees 1-3 (bubbles condensed), with and without the far-field
        // amplitude, whole and split: the layout equals the dof-wise one and the supernodal
        // analysis equals faer's of the whole dof pattern (supernodes, rows, value offsets).
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
        let material = Lame::from_young_poisson(1.0, 0.3);
        let mut cases = 0;
        for name in ["disk-L1.msh", "annulus-0.5-L1.msh"] {
            let vertex_mesh = crate::mesh::msh::read_msh(&root.join(name)).unwrap();
            for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
                let mesh = vertex_mesh.with_degree(degree);
                let radius = mesh
                    .boundary_nodes(tags::FAR)
                    .iter()
                    .map(|&n| mesh.nodes[n][0].hypot(mesh.nodes[n][1]))
                    .fold(0.0, f64::max);
                let far = FarFieldCondition::new(&mesh, &material, radius);
                for far_field in [None, Some(&far)] {
                    let pattern = StiffnessPattern::of_model(&mesh, far_field).unwrap();
                    let (offsets, rows) = (pattern.col_offsets(), pattern.row_indices());
                    let dofs = offsets.len() - 1;
                    for (part, order, interior) in orders_of(&mesh, dofs) {
                        let case =
                            format!("{name} {degree:?} far field {} {part}", far_field.is_some());
                        let got = analyse_node_pairs(offsets, rows, &order, interior)
                            .unwrap()
                            .unwrap_or_else(|| panic!("{case}: not taken as node pairs"));
                        let expected =
                            PermutedLower::of_part(offsets, rows, &order, interior).unwrap();
                        assert!(!got.couples, "{case}: the part couples to the other");
                        let expected = expected.expect("the dof-wise layout");
                        assert_same_layout(&got.lower, &expected, &case);
                        let reference = faer_analysis(expected.pattern());
                        let reference = supernodal(&reference);
                        assert_same_analysis(&got.symbolic, reference, &case);
                        let dof_wise = supernodal_of_lower(expected.pattern().as_ref()).unwrap();
                        assert_same_analysis(&dof_wise, reference, &format!("{case} dof-wise"));
                        cases += 1;
                    }
                }
            }
        }
        assert!(cases >= 24, "{cases} cases");
    }

    #[test]
    fn a_part_that_couples_outside_its_order_is_reported() {
        // The first half of a mesh's nodes, checked whole: its columns reach the other half.
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
        let mesh = crate::mesh::msh::read_msh(&root.join("disk-L1.msh"))
            .unwrap()
            .with_degree(Degree::Quadratic);
        let pattern = StiffnessPattern::new(&mesh).unwrap();
        let half: Vec<usize> = vertex_led_node_order(&mesh)[..mesh.nodes.len() / 2]
            .iter()
            .flat_map(|&m| [2 * m, 2 * m + 1])
            .collect();
        let (offsets, rows) = (pattern.col_offsets(), pattern.row_indices());
        let got = analyse_node_pairs(offsets, rows, &half, half.len())
            .unwrap()
            .unwrap();
        assert!(got.couples);
        assert!(PermutedLower::of_part(offsets, rows, &half, half.len())
            .unwrap()
            .is_none());
        // Unchecked, the same order lays out the principal submatrix, as the dof-wise layout.
        let got = analyse_node_pairs(offsets, rows, &half, 0)
            .unwrap()
            .unwrap();
        assert!(!got.couples);
        let expected = PermutedLower::new(offsets, rows, &half).unwrap();
        assert_same_layout(&got.lower, &expected, "half, unchecked");
        let reference = faer_analysis(expected.pattern());
        assert_same_analysis(&got.symbolic, supernodal(&reference), "half");
    }

    #[test]
    fn orders_and_patterns_not_in_node_pairs_are_left_to_the_dof_wise_analysis() {
        // A 3-node path (6 dofs): node pairs in the pattern, then orders that split a pair or
        // reverse it, and a pattern whose second column of a node differs from its first.
        let paired = |a: usize, b: usize| (a / 2).abs_diff(b / 2) <= 1;
        let build = |couples: &dyn Fn(usize, usize) -> bool| {
            let mut offsets = vec![0];
            let mut rows = Vec::new();
            for col in 0..6 {
                rows.extend((0..6).filter(|&row| couples(row, col)));
                offsets.push(rows.len());
            }
            (offsets, rows)
        };
        let (offsets, rows) = build(&paired);
        let taken = |order: &[usize]| {
            analyse_node_pairs(&offsets, &rows, order, 0)
                .unwrap()
                .is_some()
        };
        assert!(taken(&[2, 3, 0, 1, 4, 5]));
        assert!(!taken(&[3, 2, 0, 1, 4, 5]), "a pair reversed");
        assert!(!taken(&[0, 2, 1, 3, 4, 5]), "pairs interleaved");
        assert!(
            !taken(&[0, 1, 2, 3, 4]),
            "a single dof that is not the trailing one"
        );
        // Dof 1 (node 0's second) not coupled to dof 5: the node's columns differ.
        let (offsets, rows) = build(&|a, b| {
            paired(a, b) && !matches!((a.min(b), a.max(b)), (1, 5))
                || matches!((a.min(b), a.max(b)), (0, 4) | (0, 5) | (1, 4))
        });
        assert!(analyse_node_pairs(&offsets, &rows, &[0, 1, 2, 3, 4, 5], 0)
            .unwrap()
            .is_none());
        // A repeated dof is an error, as in the dof-wise layout.
        let (offsets, rows) = build(&paired);
        assert!(analyse_node_pairs(&offsets, &rows, &[0, 1, 0, 1, 4, 5], 0).is_err());
    }
}
