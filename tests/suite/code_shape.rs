//! The sources stay readable in one sitting: no function in the library's or the program's
//! sources (`crates/ringcontact/src/`, `src/`) runs over 100 lines, and no
//! type's inherent `impl` is spread over several files. Checked on the sources, where a
//! regression would be written (a rough scanner: comments, strings and character literals are
//! blanked before braces are counted).

use crate::common;

use std::collections::BTreeMap;
use std::path::PathBuf;

const LONGEST_FUNCTION: usize = 100;

/// `line` with its comment, string and character literals blanked, so that only code braces
/// remain.
fn code_of(line: &str) -> String {
    let mut out = String::new();
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => break,
            '"' => {
                while let Some(d) = chars.next() {
                    if d == '\\' {
                        chars.next();
                    } else if d == '"' {
                        break;
                    }
                }
                out.push_str("\"\"");
            }
            '\'' => {
                // A character literal ('{', '\n'); a lifetime ('a) has no closing quote nearby.
                let rest: String = chars.clone().take(4).collect();
                let closing = if let Some(escaped) = rest.strip_prefix('\\') {
                    escaped.find('\'').map(|i| i + 1)
                } else {
                    rest.chars().nth(1).filter(|&q| q == '\'').map(|_| 1)
                };
                match closing {
                    Some(k) => {
                        for _ in 0..=k {
                            chars.next();
                        }
                        out.push_str("' '");
                    }
                    None => out.push(c),
                }
            }
            _ => out.push(c),
        }
    }
    out
}

/// `(name, length in lines)` of every function with a body in `text`.
fn function_lengths(text: &str) -> Vec<(String, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let code = code_of(line);
        let Some(at) = code.find("fn ") else {
            continue;
        };
        let before = code[..at].trim();
        let is_item = before.split_whitespace().all(|w| {
            ["pub", "const", "async", "unsafe", "extern"].contains(&w) || w.starts_with("pub(")
        });
        if !is_item {
            continue;
        }
        let name: String = code[at + 3..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let (mut depth, mut started) = (0i64, false);
        for (j, later) in lines.iter().enumerate().skip(i) {
            let code = code_of(later);
            for c in code.chars() {
                match c {
                    '{' => {
                        depth += 1;
                        started = true;
                    }
                    '}' => depth -= 1,
                    _ => {}
                }
            }
            if started && depth == 0 {
                out.push((name.clone(), j - i + 1));
                break;
            }
            if !started && code.trim_end().ends_with(';') {
                break;
            }
        }
    }
    out
}

fn all_sources() -> Vec<PathBuf> {
    let mut files = common::rust_sources(&common::library_root());
    files.extend(common::rust_sources(&common::program_root()));
    files
}

#[test]
fn no_function_runs_over_100_lines() {
    let mut long = Vec::new();
    let mut counted = 0;
    for file in all_sources() {
        let text = std::fs::read_to_string(&file).unwrap();
        for (name, length) in function_lengths(&text) {
            counted += 1;
            if length > LONGEST_FUNCTION {
                long.push(format!("{} {name}: {length} lines", file.display()));
            }
        }
    }
    assert!(counted > 1000, "the scanner found {counted} functions only");
    assert!(
        long.is_empty(),
        "functions over {LONGEST_FUNCTION} lines (split them into named phases):\n{}",
        long.join("\n")
    );
}

#[test]
fn the_scanner_measures_a_function_it_is_given() {
    let text = "pub(crate) fn short() {\n    let s = \"}\";\n    let c = '{';\n}\n\nfn long<'a>(x: &'a str) -> &'a str {\n    x\n}\n";
    assert_eq!(
        function_lengths(text),
        vec![("short".to_string(), 4), ("long".to_string(), 3)]
    );
}

#[test]
fn no_inherent_impl_is_spread_over_files() {
    // Inherent impls by the type's name and the module path of their file; one type, one file.
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut places: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for file in all_sources() {
        let text = std::fs::read_to_string(&file).unwrap();
        let relative = file.strip_prefix(&root).unwrap().display().to_string();
        for line in text.lines() {
            let Some(rest) = line.strip_prefix("impl") else {
                continue;
            };
            let rest = rest.trim_start_matches(|c: char| c != ' ').trim();
            if rest.contains(" for ") || !rest.ends_with('{') {
                continue;
            }
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            let entry = places.entry(name).or_default();
            if !entry.contains(&relative) {
                entry.push(relative.clone());
            }
        }
    }
    // Distinct types that share a name (each defined in the file of its impl) are not a spread
    // impl; one type's impl in a file that does not define it is.
    let defines = |file: &str, name: &str| {
        let text = std::fs::read_to_string(root.join(file)).unwrap();
        text.contains(&format!("struct {name}")) || text.contains(&format!("enum {name}"))
    };
    let spread: Vec<String> = places
        .into_iter()
        .filter(|(name, files)| files.len() > 1 && files.iter().any(|f| !defines(f, name)))
        .map(|(name, files)| format!("{name}: {}", files.join(", ")))
        .collect();
    assert!(
        spread.is_empty(),
        "inherent impls of one type in several files:\n{}",
        spread.join("\n")
    );
}
