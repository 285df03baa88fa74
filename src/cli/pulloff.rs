//! `verify pulloff`: the pull-off by direct simulation (cohesive zone on the FE model).

use super::{message, refuse_non_finite, refuse_other_family_flags, to_json, Reply};
use crate::cli::args::PulloffArgs;
use crate::harness::progress::Progress;
use crate::harness::report::table::{Column, Format, Table};
use ringcontact::cohesive::study::{self, PulloffStudy};
use ringcontact::heartbeat::Heartbeat;
use ringcontact::mesh::provider::{MeshOrigin, ProvidedMesh};

/// The `d0/h` of a concave punch's direct simulation: its load path takes about `250 h/d0`
/// steps per range below `d0/h = 1` and `200 d0/h` above.
const PULLOFF_D0H_RANGE: (f64, f64) = (0.1, 100.0);

/// `verify pulloff`: the sequence at decreasing ranges, its extrapolate and the JKR route's
/// value.
pub fn pulloff(args: PulloffArgs) -> Result<Reply, String> {
    let (case, ranges) = checked_case_and_ranges(&args)?;
    // A range takes from a few seconds to a minute (meshing, condensation, the load path): a
    // plain line every ten seconds between the bar's ticks says which one is running.
    let heartbeat = Heartbeat::start("pull-off", crate::harness::progress::fem_progress());
    if let Some(first) = ranges.first() {
        heartbeat.set(format!("the first range, rho/d0 = {first}"));
    }
    if case.punch.is_free_band() {
        free_band(&args, case, &ranges, &heartbeat)
    } else if args.branch == study::Branch::Annular {
        annular_branch(&args, case, &ranges, &heartbeat)
    } else {
        closed_branch(&args, case, &ranges, &heartbeat)
    }
}

