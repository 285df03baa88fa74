//! Cholesky solves of `K` split in two parts and a separator, factorised on two cores.
//!
//! With the dofs in three groups, the two parts `1`, `2` (no entry of `K` couples them) and the
//! separator `S` (found on the mesh by `crate::discretisation::separator`),
//!
//! ```text
//!     K = [K11  0    K1S]        M_i = [Kii  KiS]   (i = 1, 2)
//!         [0    K22  K2S]              [KSi  KSS]
//!         [KS1  KS2  KSS]
//! ```
//!
//! each `M_i` (a principal submatrix of `K`, so positive definite) is factorised on its own
//! core with the separator last, `M_i = L_i L_iᵀ`. The bottom-right block `L_SS,i` of `L_i` gives
//! the part's Schur complement `S_i = KSS − KSi Kii⁻¹ KiS = L_SS,i L_SS,iᵀ`, and the Schur
//! complement of `K` is `S = S_1 + S_2 − KSS` (dense, the separator being a few dozen
//! vertices), factorised densely in zero-padded storage ([`crate::sparse::native::dense`]: `faer`'s
//! kernels compute on a column's padding, where leftover bytes read as subnormal numbers slowed
//! that factorisation up to sevenfold); each part forms its own product `L_SS,i L_SS,iᵀ` on its
//! core, and every dense matrix of this module is zero-padded.
//! A solve `K u = f` is then, per part, one forward and one backward substitution with `L_i`
//! (the two parts again on two cores):
//!
//! 1. forward with `[f_i; 0]`: `z_i = Lii⁻¹ f_i`, `z_S,i = −L_SS,i⁻¹ KSi Kii⁻¹ f_i`, so
//!    `g_i = KSi Kii⁻¹ f_i = −L_SS,i z_S,i`;
//! 2. `u_S = S⁻¹ (f_S − g_1 − g_2)`;
//! 3. backward with `[z_i; L_SS,iᵀ u_S]`: its first block is `Kii⁻¹ (f_i − KiS u_S) = u_i`.

use std::sync::Arc;

use faer::linalg::matmul::matmul;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::{Accum, Mat, MatMut, Par};

use crate::error::{Error, Result};
use crate::sparse::native::dense::{zero_padded, DenseCholesky};
use crate::sparse::native::node_pair_analysis::{analyse_node_pairs, supernodal_of_lower};
use crate::sparse::native::permuted_lower::PermutedLower;
use crate::sparse::native::whole::{factorisation_work, factorise_supernodal};
use crate::sparse::{NodeSplit, Side as PartSide};

fn solver_error(message: String) -> Error {
    Error::NoConvergence {
        method: "fem".into(),
        reason: message,
    }
}

/// One part with the separator: the layout of its matrix's lower triangle, its dofs in
/// elimination order (the part's, then the separator's), and the symbolic analysis of it.
#[derive(Debug)]
struct PartAnalysis {
    lower: PermutedLower,
    symbolic: SymbolicSupernodalCholesky<usize>,
    /// [`longest_rows`] of the symbolic factor.
    scratch_rows: usize,
}

impl PartAnalysis {
    /// The analysis of the part whose dofs are `order`'s first `interior`, then the separator's;
    /// `None` when an entry of `K` couples the part to the other one.
    fn new(
        col_offsets: &[usize],
        row_indices: &[usize],
        order: &[usize],
        interior: usize,
    ) -> Result<Option<Self>> {
        // On the node graph where K's dofs come in node pairs (always, for the solver's
        // models), dof by dof otherwise.
        if let Some(analysis) = analyse_node_pairs(col_offsets, row_indices, order, interior)? {
            return Ok((!analysis.couples).then(|| Self::of(analysis.lower, analysis.symbolic)));
        }
        let Some(lower) = PermutedLower::of_part(col_offsets, row_indices, order, interior)? else {
            return Ok(None);
        };
        let symbolic = supernodal_of_lower(lower.pattern().as_ref())?;
        Ok(Some(Self::of(lower, symbolic)))
    }

    fn of(lower: PermutedLower, symbolic: SymbolicSupernodalCholesky<usize>) -> Self {
        let scratch_rows = longest_rows(&symbolic);
        Self {
            lower,
            symbolic,
            scratch_rows,
        }
    }

