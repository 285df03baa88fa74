//! A two-way split of a mesh's nodes by a small separator, so that the two parts of the
//! stiffness matrix can be factorised on two cores ([`crate::sparse::native::split`]). Each part is
//! eliminated in the whole model's order ([`crate::discretisation::vertex_ordering`]) with the separator last;
//! two candidate splits are made and the one of the lesser estimated critical path is kept
//! ([`split_nodes_of`]):
//!
//! - **The tree split**, read off the elimination tree of the vertex graph in that order. Two
//!   subtrees share no edge, so once a separator `S` closed under taking parents (the top of the
//!   tree) is removed, the remaining trees can be dealt to the two parts freely, and every part
//!   column is the whole factor's own column. `S` grows from the root, the heaviest remaining
//!   tree giving up its root, and of the separators met on the way the one with the least
//!   estimated critical path is kept. Minimum-degree trees are often a long chain with small
//!   subtrees along it, and then no small `S` balances the parts.
//! - **The level split**: one breadth-first level of the vertex graph ([`level_split`]), the
//!   smallest that leaves about half the vertices on each side. On the graded meshes of this
//!   project the levels are rings around the refined points. Forcing a ring last costs work, and
//!   equal vertex counts need not carry equal work: when that level's estimate finds one part
//!   heavier than the other by more than a tenth, the level that should balance them
//!   ([`rebalanced_level`]) is estimated as well. On the 92 528-unknown annulus (`b/a` = 0.3,
//!   P2) the central level's parts carried 3.95e8 and 2.88e8 multiply-adds (`faer`'s count),
//!   the rebalanced level's 3.34e8 and 3.25e8. When the rebalanced level is still unbalanced
//!   (the rate model overshot or fell short), one secant step between the two levels is
//!   estimated as well ([`interpolated_level`]): on the 14 558-unknown annulus (`b/a` = 0.5, P2)
//!   the central level left 1.75e7 and 2.81e7, the rebalanced one overshot, and the secant's
//!   2.45e7 and 2.42e7 took 9 % less factorisation time.
//!
//! The estimate is the vertex-level elimination ([`Elimination`]): each vertex's weighted column
//! in the vertex-level factor, weighted by the dofs it brings, gives its columns' work; the
//! critical path is the heavier part's work plus the separator's dense work ([`critical_path`]).
//! On the 12 880-unknown annulus (`b/a` = 0.9, P2) the level split's parts carried 4.1e7 and 1.2e7
//! multiply-adds, its larger part more than the whole factor's 3.4e7; the tree split's carry
//! 1.6e7 and 1.8e7. On the 27 432-unknown annulus (`b/a` = 0.3) the tree's best split left 6.4e7
//! against 1.7e7 and the level split (5.2e7 each) is kept.
//!
//! Inner nodes of an edge and bubble nodes go with the part of their edge's or cell's vertices
//! off the separator (a cell touches at most one part); those of edges and cells lying wholly on
//! the separator join it.

use std::cmp::Ordering;
use std::collections::VecDeque;

use crate::discretisation::vertex_ordering::{
    bubble_node, edge_inner_nodes, edge_layout, vertex_graph, vertex_order, VertexCells,
    VertexGraph,
};
use crate::mesh::triangulation::Mesh;

pub use crate::sparse::{NodeSplit, Side};

/// Most separator dofs the descent from the root considers (the dense Schur complement's cost
/// grows like their cube).
const MAX_SEPARATOR_DOFS: usize = 1_200;

/// Most vertices for which the candidate splits are estimated; beyond, the level split is
/// taken as it is. The estimate's two or three vertex-level eliminations grow faster than the
/// pattern they run beside (one core, warm: 22 ms against a pattern of 19-23 ms at 9e4 P2 unknowns, 11 779
/// vertices; 288 ms against 245 ms at 6.4e5), and beyond this size (1.5e5-1.4e6 unknowns) the
/// level split's parts carry the same work within 10 %.
const ESTIMATED_SPLIT_MAX_VERTICES: usize = 16_000;

/// Fractions of the vertices each part of a level split must hold at least, tried in turn: a
/// nearly even split first, then a looser one.
const MIN_PART_SHARES: [f64; 2] = [0.47, 0.4];

/// Exponent of a part's factorisation work in its share of the vertices, for
/// [`rebalanced_level`] (nested dissection of a planar mesh of `n` vertices takes `O(n^1.5)`).
const PART_WORK_EXPONENT: f64 = 1.5;

/// Parts' estimated works within this factor of each other are taken as balanced.
const BALANCED_PARTS: f64 = 1.1;

/// No tree marker.
const NONE: usize = usize::MAX;

/// The vertex-level elimination of the vertex graph in an order (graph vertex indices), by tree
/// positions (`k`: the `k`-th eliminated vertex).
struct Elimination {
    /// Parent of each position in the elimination tree, or [`NONE`] for a root.
    parent: Vec<usize>,
    /// Dofs each position's vertex brings: its own two and two per inner node of its edges to
    /// later vertices (the vertex-led order places those just before it).
    weight: Vec<usize>,
    /// Estimated work of each position's dof columns ([`column_work`]).
    work: Vec<f64>,
}

