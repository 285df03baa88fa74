//! `verify solve`: one scene, one method; with `--batch`, many scenes ([`batch`]); `verify
//! table`: one punch at many states ([`table`], the lists of [`states`]).

pub(super) mod batch;
pub(super) mod states;
pub(super) mod table;

use super::{message, to_json, Reply};
use crate::cli::args::SolveArgs;
use crate::harness::report::table::{readable, Column, Table};
use ringcontact::methods::Degree;
use ringcontact::methods::{self, MethodOptions};
use ringcontact::punch::{Contact, PunchName};
use ringcontact::scene::{Scene, SceneSpec};
use ringcontact::solution::Solution;

/// `verify solve`: the scene from `--scene` and the flags (flags override the file), solved by
/// `--method`; prints the state (or one JSON object). With `--batch FILE`: one scene per line.
pub fn solve(args: SolveArgs) -> Result<Reply, String> {
    if let Some(path) = &args.batch {
        return batch::solve_batch(path, &args);
    }
    let scene = scene_of(&args)?;
    let solution = solve_scene(&scene, &args)?;
    Ok(Reply::ok(if args.json {
        to_json(&solution)?
    } else {
        describe(&scene, &solution).to_terminal()
    }))
}

/// Solve `scene` by `args.method` with the method options of `args` (mesh, degree, grid, ...).
pub(crate) fn solve_scene(scene: &Scene, args: &SolveArgs) -> Result<Solution, String> {
    solve_scene_by(scene, args.method, args)
}

/// Solve `scene` by `method` with the method options of `args`.
pub(crate) fn solve_scene_by(
    scene: &Scene,
    method: methods::Method,
    args: &SolveArgs,
) -> Result<Solution, String> {
    if args.mesh_parameters.is_some() && method != ringcontact::methods::Method::Fem {
        return Err(format!(
            "--mesh-parameters makes a mesh for --method fem only (not {})",
            method.name()
        ));
    }
    let mesh = crate::cli::chosen_mesh(
        args.mesh.as_deref(),
        args.mesh_parameters.as_deref(),
        "verify solve --mesh-parameters",
    )?;
    let options = MethodOptions {
        mesh,
        far_field: args.far_field,
        degree: args.degree.and_then(Degree::from_number),
        grid: args.grid.map(|g| g as usize),
        grid_extent: args.grid_extent,
        grid_without_estimate: args.no_grid_estimate,
        vtu: args.vtu.clone(),
        linear_solver: Some(crate::harness::settings::linear_solver()),
        trace: crate::harness::settings::trace(),
        data: Some(crate::harness::settings::data_paths()),
        progress: crate::harness::progress::fem_progress(),
    };
    methods::solve_with(scene, method, &options).map_err(message)
}

/// The validated scene: the file's (or the defaults), then the flags.
pub(crate) fn scene_of(args: &SolveArgs) -> Result<Scene, String> {
    let mut spec = match &args.scene {
        Some(path) => SceneSpec::from_file(path).map_err(message)?,
        None => SceneSpec::default(),
    };
    if args.punch.is_none() && args.scene.is_none() {
        let parameters: Vec<String> = PunchName::ALL
            .iter()
            .filter_map(|name| {
                let flags = name.summary().flags;
                let rest = flags.strip_prefix(&format!("--punch {name}"))?.trim();
                (!rest.is_empty()).then(|| format!("{name} with {rest}"))
            })
            .collect();
        return Err(format!(
            "give --punch {{{}}} ({}) or --scene FILE",
            PunchName::names(None, "|"),
            parameters.join(", ")
        ));
    }
    spec = spec.shape_named(args.punch, args.exponent);
    if let Some(rho) = args.tube_radius {
        spec = spec.tube_radius(rho);
    }
    if let Some(path) = &args.profile {
        spec = spec.profile(path);
    }
    // --eps fixes the annulus of a flat-faced punch, or prescribes the contact of a concave one.
    if let Some(eps) = args.eps {
        match spec.shape_name().map(PunchName::contact) {
            Some(Contact::Disk) => {
                return Err(format!(
                    "--eps does not apply to the flat circular punch; use --punch {} --eps \
                     B_OVER_A",
                    crate::cli::names_of(Contact::FixedAnnulus)
                ))
            }
            Some(Contact::FixedAnnulus) | None => {}
            Some(_) if args.depth.is_some() || args.force.is_some() => {
                return Err("--eps prescribes the contact of a concave punch; \
                            do not combine it with --depth or --force"
                    .into());
            }
            Some(_) => {}
        }
        spec = spec.eps(eps).map_err(message)?;
    }
    if let Some(d) = args.depth {
        spec = spec.depth(d);
    }
    if let Some(f) = args.force {
        spec = spec.force(f);
    }
    if let Some(tol) = args.tol {
        spec = spec.tolerance(tol);
    }
    spec.validate().map_err(message)
}

