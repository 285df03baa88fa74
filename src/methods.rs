//! Every solver behind one interface: a scene goes in, a solution comes out.
//!
//! The methods so far: the ring BEM (the yardstick) and the analytic references. Each turns the
//! dimensionless state it computes into physical units here, with
//! `F = 2 E* d a γ` (flat punches) and `d = h γ1`, `F = 2 E* h a γ2` (concave punches).

use std::time::Instant;

use serde::Serialize;

use std::path::PathBuf;

use crate::bem::grid::GridLoad;
use crate::bem::ring_contact::{self, RingBemSolver, RingState};
use crate::bem::{grid_contact, grid_estimate};
use crate::discretisation::far_field::FarField;
use crate::error::{Error, Result};
use crate::fem::solver::{self as fem_solver, FemLoad, FemOptions};
use crate::mesh::triangulation::Degree;
use crate::numerics::roots::find_root;
use crate::punch::{Contact, PunchKind};
use crate::reference::{self, power_law, Quantity, ReferenceValue};
use crate::scene::{Load, Scene};
use crate::solution::{FemProvenance, PressureSample, Solution};

/// The methods `verify solve --method` accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Axisymmetric ring-element BEM, exact elliptic kernel, Gauss-Chebyshev collocation.
    RingBem,
    /// The most trusted analytic reference valid at the state (exact, series, asymptote, fit).
    Reference,
    /// Axisymmetric finite elements (P1/P2/P3 triangles) on committed meshes, then meshes gmsh makes for the scene.
    Fem,
    /// The paper's 3-D FFT BEM on a square grid (Polonsky-Keer), `--grid N`.
    GridBem,
    /// The cheapest method whose own error estimate meets the tolerance (`--tol`): the ring BEM,
    /// then the FEM, then an analytic reference with an error bound.
    Auto,
}

impl Method {
    /// Name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::RingBem => ring_contact::METHOD,
            Method::Reference => "reference",
            Method::Fem => fem_solver::METHOD,
            Method::GridBem => crate::bem::grid::METHOD,
            Method::Auto => "auto",
        }
    }
}

/// Options that only some methods use.
#[derive(Clone, Debug, Default)]
pub struct MethodOptions {
    /// FEM: a mesh file instead of the committed family.
    pub mesh: Option<PathBuf>,
    /// FEM: element degree (default quadratic).
    pub degree: Option<Degree>,
    /// Grid BEM: cells per side (default 256).
    pub grid: Option<usize>,
    /// Grid BEM, torus only: half-size `L` of the square `[-L, L]²` in units of `a` (default:
    /// sized from a coarse solve; the other punches' grid is their own `[-a, a]²`).
    pub grid_extent: Option<f64>,
    /// Grid BEM: solve the requested grid alone, without the coarser levels of its error
    /// estimate (the paper's method as the peer codes run it; for timing it against them).
    pub grid_without_estimate: bool,
    /// FEM: write the final displacement field as VTK (`.vtu`) here.
    pub vtu: Option<PathBuf>,
    /// FEM: the condition on the far arc (default [`FarField::Boussinesq`]).
    pub far_field: Option<FarField>,
}

/// Solve `scene` with `method`.
pub fn solve(scene: &Scene, method: Method) -> Result<Solution> {
    solve_with(scene, method, &MethodOptions::default())
}

