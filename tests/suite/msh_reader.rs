//! The gmsh reader: a valid file is read with its physical tags; every kind of malformed input is
//! a clear error naming the file and the problem, never a panic.

use ringcontact::mesh::msh::{parse_msh, read_msh};
use ringcontact::mesh::triangulation::{tags, Degree};

/// Unit square `[0, 1] x [-1, 0]` in `(r, z)`: two triangles; top = contact (1), right and
/// bottom = far (3), left = axis (4); solid = 10.
const VALID: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
0 3 1 0
1 0 0 0 1 0 0 1 1 0
2 0 -1 0 1 0 0 1 3 0
3 0 -1 0 0 0 0 1 4 0
1 0 -1 0 1 0 0 1 10 0
$EndEntities
$Nodes
1 4 1 4
2 1 0 4
1
2
3
4
0 0 0
1 0 0
1 -1 0
0 -1 0
$EndNodes
$Elements
4 6 1 6
1 1 1 1
1 1 2
1 2 1 2
2 2 3
3 3 4
1 3 1 1
4 4 1
2 1 2 2
5 1 4 3
6 1 3 2
$EndElements
";

const REQUIRED: [(i32, &str); 3] = [
    (tags::CONTACT, "contact"),
    (tags::FAR, "far"),
    (tags::AXIS, "axis"),
];

fn error_of(text: &str) -> String {
    match parse_msh(text.as_bytes(), "test.msh") {
        Err(e) => e.to_string(),
        Ok(mesh) => match mesh.validate(&REQUIRED) {
            Err(e) => e.to_string(),
            Ok(()) => panic!("accepted a malformed mesh:\n{text}"),
        },
    }
}

#[test]
fn reads_a_valid_mesh_with_its_tags() {
    let mesh = parse_msh(VALID.as_bytes(), "test.msh").unwrap();
    mesh.validate(&REQUIRED).unwrap();
    assert_eq!(mesh.degree, Degree::Linear);
    assert_eq!(mesh.nodes.len(), 4);
    assert_eq!(mesh.cell_count(), 2);
    assert_eq!(mesh.boundary_nodes(tags::CONTACT).len(), 2);
    assert_eq!(mesh.boundary_nodes(tags::FAR).len(), 3);
    let quadratic = mesh.to_quadratic();
    quadratic.validate(&REQUIRED).unwrap();
    assert_eq!(quadratic.nodes.len(), 9);
    assert_eq!(quadratic.to_linear().nodes.len(), 4);
}

#[test]
fn a_clockwise_mesh_is_reoriented_consistently() {
    let clockwise = VALID.replace("5 1 4 3\n6 1 3 2", "5 1 3 4\n6 1 2 3");
    let mesh = parse_msh(clockwise.as_bytes(), "test.msh").unwrap();
    mesh.validate(&REQUIRED).unwrap();
}

#[test]
fn malformed_meshes_are_errors_that_name_the_problem() {
    let cases: Vec<(String, &str)> = vec![
        (
            VALID
                .replace("2 2 3\n3 3 4\n", "")
                .replace("1 2 1 2\n", "1 2 1 0\n")
                .replace("4 6 1 6", "4 4 1 6"),
            "physical group 3 (far) is missing",
        ),
        (
            VALID
                .replace("2 1 2 2\n5 1 4 3\n6 1 3 2", "2 1 3 1\n5 1 4 3 2")
                .replace("4 6 1 6", "4 5 1 6"),
            "unsupported element type Qua4",
        ),
        (
            VALID.replace("5 1 4 3\n", "5 1 3 4\n"),
            "element tag 5 (line 33) with node tags 1, 3, 4 is inverted",
        ),
        (
            VALID.replace("0 -1 0\n$EndNodes", "-0.5 -1 0\n$EndNodes"),
            "off the half-plane",
        ),
        // Node 3 moved onto the line between nodes 1 and 2: triangle (1, 3, 2) has zero area.
        (
            VALID.replace("1 -1 0\n0 -1 0", "0.5 0 0\n0 -1 0"),
            "degenerate",
        ),
        (VALID.replace("6 1 3 2", "6 1 3 99"), "node 99"),
        (
            VALID.replace("1 0 -1 0 1 0 0 1 10 0", "1 0 -1 0 1 0 0 0 0"),
            "surface 1 has no physical tag",
        ),
        (
            VALID.replace("3 0 -1 0 0 0 0 1 4 0", "3 0 -1 0 0 0 0 0 0"),
            "boundary curve 3 has no physical tag",
        ),
        (
            "this is not a mesh".to_string(),
            "not a readable gmsh 4.1 mesh",
        ),
        (VALID.replace("4.1 0 8", "2.2 0 8"), "test.msh"),
    ];
    for (text, needle) in cases {
        let message = error_of(&text);
        assert!(
            message.contains(needle),
            "expected {needle:?} in {message:?}"
        );
        assert!(
            message.contains("test.msh"),
            "the file is not named in {message:?}"
        );
    }
}

