//! `verify jkr`: the JKR adhesive solution built on the ring BEM's non-adhesive solutions.

use super::{message, refuse_non_finite, refuse_other_family_flags, to_json, Reply};
use crate::cli::args::JkrArgs;
use crate::harness::progress::Progress;
use crate::harness::report::table::{Cell, Column, Format, Table};
use crate::harness::studies::sweeps::{self, Sweep};
use ringcontact::adhesion::{self, BandJkr, ConcaveJkr, Critical, FixedAnnulusJkr, Jkr};
use ringcontact::methods::RingBem;
use ringcontact::punch::{Contact, PunchKind};

/// `verify jkr`: one fixed annulus (`--eps`), one concave punch or free band (`--d0h`), or a
/// sweep (`--sweep`).
pub fn jkr(args: JkrArgs) -> Result<Reply, String> {
    let punch = super::punch_kind_or_free_band(args.punch, args.exponent, args.profile.as_deref())?;
    refuse_other_family_flags(punch.clone(), args.eps, args.d0h)?;
    let solver = RingBem::new();
    if args.sweep {
        let out = crate::cli::output_directory(args.out.as_deref(), "reports/jkr");
        return Ok(Reply::ok(sweep(&punch, &solver, &out, args.json)?));
    }
    let name = punch.name();
    let what = match punch.contact() {
        Contact::Disk => return Err(kendall()),
        Contact::FixedAnnulus => {
            let eps = args
                .eps
                .ok_or_else(|| format!("{name} needs --eps B_OVER_A (or --sweep)"))?;
            format!("jkr {name} --eps {eps}")
        }
        Contact::RimAndFreeInner => {
            let s = args
                .d0h
                .ok_or("the concave punches need --d0h D0_OVER_H (or --sweep)")?;
            format!("jkr {punch} --d0h {s:e}")
        }
        Contact::FreeBand => {
            let s = args.d0h.ok_or(format!(
                "the {name} needs --d0h D0_OVER_H (h = a²/(2 rho), the gap at the axis)"
            ))?;
            format!("jkr {name} --d0h {s:e}")
        }
    };
    let r = adhesion::jkr(&solver, &punch, args.eps, args.d0h).map_err(message)?;
    refuse_non_finite(&what, &r)?;
    Ok(Reply::ok(match (&r, args.json) {
        (_, true) => to_json(&r)?,
        (Jkr::FixedAnnulus(r), false) => fixed_annulus_text(r) + UNITS,
        (Jkr::Concave(r), false) => concave_text(r) + UNITS,
        (Jkr::Band(r), false) => band_text(r) + UNITS,
    }))
}

/// The units of the text answers (the JSON's are in `verify jkr --help`).
const UNITS: &str = "  units: F0 = sqrt(8 pi E* dw a^3) (Kendall's force), d0 = \
                     sqrt(2 pi a dw / E*), dw the work of adhesion\n";

/// What `verify jkr` says of the punch whose contact is the whole disk.
fn kendall() -> String {
    format!(
        "the {} punch is Kendall's: F_c = -F0 (use {} --eps)",
        super::names_of(Contact::Disk),
        super::names_of(Contact::FixedAnnulus)
    )
}

/// `verify jkr --sweep`: a fixed annulus over `b/a`, a concave punch over `d0/h`; the table (or
/// the rows as JSON) and the files written into `out`.
pub(super) fn sweep(
    punch: &PunchKind,
    solver: &RingBem,
    out: &std::path::Path,
    json: bool,
) -> Result<String, String> {
    let out = out.to_path_buf();
    let text = match punch.contact() {
        Contact::FixedAnnulus => sweep_output(
            &sweeps::fixed_annulus_sweep(solver, &out).map_err(message)?,
            json,
        )?,
        Contact::RimAndFreeInner => {
            let mut bar = Progress::new("sweep", 25);
            let sweep = sweeps::pulloff_sweep(solver, punch.clone(), &out, |s| bar.tick(s))
                .map_err(message)?;
            sweep_output(&sweep, json)?
        }
        Contact::FreeBand => {
            return Err(format!(
                "--sweep is built for a fixed annulus and a punch with a rim; for the {} give \
                 one --d0h D0_OVER_H at a time",
                punch.name()
            ))
        }
        Contact::Disk => return Err(kendall()),
    };
    Ok(text)
}

