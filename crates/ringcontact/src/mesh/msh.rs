//! Reading gmsh `.msh` 4.1 files with `mshio`, validated.
//!
//! `mshio` 0.4 is unmaintained and returns what it parsed without checks, so this wrapper checks
//! everything the solver relies on and names the file, the tag and the element in every error:
//! unreadable or non-4.1 files, missing sections, element types other than 3/6-node triangles
//! (solid) and 2/3-node lines (boundary), boundary curves without a physical tag, nodes that do
//! not exist. Node tags may be dense (`mshio` drops them: index = tag - min) or sparse.

use std::collections::HashMap;
use std::path::Path;
use std::sync::{Arc, OnceLock};
use std::thread::JoinHandle;

use mshio::mshfile::ElementType;

use crate::error::{Error, Result};
use crate::mesh::files::sha256_hex;
use crate::mesh::triangulation::{BoundaryEdge, Degree, FileTags, Mesh};

fn err(path: &str, message: impl Into<String>) -> Error {
    Error::InvalidMesh {
        path: path.to_string(),
        message: message.into(),
    }
}

/// Check the `$MeshFormat` line ourselves: `4.1`, file type 0 (ASCII) or 1 (binary), data size
/// 8; whether the file is ASCII.
fn check_format_line(bytes: &[u8], name: &str) -> Result<bool> {
    let head = &bytes[..bytes.len().min(256)];
    let text = String::from_utf8_lossy(head);
    let mut lines = text.lines();
    if lines.next().map(str::trim) != Some("$MeshFormat") {
        return Err(err(
            name,
            "not a readable gmsh 4.1 mesh: line 1 is not `$MeshFormat`",
        ));
    }
    let format = lines.next().unwrap_or("");
    let fields: Vec<&str> = format.split_whitespace().collect();
    match fields.as_slice() {
        ["4.1", file_type @ ("0" | "1"), "8"] => Ok(*file_type == "0"),
        [version, ..] if *version != "4.1" => Err(err(
            name,
            format!("line 2: format version `{version}`; this reader takes gmsh 4.1 (gmsh -format msh41)"),
        )),
        _ => Err(err(
            name,
            format!(
                "line 2: `{}` is not `4.1 <0 ascii|1 binary> 8`",
                format.chars().take(60).collect::<String>()
            ),
        )),
    }
}

/// A map from a file's tags (node or element numbers) to values: a table indexed by the tag
/// when the tags are dense (gmsh numbers them 1..N), a hash map otherwise (any tags a file
/// holds). Reading a 1 MB mesh (9e4 quadratic unknowns) took 9 ms with the table against 12 ms
/// hashing every tag.
enum TagTable<V> {
    Dense(Vec<Option<V>>),
    Hashed(HashMap<u64, V>),
}

impl<V: Copy> TagTable<V> {
    /// An empty map for `count` tags of which the largest is `max_tag`.
    fn for_tags(max_tag: u64, count: usize) -> Self {
        match usize::try_from(max_tag) {
            Ok(max) if max <= 4 * count + 1024 => TagTable::Dense(vec![None; max + 1]),
            _ => TagTable::Hashed(HashMap::new()),
        }
    }

    /// Insert `value` under `tag`; whether the tag was there already.
    fn insert(&mut self, tag: u64, value: V) -> bool {
        match self {
            TagTable::Dense(table) => table[tag as usize].replace(value).is_some(),
            TagTable::Hashed(map) => map.insert(tag, value).is_some(),
        }
    }

    fn get(&self, tag: u64) -> Option<V> {
        match self {
            TagTable::Dense(table) => usize::try_from(tag)
                .ok()
                .and_then(|t| table.get(t).copied().flatten()),
            TagTable::Hashed(map) => map.get(&tag).copied(),
        }
    }
}

