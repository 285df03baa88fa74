//! The pull-off study: the direct simulation at a decreasing sequence of ranges (growing Tabor
//! parameter), extrapolated to the JKR limit, beside the JKR route's value.
//!
//! Units: `a = E* = 1`; the work of adhesion is set by Kendall's depth `d0 = sqrt(2π a Δw/E*)`:
//! `d0 = a` for the flat punches (the solution depends on `ρ/d0` only), `d0 = (d0/h) h` with
//! `h = 1` for the concave ones. Forces are reported as tensile-positive multiples of Kendall's
//! `F0 = sqrt(8π E* Δw a³)`.

use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::cohesive::equilibrium::CohesiveSurface;
use crate::cohesive::law::ExponentialLaw;
use crate::cohesive::path::{follow, Curve, CurvePoint, PathOptions};
use crate::discretisation::far_field::FarField;
use crate::error::{Error, Result};
use crate::fem::solver::{surface_response_on_mesh, FemOptions};
use crate::fem::surface_response::SurfaceResponse;
use crate::heartbeat::Progress;
use crate::mesh::files::DataPaths;
use crate::mesh::provider::{self, MeshRequest, ProvidedMesh};
use crate::mesh::triangulation::Degree;
use crate::methods::RingBem;
use crate::punch::{Contact, PunchKind};
use crate::sparse::Backend;

/// Default ranges `ρ/d0`: Tabor parameter `λ` 9, 18, 36 and 90 (a factor 10).
pub const DEFAULT_RANGES: [f64; 4] = [0.05, 0.025, 0.0125, 0.005];

/// Default ranges without gmsh (no rim band, the committed meshes): Tabor 9 to 36. Smaller
/// ranges there end at a mesh-dependent node hop or find no equilibrium (the linear gap at
/// `d0/h = 10`, Tabor 90, on the committed disk level 2: none at touch after 300 Newton
/// iterations).
const COMMITTED_MESH_RANGES: [f64; 3] = [0.05, 0.025, 0.0125];

/// The default ranges where the study runs: [`DEFAULT_RANGES`] with gmsh (rim bands), else
/// [`COMMITTED_MESH_RANGES`].
pub fn default_ranges(data: &DataPaths) -> Vec<f64> {
    if provider::gmsh_available(data) {
        DEFAULT_RANGES.to_vec()
    } else {
        COMMITTED_MESH_RANGES.to_vec()
    }
}

/// Width of the refined band at the rim, in cohesive-zone lengths `ℓ`: the crack front runs in
/// from the rim before the tension peaks (the flat-faced punch: `3.4 ℓ` at Tabor 9, `7.5 ℓ` at 36,
/// `9-13 ℓ` at 90), and the mesh must resolve the zone all that way.
const RIM_BAND_ZONES: f64 = 20.0;

/// Elements per zone length `ℓ` in the rim band (uniform size `ℓ / 6`); the mesh check uses
/// half as many on the level below [`RIM_BAND_LEVEL`].
const RIM_BAND_ELEMENTS_PER_ZONE: f64 = 6.0;

/// Level of the adapted family under the rim band (the rest of the contact line and the
/// body): the band resolves the zone, so the coarse level 1 suffices (the flat-faced punch at Tabor
/// 90: level 2 under a band gives the same pull-off to 1e-5).
const RIM_BAND_LEVEL: i32 = 1;

/// Largest force step, in `F0`, accepted as the crack front hopping a node inside the rim band
/// (hops there at six elements per zone: 1e-6 to 1e-4 F0).
const RIM_BAND_HOP_FORCE: f64 = 1e-3;

/// Preload of the flat punches, in units of `d0`.
const FLAT_PRELOAD: f64 = 0.5;

/// Preload of the concave punches, in units of `h`: past the depth where the parabolic gap's hole
/// closes without adhesion (`3h`); with adhesion both punches' holes close earlier where `d0/h` is
/// large.
const CONCAVE_PRELOAD: f64 = 3.0;

/// Deepest preload of a concave punch, in units of `h`: where its hole is still open at
/// [`CONCAVE_PRELOAD`] (small `d0/h`: the JKR route closes the linear gap's hole at `d0/h = 0.3`
/// only past `3.8 h`), it is pressed on in steps of `3h` until the hole closes, down to this depth.
const MAX_CONCAVE_PRELOAD: f64 = 24.0;

/// Widest error bar, relative to the extrapolate, that still gives a verdict.
const CONCLUSIVE_BAR: f64 = 0.1;

/// Which branch of a concave punch's contact a study follows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Branch {
    /// Pressed until the hole closes, then pulled: the rim lets go (JKR: from full contact).
    #[default]
    Closed,
    /// Touched (the rim plane at the undeformed surface, the hole open), then pulled: the inner
    /// edge moves outward until the annulus lets go (JKR: the fixed-load pull-off of the annular
    /// contact, the paper's route).
    Annular,
}

impl crate::choice::Choice for Branch {
    const ALL: &'static [Branch] = &[Branch::Closed, Branch::Annular];

    fn name(self) -> &'static str {
        match self {
            Branch::Closed => "closed",
            Branch::Annular => "annular",
        }
    }

    fn description(self) -> &'static str {
        match self {
            Branch::Closed => {
                "Pressed until the hole closes, then pulled: the rim lets go (JKR: from full \
                 contact)"
            }
            Branch::Annular => {
                "Touched (the rim plane at the undeformed surface, the hole open), then pulled: \
                 the inner edge moves outward until the annulus lets go (JKR: the fixed-load \
                 pull-off of the annular contact, the paper's route)"
            }
        }
    }
}

/// Default ranges `ρ/d0` of the annular branch (Tabor 4.5 to 9): its contact line is uniformly
/// refined to [`ANNULAR_ELEMENTS_PER_ZONE`] elements per zone length along the inner edge's
/// whole path, which makes smaller ranges cost `O(ρ⁻⁶)` in the dense condensed model.
pub const ANNULAR_RANGES: [f64; 3] = [0.1, 0.07, 0.05];

/// Preload of the annular branch, in units of `h`: the rim plane at the undeformed surface
/// (adhesion alone pulls the rim into contact; the hole stays open).
pub(crate) const ANNULAR_PRELOAD: f64 = 0.0;

/// Elements per cohesive-zone length `ℓ` along the annular branch's contact line (its
/// uniform size `ℓ / 3`); the mesh check uses half as many.
pub(crate) const ANNULAR_ELEMENTS_PER_ZONE: f64 = 3.0;

/// Largest force step, in `F0`, accepted as the inner edge hopping a node on the annular
/// branch (hops at three elements per zone: 4e-4 F0; the branch's end: 0.25-0.5 F0).
pub(crate) const ANNULAR_HOP_FORCE: f64 = 0.01;

