//! A check that compares nothing, or reads a corrupt file as "no problem", is a failure
//!: empty or foreign reports, truncated history lines, garbage stability
//! files, missing result directories, comparisons with nothing compared.

use std::path::PathBuf;

use ringcontact_verify::harness::records::fenicsx;
use ringcontact_verify::harness::records::peers;
use ringcontact_verify::harness::records::stored;
use ringcontact_verify::harness::report::history;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "ringcontact-integrity-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The smallest report with every section `verify history` reads (all empty).
const MINIMAL_REPORT: &str =
    r#"{"comparison": {"rows": [], "fem": [], "identities": []}, "fenicsx": [], "peers": []}"#;

#[test]
fn an_empty_report_is_an_error_not_a_first_run() {
    let dir = scratch("empty-report");
    std::fs::write(dir.join("report.json"), "{}").unwrap();
    let e = history::headline(&dir, "today", "stored", "stored").unwrap_err();
    assert!(e.to_string().contains("not a report"), "{e}");
}

#[test]
fn a_garbage_stability_file_is_an_error_not_zero_wrong_numbers() {
    let dir = scratch("garbage-stability");
    std::fs::write(dir.join("report.json"), MINIMAL_REPORT).unwrap();
    history::headline(&dir, "today", "stored", "stored").unwrap();
    for garbage in [
        "{\"probes\": 3}",
        "[]",
        "[{\"method\": \"fem\"}]",
        "not json",
    ] {
        std::fs::write(dir.join("stability.json"), garbage).unwrap();
        let e = history::headline(&dir, "today", "stored", "stored").unwrap_err();
        assert!(e.to_string().contains("stability.json"), "{garbage}: {e}");
    }
}

#[test]
fn a_truncated_history_line_is_an_error_naming_the_line() {
    let dir = scratch("truncated-history");
    std::fs::write(dir.join("report.json"), MINIMAL_REPORT).unwrap();
    let record = history::headline(&dir, "night-1", "stored", "stored").unwrap();
    let file = dir.join("history.jsonl");
    assert!(history::append(&file, &record).unwrap().is_none());
    assert!(history::append(&file, &record).unwrap().is_some());
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::write(&file, &text[..text.len() - 20]).unwrap();
    let e = history::append(&file, &record).unwrap_err();
    assert!(e.to_string().contains("line 2"), "{e}");
    assert!(history::trend(&file, 10).is_err());
}

#[test]
fn a_missing_results_directory_is_an_error() {
    let dir = scratch("missing").join("verify/fenicsx");
    let e = stored::load_json_dir::<serde_json::Value>(&dir, "FEniCSx result").unwrap_err();
    assert!(e.to_string().contains("verify/fenicsx"), "{e}");
}

#[test]
fn comparing_nothing_is_a_failure() {
    assert_eq!(fenicsx::failures(&[]), 1);
    assert!(fenicsx::coverage(&[]).contains("NOTHING COMPARED"));
    assert_eq!(peers::failures(&[]), 1);
}