/// The sweep's table (or its rows as JSON) and the files it wrote.
fn sweep_output<R: serde::Serialize>(sweep: &Sweep<R>, json: bool) -> Result<String, String> {
    if json {
        return to_json(&sweep.rows);
    }
    let files: Vec<String> = sweep
        .files
        .iter()
        .map(|f| f.display().to_string())
        .collect();
    Ok(sweep.table.to_terminal() + &format!("  wrote {}\n", files.join(", ")))
}

fn critical_columns(title: &str) -> Table {
    Table::new(
        title,
        vec![
            Column::text("edge", "edge / route"),
            Column::number("eps", "eps", Format::Fixed(6)),
            Column::number("depth", "d_c", Format::Fixed(9)),
            Column::number("force", "F_c/F0", Format::Fixed(9)),
            Column::number("bound", "error bound", Format::Scientific(1)),
            Column::text("note", "note"),
        ],
    )
}

/// The fixed annulus: critical states at each edge, and the asymptotic references.
fn fixed_annulus_text(r: &FixedAnnulusJkr) -> String {
    let mut t = critical_columns(&format!(
        "{} b/a = {}: gamma = {:.12}, gamma' = {:.9} (d_c in d0, F_c in F0; the bound \
         is the larger of d_c's and F_c's, from the ring BEM's estimates)",
        super::names_of(Contact::FixedAnnulus).replace('-', " "),
        r.eps,
        r.gamma,
        r.gamma_prime
    ));
    let governs = |edge: &str| {
        if r.governing_edge == edge {
            "governs (smaller |d_c|)"
        } else {
            ""
        }
    };
    let bounds = r.error_bounds;
    t.push(vec![
        "outer edge".into(),
        r.eps.into(),
        r.dc_outer.into(),
        r.fc_outer.into(),
        bounds.map(|b| b.dc_outer.max(b.fc_outer)).into(),
        governs("outer").into(),
    ]);
    t.push(vec![
        "inner edge".into(),
        r.eps.into(),
        r.dc_inner.into(),
        r.fc_inner.into(),
        bounds.map(|b| b.dc_inner.max(b.fc_inner)).into(),
        governs("inner").into(),
    ]);
    let references = [
        ("Collins' series in (16)-(17)", &r.collins),
        ("Argatov's asymptote (22)", &r.argatov),
    ];
    for (name, critical) in references {
        if let Some(c) = critical {
            t.push(vec![
                name.into(),
                r.eps.into(),
                c.depth.into(),
                c.force.into(),
                Cell::Missing,
                "reference".into(),
            ]);
        }
    }
    t.to_terminal()
        + &format!(
            "  kappa from the field against kappa from gamma': {:.1e}\n",
            r.kappa_consistency
        )
}

/// A concave punch: pull-off under fixed load and fixed grips by three routes, and from full
/// contact, then where the annular branch ends and the direct check.
fn concave_text(r: &ConcaveJkr) -> String {
    concave_table(r).to_terminal() + &concave_notes(r)
}

/// The pull-off table of a concave punch: per control, both edges, the inner edge only (the
/// paper's route) and the paper's fitted formulas; then full contact.
fn concave_table(r: &ConcaveJkr) -> Table {
    let mut t = Table::new(
        &format!(
            "{} d0/h = {}: pull-off (d/h; F in F0, negative = tensile)",
            r.punch,
            ringcontact::error::show(r.d0_over_h)
        ),
        vec![
            Column::text("control", "control"),
            Column::text("route", "route"),
            Column::number("eps", "eps", Format::Fixed(6)),
            Column::number("depth", "d/h", Format::Fixed(6)),
            Column::number("force", "F/F0", Format::Fixed(6)),
            Column::number("bound", "F error bound", Format::Scientific(1)),
            Column::text("edge", "governing edge / note"),
        ],
    );
    let none = "no critical state".to_string();
    for (control, both, note, inner, fits) in [
        (
            "fixed load",
            &r.fixed_load,
            &r.fixed_load_note,
            &r.inner_edge_only_fixed_load,
            r.paper_fits_fixed_load,
        ),
        (
            "fixed grips",
            &r.fixed_grips,
            &r.fixed_grips_note,
            &r.inner_edge_only_fixed_grips,
            r.paper_fits_fixed_grips,
        ),
    ] {
        let note = note.as_ref().unwrap_or(&none);
        critical_row(&mut t, control, "both edges (this harness)", both, note);
        let paper_route = "inner edge only (the paper's route)";
        critical_row(&mut t, control, paper_route, inner, &none);
        let fitted = fits.map(|(eps, force)| Critical {
            eps,
            depth: f64::NAN,
            depth_over_d0: f64::NAN,
            force,
            governing_edge: "inner".into(),
            // The paper's fitted formulas declare no error.
            error_bound: None,
            depth_error_bound: None,
        });
        let fitted_route = "the paper's route on its fitted formulas";
        critical_row(&mut t, control, fitted_route, &fitted, &none);
    }
    let full = Some(r.full_contact.pulloff.clone());
    critical_row(&mut t, "either", "from full contact (rim)", &full, &none);
    t
}