/// Solve `scene` with `method` and method-specific options.
pub fn solve_with(scene: &Scene, method: Method, options: &MethodOptions) -> Result<Solution> {
    if method != Method::Fem && (options.mesh.is_some() || options.degree.is_some()) {
        return Err(Error::Unsupported {
            method: method.name().into(),
            reason: "--mesh and --degree apply to --method fem only".into(),
        });
    }
    if method != Method::Fem && method != Method::Auto && options.vtu.is_some() {
        return Err(Error::Unsupported {
            method: method.name().into(),
            reason: "--vtu writes the FEM's displacement field: use --method fem".into(),
        });
    }
    if method != Method::Fem && options.far_field.is_some() {
        return Err(Error::Unsupported {
            method: method.name().into(),
            reason: "--far-field sets the FEM's truncated domain: use --method fem".into(),
        });
    }
    if method != Method::GridBem && options.grid.is_some() {
        return Err(Error::Unsupported {
            method: method.name().into(),
            reason: "--grid applies to --method grid-bem only".into(),
        });
    }
    if method != Method::GridBem && options.grid_without_estimate {
        return Err(Error::Unsupported {
            method: method.name().into(),
            reason: "--no-grid-estimate applies to --method grid-bem only".into(),
        });
    }
    if options.grid_extent.is_some()
        && (method != Method::GridBem || !scene.punch.kind.is_free_band())
    {
        return Err(Error::Unsupported {
            method: method.name().into(),
            reason: "--grid-extent sets the square of the torus's grid: use --punch torus \
                     --method grid-bem (the other punches' grid covers their own [-a, a]²)"
                .into(),
        });
    }
    let solution = match method {
        Method::RingBem => solve_ring_bem(scene, &RingBemSolver::new()),
        Method::Reference => solve_reference(scene),
        Method::Fem => solve_fem(scene, options),
        Method::GridBem => solve_grid_bem(
            scene,
            options.grid.unwrap_or(DEFAULT_GRID),
            options.grid_extent,
            !options.grid_without_estimate,
        ),
        Method::Auto => solve_auto(scene, options),
    }?;
    // Every state is checked before anyone sees it (never a number that cannot exist).
    solution.check_plausible()?;
    Ok(solution)
}

/// The order `auto` tries methods in: the axisymmetric ones by cost (ring BEM ~1 ms,
/// FEM 0.1-5 s; the grid BEM, first order, is never the cheapest to certify a tolerance),
/// then, as the last resort where both decline, the analytic references with an error bound
/// (the flat annulus beyond the ring BEM's `b/a = 0.9999`, whose rim the FEM cannot refine
/// enough for a tight tolerance, is the narrow-ring asymptote's, bound `δ² ln(16/δ)`): the
/// independent discretisations first wherever they apply.
const AUTO_ORDER: [Method; 3] = [Method::RingBem, Method::Fem, Method::Reference];

/// Pick the cheapest method whose own error estimate meets the scene's tolerance (default 1e-6).
pub fn solve_auto(scene: &Scene, options: &MethodOptions) -> Result<Solution> {
    let tolerance = scene.tolerance.unwrap_or(1e-6);
    let scene = Scene {
        tolerance: Some(tolerance),
        ..scene.clone()
    };
    let mut tried = Vec::new();
    for method in AUTO_ORDER {
        match solve_with(&scene, method, options) {
            Ok(mut s) if s.error_estimate.is_some_and(|e| e <= tolerance) => {
                s.selection = Some(format!(
                    "auto: {} is the cheapest method whose error estimate ({:.1e}) meets the tolerance {tolerance:.1e}{}",
                    method.name(),
                    s.error_estimate.unwrap_or(f64::NAN),
                    if tried.is_empty() { String::new() } else { format!(" (declined: {})", tried.join("; ")) }
                ));
                return Ok(s);
            }
            Ok(s) => tried.push(match s.error_estimate {
                Some(e) => format!("{} estimate {e:.1e}", method.name()),
                None => format!("{}: no error estimate", method.name()),
            }),
            Err(e) => tried.push(format!("{}: {e}", method.name())),
        }
    }
    Err(Error::NoConvergence {
        method: "auto".into(),
        reason: format!(
            "no method meets the tolerance {tolerance:.1e}: {}",
            tried.join("; ")
        ),
    })
}

/// Default cells per side of the grid BEM.
pub const DEFAULT_GRID: usize = 256;

