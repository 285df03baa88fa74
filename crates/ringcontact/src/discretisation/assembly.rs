//! Global stiffness matrix in compressed sparse column form (`nalgebra-sparse`).
//!
//! The sparsity pattern is built once from the connectivity (two dofs per node, `(u_r, u_z)`),
//! then element matrices are added in place; the pattern never changes afterwards, which lets the
//! Cholesky factorisation reuse its symbolic analysis whatever constraints are applied.
//!
//! Adding `K_e` needs, for every pair of a cell's nodes `(a, b)`, the position of node `a` in the
//! sorted neighbour list of node `b` (the rows of `b`'s columns). These positions are found once,
//! while the pattern is built (a dense marker per node, no search), and kept cell by cell; the
//! additions then run in parallel, each thread owning a range of columns.

use nalgebra_sparse::pattern::SparsityPattern;
use nalgebra_sparse::CscMatrix;
use rayon::prelude::*;

use crate::discretisation::element::{ElementKernel, Lame};
use crate::discretisation::far_field::FarFieldCondition;
use crate::discretisation::quadrature::TriangleRule;
use crate::discretisation::vertex_ordering::bubble_node;
use crate::error::{Error, Result};
use crate::mesh::triangulation::{Degree, Mesh};
use crate::numerics::prefetch::prefetch;

/// Bytes of element matrices computed together (in parallel) before they are added: small
/// enough to stay in cache and to cost little fresh memory (the kernel zeroes every new page:
/// 4096 cubic cells' matrices were 13 MB, written once per solve), large enough that each
/// parallel step has a few hundred cells.
const ASSEMBLY_BLOCK_BYTES: usize = 1 << 20;

/// How many nodes ahead of its lists the node pattern asks for their cells.
const PATTERN_PREFETCH_NODES: usize = 4;

/// How many cells ahead of its additions the assembly asks for `K`'s entries.
const SCATTER_PREFETCH_CELLS: usize = 4;

/// The node-level pattern of a mesh and where each cell's entries go in it.
struct NodePattern {
    /// Sorted neighbours of every node (itself included): node `n`'s are
    /// `neighbours[offsets[n]..offsets[n + 1]]`.
    offsets: Vec<usize>,
    neighbours: Vec<usize>,
    /// `positions[(c k + b) k + a]`: the position of cell `c`'s node `a` in the neighbour list
    /// of its node `b` (`k` nodes per cell).
    positions: Vec<u32>,
}

impl NodePattern {
    fn neighbours(&self, node: usize) -> &[usize] {
        &self.neighbours[self.offsets[node]..self.offsets[node + 1]]
    }
}

/// Marks a cell node pair with no entry in the pattern (a condensed bubble and another node).
const NO_ENTRY: u32 = u32::MAX;

/// Build the node pattern of `mesh`: each node's neighbours through its cells, sorted, and the
/// position of every cell node pair in them. With `condensed_bubbles`, a cubic cell's bubble node
/// couples to itself only (its pairs with the cell's other nodes are [`NO_ENTRY`]).
fn node_pattern(mesh: &Mesh, condensed_bubbles: bool) -> Result<NodePattern> {
    let nodes = mesh.nodes.len();
    let k = mesh.degree.nodes_per_cell();
    let cells = mesh.cell_count();
    // Cells of each node (counting sort).
    let mut cell_offsets = vec![0usize; nodes + 1];
    for c in 0..cells {
        for &a in mesh.cell(c) {
            cell_offsets[a + 1] += 1;
        }
    }
    for i in 0..nodes {
        cell_offsets[i + 1] += cell_offsets[i];
    }
    let mut fill = cell_offsets.clone();
    let mut cells_of = vec![0usize; cell_offsets[nodes]];
    for c in 0..cells {
        for &a in mesh.cell(c) {
            cells_of[fill[a]] = c;
            fill[a] += 1;
        }
    }
    let position_overflow = || Error::InvalidMesh {
        path: mesh.source.clone(),
        message: "a node has more than 2^32 neighbours".into(),
    };
    // `marker[m]`: the node whose list `m` was last put in, then `m`'s position in that list.
    let mut marker = vec![usize::MAX; nodes];
    let mut position = vec![0u32; nodes];
    let mut offsets = Vec::with_capacity(nodes + 1);
    let mut neighbours = Vec::with_capacity(cells_of.len() * 4);
    let mut positions = vec![0u32; cells * k * k];
    offsets.push(0);
    for node in 0..nodes {
        // The cells of a node a few ahead (their nodes and their slots), asked for now: a
        // node's cells are spread over the mesh's arrays.
        if let Some(&end) = cell_offsets.get(node + PATTERN_PREFETCH_NODES + 1) {
            for &c in &cells_of[cell_offsets[node + PATTERN_PREFETCH_NODES]..end] {
                prefetch(&mesh.cells, c * k);
                prefetch(&positions, c * k * k);
            }
        }
        let start = neighbours.len();
        let node_cells = &cells_of[cell_offsets[node]..cell_offsets[node + 1]];
        for &c in node_cells {
            let cell = mesh.cell(c);
            let bubble = condensed_bubble(cell, mesh.degree, condensed_bubbles);
            for &m in cell {
                if (m == bubble) != (node == bubble) {
                    continue;
                }
                if marker[m] != node {
                    marker[m] = node;
                    neighbours.push(m);
                }
            }
        }
        neighbours[start..].sort_unstable();
        for (p, &m) in neighbours[start..].iter().enumerate() {
            position[m] = u32::try_from(p)
                .ok()
                .filter(|&p| p != NO_ENTRY)
                .ok_or_else(position_overflow)?;
        }
        for &c in node_cells {
            let cell = mesh.cell(c);
            // The node's place in the cell (a node appears once in a valid cell).
            let b = cell.iter().position(|&m| m == node).unwrap_or(0);
            let slot = &mut positions[(c * k + b) * k..(c * k + b + 1) * k];
            let bubble = condensed_bubble(cell, mesh.degree, condensed_bubbles);
            for (out, &m) in slot.iter_mut().zip(cell) {
                *out = if (m == bubble) != (node == bubble) {
                    NO_ENTRY
                } else {
                    position[m]
                };
            }
        }
        offsets.push(neighbours.len());
    }
    Ok(NodePattern {
        offsets,
        neighbours,
        positions,
    })
}