/// One row of [`concave_table`]: the critical state, or `note` where there is none.
fn critical_row(t: &mut Table, control: &str, route: &str, c: &Option<Critical>, note: &str) {
    let row = match c {
        Some(c) => vec![
            control.into(),
            route.into(),
            c.eps.into(),
            Some(c.depth).filter(|d| d.is_finite()).into(),
            c.force.into(),
            c.error_bound.into(),
            c.governing_edge.clone().into(),
        ],
        None => vec![
            control.into(),
            route.into(),
            Cell::Missing,
            Cell::Missing,
            Cell::Missing,
            Cell::Missing,
            note.into(),
        ],
    };
    t.push(row);
}

/// Where the annular branch ends (the floor, or full contact) and the direct check at the
/// fixed-load critical state.
fn concave_notes(r: &ConcaveJkr) -> String {
    let mut text = match &r.floor_contact {
        Some(touch) => format!(
            "  the annular branch ends at eps = {:.6} (d/h = {:.4}, F/F0 = {:.4}), where the \
             surface in the hole meets the punch's floor: pressed further the contact is a disk \
             or a ring and the annulus, not modelled here\n",
            touch.eps, touch.depth, touch.force
        ),
        None => format!(
            "  full contact is reached when pressed past d/h = {}\n",
            r.full_contact
                .closing_depth
                .map_or("- (no closing depth)".to_string(), |d| format!("{d:.4}"))
        ),
    };
    text += &format!(
        "  direct check at the fixed-load critical state: G_inner/dw = {}, rim intensity \
         difference {}\n",
        r.direct_inner_energy_ratio
            .map_or("-".to_string(), |v| format!("{v:.9}")),
        r.direct_rim_difference
            .map_or("-".to_string(), |v| format!("{v:.1e}"))
    );
    text
}

/// A free band's pull-off under fixed load and fixed grips, and the plane-strain asymptote.
fn band_text(r: &BandJkr) -> String {
    let mut t = Table::new(
        &format!(
            "{} d0/h = {} (h = a²/(2 rho)): pull-off, both edges at G = dw (d in d0, F in F0, \
             negative = tensile)",
            r.punch.name(),
            ringcontact::error::show(r.d0_over_h)
        ),
        vec![
            Column::text("control", "control"),
            Column::number("eps", "b/a", Format::Fixed(6)),
            Column::number("outer", "c/a", Format::Fixed(6)),
            Column::number("depth", "d/d0", Format::Fixed(6)),
            Column::number("force", "F/F0", Format::Fixed(9)),
            Column::number("bound", "F error bound", Format::Scientific(1)),
            Column::text("note", "note"),
        ],
    );
    for (control, critical, note) in [
        ("fixed load", &r.fixed_load, &r.fixed_load_note),
        ("fixed grips", &r.fixed_grips, &r.fixed_grips_note),
    ] {
        t.push(match critical {
            Some(c) => vec![
                control.into(),
                c.eps.into(),
                c.outer.into(),
                c.depth_over_d0.into(),
                c.force.into(),
                c.error_bound.into(),
                "ring BEM, both edges located".into(),
            ],
            None => vec![
                control.into(),
                Cell::Missing,
                Cell::Missing,
                Cell::Missing,
                Cell::Missing,
                Cell::Missing,
                note.clone().unwrap_or_default().into(),
            ],
        });
    }
    t.push(vec![
        "fixed load".into(),
        Cell::Missing,
        Cell::Missing,
        Cell::Missing,
        r.plane_strain_fixed_load.map_or(Cell::Missing, Cell::from),
        Cell::Missing,
        "plane-strain JKR cylinder over 2 pi a (narrow limit d0/h -> 0, asymptote)".into(),
    ]);
    t.to_terminal()
}
