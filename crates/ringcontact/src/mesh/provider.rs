//! Meshes made for the scene: the FEM asks for "level k of the model for this contact line", and
//! the provider answers from the committed meshes, a content-addressed cache, or gmsh, in that
//! order, and says which (with the file's SHA-256 and the gmsh version) for the provenance.
//!
//! **Committed families** (`meshes/{disk,annulus-0.5,annulus-0.9}-L{0,1,2}.msh`): the embedded
//! default, enough for the default tolerance with neither gmsh nor network.
//!
//! **Adapted family** (generated from `meshes/half_space.geo`): geometric grading toward the
//! singular edges, `h(x) = min(hmin + g |x - a|, hmin + g |x - b|)` (the inner edge only for the
//! fixed annulus), and for a concave punch `hb + g |x - b̃|` around the free edge `b̃` located by
//! the FEM's own coarser solve; no uniform size along the contact line. Level `k` has
//! `g_k = 0.32 · 0.6^k`, `hmin_k` from [`adapted_rim_size`] and `hb_k = 10^-3 · 10^-k`: for
//! quadratic elements the force error of the graded zone falls like `g⁴` (a factor 7.7 per level),
//! for cubic like `g⁶`, and that of the innermost element like `hmin`. The domain radius is
//! `R = 1e7 a`. gmsh makes elements down to [`GMSH_MIN_ELEMENT_SIZE`]; smaller rim sizes are
//! reached by halving the corner patches in Rust ([`crate::mesh::corner_refinement`]), which the
//! provided mesh carries as a request applied when it is read.
//!
//! The cache lives in [`DataPaths::cache`] (`<project>/.mesh-cache/` by default, ignored by git),
//! keyed by the SHA-256 of the geometry file, the parameters and the gmsh version.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::mesh::corner_refinement::CornerRefinement;
use crate::mesh::files::hex;
pub use crate::mesh::files::{sha256_file, sha256_hex, DataPaths};
use crate::mesh::gmsh::Gmsh;
use sha2::{Digest, Sha256};

/// Domain radius of the adapted family, in units of `a`.
const ADAPTED_DOMAIN_RADIUS: f64 = 1e7;

/// Smallest element size (in units of `a`) asked of gmsh: its 2-D mesher keeps the elements'
/// shape only down to about `1e-8` of the coordinates' magnitude; smaller rim sizes come from
/// [`CornerRefinement`] (docs/decisions.md, "Meshes").
pub(crate) const GMSH_MIN_ELEMENT_SIZE: f64 = 1e-8;

/// Smallest element size (units of `a`) asked of gmsh around the axis point (a full contact's
/// refinement) and, by the solver, around a hole hidden inside the first node: there gmsh's time
/// grows like the inverse of the size (docs/decisions.md, "Where the constants come from").
pub(crate) const AXIS_MIN_ELEMENT_SIZE: f64 = 3e-7;

/// Smallest element size at a singular edge (after corner refinement): elements of `1e-10 a`
/// have vertex coordinates good to `1e-6` of their size.
const MIN_RIM_SIZE: f64 = 1e-10;

/// Size of the elements at the singular edges on level `k`: `1e-4 · 100^-k` for `k >= 0` (1e-4
/// on the coarse levels `k < 0`), floored at 1e-10.
/// The innermost element's force error is about `0.16 hmin` (P2), and each decade of
/// `hmin` costs only `ln(10)/g` more element layers, so the rim is refined well past the graded
/// zone's error. (The free surface is cut at `r = 2a`: gmsh 4.15 stalls meshing one curve from
/// `a` to `R = 1e7 a` with elements of 1e-7 at one end.)
fn adapted_rim_size(level: i32) -> f64 {
    (1e-4 * 0.01f64.powi(level.max(0))).max(MIN_RIM_SIZE)
}

/// Width of the contact ring (in units of `a`) below which the ring's own width, not `a`, sets
/// the size of the elements at its edges ([`ring_width_scale`]).
const NARROW_RING_WIDTH: f64 = 0.1;

/// Width `1 - b/a` of the contact ring (units of `a`), `b/a` being the annulus' inner edge
/// `contact_start` or a concave punch's located `free_edge`; no narrower than the located edge's
/// `edge_uncertainty` (an edge found at the rim, only the rim node in contact on the coarser
/// model, bounds a ring narrower than that model's spacing there).
fn ring_width(contact_start: f64, free_edge: Option<f64>, edge_uncertainty: f64) -> f64 {
    let inner = contact_start.max(free_edge.unwrap_or(0.0));
    (1.0 - inner).max(edge_uncertainty).clamp(0.0, 1.0)
}