impl Elimination {
    fn of(mesh: &Mesh, graph: &VertexGraph, order: &[usize]) -> Self {
        let graph = PositionGraph::new(graph, order);
        let parent = elimination_tree(&graph);
        let (per_edge, _) = edge_layout(mesh.degree);
        let weight: Vec<usize> = (0..graph.len())
            .map(|k| {
                let later = graph.neighbours(k).iter().filter(|&&i| i > k).count();
                2 * (1 + per_edge * later)
            })
            .collect();
        let work = column_work(&graph, &parent, &weight);
        Self {
            parent,
            weight,
            work,
        }
    }
}

/// The vertex graph renumbered by elimination position, its rows laid out in that order: the
/// elimination's passes then read it front to back instead of at random (the estimate's extra
/// ordering time, one core: 9.1 to 6.1 ms at 9e4 P2 unknowns, 31 to 22 ms at 2.4e5).
struct PositionGraph {
    offsets: Vec<usize>,
    rows: Vec<usize>,
}

impl PositionGraph {
    fn new(graph: &VertexGraph, order: &[usize]) -> Self {
        let mut position = vec![NONE; order.len()];
        for (k, &v) in order.iter().enumerate() {
            position[v] = k;
        }
        let mut offsets = Vec::with_capacity(order.len() + 1);
        let mut rows = Vec::with_capacity(graph.rows.len());
        offsets.push(0);
        for &v in order {
            rows.extend(graph.neighbours(v).iter().map(|&w| position[w]));
            offsets.push(rows.len());
        }
        Self { offsets, rows }
    }

    fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The positions adjacent to position `k` (itself included).
    fn neighbours(&self, k: usize) -> &[usize] {
        &self.rows[self.offsets[k]..self.offsets[k + 1]]
    }
}

/// Elimination tree of the graph by positions: `parent[k]` is the position of the parent of the
/// `k`-th eliminated vertex, or [`NONE`] for a root (Liu's algorithm with path compression).
fn elimination_tree(graph: &PositionGraph) -> Vec<usize> {
    let n = graph.len();
    let mut parent = vec![NONE; n];
    let mut ancestor = vec![NONE; n];
    for k in 0..n {
        for &start in graph.neighbours(k) {
            let mut i = start;
            if i >= k {
                continue;
            }
            // Climb from i to its current root, pointing the path at k.
            while ancestor[i] != NONE && ancestor[i] != k {
                let next = ancestor[i];
                ancestor[i] = k;
                i = next;
            }
            if ancestor[i] == NONE {
                ancestor[i] = k;
                parent[i] = k;
            }
        }
    }
    parent
}

/// The estimated factorisation work of each tree position's columns, in the units of
/// [`crate::sparse::native::whole::factorisation_work`] (`Σ c²` over the columns, `c` the
/// column's entries): vertex `k` brings `weight[k]` dof columns eliminated together, of
/// `W_k, W_k − 1, …` entries, `W_k` the weighted size of its column in the vertex-level factor
/// (its own weight and those of the rows below it, [`weighted_column_counts`]).
fn column_work(graph: &PositionGraph, parent: &[usize], weight: &[usize]) -> Vec<f64> {
    weighted_column_counts(graph, parent, weight)
        .iter()
        .zip(weight)
        .map(|(&count, &w)| {
            // Σ_{j < w} (w − j + below)² for the vertex's w columns, in closed form.
            let (w, b) = (w as f64, count.saturating_sub(w) as f64);
            w * (w + 1.0) * (2.0 * w + 1.0) / 6.0 + b * w * (w + 1.0) + b * b * w
        })
        .collect()
}

/// Each tree position's first child and next sibling ([`NONE`] where there is none), children
/// in increasing position.
fn child_lists(parent: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let n = parent.len();
    let mut first_child = vec![NONE; n];
    let mut next_sibling = vec![NONE; n];
    for k in (0..n).rev() {
        if parent[k] != NONE {
            next_sibling[k] = first_child[parent[k]];
            first_child[parent[k]] = k;
        }
    }
    (first_child, next_sibling)
}

