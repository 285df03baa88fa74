//! A free band's pull-off by direct simulation: touched at its lowest circle (`d = 0`), then
//! pulled, both free edges of the contact moving until the band lets go. Its JKR limit is the
//! two-edge JKR solution's fixed-load pull-off ([`crate::adhesion::band_jkr`], `verify jkr`),
//! which no published solution gives beyond the narrow limit.
//!
//! The contact band moves around `r = a` on both sides, so the model's contact line reaches
//! past the ring: the mesh's line `[0, 1]` is read in a unit of [`BAND_FRAME`] `a`
//! ([`SurfaceResponse::in_units_of_a`]), meshed uniformly at a third of the cohesive zone
//! `ℓ = π² (ρ/d0)²/2 a` as the annular branch's is, one mesh per range, and the study follows
//! the annular branch's rules ([`crate::cohesive::annular`]): node hops continue the branch, the
//! smallest range is run again with half the elements per zone (the mesh's share of the error
//! bar), and the ranges are extrapolated linearly to zero.

use std::time::Instant;

use crate::cohesive::annular::touched_sequence;
use crate::cohesive::study::{
    check_d0_over_h, check_ranges, Case, PulloffStudy, SequenceEntry, ANNULAR_ELEMENTS_PER_ZONE,
    ANNULAR_HOP_FORCE, STUDY_LEVEL,
};
use crate::error::{Error, Result};
use crate::fem::solver::surface_response_on_mesh;
use crate::fem::surface_response::SurfaceResponse;
use crate::mesh::provider::{self, ProvidedMesh};

/// Length of the model's contact line in units of `a`: the built-in ring's two-edge JKR
/// contact at its fixed-load pull-off reaches `c = 1.21 a` at `d0/h = 1` (`verify jkr`), and a
/// contact that reaches the line's end is an error.
pub const BAND_FRAME: f64 = 1.5;

/// Largest `d0/h` a free band's study takes: the contact at pull-off widens with `d0/h`
/// (`c = 1.21 a` at 1) and must stay inside the line [`BAND_FRAME`] `a` long.
pub const BAND_MAX_D0_OVER_H: f64 = 1.0;

/// Most contact-line elements a free band's mesh may ask for (the condensed model is dense).
const MAX_LINE_ELEMENTS: f64 = 600.0;

/// The mesh at `range`: level [`STUDY_LEVEL`] of the adapted family whose contact line
/// (`BAND_FRAME a` long) is uniform at `ℓ / elements_per_zone`; returns the element size in
/// units of `a`.
fn band_mesh(case: &Case, range: f64, elements_per_zone: f64) -> Result<(ProvidedMesh, f64)> {
    let size = case.zone_length(range) / elements_per_zone;
    let elements = BAND_FRAME / size;
    if elements > MAX_LINE_ELEMENTS {
        let smallest = (2.0 * elements_per_zone * BAND_FRAME
            / (MAX_LINE_ELEMENTS * std::f64::consts::PI.powi(2)))
        .sqrt();
        return Err(Error::invalid(
            "ranges",
            format!(
                "range rho/d0 = {range}: the {}'s contact line ({BAND_FRAME} a) would need \
                 {elements:.0} elements of {size:.1e} a (1/{elements_per_zone} of the zone), \
                 more than {MAX_LINE_ELEMENTS:.0}; use ranges rho/d0 >= {smallest:.3}",
                case.punch.name()
            ),
        ));
    }
    let mut parameters = provider::adapted_parameters(0.0, STUDY_LEVEL, None, 0.0, None);
    for (name, value) in parameters.iter_mut() {
        if name == "hline" {
            *value = size / BAND_FRAME;
        }
    }
    let what = format!("the {}'s pull-off simulation", case.punch.name());
    let mesh = provider::generate(&case.data, &parameters, &what)?;
    Ok((mesh, size))
}

/// The condensed model of `mesh` in units of `a` ([`BAND_FRAME`]).
fn band_response(
    mesh: &ProvidedMesh,
    linear_solver: crate::sparse::Backend,
    data: &crate::mesh::files::DataPaths,
) -> Result<(SurfaceResponse, String)> {
    let options = crate::cohesive::study::study_options(linear_solver, data);
    let (response, name) = surface_response_on_mesh(mesh, &options, 0.0)?;
    Ok((response.in_units_of_a(BAND_FRAME), name))
}

