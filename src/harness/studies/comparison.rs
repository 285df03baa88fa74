//! The default job of `verify`: every method that exists, on the three punches, side by side
//! with the analytic references, with a verdict wherever a reference declares an error bound, and
//! the FEM cross-verified against the ring BEM.
//!
//! Verdict rule (cross-verification, `docs/methods.md`): a method and a reference
//! agree when `|f_method - f_ref| <= U_method + U_ref`, with `U` each one's error estimate or
//! bound. The paper's fits declare no bound: their difference is shown, not judged.

use std::time::Instant;

use serde::Serialize;

use super::{figures, UnitLoad};
use crate::harness::cases::{self, power};
use crate::harness::report::table::{verdict, Cell, Column, Format, Table};
use ringcontact::error::Result;
use ringcontact::methods::Degree;
use ringcontact::methods::{self, Method, MethodOptions};
use ringcontact::methods::{RingBem, RingState};
use ringcontact::punch::{Contact, PunchKind};
use ringcontact::reference::{self, power_law, Quantity, ReferenceKind};

/// Contact ratios of the fixed annulus's table.
const FLAT_RATIOS: [f64; 10] = [0.0, 0.01, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.95, 0.99];
/// Contact ratios of the concave tables.
const CONCAVE_RATIOS: [f64; 9] = [0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.8, 0.9, 0.95];

/// One comparison of a computed value with a reference.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Comparison {
    pub reference: String,
    pub reference_kind: ReferenceKind,
    pub reference_value: f64,
    /// `(method - reference) / reference`.
    pub relative_difference: f64,
    /// `true`/`false` where the reference declares a bound; `None` for fits.
    pub agrees: Option<bool>,
}

/// One row: a quantity at one contact ratio, computed by the ring BEM, against every valid
/// reference.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Row {
    pub quantity: Quantity,
    pub eps: f64,
    pub method: String,
    pub value: f64,
    pub error_estimate: f64,
    pub unknowns: usize,
    pub wall_s: f64,
    pub comparisons: Vec<Comparison>,
}

/// A consistency check that involves no reference (e.g. `γ2' = γ γ1'`).
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct IdentityCheck {
    pub name: String,
    pub eps: f64,
    pub lhs: f64,
    pub rhs: f64,
    pub relative_residual: f64,
    pub tolerance: f64,
    pub passed: bool,
}

/// One state solved by the FEM and by the ring BEM (cross-verification of two discretisations).
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct CrossCheck {
    #[serde(flatten)]
    pub punch: PunchKind,
    /// `b/a` (fixed annulus) or `d/h` (concave): what was prescribed.
    pub prescribed: String,
    /// `γ` (flat) or `γ2` (concave) of each method.
    pub fem_value: f64,
    pub ring_bem_value: f64,
    pub fem_eps: f64,
    pub ring_bem_eps: f64,
    pub fem_error_estimate: f64,
    pub ring_bem_error_estimate: f64,
    pub relative_difference: f64,
    pub eps_difference: f64,
    /// A free band: FEM minus ring BEM of the outer edge `c/a` (absent where it is the rim).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_difference: Option<f64>,
    pub dofs: usize,
    pub mesh: String,
    pub fem_wall_s: f64,
    /// `|f_fem - f_bem| <= U_fem + U_bem` for the value and for eps.
    pub agrees: bool,
}

/// The whole comparison.
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct ComparisonReport {
    pub tolerance: f64,
    pub rows: Vec<Row>,
    pub identities: Vec<IdentityCheck>,
    pub fem: Vec<CrossCheck>,
    /// FEM cross-checks not run: they need meshes made by gmsh, which is not found.
    #[serde(default)]
    pub fem_not_run: usize,
}

impl ComparisonReport {
    /// Number of failed verdicts (bounded references that disagree, failed identities).
    pub fn failures(&self) -> usize {
        let rows = self
            .rows
            .iter()
            .flat_map(|r| &r.comparisons)
            .filter(|c| c.agrees == Some(false))
            .count();
        rows + self.identities.iter().filter(|i| !i.passed).count()
            + self.fem.iter().filter(|c| !c.agrees).count()
    }
}

