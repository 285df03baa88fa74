//! `verify pulloff`: the pull-off by direct simulation (cohesive zone on the FE model).

use super::args::PulloffArgs;
use super::{message, refuse_non_finite, to_json, Reply};
use crate::cohesive::study::{self, PulloffStudy};
use crate::fem::mesh_provider::{MeshOrigin, ProvidedMesh};
use crate::harness::progress::Progress;
use crate::harness::table::{Column, Format, Table};
use crate::punch::PunchKind;

/// `verify pulloff`: the sequence at decreasing ranges, its extrapolate and the JKR route's
/// value.
pub fn pulloff(args: PulloffArgs) -> Result<Reply, String> {
    let eps = match args.punch {
        PunchKind::FlatAnnulus => args.eps.ok_or("flat-annulus needs --eps B_OVER_A")?,
        _ => 0.0,
    };
    let d0_over_h = match (args.punch.is_concave(), args.d0h) {
        (true, None) => return Err("cone and sphere need --d0h D0_OVER_H".into()),
        (true, Some(s)) if !(s.is_finite() && s > 0.0) => {
            return Err(format!("--d0h {s}: need d0/h > 0"))
        }
        (_, s) => s.unwrap_or(0.0),
    };
    if args.punch == PunchKind::FlatAnnulus && !(eps > 0.0 && eps < 1.0) {
        return Err(format!(
            "--eps {eps}: the flat annulus needs 0 < b/a < 1 (b/a = 0 is --punch flat)"
        ));
    }
    let annular = args.branch == study::Branch::Annular;
    if annular && !args.punch.is_concave() {
        return Err(format!(
            "--branch annular: the annular branch is a concave punch's (cone, sphere); the {} \
             has none",
            args.punch
        ));
    }
    if annular && args.mesh.is_some() {
        return Err(
            "--branch annular makes its own mesh per range (the contact line uniform at \
                    a third of the zone); --mesh does not apply"
                .into(),
        );
    }
    let ranges = args.ranges.clone().unwrap_or_else(|| {
        if annular {
            study::ANNULAR_RANGES.to_vec()
        } else {
            study::DEFAULT_RANGES.to_vec()
        }
    });
    if let Some(r) = ranges
        .iter()
        .find(|r| !(r.is_finite() && **r > 0.0 && **r < 1.0))
    {
        return Err(format!("--ranges: {r} is not a range rho/d0 in (0, 1)"));
    }
    if ranges
        .windows(2)
        .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Less))
    {
        return Err(format!(
            "--ranges {ranges:?}: give decreasing ranges rho/d0"
        ));
    }
    let case = study::Case {
        punch: args.punch,
        eps,
        d0_over_h,
    };
    if annular {
        let mut bar = Progress::new("pull-off (annular branch)", ranges.len() + 1);
        let result = crate::cohesive::annular::run_annular(case, &ranges, |entry| {
            bar.tick(&format!(
                "rho/a = {}: F/F0 = {:.4}{}",
                entry.range_over_a,
                entry.pulloff_over_f0,
                if entry.hole_closed_at.is_some() {
                    " (the hole closed: excluded)"
                } else {
                    ""
                }
            ))
        })
        .map_err(message)?;
        refuse_non_finite("pulloff", &result.sequence)?;
        if args.json {
            return Ok(Reply::ok(to_json(&result)?));
        }
        return Ok(Reply::ok(render(&result)));
    }
    let mesh = match &args.mesh {
        Some(path) => ProvidedMesh {
            sha256: crate::fem::mesh_provider::sha256_file(path).map_err(message)?,
            path: path.clone(),
            origin: MeshOrigin::User,
            gmsh_version: None,
            corner_refinement: None,
        },
        None => study::study_mesh(eps, study::STUDY_LEVEL).map_err(message)?,
    };
    // The smallest range again one level coarser: the mesh's share of the error bar.
    let check = match &args.mesh {
        Some(_) => None,
        None => Some(study::study_mesh(eps, study::STUDY_LEVEL - 1).map_err(message)?),
    };
    let mut bar = Progress::new("pull-off", ranges.len() + usize::from(check.is_some()));
    let (given, mut simulated, mut usable) = (ranges.len(), 0, 0);
    let result = study::run(case, &ranges, &mesh, check.as_ref(), |entry| {
        simulated += 1;
        let left = study::left_the_branch(&case, entry);
        usable += usize::from(!left);
        // The study replaces a range that left the branch by a smaller one once the given
        // ranges are done and fewer than three are usable.
        let smaller = entry.range_over_a / case.d0() * 0.5;
        if left && simulated >= given && usable < 3 && smaller >= study::MIN_RANGE {
            bar.grow(1);
        }
        bar.tick(&format!(
            "rho/a = {}: F/F0 = {:.4}{}",
            entry.range_over_a,
            entry.pulloff_over_f0,
            if left {
                " (left the branch: excluded)"
            } else {
                ""
            }
        ))
    })
    .map_err(message)?;
    refuse_non_finite("pulloff", &result.sequence)?;
    if args.json {
        return Ok(Reply::ok(to_json(&result)?));
    }
    Ok(Reply::ok(render(&result)))
}

