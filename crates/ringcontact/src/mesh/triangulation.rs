//! Triangle meshes of the axisymmetric half-space model in `(r, z)` (`r >= 0`, `z <= 0`).
//!
//! Nodes are `(r, z)`; cells are 3-node (linear) or 6-node (quadratic) triangles with gmsh's node
//! order (vertices, then the mid-edge nodes of edges 0-1, 1-2, 2-0); boundary edges carry the
//! physical tag of their curve. Quadratic elements are straight-sided (affine geometry).

use std::collections::HashMap;

use crate::error::{Error, Result};

/// Physical tags of the boundary curves and the domain, as written by `meshes/half_space.geo`.
pub mod tags {
    /// Candidate contact line: `[b, a]` (fixed annulus) or `[0, a]`.
    pub const CONTACT: i32 = 1;
    /// Free surface `[a, R]`.
    pub const FREE: i32 = 2;
    /// Far boundary (arc of radius `R`), `u = 0`.
    pub const FAR: i32 = 3;
    /// Symmetry axis `r = 0`, `u_r = 0`.
    pub const AXIS: i32 = 4;
    /// Free surface under the hole of an annulus, `[0, b]`.
    pub(crate) const HOLE: i32 = 5;
    /// The solid.
    pub const SOLID: i32 = 10;
}

/// Polynomial degree of the elements.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Degree {
    Linear = 1,
    Quadratic = 2,
    Cubic = 3,
}

impl Degree {
    /// Nodes per triangle.
    pub(crate) fn nodes_per_cell(self) -> usize {
        match self {
            Degree::Linear => 3,
            Degree::Quadratic => 6,
            Degree::Cubic => 10,
        }
    }

    /// Nodes per boundary edge.
    pub(crate) fn nodes_per_edge(self) -> usize {
        match self {
            Degree::Linear => 2,
            Degree::Quadratic => 3,
            Degree::Cubic => 4,
        }
    }

    /// From the command-line number.
    pub fn from_number(n: u8) -> Option<Self> {
        match n {
            1 => Some(Degree::Linear),
            2 => Some(Degree::Quadratic),
            3 => Some(Degree::Cubic),
            _ => None,
        }
    }
}

/// A boundary edge with its physical tag; `nodes` has 2 (linear), 3 (quadratic: ends, then
/// middle) or 4 (cubic: ends, then the nodes at 1/3 and 2/3 from the first end) entries.
#[derive(Clone, Debug, PartialEq)]
pub struct BoundaryEdge {
    pub nodes: Vec<usize>,
    pub tag: i32,
}

/// A validated triangle mesh.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// `(r, z)` of every node.
    pub nodes: Vec<[f64; 2]>,
    /// Connectivity, `degree.nodes_per_cell()` entries per triangle.
    pub cells: Vec<usize>,
    pub degree: Degree,
    pub boundary: Vec<BoundaryEdge>,
    /// Where the mesh came from (a path or a generator description).
    pub source: String,
    /// The file's own node and element tags (read meshes), for messages that the file's author
    /// can look up.
    pub file_tags: FileTags,
}

/// Tags of a mesh file: `nodes[i]` is the file tag of node `i`, `cells[c]` the element tag of
/// triangle `c`; empty for generated meshes and for nodes added by a degree change.
#[derive(Clone, Debug, Default)]
pub struct FileTags {
    pub nodes: Vec<u64>,
    pub cells: Vec<u64>,
    /// Line of each node's tag and of each triangle's definition in an ASCII file (0: unknown).
    pub node_lines: Vec<usize>,
    pub cell_lines: Vec<usize>,
}

fn mesh_error(source: &str, message: String) -> Error {
    Error::InvalidMesh {
        path: source.to_string(),
        message,
    }
}

/// Edges listed under one vertex beyond which that vertex's edges are found by hashing.
const EDGE_LIST_LIMIT: usize = 32;