/// The solved state as a two-column table: quantity and value (the dimensionless functions
/// `gamma = F/(2 E* d a)`, `gamma1 = d/h`, `gamma2 = F/(2 E* h a)`, the estimate, the model,
/// the cost and the provenance).
pub(crate) fn describe(scene: &Scene, s: &Solution) -> Table {
    let p = &scene.punch;
    let es = scene.material.effective_modulus;
    let geometry = match p.kind.contact() {
        Contact::Disk => format!("a = {}", p.rim_radius),
        Contact::FixedAnnulus => format!("a = {}, b = {}", p.rim_radius, p.inner_radius),
        Contact::FreeBand => format!(
            "a = {}, rho = {}, h = a²/(2 rho) = {}",
            p.rim_radius,
            readable(p.tube_radius().unwrap_or(f64::NAN), 12),
            readable(p.hole_depth, 12)
        ),
        _ => format!("a = {}, h = {}", p.rim_radius, p.hole_depth),
    };
    let mut t = Table::new(
        &format!("{} ({geometry}, E* = {es}) by {}", p.kind, s.method),
        vec![
            Column::text("quantity", "quantity"),
            Column::text("value", "value"),
        ],
    );
    let mut row = |name: &str, value: String| t.push(vec![name.into(), value.into()]);
    row(
        "contact ratio",
        format!("eps = b/a = {}", readable(s.eps, 12)),
    );
    if !p.kind.has_rim() {
        row(
            "contact",
            format!(
                "b = {} to c = {} (both edges free)",
                readable(s.inner_radius, 12),
                readable(s.outer_radius, 12)
            ),
        );
    }
    row("depth", format!("d = {}", readable(s.depth, 12)));
    row("force", format!("F = {}", readable(s.force, 12)));
    if let Some(g) = s.gamma {
        row("gamma", format!("F/(2 E* d a) = {}", readable(g, 15)));
    }
    if let (Some(g1), Some(g2)) = (s.gamma1, s.gamma2) {
        row("gamma1", format!("d/h = {}", readable(g1, 15)));
        row("gamma2", format!("F/(2 E* h a) = {}", readable(g2, 15)));
    }
    if let Some(k) = s.stress_intensity_rim {
        row(
            "K at rim",
            format!("{} (stress x sqrt(length))", readable(k, 12)),
        );
    }
    row(
        "error estimate",
        match s.error_estimate {
            Some(e) => format!("{e:.1e} (relative in gamma's, absolute in eps)"),
            None => "none (the provenance says why)".to_string(),
        },
    );
    if let Some(fem) = &s.fem {
        row(
            "model",
            format!("{} dofs, P{} on {}", fem.dofs, fem.degree, fem.mesh),
        );
    }
    if let Some(k) = s.fem.as_ref().and_then(|fem| fem.edge_conditioning) {
        row(
            "free edge",
            format!("conditioning κ = |db/dd| d = {k:.2} (the edge moves κ times a relative depth change)"),
        );
    }
    if let Some(r) = s.complementarity_residual {
        row(
            "contact",
            format!(
                "{} active-set iterations, complementarity residual {r:.1e}",
                s.iterations
            ),
        );
    }
    row("wall time", format!("{:.3} ms", s.wall_s * 1e3));
    row("provenance", s.provenance.clone());
    if let Some(why) = &s.selection {
        row("selection", why.clone());
    }
    t
}
