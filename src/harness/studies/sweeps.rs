//! The adhesive sweeps of `verify jkr --sweep`: typed rows, one [`Table`] for every output
//! format, and the charts, written next to the physics they use ([`ringcontact::adhesion`]).
//!
//! * [`fixed_annulus_sweep`]: critical depths `d_c/d0` and forces `F_c/F0` of both edges against
//!   `b/a` (the paper's Fig. 7-8), with Collins' series (21) and Argatov's asymptote (22).
//! * [`pulloff_sweep`]: the pull-off force `-F/F0` against `d0/h` by every route (fixed load,
//!   fixed grips, the paper's route on its fitted formulas, full contact), and the adhesive
//!   branches `F/(2 E* h a)` against `d/h` for `d0/h` = 0.1, 0.3, 1, 3 (Fig. 9's analogue).

use std::path::{Path, PathBuf};

use crate::harness::report::svg;
use crate::harness::report::table::{Cell, Column, Format, Table};
use ringcontact::adhesion::{self, ConcaveJkr, Critical, FixedAnnulusJkr};
use ringcontact::error::{Error, Result};
use ringcontact::methods::RingBem;
use ringcontact::punch::{Contact, PunchKind};

/// What a sweep returns: its rows, the table of them, and the files written.
pub(crate) struct Sweep<R> {
    pub rows: Vec<R>,
    pub table: Table,
    pub files: Vec<PathBuf>,
}

fn write(path: PathBuf, text: &str, files: &mut Vec<PathBuf>) -> Result<()> {
    std::fs::write(&path, text).map_err(|e| Error::file("write", &path, e))?;
    files.push(path);
    Ok(())
}

fn create(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).map_err(|e| Error::file("create the directory", out, e))
}

/// Ratios `b/a = 1 - 0.99 · 10^(-k/20)`, `k = 1..40` (dense toward 1).
/// The fixed annulus's name as words (hyphens as spaces).
fn annulus_name() -> String {
    PunchKind::built_in(Contact::FixedAnnulus)
        .first()
        .map_or("fixed annulus".into(), |k| k.name().replace('-', " "))
}

fn annulus_ratios() -> Vec<f64> {
    (1..=40)
        .map(|k| 1.0 - 10f64.powf(-2.0 * k as f64 / 40.0) * 0.99)
        .filter(|&e| e > 0.0 && e < 1.0)
        .collect()
}

/// Fixed annulus: both edges' critical states against `b/a`; writes
/// `critical-LABEL.{csv,svg}` into `out` (`LABEL` the annulus's).
pub(crate) fn fixed_annulus_sweep(solver: &RingBem, out: &Path) -> Result<Sweep<FixedAnnulusJkr>> {
    let rows = annulus_ratios()
        .into_iter()
        .map(|e| adhesion::fixed_annulus(solver, e))
        .collect::<Result<Vec<_>>>()?;
    let fixed = |key: &str, label: &str| Column::number(key, label, Format::Fixed(5));
    let annulus = annulus_name();
    let mut table = Table::new(
        &format!("{annulus}: critical depths (units d0) and forces (units F0)"),
        vec![
            Column::number("eps", "eps", Format::Fixed(4)),
            fixed("dc_outer", "dc_outer"),
            fixed("fc_outer", "fc_outer"),
            fixed("dc_inner", "dc_inner"),
            fixed("fc_inner", "fc_inner"),
            fixed("governing_edge", "governs"),
            fixed("collins_dc", "Collins dc"),
            fixed("collins_fc", "Collins fc"),
            fixed("argatov_dc", "Argatov dc"),
            fixed("argatov_fc", "Argatov fc"),
        ],
    );
    for r in &rows {
        table.push(vec![
            r.eps.into(),
            r.dc_outer.into(),
            r.fc_outer.into(),
            r.dc_inner.into(),
            r.fc_inner.into(),
            Cell::Text(r.governing_edge.to_string()),
            r.collins.map(|c| c.depth).into(),
            r.collins.map(|c| c.force).into(),
            r.argatov.map(|c| c.depth).into(),
            r.argatov.map(|c| c.force).into(),
        ]);
    }
    create(out)?;
    let series = |name: &str, f: &dyn Fn(&FixedAnnulusJkr) -> Option<f64>| svg::Series {
        name: name.to_string(),
        points: rows
            .iter()
            .filter_map(|r| f(r).map(|v| (1.0 - r.eps, v.abs())))
            .collect(),
        bars: Vec::new(),
    };
    let chart = svg::log_log_chart(
        &format!("{annulus}: |critical force| / F0 against 1 - b/a"),
        "1 - eps",
        "|F_c| / F0",
        &[
            series("outer edge", &|r| Some(r.fc_outer)),
            series("inner edge", &|r| Some(r.fc_inner)),
            series("Collins (21)", &|r| r.collins.map(|c| c.force)),
            series("Argatov (22)", &|r| r.argatov.map(|c| c.force)),
        ],
    );
    let mut files = Vec::new();
    let stem = out.join(format!("critical-{}", annulus.replace(' ', "-")));
    write(stem.with_extension("csv"), &table.to_csv()?, &mut files)?;
    write(stem.with_extension("svg"), &chart, &mut files)?;
    Ok(Sweep { rows, table, files })
}