/// Line of each element's definition in the `$Elements` section of an ASCII file, by element tag
/// (empty for binary files). Block header lines have four numbers starting with the dimension;
/// element lines start with the element tag.
fn element_lines(bytes: &[u8]) -> TagTable<usize> {
    let mut lines = Vec::new();
    let Ok(text) = std::str::from_utf8(bytes) else {
        return TagTable::Hashed(HashMap::new());
    };
    let mut inside = false;
    let mut remaining_in_block = 0u64;
    let mut header_seen = false;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line == "$Elements" {
            inside = true;
            continue;
        }
        if line == "$EndElements" {
            break;
        }
        if !inside {
            continue;
        }
        if !header_seen {
            header_seen = true;
            continue;
        }
        let mut words = line.split_whitespace().map(|w| w.parse::<u64>().ok());
        if remaining_in_block == 0 {
            remaining_in_block = words.nth(3).flatten().unwrap_or(0);
            continue;
        }
        if let Some(Some(tag)) = words.next() {
            lines.push((tag, i + 1));
        }
        remaining_in_block -= 1;
    }
    let max_tag = lines.iter().map(|&(tag, _)| tag).max().unwrap_or(0);
    let mut table = TagTable::for_tags(max_tag, lines.len());
    for (tag, line) in lines {
        table.insert(tag, line);
    }
    table
}

/// ` at line N` for ASCII files (0: unknown, binary).
fn at_line(line: usize) -> String {
    if line > 0 {
        format!(" at line {line}")
    } else {
        String::new()
    }
}

/// The node tags of the `$Nodes` section in file order, each with its line (ASCII; 0 for binary).
fn node_tags_in_file_order(bytes: &[u8], name: &str) -> Result<Vec<(u64, usize)>> {
    let marker = b"$Nodes";
    let start = bytes
        .windows(marker.len() + 1)
        .position(|w| {
            &w[..marker.len()] == marker && (w[marker.len()] == b'\n' || w[marker.len()] == b'\r')
        })
        .ok_or_else(|| err(name, "no $Nodes section"))?;
    let binary = String::from_utf8_lossy(&bytes[..bytes.len().min(64)])
        .lines()
        .nth(1)
        .is_some_and(|l| l.split_whitespace().nth(1) == Some("1"));
    // Exactly one line ending after the marker: in a binary file the next byte is already data
    // (the block count, whose low byte may be 10 or 13, `\n` or `\r`).
    let mut body = start + marker.len();
    if bytes.get(body) == Some(&b'\r') {
        body += 1;
    }
    if bytes.get(body) == Some(&b'\n') {
        body += 1;
    }
    if binary {
        binary_node_tags(bytes, body, name)
    } else {
        text_node_tags(bytes, body, name)
    }
}

fn truncated_nodes(name: &str) -> Error {
    err(name, "the $Nodes section ends early (truncated file?)")
}

/// The node tags of a binary `$Nodes` section starting at byte `body` (line 0: no line numbers).
fn binary_node_tags(bytes: &[u8], body: usize, name: &str) -> Result<Vec<(u64, usize)>> {
    let truncated = || truncated_nodes(name);
    let mut at = body;
    let mut take = |n: usize| -> Result<&[u8]> {
        let slice = bytes.get(at..at + n).ok_or_else(truncated)?;
        at += n;
        Ok(slice)
    };
    let size = |b: &[u8]| u64::from_le_bytes(b.try_into().unwrap_or([0; 8]));
    let blocks = size(take(8)?);
    let _total = take(8)?;
    let _min_max = take(16)?;
    let mut tags = Vec::new();
    for _ in 0..blocks {
        let _dim_entity_parametric = take(12)?;
        let count = size(take(8)?);
        let tag_bytes = take(
            usize::try_from(count)
                .map_err(|_| truncated())?
                .checked_mul(8)
                .ok_or_else(truncated)?,
        )?;
        tags.extend(tag_bytes.chunks_exact(8).map(|c| (size(c), 0)));
        let coordinate_bytes = usize::try_from(count)
            .ok()
            .and_then(|c| c.checked_mul(24))
            .ok_or_else(truncated)?;
        take(coordinate_bytes)?;
    }
    Ok(tags)
}

