//! Lists of states on the command line (`verify table --eps 0.01:0.99:0.01`, `--depth 0.5,1,2`):
//! comma-separated items, each a number or an inclusive range `START:STOP:STEP`.

/// The most states one list may name (a typo such as a step of `1e-9` is refused, not run).
pub const MAX_STATES: usize = 100_000;

/// Parse `text` (the value of `--flag`) into its states, in the order written.
///
/// An item `START:STOP:STEP` stands for `START + i STEP` for `i = 0, 1, ...` up to and including
/// `STOP` (within a millionth of a step, so `0.01:0.99:0.01` ends at `0.99`); each value is
/// rounded to 12 significant digits, so that the decimal values written come out (`0.07`, not
/// `0.07000000000000001`). The error names the flag and the item.
pub fn parse(flag: &str, text: &str) -> Result<Vec<f64>, String> {
    let mut states = Vec::new();
    for item in text.split(',') {
        let item = item.trim();
        if item.is_empty() {
            return Err(format!(
                "{flag} {text:?}: an empty item (write numbers or START:STOP:STEP ranges \
                 separated by commas)"
            ));
        }
        let parts: Vec<&str> = item.split(':').map(str::trim).collect();
        match parts.as_slice() {
            [single] => states.push(number(flag, item, single)?),
            [start, stop, step] => {
                let (start, stop, step) = (
                    number(flag, item, start)?,
                    number(flag, item, stop)?,
                    number(flag, item, step)?,
                );
                range(flag, item, start, stop, step, &mut states)?;
            }
            _ => {
                return Err(format!(
                    "{flag}: {item:?} is neither a number nor a range START:STOP:STEP"
                ))
            }
        }
        if states.len() > MAX_STATES {
            return Err(format!(
                "{flag} {text:?} names more than {MAX_STATES} states; split the table"
            ));
        }
    }
    Ok(states)
}

/// One finite number of an item.
fn number(flag: &str, item: &str, text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!(
            "{flag}: {text:?} in {item:?} is not a finite number"
        )),
    }
}

/// Append the inclusive range `start, start + step, ..., stop` to `states`.
fn range(
    flag: &str,
    item: &str,
    start: f64,
    stop: f64,
    step: f64,
    states: &mut Vec<f64>,
) -> Result<(), String> {
    if step <= 0.0 {
        return Err(format!(
            "{flag}: the step of {item:?} must be > 0 (write the range from the smaller value)"
        ));
    }
    if stop < start {
        return Err(format!(
            "{flag}: {item:?} runs from {start} down to {stop}; write START <= STOP"
        ));
    }
    let intervals = ((stop - start) / step * (1.0 + 1e-12) + 1e-6).floor();
    if intervals.is_nan() || intervals >= MAX_STATES as f64 {
        return Err(format!(
            "{flag}: {item:?} names more than {MAX_STATES} states; use a larger step"
        ));
    }
    for i in 0..=intervals as usize {
        states.push(twelve_digits(start + i as f64 * step));
    }
    Ok(())
}

/// `x` rounded to 12 significant digits (the decimal the user wrote, without binary noise).
fn twelve_digits(x: f64) -> f64 {
    format!("{x:.11e}").parse().unwrap_or(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_range_includes_its_end_and_the_decimals_written() {
        let states = parse("--eps", "0.01:0.99:0.01").unwrap();
        assert_eq!(states.len(), 99);
        assert_eq!(states[0], 0.01);
        assert_eq!(states[6], 0.07);
        assert_eq!(states[98], 0.99);
        assert_eq!(
            parse("--depth", "1:2:0.3").unwrap(),
            vec![1.0, 1.3, 1.6, 1.9]
        );
    }

    #[test]
    fn lists_and_ranges_mix_in_the_order_written() {
        assert_eq!(
            parse("--depth", "0.5, 1,2:3:0.5,-1").unwrap(),
            vec![0.5, 1.0, 2.0, 2.5, 3.0, -1.0]
        );
        assert_eq!(parse("--force", "4").unwrap(), vec![4.0]);
    }

    #[test]
    fn bad_lists_are_named() {
        for (text, says) in [
            ("0.1,,0.2", "empty item"),
            ("0.1,x", "\"x\" in \"x\" is not a finite number"),
            ("1:0:0.1", "down to"),
            ("0:1:0", "step"),
            ("0:1:-0.1", "step"),
            ("0:1", "neither a number nor a range"),
            ("0:1:1e-9", "more than"),
            ("nan", "not a finite number"),
            ("1:inf:1", "not a finite number"),
        ] {
            let e = parse("--eps", text).unwrap_err();
            assert!(e.contains(says) && e.starts_with("--eps"), "{text}: {e}");
        }
    }
}
