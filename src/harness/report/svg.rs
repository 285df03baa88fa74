//! Minimal log-log line charts as standalone SVG (no system libraries, no fonts to ship).

/// Escape text for XML (`&`, `<`, `>`, quotes).
pub(crate) fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('\'', "&apos;")
        .replace('"', "&quot;")
}

/// One named series of `(x, y)` points (both positive).
pub(crate) struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// Error bars: for point `i`, `bars[i] = Some((low, high))` in data units draws a vertical bar
    /// with caps from `low` to `high` (an interval from an error estimate); empty for none.
    pub bars: Vec<Option<(f64, f64)>>,
}

const COLOURS: [&str; 8] = [
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#555555", "#8c564b",
];

/// Chart geometry: width, height and the left, right, top and bottom margins (pixels).
const FRAME: (f64, f64, f64, f64, f64, f64) = (720.0, 480.0, 80.0, 200.0, 40.0, 60.0);

/// The SVG header, white background and title (text already escaped).
fn open(title: &str) -> String {
    let (w, h, left, ..) = FRAME;
    format!(
        "<svg xmlns='http://www.w3.org/2000/svg' width='{w}' height='{h}' viewBox='0 0 {w} {h}' font-family='sans-serif' font-size='12'>\n\
         <rect width='100%' height='100%' fill='white'/>\n<text x='{left}' y='24' font-size='15'>{title}</text>\n"
    )
}

/// Axis labels (text already escaped).
fn axis_labels(x_label: &str, y_label: &str) -> String {
    let (w, h, left, right, top, bottom) = FRAME;
    format!(
        "<text x='{}' y='{}' text-anchor='middle'>{x_label}</text>\n\
         <text transform='translate(18,{}) rotate(-90)' text-anchor='middle'>{y_label}</text>\n",
        (left + w - right) / 2.0,
        h - 16.0,
        (top + h - bottom) / 2.0
    )
}

/// Each series as a polyline (points passing `keep`, mapped by `px`, `py`), with point markers
/// if `markers`, and the legend.
fn draw_series(
    series: &[Series],
    keep: impl Fn(&(f64, f64)) -> bool,
    px: impl Fn(f64) -> f64,
    py: impl Fn(f64) -> f64,
    markers: bool,
) -> String {
    let (w, _, _, right, top, _) = FRAME;
    let mut svg = String::new();
    for (k, s) in series.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        for (p, bar) in s.points.iter().zip(&s.bars) {
            let Some((low, high)) = *bar else { continue };
            if !(keep(p) && keep(&(p.0, low)) && keep(&(p.0, high))) {
                continue;
            }
            let (x, y0, y1) = (px(p.0), py(low), py(high));
            svg += &format!(
                "<g class='error-bar' stroke='{colour}' stroke-width='1.2'><line x1='{x:.1}' y1='{y0:.1}' x2='{x:.1}' y2='{y1:.1}'/>\
                 <line x1='{:.1}' y1='{y0:.1}' x2='{:.1}' y2='{y0:.1}'/><line x1='{:.1}' y1='{y1:.1}' x2='{:.1}' y2='{y1:.1}'/></g>\n",
                x - 4.0,
                x + 4.0,
                x - 4.0,
                x + 4.0
            );
        }
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .filter(|p| keep(p))
            .map(|&(x, y)| (px(x), py(y)))
            .collect();
        let joined: Vec<String> = pts.iter().map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
        svg += &format!(
            "<polyline fill='none' stroke='{colour}' stroke-width='2' points='{}'/>\n",
            joined.join(" ")
        );
        if markers {
            for (x, y) in &pts {
                svg += &format!("<circle cx='{x:.1}' cy='{y:.1}' r='3.5' fill='{colour}'/>\n");
            }
        }
        let ly = top + 20.0 + 18.0 * k as f64;
        svg += &format!(
            "<rect x='{}' y='{}' width='14' height='4' fill='{colour}'/><text x='{}' y='{}'>{}</text>\n",
            w - right + 12.0,
            ly - 4.0,
            w - right + 32.0,
            ly,
            escape(&s.name)
        );
    }
    svg
}