/// What to simulate.
#[derive(Clone, Debug)]
pub struct Case {
    pub punch: PunchKind,
    /// The FEM's sparse Cholesky for the condensation (`verify --linear-solver`).
    pub linear_solver: Backend,
    /// Where the meshes and gmsh are.
    pub data: DataPaths,
    /// `b/a` of the fixed annulus.
    pub eps: f64,
    /// `d0/h` of a concave punch.
    pub d0_over_h: f64,
}

impl Case {
    /// Cohesive-zone length `ℓ = π E* Δw/(4σ0²)` of the law at range `range` (units of `d0`), in
    /// units of `a`: `π² (ρ/d0)²/2`, whatever `d0`.
    pub(crate) fn zone_length(&self, range: f64) -> f64 {
        let d0 = self.d0();
        ExponentialLaw {
            work: d0 * d0 / (2.0 * std::f64::consts::PI),
            range: range * d0,
        }
        .zone_length()
    }

    /// Kendall's depth `d0` in units of `a` (`h = 1` for the concave punches).
    pub fn d0(&self) -> f64 {
        if self.punch.is_concave() {
            self.d0_over_h
        } else {
            1.0
        }
    }

    /// Where the pull stops if the punch is still attached (an error then): `4 d0` out, and for
    /// a concave punch `2h` more (its pull-off from full contact lies at `d = -(c h + d0 ...)`:
    /// `-1.3 h` for the parabolic gap at `d0/h = 0.3`).
    fn pull_to(&self) -> f64 {
        if self.punch.is_concave() {
            -4.0 * self.d0() - 2.0
        } else {
            -4.0 * self.d0()
        }
    }

    /// Preload depth (units of `a`).
    fn preload(&self) -> f64 {
        if self.punch.is_concave() {
            CONCAVE_PRELOAD
        } else {
            FLAT_PRELOAD
        }
    }
}

/// One simulation of the sequence.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SequenceEntry {
    /// Range `ρ/a` of the law.
    pub range_over_a: f64,
    /// `λ = sqrt(a/ℓ)`, `ℓ = π E* Δw/(4 σ0²)` the cohesive zone's length.
    pub tabor: f64,
    /// Most tensile force of the unloading branch, over `F0` (tensile positive).
    pub pulloff_over_f0: f64,
    /// Depth there, over `d0` (negative: pulled out).
    pub pulloff_depth_over_d0: f64,
    /// Whether that maximum is smooth (`dF/dd = 0`) or the end of the branch.
    pub smooth_maximum: bool,
    /// Jumps along the path (the ends of branches; small ones are the crack front passing nodes).
    pub jumps: usize,
    pub points: usize,
    /// Depth the punch was pressed to, over `d0`: the preload, or deeper where a concave
    /// punch's hole was still open there ([`MAX_CONCAVE_PRELOAD`]).
    #[serde(default)]
    pub preload_over_d0: Option<f64>,
    /// Concave punches: the hole was closed (every node within the law's range) at the preload.
    pub hole_closed_at_preload: Option<bool>,
    /// Concave punches: a hole was open at some point of the pull before the pull-off.
    pub hole_open_before_pulloff: Option<bool>,
    /// Where the hole (re)opened on the way out: `(d/d0, F/F0)`, compression positive.
    #[serde(default)]
    pub hole_reopened_at: Option<(f64, f64)>,
    /// The unloading branch ended and the state it jumps to was not found: why.
    #[serde(default)]
    pub unresolved_landing: Option<String>,
    /// Annular branch: where the hole closed between the preload and the pull-off, `(d/d0,
    /// F/F0)`, compression positive (the punch then left the annular branch).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hole_closed_at: Option<(f64, f64)>,
    /// Steps on which the crack front hopped a node and the branch went on
    /// ([`ANNULAR_HOP_FORCE`]; annular branch only).
    #[serde(default)]
    pub node_hops: usize,
    /// Annular branch: the uniform element size along the contact line (units of `a`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line_element_size: Option<f64>,
    /// Closed branch on its own mesh: the refined band at the rim this range ran on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rim_band: Option<RimBand>,
    pub wall_s: f64,
}

/// The band at the rim `[a - width, a]` meshed uniformly for one range, and the mesh.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct RimBand {
    /// Units of `a`: [`RIM_BAND_ZONES`] zone lengths.
    pub width: f64,
    /// Units of `a`: `ℓ /` [`RIM_BAND_ELEMENTS_PER_ZONE`].
    pub element_size: f64,
    pub mesh: String,
    pub mesh_sha256: String,
    pub contact_nodes: usize,
}

/// Points a stored curve is thinned to (about; its jumps are all kept).
const STORED_CURVE_POINTS: usize = 300;

/// One simulation's force-displacement curve, thinned for storage.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StoredCurve {
    pub range_over_a: f64,
    pub tabor: f64,
    /// The simulation left the closed hole's branch ([`ExcludedEntry`]).
    pub left_the_branch: bool,
    /// `(d/d0, F/F0, unloading)`, compression positive.
    pub points: Vec<CurveSample>,
    /// The contact and cohesive-zone radii at each of `points` (absent in older records).
    #[serde(default)]
    pub edges: Vec<CurveEdges>,
}

/// Where the contact and the cohesive zone are at one point of a curve (units of `a`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurveEdges {
    /// Innermost and outermost contact-line node in contact (zero separation), if any.
    pub contact: Option<(f64, f64)>,
    /// Innermost and outermost node of the cohesive zone (separation in `(0, 3ρ]`), if any.
    pub zone: Option<(f64, f64)>,
}

/// `curve` thinned to about `most` points: evenly spaced ones, the turn from loading to
/// unloading, the ends, and both sides of every step whose force changes by more than a hundredth
/// of the curve's force span (the jumps).
pub fn thin(curve: &[CurveSample], most: usize) -> Vec<CurveSample> {
    thinned_indices(curve, most)
        .into_iter()
        .map(|i| curve[i])
        .collect()
}

/// The indices [`thin`] keeps, increasing.
fn thinned_indices(curve: &[CurveSample], most: usize) -> Vec<usize> {
    let n = curve.len();
    if n <= most {
        return (0..n).collect();
    }
    let (lo, hi) = curve
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
    let big = 0.01 * (hi - lo);
    let mut keep = vec![false; n];
    let every = (n / (most / 2).max(1)).max(1);
    for i in 0..n {
        let jump_after = i + 1 < n && (curve[i + 1].1 - curve[i].1).abs() > big;
        let jump_before = i > 0 && (curve[i].1 - curve[i - 1].1).abs() > big;
        let turn = i + 1 < n && curve[i + 1].2 != curve[i].2;
        keep[i] = i % every == 0 || i + 1 == n || jump_after || jump_before || turn;
    }
    (0..n).filter(|&i| keep[i]).collect()
}

/// A simulation left out of the sequence, and why.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ExcludedEntry {
    pub entry: SequenceEntry,
    pub reason: String,
}

/// Smallest range `ρ/d0` a study extends its sequence to when a range is excluded (Tabor 450).
const MIN_RANGE: f64 = 0.001;