/// The bubble node of a cubic cell when bubbles are condensed, else `usize::MAX` (no node).
fn condensed_bubble(cell: &[usize], degree: Degree, condensed_bubbles: bool) -> usize {
    match bubble_node(cell, degree) {
        Some(bubble) if condensed_bubbles => bubble,
        _ => usize::MAX,
    }
}

/// The columns of nodes `first_node..end_node` and their stored entries (values or row
/// indices): one thread's share.
struct ColumnRange<'v, T> {
    first_node: usize,
    end_node: usize,
    /// Offset in the whole entry array of `values[0]`.
    value_start: usize,
    values: &'v mut [T],
}

/// The element matrices of a block of cells and where their entries go.
struct ScatterBlock<'a> {
    mesh: &'a Mesh,
    /// [`StiffnessPattern`]'s positions of the cells' nodes in the neighbour lists.
    positions: &'a [u32],
    col_offsets: &'a [usize],
    /// The block's `K_e`, `(2k)²` values each, in cell order.
    locals: &'a [f64],
    /// The block's cells.
    cells: std::ops::Range<usize>,
}

/// Add the block's element matrices into the entries of `range`'s node columns (`K += K_e`
/// where a cell's node lies in the range), asking for the entries a few cells ahead.
#[inline]
fn scatter_block(range: &mut ColumnRange<'_, f64>, block: ScatterBlock<'_>) {
    let ScatterBlock {
        mesh,
        positions,
        col_offsets,
        locals,
        cells,
    } = block;
    let (block_start, block_end) = (cells.start, cells.end);
    let k = mesh.degree.nodes_per_cell();
    let size = 2 * k;
    for c in block_start..block_end {
        // The entries a few cells ahead, asked for now: the cells' nodes are spread
        // over K's columns.
        let ahead = c + SCATTER_PREFETCH_CELLS;
        if ahead < block_end {
            for (b, &nb) in mesh.cell(ahead).iter().enumerate() {
                if nb < range.first_node || nb >= range.end_node {
                    continue;
                }
                let slot = &positions[(ahead * k + b) * k..(ahead * k + b + 1) * k];
                for cb in 0..2 {
                    let column = col_offsets[2 * nb + cb] - range.value_start;
                    for &pos in slot {
                        prefetch(range.values, column + 2 * pos as usize);
                    }
                }
            }
        }
        let local = &locals[(c - block_start) * size * size..][..size * size];
        for (b, &nb) in mesh.cell(c).iter().enumerate() {
            if nb < range.first_node || nb >= range.end_node {
                continue;
            }
            let slot = &positions[(c * k + b) * k..(c * k + b + 1) * k];
            for cb in 0..2 {
                let column = col_offsets[2 * nb + cb] - range.value_start;
                let values = &mut range.values[column..];
                // Column `2b + cb` of the symmetric `K_e`, read as its row.
                let row = &local[(2 * b + cb) * size..][..size];
                for (&pos, pair) in slot.iter().zip(row.chunks_exact(2)) {
                    if pos == NO_ENTRY {
                        continue;
                    }
                    let base = 2 * pos as usize;
                    values[base] += pair[0];
                    values[base + 1] += pair[1];
                }
            }
        }
    }
}

/// Split the entry array (of the node columns, `col_offsets[2 × nodes]` entries) into `parts`
/// ranges of whole nodes with about equal numbers of entries.
fn column_ranges<'v, T>(
    col_offsets: &[usize],
    nodes: usize,
    parts: usize,
    mut values: &'v mut [T],
) -> Vec<ColumnRange<'v, T>> {
    let nnz = values.len();
    let mut ranges = Vec::with_capacity(parts);
    let mut first_node = 0;
    let mut value_start = 0;
    for part in 1..=parts {
        let end_node = if part == parts {
            nodes
        } else {
            let target = nnz * part / parts;
            // First node whose columns start at or after the target.
            let dof = col_offsets.partition_point(|&o| o < target);
            first_node.max(dof.div_ceil(2).min(nodes))
        };
        let value_end = col_offsets[2 * end_node];
        let (head, tail) = values.split_at_mut(value_end - value_start);
        values = tail;
        ranges.push(ColumnRange {
            first_node,
            end_node,
            value_start,
            values: head,
        });
        first_node = end_node;
        value_start = value_end;
    }
    ranges
}

/// Values per cell of a cubic cell's bubble operator `K_bb⁻¹ K_bi` (2 rows, the 18 dofs of the
/// cell's other nine nodes).
const BUBBLE_OPERATOR_LEN: usize = 36;