/// Factor on the rim size for a contact ring `width` wide ([`ring_width`]):
/// `min(1, width /` [`NARROW_RING_WIDTH`]`)`. The two edges' singular fields scale with the
/// ring's width, and so does the innermost element's force error; unscaled, narrow rings erred
/// far beyond their estimates (docs/decisions.md, "Where the constants come from").
pub(crate) fn ring_width_scale(width: f64) -> f64 {
    (width / NARROW_RING_WIDTH).clamp(0.0, 1.0)
}

/// Rim size wanted for `level` and `target`: [`adapted_rim_size`], and no larger than a tenth of
/// the target's tolerance (the innermost element's force error is about `0.16 hmin` for P2, and
/// `0.5 hmin` for P3 on the fixed annulus `b/a = 0.97`), both times `ring_scale`
/// ([`ring_width_scale`]); never below [`MIN_RIM_SIZE`].
fn wanted_rim_size(level: i32, target: Option<SizeTarget>, ring_scale: f64) -> f64 {
    let size = match target {
        Some(t) => adapted_rim_size(level).min(0.1 * t.tolerance),
        None => adapted_rim_size(level),
    };
    (size * ring_scale).max(MIN_RIM_SIZE)
}

/// Whether the rim size that `target` needs on a contact ring `width` wide ([`ring_width`]),
/// a tenth of the tolerance times [`ring_width_scale`], is one the FEM makes (at least
/// [`MIN_RIM_SIZE`]); otherwise an error naming the loosest tolerance that would do. Below it
/// the last levels would share the floor's rim size and their changes would not see the error
/// the edges leave (docs/decisions.md, "Where the constants come from").
fn check_rim_size_reachable(width: f64, target: SizeTarget) -> Result<()> {
    let ring_scale = ring_width_scale(width);
    let needed = 0.1 * target.tolerance * ring_scale;
    // A relative slack for the rounding of the product: a need of exactly the floor is met.
    if needed >= MIN_RIM_SIZE * (1.0 - 1e-9) {
        return Ok(());
    }
    Err(Error::OutOfRange {
        method: "fem".into(),
        reason: format!(
            "a contact ring {} a wide (b/a = {}) needs elements of {} a at its edges for the \
             tolerance {:e}, below the smallest the FEM makes ({MIN_RIM_SIZE:e} a); ask for a \
             tolerance of at least {}, or use the ring BEM (rings of 1e-4 a and wider) or, for \
             a fixed annulus narrower than that, `--method reference` (the narrow-ring asymptote)",
            crate::error::show(width),
            crate::error::show(1.0 - width),
            crate::error::show(needed),
            target.tolerance,
            crate::error::show(MIN_RIM_SIZE / (0.1 * ring_scale)),
        ),
    })
}

/// The corner refinement that completes the gmsh mesh of [`adapted_parameters`] (same
/// arguments): the singular edges `r = a` (and `r = b` for `contact_start > 0`) halved down to
/// [`wanted_rim_size`] (for the ring's [`ring_width`]) when that is below
/// [`GMSH_MIN_ELEMENT_SIZE`].
fn adapted_corner_refinement(
    contact_start: f64,
    level: i32,
    free_edge: Option<f64>,
    edge_uncertainty: f64,
    target: Option<SizeTarget>,
) -> Option<CornerRefinement> {
    let ring_scale = ring_width_scale(ring_width(contact_start, free_edge, edge_uncertainty));
    let size = wanted_rim_size(level, target, ring_scale);
    (size < GMSH_MIN_ELEMENT_SIZE).then(|| CornerRefinement {
        radii: if contact_start > 0.0 {
            vec![contact_start, 1.0]
        } else {
            vec![1.0]
        },
        size,
    })
}

/// Highest level of the adapted family.
pub const ADAPTED_MAX_LEVEL: i32 = 7;
/// Lowest level of the adapted family: `g = 0.89`, a few thousand unknowns, enough for the
/// default tolerance with cubic elements.
pub const ADAPTED_MIN_LEVEL: i32 = -2;
/// Highest committed level.
pub(crate) const COMMITTED_MAX_LEVEL: usize = 2;