/// The study of one punch.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PulloffStudy {
    /// Why the sequence stopped before its last range (the ranges before it are kept), if it
    /// did.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stopped: Option<String>,
    #[serde(flatten)]
    pub punch: PunchKind,
    /// `b/a` of the fixed annulus.
    pub eps: Option<f64>,
    /// `d0/h` of a concave punch.
    pub d0_over_h: Option<f64>,
    /// The branch followed (concave punches; absent in older records: the closed hole's).
    #[serde(default)]
    pub branch: Option<Branch>,
    pub law: String,
    pub preload_over_d0: f64,
    pub mesh: String,
    pub mesh_sha256: String,
    /// The gmsh that made the mesh (generated meshes).
    pub mesh_gmsh_version: Option<String>,
    pub contact_nodes: usize,
    pub unknowns: usize,
    pub sequence: Vec<SequenceEntry>,
    /// Concave punches: simulations left out of the sequence because their hole was open at the
    /// deepest preload or reopened on the way out (another branch; a smaller range replaces
    /// each, down to [`MIN_RANGE`]), with the reason.
    #[serde(default)]
    pub excluded: Vec<ExcludedEntry>,
    /// Force-displacement curves (thinned to about [`STORED_CURVE_POINTS`] points, every
    /// jump kept) of the smallest range in the sequence and of every range left out: what the
    /// report charts.
    #[serde(default)]
    pub curves: Vec<StoredCurve>,
    /// Extrapolate to zero range from the two smallest ranges, linear in the range (the depth
    /// at which the surfaces part is offset by `O(ρ)`; the stored sequences are consistent with
    /// order 1).
    pub extrapolated_over_f0: Option<f64>,
    /// The extrapolation's correction, plus its change from the previous pair of ranges, plus
    /// the mesh difference: how far the limit, the order-1 assumption and the mesh are from
    /// settled.
    pub error_bar: Option<f64>,
    /// The smallest range's pull-off on the check mesh minus this mesh's (absolute, in `F0`).
    pub mesh_difference: Option<f64>,
    /// The JKR route (`verify jkr`): fixed-load pull-off, tensile positive.
    pub jkr_fixed_load_over_f0: Option<f64>,
    /// The JKR route's pull-off from full contact (concave punches).
    pub full_contact_over_f0: Option<f64>,
    /// The paper's route on its fitted formulas, fixed load (concave punches).
    pub paper_route_over_f0: Option<f64>,
    pub note: String,
    pub wall_s: f64,
}

impl PulloffStudy {
    /// The JKR route's value this simulation tends to: from full contact for a concave punch
    /// on the closed hole's branch, else (flat punches, the annular branch) the fixed-load
    /// pull-off.
    pub fn jkr_reference(&self) -> Option<f64> {
        if self.branch == Some(Branch::Annular) {
            self.jkr_fixed_load_over_f0
        } else if self.punch.is_concave() {
            self.full_contact_over_f0
        } else {
            self.jkr_fixed_load_over_f0
        }
    }

    /// Whether the extrapolate meets the JKR route's value within its error bar; `None` (no
    /// verdict) without one, or when the bar is wider than [`CONCLUSIVE_BAR`] of the value.
    pub fn agrees_with_jkr(&self) -> Option<bool> {
        match (
            self.extrapolated_over_f0,
            self.error_bar,
            self.jkr_reference(),
        ) {
            (Some(x), Some(bar), Some(r)) if bar <= CONCLUSIVE_BAR * x.abs() => {
                Some((x - r).abs() <= bar)
            }
            _ => None,
        }
    }
}

/// Level of the adapted family the study runs on where it has no rim band ([`run`] on one
/// mesh, the Tamaas comparison, and without gmsh the committed level closest to it): graded
/// toward the edges (element size `g |r - a|` near the rim); there the pull-off is the first end
/// of the branch, a node hop of the crack front, which moves with the mesh (the flat-faced punch at
/// Tabor 36 on levels 2-5: 0.9768-0.9834; 0.9899 with the rim band).
pub const STUDY_LEVEL: i32 = 3;

/// The mesh the study runs on (`level` of the adapted family, made by gmsh), else, without
/// gmsh, the committed level of the ratio (`b/a` = 0, 0.5, 0.9) closest to it.
pub fn study_mesh(data: &DataPaths, eps: f64, level: i32) -> Result<ProvidedMesh> {
    let adapted = MeshRequest::Adapted {
        contact_start: eps,
        level,
        free_edge: None,
        edge_uncertainty: 0.0,
        target: None,
    };
    match provider::provide(data, &adapted, "the pull-off simulation") {
        Ok(mesh) => Ok(mesh),
        Err(gmsh_error) => match provider::committed_family(data, eps) {
            Some(family) => provider::provide(
                data,
                &MeshRequest::Committed {
                    family,
                    level: (level - 1).clamp(0, provider::COMMITTED_MAX_LEVEL as i32) as usize,
                },
                "pull-off",
            ),
            None => Err(gmsh_error),
        },
    }
}

/// The cases the direct simulation covers: the flat punches, and the concave ones whose hole is
/// closed at the preload (pressed until it closes, down to [`MAX_CONCAVE_PRELOAD`]) and stays
/// closed until the pull-off. A hole still open, or reopened on the way out, puts the punch on
/// the annular branch, whose inner edge moves during the pull and is not resolved along its
/// path: such a simulation is declined with that reason.
fn open_hole_declined(case: &Case, entry: &SequenceEntry) -> Result<()> {
    match branch_left(case, entry) {
        None => Ok(()),
        Some(what) => Err(Error::Unsupported {
            method: "cohesive-fem".into(),
            reason: format!(
                "at d0/h = {} and range rho/d0 = {} {what}: the {} is then on the annular \
                 branch, whose inner edge moves during the pull, and the mesh is not refined \
                 along its path (the direct simulation covers flat punches and closed holes)",
                crate::error::show(case.d0_over_h),
                crate::error::show(entry.range_over_a / case.d0()),
                case.punch
            ),
        }),
    }
}

/// How a concave punch's simulation left the branch of the closed hole, if it did: the hole
/// still open at the deepest preload, reopened on the way out, or an unknown landing.
fn branch_left(case: &Case, entry: &SequenceEntry) -> Option<String> {
    // A fixed annulus has no hole to close: its inner edge letting go is one of its detachments.
    if !case.punch.is_concave() {
        return None;
    }
    let pressed = || crate::error::show(entry.preload_over_d0.unwrap_or(f64::NAN) * case.d0());
    if entry.hole_closed_at_preload == Some(false) {
        Some(format!(
            "the hole is still open at the deepest preload d = {} h",
            pressed()
        ))
    } else if let Some((depth, force)) = entry.hole_reopened_at {
        Some(format!(
            "the hole closed on the way in (pressed to d = {} h) and reopened on the way out at \
             d/d0 = {depth:.4}, F/F0 = {force:.4} (compression positive)",
            pressed()
        ))
    } else {
        entry.unresolved_landing.as_ref().map(|why| {
            format!(
                "the branch ended at d/d0 = {:.4}, F/F0 = {:.4} (compression positive) and the \
                 state it jumps to was not found ({why}): whether the hole reopened or the rim \
                 let go is unknown",
                entry.pulloff_depth_over_d0, -entry.pulloff_over_f0
            )
        })
    }
}

