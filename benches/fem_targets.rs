//! The FEM's accuracy-and-cost targets: the cone at `d/h` = 0.5, 2, 4, the sphere at
//! 0.5, 1.5, 2.8 and the flat annulus at `b/a` = 0.1, 0.3, 0.5, 0.7, 0.9, 0.97; the power law
//! (`n = 1.5` at `d/h = 1` and 3, `n = 4` at 1), the table punch (the sphere sampled at 21
//! points, `d/h` = 1 and 2.5, `F/(2 E* h a)` = 1) and the torus (`d/h` = 0.1 and 1,
//! `F/(2 E* h a)` = 0.3: both edges free), solved at each tolerance with the default degree,
//! against the ring BEM converged to 1e-11 (an independent discretisation). Each state is solved
//! twice: first with an empty mesh cache (gmsh makes every mesh), then again with the cache
//! filled; both wall times are printed, with the force error, the edges' error (the larger of
//! the inner and, for the torus, the outer edge's) and the FEM's own estimate (which must bound
//! them: `bound` column). The target: every state at `--tol 1e-6` in at most 1 s cached.
//!
//! Run: `cargo bench --bench fem_targets` (tolerances 1e-3 and 1e-6); `FEM_TARGETS_TOLS=1e-8`
//! for others (comma-separated). Needs gmsh (`bash scripts/install_gmsh.sh`).

use std::time::Instant;

mod common;

use ringcontact::bem::ring_contact::RingBemSolver;
use ringcontact::discretisation::far_field::FarField;
use ringcontact::fem::solver::{self, FemLoad, FemOptions};
use ringcontact::punch::{Exponent, PunchKind};

/// A state: `(punch, b/a, load, label)`.
type State = (PunchKind, f64, FemLoad, String);

/// Depth-controlled states of a concave punch at each `d/h`.
fn at_depths(kind: PunchKind, depths: &[f64]) -> Vec<State> {
    depths
        .iter()
        .map(|&d| {
            (
                kind.clone(),
                0.0,
                FemLoad::ConcaveDepth(d),
                format!("{} d/h={d}", name(&kind)),
            )
        })
        .collect()
}

/// Flat annuli at each `b/a`.
fn annuli(ratios: &[f64]) -> Vec<State> {
    ratios
        .iter()
        .map(|&e| {
            let label = format!("flat annulus b/a={e}");
            (PunchKind::FLAT_ANNULUS, e, FemLoad::Flat, label)
        })
        .collect()
}

/// A state's punch as its row names it (a table by its profile, not its path).
fn name(kind: &PunchKind) -> String {
    match kind.piecewise() {
        Some(_) => "table (sphere-21)".to_string(),
        None => kind.to_string(),
    }
}

/// A force-controlled state of `kind`.
fn at_force(kind: PunchKind, force: f64) -> State {
    let label = format!("{} F/(2E*ha)={force}", name(&kind));
    (kind, 0.0, FemLoad::ConcaveForce(force), label)
}

/// The new punches' states: the power law, the table sampled from the sphere, the torus.
fn new_punches() -> Vec<State> {
    let power = |n: f64| PunchKind::power(Exponent::new(n).expect("n > 0"));
    let table = common::sampled_sphere();
    let mut out = at_depths(power(1.5), &[1.0, 3.0]);
    out.extend(at_depths(power(4.0), &[1.0]));
    out.extend(at_depths(table.clone(), &[1.0, 2.5]));
    out.push(at_force(table, 1.0));
    out.extend(at_depths(PunchKind::TORUS, &[0.1, 1.0]));
    out.push(at_force(PunchKind::TORUS, 0.3));
    out
}

/// The 12 target states and the new punches' 9, and with `FEM_TARGETS_EXTRA=1` 17 more:
/// other depths, ratios, the disk, and force control.
fn states() -> Vec<State> {
    let mut out = at_depths(PunchKind::CONE, &[0.5, 2.0, 4.0]);
    out.extend(at_depths(PunchKind::SPHERE, &[0.5, 1.5, 2.8]));
    out.extend(annuli(&[0.1, 0.3, 0.5, 0.7, 0.9, 0.97]));
    out.extend(new_punches());
    if std::env::var_os("FEM_TARGETS_EXTRA").is_some() {
        out.push((PunchKind::FLAT, 0.0, FemLoad::Flat, "flat disk".to_string()));
        out.extend(at_depths(PunchKind::CONE, &[0.1, 1.0, 3.0, 8.0]));
        out.extend(at_depths(PunchKind::SPHERE, &[0.2, 1.0, 2.5, 2.95]));
        out.extend(annuli(&[0.02, 0.2, 0.6, 0.8, 0.95, 0.99]));
        out.push((
            PunchKind::CONE,
            0.0,
            FemLoad::ConcaveForce(1.0),
            "cone F/(2E*ha)=1".to_string(),
        ));
        out.push((
            PunchKind::SPHERE,
            0.0,
            FemLoad::ConcaveForce(0.8),
            "sphere F/(2E*ha)=0.8".to_string(),
        ));
    }
    out
}