/// The node tags of a text `$Nodes` section starting at byte `body`, each with its line number.
fn text_node_tags(bytes: &[u8], body: usize, name: &str) -> Result<Vec<(u64, usize)>> {
    let truncated = || truncated_nodes(name);
    let text = std::str::from_utf8(&bytes[body..])
        .map_err(|_| err(name, "the $Nodes section is not text"))?;
    let first_line = bytes[..body].iter().filter(|&&b| b == b'\n').count() + 1;
    let mut lines = text.lines().enumerate().map(|(i, l)| (first_line + i, l));
    let mut next_numbers = |what: &str| -> Result<(usize, Vec<u64>)> {
        let (line, content) = lines.next().ok_or_else(truncated)?;
        if what == "node coordinates" {
            return Ok((line, Vec::new()));
        }
        let numbers = content
            .split_whitespace()
            .map(|w| w.parse::<u64>())
            .collect::<std::result::Result<Vec<_>, _>>()
            .map_err(|_| {
                err(
                    name,
                    format!(
                        "line {line}: expected {what}, found `{}`",
                        content.chars().take(60).collect::<String>()
                    ),
                )
            })?;
        Ok((line, numbers))
    };
    let (line, header) = next_numbers("the $Nodes header (blocks, nodes, min tag, max tag)")?;
    let blocks = *header
        .first()
        .ok_or_else(|| err(name, format!("line {line}: empty $Nodes header")))?;
    let mut tags = Vec::new();
    for _ in 0..blocks {
        let (line, block) =
            next_numbers("a node block header (dimension, entity, parametric, count)")?;
        let count = *block.get(3).ok_or_else(|| {
            err(
                name,
                format!("line {line}: a node block header has 4 numbers"),
            )
        })?;
        for _ in 0..count {
            let (line, tag) = next_numbers("a node tag")?;
            match tag.as_slice() {
                [t] => tags.push((*t, line)),
                _ => return Err(err(name, format!("line {line}: expected one node tag"))),
            }
        }
        for _ in 0..count {
            next_numbers("node coordinates").ok();
        }
    }
    Ok(tags)
}

/// The file's name for messages and its bytes.
fn file_bytes(path: &Path) -> Result<(String, Vec<u8>)> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| err(&name, format!("cannot read: {e}")))?;
    Ok((name, bytes))
}

/// Read and parse a `.msh` file (format 4.1, ASCII or binary).
pub fn read_msh(path: &Path) -> Result<Mesh> {
    let (name, bytes) = file_bytes(path)?;
    parse_msh(&bytes, &name)
}