    /// The part's dofs (of `K`) in elimination order, the separator's last.
    fn order(&self) -> &[usize] {
        self.lower.order()
    }

    /// Number of dofs before the separator.
    fn interior(&self, separator: usize) -> usize {
        self.order().len() - separator
    }
}

/// The symbolic analysis of a split `K`: the two parts' and the separator's dofs.
#[derive(Debug)]
pub struct SplitAnalysis {
    parts: [PartAnalysis; 2],
    separator: Vec<usize>,
    /// Size and number of entries of the analysed pattern (both triangles).
    shape: (usize, usize),
}

/// Expand nodes to their two dofs each.
fn node_dofs(nodes: impl Iterator<Item = usize>) -> impl Iterator<Item = usize> {
    nodes.flat_map(|m| [2 * m, 2 * m + 1])
}

impl SplitAnalysis {
    /// Analyse `K`'s pattern (compressed columns, both triangles, two dofs per node and an
    /// optional trailing dof, which joins the separator) split as `split`, each part's nodes
    /// eliminated in the order they have in `node_order` (every node once). `None` when an entry
    /// of the pattern couples the two parts (a coupling that is not through a cell): the split
    /// does not apply.
    pub fn new(
        col_offsets: &[usize],
        row_indices: &[usize],
        node_order: &[usize],
        split: &NodeSplit,
    ) -> Result<Option<Self>> {
        Self::new_beside(col_offsets, row_indices, node_order, split, || ()).0
    }

    /// [`Self::new`], with `beside` run on the two cores beside the second part's analysis
    /// (before the analysis, when the input is wrong). The two parts' analyses are sequential and
    /// about equal; started first, one on each core, they leave `beside` (the assembly's values,
    /// itself parallel) to fill in whichever core is free first: started after `beside`'s work,
    /// the second part runs alone at the end (39 against about 28 ms for the three at 9e4
    /// quadratic unknowns). Whether an entry couples the parts is found while each part's
    /// layout is made ([`PermutedLower::of_part`]), not in a pass of its own before them (that
    /// pass was 2.5 ms of one core at 9e4 quadratic unknowns).
    pub(crate) fn new_beside<R: Send>(
        col_offsets: &[usize],
        row_indices: &[usize],
        node_order: &[usize],
        split: &NodeSplit,
        beside: impl FnOnce() -> R + Send,
    ) -> (Result<Option<Self>>, R) {
        let (separator, first, second) =
            match Self::part_orders(col_offsets, row_indices, node_order, split) {
                Ok(orders) => orders,
                Err(e) => return (Err(e), beside()),
            };
        let interior = |order: &Vec<usize>| order.len() - separator.len();
        let (first, (second, result)) = rayon::join(
            || PartAnalysis::new(col_offsets, row_indices, &first, interior(&first)),
            || {
                rayon::join(
                    || PartAnalysis::new(col_offsets, row_indices, &second, interior(&second)),
                    beside,
                )
            },
        );
        let analysis = match (first, second) {
            (Ok(Some(first)), Ok(Some(second))) => Ok(Some(Self {
                parts: [first, second],
                separator,
                shape: (col_offsets.len().saturating_sub(1), row_indices.len()),
            })),
            (Err(e), _) | (_, Err(e)) => Err(e),
            _ => Ok(None),
        };
        (analysis, result)
    }

    /// The separator's dofs and each part's dofs in elimination order (its own, then the
    /// separator's).
    fn part_orders(
        col_offsets: &[usize],
        row_indices: &[usize],
        node_order: &[usize],
        split: &NodeSplit,
    ) -> Result<(Vec<usize>, Vec<usize>, Vec<usize>)> {
        let n = col_offsets.len().saturating_sub(1);
        let nodes = split.sides.len();
        if n / 2 != nodes
            || node_order.len() != nodes
            || col_offsets.last() != Some(&row_indices.len())
        {
            return Err(solver_error(
                "internal: the split belongs to another mesh".into(),
            ));
        }
        let of_side = |side: PartSide| {
            node_order
                .iter()
                .copied()
                .filter(move |&m| split.sides[m] == side)
        };
        let mut separator: Vec<usize> = node_dofs(of_side(PartSide::Separator)).collect();
        if n % 2 == 1 {
            separator.push(n - 1);
        }
        let order_of = |side| -> Vec<usize> {
            node_dofs(of_side(side))
                .chain(separator.iter().copied())
                .collect()
        };
        let (first, second) = (order_of(PartSide::First), order_of(PartSide::Second));
        Ok((separator, first, second))
    }

