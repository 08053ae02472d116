//! Number fields that cannot break the application: every value typed, dragged or set
//! through accessibility is checked against the rule of what it stands for (the same ranges
//! as the library's loader, `pssurf::limits`) before it is used, and a refused value says
//! why. Numbers are shown for people: six significant digits, no e-notation between 1e-3
//! and 1e6, in fields of a fixed width so panels do not jump as values change.

use pssurf::limits::{MAX_VALUE, MAX_WEIGHT, MIN_WEIGHT};
use pssurf::text::{Short, Significant};

/// Significant digits shown in number fields and value tables.
pub const DIGITS: usize = 6;

/// The width of a number field, in points (fits `-0.123457`; longer numbers scroll inside
/// the field rather than widen the panel).
pub const FIELD_WIDTH: f32 = 62.0;

/// A number for people: [`DIGITS`] significant digits, e-notation only outside 1e-3 … 1e6.
pub fn compact(x: f64) -> String {
    Significant(x, DIGITS).to_string()
}

/// What values a field accepts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rule {
    /// A coordinate or control value: finite, within ±`pssurf::limits::MAX_VALUE`.
    Coordinate,
    /// A rational weight: within `MIN_WEIGHT` … `MAX_WEIGHT`.
    Weight,
    /// A finite value in `lo ..= hi`.
    Within(f64, f64),
    /// A finite value in `lo < x <= hi` (sizes, scales, contrasts).
    Positive(f64),
}

impl Rule {
    /// None when `x` is acceptable, else why not (without the field's name).
    pub fn check(self, x: f64) -> Option<String> {
        let bad = |what: String| Some(format!("{} is refused: {what}", Short(x)));
        if !x.is_finite() {
            return bad("it must be a finite number".into());
        }
        match self {
            Rule::Coordinate if x.abs() > MAX_VALUE => bad(format!(
                "coordinates must be within ±{} (the range the library accepts)",
                Short(MAX_VALUE)
            )),
            Rule::Weight if !(MIN_WEIGHT..=MAX_WEIGHT).contains(&x) => bad(format!(
                "weights must be between {} and {}",
                Short(MIN_WEIGHT),
                Short(MAX_WEIGHT)
            )),
            Rule::Within(lo, hi) if !(lo..=hi).contains(&x) => bad(format!(
                "it must be between {} and {}",
                Short(lo),
                Short(hi)
            )),
            Rule::Positive(hi) if !(x > 0.0 && x <= hi) => {
                bad(format!("it must be positive and at most {}", Short(hi)))
            }
            _ => None,
        }
    }
}

/// What happened to a number field this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// Nothing, or the same value again.
    Unchanged,
    /// A new acceptable value (already stored).
    Changed,
    /// A value that the rule refused (the old value is kept): the message names the field.
    Refused(String),
}

impl Outcome {
    /// Whether the value changed.
    pub fn changed(&self) -> bool {
        *self == Outcome::Changed
    }

    /// The refusal message, if any.
    pub fn refusal(self) -> Option<String> {
        match self {
            Outcome::Refused(m) => Some(m),
            _ => None,
        }
    }
}

/// A number field named `name` (the name is its accessibility label): drag to change by
/// `speed` per pixel, or click and type. The value changes only when `rule` accepts it.
pub fn number(ui: &mut egui::Ui, name: &str, value: &mut f64, rule: Rule, speed: f64) -> Outcome {
    number_enabled(ui, true, name, value, rule, speed)
}

/// A visible label `name`, then a [`number`] field named by it.
pub fn labelled(ui: &mut egui::Ui, name: &str, value: &mut f64, rule: Rule, speed: f64) -> Outcome {
    let label = ui.label(name);
    field(ui, true, name, Some(label.id), value, rule, speed)
}

/// [`number`], greyed out and fixed unless `enabled`.
pub fn number_enabled(
    ui: &mut egui::Ui,
    enabled: bool,
    name: &str,
    value: &mut f64,
    rule: Rule,
    speed: f64,
) -> Outcome {
    field(ui, enabled, name, None, value, rule, speed)
}

/// A number field named `name`, or by the label `label` when given.
fn field(
    ui: &mut egui::Ui,
    enabled: bool,
    name: &str,
    label: Option<egui::Id>,
    value: &mut f64,
    rule: Rule,
    speed: f64,
) -> Outcome {
    let old = *value;
    let mut typed = old;
    let shown = compact(old);
    let field = egui::DragValue::new(&mut typed)
        .speed(speed)
        .custom_formatter(|x, _| compact(x))
        // The shown text of the current value stands for the exact value, so that clicking
        // into a field and leaving it does not round the value to the digits shown.
        .custom_parser(move |t| {
            let t = t.trim();
            if t == shown {
                Some(old)
            } else {
                t.replace('−', "-").parse().ok()
            }
        });
    let height = ui.spacing().interact_size.y;
    let response = ui.add_enabled_ui(enabled, |ui| ui.add_sized([FIELD_WIDTH, height], field));
    let response = response.inner;
    match label {
        Some(id) => drop(response.labelled_by(id)),
        None => response.widget_info(|| labeled_value(enabled, old, name)),
    }
    if typed == old || (typed.is_nan() && old.is_nan()) || !enabled {
        return Outcome::Unchanged;
    }
    match rule.check(typed) {
        None => {
            *value = typed;
            Outcome::Changed
        }
        Some(why) => Outcome::Refused(format!("{name} = {why}")),
    }
}

/// Accessibility info of a number field with a name (so tests and screen readers find it).
pub fn labeled_value(enabled: bool, value: f64, name: &str) -> egui::WidgetInfo {
    let mut info = egui::WidgetInfo::drag_value(enabled, value);
    info.label = Some(name.to_string());
    info
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_refuse_what_the_library_refuses_and_say_why() {
        assert_eq!(Rule::Coordinate.check(1e60), None);
        assert_eq!(Rule::Coordinate.check(-3.5), None);
        let m = Rule::Coordinate.check(1e300).unwrap();
        assert!(m.contains("1e300") && m.contains("±1e60"), "{m}");
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(Rule::Coordinate.check(bad).unwrap().contains("finite"));
            assert!(Rule::Weight.check(bad).is_some());
            assert!(Rule::Positive(10.0).check(bad).is_some());
            assert!(Rule::Within(0.0, 1.0).check(bad).is_some());
        }
        assert!(
            Rule::Weight
                .check(0.0)
                .unwrap()
                .contains("between 1e-30 and 1e30")
        );
        assert_eq!(Rule::Weight.check(2.5), None);
        assert!(Rule::Positive(10.0).check(0.0).is_some());
        assert!(Rule::Positive(10.0).check(11.0).is_some());
        assert_eq!(Rule::Positive(10.0).check(1e-9), None);
        assert!(Rule::Within(1.0, 20.0).check(0.5).is_some());
    }

    #[test]
    fn compact_numbers_have_six_digits_and_no_e_in_the_middle_range() {
        assert_eq!(compact(0.123_456_789), "0.123457");
        assert_eq!(compact(-26.0), "-26");
        assert_eq!(compact(1e-7), "1e-7");
        assert_eq!(compact(12_345.678_9), "12345.7");
    }
}