/// Whether `entry` left the preload's branch (hole open at the deepest preload, reopened, or an
/// unknown landing; concave punches): [`run`] then leaves it out and adds a smaller range while
/// fewer than three are usable.
pub fn left_the_branch(case: &Case, entry: &SequenceEntry) -> bool {
    branch_left(case, entry).is_some()
}

/// The study as `verify pulloff` runs it without `--mesh`: [`run_rim_band`] (a mesh per range
/// with a refined band at the rim), else, where gmsh cannot make those, [`run`] on the study
/// meshes (level [`STUDY_LEVEL`], or the committed level closest to it, and the level below as
/// the check mesh).
pub fn run_on_study_meshes(
    case: Case,
    ranges: &[f64],
    mut progress: impl FnMut(&SequenceEntry),
) -> Result<PulloffStudy> {
    if provider::gmsh_available(&case.data) {
        return run_rim_band(case, ranges, progress);
    }
    let mesh = study_mesh(&case.data, case.eps, STUDY_LEVEL)?;
    let check = study_mesh(&case.data, case.eps, STUDY_LEVEL - 1)?;
    let mut study = run(case, ranges, &mesh, Some(&check), &mut progress)?;
    study.note += &format!(
        " (gmsh not found: the committed meshes, no rim band; `{}` installs it for the banded \
         study)",
        crate::mesh::gmsh::INSTALL_COMMAND
    );
    Ok(study)
}

/// The mesh of one range of the closed branch: level `level` of the adapted family with the band
/// `[a - w, a]`, `w` = [`RIM_BAND_ZONES`] zone lengths (at most the contact line), meshed
/// uniformly at `ℓ / elements_per_zone` (gmsh; `ℓ = π² (ρ/d0)²/2 a`).
fn rim_band_mesh(
    case: &Case,
    range: f64,
    elements_per_zone: f64,
    level: i32,
) -> Result<(ProvidedMesh, f64, f64)> {
    let zone = case.zone_length(range);
    let width = (RIM_BAND_ZONES * zone).min(1.0 - case.eps);
    let size = zone / elements_per_zone;
    if size < provider::GMSH_MIN_ELEMENT_SIZE {
        // ℓ = π² ρ²/2 >= per · (the smallest size gmsh meshes well at the rim).
        let smallest = (2.0 * elements_per_zone * provider::GMSH_MIN_ELEMENT_SIZE).sqrt()
            / std::f64::consts::PI;
        return Err(Error::invalid(
            "ranges",
            format!(
                "range rho/d0 = {range}: the rim band would need elements of {size:.1e} a, below \
                 what gmsh meshes well at the rim ({:.0e} a); use ranges rho/d0 >= {:.1e}",
                provider::GMSH_MIN_ELEMENT_SIZE,
                smallest * 1.01
            ),
        ));
    }
    let mut parameters = provider::adapted_parameters(case.eps, level, None, 0.0, None);
    parameters.push(("band".to_string(), width));
    parameters.push(("hband".to_string(), size));
    let mesh = provider::generate(
        &case.data,
        &parameters,
        "the pull-off simulation's rim band",
    )?;
    Ok((mesh, width, size))
}

/// Run the study of `case` at the ranges `ranges` (units of `d0`, decreasing), each on its own
/// [`rim_band_mesh`] ([`RIM_BAND_LEVEL`], [`RIM_BAND_ELEMENTS_PER_ZONE`]), and the smallest
/// range again with half the band's elements on the level below (the mesh's share of the error
/// bar); `progress` is called after each simulation.
pub fn run_rim_band(
    case: Case,
    ranges: &[f64],
    progress: impl FnMut(&SequenceEntry),
) -> Result<PulloffStudy> {
    run_sequence(case, ranges, None, progress)
}

/// Run the study of `case` on `mesh` (a disk mesh for the concave punches) at the ranges
/// `ranges` (units of `d0`, decreasing), and the smallest range again on `check_mesh` (a coarser
/// one) for the mesh's share of the error bar; `progress` is called after each simulation.
/// The pull-off is the first end of the branch (no band: the mesh's own resolution).
pub fn run(
    case: Case,
    ranges: &[f64],
    mesh: &ProvidedMesh,
    check_mesh: Option<&ProvidedMesh>,
    progress: impl FnMut(&SequenceEntry),
) -> Result<PulloffStudy> {
    run_sequence(case, ranges, Some((mesh, check_mesh)), progress)
}

/// The range a study adds once the given `ranges` (decreasing) are done, if any: where some
/// were left out (another branch), half the smallest simulated so far (`smallest`), while
/// fewer than three are usable (`usable`, decreasing) or their Tabor span falls short of the
/// given ranges' (at most 10), and not below [`MIN_RANGE`].
pub fn smaller_range(
    ranges: &[f64],
    smallest: f64,
    usable: &[f64],
    any_excluded: bool,
) -> Option<f64> {
    let span = |r: &[f64]| match (r.first(), r.last()) {
        (Some(first), Some(last)) => first / last,
        _ => 1.0,
    };
    let wanted_span = span(ranges).min(10.0);
    let smaller = 0.5 * smallest;
    let short = usable.len() < 3 || span(usable) < 0.99 * wanted_span;
    (any_excluded && short && smaller >= MIN_RANGE).then_some(smaller)
}

/// What one range ran on: the condensed model's provenance.
struct ModelInfo {
    mesh: String,
    sha256: String,
    gmsh_version: Option<String>,
    contact_nodes: usize,
    unknowns: usize,
}

impl ModelInfo {
    fn of(mesh: &ProvidedMesh, name: String, response: &SurfaceResponse) -> Result<Self> {
        Ok(ModelInfo {
            mesh: name,
            sha256: mesh.sha256()?,
            gmsh_version: mesh.gmsh_version.clone(),
            contact_nodes: response.radii.len(),
            unknowns: response.unknowns,
        })
    }
}

/// One closed-branch simulation of `case` at `range` on its own [`rim_band_mesh`] (`per`
/// elements per zone on `level`), the entry naming its band and mesh.
fn simulate_in_rim_band(
    case: &Case,
    range: f64,
    per: f64,
    level: i32,
) -> Result<(SequenceEntry, Vec<CurveSample>, Vec<CurveEdges>, ModelInfo)> {
    let (mesh, width, size) = rim_band_mesh(case, range, per, level)?;
    let (response, name) = surface_response_on_mesh(
        &mesh,
        &study_options(case.linear_solver, &case.data),
        case.eps,
    )?;
    let (mut entry, curve, edges) =
        simulate(&response, case, range, Branch::Closed, Some(1.0 - width))?;
    let info = ModelInfo::of(&mesh, name, &response)?;
    entry.rim_band = Some(RimBand {
        width,
        element_size: size,
        mesh: info.mesh.clone(),
        mesh_sha256: info.sha256.clone(),
        contact_nodes: response.radii.len(),
    });
    Ok((entry, curve, edges, info))
}

