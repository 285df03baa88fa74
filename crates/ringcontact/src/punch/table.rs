//! A measured punch profile: a table of `(r/a, g/h)` points read from a CSV file, interpolated
//! by the monotone piecewise-cubic Hermite interpolant of Fritsch and Carlson (PCHIP, as
//! SciPy's `PchipInterpolator`: weighted harmonic-mean slopes inside, a shape-preserving
//! three-point formula at the ends).
//!
//! The table is a concave punch: its last point is the sharp rim `r = a`, its first the axis,
//! and the gap falls from `g(0) = h` to `g(a) = 0` without rising anywhere (`g/h` is
//! non-increasing), so that the contact is one annulus `[b, a]` whose inner edge is free. PCHIP
//! keeps such data monotone (no overshoot between points) and is `C¹`. On a uniform table it
//! reproduces a smooth profile to third order in the point spacing where the slope is away from
//! zero (the harmonic mean of the two neighbouring secants is a second-order slope there) and to
//! second order next to a zero slope, such as a smooth tip's axis (shown in the tests).
//!
//! File format: one point per line, two numbers `r/a, g/h` separated by a comma (or blanks); an
//! optional first line of column names; blank lines and lines starting with `#` are skipped.

use std::path::Path;

use sha2::{Digest, Sha256};

use super::{Contact, Profile, PunchName, PunchRecord};
use crate::error::{show, Error, Result};

/// Fewest points a table may have: a cubic needs four to be more than a straight line.
pub const MIN_POINTS: usize = 4;
/// Most points a table may have (a measured tip profile has hundreds at most).
pub const MAX_POINTS: usize = 100_000;
/// How far the first and last points may sit from their required values (`r/a = 0, 1`,
/// `g/h = 1, 0`) and still be taken as them.
const END_SLACK: f64 = 1e-9;

/// A validated table profile with its interpolant. Compared by the SHA-256 of its file.
#[derive(Debug)]
pub struct TableProfile {
    /// The file as it was named (command line or scene file).
    source: String,
    /// SHA-256 of the file's bytes, hex.
    sha256: String,
    /// `r/a` of the points, strictly increasing from 0 to 1.
    radii: Vec<f64>,
    /// `g/h` at the points, non-increasing from 1 to 0.
    gaps: Vec<f64>,
    /// The interpolant's slopes `d(g/h)/d(r/a)` at the points (Fritsch-Carlson).
    slopes: Vec<f64>,
}

impl PartialEq for TableProfile {
    fn eq(&self, other: &Self) -> bool {
        self.sha256 == other.sha256
    }
}

impl TableProfile {
    /// Read, validate and interpolate the table in `path`.
    pub fn load(path: &Path) -> Result<TableProfile> {
        let bytes = std::fs::read(path).map_err(|e| Error::file("read", path, e))?;
        let sha256 = hex_sha256(&bytes);
        let text = String::from_utf8(bytes)
            .map_err(|_| Error::file("read", path, "the profile table is not UTF-8 text"))?;
        let (radii, gaps) =
            parse_points(&text).map_err(|message| Error::file("parse", path, message))?;
        Ok(TableProfile {
            source: path.display().to_string(),
            sha256,
            slopes: pchip_slopes(&radii, &gaps),
            radii,
            gaps,
        })
    }

    /// The file as named when it was read.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// SHA-256 of the file, hex (the table's identity and provenance).
    pub fn sha256(&self) -> &str {
        &self.sha256
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.radii.len()
    }

    /// Never true: a table has at least [`MIN_POINTS`] points.
    pub fn is_empty(&self) -> bool {
        self.radii.is_empty()
    }