/// `(force-like output, inner edge, outer edge)` of the ring BEM at 1e-11.
fn reference(kind: PunchKind, eps: f64, load: FemLoad) -> (f64, f64, f64) {
    let bem = RingBemSolver::new();
    match load {
        FemLoad::Flat => (bem.flat(eps, 1e-11).unwrap().gamma.unwrap(), eps, 1.0),
        FemLoad::ConcaveDepth(d) => {
            let r = bem.concave_at_depth(&kind, d, 1e-11).unwrap();
            (r.gamma2.unwrap(), r.eps, r.outer_edge)
        }
        FemLoad::ConcaveForce(f) => {
            let r = bem.concave_at_force(&kind, f, 1e-11).unwrap();
            (r.gamma1.unwrap(), r.eps, r.outer_edge)
        }
    }
}

fn main() {
    let tolerances: Vec<f64> = std::env::var("FEM_TARGETS_TOLS")
        .unwrap_or_else(|_| "1e-3,1e-6".into())
        .split(',')
        .map(|t| {
            t.trim()
                .parse()
                .expect("FEM_TARGETS_TOLS: comma-separated numbers")
        })
        .collect();
    let cache = std::env::temp_dir().join(format!("ringcontact-targets-{}", std::process::id()));
    let data = ringcontact::mesh::files::DataPaths {
        cache: cache.clone(),
        ..Default::default()
    };
    // Find gmsh once (its version probe is per process, not per state).
    let probe = Instant::now();
    ringcontact::mesh::gmsh::Gmsh::get(&data, "the targets benchmark").expect("gmsh is needed");
    println!(
        "gmsh found in {:.3} s (once per process); mesh cache {}",
        probe.elapsed().as_secs_f64(),
        cache.display()
    );
    for &tolerance in &tolerances {
        let degree = solver::default_degree(&data, tolerance);
        println!("\n--tol {tolerance:e} (default degree P{})", degree as u8);
        println!(
            "{:<32} {:>9} {:>9} {:>8} {:>5} {:>9} {:>9} {:>9}",
            "state", "force err", "edge err", "estimate", "bound", "unknowns", "gmsh s", "cached s"
        );
        let (mut worst_cached, mut worst_gmsh, mut all_bounded) = (0.0f64, 0.0f64, true);
        for (kind, eps, load, label) in states() {
            let (force_ref, eps_ref, outer_ref) = reference(kind.clone(), eps, load);
            let options = FemOptions {
                // As `verify` does: the environment's backend, else the built-in one.
                linear_solver: std::env::var(ringcontact::sparse::ENVIRONMENT_VARIABLE)
                    .ok()
                    .and_then(|name| name.parse().ok())
                    .unwrap_or_default(),
                trace: std::env::var_os("RINGCONTACT_TRACE").is_some(),
                data: data.clone(),
                progress: Default::default(),
                degree,
                tolerance,
                mesh: None,
                poisson_ratio: 0.0,
                far_field: FarField::Boussinesq,
            };
            let fresh = solver::solve(kind.clone(), eps, load, &options);
            // Below 1e-7 a state takes tens of seconds: one run, its cached time not measured.
            let once = tolerance < 1e-7;
            let cached = if once {
                None
            } else {
                Some(solver::solve(kind, eps, load, &options))
            };
            let (fresh, state) = match (fresh, cached) {
                (Ok(f), None) => (f.clone(), f),
                (Ok(f), Some(Ok(c))) => (f, c),
                (Err(e), _) | (_, Some(Err(e))) => {
                    println!("{label:<32} error: {e}");
                    all_bounded = false;
                    continue;
                }
            };
            // The output that is not prescribed: γ (flat), γ2 (depth given), γ1 (force given).
            let force = match load {
                FemLoad::Flat => state.gamma,
                FemLoad::ConcaveDepth(_) => state.gamma2,
                FemLoad::ConcaveForce(_) => state.gamma1,
            }
            .unwrap();
            let force_error = (force - force_ref).abs() / force_ref;
            // The located edges: the inner one, and the torus's outer one (a rim's is fixed).
            let eps_error = (state.eps - eps_ref)
                .abs()
                .max(state.outer_edge.map_or(0.0, |c| (c - outer_ref).abs()));
            let estimate = state.error_estimate.unwrap_or(f64::NAN);
            let bounded = force_error <= estimate && eps_error <= estimate;
            all_bounded &= bounded;
            if !once {
                worst_cached = worst_cached.max(state.wall_s);
            }
            worst_gmsh = worst_gmsh.max(fresh.wall_s);
            println!(
                "{label:<32} {force_error:>9.1e} {eps_error:>9.1e} {estimate:>8.1e} {:>5} {:>9} {:>9.3} {:>9}",
                if bounded { "yes" } else { "NO" },
                state.dofs,
                fresh.wall_s,
                if once {
                    "-".to_string()
                } else {
                    format!("{:.3}", state.wall_s)
                }
            );
        }
        println!(
            "worst wall time: {worst_gmsh:.3} s with gmsh meshing, {worst_cached:.3} s cached; \
             estimate bounds every error: {}",
            if all_bounded { "yes" } else { "NO" }
        );
    }
    let _ = std::fs::remove_dir_all(&cache);
}