/// A mesh the FEM asks for.
#[derive(Clone, Debug, PartialEq)]
pub enum MeshRequest {
    /// `meshes/{family}-L{level}.msh`.
    Committed { family: String, level: usize },
    /// Level `level` of the adapted family for a contact line starting at `contact_start = b/a`
    /// (0 for the disk), refined around `free_edge` when given, with elements there no smaller
    /// than a quarter of `edge_uncertainty` (the coarser model's error of that radius).
    Adapted {
        contact_start: f64,
        level: i32,
        free_edge: Option<f64>,
        edge_uncertainty: f64,
        /// The solve the mesh is made for (sizes at the edges follow its tolerance), if any.
        target: Option<SizeTarget>,
    },
    /// Level `level` for a contact with two free edges (a free band), in the mesh's units (the
    /// contact line `[0, 1]`): refined around each located edge `(radius, uncertainty)`
    /// ([`free_edges_parameters`]).
    FreeEdges {
        level: i32,
        edges: [(f64, f64); 2],
        /// The solve the mesh is made for, its tolerance in the mesh's units.
        target: SizeTarget,
        /// [`ring_width_scale`] of the contact's width.
        ring_scale: f64,
    },
}

/// What a generated mesh is made for: the relative tolerance and the element degree of the solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SizeTarget {
    pub tolerance: f64,
    pub degree: usize,
}

/// Contact nodes the free-edge window `[b̃, b̃ + δ]` may hold on each side of the located edge: the
/// element size at the edge is chosen so that the graded sizes `hb + g |r - b̃|` put about this
/// many contact nodes (elements times degree) in it, which keeps the banded contact solve
/// (at most [`crate::fem::contact_band::MAX_BAND_NODES`] nodes) in play.
const EDGE_WINDOW_NODES: f64 = 24.0;

impl MeshRequest {
    /// Short name for tables: `disk-L1`, `adapted-0.3-L4`.
    pub fn label(&self) -> String {
        match self {
            MeshRequest::Committed { family, level } => format!("{family}-L{level}"),
            MeshRequest::Adapted {
                contact_start,
                level,
                ..
            } => format!("adapted-{contact_start}-L{level}"),
            MeshRequest::FreeEdges { level, .. } => format!("free-edges-L{level}"),
        }
    }

    /// The same request refined around a free edge at `b/a`, known to within `uncertainty`
    /// (adapted family only).
    pub fn with_free_edge(self, edge: Option<f64>, uncertainty: f64) -> MeshRequest {
        match self {
            MeshRequest::Adapted {
                contact_start,
                level,
                target,
                ..
            } => MeshRequest::Adapted {
                contact_start,
                level,
                free_edge: edge.filter(|&b| b > 0.0),
                edge_uncertainty: uncertainty,
                target,
            },
            other => other,
        }
    }
}

/// Where a provided mesh came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MeshOrigin {
    Committed,
    Cache,
    Gmsh,
    /// Given by the user (`--mesh`).
    User,
}

/// A mesh file ready to read, with its provenance.
#[derive(Clone, Debug)]
pub struct ProvidedMesh {
    pub path: PathBuf,
    pub origin: MeshOrigin,
    /// Version of the gmsh that made it (generated meshes only).
    pub gmsh_version: Option<String>,
    /// Refinement around the singular edges applied to the file's mesh when it is read (rim
    /// sizes below what gmsh makes well, [`GMSH_MIN_ELEMENT_SIZE`]).
    pub corner_refinement: Option<CornerRefinement>,
}

impl ProvidedMesh {
    /// SHA-256 (hex) of the file as it is now. Not kept from when the mesh was provided: a
    /// solve reports the hash of the bytes it read (computed beside the parse, at no cost to its
    /// time), and hashing a cached file when it is looked up as well cost about 5.6 ms per MB
    /// for every rung of a ladder.
    pub fn sha256(&self) -> Result<String> {
        sha256_file(&self.path)
    }
}

/// Whether gmsh can be found for `data` ([`Gmsh::get`]): the meshes made per scene are
/// available.
pub fn gmsh_available(data: &DataPaths) -> bool {
    Gmsh::get(data, "").is_ok()
}

/// Committed family for a contact line starting at `b/a` (`disk` for 0), if there is one.
pub(crate) fn committed_family(data: &DataPaths, contact_start: f64) -> Option<String> {
    let name = if contact_start == 0.0 {
        "disk".to_string()
    } else {
        format!("annulus-{contact_start}")
    };
    data.meshes
        .join(format!("{name}-L0.msh"))
        .exists()
        .then_some(name)
}

