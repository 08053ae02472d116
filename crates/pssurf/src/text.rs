//! Values in messages: numbers in short form and long text cut, so that an error stays one
//! readable line whatever the input.

use std::fmt;

/// A number in short form for messages: up to four significant digits, in scientific
/// notation outside 1e-3 … 1e6 (`1e200`, `4.5e-30`, `0.125`, `-3`, `NaN`, `inf`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Short(pub f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&Significant(self.0, 4), f)
    }
}

/// A number for people with this many significant digits (1 … 17; at least all the digits
/// before the point), trailing zeros dropped, in scientific notation outside 1e-3 … 1e6
/// only: `Significant(0.000123456, 5)` is `1.2346e-4`, `Significant(2.5, 6)` is `2.5`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Significant(pub f64, pub usize);

impl fmt::Display for Significant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (x, digits) = (self.0, self.1.clamp(1, 17));
        if x == 0.0 || !x.is_finite() {
            // `0` for ±0; NaN and ±inf as Rust writes them.
            return if x == 0.0 {
                f.write_str("0")
            } else {
                write!(f, "{x}")
            };
        }
        let a = x.abs();
        if (1e-3..1e6).contains(&a) {
            let decimals = (digits as i32 - 1 - a.log10().floor() as i32).max(0) as usize;
            let s = format!("{x:.decimals$}");
            let s = if s.contains('.') {
                s.trim_end_matches('0').trim_end_matches('.')
            } else {
                &s
            };
            f.write_str(s)
        } else {
            let s = format!("{x:.prec$e}", prec = digits - 1);
            let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
            let mantissa = if mantissa.contains('.') {
                mantissa.trim_end_matches('0').trim_end_matches('.')
            } else {
                mantissa
            };
            write!(f, "{mantissa}e{exponent}")
        }
    }
}

/// The longest text quoted in a message, in characters.
pub const MAX_QUOTED: usize = 40;

/// `text` cut to its first [`MAX_QUOTED`] characters, with `…` when cut.
pub fn cut(text: &str) -> String {
    match text.char_indices().nth(MAX_QUOTED) {
        Some((end, _)) => format!("{}…", &text[..end]),
        None => text.to_string(),
    }
}

/// The longest message line, in characters (with its `error: ` prefix it stays within 300).
pub const MAX_LINE: usize = 290;

/// A message made readable whatever the input: a number written out in more than 20
/// digits (`1e59` as 60 digits, `1e-300` as 302 characters) is written short ([`Short`]),
/// every other word (a run without spaces) longer than 60 characters, such as an echoed
/// value or path, is cut to its first [`MAX_QUOTED`] characters with `…`, line breaks become
/// spaces, and the whole is cut to [`MAX_LINE`] characters.
pub fn cut_line(text: &str) -> String {
    let words: Vec<String> = text
        .split([' ', '\n', '\r'])
        .map(|w| {
            if let Some(short) = long_number(w) {
                short
            } else if w.chars().count() > 60 {
                cut(w)
            } else {
                w.to_string()
            }
        })
        .collect();
    let joined = words.join(" ");
    match joined.char_indices().nth(MAX_LINE) {
        Some((end, _)) => format!("{}…", &joined[..end]),
        None => joined,
    }
}

/// `word` in short form if it is a number written out in more than 20 characters (followed
/// by punctuation or not): only such expansions, so that coordinates written in full to
/// name a point (`0.30000000000000004`) keep their digits.
fn long_number(word: &str) -> Option<String> {
    let number = word.trim_end_matches([',', ';', ':', ')', ']', '.']);
    let tail = &word[number.len()..];
    let long = number.len() > 20
        && number
            .bytes()
            .all(|b| b.is_ascii_digit() || b"+-.".contains(&b));
    let x: f64 = number.parse().ok().filter(|_| long)?;
    Some(format!("{}{tail}", Short(x)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        let cases = [
            (0.0, "0"),
            (-0.0, "0"),
            (1e200, "1e200"),
            (4.500_000_000_000_000_4e-30, "4.5e-30"),
            (0.125, "0.125"),
            (-3.0, "-3"),
            (123_456.7, "123457"),
            (1.0 / 3.0, "0.3333"),
            (f64::MAX, "1.798e308"),
            (f64::MIN_POSITIVE, "2.225e-308"),
            (5e-324, "4.941e-324"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-inf"),
            (999_999.9, "1000000"),
        ];
        for (x, want) in cases {
            assert_eq!(Short(x).to_string(), want, "{x:e}");
        }
        for k in -320..=308 {
            let x = 1.234_567_89 * 10f64.powi(k);
            assert!(Short(x).to_string().len() <= 11, "{x:e}");
        }
    }

    #[test]
    fn significant_digits_for_people() {
        let cases = [
            (0.000_123_456, 5, "1.2346e-4"),
            (2.5, 6, "2.5"),
            (1.0 / 3.0, 6, "0.333333"),
            (-1234.5678, 6, "-1234.57"),
            (0.001, 6, "0.001"),
            (999_999.0, 6, "999999"),
            (1e6, 6, "1e6"),
            (1e300, 6, "1e300"),
            (-2.0e-7, 5, "-2e-7"),
            (1.5, 1, "2"),
        ];
        for (x, digits, want) in cases {
            assert_eq!(Significant(x, digits).to_string(), want, "{x:e}");
        }
        // Never e-notation in 1e-3 … 1e6, never more than `digits` significant digits.
        for k in 0..2000 {
            let x = 10f64.powf(-3.0 + 9.0 * k as f64 / 2000.0) * 0.999_999_9;
            let s = Significant(x, 5).to_string();
            if (1e-3..1e6).contains(&x) {
                assert!(!s.contains('e'), "{x:e} → {s}");
            }
            let digits = s.trim_start_matches(['0', '.']).replace('.', "");
            let digits = digits.split('e').next().unwrap().trim_end_matches('0');
            assert!(digits.len() <= 6, "{x:e} → {s}");
        }
    }

    #[test]
    fn messages_stay_one_short_line() {
        let value = "7".repeat(400);
        let m = cut_line(&format!(
            "unknown variant `{value}`, expected one of\n`a`, `b`"
        ));
        assert!(!m.contains('\n'));
        assert!(m.starts_with("unknown variant `7777"), "{m}");
        assert!(m.chars().count() < 120, "{m}");
        assert!(cut_line(&"a ".repeat(1000)).chars().count() <= MAX_LINE + 1);
    }

    /// Numbers written out in full (Rust's `{}` of 1e59 or 1e-300) come out short; a
    /// coordinate in full precision keeps its digits.
    #[test]
    fn numbers_written_out_in_full_are_made_short() {
        let m = cut_line(&format!(
            "the radius must be up to 1e12, not {}; tolerance {}, not met at ({}, 2)",
            1e59,
            1e-300,
            0.1 + 0.2
        ));
        assert_eq!(
            m,
            "the radius must be up to 1e12, not 1e59; tolerance 1e-300, not met at (0.30000000000000004, 2)"
        );
        assert_eq!(cut_line(&format!("-{}.", 2e40)), "-2e40.");
    }

    #[test]
    fn long_text_is_cut() {
        assert_eq!(cut("short"), "short");
        let long = "é".repeat(100);
        assert_eq!(cut(&long).chars().count(), MAX_QUOTED + 1);
    }
}
