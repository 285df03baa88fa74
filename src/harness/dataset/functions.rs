//! The non-adhesive functions of the dataset: `γ(ε)` of the fixed annulus, `γ1(ε)`, `γ2(ε)` of
//! the concave punches, and of a free band with its outer edge `c/a` (both edges free; in units
//! of its gap at the axis `h` one family for every size of its section), on a grid uniform in `s =
//! ln(ε/(1 - ε))`, each with the ring BEM's error estimate, and the error of interpolating
//! them, found against fresh solves.
//!
//! Interpolation: the Lagrange cubic in `s` of `ln(value)` through the four nearest grid points,
//! exponentiated (every tabulated function is positive, and near `ε = 1` they fall like powers
//! of `1 - ε`, exponentials in `s`, whose logarithm a cubic follows closely: at 48 intervals 10
//! to 100 times closer than the cubic of the values). Its error is found at the midpoint of
//! every interior interval against a fresh solve there.

use crate::harness::report::table::{Cell, Table};
use ringcontact::error::Result;
use ringcontact::methods::{RingBem, RingState};
use ringcontact::punch::{Contact, PunchKind};

use super::{Field, Resource};

/// The ring BEM's tolerance for the tables.
pub const TOLERANCE: f64 = 1e-9;

/// The contact ratios the ring BEM certifies, the ends of the grid.
pub const EPS_RANGE: (f64, f64) = (1e-4, 0.9999);

/// A free band's ends: below `b = 0.01 a` the parabolic ring's band reaches past `c = 5.8 a`
/// (its profile is far outside its validity there) and the ring BEM no longer reaches 1e-9 by
/// `b = 1e-4 a`.
pub const BAND_EPS_RANGE: (f64, f64) = (1e-2, 0.9999);

/// The ends of `kind`'s grid.
fn eps_range(kind: PunchKind) -> (f64, f64) {
    if kind.is_free_band() {
        BAND_EPS_RANGE
    } else {
        EPS_RANGE
    }
}

/// `s = ln(ε / (1 - ε))`.
fn logit(eps: f64) -> f64 {
    (eps / (1.0 - eps)).ln()
}

/// `ε = 1 / (1 + e^(-s))`.
fn logistic(s: f64) -> f64 {
    1.0 / (1.0 + (-s).exp())
}

/// The grid: `n` intervals uniform in `s` between the ends of [`EPS_RANGE`].
pub fn grid(intervals: usize) -> Vec<f64> {
    grid_over(EPS_RANGE, intervals)
}

/// `n` intervals uniform in `s` between the ends `range` (exact at both ends).
fn grid_over(range: (f64, f64), intervals: usize) -> Vec<f64> {
    let (s0, s1) = (logit(range.0), logit(range.1));
    (0..=intervals)
        .map(|k| {
            let s = s0 + (s1 - s0) * k as f64 / intervals as f64;
            match k {
                0 => range.0,
                k if k == intervals => range.1,
                _ => logistic(s),
            }
        })
        .collect()
}

/// The value at `eps` interpolated from the positive `values` on `grid`: `exp` of the cubic in
/// `s` through `ln(value)` at the four grid points nearest to it.
pub fn interpolate(grid: &[f64], values: &[f64], eps: f64) -> f64 {
    let s = logit(eps);
    let i = grid
        .partition_point(|&g| logit(g) <= s)
        .clamp(2, grid.len() - 2)
        - 2;
    let nodes: Vec<f64> = grid[i..i + 4].iter().map(|&g| logit(g)).collect();
    (0..4)
        .map(|j| {
            let weight: f64 = (0..4)
                .filter(|&m| m != j)
                .map(|m| (s - nodes[m]) / (nodes[j] - nodes[m]))
                .product();
            weight * values[i + j].ln()
        })
        .sum::<f64>()
        .exp()
}

/// One punch's function table: the solve at each state.
struct Solved {
    eps: Vec<f64>,
    states: Vec<RingState>,
}