    /// Whether this analysis is of a pattern of `n` rows and `nnz` entries.
    pub fn fits(&self, n: usize, nnz: usize) -> bool {
        self.shape == (n, nnz)
    }

    /// Number of separator dofs.
    pub(crate) fn separator_len(&self) -> usize {
        self.separator.len()
    }

    /// Each part's numeric factorisation's multiply-adds ([`factorisation_work`]).
    pub(crate) fn part_work(&self) -> [f64; 2] {
        self.parts
            .each_ref()
            .map(|part| factorisation_work(&part.symbolic))
    }

    /// Number of dofs of each part, its separator excluded.
    pub(crate) fn part_sizes(&self) -> [usize; 2] {
        let s = self.separator.len();
        [self.parts[0].interior(s), self.parts[1].interior(s)]
    }
}

/// One part's numeric factor and its separator block `L_SS,i` (dense, lower).
struct PartFactor {
    values: Vec<f64>,
    separator_block: Mat<f64>,
}

/// A part just factorised: its factor and its term of the Schur complement (lower triangle):
/// `L_SS,i L_SS,iᵀ`, less `K_SS` for the first part.
struct FactoredPart {
    factor: PartFactor,
    schur_term: Mat<f64>,
}

/// The numeric factorisation of a split `K_C` (see the module's documentation).
pub(crate) struct SplitFactor {
    analysis: Arc<SplitAnalysis>,
    parts: [PartFactor; 2],
    schur: DenseCholesky,
}

/// The dense bottom-right block (last `size` rows and columns) of a supernodal factor.
fn trailing_block(llt: SupernodalLltRef<'_, usize, f64>, size: usize) -> Mat<f64> {
    let symbolic = llt.symbolic();
    let n = symbolic.nrows();
    let first = n - size;
    let mut block = zero_padded(size, size);
    for s in 0..symbolic.n_supernodes() {
        let node = llt.supernode(s);
        let (start, width) = (node.start(), node.val().ncols());
        if start + width <= first {
            continue;
        }
        let values = node.val();
        for j in start.max(first)..start + width {
            let col = j - start;
            for row in col..width {
                block[(start + row - first, j - first)] = values[(row, col)];
            }
            for (idx, &i) in node.pattern().iter().enumerate() {
                block[(i - first, j - first)] = values[(width + idx, col)];
            }
        }
    }
    block
}

/// The lower triangle of a part's separator block `K_SS` (its trailing `separator` columns),
/// from the part's gathered `lower_values`.
fn separator_block_of(part: &PartAnalysis, lower_values: &[f64], separator: usize) -> Mat<f64> {
    let pattern = part.lower.pattern();
    let interior = part.interior(separator);
    let mut kss = zero_padded(separator, separator);
    for col in interior..part.order().len() {
        let range = pattern.col_ptr()[col]..pattern.col_ptr()[col + 1];
        for (&row, &v) in pattern.row_idx()[range.clone()]
            .iter()
            .zip(&lower_values[range])
        {
            kss[(row - interior, col - interior)] = v;
        }
    }
    kss
}

/// Most rows of any supernode of a factor (its width plus its pattern): the length of the
/// substitutions' scratch.
fn longest_rows(symbolic: &SymbolicSupernodalCholesky<usize>) -> usize {
    let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
    (0..symbolic.n_supernodes())
        .map(|s| end[s] - begin[s] + symbolic.supernode(s).pattern().len())
        .max()
        .unwrap_or(0)
}