fn compare(quantity: Quantity, eps: f64, value: f64, estimate: f64) -> Vec<Comparison> {
    reference::valid_references(quantity, eps)
        .iter()
        .filter_map(|r| {
            let v = r.evaluate(eps)?;
            let diff = value - v.value;
            Some(Comparison {
                reference: r.name.to_string(),
                reference_kind: r.kind,
                reference_value: v.value,
                relative_difference: diff / v.value,
                agrees: v
                    .error_bound
                    .map(|b| diff.abs() <= b + estimate * value.abs() + 4.0 * f64::EPSILON),
            })
        })
        .collect()
}

fn row(quantity: Quantity, state: &RingState, value: f64, wall_s: f64) -> Row {
    Row {
        quantity,
        eps: state.eps,
        method: "ring-bem".into(),
        value,
        error_estimate: state.error_estimate,
        unknowns: state.unknowns,
        wall_s,
        comparisons: compare(quantity, state.eps, value, state.error_estimate),
    }
}

/// Run the comparison with the ring BEM at `tolerance`.
pub fn run(tolerance: f64) -> Result<ComparisonReport> {
    let solver = RingBem::new();
    let mut rows = Vec::new();
    for kind in PunchKind::built_in(Contact::FixedAnnulus) {
        let Some(quantity) = reference::quantity_of(&kind, 0) else {
            continue;
        };
        for &eps in &FLAT_RATIOS {
            let start = Instant::now();
            let state = solver.flat(eps, tolerance)?;
            let wall = start.elapsed().as_secs_f64();
            rows.push(row(quantity, &state, state.gamma.unwrap_or(f64::NAN), wall));
        }
    }
    for kind in PunchKind::built_in(Contact::RimAndFreeInner) {
        let (Some(q1), Some(q2)) = (
            reference::quantity_of(&kind, 1),
            reference::quantity_of(&kind, 2),
        ) else {
            continue;
        };
        for &eps in &CONCAVE_RATIOS {
            let start = Instant::now();
            let state = solver.concave_at_ratio(&kind, eps, tolerance)?;
            let wall = start.elapsed().as_secs_f64();
            rows.push(row(q1, &state, state.gamma1.unwrap_or(f64::NAN), wall));
            rows.push(row(q2, &state, state.gamma2.unwrap_or(f64::NAN), wall));
        }
        // The onset of full contact where the hole closes (the eps -> 0 limit, exact), reached
        // from the full-contact side by the disk discretisation.
        if let Some((depth, _)) = kind.closure() {
            let start = Instant::now();
            let onset = solver.full_contact(&kind, depth, tolerance)?;
            let wall = start.elapsed().as_secs_f64();
            rows.push(row(q2, &onset, onset.gamma2.unwrap_or(f64::NAN), wall));
        }
    }
    let order = reference::quantities();
    rows.sort_by_key(|r| order.iter().position(|q| *q == r.quantity));
    let mut identities = incremental_stiffness_checks(&solver, tolerance)?;
    identities.extend(full_contact_limit_checks(&solver, tolerance)?);
    identities.extend(edge_intensity_checks(&solver, tolerance)?);
    identities.extend(power_law_checks(&solver, tolerance)?);
    identities.extend(free_band_edge_checks(&solver, tolerance)?);
    identities.extend(table_punch_checks(&solver, tolerance)?);
    let (fem, fem_not_run) = fem_cross_checks(&solver, tolerance)?;
    Ok(ComparisonReport {
        tolerance,
        rows,
        identities,
        fem,
        fem_not_run,
    })
}

