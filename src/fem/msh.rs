//! Reading gmsh `.msh` 4.1 files with `mshio`, validated.
//!
//! `mshio` 0.4 is unmaintained and returns what it parsed without checks, so this wrapper checks
//! everything the solver relies on and names the file, the tag and the element in every error:
//! unreadable or non-4.1 files, missing sections, element types other than 3/6-node triangles
//! (solid) and 2/3-node lines (boundary), boundary curves without a physical tag, nodes that do
//! not exist. Node tags may be dense (`mshio` drops them: index = tag - min) or sparse.

use std::collections::HashMap;
use std::path::Path;

use mshio::mshfile::ElementType;

use super::mesh::{BoundaryEdge, Degree, Mesh};
use crate::error::{Error, Result};

fn err(path: &str, message: impl Into<String>) -> Error {
    Error::InvalidMesh {
        path: path.to_string(),
        message: message.into(),
    }
}

/// Read and parse a `.msh` file (format 4.1, ASCII or binary).
pub fn read_msh(path: &Path) -> Result<Mesh> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| err(&name, format!("cannot read: {e}")))?;
    parse_msh(&bytes, &name)
}

/// Parse `.msh` 4.1 bytes; `name` is used in error messages.
pub fn parse_msh(bytes: &[u8], name: &str) -> Result<Mesh> {
    let file = mshio::parse_msh_bytes(bytes).map_err(|e| {
        err(
            name,
            format!(
                "not a readable gmsh 4.1 mesh: {}",
                first_line(&format!("{e}"))
            ),
        )
    })?;
    if (file.header.version - 4.1).abs() > 1e-9 {
        return Err(err(
            name,
            format!("format version {} (expected 4.1)", file.header.version),
        ));
    }
    let data = file.data;
    let entities = data
        .entities
        .ok_or_else(|| err(name, "no $Entities section (physical tags unknown)"))?;
    let nodes_section = data.nodes.ok_or_else(|| err(name, "no $Nodes section"))?;
    let elements = data
        .elements
        .ok_or_else(|| err(name, "no $Elements section"))?;

    // Node coordinates by tag.
    let min_tag = nodes_section.min_node_tag;
    let mut index_of_tag: HashMap<u64, usize> = HashMap::new();
    let mut coords: Vec<[f64; 2]> = Vec::with_capacity(nodes_section.num_nodes as usize);
    let mut dense_next = min_tag;
    for block in &nodes_section.node_blocks {
        match &block.node_tags {
            Some(map) => {
                let mut by_index: Vec<(usize, u64)> = map.iter().map(|(&t, &i)| (i, t)).collect();
                by_index.sort_unstable();
                for (i, tag) in by_index {
                    let node = block
                        .nodes
                        .get(i)
                        .ok_or_else(|| err(name, format!("node tag {tag} has no coordinates")))?;
                    index_of_tag.insert(tag, coords.len());
                    coords.push([node.x, node.y]);
                }
            }
            None => {
                for node in &block.nodes {
                    index_of_tag.insert(dense_next, coords.len());
                    coords.push([node.x, node.y]);
                    dense_next += 1;
                }
            }
        }
    }
    if coords.len() as u64 != nodes_section.num_nodes {
        return Err(err(
            name,
            format!(
                "{} nodes read, {} declared",
                coords.len(),
                nodes_section.num_nodes
            ),
        ));
    }

    // Physical tag of each curve and surface entity.
    let curve_tag: HashMap<i32, i32> = entities
        .curves
        .iter()
        .filter_map(|c| c.physical_tags.first().map(|&p| (c.tag, p)))
        .collect();
    let surface_is_physical: HashMap<i32, bool> = entities
        .surfaces
        .iter()
        .map(|s| (s.tag, !s.physical_tags.is_empty()))
        .collect();

    let node = |tag: u64, element: u64| -> Result<usize> {
        index_of_tag.get(&tag).copied().ok_or_else(|| {
            err(
                name,
                format!("element {element} refers to node {tag}, which does not exist"),
            )
        })
    };
    let mut degree: Option<Degree> = None;
    let mut cells = Vec::new();
    let mut boundary = Vec::new();
    for block in &elements.element_blocks {
        let (dim, entity, kind) = (block.entity_dim, block.entity_tag, block.element_type);
        match (dim, kind) {
            (0, _) => continue,
            (1, ElementType::Lin2 | ElementType::Lin3) => {
                let Some(&tag) = curve_tag.get(&entity) else {
                    return Err(err(
                        name,
                        format!("boundary curve {entity} has no physical tag"),
                    ));
                };
                for e in &block.elements {
                    let mut nodes = Vec::with_capacity(e.nodes.len());
                    for &t in &e.nodes {
                        nodes.push(node(t, e.element_tag)?);
                    }
                    boundary.push(BoundaryEdge { nodes, tag });
                }
            }
            (2, ElementType::Tri3 | ElementType::Tri6) => {
                if surface_is_physical.get(&entity) == Some(&false) {
                    return Err(err(name, format!("surface {entity} has no physical tag")));
                }
                let this = if kind == ElementType::Tri3 {
                    Degree::Linear
                } else {
                    Degree::Quadratic
                };
                if degree.is_some_and(|d| d != this) {
                    return Err(err(name, "mixed 3-node and 6-node triangles"));
                }
                degree = Some(this);
                for e in &block.elements {
                    if e.nodes.len() != this.nodes_per_cell() {
                        return Err(err(
                            name,
                            format!("element {} has {} nodes", e.element_tag, e.nodes.len()),
                        ));
                    }
                    for &t in &e.nodes {
                        cells.push(node(t, e.element_tag)?);
                    }
                }
            }
            (d, k) => {
                return Err(err(
                    name,
                    format!(
                        "unsupported element type {k:?} on entity {entity} (dimension {d}); \
                         supported: 3/6-node triangles and 2/3-node lines"
                    ),
                ))
            }
        }
    }
    let degree =
        degree.ok_or_else(|| err(name, "no triangles (is the solid a physical surface?)"))?;
    if boundary
        .iter()
        .any(|e| e.nodes.len() != degree.nodes_per_edge())
    {
        return Err(err(
            name,
            "boundary lines and triangles are of different order",
        ));
    }
    // Only nodes used by the elements: gmsh keeps geometry points that no element references.
    let mut mesh = compact(Mesh {
        nodes: coords,
        cells,
        degree,
        boundary,
        source: name.to_string(),
    });
    orient_counter_clockwise(&mut mesh);
    Ok(mesh)
}

