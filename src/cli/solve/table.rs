//! `verify table`: one punch at many states, one row per state.

use super::{scene_of, solve_scene, states};
use crate::cli::args::{SolveArgs, TableArgs};
use crate::cli::{message, Reply};
use crate::harness::report::table::{Cell, Column, Format, Table};
use ringcontact::heartbeat::Heartbeat;
use ringcontact::provenance::Provenance;
use ringcontact::scene::Scene;
use ringcontact::solution::Solution;

/// Which quantity the listed states give.
#[derive(Clone, Copy)]
enum StateKind {
    Eps,
    Depth,
    Force,
}

impl StateKind {
    fn name(self) -> &'static str {
        match self {
            StateKind::Eps => "eps",
            StateKind::Depth => "depth",
            StateKind::Force => "force",
        }
    }
}

/// `verify table`: solve the punch of `args` at each listed state by `--method` and write one
/// row per state (CSV, or a JSON object with the provenance and `rows`).
pub fn table(args: TableArgs) -> Result<Reply, String> {
    let (kind, list) = match (&args.eps, &args.depth, &args.force) {
        (Some(l), None, None) => (StateKind::Eps, l),
        (None, Some(l), None) => (StateKind::Depth, l),
        (None, None, Some(l)) => (StateKind::Force, l),
        _ => return Err("give exactly one of --eps, --depth, --force".into()),
    };
    let values = states::parse(&format!("--{}", kind.name()), list)?;
    // Every state's scene is checked before the first solve: a bad state costs nothing.
    let scenes: Vec<(f64, SolveArgs, Scene)> = values
        .iter()
        .map(|&value| {
            let state = solve_args(&args, kind, value);
            scene_of(&state)
                .map(|scene| (value, state, scene))
                .map_err(|e| format!("--{} {value}: {e}", kind.name()))
        })
        .collect::<Result<_, _>>()?;
    let heartbeat = Heartbeat::start("verify table", crate::harness::progress::fem_progress());
    let mut solutions = Vec::with_capacity(scenes.len());
    for (k, (value, state, scene)) in scenes.iter().enumerate() {
        heartbeat.set(format!(
            "state {} of {} ({} = {value})",
            k + 1,
            scenes.len(),
            kind.name()
        ));
        let solution = solve_scene(scene, state).map_err(|e| {
            format!(
                "--{} {value} (state {} of {}): {e}",
                kind.name(),
                k + 1,
                scenes.len()
            )
        })?;
        crate::cli::refuse_non_finite(&format!("{} = {value}", kind.name()), &solution)?;
        solutions.push((*value, solution));
    }
    drop(heartbeat);
    let table = rows(kind, &solutions);
    let text = if args.json {
        let object = serde_json::json!({
            "provenance": Provenance::of_this_process(),
            "state": kind.name(),
            "method": args.method.name(),
            "rows": table.to_json(),
        });
        crate::cli::to_json(&object)?
    } else {
        table.to_csv().map_err(message)?
    };
    match &args.out {
        Some(path) => {
            std::fs::write(path, &text)
                .map_err(|e| format!("--out {}: cannot write: {e}", path.display()))?;
            Ok(Reply::ok(format!(
                "{} rows written to {}\n",
                solutions.len(),
                path.display()
            )))
        }
        None => Ok(Reply::ok(text)),
    }
}

/// The arguments of `verify solve` for one state of the table.
fn solve_args(args: &TableArgs, kind: StateKind, value: f64) -> SolveArgs {
    SolveArgs {
        punch: args.punch,
        exponent: args.exponent,
        tube_radius: args.tube_radius,
        profile: args.profile.clone(),
        eps: matches!(kind, StateKind::Eps).then_some(value),
        depth: matches!(kind, StateKind::Depth).then_some(value),
        force: matches!(kind, StateKind::Force).then_some(value),
        method: args.method,
        scene: args.scene.clone(),
        tol: args.tol,
        mesh: None,
        mesh_parameters: None,
        far_field: args.far_field,
        degree: args.degree,
        vtu: None,
        grid: args.grid,
        grid_extent: None,
        no_grid_estimate: args.no_grid_estimate,
        json: false,
        batch: None,
    }
}

/// One row per state; the keys are those of `verify solve --json`, and a column without a value
/// in any row is left out.
fn rows(kind: StateKind, solutions: &[(f64, Solution)]) -> Table {
    let given = format!("given_{}", kind.name());
    let number = |key: &str| Column::number(key, key, Format::Scientific(12));
    let columns = vec![
        number(&given),
        Column::text("punch", "punch"),
        number("exponent"),
        number("tube_radius"),
        Column::text("method", "method"),
        number("eps"),
        number("inner_radius"),
        number("outer_radius"),
        number("rim_radius"),
        number("depth"),
        number("force"),
        number("gamma"),
        number("gamma1"),
        number("gamma2"),
        number("stress_intensity_rim"),
        number("stress_intensity_inner"),
        number("error_estimate"),
        number("unknowns"),
        number("iterations"),
        number("wall_s"),
    ];
    let all_rows: Vec<Vec<Cell>> = solutions
        .iter()
        .map(|(value, s)| {
            vec![
                (*value).into(),
                s.punch.name().into(),
                s.punch.exponent().into(),
                s.tube_radius.into(),
                s.method.clone().into(),
                s.eps.into(),
                s.inner_radius.into(),
                s.outer_radius.into(),
                s.rim_radius.into(),
                s.depth.into(),
                s.force.into(),
                s.gamma.into(),
                s.gamma1.into(),
                s.gamma2.into(),
                s.stress_intensity_rim.into(),
                s.stress_intensity_inner.into(),
                s.error_estimate.into(),
                (s.unknowns as f64).into(),
                (s.iterations as f64).into(),
                s.wall_s.into(),
            ]
        })
        .collect();
    let kept: Vec<usize> = (0..columns.len())
        .filter(|&c| all_rows.iter().any(|r| r[c] != Cell::Missing))
        .collect();
    let mut table = Table::new(
        &format!("{} states", kind.name()),
        kept.iter().map(|&c| columns[c].clone()).collect(),
    );
    for row in all_rows {
        table.push(kept.iter().map(|&c| row[c].clone()).collect());
    }
    table
}