/// The FEM (default tolerance, P2, committed meshes; a free band on meshes gmsh makes) against
/// the ring BEM on the states of [`cases::fem_cross_check_states`]; with the number of states
/// not run for want of gmsh.
fn fem_cross_checks(solver: &RingBem, tolerance: f64) -> Result<(Vec<CrossCheck>, usize)> {
    // `--method fem` at its default tolerance, P2, on the meshes it picks.
    let options = MethodOptions {
        degree: Some(Degree::Quadratic),
        ..crate::harness::settings::method_options()
    };
    let mut checks = Vec::new();
    let load = UnitLoad::of_depth;
    let cases = cases::fem_cross_check_states()
        .into_iter()
        .map(|(kind, eps, depth)| (kind, eps, load(depth)));
    // The report's punch given by points on the committed meshes, where the checkout has it.
    let table = cases::report_table_punch().map(|kind| (kind, 0.0, UnitLoad::Depth(1.5)));
    // A free band's meshes are made for the scene (gmsh): without it these are not run (counted).
    let gmsh = ringcontact::mesh::provider::gmsh_available(&crate::harness::settings::data_paths());
    let bands: Vec<_> = cases::free_bands()
        .into_iter()
        .flat_map(|band| cases::BAND_FEM_DEPTHS.map(|d| (band.clone(), 0.0, UnitLoad::Depth(d))))
        .collect();
    let not_run = if gmsh { 0 } else { bands.len() };
    let bands = bands.into_iter().filter(|_| gmsh);
    for (kind, eps, load) in cases.chain(table).chain(bands) {
        let scene = super::unit_scene(kind.clone(), eps, load, None)?;
        let fem = methods::solve_with(&scene, Method::Fem, &options)?;
        // A FEM solution always carries its model's part.
        let (dofs, mesh) = fem
            .fem
            .as_ref()
            .map_or((0, String::new()), |m| (m.dofs, m.mesh.clone()));
        let mut outer_difference = None;
        let (bem_value, bem_eps, bem_estimate, prescribed, fem_value) = match load {
            UnitLoad::Depth(d) => {
                let s = solver.concave_at_depth(&kind, d, tolerance)?;
                outer_difference = (!kind.has_rim()).then_some(fem.outer_radius - s.outer_edge);
                (
                    s.gamma2.unwrap_or(f64::NAN),
                    s.eps,
                    s.error_estimate,
                    format!("d/h = {d}"),
                    fem.gamma2.unwrap_or(f64::NAN),
                )
            }
            _ => {
                let s = solver.flat(eps, tolerance)?;
                (
                    s.gamma.unwrap_or(f64::NAN),
                    eps,
                    s.error_estimate,
                    format!("b/a = {eps}"),
                    fem.gamma.unwrap_or(f64::NAN),
                )
            }
        };
        let fem_estimate = fem.error_estimate.unwrap_or(f64::INFINITY);
        let relative_difference = (fem_value - bem_value) / bem_value;
        let eps_difference = fem.eps - bem_eps;
        let allowed = fem_estimate + bem_estimate;
        checks.push(CrossCheck {
            punch: kind,
            prescribed,
            fem_value,
            ring_bem_value: bem_value,
            fem_eps: fem.eps,
            ring_bem_eps: bem_eps,
            fem_error_estimate: fem_estimate,
            ring_bem_error_estimate: bem_estimate,
            relative_difference,
            eps_difference,
            outer_difference,
            dofs,
            mesh,
            fem_wall_s: fem.wall_s,
            agrees: relative_difference.abs() <= allowed
                && eps_difference.abs() <= allowed
                && outer_difference.is_none_or(|c| c.abs() <= allowed),
        });
    }
    Ok((checks, not_run))
}