/// Solve with the square-grid FFT BEM on `n x n` cells; `extent`: the torus's square half-size
/// `L/a` (see [`MethodOptions::grid_extent`]). Its convergence criterion is the complementarity
/// residual (tolerance 1e-10, or the scene's if tighter); its discretisation error is estimated
/// from the same problem on `n/2` and `n/4` cells over the same square
/// ([`crate::bem::grid_estimate`]); where a coarser level cannot be solved (a ring too narrow
/// for it, `n/4 < 8`) the solution has no estimate and says why. `estimated: false` skips the
/// coarser levels.
pub fn solve_grid_bem(
    scene: &Scene,
    n: usize,
    extent: Option<f64>,
    estimated: bool,
) -> Result<Solution> {
    let kind = scene.punch.kind.clone();
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    let h = scene.punch.hole_depth;
    let load = match (kind.is_concave(), scene.load) {
        (false, _) => GridLoad::Depth(1.0),
        (_, Load::Depth(d)) => GridLoad::Depth(d / h),
        (_, Load::Force(f)) => GridLoad::Force(f / (2.0 * es * h * a)),
        (_, Load::ContactRatio(_)) => {
            return Err(Error::Unsupported {
                method: crate::bem::grid::METHOD.into(),
                reason: "the grid BEM takes a depth or a force (use the ring BEM for --eps)".into(),
            })
        }
    };
    let tolerance = scene.tolerance.unwrap_or(1e-10).min(1e-10);
    let eps = scene.punch.inner_ratio();
    let start = Instant::now();
    let state = match extent {
        Some(half_size) => grid_contact::solve_torus_on_square(n, half_size, load, tolerance)?,
        None => grid_contact::solve(kind.clone(), eps, n, load, tolerance)?,
    };
    let free_edges: &[fn(&grid_contact::GridState) -> f64] = match kind.contact() {
        Contact::FreeBand => &[grid_estimate::inner_edge, grid_estimate::outer_edge],
        Contact::RimAndFreeInner => &[grid_estimate::inner_edge],
        Contact::Disk | Contact::FixedAnnulus => &[],
    };
    let estimate = estimated.then(|| {
        grid_estimate::estimate(&state, free_edges, |m| {
            if kind.is_free_band() {
                grid_contact::solve_torus_on_square(m, state.square_half_size, load, tolerance)
            } else {
                grid_contact::solve(kind.clone(), eps, m, load, tolerance)
            }
        })
    });
    let estimate_note = match &estimate {
        None => "no error estimate (--no-grid-estimate: the requested grid alone)".to_string(),
        Some(Ok(_)) => format!(
            "error estimate from {} and {} cells per side on the same square (first order, \
             safety factor {})",
            n / grid_estimate::COARSENING[0],
            n / grid_estimate::COARSENING[1],
            grid_estimate::SAFETY
        ),
        Some(Err(e)) => format!("no error estimate ({e})"),
    };
    Ok(Solution {
        outer_radius: state.outer_edge * a,
        unknowns: n * n,
        iterations: state.iterations,
        complementarity_residual: Some(state.residual),
        grid: Some(n),
        grid_extent: Some(state.square_half_size * a),
        error_estimate: estimate.and_then(Result::ok),
        provenance: format!(
            "square-grid FFT BEM (Love kernel, 2N zero padding, Polonsky-Keer CG), {n} x {n} cells on \
             [-L, L]^2 with L = {} a, {} contact cells, {} iterations, complementarity residual {:.1e}; \
             {estimate_note}",
            crate::error::show(state.square_half_size), state.contact_cells, state.iterations, state.residual
        ),
        ..base(
            scene,
            crate::bem::grid::METHOD,
            state.eps,
            (state.gamma, state.gamma1, state.gamma2),
            start.elapsed().as_secs_f64(),
        )?
    })
}

