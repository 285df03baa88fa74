//! The adhesive part of the dataset: the JKR critical states of the fixed annulus against `b/a`,
//! the concave punches' pull-off against `d0/h` under fixed load and fixed grips, and the
//! refitted formulas with their largest errors.

use crate::harness::report::table::{Cell, Table};
use ringcontact::adhesion::{self, Critical};
use ringcontact::error::Result;
use ringcontact::fit;
use ringcontact::methods::RingBem;
use ringcontact::punch::{Contact, PunchKind};

use super::{Field, Resource};

/// Fixed annulus: both edges' critical depth and force with their bounds, at `ratios`.
pub fn fixed_annulus(
    solver: &RingBem,
    ratios: &[f64],
    progress: &dyn Fn(&str),
) -> Result<Resource> {
    let annulus = PunchKind::built_in(Contact::FixedAnnulus)
        .into_iter()
        .next()
        .expect("a built-in fixed annulus");
    let words = annulus.name().replace('-', " ");
    let mut fields = vec![Field::number("eps", "1", &format!("b/a of the {words}"))];
    for (edge, where_) in [
        ("outer", "the rim r = a"),
        ("inner", "the inner edge r = b"),
    ] {
        fields.push(Field::number(
            &format!("dc_{edge}"),
            "d0",
            &format!("critical depth for detachment at {where_}, d_c/d0 (negative: pulled)"),
        ));
        fields.push(Field::number(
            &format!("dc_{edge}_error"),
            "d0",
            "absolute error bound of the depth before it (propagated from the ring BEM)",
        ));
        fields.push(Field::number(
            &format!("fc_{edge}"),
            "F0",
            &format!("critical force for detachment at {where_}, F_c/F0 (negative: tensile)"),
        ));
        fields.push(Field::number(
            &format!("fc_{edge}_error"),
            "F0",
            "absolute error bound of the force before it (propagated from the ring BEM)",
        ));
    }
    fields.push(Field::text(
        "governing_edge",
        "the edge that detaches first (the smaller |d_c|): outer or inner",
    ));
    let mut table = Table::new(
        &format!("{words} JKR"),
        fields.iter().map(Field::column).collect(),
    );
    for (k, &eps) in ratios.iter().enumerate() {
        progress(&format!("{words} JKR: {} of {}", k + 1, ratios.len()));
        let r = adhesion::fixed_annulus(solver, eps)?;
        let b = r.error_bounds;
        table.push(vec![
            eps.into(),
            r.dc_outer.into(),
            b.map(|b| b.dc_outer).into(),
            r.fc_outer.into(),
            b.map(|b| b.fc_outer).into(),
            r.dc_inner.into(),
            b.map(|b| b.dc_inner).into(),
            r.fc_inner.into(),
            b.map(|b| b.fc_inner).into(),
            Cell::Text(r.governing_edge.clone()),
        ]);
    }
    Ok(Resource {
        name: format!("jkr-{}", annulus.label()),
        title: format!("{annulus}: JKR detachment at either edge"),
        description: format!(
            "Critical states of the JKR-adhesive {words} (fixed grips, the paper's eqs. 15-20 \
             with gamma from the ring BEM): detachment at the rim or at the inner edge. Units: \
             d0 = sqrt(2 pi a dw / E*), F0 = sqrt(8 pi a^3 E* dw) (Kendall's force on the flat \
             disk of radius a)."
        ),
        fields,
        table,
        interpolation_error: Vec::new(),
    })
}

/// The fields of one critical state (`prefix_force`, its bound, `prefix_eps`, `prefix_depth`,
/// its bound, `prefix_edge`).
fn critical_fields(prefix: &str, what: &str) -> Vec<Field> {
    vec![
        Field::number(
            &format!("{prefix}_force"),
            "F0",
            &format!("{what}: pull-off force F/F0 (negative: tensile)"),
        ),
        Field::number(
            &format!("{prefix}_force_error"),
            "F0",
            "absolute error bound of the force before it (propagated from the ring BEM)",
        ),
        Field::number(
            &format!("{prefix}_eps"),
            "1",
            &format!("{what}: contact ratio b/a at pull-off (0: full contact)"),
        ),
        Field::number(
            &format!("{prefix}_depth"),
            "h",
            &format!("{what}: depth at pull-off, d/h"),
        ),
        Field::number(
            &format!("{prefix}_depth_error"),
            "h",
            "absolute error bound of the depth before it",
        ),
        Field::text(
            &format!("{prefix}_edge"),
            "the edge whose Griffith condition sets the pull-off (inner, rim, rim (full contact))",
        ),
    ]
}