/// The weighted column counts of the vertex-level factor: for each position `j`, the sum of
/// `weight[i]` over the rows `i` of its column (the diagonal `i = j` included). Gilbert, Ng and
/// Peyton's algorithm (as `cs_counts` in Davis, *Direct Methods for Sparse Linear Systems*,
/// 2006, §4.5) with each row counted by its weight: row `i`'s subtree of the elimination tree
/// gets `+w_i` at each of its leaves, `−w_i` at the least common ancestor of each two
/// consecutive leaves and at the parent of its root `i`, so that the sum of these over the
/// subtree of `j` is the weight of the rows in column `j`. Time nearly linear in the graph's
/// entries, where merging the columns' structures up the tree is linear in the factor's: at
/// 92 528 quadratic unknowns (11 779 vertices) 1.0-1.3 ms against 1.5-2.0 ms, alternated in one
/// process, and the whole split's search 7.3-7.8 against 8.5-10.2 ms.
fn weighted_column_counts(graph: &PositionGraph, parent: &[usize], weight: &[usize]) -> Vec<usize> {
    let n = graph.len();
    // Postorder of the tree (children before parents, each subtree contiguous).
    let (mut first_child, next_sibling) = child_lists(parent);
    let mut post = Vec::with_capacity(n);
    let mut stack = Vec::new();
    for root in (0..n).filter(|&k| parent[k] == NONE) {
        stack.push(root);
        while let Some(&top) = stack.last() {
            let child = first_child[top];
            if child == NONE {
                post.push(top);
                stack.pop();
            } else {
                // Visit the child next; unlink it so that the parent's next child comes after.
                first_child[top] = next_sibling[child];
                stack.push(child);
            }
        }
    }
    // first[j]: postorder number of j's first descendant; a leaf is its own.
    let mut first = vec![NONE; n];
    // Signed sums in i64: a subtree's sums stay non-negative, the deltas need not.
    let mut delta = vec![0i64; n];
    for (k, &j) in post.iter().enumerate() {
        if first[j] == NONE {
            delta[j] = weight[j] as i64;
        }
        let mut up = j;
        while up != NONE && first[up] == NONE {
            first[up] = k;
            up = parent[up];
        }
    }
    let mut max_first = vec![NONE; n];
    let mut previous_leaf = vec![NONE; n];
    let mut ancestor: Vec<usize> = (0..n).collect();
    for &j in &post {
        if parent[j] != NONE {
            delta[parent[j]] -= weight[j] as i64;
        }
        for &i in graph.neighbours(j) {
            // Is j a leaf of row i's subtree (a descendant of no earlier one of its leaves)?
            if i <= j || (max_first[i] != NONE && first[j] <= max_first[i]) {
                continue;
            }
            max_first[i] = first[j];
            let previous = previous_leaf[i];
            previous_leaf[i] = j;
            delta[j] += weight[i] as i64;
            if previous != NONE {
                // The least common ancestor of the previous leaf and j, with path compression.
                let mut q = previous;
                while q != ancestor[q] {
                    q = ancestor[q];
                }
                let mut s = previous;
                while s != q {
                    let next = ancestor[s];
                    ancestor[s] = q;
                    s = next;
                }
                delta[q] -= weight[i] as i64;
            }
        }
        if parent[j] != NONE {
            ancestor[j] = parent[j];
        }
    }
    // Children come before their parents in position order.
    for j in 0..n {
        if parent[j] != NONE {
            delta[parent[j]] += delta[j];
        }
    }
    delta.iter().map(|&d| d.max(0) as usize).collect()
}

/// How much faster a multiply-add runs in the separator's dense blocks than in the parts'
/// sparse factorisation, for [`critical_path`]: `faer`'s dense kernels run at 20-27 GFMA/s on
/// the 2-core machine, its supernodal factorisation of these meshes at 5-8 (benches/
/// FENICSX_SPEED.md, *A multifrontal factorisation, tried*). Counted at par, a separator a few
/// dofs longer outweighed a balance of the parts worth 9 % of the factorisation (14 558-unknown
/// annulus, `b/a` = 0.5: parts of 1.75e7 and 2.81e7 multiply-adds behind 134 separator dofs,
/// 7.6 ms, against 2.45e7 and 2.42e7 behind 168, 6.9 ms).
const DENSE_SPEEDUP: f64 = 4.0;

/// Estimated critical path of a split with parts of works `parts` and `separator_dofs`
/// separator dofs, in sparse multiply-adds: the heavier part plus the separator's dense work
/// that is not shared between the cores, `4 s³ / 3` (its block in one part, `s³ / 3`; the two
/// parts' products and the Schur complement's factorisation, `s³ / 3` each), which runs
/// [`DENSE_SPEEDUP`] times faster.
fn critical_path(parts: [f64; 2], separator_dofs: usize) -> f64 {
    let s = separator_dofs as f64;
    parts[0].max(parts[1]) + 4.0 * s * s * s / (3.0 * DENSE_SPEEDUP)
}

/// Deal trees (their works) to two parts, heaviest first, each to the lighter part so far:
/// the two parts' works and each tree's part (`false`: the first).
fn deal(trees: &[f64]) -> ([f64; 2], Vec<bool>) {
    let mut sorted: Vec<usize> = (0..trees.len()).collect();
    sorted.sort_by(|&a, &b| trees[b].partial_cmp(&trees[a]).unwrap_or(Ordering::Equal));
    let mut parts = [0.0, 0.0];
    let mut second = vec![false; trees.len()];
    for i in sorted {
        let to_second = parts[1] < parts[0];
        second[i] = to_second;
        parts[usize::from(to_second)] += trees[i];
    }
    (parts, second)
}