thread_local! {
    /// Set while this thread runs the mesh parser, whose panics [`catch_parser_panic`] turns
    /// into errors.
    static INSIDE_PARSER: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Whether this thread is inside the mesh parser, whose panics become an error naming the
/// file: a program's panic hook may stay silent then (the library installs no hook of its own).
pub fn inside_mesh_parser() -> bool {
    INSIDE_PARSER.with(std::cell::Cell::get)
}

/// Run `f`, turning a panic inside it into an `Err`; [`inside_mesh_parser`] says `true` on this
/// thread meanwhile. The process's panic hook is left as the program set it.
pub(crate) fn catch_parser_panic<R>(
    f: impl FnOnce() -> R + std::panic::UnwindSafe,
) -> std::thread::Result<R> {
    let was_inside = INSIDE_PARSER.with(|q| q.replace(true));
    let result = std::panic::catch_unwind(f);
    INSIDE_PARSER.with(|q| q.set(was_inside));
    result
}

/// The SHA-256 (hex) of a file's bytes, being computed on a thread of its own:
/// [`read_msh_hashed`] starts it when its scans of the text are done, so that it runs beside the
/// rest of the parse and whatever the caller does next on one core (checks, refinement);
/// [`Self::finish`] waits for it.
#[derive(Debug)]
pub(crate) enum PendingHash {
    /// Computed on this thread (no other could be started).
    Done(String),
    /// Still running, or finished and not yet joined.
    Running(JoinHandle<String>),
}

impl PendingHash {
    /// Start hashing `bytes` on a new thread (hash them here if no thread can be started).
    fn start(bytes: Arc<Vec<u8>>) -> Self {
        let hashing = std::thread::Builder::new().spawn({
            let bytes = Arc::clone(&bytes);
            move || sha256_hex(&bytes)
        });
        match hashing {
            Ok(handle) => Self::Running(handle),
            Err(_) => Self::Done(sha256_hex(&bytes)),
        }
    }

    /// The hash (lower-case hex), waiting for its thread if it is still running. A panic on that
    /// thread (none is expected) is resumed here.
    pub fn finish(self) -> String {
        match self {
            Self::Done(hex) => hex,
            Self::Running(handle) => handle
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
        }
    }
}

/// [`read_msh`], and the SHA-256 of the bytes it parsed: the provenance of exactly what was
/// solved. The hash starts on the thread that scans the text once its scans are done and is not
/// waited for here ([`PendingHash`]), since hashing a large mesh takes longer than mshio's parse
/// beside it; a caller about to use both cores waits for it first.
pub(crate) fn read_msh_hashed(path: &Path) -> Result<(Mesh, PendingHash)> {
    let (name, bytes) = file_bytes(path)?;
    let bytes = Arc::new(bytes);
    // Started once, even when the parse is retried with regular blanks.
    let hashing = OnceLock::new();
    let start_hash = || {
        hashing.get_or_init(|| PendingHash::start(Arc::clone(&bytes)));
    };
    let (mesh, ()) = parse_msh_beside(&bytes, &name, start_hash)?;
    let hash = hashing
        .into_inner()
        .unwrap_or_else(|| PendingHash::Done(sha256_hex(&bytes)));
    Ok((mesh, hash))
}

/// Parse `.msh` 4.1 bytes; `name` is used in error messages.
pub fn parse_msh(bytes: &[u8], name: &str) -> Result<Mesh> {
    parse_msh_beside(bytes, name, || ()).map(|(mesh, ())| mesh)
}

/// [`parse_msh`], with `beside` run on the thread that scans the text while mshio parses it.
///
/// gmsh reads ASCII meshes field by field, so any run of blanks separates two numbers and lines
/// may end in blanks; mshio wants exactly one space between fields and none at a line's end. An
/// ASCII mesh mshio refuses is read again with its blanks made regular
/// ([`with_regular_blanks`]), if that changes it: a hand-edited or tab-separated file is read as
/// gmsh reads it, and one wrong for other reasons gets the error found past its blanks (its
/// lines are kept, so the lines the error names are the file's).
fn parse_msh_beside<T: Send>(
    bytes: &[u8],
    name: &str,
    beside: impl Fn() -> T + Sync,
) -> Result<(Mesh, T)> {
    let ascii = check_format_line(bytes, name)?;
    match parse_regular_msh_beside(bytes, name, &beside) {
        Err(first) if ascii => match with_regular_blanks(bytes) {
            Some(regular) => parse_regular_msh_beside(&regular, name, &beside),
            None => Err(first),
        },
        result => result,
    }
}

/// `bytes` with every line's fields separated by one space and no blanks at its ends (`\n`
/// line endings, the number of lines kept, so error messages still name the file's lines), or
/// `None` when no line changes (a `\r\n` ending alone counts as regular: mshio reads it).
fn with_regular_blanks(bytes: &[u8]) -> Option<Vec<u8>> {
    let text = std::str::from_utf8(bytes).ok()?;
    let mut regular = String::with_capacity(text.len());
    let mut changed = false;
    for line in text.split_inclusive('\n') {
        let body = line.trim_end_matches(['\n', '\r']);
        let start = regular.len();
        for (i, field) in body.split_ascii_whitespace().enumerate() {
            if i > 0 {
                regular.push(' ');
            }
            regular.push_str(field);
        }
        changed |= &regular[start..] != body;
        if line.ends_with('\n') {
            regular.push('\n');
        }
    }
    changed.then(|| regular.into_bytes())
}

/// The mesh file as mshio returns it.
type MshFile = mshio::MshFile<u64, i32, f64>;
/// Its `$Entities` section (physical tags of curves and surfaces).
type MshEntities = mshio::mshfile::Entities<i32, f64>;
/// Its `$Nodes` section.
type MshNodes = mshio::mshfile::Nodes<u64, i32, f64>;
/// Its `$Elements` section.
type MshElements = mshio::mshfile::Elements<u64, i32>;

/// mshio's parse of a file beside our own scans of its text and the caller's work.
struct Scanned<T> {
    /// mshio's parse, its errors (and panics) described.
    file: Result<MshFile>,
    /// Node tags in file order with their lines.
    tags: Result<Vec<(u64, usize)>>,
    /// Each element's line by element tag (ASCII files).
    element_lines: TagTable<usize>,
    /// What the caller's `beside` returned.
    beside: T,
}

/// Run mshio's parse, our scans of the text and `beside` at the same time.
fn parse_and_scan<T: Send>(
    bytes: &[u8],
    name: &str,
    beside: &(impl Fn() -> T + Sync),
) -> Scanned<T> {
    // mshio unwraps in places (e.g. header numbers that overflow): a panic inside it is turned
    // into an error naming the file, never a crash.
    let parse = || catch_parser_panic(|| mshio::parse_msh_bytes(bytes));
    // Our own scans of the text (node tags, element lines) on a thread of their own while mshio
    // parses: at 9e4 quadratic unknowns (a 1 MB file) the whole read took 1.26-1.31 times
    // mshio's parse against 1.70-1.77 times one after the other. A thread, not the rayon pool:
    // the pool's sleeping workers took 1-2 ms to start a job here, about what the scans take.
    let scans = || (node_tags_in_file_order(bytes, name), element_lines(bytes));
    let (parsed, ((tags, element_lines), beside)) = std::thread::scope(|scope| {
        let scan_thread = std::thread::Builder::new();
        let scans = &scans;
        let scan_and_beside = move || (scans(), beside());
        match scan_thread.spawn_scoped(scope, scan_and_beside) {
            Ok(scanning) => {
                let parsed = parse();
                // A panic on the scan thread (none is expected: the scans return errors) is
                // resumed here, as if it had happened on this thread.
                let scanned = scanning
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
                (parsed, scanned)
            }
            Err(_) => (parse(), (scans(), beside())),
        }
    });
    let file = match parsed {
        Ok(result) => result.map_err(|e| {
            err(
                name,
                format!(
                    "not a readable gmsh 4.1 mesh: {}",
                    describe_parse_error(bytes, &format!("{e}"))
                ),
            )
        }),
        Err(_) => Err(err(
            name,
            "not a readable gmsh 4.1 mesh: the parser (mshio) failed on malformed content",
        )),
    };
    Scanned {
        file,
        tags,
        element_lines,
        beside,
    }
}

/// The three sections the solver needs, from a file of version 4.1.
fn required_sections(file: MshFile, name: &str) -> Result<(MshEntities, MshNodes, MshElements)> {
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

    Ok((entities, nodes_section, elements))
}

/// [`parse_msh_beside`] for a file whose format line is checked and whose blanks mshio accepts:
/// parse, check the sections, pair coordinates with tags, read the elements, compact, orient.
fn parse_regular_msh_beside<T: Send>(
    bytes: &[u8],
    name: &str,
    beside: &(impl Fn() -> T + Sync),
) -> Result<(Mesh, T)> {
    let scanned = parse_and_scan(bytes, name, beside);
    let (entities, nodes_section, elements) = required_sections(scanned.file?, name)?;
    let tags = scanned.tags?;
    let (coords, index_of_tag) = coordinates_by_tag(&nodes_section, &tags, name)?;
    let ElementsRead {
        degree,
        cells,
        cell_tags,
        boundary,
    } = read_elements(&entities, &elements, &index_of_tag, name)?;
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
        file_tags: FileTags {
            nodes: tags.iter().map(|&(tag, _)| tag).collect(),
            node_lines: tags.iter().map(|&(_, line)| line).collect(),
            cell_lines: {
                cell_tags
                    .iter()
                    .map(|&t| scanned.element_lines.get(t).unwrap_or(0))
                    .collect()
            },
            cells: cell_tags,
        },
    });
    orient_counter_clockwise(&mut mesh);
    Ok((mesh, scanned.beside))
}