/// The edges of a mesh, numbered in the order they are first met, found without hashing: each
/// edge is listed under its lower vertex, and a vertex of a gmsh mesh has a handful of edges. A
/// vertex with more than [`EDGE_LIST_LIMIT`] (a fan of many cells around one point, which a
/// file may hold) has its edges found by hashing instead, so no mesh makes the search quadratic.
struct EdgeIndex {
    /// First edge listed under each vertex (`usize::MAX`: none).
    head: Vec<usize>,
    /// Number of edges listed under each vertex.
    listed: Vec<usize>,
    /// The next edge under the same lower vertex.
    next: Vec<usize>,
    /// The higher vertex of each edge.
    upper: Vec<usize>,
    /// The edges of the vertices with more than [`EDGE_LIST_LIMIT`], by `(lower, upper)`.
    hashed: HashMap<(usize, usize), usize>,
}

impl EdgeIndex {
    fn new(vertices: usize) -> Self {
        Self {
            head: vec![usize::MAX; vertices],
            listed: vec![0; vertices],
            next: Vec::new(),
            upper: Vec::new(),
            hashed: HashMap::new(),
        }
    }

    /// The number of edge `{a, b}`, and whether it was met here for the first time.
    fn find_or_insert(&mut self, a: usize, b: usize) -> (usize, bool) {
        let (lower, upper) = (a.min(b), a.max(b));
        let new_edge = self.upper.len();
        if self.listed[lower] > EDGE_LIST_LIMIT {
            let edge = *self.hashed.entry((lower, upper)).or_insert(new_edge);
            if edge == new_edge {
                self.upper.push(upper);
                self.next.push(usize::MAX);
            }
            return (edge, edge == new_edge);
        }
        let mut edge = self.head[lower];
        while edge != usize::MAX {
            if self.upper[edge] == upper {
                return (edge, false);
            }
            edge = self.next[edge];
        }
        self.upper.push(upper);
        self.next.push(self.head[lower]);
        self.head[lower] = new_edge;
        self.listed[lower] += 1;
        if self.listed[lower] > EDGE_LIST_LIMIT {
            // From now on this vertex's edges are hashed, the listed ones included.
            let mut edge = self.head[lower];
            while edge != usize::MAX {
                self.hashed.insert((lower, self.upper[edge]), edge);
                edge = self.next[edge];
            }
        }
        (new_edge, true)
    }
}

impl Mesh {
    /// `node tag T` (the file's tag) where known, else `node i` (0-based, internal).
    pub(crate) fn node_name(&self, i: usize) -> String {
        match (
            self.file_tags.nodes.get(i),
            self.file_tags.node_lines.get(i),
        ) {
            (Some(tag), Some(&line)) if line > 0 => format!("node tag {tag} (line {line})"),
            (Some(tag), _) => format!("node tag {tag}"),
            (None, _) => format!("node {i}"),
        }
    }

    /// `element tag T` (the file's tag) where known, else `triangle c` (0-based, internal).
    fn cell_name(&self, c: usize) -> String {
        match (
            self.file_tags.cells.get(c),
            self.file_tags.cell_lines.get(c),
        ) {
            (Some(tag), Some(&line)) if line > 0 => format!("element tag {tag} (line {line})"),
            (Some(tag), _) => format!("element tag {tag}"),
            (None, _) => format!("triangle {c}"),
        }
    }

    /// Number of triangles.
    pub fn cell_count(&self) -> usize {
        self.cells.len() / self.degree.nodes_per_cell()
    }

    /// Node indices of triangle `c`.
    pub fn cell(&self, c: usize) -> &[usize] {
        let k = self.degree.nodes_per_cell();
        &self.cells[c * k..(c + 1) * k]
    }

    fn vertex_names(&self, cell: &[usize]) -> String {
        let known = cell[..3].iter().all(|&v| v < self.file_tags.nodes.len());
        let list = |f: &dyn Fn(usize) -> String| {
            cell[..3]
                .iter()
                .map(|&v| f(v))
                .collect::<Vec<_>>()
                .join(", ")
        };
        if known {
            format!(
                "node tags {}",
                list(&|v| self.file_tags.nodes[v].to_string())
            )
        } else {
            format!("nodes {}", list(&|v| v.to_string()))
        }
    }