/// The split read off the elimination tree (module documentation): its estimated critical path
/// and each tree position's side, or `None` when no separator of at most
/// [`MAX_SEPARATOR_DOFS`] dofs leaves two parts.
fn tree_split(elimination: &Elimination) -> Option<(f64, Vec<Side>)> {
    let Elimination {
        parent,
        weight,
        work,
    } = elimination;
    let n = parent.len();
    let mut subtree = work.clone();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); n];
    for k in 0..n {
        if parent[k] != NONE {
            subtree[parent[k]] += subtree[k];
            children[parent[k]].push(k);
        }
    }
    let roots: Vec<usize> = (0..n).filter(|&k| parent[k] == NONE).collect();
    // Descend from the roots, the heaviest tree giving up its root at each step; remember the
    // step with the least estimated critical path.
    let mut forest = roots.clone();
    let mut separator_dofs = 0usize;
    let mut taken: Vec<usize> = Vec::new();
    let mut best: Option<(f64, usize)> = None;
    while !forest.is_empty() {
        let trees: Vec<f64> = forest.iter().map(|&k| subtree[k]).collect();
        // No deeper separator can beat the best: its parts hold at least half the forest.
        let forest_work: f64 = trees.iter().sum();
        if best.is_some_and(|(e, _)| critical_path([forest_work / 2.0; 2], separator_dofs) >= e) {
            break;
        }
        let (parts, _) = deal(&trees);
        if parts[0] > 0.0 && parts[1] > 0.0 {
            let estimate = critical_path(parts, separator_dofs);
            if best.is_none_or(|(e, _)| estimate < e) {
                best = Some((estimate, taken.len()));
            }
        }
        let heaviest = (0..forest.len())
            .max_by(|&a, &b| trees[a].partial_cmp(&trees[b]).unwrap_or(Ordering::Equal))
            .unwrap_or(0);
        let root = forest.swap_remove(heaviest);
        separator_dofs += weight[root];
        if separator_dofs > MAX_SEPARATOR_DOFS {
            break;
        }
        taken.push(root);
        forest.extend_from_slice(&children[root]);
    }
    let (estimate, steps) = best?;
    // Replay the descent to the best separator, then deal its forest.
    let mut side = vec![Side::First; n];
    let mut forest = roots;
    for &root in &taken[..steps] {
        side[root] = Side::Separator;
        forest.retain(|&k| k != root);
        forest.extend_from_slice(&children[root]);
    }
    let trees: Vec<f64> = forest.iter().map(|&k| subtree[k]).collect();
    let (_, second) = deal(&trees);
    let mut assigned = vec![false; n];
    for (tree, &root) in forest.iter().enumerate() {
        side[root] = if second[tree] {
            Side::Second
        } else {
            Side::First
        };
        assigned[root] = true;
    }
    // A parent comes after its children: walk down from the top, each position taking its
    // parent's side (the separator's children are the roots, already dealt).
    for k in (0..n).rev() {
        if side[k] != Side::Separator && !assigned[k] {
            side[k] = side[parent[k]];
        }
    }
    Some((estimate, side))
}

/// Breadth-first levels of the vertex graph from graph vertex `start`: `(level of each vertex,
/// last vertex reached)`; vertices not reached keep `usize::MAX`.
fn levels_from(graph: &VertexGraph, start: usize) -> (Vec<usize>, usize) {
    let mut level = vec![usize::MAX; graph.vertices.len()];
    let mut queue = VecDeque::from([start]);
    level[start] = 0;
    let mut last = start;
    while let Some(v) = queue.pop_front() {
        last = v;
        for &w in graph.neighbours(v) {
            if level[w] == usize::MAX {
                level[w] = level[v] + 1;
                queue.push_back(w);
            }
        }
    }
    (level, last)
}

/// The breadth-first levels of the vertex graph from a pseudo-peripheral vertex (the last
/// vertex reached from an arbitrary start), with the number of vertices on each level.
struct Levels {
    level: Vec<usize>,
    per_level: Vec<usize>,
}

impl Levels {
    /// The levels of `graph`, or `None` when it is disconnected.
    fn of(graph: &VertexGraph) -> Option<Self> {
        let (_, far) = levels_from(graph, 0);
        let (level, _) = levels_from(graph, far);
        if level.contains(&usize::MAX) {
            return None;
        }
        let depth = level.iter().max().copied().unwrap_or(0) + 1;
        let mut per_level = vec![0usize; depth];
        for &l in &level {
            per_level[l] += 1;
        }
        Some(Self { level, per_level })
    }

    /// Share of the vertices on the levels before `cut`.
    fn share_before(&self, cut: usize) -> f64 {
        let before: usize = self.per_level[..cut].iter().sum();
        before as f64 / self.level.len() as f64
    }

    /// The smallest level with at least `share` of the vertices before it and after it.
    fn smallest_central(&self, share: f64) -> Option<usize> {
        let count = self.level.len();
        let least = (share * count as f64).ceil() as usize;
        let mut before = 0;
        let mut best: Option<(usize, usize)> = None;
        for (l, &size) in self.per_level.iter().enumerate() {
            let after = count - before - size;
            if before >= least && after >= least && best.is_none_or(|(_, s)| size < s) {
                best = Some((l, size));
            }
            before += size;
        }
        best.map(|(l, _)| l)
    }

    /// The level whose share of the vertices before it is nearest `share` (neither the first
    /// level nor the last: both parts hold vertices).
    fn nearest_share(&self, share: f64) -> Option<usize> {
        let count = self.level.len() as f64;
        let mut before = 0;
        let mut nearest: Option<(usize, f64)> = None;
        for (l, &size) in self.per_level.iter().enumerate() {
            let distance = (before as f64 / count - share).abs();
            let inner = l > 0 && l + 1 < self.per_level.len();
            if inner && nearest.is_none_or(|(_, d)| distance < d) {
                nearest = Some((l, distance));
            }
            before += size;
        }
        nearest.map(|(l, _)| l)
    }