/// Label every `n`-th decade so that at most 10 labels share an axis.
fn label_stride(decades: i32) -> i32 {
    ((decades + 9) / 10).max(1)
}

/// The label of the decade `10^e` (`1e-3`), empty where the stride skips it (its grid line stays).
fn decade_label(e: i32, first: i32, every: i32) -> String {
    if (e - first) % every == 0 {
        format!("1e{e}")
    } else {
        String::new()
    }
}

/// A log-log chart of the series with decade grid lines and a legend.
pub(crate) fn log_log_chart(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> String {
    let (title, x_label, y_label) = (escape(title), escape(x_label), escape(y_label));
    let (w, h, left, right, top, bottom) = FRAME;
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .collect();
    if all.is_empty() {
        return format!("<svg xmlns='http://www.w3.org/2000/svg' width='{w}' height='{h}'><text x='20' y='40'>{title}: no positive data</text></svg>");
    }
    let decade = |v: f64, up: bool| {
        if up {
            10f64.powf(v.log10().ceil())
        } else {
            10f64.powf(v.log10().floor())
        }
    };
    let (x0, x1) = (
        decade(all.iter().map(|p| p.0).fold(f64::INFINITY, f64::min), false),
        decade(all.iter().map(|p| p.0).fold(0.0, f64::max), true),
    );
    let (y0, y1) = (
        decade(all.iter().map(|p| p.1).fold(f64::INFINITY, f64::min), false),
        decade(all.iter().map(|p| p.1).fold(0.0, f64::max), true),
    );
    let (x1, y1) = (
        if x1 <= x0 { x0 * 10.0 } else { x1 },
        if y1 <= y0 { y0 * 10.0 } else { y1 },
    );
    let px =
        |x: f64| left + (x.log10() - x0.log10()) / (x1.log10() - x0.log10()) * (w - left - right);
    let py = |y: f64| {
        h - bottom - (y.log10() - y0.log10()) / (y1.log10() - y0.log10()) * (h - top - bottom)
    };
    let mut svg = open(&title);
    let (ex0, ex1) = (x0.log10().round() as i32, x1.log10().round() as i32);
    let x_every = label_stride(ex1 - ex0);
    for e in ex0..=ex1 {
        let x = px(10f64.powi(e));
        let label = decade_label(e, ex0, x_every);
        svg += &format!("<line x1='{x}' y1='{top}' x2='{x}' y2='{}' stroke='#ddd'/><text x='{x}' y='{}' text-anchor='middle'>{label}</text>\n", h - bottom, h - bottom + 16.0);
    }
    let (ey0, ey1) = (y0.log10().round() as i32, y1.log10().round() as i32);
    let y_every = label_stride(ey1 - ey0);
    for e in ey0..=ey1 {
        let y = py(10f64.powi(e));
        let label = decade_label(e, ey0, y_every);
        svg += &format!("<line x1='{left}' y1='{y}' x2='{}' y2='{y}' stroke='#ddd'/><text x='{}' y='{}' text-anchor='end'>{label}</text>\n", w - right, left - 6.0, y + 4.0);
    }
    svg += &axis_labels(&x_label, &y_label);
    svg += &draw_series(series, |p| p.0 > 0.0 && p.1 > 0.0, px, py, true);
    svg + "</svg>\n"
}

/// A chart with linear axes (values of either sign), grid lines at "nice" steps.
pub(crate) fn linear_chart(title: &str, x_label: &str, y_label: &str, series: &[Series]) -> String {
    linear_chart_drawn(title, x_label, y_label, series, false)
}

/// [`linear_chart`] with a marker at every point (series of one point stay visible).
pub(crate) fn linear_chart_with_markers(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> String {
    linear_chart_drawn(title, x_label, y_label, series, true)
}

fn linear_chart_drawn(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    markers: bool,
) -> String {
    let (title, x_label, y_label) = (escape(title), escape(x_label), escape(y_label));
    let (w, h, left, right, top, bottom) = FRAME;
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    if all.is_empty() {
        return format!("<svg xmlns='http://www.w3.org/2000/svg' width='{w}' height='{h}'><text x='20' y='40'>{title}: no data</text></svg>");
    }
    let bounds = |v: &mut dyn Iterator<Item = f64>| {
        v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        })
    };
    // A constant (or single) value still gets an axis: widen a zero range to ±10 % (or ±1).
    let widen = |(lo, hi): (f64, f64)| {
        if hi > lo {
            (lo, hi)
        } else {
            let pad = (0.1 * lo.abs()).max(if lo == 0.0 { 1.0 } else { 0.0 });
            (lo - pad, hi + pad)
        }
    };
    let (mut x0, mut x1) = widen(bounds(&mut all.iter().map(|p| p.0)));
    let (mut y0, mut y1) = widen(bounds(&mut all.iter().map(|p| p.1)));
    let step = |lo: f64, hi: f64| {
        let raw = ((hi - lo) / 8.0).max(1e-12);
        let mag = 10f64.powf(raw.log10().floor());
        [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|m| m * mag)
            .find(|s| *s >= raw)
            .unwrap_or(10.0 * mag)
    };
    let (sx, sy) = (step(x0, x1), step(y0, y1));
    x0 = (x0 / sx).floor() * sx;
    x1 = (x1 / sx).ceil() * sx;
    y0 = (y0 / sy).floor() * sy;
    y1 = (y1 / sy).ceil() * sy;
    let px = |x: f64| left + (x - x0) / (x1 - x0) * (w - left - right);
    let py = |y: f64| h - bottom - (y - y0) / (y1 - y0) * (h - top - bottom);
    let mut svg = open(&title);
    let mut x = x0;
    while x <= x1 + 1e-9 * sx {
        svg += &format!("<line x1='{0}' y1='{top}' x2='{0}' y2='{1}' stroke='{2}'/><text x='{0}' y='{3}' text-anchor='middle'>{4}</text>\n", px(x), h - bottom, if x.abs() < 1e-9 * sx { "#999" } else { "#ddd" }, h - bottom + 16.0, format_tick(x, sx));
        x += sx;
    }
    let mut y = y0;
    while y <= y1 + 1e-9 * sy {
        svg += &format!("<line x1='{left}' y1='{0}' x2='{1}' y2='{0}' stroke='{2}'/><text x='{3}' y='{4}' text-anchor='end'>{5}</text>\n", py(y), w - right, if y.abs() < 1e-9 * sy { "#999" } else { "#ddd" }, left - 6.0, py(y) + 4.0, format_tick(y, sy));
        y += sy;
    }
    svg += &axis_labels(&x_label, &y_label);
    svg += &draw_series(
        series,
        |p| p.0.is_finite() && p.1.is_finite(),
        px,
        py,
        markers,
    );
    svg + "</svg>\n"
}

/// A tick value with as many decimals as its step needs (step 0.02: two; step 5e-6: six).
fn format_tick(v: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        &s
    };
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_readable_at_any_scale() {
        assert_eq!(format_tick(0.04, 0.02), "0.04");
        assert_eq!(format_tick(1.5e-5, 5e-6), "0.000015");
        assert_eq!(format_tick(-0.0, 0.5), "0");
        assert_eq!(format_tick(200.0, 50.0), "200");
        // Sixteen decades: every second one labelled, the grid line kept.
        assert_eq!(label_stride(16), 2);
        assert_eq!(decade_label(-15, -16, 2), "");
        assert_eq!(decade_label(-14, -16, 2), "1e-14");
        assert_eq!(label_stride(3), 1);
    }

    #[test]
    fn text_is_escaped() {
        let svg = linear_chart(
            "a < b & c",
            "x",
            "y",
            &[Series {
                name: "<s>".into(),
                points: vec![(0.0, 1.0), (1.0, 2.0)],
                bars: Vec::new(),
            }],
        );
        assert!(
            svg.contains("a &lt; b &amp; c") && svg.contains("&lt;s&gt;") && !svg.contains("<s>")
        );
    }
}