/// Solve with the finite-element method.
pub fn solve_fem(scene: &Scene, options: &MethodOptions) -> Result<Solution> {
    let kind = scene.punch.kind.clone();
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    let h = scene.punch.hole_depth;
    let load = match (kind.is_concave(), scene.load) {
        (false, _) => FemLoad::Flat,
        (_, Load::Depth(d)) => FemLoad::ConcaveDepth(d / h),
        (_, Load::Force(f)) => FemLoad::ConcaveForce(f / (2.0 * es * h * a)),
        (_, Load::ContactRatio(_)) => {
            return Err(Error::Unsupported {
                method: fem_solver::METHOD.into(),
                reason:
                    "the FEM takes a depth or a force; the contact ratio is one of its outputs \
                         (use --depth or --force, or the ring BEM for --eps)"
                        .into(),
            })
        }
    };
    let tolerance = scene.tolerance.unwrap_or(fem_solver::DEFAULT_TOLERANCE);
    let fem_options = FemOptions {
        linear_solver: Default::default(),
        // A given mesh keeps the quadratic default; the ladder picks by tolerance.
        degree: options.degree.unwrap_or(if options.mesh.is_some() {
            Degree::Quadratic
        } else {
            fem_solver::default_degree(tolerance)
        }),
        tolerance,
        mesh: options.mesh.clone(),
        poisson_ratio: scene.material.poisson_ratio.unwrap_or(0.0),
        far_field: options.far_field.unwrap_or(FarField::Boussinesq),
    };
    let state = fem_solver::solve(kind.clone(), scene.punch.inner_ratio(), load, &fem_options)?;
    let outer_radius = state.outer_edge.map_or(a, |c| c * a);
    if let Some(path) = &options.vtu {
        crate::discretisation::vtu::write_vtu(path, &state.field.mesh, &state.field.displacement)?;
    }
    Ok(Solution {
        outer_radius,
        error_estimate: state.error_estimate,
        unknowns: state.dofs,
        iterations: state.iterations,
        fem: Some(FemProvenance {
            dofs: state.dofs,
            mesh: state.mesh.clone(),
            mesh_sha256: state.mesh_sha256.clone(),
            mesh_origin: state.mesh_origin,
            gmsh_version: state.gmsh_version.clone(),
            mesh_refinement: state.mesh_refinement.clone(),
            far_field: state.far_field,
            fem_timings: state.timings,
            degree: state.degree as u8,
        }),
        complementarity_residual: kind.is_concave().then_some(state.complementarity_residual),
        edge_conditioning: state.edge_conditioning,
        provenance: format!(
            "axisymmetric FEM, P{} triangles, {} dofs on {} ({}{}, sha256 {}){}, domain radius {:.3e} a with {} far field \
             (truncation bias {:.1e} included in the estimate){}",
            state.degree as u8,
            state.dofs,
            state.mesh,
            serde_json::to_value(state.mesh_origin)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_default(),
            state
                .gmsh_version
                .as_ref()
                .map(|v| format!(" by gmsh {v}"))
                .unwrap_or_default(),
            &state.mesh_sha256[..16.min(state.mesh_sha256.len())],
            state
                .mesh_refinement
                .as_ref()
                .map(|r| format!(" {r}"))
                .unwrap_or_default(),
            state.domain_radius,
            state.far_field.describe(),
            state.truncation_bias,
            if state.error_estimate.is_some() {
                ", estimate from the previous refinement level"
            } else {
                ", single mesh: no error estimate"
            }
        ),
        ..base(
            scene,
            fem_solver::METHOD,
            state.eps,
            (state.gamma, state.gamma1, state.gamma2),
            state.wall_s,
        )?
    })
}

/// Solve with a given ring-BEM solver (reuse it across many scenes to keep its quadrature).
pub fn solve_ring_bem(scene: &Scene, solver: &RingBemSolver) -> Result<Solution> {
    let start = Instant::now();
    let factorised = solver.factorisations();
    let kind = scene.punch.kind.clone();
    let tol = scene.tolerance.unwrap_or(crate::scene::DEFAULT_TOLERANCE);
    let h = scene.punch.hole_depth;
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    let state = match (kind.is_concave(), scene.load) {
        (false, _) => solver.flat(scene.punch.inner_ratio(), tol)?,
        (_, Load::ContactRatio(eps)) => solver.concave_at_ratio(&kind, eps, tol)?,
        (_, Load::Depth(d)) => solver.concave_at_depth(&kind, d / h, tol)?,
        (_, Load::Force(f)) => solver.concave_at_force(&kind, f / (2.0 * es * h * a), tol)?,
    };
    let wall_s = start.elapsed().as_secs_f64();
    let iterations = solver.factorisations() - factorised;
    Ok(Solution {
        iterations,
        provenance: format!(
            "ring BEM, Gauss-Chebyshev collocation, N = {} nodes, {iterations} factorisations, \
             self-convergence estimate against the previous ladder rung",
            state.unknowns
        ),
        ..ring_state_to_solution(scene, &state, wall_s)?
    })
}