/// gmsh orients triangles by the surface normal: a surface drawn clockwise in `(r, z)` gives
/// clockwise triangles throughout. A mesh that is clockwise everywhere is flipped consistently;
/// one with mixed orientation is left alone, so that validation reports its inverted elements.
fn orient_counter_clockwise(mesh: &mut Mesh) {
    let k = mesh.degree.nodes_per_cell();
    let signed_area = |cell: &[usize], nodes: &[[f64; 2]]| {
        let (p0, p1, p2) = (nodes[cell[0]], nodes[cell[1]], nodes[cell[2]]);
        (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1])
    };
    let all_clockwise = mesh
        .cells
        .chunks(k)
        .all(|c| signed_area(c, &mesh.nodes) < 0.0);
    if !all_clockwise {
        return;
    }
    for cell in mesh.cells.chunks_mut(k) {
        // (v0, v1, v2) -> (v0, v2, v1); mid-edge nodes (01, 12, 20) -> (02, 21, 10).
        cell.swap(1, 2);
        if k == 6 {
            cell.swap(3, 5);
        }
    }
}

/// Drop nodes that no triangle uses and renumber.
fn compact(mesh: Mesh) -> Mesh {
    let mut map = vec![usize::MAX; mesh.nodes.len()];
    let mut nodes = Vec::new();
    for &v in &mesh.cells {
        if map[v] == usize::MAX {
            map[v] = nodes.len();
            nodes.push(mesh.nodes[v]);
        }
    }
    let cells = mesh.cells.iter().map(|&v| map[v]).collect();
    let boundary = mesh
        .boundary
        .into_iter()
        .filter(|e| e.nodes.iter().all(|&v| map[v] != usize::MAX))
        .map(|e| BoundaryEdge {
            nodes: e.nodes.iter().map(|&v| map[v]).collect(),
            tag: e.tag,
        })
        .collect();
    Mesh {
        nodes,
        cells,
        boundary,
        ..mesh
    }
}

fn first_line(s: &str) -> String {
    s.lines().next().unwrap_or("").chars().take(200).collect()
}