/// The case and the decreasing ranges of `verify pulloff`, every flag checked against the punch
/// and the branch.
fn checked_case_and_ranges(args: &PulloffArgs) -> Result<(study::Case, Vec<f64>), String> {
    // A free band (two free edges) has its own route: touched, then pulled.
    let punch = super::punch_kind_or_free_band(args.punch, args.exponent, args.profile.as_deref())?;
    let eps = match punch.has_fixed_hole() {
        true => args
            .eps
            .ok_or_else(|| format!("{} needs --eps B_OVER_A", punch.name()))?,
        false => 0.0,
    };
    let d0_over_h = match (punch.is_concave(), args.d0h) {
        (true, None) => return Err("the concave punches need --d0h D0_OVER_H".into()),
        (true, Some(s)) if !(s.is_finite() && s > 0.0) => {
            return Err(format!("--d0h {s}: need d0/h > 0"))
        }
        (true, Some(s)) if !(PULLOFF_D0H_RANGE.0..=PULLOFF_D0H_RANGE.1).contains(&s) => {
            return Err(format!(
                "--d0h {}: the direct simulation runs for d0/h in [{}, {}] (the paper's \
                 Fig. 10 range). It follows the load path in steps of 0.02 d0, at most 0.02 h, \
                 from 3h deep to 4 d0 + 2h out: about 250 h/d0 steps per range below d0/h = 1 \
                 and 200 d0/h above: 833 at d0/h = 0.3 and 2 250 at 10, whose stored runs took \
                 52 and 25 s, but 2.5e6 at 1e-4. \
                 `verify jkr {} --d0h {}` gives the JKR limit for d0/h in [1e-6, 1e6]",
                ringcontact::error::show(s),
                PULLOFF_D0H_RANGE.0,
                PULLOFF_D0H_RANGE.1,
                punch.flags(),
                ringcontact::error::show(s)
            ));
        }
        (_, s) => s.unwrap_or(0.0),
    };
    if punch.has_fixed_hole() && !(eps > 0.0 && eps < 1.0) {
        return Err(format!(
            "--eps {eps}: the {punch} needs 0 < b/a < 1 (b/a = 0 is --punch {})",
            super::names_of(ringcontact::punch::Contact::Disk)
        ));
    }
    refuse_other_family_flags(punch.clone(), args.eps, args.d0h)?;
    let band = punch.is_free_band();
    if band && args.mesh.is_some() {
        return Err(format!(
            "the {}'s simulation makes its own mesh per range (its contact line uniform at a \
             third of the zone, 1.5 a long); --mesh does not apply",
            punch.name()
        ));
    }
    let annular = args.branch == study::Branch::Annular || band;
    if annular && !punch.is_concave() {
        return Err(format!(
            "--branch annular: the annular branch is a concave punch's ({}); the {} has none",
            super::names_of(ringcontact::punch::Contact::RimAndFreeInner),
            punch
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
        } else if args.mesh.is_some() {
            study::DEFAULT_RANGES.to_vec()
        } else {
            study::default_ranges(&crate::harness::settings::data_paths())
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
        punch,
        eps,
        d0_over_h,
        linear_solver: crate::harness::settings::linear_solver(),
        data: crate::harness::settings::data_paths(),
    };
    Ok((case, ranges))
}

/// The annular branch: touched with the hole open, then pulled, at each range.
fn annular_branch(
    args: &PulloffArgs,
    case: study::Case,
    ranges: &[f64],
    heartbeat: &Heartbeat,
) -> Result<Reply, String> {
    let mut bar = Progress::new("pull-off (annular branch)", ranges.len() + 1);
    let result = ringcontact::cohesive::annular::run_annular(case, ranges, |entry| {
        heartbeat.set(format!("the range after rho/a = {}", entry.range_over_a));
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
    Ok(Reply::ok(render(&result)))
}

/// A free band: touched at its lowest circle, then pulled, at each range.
fn free_band(
    args: &PulloffArgs,
    case: study::Case,
    ranges: &[f64],
    heartbeat: &Heartbeat,
) -> Result<Reply, String> {
    let mut bar = Progress::new(
        &format!("pull-off ({})", case.punch.name()),
        ranges.len() + 1,
    );
    let result = ringcontact::cohesive::free_band::run_band(case, ranges, |entry| {
        heartbeat.set(format!("the range after rho/a = {}", entry.range_over_a));
        bar.tick(&format!(
            "rho/a = {}: F/F0 = {:.4}",
            entry.range_over_a, entry.pulloff_over_f0
        ))
    })
    .map_err(message)?;
    refuse_non_finite("pulloff", &result.sequence)?;
    if args.json {
        return Ok(Reply::ok(to_json(&result)?));
    }
    Ok(Reply::ok(render(&result)))
}

/// The closed branch (the punch pressed until its hole closes, then pulled): a rim-band mesh
/// per range, or the given mesh for every range.
fn closed_branch(
    args: &PulloffArgs,
    case: study::Case,
    ranges: &[f64],
    heartbeat: &Heartbeat,
) -> Result<Reply, String> {
    // Without --mesh: a mesh per range with a refined band at the rim (gmsh), else the study
    // meshes; with it, that mesh for every range and no check mesh.
    let checked = args.mesh.is_none();
    let mut bar = Progress::new("pull-off", ranges.len() + usize::from(checked));
    let given = ranges.len();
    let (mut seen, mut usable, mut any_left) = (Vec::<f64>::new(), Vec::new(), false);
    let on_entry = |entry: &study::SequenceEntry| {
        let range = entry.range_over_a / case.d0();
        // The check mesh's run repeats the smallest usable range (and comes last).
        let repeat = seen.iter().any(|r| (r - range).abs() <= 1e-12 * range);
        seen.push(range);
        let left = study::left_the_branch(&case, entry);
        any_left |= left;
        if !left && !repeat {
            usable.push(range);
        }
        // Once the given ranges are done the study adds smaller ones (study::smaller_range).
        heartbeat.set(format!("the range after rho/a = {}", entry.range_over_a));
        if !repeat
            && seen.len() >= given
            && study::smaller_range(ranges, range, &usable, any_left).is_some()
        {
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
    };
    let result = match &args.mesh {
        Some(path) => {
            let mesh = ProvidedMesh {
                path: path.clone(),
                origin: MeshOrigin::User,
                gmsh_version: None,
                corner_refinement: None,
            };
            study::run(case.clone(), ranges, &mesh, None, on_entry)
        }
        None => study::run_on_study_meshes(case.clone(), ranges, on_entry),
    }
    .map_err(message)?;
    refuse_non_finite("pulloff", &result.sequence)?;
    // A sequence cut short keeps its ranges, says why, and is not a success.
    let complete = result.stopped.is_none();
    if args.json {
        return Ok(Reply::verdict(to_json(&result)?, complete));
    }
    let stopped = result
        .stopped
        .as_ref()
        .map_or(String::new(), |why| format!("  STOPPED EARLY: {why}\n"));
    Ok(Reply::verdict(render(&result) + &stopped, complete))
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
        (true, Some(j)) if s.punch.is_free_band() => {
            text += &format!(
                "  JKR route (verify jkr --punch {}: both edges at G = dw), fixed load: F/F0 = \
                 {j:.4}\n",
                s.punch.name()
            )
        }
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