/// A solution of `scene` by `method` with the physical state filled in from the dimensionless
/// results and every method-specific field empty (to be overridden with struct-update syntax).
fn base(
    scene: &Scene,
    method: &str,
    eps: f64,
    (gamma, gamma1, gamma2): (Option<f64>, Option<f64>, Option<f64>),
    wall_s: f64,
) -> Result<Solution> {
    let (depth, force) = depth_force(scene, gamma, gamma1, gamma2)?;
    let a = scene.punch.rim_radius;
    Ok(Solution {
        punch: scene.punch.kind.clone(),
        method: method.to_string(),
        eps,
        depth,
        force,
        inner_radius: eps * a,
        rim_radius: a,
        outer_radius: a,
        tube_radius: scene.punch.tube_radius(),
        gamma,
        gamma1,
        gamma2,
        stress_intensity_rim: None,
        stress_intensity_inner: None,
        error_estimate: None,
        wall_s,
        unknowns: 0,
        iterations: 0,
        fem: None,
        complementarity_residual: None,
        edge_conditioning: None,
        grid: None,
        grid_extent: None,
        selection: None,
        pressure: Vec::new(),
        provenance: String::new(),
    })
}

/// Physical depth and force from the dimensionless results: flat punches by
/// [`flat_depth_force`], concave punches by `d = h γ1`, `F = 2 E* h a γ2`.
fn depth_force(
    scene: &Scene,
    gamma: Option<f64>,
    gamma1: Option<f64>,
    gamma2: Option<f64>,
) -> Result<(f64, f64)> {
    match gamma {
        Some(gamma) => flat_depth_force(scene, gamma),
        None => {
            let (h, a, es) = (
                scene.punch.hole_depth,
                scene.punch.rim_radius,
                scene.material.effective_modulus,
            );
            Ok((
                h * gamma1.unwrap_or(f64::NAN),
                2.0 * es * h * a * gamma2.unwrap_or(f64::NAN),
            ))
        }
    }
}

/// Physical depth and force of a flat punch with `F = 2 E* d a γ`, under the scene's load.
fn flat_depth_force(scene: &Scene, gamma: f64) -> Result<(f64, f64)> {
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    match scene.load {
        Load::Depth(d) => Ok((d, 2.0 * es * d * a * gamma)),
        Load::Force(f) => Ok((f / (2.0 * es * a * gamma), f)),
        Load::ContactRatio(_) => Err(Error::invalid(
            "load.contact_ratio",
            "applies only to cone and sphere",
        )),
    }
}

fn ring_state_to_solution(scene: &Scene, state: &RingState, wall_s: f64) -> Result<Solution> {
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    let base = base(
        scene,
        ring_contact::METHOD,
        state.eps,
        (state.gamma, state.gamma1, state.gamma2),
        wall_s,
    )?;
    // Pressures and intensities scale with the depth (flat punches) or the hole depth (concave).
    let length = if state.gamma.is_some() {
        base.depth
    } else {
        scene.punch.hole_depth
    };
    let pressure_scale = es * length / a;
    let k_scale = es * length / a.sqrt();
    Ok(Solution {
        outer_radius: state.outer_edge * a,
        // The torus has no rim (its outer edge is free: K = 0 there).
        stress_intensity_rim: scene
            .punch
            .kind
            .has_rim()
            .then_some(state.rim_stress_intensity * k_scale),
        stress_intensity_inner: Some(state.inner_stress_intensity * k_scale),
        error_estimate: Some(state.error_estimate),
        unknowns: state.unknowns,
        pressure: state
            .pressure
            .iter()
            .map(|&(r, p)| PressureSample {
                r: r * a,
                p: p * pressure_scale,
            })
            .collect(),
        ..base
    })
}