/// docs/conventions.md fact 6: along the non-adhesive path `dF/dd = 2 E* a γ(eps)`, i.e.
/// `γ2'(eps) = γ(eps) γ1'(eps)`. Derivatives by a fourth-order central difference of the ring
/// BEM's own `γ1`, `γ2`; `γ` from an independent fixed-annulus solve. A free band `[b, c]`
/// has both edges free, so its stiffness is the fixed annulus `b/c` scaled by `c`:
/// `γ2'(b) = c γ(b/c) γ1'(b)` (`c = a` for the punches with a rim).
fn incremental_stiffness_checks(solver: &RingBem, tolerance: f64) -> Result<Vec<IdentityCheck>> {
    let mut checks = Vec::new();
    for (kind, ratios) in cases::stiffness_identity_ratios() {
        for &eps in ratios {
            let step = 1e-3 * eps.min(1.0 - eps);
            let at = |e: f64| solver.concave_at_ratio(&kind, e, tolerance);
            let (p2, p1, m1, m2) = (
                at(eps + 2.0 * step)?,
                at(eps + step)?,
                at(eps - step)?,
                at(eps - 2.0 * step)?,
            );
            let derivative = |f: fn(&RingState) -> f64| {
                (-f(&p2) + 8.0 * f(&p1) - 8.0 * f(&m1) + f(&m2)) / (12.0 * step)
            };
            let d1 = derivative(|s| s.gamma1.unwrap_or(f64::NAN));
            let d2 = derivative(|s| s.gamma2.unwrap_or(f64::NAN));
            let outer = at(eps)?.outer_edge;
            let gamma = outer
                * solver
                    .flat(eps / outer, tolerance)?
                    .gamma
                    .unwrap_or(f64::NAN);
            let residual = (d2 - gamma * d1).abs() / d2.abs();
            // Difference-quotient error: O(step⁴) truncation plus rounding amplified by 1/step.
            let allowed = 1e-6_f64.max(100.0 * tolerance);
            checks.push(IdentityCheck {
                name: if kind.has_rim() {
                    format!("{kind}: gamma2' = gamma * gamma1'")
                } else {
                    format!("{kind}: gamma2' = c gamma(b/c) * gamma1' (both edges free)")
                },
                eps,
                lhs: d2,
                rhs: gamma * d1,
                relative_residual: residual,
                tolerance: allowed,
                passed: residual <= allowed,
            });
        }
    }
    Ok(checks)
}

/// Small-`eps` limits from the full-contact solutions (method of dimensionality reduction): a
/// small hole perturbs the force by `O(eps³)`, so as `eps -> 0` the gap `1 - ρ^n` of exponent
/// `n` has `γ1 - γ2 -> 1 - κ_n/(n + 1)` (`F = 2 E* a (d - h (1 - κ_n/(n + 1)))` in full
/// contact): `1 - π/4` for `n = 1`, `1/3` for `n = 2`. Checked at `eps = 0.01` with the bound
/// `eps³`.
fn full_contact_limit_checks(solver: &RingBem, tolerance: f64) -> Result<Vec<IdentityCheck>> {
    let eps = 0.01_f64;
    let mut checks = Vec::new();
    for kind in cases::full_contact_limit_punches() {
        let Some(n) = kind.power_law_exponent() else {
            continue;
        };
        let (limit, label) = full_contact_limit(n);
        let state = solver.concave_at_ratio(&kind, eps, tolerance)?;
        let difference = state.gamma1.unwrap_or(f64::NAN) - state.gamma2.unwrap_or(f64::NAN);
        let residual = (difference - limit).abs() / limit;
        let allowed = eps.powi(3);
        checks.push(IdentityCheck {
            name: format!("{kind}: gamma1 - gamma2 -> {label} (MDR)"),
            eps,
            lhs: difference,
            rhs: limit,
            relative_residual: residual,
            tolerance: allowed,
            passed: residual <= allowed,
        });
    }
    Ok(checks)
}

/// `γ1 - γ2` of the gap `1 - ρ^n` in full contact, `1 - κ_n/(n + 1)`, written
/// in closed form where it has one (`n = 1`: `1 - π/4`; `n = 2`: `1/3`).
fn full_contact_limit(n: f64) -> (f64, &'static str) {
    if n == 1.0 {
        (1.0 - std::f64::consts::FRAC_PI_4, "1 - pi/4")
    } else if n == 2.0 {
        (1.0 / 3.0, "1/3")
    } else {
        (1.0 - power_law::kappa(n) / (n + 1.0), "1 - kappa_n/(n + 1)")
    }
}