fn solve_all(
    solver: &RingBem,
    kind: PunchKind,
    eps: &[f64],
    progress: &dyn Fn(&str),
) -> Result<Solved> {
    let mut states = Vec::with_capacity(eps.len());
    for (k, &e) in eps.iter().enumerate() {
        if k % 50 == 0 {
            progress(&format!("{kind}: state {} of {}", k + 1, eps.len()));
        }
        states.push(match kind.has_fixed_hole() {
            true => solver.flat(e, TOLERANCE)?,
            false => solver.concave_at_ratio(&kind, e, TOLERANCE)?,
        });
    }
    Ok(Solved {
        eps: eps.to_vec(),
        states,
    })
}

/// The interpolated columns of `kind`'s table.
fn function_names(kind: PunchKind) -> Vec<&'static str> {
    match kind.contact() {
        Contact::FixedAnnulus | Contact::Disk => vec!["gamma"],
        Contact::FreeBand => vec!["gamma1", "gamma2", "outer_radius"],
        Contact::RimAndFreeInner => vec!["gamma1", "gamma2"],
    }
}

/// The function values of a state (`γ`; `γ1` and `γ2`; a free band's also `c/a`).
fn functions(kind: PunchKind, s: &RingState) -> Vec<f64> {
    match kind.contact() {
        Contact::FixedAnnulus | Contact::Disk => vec![s.gamma.unwrap_or(f64::NAN)],
        Contact::FreeBand => vec![
            s.gamma1.unwrap_or(f64::NAN),
            s.gamma2.unwrap_or(f64::NAN),
            s.outer_edge,
        ],
        Contact::RimAndFreeInner => {
            vec![s.gamma1.unwrap_or(f64::NAN), s.gamma2.unwrap_or(f64::NAN)]
        }
    }
}

/// The largest relative error of interpolating each function at the midpoints of the interior
/// intervals, against fresh solves there.
fn interpolation_error(
    solver: &RingBem,
    kind: PunchKind,
    solved: &Solved,
    progress: &dyn Fn(&str),
) -> Result<Vec<f64>> {
    let grid = &solved.eps;
    let columns: Vec<Vec<f64>> = (0..functions(kind.clone(), &solved.states[0]).len())
        .map(|c| {
            solved
                .states
                .iter()
                .map(|s| functions(kind.clone(), s)[c])
                .collect()
        })
        .collect();
    let midpoints: Vec<f64> = grid
        .windows(2)
        .skip(1)
        .take(grid.len().saturating_sub(3))
        .map(|w| logistic(0.5 * (logit(w[0]) + logit(w[1]))))
        .collect();
    let fresh = solve_all(solver, kind.clone(), &midpoints, progress)?;
    let mut worst = vec![0.0f64; columns.len()];
    for (e, state) in midpoints.iter().zip(&fresh.states) {
        for (c, exact) in functions(kind.clone(), state).into_iter().enumerate() {
            let error = (interpolate(grid, &columns[c], *e) - exact).abs() / exact.abs();
            worst[c] = worst[c].max(error);
        }
    }
    Ok(worst)
}

/// The function table of `kind` on a grid of `intervals` intervals, as a dataset resource.
pub fn resource(
    solver: &RingBem,
    kind: PunchKind,
    intervals: usize,
    progress: &dyn Fn(&str),
) -> Result<Resource> {
    let range = eps_range(kind.clone());
    let solved = solve_all(solver, kind.clone(), &grid_over(range, intervals), progress)?;
    let worst = interpolation_error(solver, kind.clone(), &solved, progress)?;
    let fields = function_fields(&kind);
    let mut table = Table::new(
        &format!("{kind}"),
        fields.iter().map(Field::column).collect(),
    );
    let (fixed_hole, free_band) = table_shape(&kind);
    for (e, s) in solved.eps.iter().zip(&solved.states) {
        let mut row: Vec<Cell> = vec![(*e).into()];
        row.extend(functions(kind.clone(), s).into_iter().map(Cell::from));
        row.push(s.error_estimate.into());
        if !free_band {
            row.push(s.rim_stress_intensity.into());
        }
        if fixed_hole {
            row.push(s.inner_stress_intensity.into());
        }
        table.push(row);
    }
    let names = function_names(kind.clone());
    let interpolation_errors: Vec<String> = names
        .iter()
        .zip(&worst)
        .map(|(n, w)| format!("{n} {w:.1e}"))
        .collect();
    Ok(Resource {
        name: format!("functions-{}", kind.label()),
        title: function_title(&kind),
        description: format!(
            "Non-adhesive {kind}, frictionless, on an elastic half-space (effective modulus E*), \
             by the ring BEM at tolerance {TOLERANCE:e}; {} states uniform in s = ln(eps/(1 - \
             eps)) from eps = {} to {}. Interpolation: exp of the cubic in s through ln(value) \
             at the four nearest rows; its largest relative error measured at the midpoints of the interior \
             intervals against fresh solves: {}.",
            solved.eps.len(),
            range.0,
            range.1,
            interpolation_errors.join(", ")
        ),
        fields,
        table,
        interpolation_error: names
            .iter()
            .zip(&worst)
            .map(|(n, w)| (n.to_string(), *w))
            .collect(),
    })
}