fn critical_cells(c: Option<&Critical>) -> Vec<Cell> {
    match c {
        Some(c) => vec![
            c.force.into(),
            c.error_bound.into(),
            c.eps.into(),
            c.depth.into(),
            c.depth_error_bound.into(),
            Cell::Text(c.governing_edge.clone()),
        ],
        None => vec![Cell::Missing; 6],
    }
}

/// A concave punch: the pull-off under fixed load and fixed grips, and from full contact, at
/// each `d0/h` of `scales`.
pub fn concave(
    solver: &RingBem,
    kind: PunchKind,
    scales: &[f64],
    progress: &dyn Fn(&str),
) -> Result<Resource> {
    let mut fields = vec![Field::number(
        "d0_over_h",
        "1",
        "work of adhesion as d0/h, d0 = sqrt(2 pi a dw / E*)",
    )];
    fields.extend(critical_fields(
        "fixed_load",
        "annular contact under fixed load",
    ));
    fields.extend(critical_fields(
        "fixed_grips",
        "annular contact under fixed grips",
    ));
    fields.extend(critical_fields(
        "full_contact",
        "full contact (the hole closed; the same under fixed load and fixed grips)",
    ));
    let mut table = Table::new(
        &format!("{kind} JKR"),
        fields.iter().map(Field::column).collect(),
    );
    let branch = adhesion::ConcaveBranch::new(solver, kind.clone())?;
    for (k, &s) in scales.iter().enumerate() {
        progress(&format!(
            "{kind} JKR: {} of {} (d0/h = {s:.3})",
            k + 1,
            scales.len()
        ));
        let r = branch.jkr(s)?;
        let mut row: Vec<Cell> = vec![s.into()];
        row.extend(critical_cells(r.fixed_load.as_ref()));
        row.extend(critical_cells(r.fixed_grips.as_ref()));
        row.extend(critical_cells(Some(&r.full_contact.pulloff)));
        table.push(row);
    }
    Ok(Resource {
        name: format!("jkr-{}", kind.label()),
        title: format!("{kind}: JKR pull-off against d0/h"),
        description: format!(
            "JKR-adhesive {kind} (Griffith condition at the inner edge, detachment of the rim \
             where its energy release rate reaches dw), from the ring BEM's non-adhesive \
             solutions: the pull-off from the annular contact under fixed load and under fixed \
             grips (empty where no stable annular branch exists), and from full contact. \
             Units: F0 = sqrt(8 pi a^3 E* dw), d0 = sqrt(2 pi a dw / E*)."
        ),
        fields,
        table,
        interpolation_error: Vec::new(),
    })
}

/// A free band: the pull-off under fixed load and fixed grips (Griffith condition at both free
/// edges, [`adhesion::band_jkr`]) at each `d0/h` of `scales`, beside the plane-strain JKR
/// cylinder's fixed-load pull-off (the narrow limit).
pub fn free_band(
    solver: &RingBem,
    band: &PunchKind,
    scales: &[f64],
    progress: &dyn Fn(&str),
) -> Result<Resource> {
    let gap = band
        .shape_name()
        .map_or_else(|| band.describe(), |name| name.summary().gap.to_string());
    let fields = band_fields(&gap);
    let label = band.label();
    let mut table = Table::new(
        &format!("{label} JKR"),
        fields.iter().map(Field::column).collect(),
    );
    let cells = |c: Option<&adhesion::BandCritical>| -> Vec<Cell> {
        match c {
            Some(c) => vec![
                c.force.into(),
                c.error_bound.into(),
                c.eps.into(),
                c.outer.into(),
                c.depth.into(),
                c.depth_error_bound.into(),
            ],
            None => vec![Cell::Missing; 6],
        }
    };
    for (k, &s) in scales.iter().enumerate() {
        progress(&format!(
            "{label} JKR: {} of {} (d0/h = {s:.3e})",
            k + 1,
            scales.len()
        ));
        let r = adhesion::band_jkr(solver, band, s)?;
        let mut row: Vec<Cell> = vec![s.into()];
        row.extend(cells(r.fixed_load.as_ref()));
        row.extend(cells(r.fixed_grips.as_ref()));
        row.push(r.plane_strain_fixed_load.map_or(Cell::Missing, Cell::from));
        table.push(row);
    }
    Ok(Resource {
        name: format!("jkr-{label}"),
        title: format!(
            "{}: JKR pull-off against d0/h (both edges free)",
            capitalised(&label)
        ),
        description: format!(
            "JKR-adhesive {label}, gap {gap}: the band b <= r <= c with the Griffith condition \
             at both edges, from the ring BEM's equilibria; the pull-off under fixed load and \
             under fixed grips, and the plane-strain JKR cylinder's (the narrow limit). In \
             units of h the band is one family for every size of its section. \
             Units: F0 = sqrt(8 pi a^3 E* dw), d0 = sqrt(2 pi a dw / E*)."
        ),
        fields,
        table,
        interpolation_error: Vec::new(),
    })
}

