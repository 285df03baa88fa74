//! The annular branch of a concave punch by direct simulation: touched with the hole open, then
//! pulled, the inner edge of the contact moving outward until the annulus lets go. Its JKR limit
//! is the fixed-load pull-off of the annular contact (`verify jkr`, the paper's route), the value
//! the closed hole's study ([`crate::cohesive::study::run`]) does not reach.
//!
//! The inner edge travels a large part of the contact line (the linear gap at `d0/h = 1`: from
//! `b/a = 0.33` at first touch to `0.78` at pull-off), so the line is meshed uniformly, with
//! elements of a third of the cohesive zone `ℓ = π E* Δw/(4σ0²)` (`ℓ = π² (ρ/d0)²/2 a` for this
//! study's units), one mesh per range. There the front still advances node by node (lattice
//! trapping), but each hop changes the force by about `4e-4 F0`: steps whose Hessian needed a
//! shift and whose force changed by less than [`ANNULAR_HOP_FORCE`] continue the branch
//! (counted as `node_hops`), and the branch ends where the force jumps by more.

use std::time::Instant;

use crate::cohesive::study::{
    check_d0_over_h, check_ranges, extrapolate, file_simulation, jkr_values, simulate, Branch,
    Case, CurveEdges, ExcludedEntry, PulloffStudy, SequenceEntry, StoredCurve,
    ANNULAR_ELEMENTS_PER_ZONE, ANNULAR_HOP_FORCE, ANNULAR_PRELOAD, STUDY_LEVEL,
};
use crate::error::{Error, Result};
use crate::fem::solver::surface_response_on_mesh;
use crate::fem::surface_response::SurfaceResponse;
use crate::mesh::provider::{self, ProvidedMesh};

/// Most contact-line elements an annular mesh may ask for (the condensed model is dense: 1000
/// elements are about 2000 nodes, a few seconds per Newton step).
const MAX_LINE_ELEMENTS: f64 = 600.0;

/// Smallest range `ρ/d0` whose uniform contact line at `ℓ / elements_per_zone` stays within
/// [`MAX_LINE_ELEMENTS`]: `ℓ = π² (ρ/d0)²/2 >= elements_per_zone / MAX_LINE_ELEMENTS`.
fn smallest_range(elements_per_zone: f64) -> f64 {
    (2.0 * elements_per_zone / (MAX_LINE_ELEMENTS * std::f64::consts::PI.powi(2))).sqrt()
}

/// The mesh of the annular branch at `range`: level [`STUDY_LEVEL`] of the adapted family with
/// a uniform contact line of `ℓ / elements_per_zone` (gmsh; there is no committed fallback).
fn annular_mesh(case: &Case, range: f64, elements_per_zone: f64) -> Result<(ProvidedMesh, f64)> {
    let size = case.zone_length(range) / elements_per_zone;
    if 1.0 / size > MAX_LINE_ELEMENTS {
        return Err(Error::invalid(
            "ranges",
            format!(
                "range rho/d0 = {range}: the annular branch's contact line would need {:.0} \
                 elements of {size:.1e} a (1/{elements_per_zone} of the zone), more than \
                 {MAX_LINE_ELEMENTS:.0}; use ranges rho/d0 >= {:.3}",
                1.0 / size,
                smallest_range(elements_per_zone)
            ),
        ));
    }
    let mut parameters = provider::adapted_parameters(0.0, STUDY_LEVEL, None, 0.0, None);
    for (name, value) in parameters.iter_mut() {
        if name == "hline" {
            *value = size;
        }
    }
    let mesh = provider::generate(
        &case.data,
        &parameters,
        "the annular branch's pull-off simulation",
    )?;
    Ok((mesh, size))
}

/// How an annular simulation left the annular branch, if it did.
fn left_the_annular_branch(case: &Case, entry: &SequenceEntry) -> Option<String> {
    if let Some((depth, force)) = entry.hole_closed_at {
        Some(format!(
            "the hole closed at d/d0 = {depth:.4}, F/F0 = {force:.4} (compression positive) \
             before any pull-off: at d0/h = {} the {} has no stable annular contact there",
            crate::error::show(case.d0_over_h),
            case.punch
        ))
    } else {
        entry.unresolved_landing.as_ref().map(|why| {
            format!(
                "the branch ended at d/d0 = {:.4}, F/F0 = {:.4} and the state it jumps to was \
                 not found ({why})",
                entry.pulloff_depth_over_d0, -entry.pulloff_over_f0
            )
        })
    }
}

