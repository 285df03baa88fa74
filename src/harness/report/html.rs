//! The report as a web page: `index.html` in the report directory, self-contained (inline SVG and
//! CSS, no network, no script), made from the same `report.md` the Markdown readers get.
//!
//! Layout: a summary bar (checks and failures, the run's date), the paper's claims and this run's
//! verdicts first (they are the report's first section), then every table and chart of the
//! Markdown report with each chart's SVG inlined, links to the data files behind them
//! (`report.json`, CSVs), and, for nightly runs, trend charts of every headline figure over the
//! recorded history with regressions marked ([`trend_section`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use pulldown_cmark::{html, Options, Parser};

use crate::harness::report::history::{Headline, MIN_TIME, SLOWDOWN};
use crate::harness::report::svg::{escape, Series};
use ringcontact::error::{Error, Result};

/// Name of the page in the report directory.
const INDEX: &str = "index.html";

const STYLE: &str = "
body { font-family: system-ui, sans-serif; margin: 0 auto; max-width: 1100px; padding: 0 16px 48px; color: #1a1a1a; }
header.summary { position: sticky; top: 0; background: #fff; border-bottom: 2px solid #ddd; padding: 10px 0; z-index: 1; }
header.summary .badge { display: inline-block; padding: 4px 10px; border-radius: 4px; font-weight: 600; margin-right: 8px; }
.pass { background: #d9f2dd; color: #11561f; } .fail { background: #fbd9d9; color: #8a1111; }
nav a { margin-right: 12px; } nav.contents { margin: 12px 0; line-height: 1.8; }
table { border-collapse: collapse; margin: 8px 0 20px; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: left; vertical-align: top; }
th { background: #f2f2f2; } tr:nth-child(even) td { background: #fafafa; }
td:has(strong) { background: #fbd9d9 !important; }
figure { margin: 10px 0 24px; } figure svg { max-width: 100%; height: auto; border: 1px solid #eee; }
.trends figure { display: inline-block; width: 32%; margin: 4px 0.5%; vertical-align: top; }
.missing { color: #8a1111; border: 2px solid #8a1111; padding: 8px; }
pre { background: #f6f6f6; padding: 8px; overflow-x: auto; font-size: 12px; }
h2 { border-bottom: 1px solid #ddd; padding-bottom: 4px; margin-top: 32px; }
";

fn file_error(path: &Path, what: &str, e: impl std::fmt::Display) -> Error {
    Error::file(what, path, e)
}

/// Replace every `<img src="NAME.svg" ...>` by the SVG file's content (a visible error box when
/// the file is missing: the page never refers to a file).
fn inline_charts(body: &str, dir: &Path) -> String {
    let mut out = String::with_capacity(body.len());
    let mut rest = body;
    while let Some(start) = rest.find("<img src=\"") {
        out.push_str(&rest[..start]);
        let after = &rest[start + 10..];
        let Some(quote) = after.find('"') else {
            out.push_str(&rest[start..]);
            return out;
        };
        let name = &after[..quote];
        let end = after.find('>').map_or(after.len(), |e| e + 1);
        let path = dir.join(name);
        match std::fs::read_to_string(&path) {
            Ok(svg) if name.ends_with(".svg") && svg.contains("<svg") => {
                // Inline from the <svg> element on (an XML declaration is not allowed in HTML).
                let svg = &svg[svg.find("<svg").unwrap_or(0)..];
                let _ = write!(
                    out,
                    "<figure data-chart=\"{}\">{svg}</figure>",
                    escape(name)
                );
            }
            _ => {
                let _ = write!(
                    out,
                    "<div class=\"missing\" data-missing-chart=\"{}\">chart {} is missing from the report directory</div>",
                    escape(name),
                    escape(name)
                );
            }
        }
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

/// Give every `<h2>` an id (`s1`, `s2`, ...) and return the page with the list of
/// `(id, heading)` for the table of contents.
fn number_sections(body: &str) -> (String, Vec<(String, String)>) {
    let mut out = String::with_capacity(body.len());
    let mut contents = Vec::new();
    let mut rest = body;
    while let Some(start) = rest.find("<h2>") {
        out.push_str(&rest[..start]);
        let after = &rest[start + 4..];
        let end = after.find("</h2>").unwrap_or(after.len());
        let id = format!("s{}", contents.len() + 1);
        let _ = write!(out, "<h2 id=\"{id}\">");
        contents.push((id, after[..end].to_string()));
        rest = after;
    }
    out.push_str(rest);
    (out, contents)
}

/// Links to the data files of the report directory (JSON, CSV, Markdown, text).
fn data_links(dir: &Path) -> String {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| {
                    [".json", ".csv", ".md", ".txt"]
                        .iter()
                        .any(|x| n.ends_with(x))
                })
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    let mut html = String::from("<nav><strong>Data:</strong> ");
    for n in &names {
        let _ = write!(html, "<a href=\"{0}\">{0}</a>", escape(n));
    }
    html.push_str("</nav>");
    html
}

/// `(checks, failed, the headline's bold part)` from the report's first line
/// `**N checks, M failed[, K not run: ...].**`.
fn summary_counts(markdown: &str) -> Option<(usize, usize, String)> {
    let line = markdown.lines().find(|l| l.starts_with("**"))?;
    let inner = line.trim_start_matches("**");
    let bold = inner.split("**").next()?.trim_end_matches('.').to_string();
    let mut words = inner.split_whitespace();
    let checks = words.next()?.parse().ok()?;
    words.next()?;
    let failed = words.next()?.trim_end_matches(',').parse().ok()?;
    Some((checks, failed, bold))
}

/// A line chart of one headline figure over the runs (x: run number), with the runs that
/// regressed against the previous one marked.
fn trend_chart(title: &str, unit: &str, values: &[(usize, f64)], regressed: &[usize]) -> String {
    let series = vec![
        Series {
            name: title.to_string(),
            points: values.iter().map(|&(i, v)| (i as f64 + 1.0, v)).collect(),
            bars: Vec::new(),
        },
        Series {
            name: "regression".to_string(),
            points: values
                .iter()
                .filter(|(i, _)| regressed.contains(i))
                .map(|&(i, v)| (i as f64 + 1.0, v))
                .collect(),
            bars: Vec::new(),
        },
    ];
    crate::harness::report::svg::linear_chart_with_markers(title, "run", unit, &series)
}

/// Trend charts of every headline figure over `history` (oldest first): accuracy figures as
/// `log10 |value|` (regression: beyond their tolerance) and times (regression: over [`SLOWDOWN`] times the
/// previous run, both at least [`MIN_TIME`]).
fn trend_section(history: &[Headline]) -> String {
    if history.is_empty() {
        return String::new();
    }
    let mut html = format!(
        "<section class=\"trends\"><h2 id=\"trends\">Trends over {} recorded runs ({} to {})</h2>\n<p>Each chart is one headline figure per run; red points are regressions (accuracy beyond its tolerance, or a time over {SLOWDOWN}x the previous run's). The figures of every run: <a href=\"table-trend.csv\">table-trend.csv</a>.</p>\n",
        history.len(),
        escape(&history[0].date),
        escape(&history[history.len() - 1].date)
    );
    let accuracy_names: std::collections::BTreeSet<&String> =
        history.iter().flat_map(|h| h.accuracy.keys()).collect();
    for name in accuracy_names {
        let values: Vec<(usize, f64)> = history
            .iter()
            .enumerate()
            .filter_map(|(i, h)| {
                h.accuracy
                    .get(name)
                    .map(|&(v, _)| (i, v.abs().max(1e-300).log10()))
            })
            .collect();
        let regressed: Vec<usize> = history
            .iter()
            .enumerate()
            .filter(|(_, h)| h.accuracy.get(name).is_some_and(|&(v, t)| v.abs() > t))
            .map(|(i, _)| i)
            .collect();
        let _ = writeln!(
            html,
            "<figure data-chart=\"trend {}\">{}</figure>",
            escape(name),
            trend_chart(
                name,
                "log10 |value| (tolerance: see report)",
                &values,
                &regressed
            )
        );
    }
    let time_names: std::collections::BTreeSet<&String> =
        history.iter().flat_map(|h| h.times.keys()).collect();
    for name in time_names {
        let values: Vec<(usize, f64)> = history
            .iter()
            .enumerate()
            .filter_map(|(i, h)| h.times.get(name).map(|&t| (i, t)))
            .collect();
        let regressed: Vec<usize> = values
            .windows(2)
            .filter(|w| w[0].1 >= MIN_TIME && w[1].1 >= MIN_TIME && w[1].1 > SLOWDOWN * w[0].1)
            .map(|w| w[1].0)
            .collect();
        let _ = writeln!(
            html,
            "<figure data-chart=\"trend {}\">{}</figure>",
            escape(name),
            trend_chart(name, "wall time, s", &values, &regressed)
        );
    }
    html.push_str("</section>\n");
    html
}

/// The current UTC time as `YYYY-MM-DD HH:MM UTC`.
fn utc_now() -> String {
    let (year, month, day, rem) = utc_civil_now();
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        rem / 3600,
        (rem % 3600) / 60
    )
}

/// The current UTC time as ISO 8601, `YYYY-MM-DDTHH:MM:SS+00:00` (the stored records' dates).
pub(crate) fn utc_now_iso() -> String {
    let (year, month, day, rem) = utc_civil_now();
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}+00:00",
        rem / 3600,
        (rem % 3600) / 60,
        rem % 60
    )
}

/// Year, month, day and seconds into the day now, UTC (civil date from days since 1970,
/// Hinnant's algorithm).
fn utc_civil_now() -> (i64, i64, i64, i64) {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    (year, month, day, rem)
}

/// Write `dir/index.html` from `dir/report.md` (and the SVG charts it names), with trend charts
/// of `history` when given.
pub(crate) fn write_index(dir: &Path, history: Option<&[Headline]>) -> Result<PathBuf> {
    let md_path = dir.join("report.md");
    let markdown =
        std::fs::read_to_string(&md_path).map_err(|e| file_error(&md_path, "read", e))?;
    let mut body = String::new();
    html::push_html(
        &mut body,
        Parser::new_ext(&markdown, Options::ENABLE_TABLES),
    );
    let (body, contents) = number_sections(&inline_charts(&body, dir));
    let (checks, failed, badge) =
        summary_counts(&markdown).unwrap_or((0, 1, "the report's headline is missing".to_string()));
    let title = markdown
        .lines()
        .next()
        .unwrap_or("ringcontact verification report")
        .trim_start_matches('#')
        .trim();
    let generated = format!("page made {}", utc_now());
    let mut page = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<header class=\"summary\"><span class=\"badge {}\">{}</span><span>{}</span> {}</header>\n<main>\n",
        escape(title),
        if failed == 0 && checks > 0 { "pass" } else { "fail" },
        escape(&badge),
        escape(&generated),
        data_links(dir)
    );
    let trends = history.map(trend_section).unwrap_or_default();
    page.push_str("<nav class=\"contents\"><strong>Contents:</strong> ");
    for (id, heading) in &contents {
        let _ = write!(page, "<a href=\"#{id}\">{heading}</a>");
    }
    if !trends.is_empty() {
        page.push_str("<a href=\"#trends\">Trends</a>");
    }
    page.push_str("</nav>\n");
    page.push_str(&body);
    page.push_str(&trends);
    page.push_str("</main>\n</body>\n</html>\n");
    let path = dir.join(INDEX);
    std::fs::write(&path, page).map_err(|e| file_error(&path, "write", e))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn charts_are_inlined_and_a_missing_one_is_shown_not_linked() {
        let dir = std::env::temp_dir().join(format!("ringcontact-html-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("a.svg"), "<?xml version='1.0'?><svg id='a'></svg>").unwrap();
        let body = inline_charts(
            "<p><img src=\"a.svg\" alt=\"\" /><img src=\"b.svg\" alt=\"\" /></p>",
            &dir,
        );
        assert!(
            body.contains("<figure data-chart=\"a.svg\"><svg id='a'></svg></figure>"),
            "{body}"
        );
        assert!(body.contains("data-missing-chart=\"b.svg\""), "{body}");
        assert!(!body.contains("<img"), "{body}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_date_is_a_civil_date() {
        let now = utc_now();
        assert_eq!(now.len(), 20, "{now}");
        assert!(now.starts_with("20") && now.ends_with(" UTC"), "{now}");
    }

    #[test]
    fn the_summary_line_is_read() {
        assert_eq!(
            summary_counts("# t\n\n**75 checks, 2 failed.** Ring BEM ..."),
            Some((75, 2, "75 checks, 2 failed".to_string()))
        );
        assert_eq!(
            summary_counts("# t\n\n**70 checks, 0 failed, 10 not run: need gmsh (10).** ..."),
            Some((
                70,
                0,
                "70 checks, 0 failed, 10 not run: need gmsh (10)".to_string()
            ))
        );
    }
}