/// Why a simulation is not a pull-off of the touched band, if it is not: its contact reached
/// the end of the model's line or the axis, or the state the branch jumps to was not found.
fn left_the_band(
    case: &Case,
    response: &SurfaceResponse,
    entry: &SequenceEntry,
    edges: &[crate::cohesive::study::CurveEdges],
) -> Option<String> {
    let line_end = response.radii.last().copied().unwrap_or(0.0);
    let spacing = line_end - response.radii[response.radii.len().saturating_sub(2)];
    if let Some((_, outer)) = edges
        .iter()
        .filter_map(|e| e.contact.or(e.zone))
        .find(|&(_, outer)| outer >= line_end - spacing)
    {
        return Some(format!(
            "the contact or its cohesive zone reached the end of the model's contact line \
             (r = {} a, {outer:.3} a reached) at d0/h = {}",
            crate::error::show(line_end),
            crate::error::show(case.d0_over_h)
        ));
    }
    if let Some((depth, force)) = entry.hole_closed_at {
        return Some(format!(
            "the contact reached the axis at d/d0 = {depth:.4}, F/F0 = {force:.4}: a disk, not \
             the {}'s band",
            case.punch.name()
        ));
    }
    entry.unresolved_landing.as_ref().map(|why| {
        format!(
            "the branch ended at d/d0 = {:.4}, F/F0 = {:.4} and the state it jumps to was not \
             found ({why})",
            entry.pulloff_depth_over_d0, -entry.pulloff_over_f0
        )
    })
}

/// Run a free band's study of `case` at `ranges` (units of `d0`, decreasing): touch, pull, the
/// most tensile force at each range, the smallest range again with half the elements per zone,
/// extrapolated linearly to zero range beside the JKR route's fixed-load pull-off (module
/// documentation).
pub fn run_band(
    case: Case,
    ranges: &[f64],
    mut progress: impl FnMut(&SequenceEntry),
) -> Result<PulloffStudy> {
    let start = Instant::now();
    if !case.punch.is_free_band() {
        return Err(Error::invalid(
            "punch",
            format!(
                "the free band's study takes a punch whose contact has two free edges, not the {}",
                case.punch
            ),
        ));
    }
    check_d0_over_h(&case)?;
    if case.d0_over_h > BAND_MAX_D0_OVER_H {
        return Err(Error::invalid(
            "d0h",
            format!(
                "d0/h = {}: the {}'s simulation runs for d0/h <= {BAND_MAX_D0_OVER_H} (its \
                 contact must stay inside a line {BAND_FRAME} a long); `verify jkr --punch \
                 {} --d0h {}` gives the JKR limit",
                crate::error::show(case.d0_over_h),
                case.punch.name(),
                case.punch.name(),
                crate::error::show(case.d0_over_h)
            ),
        ));
    }
    check_ranges(ranges)?;
    let meshes = ranges
        .iter()
        .map(|&r| band_mesh(&case, r, ANNULAR_ELEMENTS_PER_ZONE))
        .collect::<Result<Vec<_>>>()?;
    let jkr =
        crate::adhesion::band_jkr(&crate::methods::RingBem::new(), &case.punch, case.d0_over_h)?;
    touched_sequence(
        &case,
        ranges,
        &format!("pull-off of the {}'s band", case.punch.name()),
        (&meshes, &|range, per_zone| {
            band_mesh(&case, range, per_zone)
        }),
        &|mesh| band_response(mesh, case.linear_solver, &case.data),
        &|response, entry, edges| left_the_band(&case, response, entry, edges),
        &mut progress,
    )?
    .into_study(
        &case,
        (jkr.fixed_load.map(|c| -c.force), None, None),
        format!(
            "{}: touched at its lowest circle (d = 0), pulled; the contact line [0, \
             {BAND_FRAME} a] meshed uniformly at a third of the zone length per range (mesh \
             named: the smallest range's; line_element_size in each entry), the check at two \
             thirds; steps where an edge hops a node (force change under {ANNULAR_HOP_FORCE} \
             F0) continue the branch; pull-off: its most tensile force before the band lets go \
             (the fixed-load pull-off)",
            case.punch.name()
        ),
        start,
    )
}