/// One range on its model: the shared one, or its own rim band (`per` elements per zone on
/// `level`); the model is returned only for a rim band.
type RangeSimulation = (
    SequenceEntry,
    Vec<CurveSample>,
    Vec<CurveEdges>,
    Option<ModelInfo>,
);

/// Simulate one range on the shared model, or on a rim-band mesh of its own.
fn simulate_range(
    shared: Option<&crate::fem::surface_response::SurfaceResponse>,
    case: &Case,
    range: f64,
    per: f64,
    level: i32,
) -> Result<RangeSimulation> {
    match shared {
        Some(response) => {
            let (entry, curve, edges) = simulate(response, case, range, Branch::Closed, None)?;
            Ok((entry, curve, edges, None))
        }
        None => {
            let (entry, curve, edges, model) = simulate_in_rim_band(case, range, per, level)?;
            Ok((entry, curve, edges, Some(model)))
        }
    }
}

/// The ranges a study simulated: those on the preload's branch, those left out with why,
/// the stored curves, the model of the smallest range kept (rim bands) and why the sequence
/// stopped early (a range that failed after others succeeded).
struct RangeSequence {
    sequence: Vec<SequenceEntry>,
    excluded: Vec<ExcludedEntry>,
    curves: Vec<StoredCurve>,
    smallest_model: Option<ModelInfo>,
    stopped: Option<String>,
}

/// Simulate `ranges`, then smaller ones while a range left the branch or the sequence is short
/// ([`smaller_range`]), calling `progress` after each.
fn simulate_ranges(
    case: &Case,
    ranges: &[f64],
    shared: Option<&crate::fem::surface_response::SurfaceResponse>,
    progress: &mut impl FnMut(&SequenceEntry),
) -> Result<RangeSequence> {
    let case = case.clone();
    let mut sequence = Vec::new();
    let mut excluded = Vec::new();
    let mut curves = Vec::new();
    let mut smallest_model = None;
    let mut queue: Vec<f64> = ranges.to_vec();
    let mut next = 0;
    let mut stopped = None;
    loop {
        if next == queue.len() {
            let usable: Vec<f64> = sequence
                .iter()
                .map(|e: &SequenceEntry| e.range_over_a / case.d0())
                .collect();
            match smaller_range(
                ranges,
                queue[queue.len() - 1],
                &usable,
                !excluded.is_empty(),
            ) {
                Some(smaller) => queue.push(smaller),
                None => break,
            }
        }
        let range = queue[next];
        next += 1;
        // A range that fails after others succeeded ends the sequence there; they are kept.
        let (entry, curve, edges, model) = match simulate_range(
            shared,
            &case,
            range,
            RIM_BAND_ELEMENTS_PER_ZONE,
            RIM_BAND_LEVEL,
        ) {
            Ok(simulated) => simulated,
            Err(e) if !sequence.is_empty() => {
                stopped = Some(format!("the range rho/d0 = {range} failed: {e}"));
                break;
            }
            Err(e) => return Err(e),
        };
        progress(&entry);
        let left = branch_left(&case, &entry);
        if left.is_none() && model.is_some() {
            smallest_model = model;
        }
        file_simulation(
            (&mut sequence, &mut excluded, &mut curves),
            entry,
            (&curve, &edges),
            left,
        );
    }
    Ok(RangeSequence {
        sequence,
        excluded,
        curves,
        smallest_model,
        stopped,
    })
}

/// The case with `eps` zero unless the punch is a fixed annulus, checked: `d0/h` of a concave
/// punch, `0 < b/a < 1` of a fixed annulus, the ranges.
fn checked_case(case: Case, ranges: &[f64]) -> Result<Case> {
    let eps = if case.punch.has_fixed_hole() {
        case.eps
    } else {
        0.0
    };
    if case.punch.is_concave() {
        check_d0_over_h(&case)?;
    }
    if case.punch.has_fixed_hole() && !(eps > 0.0 && eps < 1.0) {
        return Err(Error::invalid(
            "eps",
            format!(
                "the {} needs 0 < b/a < 1 (got {eps}; b/a = 0 is the {})",
                case.punch,
                crate::punch::PunchName::names(Some(crate::punch::Contact::Disk), ", ")
            ),
        ));
    }
    check_ranges(ranges)?;
    Ok(Case { eps, ..case })
}

/// What a study's pull-off means on its meshes: one mesh for every range (`fixed_mesh`), or a
/// rim band per range.
fn study_note(fixed_mesh: bool) -> String {
    if fixed_mesh {
        "pull-off: the most tensile force of the branch the preload is on, which ends where \
         the crack front first runs (a jump under fixed grips); past it the discrete front \
         is pinned node by node (lattice trapping) and the path is not followed"
            .into()
    } else {
        format!(
            "pull-off: the most tensile force of the branch the preload is on while its crack \
             front lies in the rim band (each range on its own mesh: the band [a - w, a], w = \
             {RIM_BAND_ZONES} zone lengths, meshed at 1/{RIM_BAND_ELEMENTS_PER_ZONE} of the \
             zone on level {RIM_BAND_LEVEL} of the adapted family; rim_band in each entry); \
             node hops of the front there (force steps under {RIM_BAND_HOP_FORCE} F0) \
             continue the branch; the check: the smallest range with half the band's \
             elements on level {}; mesh and contact_nodes: the smallest range's",
            RIM_BAND_LEVEL - 1
        )
    }
}