    /// Nodes on boundary edges with `tag`, sorted and without duplicates.
    pub fn boundary_nodes(&self, tag: i32) -> Vec<usize> {
        let mut nodes: Vec<usize> = self
            .boundary
            .iter()
            .filter(|e| e.tag == tag)
            .flat_map(|e| e.nodes.iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// Whether any boundary edge carries `tag`.
    fn has_tag(&self, tag: i32) -> bool {
        self.boundary.iter().any(|e| e.tag == tag)
    }

    /// Check what the solver relies on: indices in range, `r >= 0`, positively oriented
    /// non-degenerate triangles (inverted ones are reported, not flipped), the required boundary
    /// groups, and straight quadratic edges.
    pub fn validate(&self, required_tags: &[(i32, &str)]) -> Result<()> {
        let src = &self.source;
        if self.cell_count() == 0 {
            return Err(mesh_error(
                src,
                "the mesh has no triangles in the solid".into(),
            ));
        }
        self.check_nodes()?;
        for c in 0..self.cell_count() {
            self.check_cell(c)?;
        }
        for (tag, name) in required_tags {
            if !self.has_tag(*tag) {
                return Err(mesh_error(
                    src,
                    format!("the physical group {tag} ({name}) is missing from the boundary"),
                ));
            }
        }
        Ok(())
    }

    /// Every node finite and in the half-plane `r >= 0`.
    fn check_nodes(&self) -> Result<()> {
        for (i, p) in self.nodes.iter().enumerate() {
            if !p[0].is_finite() || !p[1].is_finite() {
                return Err(mesh_error(
                    &self.source,
                    format!("{} has a non-finite coordinate", self.node_name(i)),
                ));
            }
            if p[0] < -1e-12 * (1.0 + p[1].abs()) {
                return Err(mesh_error(
                    &self.source,
                    format!(
                        "{} at r = {} lies off the half-plane r >= 0",
                        self.node_name(i),
                        p[0]
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Cell `c`: its nodes exist, it is neither degenerate nor inverted, its edges are straight.
    fn check_cell(&self, c: usize) -> Result<()> {
        let src = &self.source;
        let cell = self.cell(c);
        if let Some(&bad) = cell.iter().find(|&&v| v >= self.nodes.len()) {
            return Err(mesh_error(
                src,
                format!("{} refers to missing node {bad}", self.cell_name(c)),
            ));
        }
        let [p0, p1, p2] = [
            self.nodes[cell[0]],
            self.nodes[cell[1]],
            self.nodes[cell[2]],
        ];
        let twice_area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
        let longest = distance(p0, p1).max(distance(p1, p2)).max(distance(p2, p0));
        // Degenerate: flat relative to its own size, or so small that its vertices' coordinates
        // cannot resolve it (relative to their magnitude, not the domain's: graded meshes have
        // elements of 1e-10 a next to ones of 1e6 a).
        let magnitude = p0[0].abs().max(p0[1].abs());
        if twice_area.abs() <= 1e-14 * longest * longest.max(1e-300) || longest <= 1e-13 * magnitude
        {
            return Err(mesh_error(
                src,
                format!(
                    "{} with {} is degenerate",
                    self.cell_name(c),
                    self.vertex_names(cell)
                ),
            ));
        }
        if twice_area < 0.0 {
            return Err(mesh_error(
                src,
                format!(
                    "{} with {} is inverted (clockwise in (r, z))",
                    self.cell_name(c),
                    self.vertex_names(cell)
                ),
            ));
        }
        self.check_straight_edges(c)
    }

    /// Edge nodes of higher-order triangles: at the fractions `k/p` of straight edges.
    fn check_straight_edges(&self, c: usize) -> Result<()> {
        let cell = self.cell(c);
        let per_edge = self.degree as usize - 1;
        for (e, (a, b)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
            for j in 0..per_edge {
                let t = (j + 1) as f64 / self.degree as usize as f64;
                let (pa, pb, pm) = (
                    self.nodes[cell[a]],
                    self.nodes[cell[b]],
                    self.nodes[cell[3 + per_edge * e + j]],
                );
                let expected = [pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1])];
                if distance(expected, pm) > 1e-9 * distance(pa, pb) {
                    return Err(mesh_error(
                        &self.source,
                        format!(
                            "{} has a curved edge ({} off the chord); only \
                             straight-sided elements are supported (Mesh.SecondOrderLinear = 1)",
                            self.cell_name(c),
                            self.node_name(cell[3 + per_edge * e + j])
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Check that every physical group lies where its role says (`meshes/half_space.geo`), for a
    /// contact line that must start at `contact_start` (`b/a` of the fixed annulus, 0 otherwise):
    ///
    /// * axis (4) on `r = 0`; contact (1), free (2) and hole (5) on `z = 0`; every node in
    ///   `r >= 0`, `z <= 0`;
    /// * contact over exactly `[contact_start, 1]` (units of the rim radius); free surface at
    ///   `r >= 1`, hole at `r <= contact_start`;
    /// * far boundary (3) on one arc `r² + z² = R²` with `R > 1`;
    /// * the triangles tile the domain: their areas sum to the area enclosed by the boundary
    ///   (`Σ_far ½ |p × q|`, the other boundaries pass through the origin) to 1e-9, so none overlap
    ///   and none is missing.
    pub fn validate_geometry(&self, contact_start: f64) -> Result<()> {
        let src = &self.source;
        let radius = self
            .boundary_nodes(tags::FAR)
            .iter()
            .map(|&n| self.nodes[n][0].hypot(self.nodes[n][1]))
            .fold(0.0, f64::max);
        let tolerance = 1e-9 * radius.max(1.0);
        if let Some((i, p)) = self
            .nodes
            .iter()
            .enumerate()
            .find(|(_, p)| p[1] > tolerance)
        {
            return Err(mesh_error(
                src,
                format!(
                    "node {i} at z = {} lies above the surface z = 0 (the solid is z <= 0)",
                    p[1]
                ),
            ));
        }
        self.check_boundary_placement(contact_start, radius, tolerance)?;
        if radius <= 1.0 {
            return Err(mesh_error(
                src,
                format!(
                    "the far boundary has radius R = {radius}, inside the punch (R > a needed)"
                ),
            ));
        }
        self.check_tiling()
    }

    /// Every boundary group on its line: the contact line spans `[contact_start, 1]`; axis at
    /// `r = 0`, contact, free surface and hole at `z = 0`, free surface at `r >= 1`, hole at
    /// `r <= contact_start`, far boundary on the arc of `radius` (within `tolerance`).
    fn check_boundary_placement(
        &self,
        contact_start: f64,
        radius: f64,
        tolerance: f64,
    ) -> Result<()> {
        let src = &self.source;
        let role_of = |tag: i32| match tag {
            tags::CONTACT => "contact",
            tags::FREE => "free surface",
            tags::FAR => "far boundary",
            tags::AXIS => "axis",
            tags::HOLE => "hole",
            _ => "other",
        };
        let contact_range = self
            .boundary_nodes(tags::CONTACT)
            .iter()
            .map(|&n| self.nodes[n][0])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
                (lo.min(r), hi.max(r))
            });
        if (contact_range.0 - contact_start).abs() > 1e-9 || (contact_range.1 - 1.0).abs() > 1e-9 {
            return Err(mesh_error(
                src,
                format!(
                    "the contact line spans r/a in [{}, {}]; this punch needs [{contact_start}, 1] \
                     (a concave or flat-faced punch needs a disk mesh, a fixed annulus one whose \
                     contact line starts at b/a)",
                    contact_range.0, contact_range.1
                ),
            ));
        }
        for edge in &self.boundary {
            for &n in &edge.nodes {
                let [r, z] = self.nodes[n];
                let misplaced = match edge.tag {
                    tags::AXIS => (r.abs() > tolerance).then(|| "r = 0".to_string()),
                    tags::CONTACT | tags::FREE | tags::HOLE if z.abs() > tolerance => {
                        Some("z = 0".to_string())
                    }
                    tags::FREE => (r < 1.0 - 1e-9).then(|| "r >= a".to_string()),
                    tags::HOLE => {
                        (r > contact_start + 1e-9).then(|| format!("r <= b = {contact_start}"))
                    }
                    tags::FAR => ((r.hypot(z) - radius).abs() > 1e-6 * radius)
                        .then(|| format!("the arc of radius R = {radius}")),
                    _ => None,
                };
                if let Some(place) = misplaced {
                    return Err(mesh_error(
                        src,
                        format!(
                            "a node of the {} group ({}) lies at (r, z) = ({r}, {z}), not on {place}: \
                             are the physical tags swapped?",
                            role_of(edge.tag),
                            edge.tag
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The triangles' areas sum to the area the far arc encloses, to 1e-9: none overlap and none
    /// is missing.
    fn check_tiling(&self) -> Result<()> {
        let src = &self.source;
        let enclosed: f64 = self
            .boundary
            .iter()
            .filter(|e| e.tag == tags::FAR)
            .map(|e| {
                let (p, q) = (self.nodes[e.nodes[0]], self.nodes[e.nodes[1]]);
                0.5 * (p[0] * q[1] - p[1] * q[0]).abs()
            })
            .sum();
        let tiled: f64 = (0..self.cell_count())
            .map(|c| {
                let cell = self.cell(c);
                let [p0, p1, p2] = [
                    self.nodes[cell[0]],
                    self.nodes[cell[1]],
                    self.nodes[cell[2]],
                ];
                0.5 * ((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1])).abs()
            })
            .sum();
        if (tiled - enclosed).abs() > 1e-9 * enclosed {
            return Err(mesh_error(
                src,
                format!(
                    "the triangles cover an area of {tiled:.12e}, the boundary encloses {enclosed:.12e}: \
                     elements {} (relative difference {:.1e})",
                    if tiled > enclosed { "overlap" } else { "leave gaps" },
                    (tiled - enclosed).abs() / enclosed
                ),
            ));
        }
        Ok(())
    }

    /// The same mesh with quadratic triangles: a node is added at the midpoint of every edge.
    /// A quadratic mesh is returned unchanged.
    pub fn to_quadratic(&self) -> Mesh {
        if self.degree == Degree::Quadratic {
            return self.clone();
        }
        let mut nodes = self.nodes.clone();
        let mut edges = EdgeIndex::new(nodes.len());
        let mut midpoint: Vec<usize> = Vec::new();
        let mut mid = |a: usize, b: usize, nodes: &mut Vec<[f64; 2]>| -> usize {
            let (edge, new) = edges.find_or_insert(a, b);
            if new {
                let (pa, pb) = (nodes[a], nodes[b]);
                nodes.push([0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])]);
                midpoint.push(nodes.len() - 1);
            }
            midpoint[edge]
        };
        let mut cells = Vec::with_capacity(self.cell_count() * 6);
        for c in 0..self.cell_count() {
            let t = self.cell(c);
            let (m01, m12, m20) = (
                mid(t[0], t[1], &mut nodes),
                mid(t[1], t[2], &mut nodes),
                mid(t[2], t[0], &mut nodes),
            );
            cells.extend_from_slice(&[t[0], t[1], t[2], m01, m12, m20]);
        }
        let boundary = self
            .boundary
            .iter()
            .map(|e| BoundaryEdge {
                nodes: vec![
                    e.nodes[0],
                    e.nodes[1],
                    mid(e.nodes[0], e.nodes[1], &mut nodes),
                ],
                tag: e.tag,
            })
            .collect();
        Mesh {
            nodes,
            cells,
            degree: Degree::Quadratic,
            boundary,
            source: format!(
                "{} (edge midpoints added for quadratic elements)",
                self.source
            ),
            // Existing nodes keep their indices; the added midpoints have no file tag.
            file_tags: self.file_tags.clone(),
        }
    }

    /// The linear mesh on the vertices of a quadratic mesh (mid-edge nodes dropped, renumbered).
    pub fn to_linear(&self) -> Mesh {
        if self.degree == Degree::Linear {
            return self.clone();
        }
        let mut map = vec![usize::MAX; self.nodes.len()];
        let mut nodes = Vec::new();
        let mut kept_tags = Vec::new();
        let mut kept_lines = Vec::new();
        let mut keep = |v: usize, nodes: &mut Vec<[f64; 2]>| -> usize {
            if map[v] == usize::MAX {
                map[v] = nodes.len();
                nodes.push(self.nodes[v]);
                kept_tags.push(self.file_tags.nodes.get(v).copied().unwrap_or(0));
                kept_lines.push(self.file_tags.node_lines.get(v).copied().unwrap_or(0));
            }
            map[v]
        };
        let mut cells = Vec::with_capacity(self.cell_count() * 3);
        for c in 0..self.cell_count() {
            let t = self.cell(c);
            for &v in &t[..3] {
                cells.push(keep(v, &mut nodes));
            }
        }
        let boundary = self
            .boundary
            .iter()
            .map(|e| BoundaryEdge {
                nodes: vec![keep(e.nodes[0], &mut nodes), keep(e.nodes[1], &mut nodes)],
                tag: e.tag,
            })
            .collect();
        Mesh {
            nodes,
            cells,
            degree: Degree::Linear,
            boundary,
            source: format!("{} (vertices only, linear elements)", self.source),
            file_tags: FileTags {
                nodes: if self.file_tags.nodes.is_empty() {
                    Vec::new()
                } else {
                    kept_tags
                },
                node_lines: if self.file_tags.node_lines.is_empty() {
                    Vec::new()
                } else {
                    kept_lines
                },
                cells: self.file_tags.cells.clone(),
                cell_lines: self.file_tags.cell_lines.clone(),
            },
        }
    }

    /// The same mesh with cubic (10-node) triangles on its vertices: two nodes on every edge at
    /// 1/3 and 2/3, one at the centroid; cell order as gmsh's and VTK's: vertices, edge 0-1 (from
    /// vertex 0), edge 1-2, edge 2-0, centre.
    fn to_cubic(&self) -> Mesh {
        if self.degree == Degree::Cubic {
            return self.clone();
        }
        let linear_copy;
        let linear = if self.degree == Degree::Linear {
            self
        } else {
            linear_copy = self.to_linear();
            &linear_copy
        };
        let mut nodes = linear.nodes.clone();
        // Edge number -> the nodes at 1/3 and 2/3 from its lower vertex.
        let mut edges = EdgeIndex::new(nodes.len());
        let mut thirds: Vec<[usize; 2]> = Vec::new();
        let mut edge_nodes = |a: usize, b: usize, nodes: &mut Vec<[f64; 2]>| -> [usize; 2] {
            let (edge, new) = edges.find_or_insert(a, b);
            if new {
                let (p, q) = (nodes[a.min(b)], nodes[a.max(b)]);
                let at = |t: f64| [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
                nodes.push(at(1.0 / 3.0));
                nodes.push(at(2.0 / 3.0));
                thirds.push([nodes.len() - 2, nodes.len() - 1]);
            }
            let pair = thirds[edge];
            if a < b {
                pair
            } else {
                [pair[1], pair[0]]
            }
        };
        let mut cells = Vec::with_capacity(linear.cell_count() * 10);
        for c in 0..linear.cell_count() {
            let t = linear.cell(c);
            let e01 = edge_nodes(t[0], t[1], &mut nodes);
            let e12 = edge_nodes(t[1], t[2], &mut nodes);
            let e20 = edge_nodes(t[2], t[0], &mut nodes);
            let (p0, p1, p2) = (nodes[t[0]], nodes[t[1]], nodes[t[2]]);
            nodes.push([(p0[0] + p1[0] + p2[0]) / 3.0, (p0[1] + p1[1] + p2[1]) / 3.0]);
            let centre = nodes.len() - 1;
            cells.extend_from_slice(&[
                t[0], t[1], t[2], e01[0], e01[1], e12[0], e12[1], e20[0], e20[1], centre,
            ]);
        }
        let boundary = linear
            .boundary
            .iter()
            .map(|e| {
                let [m1, m2] = edge_nodes(e.nodes[0], e.nodes[1], &mut nodes);
                BoundaryEdge {
                    nodes: vec![e.nodes[0], e.nodes[1], m1, m2],
                    tag: e.tag,
                }
            })
            .collect();
        Mesh {
            nodes,
            cells,
            degree: Degree::Cubic,
            boundary,
            source: format!("{} (cubic elements on its vertices)", self.source),
            // The vertices keep the linear mesh's indices; added nodes have no file tag.
            file_tags: linear.file_tags.clone(),
        }
    }

    /// The mesh with elements of `degree` (always on the vertices of this mesh).
    pub fn with_degree(&self, degree: Degree) -> Mesh {
        match (self.degree, degree) {
            (a, b) if a == b => self.clone(),
            (_, Degree::Linear) => self.to_linear(),
            (Degree::Linear, Degree::Quadratic) => self.to_quadratic(),
            (_, Degree::Quadratic) => self.to_linear().to_quadratic(),
            (_, Degree::Cubic) => self.to_cubic(),
        }
    }
}

/// A structured mesh of the rectangle `[0, width] x [-height, 0]` with `nr x nz` cells, each split
/// into two triangles; boundary tags: top `z = 0` -> `top_tag`, right -> `side_tag`,
/// bottom -> `bottom_tag`, axis `r = 0` -> [`tags::AXIS`]. Used by the manufactured-solution tests.
pub fn structured_rectangle(
    width: f64,
    height: f64,
    nr: usize,
    nz: usize,
    top_tag: i32,
    side_tag: i32,
    bottom_tag: i32,
) -> Mesh {
    let index = |i: usize, j: usize| j * (nr + 1) + i;
    let mut nodes = Vec::with_capacity((nr + 1) * (nz + 1));
    for j in 0..=nz {
        for i in 0..=nr {
            nodes.push([width * i as f64 / nr as f64, -height * j as f64 / nz as f64]);
        }
    }
    let mut cells = Vec::with_capacity(6 * nr * nz);
    for j in 0..nz {
        for i in 0..nr {
            // (i, j) is the upper-left corner in (r, z) with z decreasing in j.
            let (a, b, c, d) = (
                index(i, j),
                index(i + 1, j),
                index(i + 1, j + 1),
                index(i, j + 1),
            );
            // Counter-clockwise in (r, z): a (top-left), d (bottom-left), c (bottom-right).
            cells.extend_from_slice(&[a, d, c]);
            cells.extend_from_slice(&[a, c, b]);
        }
    }
    let mut boundary = Vec::new();
    for i in 0..nr {
        boundary.push(BoundaryEdge {
            nodes: vec![index(i, 0), index(i + 1, 0)],
            tag: top_tag,
        });
        boundary.push(BoundaryEdge {
            nodes: vec![index(i, nz), index(i + 1, nz)],
            tag: bottom_tag,
        });
    }
    for j in 0..nz {
        boundary.push(BoundaryEdge {
            nodes: vec![index(nr, j), index(nr, j + 1)],
            tag: side_tag,
        });
        boundary.push(BoundaryEdge {
            nodes: vec![index(0, j), index(0, j + 1)],
            tag: tags::AXIS,
        });
    }
    Mesh {
        nodes,
        cells,
        degree: Degree::Linear,
        boundary,
        source: format!("structured {nr}x{nz} rectangle {width} x {height}"),
        file_tags: FileTags::default(),
    }
}

/// Euclidean distance of two points of the `(r, z)` plane.
fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fan of `cells` triangles around vertex 0 (every edge from it is listed under it), with
    /// its rim vertices on the unit circle's lower half.
    fn fan(cells: usize) -> Mesh {
        let mut nodes = vec![[0.0, 0.0]];
        for k in 0..=cells {
            let angle = std::f64::consts::PI * (1.0 + k as f64 / cells as f64);
            nodes.push([angle.cos() + 1.5, angle.sin()]);
        }
        let cells: Vec<usize> = (0..cells).flat_map(|k| [0, k + 1, k + 2]).collect();
        Mesh {
            nodes,
            cells,
            degree: Degree::Linear,
            boundary: Vec::new(),
            source: "fan".into(),
            file_tags: FileTags::default(),
        }
    }

    /// The solver validates the vertex mesh (after any corner refinement) and not the mesh
    /// raised from it: raising must keep a valid mesh valid, whatever the file's degree.
    #[test]
    fn raising_the_degree_keeps_a_mesh_valid() {
        use crate::mesh::corner_refinement::CornerRefinement;
        let required = [
            (tags::CONTACT, "contact"),
            (tags::FAR, "far"),
            (tags::AXIS, "axis"),
        ];
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
        let mut meshes = Vec::new();
        for file in ["disk-L0.msh", "annulus-0.5-L0.msh", "annulus-0.9-L1.msh"] {
            let mesh = crate::mesh::msh::read_msh(&root.join(file)).expect("committed mesh");
            mesh.validate(&required).expect("committed mesh valid");
            let refined = CornerRefinement {
                radii: vec![1.0],
                size: 1e-9,
            }
            .apply(&mesh)
            .expect("refinement at the rim");
            refined.validate(&required).expect("refined mesh valid");
            // A file of quadratic triangles is raised from its own degree too.
            let quadratic = mesh.to_quadratic();
            quadratic.validate(&required).expect("quadratic mesh valid");
            meshes.extend([mesh, refined, quadratic]);
        }
        meshes.push(structured_rectangle(
            2.0,
            1.0,
            5,
            3,
            tags::CONTACT,
            tags::FAR,
            tags::AXIS,
        ));
        for mesh in &meshes {
            for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
                let raised = mesh.with_degree(degree);
                assert_eq!(raised.degree, degree);
                raised
                    .validate(&required)
                    .unwrap_or_else(|e| panic!("{} as P{}: {e}", mesh.source, degree as u8));
            }
        }
    }

    #[test]
    fn each_edge_gets_its_own_inner_nodes_even_around_a_vertex_of_many_cells() {
        // 5 000 cells around one vertex: 10 001 edges (the fan's spokes, its rim), each met once
        // or twice; listed and hashed edges must give one inner node (P2), two (P3) per edge.
        let cells = 5_000;
        let linear = fan(cells);
        let vertices = linear.nodes.len();
        let edges = 2 * cells + 1;
        let quadratic = linear.to_quadratic();
        assert_eq!(quadratic.nodes.len(), vertices + edges);
        let cubic = linear.to_cubic();
        assert_eq!(cubic.nodes.len(), vertices + 2 * edges + cells);
        // Neighbouring cells share the inner node of their common spoke.
        for k in 0..cells - 1 {
            let (this, next) = (quadratic.cell(k), quadratic.cell(k + 1));
            // Edge 2-0 of cell k is spoke k + 2, edge 0-1 of cell k + 1 the same spoke.
            assert_eq!(this[5], next[3], "cell {k}");
            let (this, next) = (cubic.cell(k), cubic.cell(k + 1));
            // The thirds run from the lower vertex (0) out: reversed across the two cells.
            assert_eq!([this[7], this[8]], [next[4], next[3]], "cell {k}");
        }
    }
}