#[test]
fn nodes_are_read_by_tag_in_any_order() {
    // The same nodes listed in the order 2, 1, 4, 3: mshio treats tags 1..4 as dense and drops
    // them; the reader must still place every node by its tag.
    let shuffled = VALID.replace(
        "1\n2\n3\n4\n0 0 0\n1 0 0\n1 -1 0\n0 -1 0\n",
        "2\n1\n4\n3\n1 0 0\n0 0 0\n0 -1 0\n1 -1 0\n",
    );
    assert_ne!(shuffled, VALID);
    let a = parse_msh(VALID.as_bytes(), "test.msh").unwrap();
    let b = parse_msh(shuffled.as_bytes(), "test.msh").unwrap();
    b.validate(&REQUIRED).unwrap();
    let area = |m: &ringcontact::mesh::triangulation::Mesh| -> Vec<[f64; 2]> {
        let mut cells: Vec<[f64; 2]> = (0..m.cell_count())
            .map(|c| {
                let cell = m.cell(c);
                let (cr, cz) = cell.iter().fold((0.0, 0.0), |(r, z), &n| {
                    (r + m.nodes[n][0], z + m.nodes[n][1])
                });
                [cr, cz]
            })
            .collect();
        cells.sort_by(|x, y| x.partial_cmp(y).unwrap());
        cells
    };
    assert_eq!(
        area(&a),
        area(&b),
        "the cells differ: nodes were placed by position"
    );
}

#[test]
fn a_duplicated_node_tag_is_an_error_naming_tag_and_line() {
    let duplicated = VALID.replace("1\n2\n3\n4\n0 0 0", "1\n2\n3\n2\n0 0 0");
    let message = error_of(&duplicated);
    assert!(message.contains("node tag 2 appears twice"), "{message}");
    assert!(message.contains("line 17"), "{message}");
}

/// `text` with its blanks made irregular as gmsh still reads them (it reads fields with
/// `fscanf`): fields separated by runs of spaces and tabs, lines indented and ending in blanks,
/// Windows line endings.
fn with_irregular_blanks(text: &str) -> String {
    text.lines()
        .enumerate()
        .map(|(i, line)| {
            let fields = line
                .split(' ')
                .collect::<Vec<_>>()
                .join(["  ", "\t", " \t "][i % 3]);
            format!(
                "{}{fields}{}\r\n",
                [" ", "", "\t"][i % 3],
                [" ", "\t", "  "][i % 2]
            )
        })
        .collect()
}

/// What a mesh holds, for comparing two reads: nodes, cells and tagged boundary edges.
fn contents(mesh: &ringcontact::mesh::triangulation::Mesh) -> String {
    let boundary: Vec<(i32, Vec<usize>)> = mesh
        .boundary
        .iter()
        .map(|e| (e.tag, e.nodes.clone()))
        .collect();
    let cells: Vec<Vec<usize>> = (0..mesh.cell_count())
        .map(|c| mesh.cell(c).to_vec())
        .collect();
    format!("{:?} {cells:?} {boundary:?}", mesh.nodes)
}

#[test]
fn irregular_blanks_are_read_as_gmsh_reads_them() {
    let irregular = with_irregular_blanks(VALID);
    assert!(irregular.contains("  ") && irregular.contains('\t') && irregular.contains(" \r\n"));
    let expected = parse_msh(VALID.as_bytes(), "test.msh").unwrap();
    let mesh = parse_msh(irregular.as_bytes(), "test.msh").unwrap();
    mesh.validate(&REQUIRED).unwrap();
    assert_eq!(contents(&mesh), contents(&expected));
    // A committed mesh (its nodes in several blocks, quadratic cells) likewise.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes/annulus-0.5-L1.msh");
    let text = std::fs::read_to_string(&path).unwrap();
    let expected = parse_msh(text.as_bytes(), "annulus.msh").unwrap();
    let mesh = parse_msh(with_irregular_blanks(&text).as_bytes(), "annulus.msh").unwrap();
    assert_eq!(contents(&mesh), contents(&expected));
}

#[test]
fn a_malformed_mesh_with_irregular_blanks_is_still_an_error_naming_its_line() {
    // The duplicated tag of the test above, in a file with irregular blanks: the same message,
    // the same line (the lines are kept as they are counted in the file).
    let duplicated = VALID.replace("1\n2\n3\n4\n0 0 0", "1\n2\n3\n2\n0 0 0");
    let message = error_of(&with_irregular_blanks(&duplicated));
    assert!(message.contains("node tag 2 appears twice"), "{message}");
    assert!(message.contains("line 17"), "{message}");
    // A file cut short, or cut inside a line: the same error as with regular blanks.
    for end in [
        VALID.find("$Elements").unwrap(),
        VALID.find("$EndNodes").unwrap() - 3,
    ] {
        let cut = &VALID[..end];
        assert_eq!(error_of(&with_irregular_blanks(cut)), error_of(cut));
    }
}