/// The gap `h (1 - (r/a)^n)` with a free exponent: with the exponent of each built-in punch that
/// fixes one it is that punch (`γ2` at `eps = 0.3` to 1e-12, two evaluations of the gap), and past
/// its closure depth its force is the MDR's closed form `γ2 = γ1 - 1 + κ_n/(n + 1)` (`n = 4` at
/// `d = 3h`, where the disk basis is exact to rounding; docs/conventions.md fact 8).
fn power_law_checks(solver: &RingBem, tolerance: f64) -> Result<Vec<IdentityCheck>> {
    let mut checks = Vec::new();
    let eps = 0.3;
    let named_power_laws = PunchKind::built_in(Contact::RimAndFreeInner)
        .into_iter()
        .filter_map(|kind| Some((kind.power_law_exponent()?, kind)));
    for (n, named) in named_power_laws {
        let lhs = solver
            .concave_at_ratio(&power(n), eps, tolerance)?
            .gamma2
            .unwrap_or(f64::NAN);
        let rhs = solver
            .concave_at_ratio(&named, eps, tolerance)?
            .gamma2
            .unwrap_or(f64::NAN);
        let residual = (lhs - rhs).abs() / rhs.abs();
        checks.push(IdentityCheck {
            name: format!("power (n = {n}): gamma2 = {named}'s"),
            eps,
            lhs,
            rhs,
            relative_residual: residual,
            tolerance: 1e-12,
            passed: residual <= 1e-12,
        });
    }
    let (n, depth) = (4.0, 3.0);
    let lhs = solver
        .concave_at_depth(&power(n), depth, tolerance)?
        .gamma2
        .unwrap_or(f64::NAN);
    let rhs = power_law::full_contact_gamma2(n, depth).unwrap_or(f64::NAN);
    let residual = (lhs - rhs).abs() / rhs.abs();
    let allowed = tolerance.max(1e-12);
    checks.push(IdentityCheck {
        name: "power (n = 4) at d = 3h: gamma2 = gamma1 - 1 + kappa_n/(n + 1) (MDR)".into(),
        eps: 0.0,
        lhs,
        rhs,
        relative_residual: residual,
        tolerance: allowed,
        passed: residual <= allowed,
    });
    Ok(checks)
}

/// A free band's two edges: the ring BEM on the prescribed band `[b, c]` at the state's depth
/// (the other path: both edges given, both intensities computed) finds `K = 0` at each,
/// relative to the band's scale `F/(π (b + c) sqrt(c - b))`, and the state's force.
fn free_band_edge_checks(solver: &RingBem, tolerance: f64) -> Result<Vec<IdentityCheck>> {
    let mut checks = Vec::new();
    for band in cases::free_bands() {
        for eps in cases::BAND_EDGE_RATIOS {
            let state = solver.concave_at_ratio(&band, eps, tolerance)?;
            let (c, depth) = (state.outer_edge, state.gamma1.unwrap_or(f64::NAN));
            let gap = |r: f64| band.gap_shape(r);
            let band_state = solver.prescribed_band(gap, eps, c, depth, tolerance)?;
            let scale = band_state.force / (std::f64::consts::PI * (eps + c) * (c - eps).sqrt());
            let largest = band_state
                .inner_stress_intensity
                .abs()
                .max(band_state.outer_stress_intensity.abs());
            let residual = largest / scale;
            let allowed = 1e-8_f64.max(100.0 * tolerance);
            checks.push(IdentityCheck {
                name: format!(
                    "{band}: K = 0 at both edges of its band (prescribed-band solve), |K| / scale"
                ),
                eps,
                lhs: residual,
                rhs: 0.0,
                relative_residual: residual,
                tolerance: allowed,
                passed: residual <= allowed,
            });
        }
    }
    Ok(checks)
}

/// Depths `d/h` at which the report's punch given by points is checked against the punch it
/// samples.
const TABLE_CHECK_DEPTHS: [f64; 3] = [0.5, 1.5, 2.5];