/// The study's loop: `fixed` = one mesh (and a check mesh) for every range, `None` = a rim-band
/// mesh per range.
fn run_sequence(
    case: Case,
    ranges: &[f64],
    fixed: Option<(&ProvidedMesh, Option<&ProvidedMesh>)>,
    mut progress: impl FnMut(&SequenceEntry),
) -> Result<PulloffStudy> {
    let start = Instant::now();
    let case = checked_case(case, ranges)?;
    let (punch, eps) = (case.punch.clone(), case.eps);
    let options = study_options(case.linear_solver, &case.data);
    let shared = match fixed {
        Some((mesh, _)) => {
            let (response, name) = surface_response_on_mesh(mesh, &options, eps)?;
            Some((ModelInfo::of(mesh, name, &response)?, response))
        }
        None => None,
    };
    let shared_response = shared.as_ref().map(|(_, response)| response);
    let RangeSequence {
        sequence,
        excluded,
        curves,
        smallest_model,
        stopped,
    } = simulate_ranges(&case, ranges, shared_response, &mut progress)?;
    if sequence.is_empty() {
        let reasons: Vec<&str> = excluded.iter().map(|e| e.reason.as_str()).collect();
        return Err(Error::Unsupported {
            method: "cohesive-fem".into(),
            reason: format!("no range gave a closed hole: {}", reasons.join("; ")),
        });
    }
    let smallest = sequence[sequence.len() - 1].range_over_a / case.d0();
    let check = match fixed {
        Some((_, Some(coarser))) => {
            let (response, _) = surface_response_on_mesh(coarser, &options, eps)?;
            Some(simulate(&response, &case, smallest, Branch::Closed, None)?.0)
        }
        Some((_, None)) => None,
        None => Some(
            simulate_range(
                shared_response,
                &case,
                smallest,
                0.5 * RIM_BAND_ELEMENTS_PER_ZONE,
                RIM_BAND_LEVEL - 1,
            )?
            .0,
        ),
    };
    let mesh_difference = match check {
        Some(entry) => {
            progress(&entry);
            open_hole_declined(&case, &entry)?;
            Some((entry.pulloff_over_f0 - sequence[sequence.len() - 1].pulloff_over_f0).abs())
        }
        None => None,
    };
    let (extrapolated, error_bar) = extrapolate(&sequence, mesh_difference.unwrap_or(0.0));
    let (jkr, full_contact, paper) = jkr_values(&case)?;
    let model = match shared {
        Some((model, _)) => model,
        None => smallest_model.expect("a rim-band model for every range in the sequence"),
    };
    Ok(PulloffStudy {
        stopped,
        punch: punch.clone(),
        eps: punch.has_fixed_hole().then_some(eps),
        d0_over_h: punch.is_concave().then_some(case.d0_over_h),
        branch: punch.is_concave().then_some(Branch::Closed),
        law: "exponential: tension (dw/rho) exp(-s/rho), dw = d0^2 E*/(2 pi a) (d0 = a for the \
              flat punches, h = 1 for the concave ones); non-penetration; nodal quadrature on \
              the FE contact line (P2)"
            .into(),
        preload_over_d0: case.preload() / case.d0(),
        mesh: model.mesh,
        mesh_sha256: model.sha256,
        mesh_gmsh_version: model.gmsh_version,
        contact_nodes: model.contact_nodes,
        unknowns: model.unknowns,
        sequence,
        excluded,
        curves,
        extrapolated_over_f0: extrapolated,
        error_bar,
        mesh_difference,
        jkr_fixed_load_over_f0: jkr,
        full_contact_over_f0: full_contact,
        paper_route_over_f0: paper,
        note: study_note(fixed.is_some()),
        wall_s: start.elapsed().as_secs_f64(),
    })
}

/// A concave punch's `d0/h` must be finite and positive.
pub(super) fn check_d0_over_h(case: &Case) -> Result<()> {
    if case.d0_over_h.is_finite() && case.d0_over_h > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            "d0_over_h",
            format!("need d0/h > 0 (got {})", case.d0_over_h),
        ))
    }
}

/// At least one range, each `ρ/d0` in `(0, 1)`.
pub(super) fn check_ranges(ranges: &[f64]) -> Result<()> {
    if ranges.is_empty()
        || ranges
            .iter()
            .any(|r| !(r.is_finite() && *r > 0.0 && *r < 1.0))
    {
        return Err(Error::invalid(
            "ranges",
            format!("need ranges rho/d0 in (0, 1) (got {ranges:?})"),
        ));
    }
    Ok(())
}

/// File one simulation: into the sequence (its curve kept as the smallest range's, replacing the
/// previous one) or, where `left` names how it left the branch, among the excluded (its curve
/// kept too).
pub(super) fn file_simulation(
    (sequence, excluded, curves): (
        &mut Vec<SequenceEntry>,
        &mut Vec<ExcludedEntry>,
        &mut Vec<StoredCurve>,
    ),
    entry: SequenceEntry,
    (curve, edges): (&[CurveSample], &[CurveEdges]),
    left: Option<String>,
) {
    let kept = thinned_indices(curve, STORED_CURVE_POINTS);
    let stored = StoredCurve {
        range_over_a: entry.range_over_a,
        tabor: entry.tabor,
        left_the_branch: left.is_some(),
        points: kept.iter().map(|&i| curve[i]).collect(),
        edges: kept.iter().filter_map(|&i| edges.get(i).copied()).collect(),
    };
    match left {
        None => {
            sequence.push(entry);
            // Only the smallest range's curve of the sequence is kept.
            curves.retain(|c| c.left_the_branch);
        }
        Some(reason) => excluded.push(ExcludedEntry { reason, entry }),
    }
    curves.push(stored);
}

/// The JKR route's values for `case` (`verify jkr`), tensile positive: the fixed-load pull-off
/// (flat punches; the annular contact of a concave one, if it has a stable one), the pull-off
/// from full contact and the paper's route on its fitted formulas (concave punches).
pub(super) fn jkr_values(case: &Case) -> Result<(Option<f64>, Option<f64>, Option<f64>)> {
    let ring = RingBem::new();
    Ok(match case.punch.contact() {
        Contact::Disk => (Some(1.0), None, None),
        Contact::FixedAnnulus => {
            let r = crate::adhesion::fixed_annulus(&ring, case.eps)?;
            // The edge that lets go first (smaller |d_c|) sets the pull-off.
            let edge = if r.governing_edge == "outer" {
                r.fc_outer
            } else {
                r.fc_inner
            };
            (Some(-edge), None, None)
        }
        Contact::RimAndFreeInner | Contact::FreeBand => {
            let r = crate::adhesion::concave(&ring, case.punch.clone(), case.d0_over_h)?;
            (
                r.fixed_load.map(|c| -c.force),
                Some(-r.full_contact.pulloff.force),
                r.paper_fits_fixed_load.map(|(_, f)| -f),
            )
        }
    })
}

/// The FE model the study condenses: P2, `ν = 0`, Boussinesq's far field.
pub fn study_options(linear_solver: Backend, data: &DataPaths) -> FemOptions {
    FemOptions {
        linear_solver,
        trace: false,
        degree: Degree::Quadratic,
        tolerance: 1e-3,
        mesh: None,
        poisson_ratio: 0.0,
        far_field: FarField::Boussinesq,
        data: data.clone(),
        progress: Progress::Silent,
    }
}

/// One simulation of `case` at range `range` (units of `d0`) on `mesh`, condensation included
/// (the report's live check: a concave case must keep its hole closed, else it is declined).
pub fn simulate_once(case: Case, range: f64, mesh: &ProvidedMesh) -> Result<LiveSimulation> {
    let start = Instant::now();
    let options = study_options(case.linear_solver, &case.data);
    let (response, mesh_name) = surface_response_on_mesh(mesh, &options, case.eps)?;
    let (entry, curve, _) = simulate(&response, &case, range, Branch::Closed, None)?;
    LiveSimulation::unless_declined(
        &case,
        (entry, curve),
        (mesh_name, response.radii.len()),
        start.elapsed().as_secs_f64(),
    )
}