/// The most trusted reference for `quantity` at `eps`, or an out-of-range error.
fn best_reference(
    quantity: Quantity,
    eps: f64,
) -> Result<(ReferenceValue, &'static str, &'static str)> {
    reference::valid_references(quantity, eps)
        .first()
        .map(|r| {
            (
                r.evaluate(eps).expect("valid range checked"),
                r.name,
                r.source,
            )
        })
        .ok_or_else(|| Error::OutOfRange {
            method: "reference".into(),
            reason: format!(
                "no analytic reference for {quantity:?} is valid at eps = {}",
                crate::error::show(eps)
            ),
        })
}

/// Solve with the analytic references (exact results, series, asymptotes, the paper's fits).
pub fn solve_reference(scene: &Scene) -> Result<Solution> {
    let start = Instant::now();
    let kind = &scene.punch.kind;
    let a = scene.punch.rim_radius;
    let es = scene.material.effective_modulus;
    let h = scene.punch.hole_depth;
    // Every field below is set from the reference that applies.
    let mut solution = base(scene, "reference", 0.0, (None, None, None), 0.0)?;
    match reference_family(kind)? {
        ReferenceFamily::Flat => {
            let eps = scene.punch.inner_ratio();
            let (value, name, source) = best_reference(Quantity::FlatGamma, eps)?;
            let (d, f) = flat_depth_force(scene, value.value)?;
            solution.eps = eps;
            solution.inner_radius = eps * a;
            solution.gamma = Some(value.value);
            solution.depth = d;
            solution.force = f;
            solution.error_estimate = value.error_bound.map(|b| b / value.value);
            solution.method = format!("reference:{name}");
            solution.provenance = source.to_string();
        }
        family @ (ReferenceFamily::Cone | ReferenceFamily::Sphere) => {
            let sphere = matches!(family, ReferenceFamily::Sphere);
            let (q1, q2) = if !sphere {
                (Quantity::ConeGamma1, Quantity::ConeGamma2)
            } else {
                (Quantity::SphereGamma1, Quantity::SphereGamma2)
            };
            let full_contact = match scene.load {
                Load::Depth(d) if sphere => {
                    reference::sphere_full_contact_gamma2(d / h).map(|g2| (d / h, g2))
                }
                Load::Force(f) if sphere => {
                    let g2 = f / (2.0 * es * h * a);
                    (g2 >= 8.0 / 3.0).then_some((g2 + 1.0 / 3.0, g2))
                }
                _ => None,
            };
            let (eps, g1, g2, name, source, bound) = if let Some((g1, g2)) = full_contact {
                (
                    0.0,
                    g1,
                    g2,
                    "sphere-full-contact",
                    "MDR: F = 2 E* a (d - h/3) for d >= 3h",
                    Some(0.0),
                )
            } else {
                let eps = match scene.load {
                    Load::ContactRatio(eps) => eps,
                    Load::Depth(d) => invert_reference(q1, d / h)?,
                    Load::Force(f) => invert_reference(q2, f / (2.0 * es * h * a))?,
                };
                let (v1, name, source) = best_reference(q1, eps)?;
                let (v2, _, _) = best_reference(q2, eps)?;
                let bound = match (v1.error_bound, v2.error_bound) {
                    (Some(b1), Some(b2)) => Some((b1 / v1.value).max(b2 / v2.value)),
                    _ => None,
                };
                (eps, v1.value, v2.value, name, source, bound)
            };
            solution.eps = eps;
            solution.inner_radius = eps * a;
            solution.gamma1 = Some(g1);
            solution.gamma2 = Some(g2);
            solution.depth = h * g1;
            solution.force = 2.0 * es * h * a * g2;
            solution.error_estimate = bound;
            solution.method = format!("reference:{name}");
            solution.provenance = source.to_string();
        }
        ReferenceFamily::Power(n) => {
            let full_contact = match scene.load {
                Load::Depth(d) => power_law::full_contact_gamma2(n, d / h).map(|g2| (d / h, g2)),
                Load::Force(f) => {
                    let g2 = f / (2.0 * es * h * a);
                    power_law::full_contact_gamma1(n, g2).map(|g1| (g1, g2))
                }
                Load::ContactRatio(_) => None,
            };
            let Some((g1, g2)) = full_contact else {
                return Err(Error::OutOfRange {
                    method: "reference".into(),
                    reason: format!(
                        "the power-law punch has a closed form only in full contact (n > 1 and \
                         d >= h (1 + κ_n/(n - 1)){}); its annular contact is the ring BEM's \
                         (--method ring-bem)",
                        power_law::closure_depth(n)
                            .map(|d| format!(", here d >= {} h", crate::error::show(d)))
                            .unwrap_or_default()
                    ),
                });
            };
            solution.eps = 0.0;
            solution.inner_radius = 0.0;
            solution.gamma1 = Some(g1);
            solution.gamma2 = Some(g2);
            solution.depth = h * g1;
            solution.force = 2.0 * es * h * a * g2;
            solution.error_estimate = Some(0.0);
            solution.method = "reference:power-full-contact".into();
            solution.provenance = "MDR: F = 2 E* a ((d - h) + κ_n h/(n + 1)) for \
                                   d >= h (1 + κ_n/(n - 1)), κ_n = (n √π/2) Γ(n/2)/Γ((n+1)/2)"
                .into();
        }
    }
    solution.wall_s = start.elapsed().as_secs_f64();
    Ok(solution)
}