/// Grading `g_k = 0.32 · 0.6^k` of level `k` of the adapted family.
fn adapted_grading(level: i32) -> f64 {
    0.32 * 0.6f64.powi(level)
}

/// `gmsh -setnumber` parameters of level `level` of the adapted family (module documentation).
///
/// Sizes: grading `g` from [`adapted_grading`]; rim size `hmin` from [`wanted_rim_size`], but
/// not below [`GMSH_MIN_ELEMENT_SIZE`] (finer is [`adapted_corner_refinement`]'s job); around a
/// free edge known to within `δ`, the edge size `hb = g δ / (exp(N g / p) - 1)` puts `N` =
/// [`EDGE_WINDOW_NODES`] contact nodes of degree `p` in `[b̃, b̃ + δ]` (`∫ p dr / (hb + g r) = N`),
/// but never below `0.75 p · tol` times the ring's [`ring_width_scale`] (which makes the edge's
/// location bound `0.3 hb / p` under a quarter of the tolerance, and on a narrow ring keeps as many
/// elements across the ring at the edge as on a wide one) or, without a target, `1e-3 · 10^-k`,
/// unless a quarter of a hole `b̃ > 0` is smaller (a small hole keeps a few elements). Unscaled,
/// the free edge of a ring `3e-4 a` wide (parabolic gap at `d = 0.004 h`, P2, `--tol 1e-5`) had
/// elements of `1.5e-5 a`, and its force error of 2.6e-6 was above the estimate of 2.0e-6: the
/// levels shared that size, so their changes did not see the edge's share. Around the axis point
/// (full contact) the edge size is never below [`AXIS_MIN_ELEMENT_SIZE`].
pub fn adapted_parameters(
    contact_start: f64,
    level: i32,
    free_edge: Option<f64>,
    edge_uncertainty: f64,
    target: Option<SizeTarget>,
) -> Vec<(String, f64)> {
    let grading = adapted_grading(level);
    let degree = target.map_or(2.0, |t| t.degree as f64);
    let ring_scale = ring_width_scale(ring_width(contact_start, free_edge, edge_uncertainty));
    let hmin = wanted_rim_size(level, target, ring_scale).max(GMSH_MIN_ELEMENT_SIZE);
    let edge_floor = free_edge_floor(level, target, ring_scale);
    let window = free_edge_window(grading, degree, edge_uncertainty);
    // A hole smaller than the floor (a deep linear gap: b/a = 9e-4 at d = 12h) still gets elements
    // of a quarter of its radius. Full contact (`b̃ = 0`) has no hole to keep elements in: its
    // axis refinement stays at the floor (else each level's window, a fraction of the last
    // node spacing, shrank it again, down to gmsh stalling on 5e-10 a).
    let edge_floor = match free_edge {
        Some(b) if b > 0.0 => edge_floor.min(0.25 * b),
        _ => edge_floor,
    };
    // Never below what gmsh meshes well at the edge's radius (GMSH_MIN_ELEMENT_SIZE of the
    // coordinates' magnitude; the free edge is not singular, so no corner refinement goes
    // further): binds only on levels 6 and 7 without a target. Around the axis point itself
    // (full contact), never below [`AXIS_MIN_ELEMENT_SIZE`].
    let smallest = match free_edge {
        Some(b) if b <= 0.0 => AXIS_MIN_ELEMENT_SIZE,
        _ => GMSH_MIN_ELEMENT_SIZE * free_edge.unwrap_or(1.0).max(1e-2),
    };
    let hb = window.max(edge_floor).clamp(smallest, 1e-2);
    let mut p = vec![
        ("a".to_string(), 1.0),
        ("b".to_string(), contact_start),
        ("R".to_string(), ADAPTED_DOMAIN_RADIUS),
        ("split".to_string(), 2.0),
        ("hmin".to_string(), hmin),
        // No uniform size along the contact line: the line field never binds.
        ("hline".to_string(), 10.0),
        ("grading".to_string(), grading),
        ("order".to_string(), 1.0),
    ];
    // bref = 0: a concave punch found in full contact, refined around the axis point.
    if let Some(b) = free_edge.filter(|&b| b >= 0.0) {
        p.push(("bref".to_string(), b));
        p.push(("hb".to_string(), hb));
    }
    p
}