/// Condense the bubble (node 9, dofs 18 and 19) of a cubic element matrix `local` (20 x 20,
/// row-major) in place: `K_ii -= K_ib K_bb⁻¹ K_bi`, the bubble's couplings left as they were
/// (the pattern has no place for them), and `K_bb⁻¹ K_bi` written to `operator` (2 x 18).
fn condense_bubble(local: &mut [f64], operator: &mut [f64]) {
    const SIZE: usize = 20;
    const B: usize = 18;
    let at = |i: usize, j: usize| local[i * SIZE + j];
    let (a, b, c, d) = (at(B, B), at(B, B + 1), at(B + 1, B), at(B + 1, B + 1));
    let det = a * d - b * c;
    let inverse = [[d / det, -b / det], [-c / det, a / det]];
    for p in 0..2 {
        for j in 0..B {
            operator[p * B + j] = inverse[p][0] * at(B, j) + inverse[p][1] * at(B + 1, j);
        }
    }
    for i in 0..B {
        let (kib0, kib1) = (local[i * SIZE + B], local[i * SIZE + B + 1]);
        let row = &mut local[i * SIZE..i * SIZE + B];
        for (j, value) in row.iter_mut().enumerate() {
            *value -= kib0 * operator[j] + kib1 * operator[B + j];
        }
    }
}

/// What recovers the condensed bubbles' displacements of a cubic model
/// ([`StiffnessPattern::condensed_values`]): `u_b = -K_bb⁻¹ K_bi u_i` cell by cell.
#[derive(Clone, Debug)]
pub(crate) struct BubbleRecovery {
    /// [`BUBBLE_OPERATOR_LEN`] values of `K_bb⁻¹ K_bi` per cell, rows of 18.
    operators: Vec<f64>,
}

impl BubbleRecovery {
    /// Write every bubble's displacement into the nodal field `u` (`(u_r, u_z)` per node of the
    /// cubic `mesh` the model was assembled on, the other nodes' values final).
    pub(crate) fn recover(&self, mesh: &Mesh, u: &mut [f64]) {
        for (c, operator) in self.operators.chunks_exact(BUBBLE_OPERATOR_LEN).enumerate() {
            let cell = mesh.cell(c);
            let Some(bubble) = bubble_node(cell, mesh.degree) else {
                return;
            };
            for p in 0..2 {
                let row = &operator[p * 18..(p + 1) * 18];
                let coupled: f64 = row
                    .chunks_exact(2)
                    .zip(&cell[..9])
                    .map(|(pair, &node)| pair[0] * u[2 * node] + pair[1] * u[2 * node + 1])
                    .sum();
                u[2 * bubble + p] = -coupled;
            }
        }
    }
}

/// The sparsity pattern of a mesh's stiffness matrix (compressed sparse columns, rows sorted,
/// both triangles) and where each cell's entries go in it: known before any value, so that the
/// symbolic analysis of the factorisation can run while the values are assembled.
pub struct StiffnessPattern {
    /// Start of each column's entries (`2 × nodes + 1` of them, one more with the far-field
    /// amplitude).
    col_offsets: Vec<usize>,
    /// Row of each entry, strictly increasing in each column (so [`Self::into_matrix`] need not
    /// check it again: the fields are private and only [`Self::build`] writes them).
    row_indices: Vec<usize>,
    /// Where each column's diagonal entry is in [`Self::row_indices`], or `usize::MAX` for the
    /// dofs of a node in no cell (which have no entry at all).
    diagonal: Vec<usize>,
    nodes: NodePattern,
    /// Whether the far-field amplitude's row and column were laid out ([`Self::of_model`]).
    extended: bool,
    /// Whether cubic cells' bubble nodes are condensed ([`Self::with_condensed_bubbles`]).
    condensed: bool,
}

impl StiffnessPattern {
    /// The pattern of `mesh` (two dofs per node, `(u_r, u_z)`): dof `2n + c` couples to both
    /// dofs of every node that shares a cell with node `n`.
    pub fn new(mesh: &Mesh) -> Result<Self> {
        Self::build(mesh, false, None)
    }

    /// The pattern of `mesh` with the bubble node of every cubic cell condensed out of the
    /// coupling (for other degrees the same as [`Self::new`]): a bubble couples to itself only,
    /// and [`Self::condensed_values`] gives its cell's Schur complement instead. The bubble lies
    /// inside its cell, so it carries no load, constraint or far-field coupling of its own, and
    /// the condensed system has the full system's solution at every other node. The factorisation
    /// then no longer meets a third of the cubic mesh's nodes as small supernodes coupled to
    /// their cells (a quarter less factorisation time).
    pub fn with_condensed_bubbles(mesh: &Mesh) -> Result<Self> {
        Self::build(mesh, true, None)
    }

    /// The pattern of a model: bubbles condensed ([`Self::with_condensed_bubbles`]) and, with
    /// a far-field condition, the amplitude's row and column laid out with the rest (known before
    /// `K`'s values, so the symbolic analysis of `K̃` runs while `K` is assembled; the values then
    /// go straight into the extended layout and [`FarFieldCondition::fill_extension`] adds the
    /// new entries: no copy of `K`).
    pub(crate) fn of_model(mesh: &Mesh, far_field: Option<&FarFieldCondition>) -> Result<Self> {
        Self::build(mesh, true, far_field)
    }