/// Run the annular branch's study of `case` (a concave punch) at `ranges` (units of `d0`,
/// decreasing): touch (`d = `[`ANNULAR_PRELOAD`]), pull, the most tensile force of the branch
/// at each range, the smallest range again with half the elements per zone (the mesh's share of
/// the error bar), extrapolated linearly to zero range beside the JKR route's fixed-load
/// pull-off. Where the hole closes before the pull-off (no stable annular contact, as the JKR
/// route says for `d0/h` >= 3) the range is left out with that reason; if every range is, the
/// study is declined.
pub fn run_annular(
    case: Case,
    ranges: &[f64],
    mut progress: impl FnMut(&SequenceEntry),
) -> Result<PulloffStudy> {
    let start = Instant::now();
    if !case.punch.is_concave() {
        return Err(Error::invalid(
            "branch",
            format!(
                "the annular branch is a concave punch's ({}); the {} has none",
                crate::punch::PunchName::names(Some(crate::punch::Contact::RimAndFreeInner), ", "),
                case.punch
            ),
        ));
    }
    check_d0_over_h(&case)?;
    check_ranges(ranges)?;
    // Every mesh is asked for first: a range too small is refused before any simulation runs.
    let meshes = ranges
        .iter()
        .map(|&r| annular_mesh(&case, r, ANNULAR_ELEMENTS_PER_ZONE))
        .collect::<Result<Vec<_>>>()?;
    let options = crate::cohesive::study::study_options(case.linear_solver, &case.data);
    touched_sequence(
        &case,
        ranges,
        "annular branch",
        (&meshes, &|range, per_zone| {
            annular_mesh(&case, range, per_zone)
        }),
        &|mesh| surface_response_on_mesh(mesh, &options, 0.0),
        &|_, entry, _| left_the_annular_branch(&case, entry),
        &mut progress,
    )?
    .into_study(
        &case,
        jkr_values(&case)?,
        format!(
            "annular branch: touched (rim plane at the surface, hole open), pulled; the contact \
             line meshed uniformly at a third of the zone length per range (mesh named: the \
             smallest range's; line_element_size in each entry), the check at two thirds; \
             steps where the inner edge hops a node (force change under {ANNULAR_HOP_FORCE} F0) \
             continue the branch; pull-off: its most tensile force before the annulus lets go"
        ),
        start,
    )
}
/// A mesh per range and the study's element density per zone:
/// `(meshes at ANNULAR_ELEMENTS_PER_ZONE, mesh_at(range, elements_per_zone))`.
pub(super) type RangeMeshes<'m> = (
    &'m [(ProvidedMesh, f64)],
    &'m dyn Fn(f64, f64) -> Result<(ProvidedMesh, f64)>,
);

/// Why a simulation left the branch a study follows, if it did.
pub(super) type LeftTheBranch<'l> =
    &'l dyn Fn(&SurfaceResponse, &SequenceEntry, &[CurveEdges]) -> Option<String>;

/// What a touched-and-pulled study found over its ranges.
pub(super) struct TouchedSequence {
    pub sequence: Vec<SequenceEntry>,
    pub excluded: Vec<ExcludedEntry>,
    pub curves: Vec<StoredCurve>,
    /// The smallest range's mesh on the branch: its name, file, contact nodes and unknowns.
    pub mesh_name: String,
    pub mesh: ProvidedMesh,
    pub contact_nodes: usize,
    pub unknowns: usize,
    /// The smallest range's pull-off change on the mesh with half the elements per zone.
    pub mesh_difference: f64,
}