/// Smallest element size asked at a free edge for `target` (module documentation of
/// [`adapted_parameters`]): `0.75 p · tol` times the ring's `ring_scale`, or without a target
/// `1e-3 · 10^-k`.
fn free_edge_floor(level: i32, target: Option<SizeTarget>, ring_scale: f64) -> f64 {
    match target {
        Some(t) => 0.75 * t.degree as f64 * t.tolerance * ring_scale,
        None => 1e-3 * 0.1f64.powi(level.max(0)),
    }
}

/// Element size at a free edge known to within `uncertainty` that puts
/// [`EDGE_WINDOW_NODES`] contact nodes of degree `p` in the window of that width:
/// `hb = g δ / (exp(N g / p) - 1)`.
fn free_edge_window(grading: f64, degree: f64, uncertainty: f64) -> f64 {
    grading * uncertainty / (EDGE_WINDOW_NODES * grading / degree).exp_m1()
}

/// `gmsh -setnumber` parameters of level `level` for a contact with two free edges (a free band),
/// in the mesh's units (the contact line `[0, 1]`): the adapted family's grading, no refinement
/// at the line's end `r = 1` (not an edge of the contact), and around each located edge
/// (`inner`, `outer`, known to within `inner_uncertainty`, `outer_uncertainty`) the size of
/// [`free_edge_window`], no smaller than [`free_edge_floor`] for `target` (whose tolerance the
/// caller states in the mesh's units) and `ring_scale`, nor than gmsh shapes well.
pub(crate) fn free_edges_parameters(
    level: i32,
    edges: [(f64, f64); 2],
    target: SizeTarget,
    ring_scale: f64,
) -> Vec<(String, f64)> {
    let grading = adapted_grading(level);
    let degree = target.degree as f64;
    let floor = free_edge_floor(level, Some(target), ring_scale);
    let size = |(edge, uncertainty): (f64, f64)| {
        let smallest = GMSH_MIN_ELEMENT_SIZE * edge.max(1e-2);
        let floor = if edge > 0.0 {
            floor.min(0.25 * edge)
        } else {
            floor
        };
        free_edge_window(grading, degree, uncertainty)
            .max(floor)
            .clamp(smallest, 1e-2)
    };
    let [inner, outer] = edges;
    vec![
        ("a".to_string(), 1.0),
        ("b".to_string(), 0.0),
        ("R".to_string(), ADAPTED_DOMAIN_RADIUS),
        ("split".to_string(), 2.0),
        ("hmin".to_string(), 1e-2),
        ("hline".to_string(), 10.0),
        ("grading".to_string(), grading),
        ("order".to_string(), 1.0),
        ("bref".to_string(), inner.0),
        ("hb".to_string(), size(inner)),
        ("cref".to_string(), outer.0),
        ("hc".to_string(), size(outer)),
    ]
}

/// Provide the mesh of `request` from `data` (committed file, cache, or gmsh); `why` names the
/// scene for the error when gmsh is needed and missing.
pub fn provide(data: &DataPaths, request: &MeshRequest, why: &str) -> Result<ProvidedMesh> {
    match request {
        MeshRequest::Committed { family, level } => {
            let path = data.meshes.join(format!("{family}-L{level}.msh"));
            if !path.is_file() && data.meshes == data.root.join("meshes") {
                // A missing data directory is named as such, not as a missing mesh.
                data.check()?;
            }
            Ok(ProvidedMesh {
                path,
                origin: MeshOrigin::Committed,
                gmsh_version: None,
                corner_refinement: None,
            })
        }
        MeshRequest::Adapted {
            contact_start,
            level,
            free_edge,
            edge_uncertainty,
            target,
        } => {
            if let Some(target) = target {
                let width = ring_width(*contact_start, *free_edge, *edge_uncertainty);
                check_rim_size_reachable(width, *target)?;
            }
            let (start, level, edge, uncertainty, target) = (
                *contact_start,
                *level,
                *free_edge,
                *edge_uncertainty,
                *target,
            );
            let parameters = adapted_parameters(start, level, edge, uncertainty, target);
            let mut provided = generate(data, &parameters, why)?;
            provided.corner_refinement =
                adapted_corner_refinement(start, level, edge, uncertainty, target);
            Ok(provided)
        }
        MeshRequest::FreeEdges {
            level,
            edges,
            target,
            ring_scale,
        } => generate(
            data,
            &free_edges_parameters(*level, *edges, *target, *ring_scale),
            why,
        ),
    }
}

