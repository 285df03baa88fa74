//! `verify solve --batch FILE`: many scenes in one process, one JSON line in and one out each.

use std::path::Path;

use super::solve_scene_by;
use crate::cli::args::SolveArgs;
use crate::cli::{message, Reply};
use ringcontact::heartbeat::Heartbeat;
use ringcontact::methods::Method;
use ringcontact::scene::SceneSpec;

/// Solve every scene of the JSON-lines file `path` (`-`: standard input) in order. Each
/// non-blank line is a JSON object with the keys of a scene file and optionally `"method"`;
/// `--method` and `--tol` of `args` apply where a line does not say. Each answer is one compact
/// JSON line: the solution (the object of `verify solve --json`) with `"line"` first, or
/// `{"line": N, "error": "..."}`. The reply fails (exit status 1) if any line failed.
pub fn solve_batch(path: &Path, args: &SolveArgs) -> Result<Reply, String> {
    let (text, base) = read_batch(path)?;
    let lines: Vec<(usize, &str)> = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty())
        .collect();
    if lines.is_empty() {
        return Err(format!(
            "--batch {}: no scene in the file (one JSON object per line, e.g. \
             {{\"punch\": {{\"shape\": \"flat\"}}, \"load\": {{\"depth\": 2}}}})",
            path.display()
        ));
    }
    let heartbeat = Heartbeat::start(
        "verify solve --batch",
        crate::harness::progress::fem_progress(),
    );
    let mut out = String::new();
    let mut failed = 0usize;
    for (k, (number, line)) in lines.iter().enumerate() {
        heartbeat.set(format!(
            "scene {} of {} (line {number})",
            k + 1,
            lines.len()
        ));
        let answer = solve_line(line, *number, path, base.as_deref(), args);
        match answer {
            Ok(json) => out.push_str(&json),
            Err(e) => {
                failed += 1;
                let error = serde_json::Value::String(e).to_string();
                out.push_str(&format!("{{\"line\":{number},\"error\":{error}}}"));
            }
        }
        out.push('\n');
    }
    Ok(Reply::verdict(out, failed == 0))
}

/// The batch's text and the directory relative profile paths are read from.
fn read_batch(path: &Path) -> Result<(String, Option<std::path::PathBuf>), String> {
    if path == Path::new("-") {
        let mut text = String::new();
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut text)
            .map_err(|e| format!("--batch -: cannot read standard input: {e}"))?;
        return Ok((text, None));
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("--batch {}: cannot read: {e}", path.display()))?;
    Ok((text, path.parent().map(Path::to_path_buf)))
}

/// One line's answer: the solution as one JSON line with `"line"` first.
fn solve_line(
    line: &str,
    number: usize,
    path: &Path,
    base: Option<&Path>,
    args: &SolveArgs,
) -> Result<String, String> {
    let origin = format!("{} line {number}", path.display());
    let value: serde_json::Value =
        serde_json::from_str(line).map_err(|e| format!("{origin}: not JSON: {e}"))?;
    let serde_json::Value::Object(mut object) = value else {
        return Err(format!(
            "{origin}: a scene is a JSON object ({{\"punch\": ..., \"load\": ...}})"
        ));
    };
    let method = match object.remove("method") {
        None => args.method,
        Some(serde_json::Value::String(name)) => {
            <Method as ringcontact::choice::Choice>::named(&name).ok_or_else(|| {
                format!(
                    "{origin}: method {name:?} is not one of {}",
                    <Method as ringcontact::choice::Choice>::names_joined(", ")
                )
            })?
        }
        Some(other) => return Err(format!("{origin}: method must be a name, not {other}")),
    };
    let mut spec = SceneSpec::from_json_value(serde_json::Value::Object(object), &origin, base)
        .map_err(message)?;
    if let (None, Some(tol)) = (spec.stated_tolerance(), args.tol) {
        spec = spec.tolerance(tol);
    }
    let scene = spec.validate().map_err(message)?;
    let solution = solve_scene_by(&scene, method, args)?;
    crate::cli::refuse_non_finite("the scene", &solution)?;
    let json = serde_json::to_string(&solution).map_err(message)?;
    // The solution's own keys, in their order, after "line".
    Ok(format!("{{\"line\":{number},{}", &json[1..]))
}