    /// Each graph vertex's side when level `cut` is the separator: the levels before it form
    /// the first part, those after it the second.
    fn sides(&self, cut: usize) -> Vec<Side> {
        self.level
            .iter()
            .map(|&l| match l.cmp(&cut) {
                Ordering::Less => Side::First,
                Ordering::Greater => Side::Second,
                Ordering::Equal => Side::Separator,
            })
            .collect()
    }
}

/// The level of the level split: of the levels that leave 47-53 % of the vertices on each side
/// (else 40-60 %), the smallest. On the graded meshes of this project the levels are rings
/// around the refined points.
fn central_level(levels: &Levels) -> Option<usize> {
    MIN_PART_SHARES
        .iter()
        .find_map(|&share| levels.smallest_central(share))
}

/// The split by the [`central_level`] of the vertex graph's [`Levels`]: each graph vertex's
/// side, or `None` when the graph is disconnected or no level qualifies.
fn level_split(graph: &VertexGraph) -> Option<Vec<Side>> {
    let levels = Levels::of(graph)?;
    Some(levels.sides(central_level(&levels)?))
}

/// The level whose split should carry equal work in its two parts, from the estimated works
/// `parts` of the split at level `cut`: each part's work taken to grow like its share of the
/// vertices to the power [`PART_WORK_EXPONENT`], with the density the split at `cut` shows
/// (`p_1 = c_1 s^γ`, `p_2 = c_2 (1 − s)^γ`, equal where `s / (1 − s) = (c_2 / c_1)^{1/γ}`).
/// `None` when the parts are within [`BALANCED_PARTS`] of each other or that level is `cut`.
fn rebalanced_level(levels: &Levels, cut: usize, parts: [f64; 2]) -> Option<usize> {
    if parts[0].min(parts[1]) <= 0.0 || balanced(parts) {
        return None;
    }
    let share = levels.share_before(cut);
    let first_density = parts[0] / share.powf(PART_WORK_EXPONENT);
    let second_density = parts[1] / (1.0 - share).powf(PART_WORK_EXPONENT);
    let ratio = (second_density / first_density).powf(1.0 / PART_WORK_EXPONENT);
    let level = levels.nearest_share(ratio / (1.0 + ratio))?;
    (level != cut).then_some(level)
}

/// The level between two estimated level splits where the parts' works should be equal, by
/// linear interpolation of the difference of the two parts' works over the levels (a secant
/// step after [`rebalanced_level`], whose rate model overshot or fell short): `None` when the
/// difference is the same at both, or the level is one of the two or outside the inner levels.
fn interpolated_level(
    levels: &Levels,
    (cut, parts): (usize, [f64; 2]),
    (other, other_parts): (usize, [f64; 2]),
) -> Option<usize> {
    let (d0, d1) = (parts[0] - parts[1], other_parts[0] - other_parts[1]);
    if d0 == d1 || !(d0.is_finite() && d1.is_finite()) {
        return None;
    }
    let (c0, c1) = (cut as f64, other as f64);
    let level = (c0 - d0 * (c1 - c0) / (d1 - d0)).round();
    let inner = 1.0..(levels.per_level.len() - 1) as f64;
    (inner.contains(&level) && level != c0 && level != c1).then_some(level as usize)
}

/// Whether two parts' works are within [`BALANCED_PARTS`] of each other.
fn balanced(parts: [f64; 2]) -> bool {
    parts[0].max(parts[1]) <= BALANCED_PARTS * parts[0].min(parts[1])
}

/// The estimated works of a split's two parts and its critical path ([`critical_path`]).
struct SplitEstimate {
    critical_path: f64,
    parts: [f64; 2],
}

/// Estimate a split given by each graph vertex's side, the parts eliminated in `order` and the
/// separator last (a vertex-level [`Elimination`]).
fn split_estimate(
    mesh: &Mesh,
    graph: &VertexGraph,
    order: &[usize],
    sides: &[Side],
) -> SplitEstimate {
    let reordered: Vec<usize> = [Side::First, Side::Second, Side::Separator]
        .iter()
        .flat_map(|&side| order.iter().copied().filter(move |&v| sides[v] == side))
        .collect();
    let elimination = Elimination::of(mesh, graph, &reordered);
    let mut parts = [0.0, 0.0];
    let mut separator_dofs = 0;
    for (k, &v) in reordered.iter().enumerate() {
        match sides[v] {
            Side::First => parts[0] += elimination.work[k],
            Side::Second => parts[1] += elimination.work[k],
            Side::Separator => separator_dofs += elimination.weight[k],
        }
    }
    SplitEstimate {
        critical_path: critical_path(parts, separator_dofs),
        parts,
    }
}

/// Split the nodes of `mesh` in two parts and a separator (see the module's documentation), or
/// `None` when the mesh is too small or no split promises a shorter critical path than the
/// whole factorisation on one core.
pub fn split_nodes(mesh: &Mesh) -> Option<NodeSplit> {
    let incidence = VertexCells::new(mesh);
    let graph = vertex_graph(mesh, &incidence);
    split_nodes_of(mesh, &graph, &vertex_order(&graph))
}