/// One closed-branch simulation of `case` at range `range` (units of `d0`) as the study makes
/// it: on its own [`rim_band_mesh`] where gmsh is available, else [`simulate_once`] on the
/// study mesh (the committed level closest to it without gmsh). A concave case whose hole opens
/// is declined.
pub fn simulate_as_studied(case: Case, range: f64) -> Result<LiveSimulation> {
    if !provider::gmsh_available(&case.data) {
        let mesh = study_mesh(&case.data, case.eps, STUDY_LEVEL)?;
        return simulate_once(case.clone(), range, &mesh);
    }
    let start = Instant::now();
    let (entry, curve, _, model) =
        simulate_in_rim_band(&case, range, RIM_BAND_ELEMENTS_PER_ZONE, RIM_BAND_LEVEL)?;
    LiveSimulation::unless_declined(
        &case,
        (entry, curve),
        (model.mesh, model.contact_nodes),
        start.elapsed().as_secs_f64(),
    )
}

/// One simulation of each of `cases` (contact line from `b/a = 0`: flat and concave punches) at
/// range `range` (units of `d0`) on `mesh`, the mesh condensed once for all; each as
/// [`simulate_once`] (a concave case whose hole opens is declined). The cases run in parallel;
/// each one's wall time is its own (3-5 % longer than alone, the cores being shared).
pub fn simulate_cases(
    cases: &[Case],
    range: f64,
    mesh: &ProvidedMesh,
) -> Result<Vec<LiveSimulation>> {
    // The cases share one condensation, on the first one's backend.
    let Some(first) = cases.first() else {
        return Ok(Vec::new());
    };
    let options = study_options(first.linear_solver, &first.data);
    let start = Instant::now();
    let (response, mesh_name) = surface_response_on_mesh(mesh, &options, 0.0)?;
    let condensation_s = start.elapsed().as_secs_f64();
    cases
        .par_iter()
        .map(|case| {
            if case.punch.has_fixed_hole() {
                return Err(Error::Unsupported {
                    method: "cohesive-fem".into(),
                    reason: format!(
                        "simulate_cases covers contact lines from the axis; the {} needs its own \
                         mesh",
                        case.punch
                    ),
                });
            }
            let (entry, curve, _) = simulate(&response, case, range, Branch::Closed, None)?;
            let wall_s = entry.wall_s + condensation_s / cases.len() as f64;
            LiveSimulation::unless_declined(
                case,
                (entry, curve),
                (mesh_name.clone(), response.radii.len()),
                wall_s,
            )
        })
        .collect()
}

/// One point of a force-displacement curve: `(d/d0, F/F0, unloading)`.
type CurveSample = (f64, f64, bool);

/// A single simulation run by the report (the stored studies are too slow for the default run).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct LiveSimulation {
    #[serde(flatten)]
    pub punch: PunchKind,
    pub d0_over_h: Option<f64>,
    pub mesh: String,
    pub contact_nodes: usize,
    pub entry: SequenceEntry,
    /// The force-displacement curve: `(d/d0, F/F0, unloading)`, compression positive.
    pub curve: Vec<CurveSample>,
    /// Condensation and simulation.
    pub wall_s: f64,
}

impl LiveSimulation {
    /// The simulation of `case` that gave `entry` and `curve` on `(mesh, contact_nodes)`, or the
    /// error saying why it is declined (a concave punch whose hole opened).
    fn unless_declined(
        case: &Case,
        (entry, curve): (SequenceEntry, Vec<CurveSample>),
        (mesh, contact_nodes): (String, usize),
        wall_s: f64,
    ) -> Result<Self> {
        open_hole_declined(case, &entry)?;
        Ok(LiveSimulation {
            punch: case.punch.clone(),
            d0_over_h: case.punch.is_concave().then_some(case.d0_over_h),
            mesh,
            contact_nodes,
            entry,
            curve,
            wall_s,
        })
    }
}

/// One loading-unloading simulation of `case` at range `range` (units of `d0`).
///
/// `band`: the radius from which outward the mesh resolves the zone (a rim band,
/// [`rim_band_mesh`]): node hops of the crack front there continue the branch, and the pull-off
/// is the branch's most tensile state there (an error if that is the band's inner edge).
pub(crate) fn simulate(
    response: &crate::fem::surface_response::SurfaceResponse,
    case: &Case,
    range: f64,
    branch: Branch,
    band: Option<f64>,
) -> Result<(SequenceEntry, Vec<CurveSample>, Vec<CurveEdges>)> {
    let begun = Instant::now();
    let d0 = case.d0();
    let work = d0 * d0 / (2.0 * std::f64::consts::PI);
    let law = ExponentialLaw {
        work,
        range: range * d0,
    };
    let recess: Vec<f64> = response
        .radii
        .iter()
        .map(|&r| case.punch.gap_shape(r))
        .collect();
    let surface = CohesiveSurface::new(response, recess, law)?;
    let curve = follow(&surface, path_options(case, branch, band))?;
    if curve.pulloff.at_band_edge {
        return Err(Error::NoConvergence {
            method: "cohesive-fem".into(),
            reason: format!(
                "range rho/d0 = {}: the tension still rises where the crack front leaves the \
                 refined band at the rim (r >= {} a, {RIM_BAND_ZONES} zone lengths): the \
                 pull-off is not resolved there (a larger range, or --mesh with a finer \
                 contact line)",
                crate::error::show(range),
                crate::error::show(band.unwrap_or(f64::NAN))
            ),
        });
    }
    let units = CurveUnits {
        d0,
        f0: (8.0 * std::f64::consts::PI * work).sqrt(),
    };
    let mut entry = units.entry(&curve, case, branch == Branch::Annular);
    entry.range_over_a = range * d0;
    entry.tabor = law.tabor();
    entry.wall_s = begun.elapsed().as_secs_f64();
    // The curve in units of d0 and F0: (depth, force, unloading).
    let points = curve
        .points
        .iter()
        .map(|p| (p.depth / units.d0, p.force / units.f0, p.unloading))
        .collect();
    let edges = curve
        .points
        .iter()
        .map(|p| CurveEdges {
            contact: p.contact,
            zone: p.zone,
        })
        .collect();
    Ok((entry, points, edges))
}