/// `d0/h = 10^(-1 + 3k/steps)`, `k = 0..=steps`: `steps + 1` values from 0.1 to 100, evenly in
/// the logarithm (the sweep's 25, the report's charts' 9, the dataset's).
pub(crate) fn pulloff_scales(steps: usize) -> Vec<f64> {
    (0..=steps)
        .map(|k| 10f64.powf(-1.0 + 3.0 * k as f64 / steps as f64))
        .collect()
}

/// Tensile pull-off `-F/F0` of a critical state.
fn pulloff(c: &Option<Critical>) -> Option<f64> {
    c.as_ref().map(|c| -c.force)
}

/// Concave punch: the pull-off force against `d0/h` by every route, and the adhesive branches;
/// writes `pulloff-KIND.{csv,svg}` and `branches-KIND.{csv,svg}` into `out`. `progress` is
/// called after each `d0/h`.
pub(crate) fn pulloff_sweep(
    solver: &RingBem,
    kind: PunchKind,
    out: &Path,
    mut progress: impl FnMut(&str),
) -> Result<Sweep<ConcaveJkr>> {
    let mut rows = Vec::new();
    let branch = adhesion::ConcaveBranch::new(solver, kind.clone())?;
    for s in pulloff_scales(24) {
        rows.push(branch.jkr(s)?);
        progress(&format!("d0/h = {s:.3}"));
    }
    let force = |key: &str, label: &str| Column::number(key, label, Format::Fixed(4));
    let mut table = Table::new(
        &format!(
            "{kind}: pull-off force -F/F0 against d0/h (F0 = Kendall's force, sqrt(8 pi E* dw a^3))"
        ),
        vec![
            Column::number("d0_over_h", "d0/h", Format::Fixed(3)),
            force("fixed_load", "fixed load"),
            force("fixed_grips", "fixed grips"),
            force("paper_fits_fixed_load", "paper fits FL"),
            force("paper_fits_fixed_grips", "paper fits FG"),
            force("full_contact", "full contact"),
        ],
    );
    for r in &rows {
        table.push(vec![
            r.d0_over_h.into(),
            pulloff(&r.fixed_load).into(),
            pulloff(&r.fixed_grips).into(),
            r.paper_fits_fixed_load.map(|p| -p.1).into(),
            r.paper_fits_fixed_grips.map(|p| -p.1).into(),
            (-r.full_contact.pulloff.force).into(),
        ]);
    }
    create(out)?;
    let series = |name: &str, f: &dyn Fn(&ConcaveJkr) -> Option<f64>| svg::Series {
        name: name.to_string(),
        points: rows
            .iter()
            .filter_map(|r| f(r).map(|v| (r.d0_over_h, v)))
            .collect(),
        bars: Vec::new(),
    };
    let chart = svg::log_log_chart(
        &format!("{kind}: pull-off force / F0 against d0/h"),
        "d0/h",
        "-F_pulloff / F0",
        &[
            series("fixed load", &|r| pulloff(&r.fixed_load)),
            series("fixed grips", &|r| pulloff(&r.fixed_grips)),
            series("paper fits, FL", &|r| r.paper_fits_fixed_load.map(|p| -p.1)),
            series("full contact", &|r| Some(-r.full_contact.pulloff.force)),
        ],
    );
    let mut files = Vec::new();
    let stem = out.join(format!("pulloff-{}", kind.name()));
    write(stem.with_extension("csv"), &table.to_csv()?, &mut files)?;
    write(stem.with_extension("svg"), &chart, &mut files)?;
    branches(solver, kind, out, &mut files)?;
    Ok(Sweep { rows, table, files })
}