/// The report's punch given by points ([`cases::report_table_punch`], the parabolic gap's profile
/// at 21 points) against the punch it samples: `|Δγ2| <= δ` at any depth, `δ` the largest
/// difference of the two gaps `g/h` (the contact problem is monotone in the gap,
/// [`figures::largest_gap_difference`]). None where the checkout has no table file.
fn table_punch_checks(solver: &RingBem, tolerance: f64) -> Result<Vec<IdentityCheck>> {
    let Some(table) = cases::report_table_punch() else {
        return Ok(Vec::new());
    };
    let sampled = cases::REPORT_TABLE_SAMPLES;
    let delta = figures::largest_gap_difference(table.clone(), sampled.clone());
    let mut checks = Vec::new();
    for depth in TABLE_CHECK_DEPTHS {
        let state = solver.concave_at_depth(&table, depth, tolerance)?;
        let reference = solver.concave_at_depth(&sampled, depth, tolerance)?;
        let difference =
            (state.gamma2.unwrap_or(f64::NAN) - reference.gamma2.unwrap_or(f64::NAN)).abs();
        checks.push(IdentityCheck {
            name: format!(
                "table ({sampled} sampled, {}) at d = {depth}h: |gamma2 - {sampled}'s| <= largest gap difference (monotone contact)",
                cases::REPORT_TABLE_FILE
            ),
            eps: state.eps,
            lhs: difference,
            rhs: delta,
            relative_residual: difference / delta,
            tolerance: 1.0,
            passed: difference <= delta,
        });
    }
    Ok(checks)
}

/// docs/conventions.md fact 7: the fixed annulus' edge stress intensities,
/// `K = E* d κ / sqrt(π a)`, follow from the derivative of its force: `κ_out² = γ - eps γ'` and
/// `κ_in² = -γ'/eps` (energy release rate at a fixed-depth edge). Left: the ring BEM's edge
/// coefficients (local); right: a fourth-order difference of its force (global).
fn edge_intensity_checks(solver: &RingBem, tolerance: f64) -> Result<Vec<IdentityCheck>> {
    let mut checks = Vec::new();
    let root_pi = std::f64::consts::PI.sqrt();
    let Some(annulus) = PunchKind::built_in(Contact::FixedAnnulus)
        .into_iter()
        .next()
    else {
        return Ok(checks);
    };
    for &eps in &[0.2_f64, 0.5, 0.8] {
        let step = 1e-3 * eps.min(1.0 - eps);
        let gamma =
            |e: f64| -> Result<f64> { Ok(solver.flat(e, tolerance)?.gamma.unwrap_or(f64::NAN)) };
        let slope = (-gamma(eps + 2.0 * step)? + 8.0 * gamma(eps + step)?
            - 8.0 * gamma(eps - step)?
            + gamma(eps - 2.0 * step)?)
            / (12.0 * step);
        let state = solver.flat(eps, tolerance)?;
        let g = state.gamma.unwrap_or(f64::NAN);
        let allowed = 1e-6_f64.max(100.0 * tolerance);
        for (edge, kappa, expected) in [
            (
                "outer",
                state.rim_stress_intensity * root_pi,
                g - eps * slope,
            ),
            (
                "inner",
                state.inner_stress_intensity * root_pi,
                -slope / eps,
            ),
        ] {
            let lhs = kappa * kappa;
            let residual = (lhs - expected).abs() / expected.abs();
            checks.push(IdentityCheck {
                name: format!("{annulus}: kappa_{edge}^2 from gamma'"),
                eps,
                lhs,
                rhs: expected,
                relative_residual: residual,
                tolerance: allowed,
                passed: residual <= allowed,
            });
        }
    }
    Ok(checks)
}

/// The ring BEM against every bounded reference.
pub(crate) fn reference_table(comparison: &ComparisonReport) -> Table {
    let mut t = Table::new(
        "Ring BEM against the references",
        vec![
            Column::text("quantity", "quantity"),
            Column::number("eps", "eps", Format::Fixed(2)),
            Column::number("ring_bem", "ring BEM", Format::Fixed(12)),
            Column::number("error_estimate", "est. error", Format::Scientific(0)),
            Column::number("unknowns", "N", Format::Fixed(0)),
            Column::number("wall_ms", "time (one run)", Format::Fixed(3)).with_unit("ms"),
            Column::text("references", "references (rel. difference, verdict)"),
        ],
    );
    for r in &comparison.rows {
        let refs: Vec<String> = r
            .comparisons
            .iter()
            .map(|c| {
                format!(
                    "{} {:+.1e} {}",
                    c.reference,
                    c.relative_difference,
                    match c.agrees {
                        Some(true) => "ok",
                        Some(false) => "FAIL",
                        None => "",
                    }
                )
            })
            .collect();
        let failed = r.comparisons.iter().any(|c| c.agrees == Some(false));
        let refs = refs.join("; ");
        t.push(vec![
            r.quantity.label().into(),
            r.eps.into(),
            r.value.into(),
            r.error_estimate.into(),
            (r.unknowns as f64).into(),
            (r.wall_s * 1e3).into(),
            if failed {
                Cell::Flag(refs)
            } else {
                Cell::Text(refs)
            },
        ]);
    }
    t
}

