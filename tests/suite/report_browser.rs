//! The report's web page opened in a real browser: Debian's `chromium`, headless,
//! renders `index.html` of a fresh `verify compare` report; the test checks that every chart of
//! the Markdown report is on the page and drawn, that nothing failed to load, and that the
//! screenshot (written to the report directory, `reports/browser-test/screenshot.png`) is not
//! blank.
//!
//! Without chromium when the tests were built the test is reported as ignored (the default
//! `cargo test --release` needs no browser); `.ci/run` installs it and sets
//! `RINGCONTACT_REQUIRE_CHROMIUM=1`, which makes its absence a failure.

use std::path::{Path, PathBuf};
use std::process::Command;

fn chromium() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("RINGCONTACT_CHROMIUM") {
        return Some(PathBuf::from(path));
    }
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .find(|name| {
            Command::new(name)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
        .map(PathBuf::from)
}

fn browser(chromium: &Path, args: &[&str], page: &Path) -> std::process::Output {
    Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .args(args)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("run chromium")
}

/// Lines of the browser's log that report the page's own problems (not the sandbox's D-Bus).
fn page_errors(log: &str) -> Vec<&str> {
    log.lines()
        .filter(|l| {
            l.contains("CONSOLE")
                || l.contains("net::ERR")
                || l.contains("Uncaught")
                || l.contains("Not allowed to load")
        })
        .collect()
}

#[test]
#[cfg_attr(
    chromium_missing,
    ignore = "needs chromium: bash scripts/install_chromium.sh"
)]
fn the_report_page_renders_in_a_browser_with_every_chart() {
    let chromium = chromium().expect("chromium, or RINGCONTACT_CHROMIUM naming it");
    // Kept after the test (reports/ is ignored by git): the page and its screenshot to look at.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("reports/browser-test");
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["compare", "--report"])
        .arg(&dir)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let page = dir.join("index.html");
    let html = std::fs::read_to_string(&page).unwrap();
    // Self-contained: no script, nothing fetched from elsewhere.
    assert!(!html.contains("<script"), "the page has a script");
    assert!(
        !html.contains("src=\"http") && !html.contains("<img"),
        "the page loads files"
    );
    let markdown = std::fs::read_to_string(dir.join("report.md")).unwrap();
    let charts = markdown.matches("![](").count();
    assert!(charts >= 10, "the Markdown report has {charts} charts");

    // The DOM after rendering: every chart there, inline, none missing.
    let dom = browser(&chromium, &["--dump-dom"], &page);
    let dom_text = String::from_utf8_lossy(&dom.stdout);
    assert_eq!(dom_text.matches("<figure data-chart=").count(), charts);
    assert_eq!(dom_text.matches("data-missing-chart").count(), 0);
    assert!(dom_text.matches("<svg").count() >= charts);
    let errors = page_errors(&String::from_utf8_lossy(&dom.stderr)).join("\n");
    assert!(errors.is_empty(), "the browser reported: {errors}");

    // The screenshot: tall enough for the whole page, not blank, with the charts' colours.
    let shot = dir.join("screenshot.png");
    let render = browser(
        &chromium,
        &[
            "--window-size=1280,20000",
            &format!("--screenshot={}", shot.display()),
        ],
        &page,
    );
    let errors = page_errors(&String::from_utf8_lossy(&render.stderr)).join("\n");
    assert!(errors.is_empty(), "the browser reported: {errors}");
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&shot).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut pixels).unwrap();
    let channels = info.color_type.samples();
    let rgb: Vec<[u8; 3]> = pixels[..info.buffer_size()]
        .chunks(channels)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    let white = rgb.iter().filter(|p| **p == [255, 255, 255]).count();
    assert!(white < rgb.len(), "the screenshot is blank");
    let mut distinct: Vec<[u8; 3]> = rgb.iter().step_by(7).copied().collect();
    distinct.sort_unstable();
    distinct.dedup();
    assert!(distinct.len() > 50, "only {} colours", distinct.len());
    // The first series colour of the charts (#1f77b4) is drawn.
    let near = |p: &[u8; 3], q: [u8; 3]| p.iter().zip(q).all(|(a, b)| a.abs_diff(b) <= 12);
    let blue = rgb.iter().filter(|p| near(p, [0x1f, 0x77, 0xb4])).count();
    assert!(
        blue > 1000,
        "chart lines not drawn ({blue} pixels of the first series colour)"
    );
    println!(
        "{}: {}x{}, {} non-white pixels, {} colours, {blue} chart-blue pixels",
        shot.display(),
        info.width,
        info.height,
        rgb.len() - white,
        distinct.len()
    );
}