/// The closed-form references that hold for a punch, asked of its profile.
enum ReferenceFamily {
    /// The flat circular and annular punch's `γ(b/a)`.
    Flat,
    /// The cone's `γ1`, `γ2` (series and asymptotes).
    Cone,
    /// The sphere's `γ1`, `γ2` and its full contact.
    Sphere,
    /// The power law's full contact (the MDR).
    Power(f64),
}

/// Which [`ReferenceFamily`] holds for `kind`; an error saying why where none does.
fn reference_family(kind: &PunchKind) -> Result<ReferenceFamily> {
    let none = |reason: String| Error::OutOfRange {
        method: "reference".into(),
        reason,
    };
    if !kind.is_concave() {
        return Ok(ReferenceFamily::Flat);
    }
    if kind.tabulated().is_some() {
        return Err(none(format!(
            "the {} punch has no closed form (its full contact is a quadrature of the \
             interpolated profile); it is the ring BEM's (--method ring-bem)",
            kind.name()
        )));
    }
    if kind.is_free_band() {
        return Err(none(format!(
            "the {} has no closed form (its narrow limit, the plane-strain Hertz cylinder, is an \
             asymptote without an error bound); it is the ring BEM's (--method ring-bem)",
            kind.name()
        )));
    }
    match (kind.exponent_parameter(), kind.power_law_exponent()) {
        (Some(n), _) => Ok(ReferenceFamily::Power(n)),
        (None, Some(1.0)) => Ok(ReferenceFamily::Cone),
        (None, Some(2.0)) => Ok(ReferenceFamily::Sphere),
        (None, Some(n)) => Ok(ReferenceFamily::Power(n)),
        (None, None) => Err(none(format!(
            "the {kind} has no closed form here; it is the ring BEM's (--method ring-bem)"
        ))),
    }
}

/// `eps` where the most trusted reference for `quantity` equals `target` (references decrease
/// monotonically in `eps`).
fn invert_reference(quantity: Quantity, target: f64) -> Result<f64> {
    let (lo, hi) = (1e-12, 1.0 - 1e-12);
    find_root(
        |eps| {
            best_reference(quantity, eps)
                .map(|(v, _, _)| v.value - target)
                .map_err(|e| e.to_string())
        },
        lo,
        hi,
        0.5,
        1e-15,
        200,
    )
    .map(|r| r.x)
    .map_err(|e| Error::OutOfRange {
        method: "reference".into(),
        reason: format!(
            "cannot invert {quantity:?} = {} with the references: {e:?}",
            crate::error::show(target)
        ),
    })
}