    /// The points `(r/a, g/h)`.
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.radii.iter().copied().zip(self.gaps.iter().copied())
    }

    /// `g/h` at `rho = r/a`: the cubic Hermite piece through the two neighbouring points,
    /// `g = g_k H00(t) + Δ s_k H10(t) + g_{k+1} H01(t) + Δ s_{k+1} H11(t)`, `t = (rho - r_k)/Δ`.
    /// Even in `rho` below the axis; beyond the rim continued along the rim's tangent.
    pub fn value(&self, rho: f64) -> f64 {
        let rho = rho.abs();
        if rho > 1.0 {
            let last = self.radii.len() - 1;
            return self.gaps[last] + self.slopes[last] * (rho - 1.0);
        }
        let (k, width, t) = self.locate(rho);
        let (t2, t3) = (t * t, t * t * t);
        self.gaps[k] * (2.0 * t3 - 3.0 * t2 + 1.0)
            + width * self.slopes[k] * (t3 - 2.0 * t2 + t)
            + self.gaps[k + 1] * (-2.0 * t3 + 3.0 * t2)
            + width * self.slopes[k + 1] * (t3 - t2)
    }

    /// `d(g/h)/d(r/a)` at `0 <= rho <= 1` (the derivative of [`value`](Self::value)).
    pub fn slope(&self, rho: f64) -> f64 {
        let (k, width, t) = self.locate(rho.clamp(0.0, 1.0));
        self.piece_slope(k, width, t)
    }

    /// `d²(g/h)/d(r/a)²` at `0 <= rho <= 1`, piecewise linear (discontinuous at the points).
    pub fn curvature(&self, rho: f64) -> f64 {
        let (k, width, t) = self.locate(rho.clamp(0.0, 1.0));
        self.piece_curvature(k, width, t)
    }

    /// `g(rho + offset) - g(rho)` (units of `h`) without the cancellation of subtracting two
    /// values: where both radii lie on one cubic piece, its Taylor series about `rho`,
    /// `g' δ + g'' δ²/2 + g''' δ³/6` (exact for a cubic), so the increment keeps its relative
    /// precision as `offset -> 0`; otherwise the difference of the two values.
    pub fn increment(&self, rho: f64, offset: f64) -> f64 {
        let end = rho + offset;
        let inside = |x: f64| (0.0..=1.0).contains(&x);
        if !(inside(rho) && inside(end)) {
            return self.value(end) - self.value(rho);
        }
        let (k, width, _) = self.locate(rho + 0.5 * offset);
        let piece = self.radii[k]..=self.radii[k + 1];
        if !(piece.contains(&rho) && piece.contains(&end)) {
            return self.value(end) - self.value(rho);
        }
        let t = (rho - self.radii[k]) / width;
        let slope = self.piece_slope(k, width, t);
        let curvature = self.piece_curvature(k, width, t);
        let third = ((self.gaps[k] - self.gaps[k + 1]) * 12.0 / width
            + 6.0 * (self.slopes[k] + self.slopes[k + 1]))
            / (width * width);
        offset * (slope + offset * (0.5 * curvature + offset * third / 6.0))
    }

    /// Slope of piece `k` (width `width`) at its local coordinate `t`.
    fn piece_slope(&self, k: usize, width: f64, t: f64) -> f64 {
        let t2 = t * t;
        (self.gaps[k] * (6.0 * t2 - 6.0 * t) + self.gaps[k + 1] * (6.0 * t - 6.0 * t2)) / width
            + self.slopes[k] * (3.0 * t2 - 4.0 * t + 1.0)
            + self.slopes[k + 1] * (3.0 * t2 - 2.0 * t)
    }

    /// Curvature of piece `k` (width `width`) at its local coordinate `t`.
    fn piece_curvature(&self, k: usize, width: f64, t: f64) -> f64 {
        ((self.gaps[k] - self.gaps[k + 1]) * (12.0 * t - 6.0) / width
            + self.slopes[k] * (6.0 * t - 4.0)
            + self.slopes[k + 1] * (6.0 * t - 2.0))
            / width
    }

    /// The table's radii `r/a` (the interpolant's knots).
    pub fn knots(&self) -> &[f64] {
        &self.radii
    }

    /// Interval `k` holding `rho` (`r_k <= rho <= r_{k+1}`), its width and the local coordinate.
    fn locate(&self, rho: f64) -> (usize, f64, f64) {
        let last = self.radii.len() - 2;
        let k = self
            .radii
            .partition_point(|&r| r <= rho)
            .saturating_sub(1)
            .min(last);
        let width = self.radii[k + 1] - self.radii[k];
        (k, width, (rho - self.radii[k]) / width)
    }
}

fn hex_sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

impl super::profile::PiecewiseProfile for TableProfile {
    fn value(&self, rho: f64) -> f64 {
        TableProfile::value(self, rho)
    }
    fn increment(&self, rho: f64, offset: f64) -> f64 {
        TableProfile::increment(self, rho, offset)
    }
    fn slope(&self, rho: f64) -> f64 {
        TableProfile::slope(self, rho)
    }
    fn curvature(&self, rho: f64) -> f64 {
        TableProfile::curvature(self, rho)
    }
    fn break_points(&self) -> &[f64] {
        self.knots()
    }
    fn content_key(&self) -> &str {
        self.sha256()
    }
}