/// Node coordinates in file order and each node's index by tag. mshio drops the tags when they
/// look dense (max - min = count - 1) and then only the position is known, so the tags are read
/// by our scan, in file order, and paired with mshio's coordinates (same order): nodes are found
/// by their tag, in any order, and a tag given twice is an error.
fn coordinates_by_tag(
    nodes_section: &MshNodes,
    tags: &[(u64, usize)],
    name: &str,
) -> Result<(Vec<[f64; 2]>, TagTable<usize>)> {
    let max_tag = tags.iter().map(|&(tag, _)| tag).max().unwrap_or(0);
    let mut index_of_tag: TagTable<usize> = TagTable::for_tags(max_tag, tags.len());
    // Never sized from the header's count: a file may claim 2^60 nodes (it is compared with the
    // nodes actually read below).
    let mut coords: Vec<[f64; 2]> = Vec::new();
    for node in nodes_section
        .node_blocks
        .iter()
        .flat_map(|b| b.nodes.iter())
    {
        let Some(&(tag, line)) = tags.get(coords.len()) else {
            return Err(err(
                name,
                "the $Nodes section has more coordinates than node tags",
            ));
        };
        if index_of_tag.insert(tag, coords.len()) {
            return Err(err(
                name,
                format!(
                    "node tag {tag} appears twice (second time{})",
                    at_line(line)
                ),
            ));
        }
        coords.push([node.x, node.y]);
    }
    if coords.len() != tags.len() {
        return Err(err(
            name,
            format!(
                "{} node tags but {} node coordinates",
                tags.len(),
                coords.len()
            ),
        ));
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

    Ok((coords, index_of_tag))
}

/// The triangles and boundary lines of a mesh file, checked.
struct ElementsRead {
    /// Linear (3-node) or quadratic (6-node) triangles.
    degree: Degree,
    /// Node indices of the triangles, `degree.nodes_per_cell()` a triangle.
    cells: Vec<usize>,
    /// Each triangle's element tag in the file.
    cell_tags: Vec<u64>,
    /// The boundary lines with their physical tags.
    boundary: Vec<BoundaryEdge>,
}

/// Read the element blocks: triangles on physical surfaces, lines on physical curves (points
/// skipped), one triangle order throughout, nodes that exist.
fn read_elements(
    entities: &MshEntities,
    elements: &MshElements,
    index_of_tag: &TagTable<usize>,
    name: &str,
) -> Result<ElementsRead> {
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
        index_of_tag.get(tag).ok_or_else(|| {
            err(
                name,
                format!("element {element} refers to node {tag}, which does not exist"),
            )
        })
    };
    let mut degree: Option<Degree> = None;
    let mut cells = Vec::new();
    let mut cell_tags = Vec::new();
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
                    cell_tags.push(e.element_tag);
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
    Ok(ElementsRead {
        degree,
        cells,
        cell_tags,
        boundary,
    })
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
    let mut node_tags = vec![0; nodes.len()];
    let mut node_lines = vec![0; nodes.len()];
    for (old, &new) in map.iter().enumerate() {
        if new != usize::MAX {
            node_tags[new] = mesh.file_tags.nodes.get(old).copied().unwrap_or(0);
            node_lines[new] = mesh.file_tags.node_lines.get(old).copied().unwrap_or(0);
        }
    }
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
        file_tags: FileTags {
            nodes: node_tags,
            node_lines,
            cells: mesh.file_tags.cells,
            cell_lines: mesh.file_tags.cell_lines,
        },
        ..mesh
    }
}

