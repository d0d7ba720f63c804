//! Quantities for people: one formatter for lengths that picks nm, µm, mm or m so that a value
//! prints with four significant digits and no long run of digits ("18.16 µm", not
//! "18155.0 nm"), counts with the noun in the right number ("1 curve", "4 curves"), and lists
//! of values as a list flag takes them ("20,45,60,70").

/// `metres` in the unit that puts it between 1 and 1000 (nm below 1 µm, m from 1 m up), with
/// four significant digits: "3.500 nm", "201.0 nm", "18.16 µm", "3.766 m". Not finite: "-".
/// Beyond what any instrument measures (below a picometre, from 10 km up: a damaged header's
/// spacing, say) in metres in scientific notation, "1.188e-41 m", rather than "0.000 nm".
pub fn length(metres: f64) -> String {
    if !metres.is_finite() {
        return "-".into();
    }
    let a = metres.abs();
    if a != 0.0 && !(1e-12..1e4).contains(&a) {
        return format!("{metres:.3e} m");
    }
    let (value, unit) = length_parts(metres);
    format!("{} {unit}", four_digits(value))
}

/// `metres` as a value and unit for [`length`]; also what a column of lengths shares.
pub fn length_parts(metres: f64) -> (f64, &'static str) {
    let a = metres.abs();
    let (factor, unit) = if a < 1e-6 {
        (1e9, "nm")
    } else if a < 1e-3 {
        (1e6, "µm")
    } else if a < 1.0 {
        (1e3, "mm")
    } else {
        (1.0, "m")
    };
    (metres * factor, unit)
}

/// `v` with four significant digits in fixed notation (decimals from 3 for |v| < 10 down to 0
/// from 1000 up).
fn four_digits(v: f64) -> String {
    let a = v.abs();
    let decimals = if a < 10.0 {
        3
    } else if a < 100.0 {
        2
    } else if a < 1000.0 {
        1
    } else {
        0
    };
    // Rounding can carry into the next decade (9.9996 → "10.000"): one digit fewer then.
    let text = format!("{v:.decimals$}");
    let digits = text.chars().filter(char::is_ascii_digit).count();
    if decimals > 0 && digits > 4 && text.trim_start_matches('-').starts_with("10") {
        format!("{v:.0$}", decimals - 1)
    } else {
        text
    }
}

/// `n` and `noun`, with an "s" unless `n` is 1: "1 curve", "0 curves", "4 curves".
pub fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// `values` as a list flag takes them, comma-separated: "20,45,60,70".
pub fn comma_list<T: std::fmt::Display>(values: &[T]) -> String {
    let text: Vec<String> = values.iter().map(T::to_string).collect();
    text.join(",")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_agree_in_number() {
        assert_eq!(count(1, "curve"), "1 curve");
        assert_eq!(count(0, "file"), "0 files");
        assert_eq!(count(4, "curve"), "4 curves");
    }

    #[test]
    fn each_length_gets_the_unit_that_keeps_it_short() {
        assert_eq!(length(3.5e-9), "3.500 nm");
        assert_eq!(length(0.25e-9), "0.250 nm");
        assert_eq!(length(201e-9), "201.0 nm");
        assert_eq!(length(18.1554e-6), "18.16 µm");
        assert_eq!(length(3.766353231797), "3.766 m");
        assert_eq!(length(-2.5e-4), "-250.0 µm");
        assert_eq!(length(0.0), "0.000 nm");
        assert_eq!(length(1.1884e-41), "1.188e-41 m");
        assert_eq!(length(3.2e15), "3.200e15 m");
        assert_eq!(length(1.5e-3), "1.500 mm");
        assert_eq!(length(0.0), "0.000 nm");
        assert_eq!(length(f64::NAN), "-");
    }

    #[test]
    fn rounding_up_to_the_next_decade_keeps_four_digits() {
        assert_eq!(length(9.9996e-9), "10.00 nm");
        assert_eq!(length(99.996e-9), "100.0 nm");
    }
}