/// The load path of one simulation: steps of 0.02 d0 on the way out (0.02 h where d0 > h), of
/// 0.02 h on the way in to a concave punch's preload (its hole closes over several h, node by
/// node, whatever the step); the annular branch's preload and hops, or a rim band's hops.
fn path_options(case: &Case, branch: Branch, band: Option<f64>) -> PathOptions {
    let d0 = case.d0();
    let step = 0.02 * d0.min(1.0);
    let annular = branch == Branch::Annular;
    PathOptions {
        preload: if annular {
            ANNULAR_PRELOAD
        } else {
            case.preload()
        },
        pull_to: case.pull_to(),
        max_step: step,
        max_press_step: if case.punch.is_concave() { 0.02 } else { step },
        min_step: 1e-7 * d0,
        press_until_closed: (case.punch.is_concave() && !annular).then_some(MAX_CONCAVE_PRELOAD),
        hop_force: if annular {
            ANNULAR_HOP_FORCE
        } else if band.is_some() {
            RIM_BAND_HOP_FORCE
        } else {
            0.0
        },
        hop_band: if annular { None } else { band },
    }
}

/// The units a simulation reports in: `d0` and Kendall's `F0 = sqrt(8 π Δw)` (`a = E* = 1`).
struct CurveUnits {
    d0: f64,
    f0: f64,
}

impl CurveUnits {
    /// The sequence entry of a followed curve: its pull-off and what the hole did before it
    /// (the range, the Tabor parameter and the wall time are the caller's).
    fn entry(&self, curve: &Curve, case: &Case, annular: bool) -> SequenceEntry {
        let (d0, f0) = (self.d0, self.f0);
        let concave = case.punch.is_concave();
        let preload = curve.points.iter().rposition(|p| !p.unloading).unwrap_or(0);
        let closed_at_preload = !curve.points[preload].centre_open;
        let reopened = reopened_before_pulloff(curve, preload);
        // The annular branch: the hole closed (some node in contact, the centre not open)
        // before the pull-off.
        let closed = annular
            .then(|| {
                curve
                    .points
                    .iter()
                    .take_while(|p| !p.unloading || p.depth >= curve.pulloff.depth)
                    .find(|p| p.contact.is_some() && !p.centre_open)
            })
            .flatten();
        SequenceEntry {
            range_over_a: 0.0,
            tabor: 0.0,
            pulloff_over_f0: -curve.pulloff.force / f0,
            pulloff_depth_over_d0: curve.pulloff.depth / d0,
            smooth_maximum: curve.pulloff.smooth,
            jumps: curve.jumps.len(),
            points: curve.points.len(),
            preload_over_d0: Some(curve.points[preload].depth / d0),
            hole_closed_at_preload: concave.then_some(closed_at_preload),
            hole_open_before_pulloff: concave.then_some(reopened.is_some()),
            hole_reopened_at: reopened
                .filter(|_| concave)
                .map(|p| (p.depth / d0, p.force / f0)),
            unresolved_landing: curve.unresolved_landing.clone(),
            hole_closed_at: closed.map(|p| (p.depth / d0, p.force / f0)),
            node_hops: curve.hops,
            line_element_size: None,
            rim_band: None,
            wall_s: 0.0,
        }
    }
}

/// The first state after the preload whose centre is open before the pull-off, or the state the
/// jump that ends the branch lands on if its centre is open while the punch stays on (then that
/// jump is the hole's, not the pull-off).
fn reopened_before_pulloff(curve: &Curve, preload: usize) -> Option<&CurvePoint> {
    let branch = curve.points[preload].branch;
    let landing = curve
        .points
        .iter()
        .skip(preload)
        .find(|p| p.branch > branch);
    curve
        .points
        .iter()
        .skip(preload)
        .take_while(|p| p.depth >= curve.pulloff.depth)
        .find(|p| p.centre_open)
        .or(landing.filter(|p| p.centre_open))
}

/// Linear extrapolation in the range to zero from the two smallest ranges,
/// `F∞ = F1 + (F1 - F2) ρ1/(ρ2 - ρ1)`. Its error bar adds the correction itself (the sequences
/// approach their limits no faster than linearly, so what remains may be as large), its change
/// from the previous pair, and `mesh_difference`. Needs three ranges.
pub(super) fn extrapolate(
    sequence: &[SequenceEntry],
    mesh_difference: f64,
) -> (Option<f64>, Option<f64>) {
    let n = sequence.len();
    if n < 3 {
        return (None, None);
    }
    let linear = |fine: &SequenceEntry, coarse: &SequenceEntry| {
        fine.pulloff_over_f0
            + (fine.pulloff_over_f0 - coarse.pulloff_over_f0) * fine.range_over_a
                / (coarse.range_over_a - fine.range_over_a)
    };
    let last = linear(&sequence[n - 1], &sequence[n - 2]);
    let previous = linear(&sequence[n - 2], &sequence[n - 3]);
    let correction = (last - sequence[n - 1].pulloff_over_f0).abs();
    (
        Some(last),
        Some(correction + (last - previous).abs() + mesh_difference),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sequence_that_lost_ranges_is_extended_to_three_over_the_given_span() {
        let given = DEFAULT_RANGES;
        // Nothing left out: the given ranges are the sequence, whatever their span.
        assert_eq!(
            smaller_range(&given, 0.005, &[0.025, 0.0125, 0.005], false),
            None
        );
        // Tabor 9 left out: three usable spanning 5 of the wanted 10, so half the smallest.
        assert_eq!(
            smaller_range(&given, 0.005, &[0.025, 0.0125, 0.005], true),
            Some(0.0025)
        );
        // Then the span is 10: done.
        let usable = [0.025, 0.0125, 0.005, 0.0025];
        assert_eq!(smaller_range(&given, 0.0025, &usable, true), None);
        // Fewer than three usable: on, from the smallest simulated (a left-out one too).
        assert_eq!(smaller_range(&given, 0.0025, &[0.005], true), Some(0.00125));
        // Never below MIN_RANGE.
        assert_eq!(smaller_range(&given, 1.5 * MIN_RANGE, &[0.005], true), None);
        // Given ranges spanning 4 (the user's): three usable spanning 4 are enough.
        let given = [0.1, 0.05, 0.025];
        assert_eq!(
            smaller_range(&given, 0.0125, &[0.05, 0.025, 0.0125], true),
            None
        );
    }

    #[test]
    fn thinning_keeps_the_ends_the_turn_and_both_sides_of_every_jump() {
        // A saw: 2000 points of a slow ramp with a drop of 1 every 400 points, pressing for the
        // first half, pulling for the second.
        let curve: Vec<CurveSample> = (0..2000)
            .map(|i| {
                let f = i as f64 * 1e-3 - (i / 400) as f64;
                (i as f64, f, i >= 1000)
            })
            .collect();
        let thinned = thin(&curve, 100);
        assert!(thinned.len() <= 140, "{} points", thinned.len());
        assert_eq!(thinned.first(), curve.first());
        assert_eq!(thinned.last(), curve.last());
        for jump in [400, 800, 1200, 1600] {
            assert!(thinned.contains(&curve[jump - 1]) && thinned.contains(&curve[jump]));
        }
        assert!(thinned.contains(&curve[999]) && thinned.contains(&curve[1000]));
        // Short curves are kept whole.
        assert_eq!(thin(&curve[..50], 100).len(), 50);
    }
}