/// `x ← L⁻¹ x` with a supernodal factor (forward substitution).
/// `scratch_rows` is [`longest_rows`] of the factor.
fn forward(llt: SupernodalLltRef<'_, usize, f64>, scratch_rows: usize, mut x: MatMut<'_, f64>) {
    if let Some(column) = single_column(x.rb_mut()) {
        return forward_one(llt, scratch_rows, column);
    }
    let k = x.ncols();
    let mut scratch = zero_padded(scratch_rows, k);
    for s in 0..llt.symbolic().n_supernodes() {
        let node = llt.supernode(s);
        let width = node.val().ncols();
        let (top, bottom) = node.val().split_at_row(width);
        let mut x_top = x.rb_mut().subrows_mut(node.start(), width);
        solve_lower_triangular_in_place(top, x_top.rb_mut(), Par::Seq);
        let mut update = scratch.as_mut().subrows_mut(0, node.pattern().len());
        matmul(
            update.rb_mut(),
            Accum::Replace,
            bottom,
            x_top.rb(),
            1.0,
            Par::Seq,
        );
        for j in 0..k {
            for (idx, &i) in node.pattern().iter().enumerate() {
                x[(i, j)] -= update[(idx, j)];
            }
        }
    }
}

/// `x ← L⁻ᵀ x` with a supernodal factor (backward substitution).
/// `scratch_rows` is [`longest_rows`] of the factor.
fn backward(llt: SupernodalLltRef<'_, usize, f64>, scratch_rows: usize, mut x: MatMut<'_, f64>) {
    if let Some(column) = single_column(x.rb_mut()) {
        return backward_one(llt, scratch_rows, column);
    }
    let k = x.ncols();
    let mut scratch = zero_padded(scratch_rows, k);
    for s in (0..llt.symbolic().n_supernodes()).rev() {
        let node = llt.supernode(s);
        let width = node.val().ncols();
        let (top, bottom) = node.val().split_at_row(width);
        let mut gathered = scratch.as_mut().subrows_mut(0, node.pattern().len());
        for j in 0..k {
            for (idx, &i) in node.pattern().iter().enumerate() {
                gathered[(idx, j)] = x[(i, j)];
            }
        }
        let mut x_top = x.rb_mut().subrows_mut(node.start(), width);
        matmul(
            x_top.rb_mut(),
            Accum::Add,
            bottom.transpose(),
            gathered.rb(),
            -1.0,
            Par::Seq,
        );
        solve_upper_triangular_in_place(top.transpose(), x_top, Par::Seq);
    }
}

/// `x`'s only column as a slice, or `None` for several columns (or a strided one).
fn single_column(x: MatMut<'_, f64>) -> Option<&mut [f64]> {
    if x.ncols() != 1 {
        return None;
    }
    x.col_mut(0)
        .try_as_col_major_mut()
        .map(|c| c.as_slice_mut())
}

/// Supernode `s`'s values, column after column (each column its diagonal block's rows, then the
/// pattern's): the slice `faer` itself views as the supernode's column-major matrix.
fn supernode_values(llt: SupernodalLltRef<'_, usize, f64>, s: usize) -> &[f64] {
    let offsets = llt.symbolic().col_ptr_for_val();
    &llt.values()[offsets[s]..offsets[s + 1]]
}

/// `Σ a_i b_i` in four interleaved sums (one running sum would be a chain of dependent
/// additions, which the compiler may not reorder into vector lanes).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    debug_assert_eq!(a.len(), b.len(), "a dot product of unequal lengths");
    let mut sums = [0.0; 4];
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in a4.zip(b4) {
        for lane in 0..4 {
            sums[lane] += x[lane] * y[lane];
        }
    }
    (sums[0] + sums[1]) + (sums[2] + sums[3]) + tail
}