/// mshio's message in one line: the section and the block or entry where parsing stopped, then
/// what was wrong (its hex dump dropped). A file cut short says so.
fn describe_parse_error(bytes: &[u8], message: &str) -> String {
    let mut parts: Vec<String> = Vec::new();
    for line in message.lines().map(str::trim) {
        if line.is_empty() || line.starts_with("During parsing") {
            continue;
        }
        if line.starts_with("Hex dump") {
            break;
        }
        parts.push(line.trim_end_matches(',').to_string());
    }
    let mut text = parts.join(", ").replace(", an error occurred:", ":");
    if text.is_empty() {
        text = first_line(message);
    }
    let ends_cleanly = String::from_utf8_lossy(&bytes[bytes.len().saturating_sub(64)..])
        .trim_end()
        .ends_with("$EndElements");
    if !ends_cleanly && !bytes.windows(12).any(|w| w == b"$EndElements") {
        text.push_str(" (the file ends before `$EndElements`: truncated?)");
    }
    text.chars().take(400).collect()
}

fn first_line(s: &str) -> String {
    s.lines().next().unwrap_or("").chars().take(200).collect()
}

#[cfg(test)]
mod tests {
    /// A panic inside the parser becomes an error, and the library leaves the process's panic
    /// hook alone: the hook still sees it, and can tell it from others by [`inside_mesh_parser`].
    #[test]
    fn a_parser_panic_is_an_error_and_the_hook_is_the_programs() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        use std::sync::Arc;
        let (inside, outside) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)));
        let (inside_seen, outside_seen) = (Arc::clone(&inside), Arc::clone(&outside));
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |_| {
            let counter = if super::inside_mesh_parser() {
                &inside_seen
            } else {
                &outside_seen
            };
            counter.fetch_add(1, Ordering::SeqCst);
        }));
        let caught = super::catch_parser_panic(|| panic!("inside mshio"));
        let elsewhere = std::panic::catch_unwind(|| panic!("outside"));
        std::panic::set_hook(previous);
        assert!(caught.is_err() && elsewhere.is_err());
        assert!(!super::inside_mesh_parser());
        assert_eq!(inside.load(Ordering::SeqCst), 1);
        assert_eq!(outside.load(Ordering::SeqCst), 1);
    }

    use super::*;

    /// FIPS 180-2's first SHA-256 example ("abc"), computed on the hashing thread; a hash
    /// already computed is given as it is.
    #[test]
    fn the_hash_on_its_own_thread_is_sha256() {
        let abc = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
        let pending = PendingHash::start(Arc::new(b"abc".to_vec()));
        assert!(matches!(pending, PendingHash::Running(_)));
        assert_eq!(pending.finish(), abc);
        assert_eq!(PendingHash::Done(abc.into()).finish(), abc);
    }

    /// The hash a read reports is that of the file's bytes (the one `verify fenicsx` checks
    /// stored results against).
    #[test]
    fn a_read_reports_the_files_hash() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/annulus-0.9-L1.msh");
        let (mesh, hash) = read_msh_hashed(&path).unwrap();
        assert!(!mesh.nodes.is_empty());
        assert_eq!(
            hash.finish(),
            crate::mesh::provider::sha256_file(&path).unwrap()
        );
    }
}