#[test]
fn a_missing_file_is_an_error() {
    let e = read_msh(std::path::Path::new("/nonexistent/mesh.msh"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("/nonexistent/mesh.msh") && e.contains("cannot read"),
        "{e}"
    );
}

#[test]
fn committed_meshes_are_valid() {
    let dir = ringcontact::fem::solver::mesh_directory();
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "msh") {
            let mesh = read_msh(&path).unwrap();
            mesh.validate(&REQUIRED).unwrap();
            mesh.to_quadratic().validate(&REQUIRED).unwrap();
            count += 1;
        }
    }
    assert!(
        count >= 9,
        "expected the committed mesh families L0-L2 in {}",
        dir.display()
    );
}

/// `VALID` with its node tags 1-4 and element tags 1-6 renumbered sparsely (far beyond their
/// count, so the reader looks them up by hashing instead of in a table).
fn sparsely_tagged(duplicate_node: bool) -> String {
    let node = |t: u64| [7u64, 900_000, 12, 5_000_000][t as usize - 1];
    let element = |t: u64| t * 1_000_003;
    let mut out = String::new();
    let mut section = "";
    // Element lines still to come in the current block (the line before them gives the count).
    let mut elements_left = 0;
    for line in VALID.lines() {
        if line.starts_with('$') {
            section = line;
            out.push_str(line);
            out.push('\n');
            continue;
        }
        let words: Vec<u64> = line
            .split_whitespace()
            .filter_map(|w| w.parse().ok())
            .collect();
        let renumbered = match (section, words.as_slice()) {
            ("$Nodes", [1, 4, 1, 4]) => "1 4 7 5000000".to_string(),
            ("$Nodes", [t]) => {
                let tag = if duplicate_node && *t == 4 { 2 } else { *t };
                node(tag).to_string()
            }
            ("$Elements", [4, 6, 1, 6]) => format!("4 6 {} {}", element(1), element(6)),
            ("$Elements", [tag, nodes @ ..]) if elements_left > 0 => {
                elements_left -= 1;
                let mut words = vec![element(*tag).to_string()];
                words.extend(nodes.iter().map(|&n| node(n).to_string()));
                words.join(" ")
            }
            ("$Elements", [_, _, _, count]) => {
                elements_left = *count;
                line.to_string()
            }
            _ => line.to_string(),
        };
        out.push_str(&renumbered);
        out.push('\n');
    }
    out
}

#[test]
fn sparse_node_and_element_tags_are_read_like_dense_ones() {
    let dense = parse_msh(VALID.as_bytes(), "test.msh").unwrap();
    let sparse_text = sparsely_tagged(false);
    assert!(sparse_text.contains("5000000"), "{sparse_text}");
    let sparse = parse_msh(sparse_text.as_bytes(), "test.msh").unwrap();
    sparse.validate(&REQUIRED).unwrap();
    assert_eq!(dense.nodes, sparse.nodes);
    assert_eq!(dense.cells, sparse.cells);
    assert_eq!(dense.file_tags.cell_lines, sparse.file_tags.cell_lines);
    let message = error_of(&sparsely_tagged(true));
    assert!(
        message.contains("node tag 900000 appears twice"),
        "{message}"
    );
}

/// `bytes` (a binary 4.1 mesh) with `extra` empty node blocks (a point entity, no nodes) after
/// the `$Nodes` header: the same mesh, with a block count of the caller's choosing.
fn with_empty_node_blocks(bytes: &[u8], extra: u64) -> Vec<u8> {
    let marker = b"$Nodes\n";
    let at = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .expect("a $Nodes section")
        + marker.len();
    let blocks = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap());
    let mut out = bytes[..at].to_vec();
    out.extend_from_slice(&(blocks + extra).to_le_bytes());
    out.extend_from_slice(&bytes[at + 8..at + 32]);
    for _ in 0..extra {
        // dimension 0, entity 1, not parametric (three i32), then a count of 0 (u64).
        for v in [0i32, 1, 0] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&0u64.to_le_bytes());
    }
    out.extend_from_slice(&bytes[at + 32..]);
    out
}

/// A binary mesh is read whatever its node block count, including 10 and 13, whose low byte is a
/// line ending (`\n`, `\r`): a reader that skipped every line-ending byte after `$Nodes` took
/// the count for one and rejected a valid gmsh mesh of 13 entities as truncated.
#[test]
fn binary_meshes_are_read_whatever_their_node_block_count() {
    let dir = ringcontact::fem::solver::mesh_directory();
    let bytes = std::fs::read(dir.join("small-domain-R5-binary.msh")).unwrap();
    let reference = parse_msh(&bytes, "small-domain-R5-binary.msh").unwrap();
    for extra in 1..=5 {
        let name = format!("small-domain-R5-binary.msh with {extra} empty node blocks");
        let mesh = parse_msh(&with_empty_node_blocks(&bytes, extra), &name)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(mesh.nodes, reference.nodes, "{name}");
        assert_eq!(mesh.cells.len(), reference.cells.len(), "{name}");
        mesh.validate(&REQUIRED).unwrap();
    }
}