/// The paper's formulas refitted to converged data and the best forms found, with their
/// largest relative errors on `0.05 <= eps <= 0.99`.
pub fn fits(solver: &RingBem) -> Result<Resource> {
    let fields = vec![
        Field::text(
            "function",
            "the fitted function (flat for gamma, else the quantity's key: PUNCH_gamma1, \
             PUNCH_gamma2)",
        ),
        Field::text("paper_form", "the paper's formula"),
        Field::text("paper_parameters", "the paper's parameters, ';'-separated"),
        Field::number(
            "paper_max_relative_error",
            "1",
            "largest relative error of the paper's formula with the paper's parameters",
        ),
        Field::number("paper_max_error_eps", "1", "where that error is largest"),
        Field::text(
            "refit_parameters",
            "the paper's formula refitted to the ring BEM, ';'-separated",
        ),
        Field::number(
            "refit_max_relative_error",
            "1",
            "its largest relative error",
        ),
        Field::text("best_form", "the best form found"),
        Field::text("best_parameters", "its parameters, ';'-separated"),
        Field::number("best_max_relative_error", "1", "its largest relative error"),
        Field::number("best_max_error_eps", "1", "where that error is largest"),
    ];
    let mut table = Table::new("fits", fields.iter().map(Field::column).collect());
    let joined = |p: &[f64]| {
        p.iter()
            .map(|x| format!("{x:?}"))
            .collect::<Vec<_>>()
            .join(";")
    };
    for f in fit::run(solver)? {
        table.push(vec![
            Cell::Text(f.name.clone()),
            Cell::Text(f.paper_form.clone()),
            Cell::Text(joined(&f.paper_params)),
            f.paper_max_rel_err.into(),
            f.paper_max_rel_err_eps.into(),
            Cell::Text(joined(&f.params)),
            f.max_rel_err.into(),
            Cell::Text(f.best_form.clone()),
            Cell::Text(joined(&f.best_params)),
            f.best_max_rel_err.into(),
            f.best_max_rel_err_eps.into(),
        ]);
    }
    Ok(Resource {
        name: "fits".into(),
        title: "Fitted formulas and their largest errors".into(),
        description: "The paper's fitted formulas (3), (8), (10) with the paper's parameters, \
                      refitted by Levenberg-Marquardt to ring-BEM data on 60 points of \
                      0.05 <= eps <= 0.99, and the best form found; each with its largest \
                      relative error on 301 points of that range."
            .into(),
        fields,
        table,
        interpolation_error: Vec::new(),
    })
}

/// The columns of a free band's JKR table: `d0/h`, then the pull-off under fixed load and
/// under fixed grips (force, edges, depth, with their bounds), and the plane-strain cylinder's.
fn band_fields(gap: &str) -> Vec<Field> {
    let mut fields = vec![Field::number(
        "d0_over_h",
        "1",
        &format!("work of adhesion as d0/h, d0 = sqrt(2 pi a dw / E*), h from the gap {gap}"),
    )];
    for (prefix, what) in [
        (
            "fixed_load",
            "under fixed load (the minimum of F along the equilibria)",
        ),
        (
            "fixed_grips",
            "under fixed grips (the minimum of d along the equilibria)",
        ),
    ] {
        fields.extend([
            Field::number(
                &format!("{prefix}_force"),
                "F0",
                &format!("pull-off {what}: force F/F0 (negative: tensile)"),
            ),
            Field::number(
                &format!("{prefix}_force_error"),
                "F0",
                "absolute error bound of the force before it (the ring BEM's estimate and the \
                 location's tolerance)",
            ),
            Field::number(
                &format!("{prefix}_eps"),
                "1",
                &format!("pull-off {what}: inner edge of the band, b/a"),
            ),
            Field::number(
                &format!("{prefix}_outer_radius"),
                "1",
                &format!("pull-off {what}: outer edge of the band, c/a"),
            ),
            Field::number(
                &format!("{prefix}_depth"),
                "h",
                &format!("pull-off {what}: depth d/h (negative: pulled)"),
            ),
            Field::number(
                &format!("{prefix}_depth_error"),
                "h",
                "absolute error bound of the depth before it",
            ),
        ]);
    }
    fields.push(Field::number(
        "plane_strain_fixed_load_force",
        "F0",
        "the plane-strain JKR cylinder's fixed-load pull-off over the length 2 pi a, F/F0: the \
         narrow limit d0/h -> 0 (an asymptote, no bound)",
    ));
    fields
}

/// `label` with its first letter upper case (a table's title).
fn capitalised(label: &str) -> String {
    let mut letters = label.chars();
    letters.next().map_or_else(String::new, |first| {
        first.to_uppercase().chain(letters).collect()
    })
}