    /// Columns node by node: each dof of node `n` holds both dofs of every neighbour, then the
    /// amplitude row `2 × nodes` when `n` couples to the far arc; the amplitude's own column (the
    /// coupled dofs and its diagonal) last. Written in parallel over ranges of nodes.
    fn build(mesh: &Mesh, condensed: bool, far_field: Option<&FarFieldCondition>) -> Result<Self> {
        let condensed = condensed && mesh.degree == Degree::Cubic;
        let nodes = node_pattern(mesh, condensed)?;
        let count = mesh.nodes.len();
        let amplitude = 2 * count;
        // Nodes off the arc that share a cell with an arc node couple to the amplitude.
        let coupled = match far_field {
            None => Vec::new(),
            Some(condition) => {
                let mut on_arc = vec![false; count];
                for &(dof, _) in &condition.arc {
                    on_arc[dof / 2] = true;
                }
                (0..count)
                    .map(|n| !on_arc[n] && nodes.neighbours(n).iter().any(|&m| on_arc[m]))
                    .collect()
            }
        };
        let is_coupled = |n: usize| coupled.get(n).copied().unwrap_or(false);
        let mut col_offsets = Vec::with_capacity(amplitude + 2);
        col_offsets.push(0);
        for node in 0..count {
            let len = 2 * nodes.neighbours(node).len() + usize::from(is_coupled(node));
            for _ in 0..2 {
                let last = *col_offsets.last().unwrap_or(&0);
                col_offsets.push(last + len);
            }
        }
        let node_entries = *col_offsets.last().unwrap_or(&0);
        let coupled_count = coupled.iter().filter(|&&c| c).count();
        let nnz = node_entries + far_field.map_or(0, |_| 2 * coupled_count + 1);
        let mut row_indices = vec![0usize; nnz];
        let mut diagonal = vec![usize::MAX; amplitude + usize::from(far_field.is_some())];
        let (node_rows, amplitude_rows) = row_indices.split_at_mut(node_entries);
        let ranges = column_ranges(
            &col_offsets,
            count,
            rayon::current_num_threads().max(1),
            node_rows,
        );
        // Each range's nodes' diagonal positions beside its columns.
        let mut diagonal_rest = &mut diagonal[..amplitude];
        let mut diagonal_chunks = Vec::with_capacity(ranges.len());
        for range in &ranges {
            let (chunk, rest) = diagonal_rest.split_at_mut(2 * (range.end_node - range.first_node));
            diagonal_chunks.push(chunk);
            diagonal_rest = rest;
        }
        ranges
            .into_par_iter()
            .zip(diagonal_chunks)
            .for_each(|(range, diagonal)| {
                let mut at = 0;
                for node in range.first_node..range.end_node {
                    for c in 0..2 {
                        for &m in nodes.neighbours(node) {
                            if m == node {
                                diagonal[2 * (node - range.first_node) + c] =
                                    range.value_start + at + c;
                            }
                            range.values[at] = 2 * m;
                            range.values[at + 1] = 2 * m + 1;
                            at += 2;
                        }
                        if is_coupled(node) {
                            range.values[at] = amplitude;
                            at += 1;
                        }
                    }
                }
            });
        if far_field.is_some() {
            let coupled_dofs = (0..count)
                .filter(|&n| coupled[n])
                .flat_map(|n| [2 * n, 2 * n + 1]);
            for (out, row) in amplitude_rows
                .iter_mut()
                .zip(coupled_dofs.chain([amplitude]))
            {
                *out = row;
            }
            col_offsets.push(nnz);
            diagonal[amplitude] = nnz - 1;
        }
        Ok(Self {
            col_offsets,
            row_indices,
            diagonal,
            nodes,
            extended: far_field.is_some(),
            condensed,
        })
    }

    /// Start of each column's entries in [`Self::row_indices`] (one more than the columns).
    pub fn col_offsets(&self) -> &[usize] {
        &self.col_offsets
    }

    /// Row of each entry, sorted within each column.
    pub fn row_indices(&self) -> &[usize] {
        &self.row_indices
    }

    /// Number of rows (and columns).
    pub fn dofs(&self) -> usize {
        self.col_offsets.len() - 1
    }

    /// The values of `K = Σ_e K_e` on this pattern (`mesh` the one it was made from), in the
    /// order of [`Self::row_indices`] (the far-field extension's entries, if any, zero). A
    /// pattern with condensed bubbles gives [`Self::condensed_values`]' matrix.
    ///
    /// Element matrices are computed in parallel, a block of cells at a time, then added in
    /// parallel: each thread adds the columns of its own range of nodes.
    pub fn values(&self, mesh: &Mesh, material: &Lame, rule: &TriangleRule) -> Result<Vec<f64>> {
        self.assemble(mesh, material, rule, None)
    }

    /// The values of the matrix with every cubic cell's bubble condensed: in each cell,
    /// `K_e` is replaced by `K_ii - K_ib K_bb⁻¹ K_bi` on its other nodes `i` and by `K_bb` on the
    /// bubble `b` (a block of its own), and the bubble's displacement is recovered after the
    /// solve from `u_b = -K_bb⁻¹ K_bi u_i` ([`BubbleRecovery`]; the bubble's load is zero).
    /// `None` for the recovery when the pattern condenses nothing.
    pub(crate) fn condensed_values(
        &self,
        mesh: &Mesh,
        material: &Lame,
        rule: &TriangleRule,
    ) -> Result<(Vec<f64>, Option<BubbleRecovery>)> {
        if !self.condensed {
            return Ok((self.values(mesh, material, rule)?, None));
        }
        let mut operators = vec![0.0; mesh.cell_count() * BUBBLE_OPERATOR_LEN];
        let values = self.assemble(mesh, material, rule, Some(&mut operators))?;
        Ok((values, Some(BubbleRecovery { operators })))
    }