impl TouchedSequence {
    /// The study: the sequence extrapolated to zero range ([`extrapolate`], the mesh check's
    /// difference in the bar) beside the JKR route's `(fixed load, full contact, the paper's
    /// route)` values, with its note and its time since `start`.
    pub(super) fn into_study(
        self,
        case: &Case,
        (jkr, full_contact, paper): (Option<f64>, Option<f64>, Option<f64>),
        note: String,
        start: Instant,
    ) -> Result<PulloffStudy> {
        let (extrapolated, error_bar) = extrapolate(&self.sequence, self.mesh_difference);
        Ok(PulloffStudy {
            stopped: None,
            punch: case.punch.clone(),
            eps: None,
            d0_over_h: Some(case.d0_over_h),
            branch: Some(Branch::Annular),
            law: "exponential: tension (dw/rho) exp(-s/rho), dw = d0^2 E*/(2 pi a) (h = 1); \
                  non-penetration; nodal quadrature on the FE contact line (P2)"
                .into(),
            preload_over_d0: ANNULAR_PRELOAD / case.d0(),
            mesh: self.mesh_name,
            mesh_sha256: self.mesh.sha256()?,
            mesh_gmsh_version: self.mesh.gmsh_version.clone(),
            contact_nodes: self.contact_nodes,
            unknowns: self.unknowns,
            sequence: self.sequence,
            excluded: self.excluded,
            curves: self.curves,
            extrapolated_over_f0: extrapolated,
            error_bar,
            mesh_difference: Some(self.mesh_difference),
            jkr_fixed_load_over_f0: jkr,
            full_contact_over_f0: full_contact,
            paper_route_over_f0: paper,
            note,
            wall_s: start.elapsed().as_secs_f64(),
        })
    }
}

/// Touch and pull at each range on its mesh (`meshes`), the ranges that leave the branch
/// (`left`) filed apart with the reason, then the smallest range on the branch again on a mesh
/// with half the elements per zone (the mesh's share of the error bar): the annular branch's
/// study and a free band's. `what` names the branch in errors.
pub(super) fn touched_sequence(
    case: &Case,
    ranges: &[f64],
    what: &str,
    (meshes, mesh_at): RangeMeshes,
    response_of: &dyn Fn(&ProvidedMesh) -> Result<(SurfaceResponse, String)>,
    left: LeftTheBranch,
    progress: &mut dyn FnMut(&SequenceEntry),
) -> Result<TouchedSequence> {
    let (mut sequence, mut excluded, mut curves) = (Vec::new(), Vec::new(), Vec::new());
    let mut finest = None;
    for (&range, (mesh, size)) in ranges.iter().zip(meshes) {
        let (response, name) = response_of(mesh)?;
        let (mut entry, curve, edges) = simulate(&response, case, range, Branch::Annular, None)?;
        entry.line_element_size = Some(*size);
        progress(&entry);
        let why = left(&response, &entry, &edges);
        if why.is_none() {
            finest = Some((name, mesh.clone(), response.radii.len(), response.unknowns));
        }
        file_simulation(
            (&mut sequence, &mut excluded, &mut curves),
            entry,
            (&curve, &edges),
            why,
        );
    }
    let Some((mesh_name, mesh, contact_nodes, unknowns)) = finest else {
        let mut reasons: Vec<&str> = excluded.iter().map(|e| e.reason.as_str()).collect();
        reasons.dedup();
        return Err(Error::Unsupported {
            method: "cohesive-fem".into(),
            reason: format!(
                "no {what} at any range (rho/d0 = {ranges:?}): {}",
                reasons.join("; ")
            ),
        });
    };
    let smallest = sequence[sequence.len() - 1].range_over_a / case.d0();
    let (coarser, _) = mesh_at(smallest, 0.5 * ANNULAR_ELEMENTS_PER_ZONE)?;
    let (response, _) = response_of(&coarser)?;
    let (check, _, edges) = simulate(&response, case, smallest, Branch::Annular, None)?;
    progress(&check);
    if let Some(reason) = left(&response, &check, &edges) {
        return Err(Error::NoConvergence {
            method: "cohesive-fem".into(),
            reason: format!(
                "the mesh check (half the elements per zone) left the {what}: {reason}"
            ),
        });
    }
    let mesh_difference =
        (check.pulloff_over_f0 - sequence[sequence.len() - 1].pulloff_over_f0).abs();
    Ok(TouchedSequence {
        sequence,
        excluded,
        curves,
        mesh_name,
        mesh,
        contact_nodes,
        unknowns,
        mesh_difference,
    })
}