impl Profile for TableProfile {
    fn name(&self) -> &str {
        "table"
    }
    fn builtin(&self) -> Option<PunchName> {
        Some(PunchName::Table)
    }
    fn contact(&self) -> Contact {
        Contact::RimAndFreeInner
    }
    fn gap(&self, rho: f64) -> f64 {
        self.value(rho)
    }
    fn slope(&self, rho: f64) -> f64 {
        TableProfile::slope(self, rho)
    }
    fn label(&self) -> String {
        format!("table-{}", &self.sha256[..12])
    }
    fn flags(&self) -> String {
        format!("--punch table --profile {}", self.source)
    }
    fn describe(&self) -> String {
        format!("table ({})", self.source)
    }
    fn record(&self) -> PunchRecord {
        PunchRecord {
            profile_file: Some(self.source.clone()),
            profile_sha256: Some(self.sha256.clone()),
            ..PunchRecord::named(self.name())
        }
    }
    fn piecewise(&self) -> Option<&dyn super::profile::PiecewiseProfile> {
        Some(self)
    }
    /// The MDR's quadrature of the interpolant ([`super::mdr`]): a table smooth at
    /// the axis closes; one with a slope there does not.
    fn closure(&self) -> Option<(f64, f64)> {
        let full = super::mdr::piecewise_full_contact(self);
        Some((full.closure_depth?, full.closure_force()?))
    }
    /// Whether its full-contact pressure first vanishes on a ring [`OPENING_OFF_AXIS`] or more
    /// from the axis (the MDR).
    fn flatter_than_the_sphere(&self) -> bool {
        super::mdr::piecewise_full_contact(self).opening_radius >= OPENING_OFF_AXIS
    }
}

/// Radius (units of `a`) from which a table's full contact is taken to open on a ring rather
/// than at the axis: the MDR's maximisation places the opening of `1 - ρ²` within 1e-10 of it,
/// that of `1 - ρ^2.05` at 0.035.
const OPENING_OFF_AXIS: f64 = 1e-3;

/// The points of a table file, checked: at least [`MIN_POINTS`], finite, `r/a` strictly
/// increasing from 0 to 1, `g/h` non-increasing from 1 to 0. Errors name the line.
fn parse_points(text: &str) -> std::result::Result<(Vec<f64>, Vec<f64>), String> {
    let mut radii = Vec::new();
    let mut gaps = Vec::new();
    let mut lines = Vec::new();
    for (index, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let numbers: Vec<Option<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        if radii.is_empty() && lines.is_empty() && numbers.iter().all(Option::is_none) {
            // A header row of column names.
            lines.push(index + 1);
            continue;
        }
        let number = index + 1;
        if fields.len() != 2 {
            return Err(format!(
                "line {number}: expected two numbers `r/a, g/h`, found {} field(s) in `{line}`",
                fields.len()
            ));
        }
        let (Some(r), Some(g)) = (numbers[0], numbers[1]) else {
            return Err(format!(
                "line {number}: `{line}` is not two numbers `r/a, g/h`"
            ));
        };
        if !(r.is_finite() && g.is_finite()) {
            return Err(format!("line {number}: non-finite value in `{line}`"));
        }
        if let Some(&previous) = radii.last() {
            if r <= previous {
                return Err(format!(
                    "line {number}: r/a = {} does not increase (the previous point is at {}); \
                     the points must be sorted by radius, each radius once",
                    show(r),
                    show(previous)
                ));
            }
        }
        if let Some(&previous) = gaps.last() {
            if g > previous {
                return Err(format!(
                    "line {number}: g/h = {} rises above the previous point's {}; a concave \
                     punch's gap must not increase outward (the contact would be several \
                     rings, which one annulus with a free inner edge does not model)",
                    show(g),
                    show(previous)
                ));
            }
        }
        radii.push(r);
        gaps.push(g);
        lines.push(number);
        if radii.len() > MAX_POINTS {
            return Err(format!("more than {MAX_POINTS} points"));
        }
    }
    if radii.len() < MIN_POINTS {
        return Err(format!(
            "{} point(s); a profile table needs at least {MIN_POINTS} (r/a, g/h) points",
            radii.len()
        ));
    }
    let last = radii.len() - 1;
    let ends = [
        (radii[0], 0.0, "the first point's r/a", "the axis"),
        (radii[last], 1.0, "the last point's r/a", "the rim r = a"),
        (
            gaps[0],
            1.0,
            "the first point's g/h",
            "the gap at the axis, which defines h",
        ),
        (
            gaps[last],
            0.0,
            "the last point's g/h",
            "the rim, the punch's lowest point",
        ),
    ];
    for (value, wanted, what, meaning) in ends {
        if (value - wanted).abs() > END_SLACK {
            return Err(format!(
                "{what} is {} but must be {wanted} ({meaning}); scale the table to r/a and g/h",
                show(value)
            ));
        }
    }
    radii[0] = 0.0;
    radii[last] = 1.0;
    gaps[0] = 1.0;
    gaps[last] = 0.0;
    Ok((radii, gaps))
}