    /// Assemble, condensing each cell's bubble when `recovery` is given (its operator
    /// `K_bb⁻¹ K_bi` written there, [`BUBBLE_OPERATOR_LEN`] values per cell).
    fn assemble(
        &self,
        mesh: &Mesh,
        material: &Lame,
        rule: &TriangleRule,
        mut recovery: Option<&mut [f64]>,
    ) -> Result<Vec<f64>> {
        let count = mesh.nodes.len();
        let dofs = 2 * count + usize::from(self.extended);
        if self.dofs() != dofs || self.condensed != recovery.is_some() {
            return Err(Error::InvalidMesh {
                path: mesh.source.clone(),
                message: "internal: the stiffness pattern belongs to another mesh".into(),
            });
        }
        let (col_offsets, nodes) = (&self.col_offsets, &self.nodes);
        // Written, not only allocated: the scatter-adds below read before they write.
        let mut values = crate::numerics::zeroed::zeros_written(self.row_indices.len());
        let k = mesh.degree.nodes_per_cell();
        let size = 2 * k;
        let mut ranges = column_ranges(
            col_offsets,
            count,
            rayon::current_num_threads().max(1),
            &mut values,
        );
        let kernel = ElementKernel::new(mesh.degree, rule);
        let block = (ASSEMBLY_BLOCK_BYTES / (8 * size * size)).min(mesh.cell_count().max(1));
        let mut locals = vec![0.0; block * size * size];
        for block_start in (0..mesh.cell_count()).step_by(block) {
            let block_end = (block_start + block).min(mesh.cell_count());
            let element = |i: usize, local: &mut [f64]| {
                let cell = mesh.cell(block_start + i);
                let vertices = [
                    mesh.nodes[cell[0]],
                    mesh.nodes[cell[1]],
                    mesh.nodes[cell[2]],
                ];
                kernel.stiffness(vertices, material, local);
            };
            let locals_in_block = &mut locals[..(block_end - block_start) * size * size];
            match recovery.as_deref_mut() {
                None => locals_in_block
                    .par_chunks_mut(size * size)
                    .enumerate()
                    .for_each(|(i, local)| element(i, local)),
                Some(operators) => locals_in_block
                    .par_chunks_mut(size * size)
                    .zip(
                        operators
                            [block_start * BUBBLE_OPERATOR_LEN..block_end * BUBBLE_OPERATOR_LEN]
                            .par_chunks_mut(BUBBLE_OPERATOR_LEN),
                    )
                    .enumerate()
                    .for_each(|(i, (local, operator))| {
                        element(i, local);
                        condense_bubble(local, operator);
                    }),
            }
            let locals = &locals;
            let positions = &nodes.positions;
            ranges.par_iter_mut().for_each(|range| {
                scatter_block(
                    range,
                    ScatterBlock {
                        mesh,
                        positions,
                        col_offsets,
                        locals,
                        cells: block_start..block_end,
                    },
                );
            });
        }
        drop(ranges);
        Ok(values)
    }

    /// The matrix of this pattern with `values` ([`Self::values`]).
    fn into_matrix(self, values: Vec<f64>) -> Result<CscMatrix<f64>> {
        self.into_matrix_and_diagonal(values)
            .map(|(matrix, _)| matrix)
    }

    /// [`Self::into_matrix`], and where each column's diagonal entry is in the matrix's entries
    /// (`usize::MAX` for a dof with none: a node in no cell), for
    /// [`crate::sparse::constrained::ConstrainedCholesky::with_symbolic_and_diagonal`].
    ///
    /// The pattern is not checked again (`nalgebra_sparse`'s check is a serial pass over every
    /// entry: 2.5 ms at 92 528 quadratic unknowns, where the whole solve takes 0.12 s): each
    /// column was written from one node's neighbour list, sorted and without repeats
    /// ([`node_pattern`]), as `2m, 2m + 1` per neighbour `m`, then the amplitude's row
    /// `2 × nodes`, larger than every other; the amplitude's column lists coupled dofs in
    /// increasing order and its own diagonal last. The test
    /// `built_patterns_pass_the_checked_constructor` holds every kind of pattern to
    /// `nalgebra_sparse`'s check.
    pub(crate) fn into_matrix_and_diagonal(
        self,
        values: Vec<f64>,
    ) -> Result<(CscMatrix<f64>, Vec<usize>)> {
        let dofs = self.dofs();
        let rejected = |message: String| Error::InvalidMesh {
            path: String::new(),
            message: format!("internal: stiffness pattern rejected: {message}"),
        };
        if values.len() != self.row_indices.len() {
            return Err(rejected(format!(
                "{} values for {} entries",
                values.len(),
                self.row_indices.len()
            )));
        }
        // Checked (one pass over the rows, about 1 ms at 1e5 unknowns) rather than trusted: no
        // `unsafe` outside the native linear-algebra backend.
        let pattern = SparsityPattern::try_from_offsets_and_indices(
            dofs,
            dofs,
            self.col_offsets,
            self.row_indices,
        )
        .map_err(|e| rejected(e.to_string()))?;
        let matrix = CscMatrix::try_from_pattern_and_values(pattern, values)
            .map_err(|e| rejected(e.to_string()))?;
        Ok((matrix, self.diagonal))
    }
}