/// Whether the file's last line is a whole section end (`$End...` and a newline), as every gmsh
/// `.msh` file's is: false for a file cut short (or unreadable).
fn ends_with_a_section_end(path: &Path) -> bool {
    use std::io::{Read, Seek, SeekFrom};
    let Ok(mut file) = std::fs::File::open(path) else {
        return false;
    };
    let Ok(len) = file.seek(SeekFrom::End(0)) else {
        return false;
    };
    let mut tail = Vec::new();
    if file.seek(SeekFrom::Start(len.saturating_sub(64))).is_err()
        || file.read_to_end(&mut tail).is_err()
    {
        return false;
    }
    // gmsh ends every line, the last one too, with a newline: a file cut inside its last line
    // has none at its end.
    tail.ends_with(b"\n")
        && tail
            .split(|&b| b == b'\n')
            .map(|line| line.trim_ascii())
            .rfind(|line| !line.is_empty())
            .is_some_and(|line| line.starts_with(b"$End"))
}

/// The parameters `meshes/half_space.geo` declares (its `DefineConstant` block): the names
/// [`parse_parameters`] accepts.
const GEO_PARAMETERS: [&str; 14] = [
    "a", "b", "R", "hmin", "hline", "grading", "bref", "hb", "cref", "hc", "band", "hband",
    "split", "order",
];

/// Read `NAME=VALUE,NAME=VALUE,...` (the form [`format_parameters`] writes and stored results
/// carry in their `reproduce` commands) into `-setnumber` parameters, in the order given (the
/// cache key depends on it). Unknown names, repeated names and values that are not finite
/// numbers are refused with the offending item named.
pub fn parse_parameters(text: &str) -> Result<Vec<(String, f64)>> {
    let refuse = |message: String| Error::invalid("mesh parameters", message);
    let mut out: Vec<(String, f64)> = Vec::new();
    for item in text.split(',').map(str::trim).filter(|i| !i.is_empty()) {
        let (name, value) = item
            .split_once('=')
            .ok_or_else(|| refuse(format!("'{item}' is not NAME=VALUE")))?;
        let name = name.trim();
        if !GEO_PARAMETERS.contains(&name) {
            return Err(refuse(format!(
                "unknown parameter '{name}' (meshes/half_space.geo takes {})",
                GEO_PARAMETERS.join(", ")
            )));
        }
        if out.iter().any(|(n, _)| n == name) {
            return Err(refuse(format!("'{name}' is given twice")));
        }
        let value: f64 = value
            .trim()
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| refuse(format!("'{item}': the value is not a finite number")))?;
        out.push((name.to_string(), value));
    }
    if out.is_empty() {
        return Err(refuse("no parameters given".into()));
    }
    check_geometry(&out).map_err(refuse)?;
    Ok(out)
}

/// The rules `meshes/half_space.geo` needs of its parameters (the file's defaults for those not
/// given): `0 <= b < a < R`, positive sizes and grading, `split` 0 or beyond `a` and inside `R`,
/// `order` 1 or 2.
fn check_geometry(parameters: &[(String, f64)]) -> std::result::Result<(), String> {
    let get = |name: &str, default: f64| {
        parameters
            .iter()
            .find(|(n, _)| n == name)
            .map_or(default, |(_, v)| *v)
    };
    let (a, b, r) = (get("a", 1.0), get("b", 0.0), get("R", 1e5));
    if !(0.0 <= b && b < a && a < r) {
        return Err(format!(
            "need 0 <= b < a < R (got b = {b}, a = {a}, R = {r})"
        ));
    }
    for name in ["hmin", "hline", "grading", "hb", "hc", "hband"] {
        if let Some((_, v)) = parameters.iter().find(|(n, _)| n == name) {
            if *v <= 0.0 {
                return Err(format!("{name} must be positive (got {v})"));
            }
        }
    }
    let split = get("split", 0.0);
    if split != 0.0 && !(split * a > a && split * a < r) {
        return Err(format!(
            "split cuts the free surface at split * a: need 0 (no cut) or a < split * a < R \
             (got {split})"
        ));
    }
    if !matches!(get("order", 1.0), 1.0 | 2.0) {
        return Err("order must be 1 or 2".into());
    }
    Ok(())
}

/// `NAME=VALUE,...` with each value in its shortest form that reads back to the same `f64`
/// (so a mesh remade from the text is the same mesh, byte for byte, as the one stored).
pub fn format_parameters(parameters: &[(String, f64)]) -> String {
    parameters
        .iter()
        .map(|(name, value)| {
            // Both forms are Rust's shortest text that reads back to the same f64.
            if value.abs() >= 1e-3 && value.abs() < 1e6 || *value == 0.0 {
                format!("{name}={value}")
            } else {
                format!("{name}={value:e}")
            }
        })
        .collect::<Vec<_>>()
        .join(",")
}