/// [`forward`] for one right-hand side, column by column of each supernode: `y` holds the
/// supernode's rows (its own unknowns, then the pattern's updates, starting at zero); column
/// `j` divides `y_j` by the diagonal and subtracts `L_ij y_j` below it in one pass over the
/// column, and the pattern's updates are then added to `x`. With one right-hand side a
/// supernode's work is a few vector operations, which `faer`'s dense kernels (a triangular solve
/// and a product per supernode) cost more to dispatch than plain loops: the contact step's
/// substitution and reactions took 10-14 % less time this way at 1.5e4-9.3e4 unknowns (medians
/// of 12-50 warm flat solves, five alternated rounds against the kernels).
fn forward_one(llt: SupernodalLltRef<'_, usize, f64>, scratch_rows: usize, x: &mut [f64]) {
    let mut y = vec![0.0; scratch_rows];
    for s in 0..llt.symbolic().n_supernodes() {
        let node = llt.supernode(s);
        let (start, rows) = (node.start(), node.val().nrows());
        let (width, pattern) = (node.val().ncols(), node.pattern());
        let y = &mut y[..rows];
        y[..width].copy_from_slice(&x[start..start + width]);
        y[width..].fill(0.0);
        for (j, column) in supernode_values(llt, s).chunks_exact(rows).enumerate() {
            let yj = y[j] / column[j];
            y[j] = yj;
            for (yi, &l) in y[j + 1..].iter_mut().zip(&column[j + 1..]) {
                *yi -= l * yj;
            }
        }
        x[start..start + width].copy_from_slice(&y[..width]);
        for (&i, &update) in pattern.iter().zip(&y[width..]) {
            x[i] += update;
        }
    }
}

/// [`backward`] for one right-hand side: `y` gathers the supernode's unknowns and the pattern's
/// (already solved) values, and column `j`, last first, gives `y_j = (y_j − Σ_{i>j} L_ij y_i) /
/// L_jj` as one dot product over the column below its diagonal.
fn backward_one(llt: SupernodalLltRef<'_, usize, f64>, scratch_rows: usize, x: &mut [f64]) {
    let mut y = vec![0.0; scratch_rows];
    for s in (0..llt.symbolic().n_supernodes()).rev() {
        let node = llt.supernode(s);
        let (start, rows) = (node.start(), node.val().nrows());
        let (width, pattern) = (node.val().ncols(), node.pattern());
        let y = &mut y[..rows];
        y[..width].copy_from_slice(&x[start..start + width]);
        for (yi, &i) in y[width..].iter_mut().zip(pattern) {
            *yi = x[i];
        }
        for (j, column) in supernode_values(llt, s)
            .chunks_exact(rows)
            .enumerate()
            .rev()
        {
            y[j] = (y[j] - dot(&column[j + 1..], &y[j + 1..])) / column[j];
        }
        x[start..start + width].copy_from_slice(&y[..width]);
    }
}

impl SplitFactor {
    /// Factorise `K_C`: `values` are `K`'s (on the analysed pattern), with every off-diagonal
    /// entry of a `constrained` dof's row and column taken as zero.
    pub fn new(
        analysis: &Arc<SplitAnalysis>,
        values: &[f64],
        constrained: &[bool],
    ) -> Result<Self> {
        let separator = analysis.separator.len();
        // Each part's factor and Schur term on its own core; the first also subtracts K_SS
        // (lower), read from its trailing columns before the factorisation (the second's are the
        // same).
        let factor_part = |part: &PartAnalysis, with_kss: bool| -> Result<FactoredPart> {
            let lower_values = part.lower.gathered(values, constrained);
            let kss = with_kss.then(|| separator_block_of(part, &lower_values, separator));
            let pattern = part.lower.pattern();
            let values = factorise_supernodal(&part.symbolic, pattern, &lower_values)?;
            let llt = SupernodalLltRef::new(&part.symbolic, &values);
            let separator_block = trailing_block(llt, separator);
            // L_SS,i L_SS,iᵀ (lower triangle, from the triangular blocks: a sixth of a full
            // product's work).
            let mut schur_term = zero_padded(separator, separator);
            triangular::matmul(
                schur_term.as_mut(),
                BlockStructure::TriangularLower,
                Accum::Replace,
                separator_block.as_ref(),
                BlockStructure::TriangularLower,
                separator_block.transpose(),
                BlockStructure::TriangularUpper,
                1.0,
                Par::Seq,
            );
            if let Some(kss) = &kss {
                for j in 0..separator {
                    for i in j..separator {
                        schur_term[(i, j)] -= kss[(i, j)];
                    }
                }
            }
            Ok(FactoredPart {
                factor: PartFactor {
                    values,
                    separator_block,
                },
                schur_term,
            })
        };
        let (first, second) = rayon::join(
            || factor_part(&analysis.parts[0], true),
            || factor_part(&analysis.parts[1], false),
        );
        let (first, second) = (first?, second?);
        // S = (L_SS,1 L_SS,1ᵀ − K_SS) + L_SS,2 L_SS,2ᵀ (lower triangle).
        let schur = DenseCholesky::of_lower(separator, |i, j| {
            first.schur_term[(i, j)] + second.schur_term[(i, j)]
        });
        let schur = schur.map_err(|e| {
            solver_error(format!(
                "the stiffness matrix is not positive definite on the separator (pivot {}): is \
                 the body held against rigid motion?",
                e.column
            ))
        })?;
        Ok(Self {
            analysis: Arc::clone(analysis),
            parts: [first.factor, second.factor],
            schur,
        })
    }