/// Assemble `K = Σ_e K_e` for the whole mesh ([`StiffnessPattern::new`], its
/// [`StiffnessPattern::values`] and [`StiffnessPattern::into_matrix`]).
pub fn assemble_stiffness(
    mesh: &Mesh,
    material: &Lame,
    rule: &TriangleRule,
) -> Result<CscMatrix<f64>> {
    let pattern = StiffnessPattern::new(mesh)?;
    let values = pattern.values(mesh, material, rule)?;
    pattern.into_matrix(values)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretisation::element::stiffness;
    use crate::discretisation::quadrature::stiffness_rule;
    use crate::mesh::triangulation::{structured_rectangle, Degree};

    /// `K` by adding every element matrix into a dense matrix at its nodes' dofs.
    fn dense_by_definition(mesh: &Mesh, material: &Lame, rule: &TriangleRule) -> Vec<Vec<f64>> {
        let dofs = 2 * mesh.nodes.len();
        let size = 2 * mesh.degree.nodes_per_cell();
        let mut k = vec![vec![0.0; dofs]; dofs];
        let mut local = vec![0.0; size * size];
        for c in 0..mesh.cell_count() {
            let cell = mesh.cell(c);
            let vertices = [
                mesh.nodes[cell[0]],
                mesh.nodes[cell[1]],
                mesh.nodes[cell[2]],
            ];
            stiffness(mesh.degree, vertices, material, rule, &mut local);
            for i in 0..size {
                for j in 0..size {
                    k[2 * cell[i / 2] + i % 2][2 * cell[j / 2] + j % 2] += local[i * size + j];
                }
            }
        }
        k
    }

    #[test]
    fn the_assembled_matrix_is_the_sum_of_its_element_matrices() {
        let material = Lame::from_young_poisson(1.0, 0.25);
        for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
            let mesh = structured_rectangle(2.0, 1.0, 4, 3, 1, 2, 3).with_degree(degree);
            let rule = stiffness_rule(degree);
            let k = assemble_stiffness(&mesh, &material, &rule).unwrap();
            let reference = dense_by_definition(&mesh, &material, &rule);
            let scale = reference
                .iter()
                .flatten()
                .fold(0.0_f64, |m, v| m.max(v.abs()));
            let mut stored = vec![vec![false; k.ncols()]; k.ncols()];
            for (col, column) in k.col_iter().enumerate() {
                for (&row, &value) in column.row_indices().iter().zip(column.values()) {
                    stored[row][col] = true;
                    assert!(
                        (value - reference[row][col]).abs() <= 1e-13 * scale,
                        "{degree:?} ({row}, {col}): {value} against {}",
                        reference[row][col]
                    );
                }
            }
            // Nothing of the reference lies outside the pattern.
            for (row, line) in reference.iter().enumerate() {
                for (col, &value) in line.iter().enumerate() {
                    assert!(
                        stored[row][col] || value == 0.0,
                        "{degree:?} ({row}, {col})"
                    );
                }
            }
        }
    }

    /// Solve `A X = B` (dense, `A` square and nonsingular) by Gaussian elimination with partial
    /// pivoting; `B` given by columns.
    fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
        let n = a.len();
        for k in 0..n {
            let p = (k..n)
                .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
                .unwrap();
            a.swap(k, p);
            for column in b.iter_mut() {
                column.swap(k, p);
            }
            for i in k + 1..n {
                let f = a[i][k] / a[k][k];
                let pivot_row = a[k].clone();
                for (value, pivot) in a[i][k..].iter_mut().zip(&pivot_row[k..]) {
                    *value -= f * pivot;
                }
                for column in b.iter_mut() {
                    column[i] -= f * column[k];
                }
            }
        }
        for column in b.iter_mut() {
            for i in (0..n).rev() {
                let s: f64 = (i + 1..n).map(|j| a[i][j] * column[j]).sum();
                column[i] = (column[i] - s) / a[i][i];
            }
        }
        b
    }

    #[test]
    fn the_condensed_matrix_is_the_schur_complement_on_the_bubbles_and_recovers_them() {
        // By definition, with the bubble dofs B and the others I of the full dense K:
        // K_c = K_II - K_IB K_BB⁻¹ K_BI on I, K_BB on B, no coupling; u_B = -K_BB⁻¹ K_BI u_I.
        let material = Lame::from_young_poisson(1.0, 0.3);
        let mesh = structured_rectangle(2.0, 1.0, 3, 2, 1, 2, 3).with_degree(Degree::Cubic);
        let rule = stiffness_rule(Degree::Cubic);
        let k = dense_by_definition(&mesh, &material, &rule);
        let n = k.len();
        let mut is_bubble = vec![false; n];
        for c in 0..mesh.cell_count() {
            let b = mesh.cell(c)[9];
            is_bubble[2 * b] = true;
            is_bubble[2 * b + 1] = true;
        }
        let (bubbles, others): (Vec<usize>, Vec<usize>) = (0..n).partition(|&d| is_bubble[d]);
        let k_bb: Vec<Vec<f64>> = bubbles
            .iter()
            .map(|&i| bubbles.iter().map(|&j| k[i][j]).collect())
            .collect();
        // K_BB⁻¹ K_BI, by columns (one per dof of I).
        let k_bi: Vec<Vec<f64>> = others
            .iter()
            .map(|&j| bubbles.iter().map(|&i| k[i][j]).collect())
            .collect();
        let solved = dense_solve(k_bb, k_bi);
        let pattern = StiffnessPattern::with_condensed_bubbles(&mesh).unwrap();
        let (values, recovery) = pattern.condensed_values(&mesh, &material, &rule).unwrap();
        let recovery = recovery.expect("a cubic mesh has bubbles to recover");
        let condensed = pattern.into_matrix(values).unwrap();
        let mut dense = vec![vec![0.0; n]; n];
        for (col, column) in condensed.col_iter().enumerate() {
            for (&row, &value) in column.row_indices().iter().zip(column.values()) {
                dense[row][col] = value;
            }
        }
        let scale = k.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        for &i in &others {
            for (c, &j) in others.iter().enumerate() {
                let schur = k[i][j]
                    - bubbles
                        .iter()
                        .enumerate()
                        .map(|(q, &b)| k[i][b] * solved[c][q])
                        .sum::<f64>();
                assert!(
                    (dense[i][j] - schur).abs() <= 1e-12 * scale,
                    "({i}, {j}): {} against {schur}",
                    dense[i][j]
                );
            }
            for &b in &bubbles {
                assert_eq!(dense[i][b], 0.0, "({i}, {b}) couples a bubble");
                assert_eq!(dense[b][i], 0.0, "({b}, {i}) couples a bubble");
            }
        }
        for &i in &bubbles {
            for &j in &bubbles {
                assert!((dense[i][j] - k[i][j]).abs() <= 1e-12 * scale, "({i}, {j})");
            }
        }
        // Recovery from an arbitrary field on I.
        let mut u: Vec<f64> = (0..n)
            .map(|d| ((d * 7919) % 101) as f64 / 50.0 - 1.0)
            .collect();
        let expected: Vec<f64> = (0..bubbles.len())
            .map(|q| {
                -others
                    .iter()
                    .enumerate()
                    .map(|(c, &j)| solved[c][q] * u[j])
                    .sum::<f64>()
            })
            .collect();
        recovery.recover(&mesh, &mut u);
        for (q, &b) in bubbles.iter().enumerate() {
            assert!(
                (u[b] - expected[q]).abs() <= 1e-12 * expected[q].abs().max(1.0),
                "bubble dof {b}: {} against {}",
                u[b],
                expected[q]
            );
        }
    }

    #[test]
    fn only_cubic_patterns_condense() {
        let material = Lame::from_young_poisson(1.0, 0.3);
        for degree in [Degree::Linear, Degree::Quadratic] {
            let mesh = structured_rectangle(1.0, 1.0, 2, 2, 1, 2, 3).with_degree(degree);
            let rule = stiffness_rule(degree);
            let full = assemble_stiffness(&mesh, &material, &rule).unwrap();
            let pattern = StiffnessPattern::with_condensed_bubbles(&mesh).unwrap();
            let (values, recovery) = pattern.condensed_values(&mesh, &material, &rule).unwrap();
            assert!(recovery.is_none(), "{degree:?}");
            assert_eq!(values, full.values(), "{degree:?}");
        }
    }

    #[test]
    fn the_column_ranges_cover_every_node_once_whatever_the_parts() {
        let mesh = structured_rectangle(1.0, 1.0, 2, 1, 1, 2, 3);
        let pattern = StiffnessPattern::new(&mesh).unwrap();
        let nodes = mesh.nodes.len();
        for parts in [1, 2, 3, nodes, nodes + 5] {
            let mut values = vec![0.0; pattern.row_indices.len()];
            let ranges = column_ranges(&pattern.col_offsets, nodes, parts, &mut values);
            assert_eq!(ranges.len(), parts);
            let mut next = 0;
            for range in &ranges {
                assert_eq!(range.first_node, next);
                assert_eq!(range.value_start, pattern.col_offsets[2 * next]);
                next = range.end_node;
                assert_eq!(
                    range.values.len(),
                    pattern.col_offsets[2 * next] - range.value_start
                );
            }
            assert_eq!(next, nodes, "{parts} parts");
        }
    }

    /// Every kind of pattern `build` makes (degrees 1-3, bubbles condensed or not, with and
    /// without the far-field amplitude; a structured mesh and a committed gmsh mesh), on its way
    /// into a matrix: `nalgebra_sparse`'s own checked constructor accepts it (what
    /// [`StiffnessPattern::into_matrix_and_diagonal`] no longer asks it to check), and the
    /// diagonal positions it reports are those a search of each column finds.
    fn every_built_pattern() -> Vec<(String, StiffnessPattern)> {
        let material = Lame::from_young_poisson(1.0, 0.3);
        let gmsh = crate::mesh::msh::read_msh(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../meshes/annulus-0.5-L0.msh"
        )))
        .unwrap();
        let mut patterns = Vec::new();
        for (name, vertex_mesh) in [
            ("structured", structured_rectangle(2.0, 1.0, 3, 2, 1, 2, 3)),
            ("annulus-0.5-L0", gmsh),
        ] {
            for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
                let mesh = vertex_mesh.with_degree(degree);
                let radius = mesh
                    .boundary_nodes(crate::mesh::triangulation::tags::FAR)
                    .iter()
                    .map(|&n| mesh.nodes[n][0].hypot(mesh.nodes[n][1]))
                    .fold(0.0, f64::max);
                let condition = FarFieldCondition::new(&mesh, &material, radius.max(1.0));
                for condensed in [false, true] {
                    for far in [None, Some(&condition)] {
                        let label = format!(
                            "{name} {degree:?} condensed {condensed} far {}",
                            far.is_some()
                        );
                        let pattern = StiffnessPattern::build(&mesh, condensed, far).unwrap();
                        patterns.push((label, pattern));
                    }
                }
            }
        }
        patterns
    }

    #[test]
    fn built_patterns_pass_the_checked_constructor() {
        for (label, pattern) in every_built_pattern() {
            let (dofs, nnz) = (pattern.dofs(), pattern.row_indices.len());
            let checked = CscMatrix::try_from_csc_data(
                dofs,
                dofs,
                pattern.col_offsets.clone(),
                pattern.row_indices.clone(),
                vec![1.0; nnz],
            );
            assert!(checked.is_ok(), "{label}: {:?}", checked.err());
            let (unchecked, _) = pattern.into_matrix_and_diagonal(vec![1.0; nnz]).unwrap();
            assert_eq!(unchecked, checked.unwrap(), "{label}");
        }
    }

    #[test]
    fn assembled_diagonal_positions_are_the_diagonal() {
        for (label, pattern) in every_built_pattern() {
            let nnz = pattern.row_indices.len();
            let (matrix, diagonal) = pattern.into_matrix_and_diagonal(vec![0.0; nnz]).unwrap();
            let (offsets, rows) = (matrix.col_offsets(), matrix.row_indices());
            assert_eq!(diagonal.len(), matrix.ncols(), "{label}");
            for (col, &position) in diagonal.iter().enumerate() {
                let searched = (offsets[col]..offsets[col + 1]).find(|&k| rows[k] == col);
                assert_eq!(Some(position), searched, "{label}: column {col}");
            }
        }
    }

    #[test]
    fn into_matrix_rejects_values_of_another_length() {
        let mesh = structured_rectangle(1.0, 1.0, 2, 2, 1, 2, 3);
        let pattern = StiffnessPattern::new(&mesh).unwrap();
        let nnz = pattern.row_indices.len();
        let error = pattern.into_matrix(vec![0.0; nnz + 1]).unwrap_err();
        assert!(error.to_string().contains("values for"), "{error}");
    }

    #[test]
    fn the_far_field_layout_is_the_extended_matrix_by_definition() {
        // K̃ = [K, K T g; gᵀ Tᵀ K, gᵀ K_aa g + k_ext] with the arc's coupling kept off the arc
        // rows; here the bottom side (tag 3, the far boundary's) plays the arc.
        let material = Lame::from_young_poisson(1.0, 0.3);
        for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
            let mesh = structured_rectangle(2.0, 1.0, 3, 2, 1, 2, 3).with_degree(degree);
            let rule = stiffness_rule(degree);
            let condition = FarFieldCondition::new(&mesh, &material, 2.0);
            // The model's layout without the bubbles' condensation (of `K` itself, as defined);
            // with it, the same layout at every other node (checked below).
            let pattern = StiffnessPattern::build(&mesh, false, Some(&condition)).unwrap();
            let condensed = StiffnessPattern::of_model(&mesh, Some(&condition)).unwrap();
            if degree != Degree::Cubic {
                assert_eq!(condensed.row_indices, pattern.row_indices, "{degree:?}");
            }
            assert_eq!(condensed.dofs(), pattern.dofs(), "{degree:?}");
            // The amplitude couples to the same dofs but the bubbles (which, condensed, couple
            // to their own node only).
            let amplitude_column = |p: &StiffnessPattern| {
                let n = p.dofs() - 1;
                p.row_indices[p.col_offsets[n]..p.col_offsets[n + 1]].to_vec()
            };
            let bubbles: Vec<usize> = (0..mesh.cell_count())
                .filter_map(|c| bubble_node(mesh.cell(c), degree))
                .flat_map(|b| [2 * b, 2 * b + 1])
                .collect();
            let mut expected = amplitude_column(&pattern);
            expected.retain(|row| !bubbles.contains(row));
            assert_eq!(amplitude_column(&condensed), expected, "{degree:?}");
            let mut values = pattern.values(&mesh, &material, &rule).unwrap();
            condition.fill_extension(&pattern.col_offsets, &pattern.row_indices, &mut values);
            let extended = pattern.into_matrix(values).unwrap();

            let k = dense_by_definition(&mesh, &material, &rule);
            let n = k.len();
            let (mut g, mut on_arc) = (vec![0.0; n], vec![false; n]);
            for &(dof, value) in &condition.arc {
                g[dof] = value;
                on_arc[dof] = true;
            }
            let mut reference = vec![vec![0.0; n + 1]; n + 1];
            for i in 0..n {
                reference[i][..n].copy_from_slice(&k[i]);
                if !on_arc[i] {
                    reference[i][n] = (0..n).map(|j| k[i][j] * g[j]).sum();
                    reference[n][i] = reference[i][n];
                }
            }
            reference[n][n] = condition.exterior_stiffness
                + (0..n)
                    .flat_map(|i| (0..n).map(move |j| (i, j)))
                    .map(|(i, j)| g[i] * k[i][j] * g[j])
                    .sum::<f64>();
            let scale = k.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
            let mut dense = vec![vec![0.0; n + 1]; n + 1];
            for (col, column) in extended.col_iter().enumerate() {
                let rows = column.row_indices();
                assert!(
                    rows.windows(2).all(|w| w[0] < w[1]),
                    "{degree:?} column {col}"
                );
                for (&row, &value) in rows.iter().zip(column.values()) {
                    dense[row][col] = value;
                }
            }
            for i in 0..=n {
                for j in 0..=n {
                    assert!(
                        (dense[i][j] - reference[i][j]).abs() <= 1e-12 * scale,
                        "{degree:?} ({i}, {j}): {} against {}",
                        dense[i][j],
                        reference[i][j]
                    );
                }
            }
        }
    }
}
