//! The commands around meshes and FEniCSx: `fenicsx` (stored results), `export` (the assembled
//! operator, and its comparison with FEniCSx's) and `mesh` (a gmsh mesh of the adapted family).

use super::{message, to_json, Reply};
use crate::cli::args::{ExportArgs, FenicsxArgs, MeshArgs};
use crate::harness::records::fenicsx;
use crate::harness::records::operator;
use ringcontact::discretisation::export::export_mesh;
use ringcontact::mesh::provider::{self, MeshRequest};
use ringcontact::methods::Degree;

/// `verify fenicsx`: every stored FEniCSx result against our FEM, and the stored operator
/// comparisons (`--operators`: those alone).
pub fn fenicsx(args: FenicsxArgs) -> Result<Reply, String> {
    let operators = operator::load_records().map_err(message)?;
    let operators_met = operator::failures(&operators) == 0;
    if args.operators {
        let text = if args.json {
            to_json(&operators)?
        } else {
            operator::render_records(&operators)
        };
        return Ok(Reply::verdict(text, operators_met));
    }
    let rows = fenicsx::run_with(args.large).map_err(message)?;
    let success = fenicsx::failures(&rows) == 0 && operators_met;
    let text = if args.json {
        to_json(&rows)?
    } else {
        fenicsx::render(&rows) + "\n" + &operator::render_records(&operators)
    };
    Ok(Reply::verdict(text, success))
}

/// `verify export`: write our assembled system; with `--compare`, compare it with FEniCSx's
/// (fails above the goal of 1e-12).
pub fn export(args: ExportArgs) -> Result<Reply, String> {
    let degree = Degree::from_number(args.degree)
        .ok_or_else(|| format!("--degree {}: need 1, 2 or 3", args.degree))?;
    if args.json && args.compare.is_none() {
        return Err("--json prints the comparison: give --compare DIR as well".into());
    }
    let mesh = crate::cli::chosen_mesh(
        args.mesh.as_deref(),
        args.mesh_parameters.as_deref(),
        "verify export --mesh-parameters",
    )?
    .ok_or("give --mesh FILE or --mesh-parameters NAME=VALUE,...")?;
    // With --compare and no --out, our files go to a scratch directory removed at the end.
    let scratch = args
        .out
        .is_none()
        .then(|| std::env::temp_dir().join(format!("ringcontact-export-{}", std::process::id())));
    let out = args
        .out
        .clone()
        .or_else(|| scratch.clone())
        .unwrap_or_default();
    let result = export_and_compare(&args, &mesh, degree, &out);
    if let Some(dir) = scratch {
        let _ = std::fs::remove_dir_all(dir);
    }
    result
}

/// The body of [`export`]: write into `out`, compare with `--compare`'s directory if given.
fn export_and_compare(
    args: &ExportArgs,
    mesh: &std::path::Path,
    degree: Degree,
    out: &std::path::Path,
) -> Result<Reply, String> {
    let written = export_mesh(mesh, degree, out).map_err(message)?;
    let mut text = String::new();
    if !args.json && args.out.is_some() {
        for path in &written {
            text += &format!("wrote {}\n", path.display());
        }
    }
    let Some(fenicsx_dir) = &args.compare else {
        return Ok(Reply::ok(text));
    };
    let comparison = operator::compare_operator(mesh, degree, fenicsx_dir).map_err(message)?;
    let met = comparison.meets_goal();
    text += &if args.json {
        to_json(&comparison)?
    } else {
        operator::render(&[comparison])
    };
    Ok(Reply::verdict(text, met))
}

/// `verify mesh`: make (or find in the cache) a mesh of the adapted family and print one JSON
/// object naming it.
pub fn mesh(args: MeshArgs) -> Result<Reply, String> {
    if let Some(text) = &args.parameters {
        let parameters = provider::parse_parameters(text).map_err(message)?;
        let provided = provider::generate(
            &crate::harness::settings::data_paths(),
            &parameters,
            "verify mesh --parameters",
        )
        .map_err(message)?;
        return describe_mesh(&provided, None, &parameters);
    }
    if !(0.0..1.0).contains(&args.eps) {
        return Err(format!("--eps {}: need 0 <= b/a < 1", args.eps));
    }
    let levels = provider::ADAPTED_MIN_LEVEL..=provider::ADAPTED_MAX_LEVEL;
    if !levels.contains(&args.level) {
        return Err(format!(
            "--level {}: the adapted family has levels {} to {}",
            args.level,
            levels.start(),
            levels.end()
        ));
    }
    if !(args.edge_uncertainty >= 0.0 && args.edge_uncertainty < 1.0) {
        return Err(format!(
            "--edge-uncertainty {}: need 0 <= uncertainty < 1 (units of a)",
            args.edge_uncertainty
        ));
    }
    if let Some(b) = args.free_edge {
        if !(0.0..1.0).contains(&b) {
            return Err(format!("--free-edge {b}: need 0 <= b/a < 1"));
        }
        if b < args.eps {
            return Err(format!(
                "--free-edge {b} lies in the hole of the contact line, which starts at --eps {}: \
                 a free edge is located on the contact line",
                args.eps
            ));
        }
    }
    if let Some(tol) = args.tol {
        if !(tol > 0.0 && tol < 1.0) {
            return Err(format!("--tol {tol}: need 0 < tolerance < 1"));
        }
    }
    let target = args.tol.map(|tolerance| provider::SizeTarget {
        tolerance,
        degree: args.degree as usize,
    });
    // The printed parameters are those of the request, so that they remake its mesh.
    let free_edge = args.free_edge.filter(|&b| b > 0.0);
    let request = MeshRequest::Adapted {
        contact_start: args.eps,
        level: args.level,
        free_edge,
        edge_uncertainty: args.edge_uncertainty,
        target,
    };
    let provided = provider::provide(
        &crate::harness::settings::data_paths(),
        &request,
        "verify mesh",
    )
    .map_err(message)?;
    let parameters = provider::adapted_parameters(
        args.eps,
        args.level,
        free_edge,
        args.edge_uncertainty,
        target,
    );
    describe_mesh(&provided, Some(request.label()), &parameters)
}

/// The JSON object `verify mesh` prints: where the mesh is, its hash and origin, and the
/// parameters that remake it (as a list and as `--mesh-parameters` text).
fn describe_mesh(
    provided: &provider::ProvidedMesh,
    label: Option<String>,
    parameters: &[(String, f64)],
) -> Result<Reply, String> {
    let out = serde_json::json!({
        "path": provided.path.display().to_string(),
        "sha256": provided.sha256().map_err(message)?,
        "origin": provided.origin,
        "gmsh_version": provided.gmsh_version,
        "label": label,
        "parameters": parameters,
        "mesh_parameters": provider::format_parameters(parameters),
        "corner_refinement": provided.corner_refinement.as_ref().map(|r| r.describe()),
    });
    Ok(Reply::ok(to_json(&out)?))
}