/// Fritsch-Carlson slopes of the monotone cubic Hermite interpolant (SciPy's
/// `PchipInterpolator`): inside, the weighted harmonic mean of the neighbouring secants
/// `δ_{k-1}`, `δ_k` (zero where they differ in sign or one vanishes), with weights
/// `2Δ_k + Δ_{k-1}` and `Δ_k + 2Δ_{k-1}`; at the ends the three-point formula, limited to keep
/// the shape.
fn pchip_slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let widths: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let secants: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / widths[k]).collect();
    let mut slopes = vec![0.0; n];
    for k in 1..n - 1 {
        let (left, right) = (secants[k - 1], secants[k]);
        if left * right > 0.0 {
            let w1 = 2.0 * widths[k] + widths[k - 1];
            let w2 = widths[k] + 2.0 * widths[k - 1];
            slopes[k] = (w1 + w2) / (w1 / left + w2 / right);
        }
    }
    slopes[0] = end_slope(widths[0], widths[1], secants[0], secants[1]);
    slopes[n - 1] = end_slope(widths[n - 2], widths[n - 3], secants[n - 2], secants[n - 3]);
    slopes
}

/// Shape-preserving three-point end slope from the end interval (`h0`, `m0`) and its neighbour.
fn end_slope(h0: f64, h1: f64, m0: f64, m1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
    if d.signum() != m0.signum() || m0 == 0.0 {
        0.0
    } else if m0.signum() != m1.signum() && d.abs() > 3.0 * m0.abs() {
        3.0 * m0
    } else {
        d
    }
}