/// The level split of `mesh` whatever its estimate ([`level_split`]; for tests of the split
/// solve, which need a split of a small mesh that would not pay), or `None` when no level
/// qualifies.
pub fn split_by_level(mesh: &Mesh) -> Option<NodeSplit> {
    let incidence = VertexCells::new(mesh);
    let graph = vertex_graph(mesh, &incidence);
    let sides = level_split(&graph)?;
    Some(node_sides(mesh, &graph, &sides))
}

/// [`split_nodes`] with the mesh's vertex graph and its elimination order (graph vertex indices)
/// given (shared with [`crate::discretisation::vertex_ordering::vertex_led_node_order_of`]): of the tree split
/// and the level split, the one of the lesser estimated critical path, if that is less than the
/// whole factor's estimated work.
pub(super) fn split_nodes_of(
    mesh: &Mesh,
    graph: &VertexGraph,
    order: &[usize],
) -> Option<NodeSplit> {
    let n = graph.vertices.len();
    if n < 16 || order.len() != n {
        return None;
    }
    if n > ESTIMATED_SPLIT_MAX_VERTICES {
        return level_split(graph).map(|sides| node_sides(mesh, graph, &sides));
    }
    let elimination = Elimination::of(mesh, graph, order);
    let whole: f64 = elimination.work.iter().sum();
    let tree = tree_split(&elimination).map(|(estimate, by_position)| {
        let mut sides = vec![Side::First; n];
        for (k, &v) in order.iter().enumerate() {
            sides[v] = by_position[k];
        }
        (estimate, sides)
    });
    // The central level, and the level that should balance its parts' estimated work.
    let mut levels_tried = Vec::new();
    if let Some(levels) = Levels::of(graph) {
        if let Some(cut) = central_level(&levels) {
            let sides = levels.sides(cut);
            let estimate = split_estimate(mesh, graph, order, &sides);
            let rebalanced = rebalanced_level(&levels, cut, estimate.parts);
            levels_tried.push((estimate.critical_path, sides));
            if let Some(level) = rebalanced {
                let sides = levels.sides(level);
                let second = split_estimate(mesh, graph, order, &sides);
                levels_tried.push((second.critical_path, sides));
                // Still unbalanced: one secant step between the two levels estimated.
                let secant = (!balanced(second.parts))
                    .then(|| {
                        interpolated_level(&levels, (cut, estimate.parts), (level, second.parts))
                    })
                    .flatten();
                if let Some(level) = secant {
                    let sides = levels.sides(level);
                    let third = split_estimate(mesh, graph, order, &sides);
                    levels_tried.push((third.critical_path, sides));
                }
            }
        }
    }
    let (estimate, sides) = tree
        .into_iter()
        .chain(levels_tried)
        .min_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(Ordering::Equal))?;
    (estimate < whole).then(|| node_sides(mesh, graph, &sides))
}

