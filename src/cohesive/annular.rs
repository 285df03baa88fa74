//! The annular branch of a concave punch by direct simulation: touched with the hole open, then
//! pulled, the inner edge of the contact moving outward until the annulus lets go. Its JKR limit
//! is the fixed-load pull-off of the annular contact (`verify jkr`, the paper's route), the value
//! the closed hole's study ([`crate::cohesive::study::run`]) does not reach.
//!
//! The inner edge travels a large part of the contact line (the cone at `d0/h = 1`: from
//! `b/a = 0.33` at first touch to `0.78` at pull-off), so the line is meshed uniformly, with
//! elements of a third of the cohesive zone `ℓ = π E* Δw/(4σ0²)` (`ℓ = π² (ρ/d0)²/2 a` for this
//! study's units), one mesh per range. There the front still advances node by node (lattice
//! trapping), but each hop changes the force by about `4e-4 F0`: steps whose Hessian needed a
//! shift and whose force changed by less than [`ANNULAR_HOP_FORCE`] continue the branch
//! (counted as `node_hops`), and the branch ends where the force jumps by more.

use std::time::Instant;

use crate::cohesive::study::{
    check_d0_over_h, check_ranges, extrapolate, file_simulation, jkr_values, simulate, Branch,
    Case, PulloffStudy, SequenceEntry, ANNULAR_ELEMENTS_PER_ZONE, ANNULAR_HOP_FORCE,
    ANNULAR_PRELOAD, STUDY_LEVEL,
};
use crate::error::{Error, Result};
use crate::fem::solver::surface_response_on_mesh;
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
    let mesh = provider::generate(&parameters, "the annular branch's pull-off simulation")?;
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
                "the annular branch is a concave punch's (cone, sphere); the {} has none",
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
    let options = crate::cohesive::study::study_options();
    let (mut sequence, mut excluded, mut curves) = (Vec::new(), Vec::new(), Vec::new());
    let mut finest = None;
    for (&range, (mesh, size)) in ranges.iter().zip(&meshes) {
        let (response, name) = surface_response_on_mesh(mesh, &options, 0.0)?;
        let (mut entry, curve, edges) = simulate(&response, &case, range, Branch::Annular, None)?;
        entry.line_element_size = Some(*size);
        progress(&entry);
        let left = left_the_annular_branch(&case, &entry);
        if left.is_none() {
            finest = Some((name, mesh.clone(), response.radii.len(), response.unknowns));
        }
        file_simulation(
            (&mut sequence, &mut excluded, &mut curves),
            entry,
            (&curve, &edges),
            left,
        );
    }
    let Some((mesh_name, mesh, contact_nodes, unknowns)) = finest else {
        let mut reasons: Vec<&str> = excluded.iter().map(|e| e.reason.as_str()).collect();
        reasons.dedup();
        return Err(Error::Unsupported {
            method: "cohesive-fem".into(),
            reason: format!(
                "no annular branch at any range (rho/d0 = {ranges:?}): {}",
                reasons.join("; ")
            ),
        });
    };
    let smallest = sequence[sequence.len() - 1].range_over_a / case.d0();
    let (coarser, _) = annular_mesh(&case, smallest, 0.5 * ANNULAR_ELEMENTS_PER_ZONE)?;
    let (response, _) = surface_response_on_mesh(&coarser, &options, 0.0)?;
    let (check, _, _) = simulate(&response, &case, smallest, Branch::Annular, None)?;
    progress(&check);
    let mesh_difference = match left_the_annular_branch(&case, &check) {
        None => Some((check.pulloff_over_f0 - sequence[sequence.len() - 1].pulloff_over_f0).abs()),
        Some(reason) => {
            return Err(Error::NoConvergence {
                method: "cohesive-fem".into(),
                reason: format!(
                    "the mesh check (half the elements per zone) left the annular branch: {reason}"
                ),
            })
        }
    };
    let (extrapolated, error_bar) = extrapolate(&sequence, mesh_difference.unwrap_or(0.0));
    let (jkr, full_contact, paper) = jkr_values(&case)?;
    Ok(PulloffStudy {
        stopped: None,
        punch: case.punch,
        eps: None,
        d0_over_h: Some(case.d0_over_h),
        branch: Some(Branch::Annular),
        law: "exponential: tension (dw/rho) exp(-s/rho), dw = d0^2 E*/(2 pi a) (h = 1); \
              non-penetration; nodal quadrature on the FE contact line (P2)"
            .into(),
        preload_over_d0: ANNULAR_PRELOAD / case.d0(),
        mesh: mesh_name,
        mesh_sha256: mesh.sha256()?,
        mesh_gmsh_version: mesh.gmsh_version.clone(),
        contact_nodes,
        unknowns,
        sequence,
        excluded,
        curves,
        extrapolated_over_f0: extrapolated,
        error_bar,
        mesh_difference,
        jkr_fixed_load_over_f0: jkr,
        full_contact_over_f0: full_contact,
        paper_route_over_f0: paper,
        note: format!(
            "annular branch: touched (rim plane at the surface, hole open), pulled; the contact \
             line meshed uniformly at a third of the zone length per range (mesh named: the \
             smallest range's; line_element_size in each entry), the check at two thirds; \
             steps where the inner edge hops a node (force change under {ANNULAR_HOP_FORCE} F0) \
             continue the branch; pull-off: its most tensile force before the annulus lets go"
        ),
        wall_s: start.elapsed().as_secs_f64(),
    })
}