/// Mesh `meshes/half_space.geo` of `data` with `parameters`, through its cache.
pub fn generate(data: &DataPaths, parameters: &[(String, f64)], why: &str) -> Result<ProvidedMesh> {
    let geo = data.meshes.join("half_space.geo");
    let geo_bytes = std::fs::read(&geo).map_err(|e| Error::InvalidMesh {
        path: geo.display().to_string(),
        message: format!("cannot read the geometry file: {e}"),
    })?;
    let gmsh = Gmsh::get(data, why)?;
    let mut hasher = Sha256::new();
    hasher.update(&geo_bytes);
    for (name, value) in parameters {
        hasher.update(format!("{name}={value:e};").as_bytes());
    }
    hasher.update(format!("gmsh {}", gmsh.version).as_bytes());
    let key = hex(&hasher.finalize());
    let dir = data.cache.clone();
    let path = dir.join(format!("{}.msh", &key[..24]));
    if path.exists() && !ends_with_a_section_end(&path) {
        // Cut short after gmsh made it (files enter the cache whole, renamed from a partial
        // name): made again below. Damage elsewhere in a file is found by the reader, whose
        // message names the cache.
        eprintln!(
            "note: the cached mesh {} is cut short; gmsh makes it again",
            path.display()
        );
        let _ = std::fs::remove_file(&path);
    }
    if path.exists() {
        return Ok(ProvidedMesh {
            path,
            origin: MeshOrigin::Cache,
            gmsh_version: Some(gmsh.version),
            corner_refinement: None,
        });
    }
    std::fs::create_dir_all(&dir).map_err(|e| Error::InvalidMesh {
        path: dir.display().to_string(),
        message: format!("cannot create the mesh cache: {e}"),
    })?;
    // Write under a unique name, then rename: concurrent runs never see a half-written file.
    let partial = dir.join(format!("{}.{}.partial.msh", &key[..24], std::process::id()));
    gmsh.mesh(&geo, parameters, &partial)?;
    std::fs::rename(&partial, &path).map_err(|e| Error::InvalidMesh {
        path: path.display().to_string(),
        message: format!("cannot store the generated mesh: {e}"),
    })?;
    Ok(ProvidedMesh {
        path,
        origin: MeshOrigin::Gmsh,
        gmsh_version: Some(gmsh.version),
        corner_refinement: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_parameters_read_back_exactly_and_bad_ones_are_named() {
        let parameters = adapted_parameters(0.0, 1, Some(0.4505), 1e-4, None);
        let text = format_parameters(&parameters);
        assert_eq!(parse_parameters(&text).unwrap(), parameters);
        let tiny = vec![("hmin".to_string(), 1.0000000000000002e-6)];
        assert_eq!(parse_parameters(&format_parameters(&tiny)).unwrap(), tiny);
        for (bad, named) in [
            ("a=1,zz=2", "zz"),
            ("a=1,a=2", "'a' is given twice"),
            ("a=x", "a=x"),
            ("a=inf", "a=inf"),
            ("a", "'a' is not NAME=VALUE"),
            ("", "no parameters"),
            ("b=2", "need 0 <= b < a < R"),
            ("R=-5", "need 0 <= b < a < R"),
            ("hmin=0", "hmin must be positive"),
            ("order=3", "order must be 1 or 2"),
        ] {
            let message = parse_parameters(bad).unwrap_err().to_string();
            assert!(message.contains(named), "{bad}: {message}");
        }
    }

    #[test]
    fn a_mesh_file_cut_short_is_told_from_a_whole_one() {
        let dir = std::env::temp_dir().join(format!("ringcontact-tail-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let meshes = DataPaths::default().meshes;
        let whole = std::fs::read(meshes.join("annulus-0.5-L0.msh")).unwrap();
        let binary = std::fs::read(meshes.join("small-domain-R5-binary.msh")).unwrap();
        let cases: [(&str, &[u8], bool); 5] = [
            ("whole.msh", &whole, true),
            ("binary.msh", &binary, true),
            ("cut.msh", &whole[..whole.len() / 2], false),
            ("cut-in-last-line.msh", &whole[..whole.len() - 4], false),
            ("empty.msh", b"", false),
        ];
        for (name, bytes, expected) in cases {
            let path = dir.join(name);
            std::fs::write(&path, bytes).unwrap();
            assert_eq!(ends_with_a_section_end(&path), expected, "{name}");
        }
        assert!(!ends_with_a_section_end(&dir.join("missing.msh")));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_rim_size_follows_the_contact_rings_width() {
        // Wide rings keep the rim size of the level; narrower than 0.1 a it shrinks with the ring.
        assert_eq!(ring_width(0.5, None, 0.0), 0.5);
        assert_eq!(ring_width_scale(ring_width(0.5, None, 0.0)), 1.0);
        assert!((ring_width_scale(ring_width(0.999, None, 0.0)) - 0.01).abs() < 1e-12);
        // A concave punch's located edge, the larger of the annulus' and the located one.
        assert!((ring_width(0.0, Some(0.99), 1e-4) - 0.01).abs() < 1e-12);
        // An edge located at the rim bounds the ring by its uncertainty, never by zero.
        assert_eq!(ring_width(0.0, Some(1.0), 3e-4), 3e-4);
        let level0 = wanted_rim_size(0, None, 1.0);
        assert!((wanted_rim_size(0, None, 0.01) - 0.01 * level0).abs() < 1e-18);
        // Never below the floor; a target that would need less is declined, naming a tolerance.
        assert_eq!(wanted_rim_size(3, None, 1e-6), MIN_RIM_SIZE);
        let target = |tolerance| SizeTarget {
            tolerance,
            degree: 3,
        };
        assert!(check_rim_size_reachable(0.01, target(1e-6)).is_ok());
        assert!(check_rim_size_reachable(1e-3, target(1e-7)).is_ok());
        let e = check_rim_size_reachable(1e-3, target(1e-8)).unwrap_err();
        assert!(
            matches!(&e, Error::OutOfRange { reason, .. } if reason.contains("at least 1.000000e-7")),
            "{e}"
        );
    }

    #[test]
    fn the_free_edge_size_follows_the_contact_rings_width() {
        // The floor of the free edge's elements, 0.75 p tol, scales like the rim's with the ring.
        let hb = |free_edge: f64| {
            let target = SizeTarget {
                tolerance: 1e-5,
                degree: 2,
            };
            let p = adapted_parameters(0.0, 3, Some(free_edge), 1e-7, Some(target));
            p.iter().find(|(n, _)| n == "hb").map(|(_, v)| *v).unwrap()
        };
        assert!((hb(0.5) - 1.5e-5).abs() < 1e-18, "{}", hb(0.5));
        let narrow = ring_width_scale(ring_width(0.0, Some(0.9997), 1e-7));
        assert!(
            (hb(0.9997) - 1.5e-5 * narrow).abs() < 1e-15,
            "{}",
            hb(0.9997)
        );
    }

    #[test]
    fn gmsh_is_never_asked_for_elements_it_cannot_shape() {
        // Below 1e-8 of the coordinates' magnitude gmsh makes slivers (GMSH_MIN_ELEMENT_SIZE);
        // smaller rims come from the corner refinement, which must then be requested.
        for level in ADAPTED_MIN_LEVEL..=ADAPTED_MAX_LEVEL {
            for target in [None, Some(1e-3), Some(1e-6), Some(1e-8)] {
                let target = target.map(|tolerance| SizeTarget {
                    tolerance,
                    degree: 3,
                });
                for free_edge in [None, Some(0.5), Some(0.01)] {
                    let p = adapted_parameters(0.0, level, free_edge, 1e-4, target);
                    let get = |name: &str| p.iter().find(|(n, _)| n == name).map(|(_, v)| *v);
                    assert!(get("hmin").unwrap() >= GMSH_MIN_ELEMENT_SIZE, "{p:?}");
                    if let (Some(hb), Some(b)) = (get("hb"), free_edge) {
                        assert!(hb >= GMSH_MIN_ELEMENT_SIZE * b.max(1e-2), "{p:?}");
                    }
                    let wanted = wanted_rim_size(level, target, 1.0);
                    let refinement = adapted_corner_refinement(0.3, level, None, 0.0, target);
                    assert_eq!(refinement.is_some(), wanted < GMSH_MIN_ELEMENT_SIZE);
                    if let Some(r) = refinement {
                        assert_eq!(r.radii, vec![0.3, 1.0]);
                        assert_eq!(r.size, wanted);
                    }
                }
            }
        }
    }
}