/// The side of every node, given each graph vertex's (`graph_sides`): an edge's inner nodes and a
/// cell's bubble join the part of their vertices off the separator, or the separator when all
/// are on it. Nodes in no cell couple to nothing: the first part takes them.
fn node_sides(mesh: &Mesh, graph: &VertexGraph, graph_sides: &[Side]) -> NodeSplit {
    let mut vertex_side = vec![Side::First; mesh.nodes.len()];
    for (i, &v) in graph.vertices.iter().enumerate() {
        vertex_side[v] = graph_sides[i];
    }
    let mut sides = vec![Side::First; mesh.nodes.len()];
    let joined = |a: Side, b: Side| match (a, b) {
        (Side::First, _) | (_, Side::First) => Side::First,
        (Side::Second, _) | (_, Side::Second) => Side::Second,
        _ => Side::Separator,
    };
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        let corner: [Side; 3] = std::array::from_fn(|i| vertex_side[cell[i]]);
        for (i, &side) in corner.iter().enumerate() {
            sides[cell[i]] = side;
        }
        for edge in 0..3 {
            let side = joined(corner[edge], corner[(edge + 1) % 3]);
            for &m in edge_inner_nodes(cell, mesh.degree, edge) {
                sides[m] = side;
            }
        }
        if let Some(bubble) = bubble_node(cell, mesh.degree) {
            sides[bubble] = joined(joined(corner[0], corner[1]), corner[2]);
        }
    }
    NodeSplit { sides }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::triangulation::{structured_rectangle, Degree};

    #[test]
    fn the_parts_share_no_cell_and_hold_comparable_shares() {
        for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
            let mesh = structured_rectangle(4.0, 1.0, 24, 6, 1, 2, 3).with_degree(degree);
            let split = split_by_level(&mesh).expect("a long strip splits");
            for c in 0..mesh.cell_count() {
                let cell = mesh.cell(c);
                let has = |side| cell.iter().any(|&m| split.sides[m] == side);
                assert!(
                    !(has(Side::First) && has(Side::Second)),
                    "{degree:?}: cell {c} couples both parts"
                );
            }
            let (first, second) = (split.count(Side::First), split.count(Side::Second));
            let separator = split.count(Side::Separator);
            assert!(first > 0 && second > 0, "{degree:?}");
            assert!(
                separator < (first + second) / 4,
                "{degree:?}: separator {separator} of {}",
                mesh.nodes.len()
            );
        }
    }

    /// Number of later neighbours of each position in the filled graph of `order`, by dense
    /// elimination (the definition of fill: eliminating a vertex joins its later neighbours).
    fn filled_later_neighbours(graph: &VertexGraph, order: &[usize]) -> Vec<Vec<usize>> {
        let n = order.len();
        let mut position = vec![0; n];
        for (k, &v) in order.iter().enumerate() {
            position[v] = k;
        }
        let mut adjacent = vec![vec![false; n]; n];
        for v in 0..n {
            for &w in graph.neighbours(v) {
                adjacent[position[v]][position[w]] = true;
            }
        }
        let mut later = Vec::with_capacity(n);
        for k in 0..n {
            let rows: Vec<usize> = (k + 1..n).filter(|&i| adjacent[k][i]).collect();
            for &a in &rows {
                for &b in &rows {
                    adjacent[a][b] = true;
                }
            }
            later.push(rows);
        }
        later
    }

    /// The work of [`column_work`] as the previous builds found it, a reference for the weighted
    /// counts: each column's structure merged up the tree from its children's
    /// (`struct(k) = adj⁺(k) ∪ ⋃ struct(child) \ {k}`, linear in the factor's entries), each
    /// written once to one arena and read once, by its parent.
    fn merged_column_work(graph: &PositionGraph, parent: &[usize], weight: &[usize]) -> Vec<f64> {
        let n = graph.len();
        let (first_child, next_sibling) = child_lists(parent);
        // Column k's rows below the diagonal: arena[start[k]..end[k]].
        let mut arena: Vec<usize> = Vec::with_capacity(8 * graph.rows.len());
        let mut start = vec![0usize; n];
        let mut end = vec![0usize; n];
        let mut marker = vec![NONE; n];
        let mut work = vec![0.0; n];
        for k in 0..n {
            start[k] = arena.len();
            marker[k] = k;
            let mut below = 0usize;
            for &i in graph.neighbours(k) {
                if i > k && marker[i] != k {
                    marker[i] = k;
                    below += weight[i];
                    arena.push(i);
                }
            }
            let mut child = first_child[k];
            while child != NONE {
                for e in start[child]..end[child] {
                    let i = arena[e];
                    if marker[i] != k {
                        marker[i] = k;
                        below += weight[i];
                        arena.push(i);
                    }
                }
                child = next_sibling[child];
            }
            end[k] = arena.len();
            // Σ_{j < w} (w − j + below)² for the vertex's w = weight[k] columns, in closed form.
            let (w, b) = (weight[k] as f64, below as f64);
            work[k] = w * (w + 1.0) * (2.0 * w + 1.0) / 6.0 + b * w * (w + 1.0) + b * b * w;
        }
        work
    }

    #[test]
    fn the_weighted_counts_give_the_merged_structures_work() {
        let meshes = [
            structured_rectangle(3.0, 2.0, 9, 6, 1, 2, 3),
            crate::mesh::msh::read_msh(std::path::Path::new(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../meshes/annulus-0.9-L1.msh"
            )))
            .unwrap(),
            crate::mesh::msh::read_msh(std::path::Path::new(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../meshes/disk-L1.msh"
            )))
            .unwrap(),
        ];
        for vertex_mesh in &meshes {
            for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
                let mesh = vertex_mesh.with_degree(degree);
                let incidence = VertexCells::new(&mesh);
                let graph = vertex_graph(&mesh, &incidence);
                let order = vertex_order(&graph);
                // The whole order, and the level split's (parts first, the separator last:
                // a forest until the separator joins it).
                let mut orders = vec![order.clone()];
                if let Some(sides) = level_split(&graph) {
                    let sides = &sides;
                    orders.push(
                        [Side::First, Side::Second, Side::Separator]
                            .iter()
                            .flat_map(|&side| {
                                order.iter().copied().filter(move |&v| sides[v] == side)
                            })
                            .collect(),
                    );
                }
                for order in &orders {
                    let positions = PositionGraph::new(&graph, order);
                    let parent = elimination_tree(&positions);
                    let weight: Vec<usize> = (0..order.len()).map(|k| 2 + (k * 7) % 11).collect();
                    let merged = merged_column_work(&positions, &parent, &weight);
                    let counted = column_work(&positions, &parent, &weight);
                    assert_eq!(counted, merged, "{} {degree:?}", mesh.source);
                }
            }
        }
    }

    #[test]
    fn the_vertex_level_work_is_that_of_the_dense_elimination() {
        for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
            let mesh = structured_rectangle(3.0, 2.0, 9, 6, 1, 2, 3).with_degree(degree);
            let incidence = VertexCells::new(&mesh);
            let graph = vertex_graph(&mesh, &incidence);
            let order = vertex_order(&graph);
            let elimination = Elimination::of(&mesh, &graph, &order);
            let filled = filled_later_neighbours(&graph, &order);
            let per_edge = match degree {
                Degree::Linear => 0,
                Degree::Quadratic => 1,
                Degree::Cubic => 2,
            };
            let mut position = vec![0; order.len()];
            for (k, &v) in order.iter().enumerate() {
                position[v] = k;
            }
            let weight: Vec<usize> = (0..order.len())
                .map(|k| {
                    let later_edges = graph
                        .neighbours(order[k])
                        .iter()
                        .filter(|&&w| position[w] > k)
                        .count();
                    2 + 2 * per_edge * later_edges
                })
                .collect();
            assert_eq!(elimination.weight, weight, "{degree:?}");
            for k in 0..order.len() {
                let below: usize = filled[k].iter().map(|&i| weight[i]).sum();
                // Columns of w, w − 1, …, 1 entries above the `below` rows, counted one by one.
                let expected: f64 = (1..=weight[k]).map(|c| ((c + below) as f64).powi(2)).sum();
                assert!(
                    (elimination.work[k] - expected).abs() <= 1e-9 * expected,
                    "{degree:?} position {k}: {} against {expected}",
                    elimination.work[k]
                );
                // The tree's parent is the first later neighbour in the filled graph.
                assert_eq!(
                    elimination.parent[k],
                    filled[k].first().copied().unwrap_or(NONE),
                    "{degree:?} position {k}"
                );
            }
        }
    }

    #[test]
    fn the_tree_split_separates_the_parts_by_the_top_of_the_tree() {
        for (width, nr, nz) in [(6.0, 36, 4), (2.0, 12, 10)] {
            let mesh = structured_rectangle(width, 1.0, nr, nz, 1, 2, 3);
            let incidence = VertexCells::new(&mesh);
            let graph = vertex_graph(&mesh, &incidence);
            let order = vertex_order(&graph);
            let elimination = Elimination::of(&mesh, &graph, &order);
            let (estimate, side) = tree_split(&elimination).expect("the mesh splits");
            assert!(estimate.is_finite() && estimate > 0.0);
            assert!(side.contains(&Side::First) && side.contains(&Side::Second));
            let mut position = vec![0; order.len()];
            for (k, &v) in order.iter().enumerate() {
                position[v] = k;
            }
            for k in 0..order.len() {
                // The separator is closed under taking parents.
                let parent = elimination.parent[k];
                if side[k] == Side::Separator && parent != NONE {
                    assert_eq!(side[parent], Side::Separator, "{nr}x{nz}: position {k}");
                }
                // No edge of the vertex graph joins the two parts.
                for &w in graph.neighbours(order[k]) {
                    let other = side[position[w]];
                    assert!(
                        !matches!(
                            (side[k], other),
                            (Side::First, Side::Second) | (Side::Second, Side::First)
                        ),
                        "{nr}x{nz}: positions {k} and {}",
                        position[w]
                    );
                }
            }
        }
    }

    #[test]
    fn the_rebalanced_level_moves_the_cut_toward_the_lighter_part() {
        // Ten levels of ten vertices: the level `l` cut leaves a share `l / 10` before it.
        let levels = Levels {
            level: (0..100).map(|v| v / 10).collect(),
            per_level: vec![10; 10],
        };
        assert!((levels.share_before(5) - 0.5).abs() < 1e-12);
        // First part twice the second at s = 0.5: c_1 = 2 c_2, so s / (1 − s) = 2^(−2/3) and
        // s = 0.386, nearest the share 0.4 before level 4.
        assert_eq!(rebalanced_level(&levels, 5, [2.0, 1.0]), Some(4));
        assert_eq!(rebalanced_level(&levels, 5, [1.0, 2.0]), Some(6));
        // Parts within BALANCED_PARTS of each other, or no other level to go to, stay.
        assert_eq!(rebalanced_level(&levels, 5, [1.0, 1.05]), None);
        assert_eq!(rebalanced_level(&levels, 4, [1.02, 1.0]), None);
        assert_eq!(rebalanced_level(&levels, 5, [1.0, 0.0]), None);
        // Never the first or last level (a part would be empty).
        assert_eq!(rebalanced_level(&levels, 5, [1e6, 1.0]), Some(1));
        assert_eq!(rebalanced_level(&levels, 5, [1.0, 1e6]), Some(8));
    }

    #[test]
    fn the_secant_level_lies_where_the_parts_difference_crosses_zero() {
        let levels = Levels {
            level: (0..100).map(|v| v / 10).collect(),
            per_level: vec![10; 10],
        };
        // Difference -3 at level 2, +1 at level 6: zero at level 5.
        assert_eq!(
            interpolated_level(&levels, (2, [1.0, 4.0]), (6, [3.0, 2.0])),
            Some(5)
        );
        // Both on the same side (the rate model fell short): the line goes on past the second
        // (-4 at level 2, -2 at level 4: zero at level 6).
        assert_eq!(
            interpolated_level(&levels, (2, [1.0, 5.0]), (4, [1.0, 3.0])),
            Some(6)
        );
        // No slope, a level already estimated, or beyond the inner levels: none.
        assert_eq!(
            interpolated_level(&levels, (2, [1.0, 4.0]), (6, [1.0, 4.0])),
            None
        );
        assert_eq!(
            interpolated_level(&levels, (2, [1.0, 4.0]), (3, [3.0, 2.0])),
            None
        );
        assert_eq!(
            interpolated_level(&levels, (2, [1.0, 9.0]), (3, [1.0, 8.0])),
            None
        );
    }

    #[test]
    fn a_tiny_mesh_is_not_split() {
        let mesh = structured_rectangle(1.0, 1.0, 2, 1, 1, 2, 3);
        assert!(split_nodes(&mesh).is_none());
    }
}