/// Whether `kind`'s table has a fixed hole (`γ` and the inner edge's intensity) and whether
/// its contact is a free band (its outer edge, no rim): asked of the profile's contact.
fn table_shape(kind: &PunchKind) -> (bool, bool) {
    match kind.contact() {
        Contact::FixedAnnulus => (true, false),
        Contact::FreeBand => (false, true),
        Contact::Disk | Contact::RimAndFreeInner => (false, false),
    }
}

/// The title of `kind`'s function table.
fn function_title(kind: &PunchKind) -> String {
    match table_shape(kind) {
        (true, _) => format!("{kind}: gamma(eps) = F/(2 E* d a)"),
        (_, true) => {
            format!("{kind}: gamma1(eps) = d/h, gamma2(eps) = F/(2 E* h a) and c/a, h = a²/(2 rho)")
        }
        _ => format!("{kind}: gamma1(eps) = d/h and gamma2(eps) = F/(2 E* h a)"),
    }
}

/// The columns of `kind`'s function table, with their units and meaning.
fn function_fields(kind: &PunchKind) -> Vec<Field> {
    let (fixed_hole, free_band) = table_shape(kind);
    let mut fields = vec![Field::number(
        "eps",
        "1",
        "contact ratio b/a (a fixed annulus's hole; the inner contact edge of the others)",
    )];
    if fixed_hole {
        fields.push(Field::number(
            "gamma",
            "1",
            "F/(2 E* d a): force of the fixed annulus at depth d",
        ));
    } else {
        fields.push(Field::number(
            "gamma1",
            "1",
            "d/h: depth at which the contact ratio is eps",
        ));
        fields.push(Field::number(
            "gamma2",
            "1",
            "F/(2 E* h a): force at that depth",
        ));
    }
    if free_band {
        fields.push(Field::number(
            "outer_radius",
            "1",
            "c/a: the band's outer (free) edge; the error estimate covers it too",
        ));
    }
    fields.push(Field::number(
        "error_estimate",
        "1",
        "relative error bound of the gamma columns (the ring BEM's estimate, tolerance 1e-9; the column gives what it reached)",
    ));
    if !free_band {
        fields.push(Field::number(
            "stress_intensity_rim",
            if fixed_hole {
                "E* d / sqrt(a)"
            } else {
                "E* h / sqrt(a)"
            },
            "mode-I stress intensity factor at the rim r = a, K = lim sqrt(2 pi (a - r)) p(r) \
         (from the same solution; not separately bounded)",
        ));
    }
    if fixed_hole {
        fields.push(Field::number(
            "stress_intensity_inner",
            "E* d / sqrt(a)",
            "mode-I stress intensity factor at the inner edge r = b (from the same solution; \
             not separately bounded)",
        ));
    }
    fields
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_interpolation_reproduces_exponentials_of_cubics_and_the_grid_ends_are_exact() {
        let g = grid(40);
        assert_eq!((g[0], g[40]), EPS_RANGE);
        let cubic = |e: f64| {
            let s = logit(e);
            (1.0 + s - 0.05 * s * s + 0.001 * s * s * s).exp()
        };
        let values: Vec<f64> = g.iter().map(|&e| cubic(e)).collect();
        for e in [2e-4, 0.01, 0.3, 0.5, 0.77, 0.9991] {
            assert!(
                (interpolate(&g, &values, e) - cubic(e)).abs() < 1e-9 * cubic(e).abs().max(1.0)
            );
        }
    }
}