/// The sequence as a table, then the extrapolate beside the JKR route.
pub fn render(s: &PulloffStudy) -> String {
    let mut t = Table::new(
        &format!(
            "{}{}{}: pull-off by direct simulation ({} contact nodes, {} unknowns, mesh {})",
            s.punch,
            s.eps.map_or(String::new(), |e| format!(" b/a = {e}")),
            s.d0_over_h.map_or(String::new(), |x| {
                if s.branch == Some(study::Branch::Annular) {
                    format!(
                        " d0/h = {x}, annular branch: touched at d = {} h with the hole open",
                        s.preload_over_d0 * x
                    )
                } else {
                    format!(
                        " d0/h = {x}, pressed to d = {} h or deeper until the hole closes",
                        s.preload_over_d0 * x
                    )
                }
            }),
            s.contact_nodes,
            s.unknowns,
            s.mesh
        ),
        vec![
            Column::number("range_over_a", "range rho/a", Format::Scientific(3)),
            Column::number("tabor", "Tabor", Format::Fixed(2)),
            Column::number("pulloff_over_f0", "pull-off F/F0", Format::Fixed(5)),
            Column::number("pulloff_depth_over_d0", "at d/d0", Format::Fixed(5)),
            Column::text("maximum", "maximum"),
            Column::number("jumps", "jumps", Format::Fixed(0)),
            Column::number("preload_over_d0", "pressed to d/d0", Format::Fixed(3)),
            Column::number("wall_s", "time", Format::Fixed(2)).with_unit("s"),
        ],
    );
    for e in &s.sequence {
        t.push(vec![
            e.range_over_a.into(),
            e.tabor.into(),
            e.pulloff_over_f0.into(),
            e.pulloff_depth_over_d0.into(),
            if e.smooth_maximum {
                "smooth"
            } else {
                "end of branch"
            }
            .into(),
            (e.jumps as f64).into(),
            e.preload_over_d0.unwrap_or(s.preload_over_d0).into(),
            e.wall_s.into(),
        ]);
    }
    let mut text = t.to_terminal();
    for x in &s.excluded {
        text += &format!(
            "  left out: rho/a = {:.3e} (Tabor {:.2}), {}\n",
            x.entry.range_over_a, x.entry.tabor, x.reason
        );
    }
    text += &match (s.extrapolated_over_f0, s.error_bar) {
        (Some(x), Some(bar)) => format!(
            "  extrapolated to zero range (linear in the range): F/F0 = {x:.4} +- {bar:.1e} \
             (mesh difference at the smallest range: {})\n",
            s.mesh_difference
                .map_or("not checked".to_string(), |d| format!("{d:.1e}"))
        ),
        _ => "  no extrapolate: it needs three ranges\n".to_string(),
    };
    match (s.punch.is_concave(), s.jkr_fixed_load_over_f0) {
        (false, Some(j)) => {
            text += &format!("  JKR route (verify jkr), fixed load: F/F0 = {j:.4}\n")
        }
        (true, j) => {
            text +=
                &format!(
                "  JKR route (verify jkr): from full contact F/F0 = {}; from the annular contact \
                 (fixed load) {}; the paper's route on its fitted formulas {}\n",
                s.full_contact_over_f0.map_or("-".into(), |v| format!("{v:.4}")),
                j.map_or("none (no stable annular state)".into(), |v| format!("{v:.4}")),
                s.paper_route_over_f0.map_or("-".into(), |v| format!("{v:.4}"))
            );
        }
        _ => {}
    }
    text += &format!("  {}\n  law: {}\n", s.note, s.law);
    text
}