/// The consistency identities (no reference involved).
pub(crate) fn identity_table(comparison: &ComparisonReport) -> Table {
    let mut t = Table::new(
        "Consistency identities",
        vec![
            Column::text("check", "check"),
            Column::number("eps", "eps", Format::Fixed(2)),
            Column::number("residual", "residual", Format::Scientific(1)),
            Column::number("allowed", "allowed", Format::Scientific(0)),
            Column::text("verdict", "verdict"),
        ],
    );
    for c in &comparison.identities {
        t.push(vec![
            c.name.clone().into(),
            c.eps.into(),
            c.relative_residual.into(),
            c.tolerance.into(),
            verdict(c.passed, "FAIL"),
        ]);
    }
    t
}

/// The FEM against the ring BEM.
pub(crate) fn fem_table(comparison: &ComparisonReport) -> Table {
    let mut t = Table::new(
        "FEM against the ring BEM at the default tolerance",
        vec![
            Column::text("punch", "punch"),
            Column::text("state", "state"),
            Column::number(
                "relative_difference",
                "rel. diff",
                Format::SignedScientific(2),
            ),
            Column::number("fem_value", "FEM gamma/gamma2", Format::Fixed(10)),
            Column::number("eps_difference", "eps diff", Format::SignedScientific(2)),
            Column::number(
                "outer_difference",
                "c/a diff (band)",
                Format::SignedScientific(2),
            ),
            Column::number("fem_estimate", "FEM estimate", Format::Scientific(1)),
            Column::number("dofs", "dofs", Format::Fixed(0)),
            Column::number("wall_s", "time (one run)", Format::Fixed(2)).with_unit("s"),
            Column::text("mesh", "mesh"),
            Column::text("verdict", "verdict"),
        ],
    );
    for c in &comparison.fem {
        t.push(vec![
            c.punch.to_string().into(),
            c.prescribed.clone().into(),
            c.relative_difference.into(),
            c.fem_value.into(),
            c.eps_difference.into(),
            c.outer_difference.into(),
            c.fem_error_estimate.into(),
            (c.dofs as f64).into(),
            c.fem_wall_s.into(),
            c.mesh.clone().into(),
            verdict(c.agrees, "FAIL"),
        ]);
    }
    t
}

/// Human-readable tables: [`reference_table`], [`identity_table`], [`fem_table`] and the count of
/// verdicts.
pub fn render(report: &ComparisonReport) -> String {
    let mut out = format!(
        "Ring BEM (the yardstick) against the analytic references; tolerance {:.0e}.\n\
         rel. difference = (ring-bem - reference)/reference; verdicts where the reference declares \
         a bound.\n",
        report.tolerance
    );
    out += &reference_table(report).to_terminal();
    out += "\nNo reference involved: docs/conventions.md facts 6 and 7, full-contact limits.\n";
    out += &identity_table(report).to_terminal();
    out += "\nFEM (P2, default tolerance, on the meshes named in the mesh column) against the \
            ring BEM; agree when |diff| <= U_fem + U_bem (value relative, eps absolute).\n";
    out += &fem_table(report).to_terminal();
    let checked = report
        .rows
        .iter()
        .flat_map(|r| &r.comparisons)
        .filter(|c| c.agrees.is_some())
        .count()
        + report.identities.len()
        + report.fem.len();
    out += &format!(
        "\n{checked} checks with a verdict, {} failed.\n",
        report.failures()
    );
    out
}