/// Contact ratios of the branch curves: `0.02 + 0.9799 sqrt(k/120)`, `k = 0..120`.
fn branch_ratios() -> impl Iterator<Item = f64> {
    (0..=120).map(|k| 0.02 + 0.9799 * (k as f64 / 120.0).powf(0.5))
}

/// Fig. 9's analogue: the adhesive branches `F/(2E*ha)` against `d/h` (inner edge in
/// equilibrium) for a few `d0/h`, with the non-adhesive curve.
fn branches(solver: &RingBem, kind: PunchKind, out: &Path, files: &mut Vec<PathBuf>) -> Result<()> {
    let mut table = Table::new(
        &format!("{kind}: adhesive branches"),
        vec![
            Column::number("d0_over_h", "d0/h", Format::Fixed(2)),
            Column::number("eps", "eps", Format::Fixed(4)),
            Column::number("depth_over_h", "d/h", Format::Fixed(4)),
            Column::number("force_over_2eha", "F/(2E*ha)", Format::Fixed(4)),
            Column::number("force_over_f0", "F/F0", Format::Fixed(4)),
            Column::number("rim_attached", "rim attached", Format::Fixed(0)),
        ],
    );
    let mut curves = Vec::new();
    for s in [0.1, 0.3, 1.0, 3.0] {
        let mut points = Vec::new();
        for e in branch_ratios() {
            let p = adhesion::branch_point(solver, kind.clone(), e)?;
            if !p.clears_floor(s) {
                // The punch would rise into the surface in the hole: not an annular state.
                continue;
            }
            let (d, f) = (p.depth(s), p.force(s) * s);
            let rim_attached = p.rim_intensity(s) >= -1.0;
            table.push(vec![
                s.into(),
                e.into(),
                d.into(),
                f.into(),
                p.force(s).into(),
                Cell::Text(rim_attached.to_string()),
            ]);
            if d > -4.0 {
                points.push((d, f));
            }
        }
        curves.push(svg::Series {
            name: format!("d0/h = {s}"),
            points,
            bars: Vec::new(),
        });
    }
    curves.push(svg::Series {
        name: "non-adhesive".into(),
        points: branch_ratios()
            .filter_map(|e| {
                adhesion::branch_point(solver, kind.clone(), e)
                    .ok()
                    .filter(|p| p.clears_floor(0.0))
                    .map(|p| (p.gamma1, p.gamma2))
            })
            .collect(),
        bars: Vec::new(),
    });
    let stem = out.join(format!("branches-{}", kind.name()));
    write(stem.with_extension("csv"), &table.to_csv()?, files)?;
    let chart = svg::linear_chart(
        &format!("{kind}: adhesive branches (inner edge in equilibrium)"),
        "d/h",
        "F/(2 E* h a)",
        &curves,
    );
    write(stem.with_extension("svg"), &chart, files)
}