/// What `verify references` says of this punch.
pub(crate) const SUMMARY: super::profile::Summary = super::profile::Summary {
    description:
        "Concave punch of a measured profile: `(r/a, g/h)` points from a CSV file, rim at \
                  the last point `r = a`, inner edge free (give `--profile FILE`)",
    flags: "--punch table --profile FILE",
    gap: "h ĝ(r/a), ĝ by PCHIP through the file's (r/a, g/h)",
    edges: "rim at a, free inner edge",
    closed_forms: "none; full contact by the MDR's quadratures in the ring BEM",
};

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> std::result::Result<TableProfile, String> {
        let (radii, gaps) = parse_points(text)?;
        Ok(TableProfile {
            source: "test".into(),
            sha256: hex_sha256(text.as_bytes()),
            slopes: pchip_slopes(&radii, &gaps),
            radii,
            gaps,
        })
    }

    fn sphere_table(points: usize) -> String {
        let mut text = String::from("r/a,g/h\n");
        for k in 0..points {
            let r = k as f64 / (points - 1) as f64;
            text.push_str(&format!("{r},{}\n", 1.0 - r * r));
        }
        text
    }

    #[test]
    fn interpolates_its_points_and_a_quadratic_nearly() {
        let t = table(&sphere_table(11)).unwrap();
        for (r, g) in t.points() {
            assert!((t.value(r) - g).abs() < 1e-15);
        }
        // A quadratic's three-point end slope is exact: 0 at the axis, -2 at the rim.
        assert!(t.slope(0.0).abs() < 1e-12 && (t.slope(1.0) + 2.0).abs() < 1e-12);
    }

    #[test]
    fn derivatives_are_those_of_the_value() {
        // Away from the points (0.125 apart), where the curvature jumps.
        let t = table(&sphere_table(9)).unwrap();
        let step = 1e-6;
        for rho in [0.05, 0.31, 0.55, 0.77, 0.93] {
            let slope = (t.value(rho + step) - t.value(rho - step)) / (2.0 * step);
            let curvature = (t.slope(rho + step) - t.slope(rho - step)) / (2.0 * step);
            assert!((slope - t.slope(rho)).abs() < 1e-8, "slope at {rho}");
            assert!(
                (curvature - t.curvature(rho)).abs() < 1e-6,
                "curvature at {rho}"
            );
        }
    }

    /// The increment is the difference of two values where that difference is not cancelled
    /// away, and keeps its relative precision as the offset vanishes (where the difference of
    /// values would be all rounding): the slope times the offset, to the curvature's order.
    #[test]
    fn increments_keep_their_precision_as_the_offset_vanishes() {
        let t = table(&sphere_table(9)).unwrap();
        for rho in [0.0, 0.125, 0.3, 0.5, 0.875, 1.0] {
            for offset in [0.2, -0.2, 0.01, -0.01, 0.125, -0.125] {
                let end = rho + offset;
                if !(0.0..=1.0).contains(&end) {
                    continue;
                }
                let difference = t.value(end) - t.value(rho);
                assert!(
                    (t.increment(rho, offset) - difference).abs() < 1e-15,
                    "{rho} {offset}"
                );
            }
            for offset in [1e-9, -1e-13, 1e-300] {
                if !(0.0..=1.0).contains(&(rho + offset)) {
                    continue;
                }
                let linear = t.slope(rho) * offset;
                let relative = (t.increment(rho, offset) - linear) / offset.abs();
                assert!(relative.abs() < 10.0 * offset.abs(), "{rho} {offset}");
            }
        }
    }

    /// The interpolation's order on the parabolic gap's profile `1 - ρ²`, sampled densely: the
    /// largest error falls as the square of the spacing (it sits next to the axis, where the slope
    /// vanishes and the harmonic mean's slope is first-order, `h²/(2 r_k)`); away from the axis
    /// (`ρ >= 1/4`) it falls as the cube.
    #[test]
    fn reproduces_a_smooth_profile_at_its_order() {
        let error = |points: usize, from: f64| {
            let t = table(&sphere_table(points)).unwrap();
            (0..=4000)
                .map(|k| from + (1.0 - from) * k as f64 / 4000.0)
                .map(|rho| (t.value(rho) - (1.0 - rho * rho)).abs())
                .fold(0.0, f64::max)
        };
        for (from, order) in [(0.0, 2.0), (0.25, 3.0)] {
            let errors: Vec<f64> = [11, 21, 41, 81]
                .into_iter()
                .map(|p| error(p, from))
                .collect();
            // The asymptotic range: from 21 points on (11 to 21 gives 2.8 away from the axis).
            for pair in errors.windows(2).skip(1) {
                let observed = (pair[0] / pair[1]).log2();
                assert!(
                    observed > order - 0.1,
                    "from {from}: errors {errors:?}, order {observed:.2}"
                );
            }
        }
    }

    #[test]
    fn bad_tables_are_named() {
        let cases = [
            ("0,1\n0.5,0.7\n1,0\n", "at least 4"),
            ("0,1\n0.5,0.7\n0.4,0.5\n1,0\n", "sorted"),
            ("0,1\n0.3,0.8\n0.6,0.9\n1,0\n", "rises"),
            ("0,1\n0.3,NaN\n0.6,0.5\n1,0\n", "non-finite"),
            ("0,1\n0.3,abc\n0.6,0.5\n1,0\n", "not two numbers"),
            ("0,1\n0.3,0.8,2\n0.6,0.5\n1,0\n", "two numbers"),
            ("0.1,1\n0.3,0.8\n0.6,0.5\n1,0\n", "the axis"),
            ("0,1\n0.3,0.8\n0.6,0.5\n0.9,0\n", "the rim r = a"),
            ("0,2\n0.3,0.8\n0.6,0.5\n1,0\n", "defines h"),
            ("0,1\n0.3,0.8\n0.6,0.5\n1,0.1\n", "lowest point"),
            ("", "0 point(s)"),
        ];
        for (text, expected) in cases {
            let message = table(text).unwrap_err();
            assert!(message.contains(expected), "{text:?}: {message}");
        }
    }

    #[test]
    fn stays_monotone_between_points() {
        // Sharp knee: a cubic spline would overshoot below 0 or above the points.
        let t = table("0,1\n0.5,1\n0.55,0.1\n0.9,0.05\n1,0\n").unwrap();
        let mut previous = f64::INFINITY;
        for k in 0..=1000 {
            let g = t.value(k as f64 / 1000.0);
            assert!(g <= previous + 1e-15 && (0.0..=1.0).contains(&g));
            previous = g;
        }
    }
}