    /// Overwrite `rhs` (one or more columns) with `K_C⁻¹ rhs`.
    pub(crate) fn solve_in_place(&self, mut rhs: MatMut<'_, f64>) {
        let analysis = &self.analysis;
        let separator = analysis.separator.len();
        let k = rhs.ncols();
        let rhs_ref = rhs.rb();
        // Steps 1: per part, forward with [f_i; 0]; g_i = −L_SS,i z_S,i.
        let forward_part = |i: usize| -> (Mat<f64>, Mat<f64>) {
            let part = &analysis.parts[i];
            let interior = part.interior(separator);
            let mut x = zero_padded(part.order().len(), k);
            for j in 0..k {
                for (p, &d) in part.order()[..interior].iter().enumerate() {
                    x[(p, j)] = rhs_ref[(d, j)];
                }
            }
            let llt = SupernodalLltRef::new(&part.symbolic, &self.parts[i].values);
            forward(llt, part.scratch_rows, x.as_mut());
            let mut g = zero_padded(separator, k);
            matmul(
                g.as_mut(),
                Accum::Replace,
                self.parts[i].separator_block.as_ref(),
                x.as_ref().subrows(interior, separator),
                -1.0,
                Par::Seq,
            );
            (x, g)
        };
        let ((mut x1, g1), (mut x2, g2)) = rayon::join(|| forward_part(0), || forward_part(1));
        // Step 2: u_S = S⁻¹ (f_S − g_1 − g_2).
        let mut u_s = zero_padded(separator, k);
        for j in 0..k {
            for (p, &d) in analysis.separator.iter().enumerate() {
                u_s[(p, j)] = rhs_ref[(d, j)] - g1[(p, j)] - g2[(p, j)];
            }
        }
        self.schur.solve_in_place(u_s.as_mut());
        // Step 3: per part, backward with [z_i; L_SS,iᵀ u_S].
        let backward_part = |i: usize, x: &mut Mat<f64>| {
            let part = &analysis.parts[i];
            let interior = part.interior(separator);
            matmul(
                x.as_mut().subrows_mut(interior, separator),
                Accum::Replace,
                self.parts[i].separator_block.transpose(),
                u_s.as_ref(),
                1.0,
                Par::Seq,
            );
            let llt = SupernodalLltRef::new(&part.symbolic, &self.parts[i].values);
            backward(llt, part.scratch_rows, x.as_mut());
        };
        rayon::join(|| backward_part(0, &mut x1), || backward_part(1, &mut x2));
        for (part, x) in analysis.parts.iter().zip([&x1, &x2]) {
            let interior = part.interior(separator);
            for j in 0..k {
                for (p, &d) in part.order()[..interior].iter().enumerate() {
                    rhs[(d, j)] = x[(p, j)];
                }
            }
        }
        for j in 0..k {
            for (p, &d) in analysis.separator.iter().enumerate() {
                rhs[(d, j)] = u_s[(p, j)];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretisation::assembly::assemble_stiffness;
    use crate::discretisation::element::Lame;
    use crate::discretisation::quadrature::stiffness_rule;
    use crate::discretisation::separator::{split_by_level, split_nodes};
    use crate::discretisation::vertex_ordering::vertex_led_node_order;
    use crate::mesh::triangulation::{structured_rectangle, tags, Degree};
    use faer::linalg::solvers::Solve;

    /// A 6 × 1 strip of `degree` (18 × 3 cells): its stiffness matrix, the analysis of its
    /// level split, and its bottom (far) nodes' dofs marked as held.
    fn split_strip(
        degree: Degree,
    ) -> (
        nalgebra_sparse::CscMatrix<f64>,
        Arc<SplitAnalysis>,
        Vec<bool>,
    ) {
        let material = Lame::from_young_poisson(1.0, 0.3);
        let mesh = structured_rectangle(6.0, 1.0, 18, 3, tags::CONTACT, tags::AXIS, tags::FAR)
            .with_degree(degree);
        let k = assemble_stiffness(&mesh, &material, &stiffness_rule(degree)).unwrap();
        let split = split_by_level(&mesh).expect("the strip splits");
        let order = vertex_led_node_order(&mesh);
        let analysis = Arc::new(
            SplitAnalysis::new(k.col_offsets(), k.row_indices(), &order, &split)
                .unwrap()
                .expect("the parts share no cell"),
        );
        let mut held = vec![false; k.nrows()];
        for node in mesh.boundary_nodes(tags::FAR) {
            held[2 * node] = true;
            held[2 * node + 1] = true;
        }
        (k, analysis, held)
    }

    #[test]
    fn the_split_solve_equals_the_dense_solve_with_constraints() {
        for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
            let (k, analysis, mut constrained) = split_strip(degree);
            let n = k.nrows();
            assert!(analysis.separator_len() > 0);
            assert!(analysis
                .part_sizes()
                .iter()
                .all(|&p| p > analysis.separator_len()));
            // The bottom (far) nodes held fixed, as the solver does, and one separator dof.
            constrained[analysis.separator[0]] = true;
            let factor = SplitFactor::new(&analysis, k.values(), &constrained).unwrap();
            // Dense K_C and two right-hand sides.
            let mut dense = Mat::<f64>::zeros(n, n);
            for (col, column) in k.col_iter().enumerate() {
                for (&row, &v) in column.row_indices().iter().zip(column.values()) {
                    if row == col || !(constrained[row] || constrained[col]) {
                        dense[(row, col)] = v;
                    }
                }
            }
            let rhs = Mat::<f64>::from_fn(n, 2, |i, j| ((i * 7 + j * 3) % 11) as f64 - 5.0);
            let expected = dense.partial_piv_lu().solve(rhs.as_ref());
            let mut solved = rhs.clone();
            factor.solve_in_place(solved.as_mut());
            let scale = expected.norm_max();
            let error = (&solved - &expected).norm_max();
            assert!(error <= 1e-10 * scale, "{degree:?}: {error:e} of {scale:e}");
            // One right-hand side at a time takes the single-column substitutions.
            for j in 0..2 {
                let mut one = rhs.col(j).to_owned();
                factor.solve_in_place(one.as_mat_mut());
                let error = (&one - expected.col(j)).norm_max();
                assert!(error <= 1e-10 * scale, "{degree:?}, column {j}: {error:e}");
            }
        }
    }

    #[test]
    fn a_matrix_positive_definite_in_each_part_but_not_whole_is_refused_at_the_separator() {
        // Scale the entries that couple the parts to the separator by t. Part i's matrix
        // [K_ii, t K_iS; t K_Si, K_SS] is positive definite while K_SS − t² M_i is (M_i =
        // K_Si K_ii⁻¹ K_iS), the whole while K_SS − t² (M_1 + M_2) is, and the latter is the
        // smaller: growing t in small steps, the whole loses definiteness first, in the Schur
        // complement, which must be refused with its own message (an error, not a panic).
        let (k, analysis, constrained) = split_strip(Degree::Quadratic);
        let mut on_separator = vec![false; k.nrows()];
        for &d in &analysis.separator {
            on_separator[d] = true;
        }
        let scaled = |t: f64| -> Vec<f64> {
            let mut values = k.values().to_vec();
            for (col, range) in k.col_offsets().windows(2).enumerate() {
                let rows = &k.row_indices()[range[0]..range[1]];
                for (value, &row) in values[range[0]..range[1]].iter_mut().zip(rows) {
                    if on_separator[row] != on_separator[col] {
                        *value *= t;
                    }
                }
            }
            values
        };
        assert!(SplitFactor::new(&analysis, &scaled(1.0), &constrained).is_ok());
        let mut t = 1.0;
        let refusal = loop {
            t *= 1.01;
            assert!(
                t < 100.0,
                "no scaling up to t = 100 made the matrix indefinite"
            );
            if let Err(e) = SplitFactor::new(&analysis, &scaled(t), &constrained) {
                break e.to_string();
            }
        };
        assert!(
            refusal.contains("not positive definite on the separator (pivot"),
            "at t = {t}: {refusal}"
        );
    }

    #[test]
    fn the_interleaved_dot_product_is_the_plain_one() {
        for n in 0..13 {
            let a: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 / 3.0).collect();
            let b: Vec<f64> = (0..n).map(|i| 2.0 - (i * i) as f64 / 7.0).collect();
            let plain: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
            assert!(
                (dot(&a, &b) - plain).abs() <= 1e-13 * plain.abs().max(1.0),
                "n = {n}"
            );
        }
    }

    #[test]
    fn on_the_committed_meshes_the_larger_part_costs_well_below_the_whole() {
        // The split runs its two parts side by side, so it pays when the larger carries well
        // under the whole factor's work. The level split alone gave 4.1e7 against the whole's
        // 3.4e7 on the b/a = 0.9 annulus; this build: 0.53-0.70 of the whole on these meshes.
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
        for name in ["disk-L1.msh", "annulus-0.5-L1.msh", "annulus-0.9-L1.msh"] {
            let mesh = crate::mesh::msh::read_msh(&root.join(name))
                .unwrap()
                .with_degree(Degree::Quadratic);
            let pattern = crate::discretisation::assembly::StiffnessPattern::new(&mesh).unwrap();
            let order = vertex_led_node_order(&mesh);
            let whole = crate::sparse::native::whole::SymbolicFactor::with_node_order(
                pattern.col_offsets(),
                pattern.row_indices(),
                &order,
            )
            .unwrap()
            .work();
            let split = split_nodes(&mesh).expect("the mesh splits");
            let analysis =
                SplitAnalysis::new(pattern.col_offsets(), pattern.row_indices(), &order, &split)
                    .unwrap()
                    .expect("the parts share no cell");
            let larger = analysis.part_work().into_iter().fold(0.0, f64::max);
            assert!(
                larger <= 0.75 * whole,
                "{name}: larger part {larger:.3e} against the whole {whole:.3e}"
            );
        }
    }

    #[test]
    fn a_pattern_coupling_the_parts_is_not_split() {
        let mesh = structured_rectangle(6.0, 1.0, 18, 3, tags::CONTACT, tags::AXIS, tags::FAR);
        let split = split_by_level(&mesh).expect("the strip splits");
        let first = split
            .sides
            .iter()
            .position(|&s| s == PartSide::First)
            .unwrap();
        let second = split
            .sides
            .iter()
            .position(|&s| s == PartSide::Second)
            .unwrap();
        // Every node couples to itself, and one node of each part to the other.
        let n = 2 * mesh.nodes.len();
        let (mut offsets, mut rows) = (vec![0], Vec::new());
        for d in 0..n {
            let start = rows.len();
            rows.push(d);
            let node = d / 2;
            if node == first {
                rows.extend([2 * second, 2 * second + 1]);
            } else if node == second {
                rows.extend([2 * first, 2 * first + 1]);
            }
            rows[start..].sort_unstable();
            offsets.push(rows.len());
        }
        let order: Vec<usize> = (0..mesh.nodes.len()).collect();
        assert!(SplitAnalysis::new(&offsets, &rows, &order, &split)
            .unwrap()
            .is_none());
        // The work given to run beside is done (and returned) whether or not the split applies.
        let (analysis, beside) = SplitAnalysis::new_beside(&offsets, &rows, &order, &split, || 7);
        assert!(analysis.unwrap().is_none());
        assert_eq!(beside, 7);
        let plain = structured_rectangle(6.0, 1.0, 18, 3, tags::CONTACT, tags::AXIS, tags::FAR);
        let material = Lame::from_young_poisson(1.0, 0.3);
        let k = assemble_stiffness(&plain, &material, &stiffness_rule(Degree::Linear)).unwrap();
        let (analysis, beside) =
            SplitAnalysis::new_beside(k.col_offsets(), k.row_indices(), &order, &split, || 9);
        assert!(analysis.unwrap().is_some());
        assert_eq!(beside, 9);
    }
}
