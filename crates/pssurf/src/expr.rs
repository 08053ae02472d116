//! Height functions z = f(x, y) given as formulas, evaluated with their exact gradient by
//! forward-mode automatic differentiation (dual numbers), so that Hermite interpolation of a
//! formula needs no finite differences.
//!
//! Syntax (parsed by the `exmex` crate): numbers, the variables `x` and `y`, `+ - * / ^`,
//! parentheses, `sin cos tan exp ln sqrt abs`, and the constants `PI` (or `pi`) and `E`.
//! `^` binds tighter than `*` and `/`, which bind tighter than `+` and `-`. A leading minus
//! directly before a power (`-x^2`) is refused: the parser would read it as `(-x)^2`, the
//! opposite of the usual `-(x^2)`, so write either explicitly.

use std::str::FromStr;

use exmex::prelude::*;
use exmex::{BinOp, MakeOperators, Operator, ops_factory};
use thiserror::Error;

/// A value with its partial derivatives w.r.t. x and y.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dual {
    /// The value.
    pub v: f64,
    /// ∂/∂x.
    pub dx: f64,
    /// ∂/∂y.
    pub dy: f64,
}

impl Dual {
    fn constant(v: f64) -> Dual {
        Dual {
            v,
            dx: 0.0,
            dy: 0.0,
        }
    }
    /// f(a) with f'(a) = `d`.
    fn chain(self, v: f64, d: f64) -> Dual {
        Dual {
            v,
            dx: d * self.dx,
            dy: d * self.dy,
        }
    }
}

impl FromStr for Dual {
    type Err = std::num::ParseFloatError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Ok(Dual::constant(s.parse()?))
    }
}

impl std::fmt::Display for Dual {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.v)
    }
}

fn add(a: Dual, b: Dual) -> Dual {
    Dual {
        v: a.v + b.v,
        dx: a.dx + b.dx,
        dy: a.dy + b.dy,
    }
}
fn sub(a: Dual, b: Dual) -> Dual {
    Dual {
        v: a.v - b.v,
        dx: a.dx - b.dx,
        dy: a.dy - b.dy,
    }
}
fn mul(a: Dual, b: Dual) -> Dual {
    Dual {
        v: a.v * b.v,
        dx: a.dx * b.v + a.v * b.dx,
        dy: a.dy * b.v + a.v * b.dy,
    }
}
fn div(a: Dual, b: Dual) -> Dual {
    let q = a.v / b.v;
    Dual {
        v: q,
        dx: (a.dx - q * b.dx) / b.v,
        dy: (a.dy - q * b.dy) / b.v,
    }
}
/// a^b: for a constant exponent b·a^(b−1)·a' (valid for negative a and integer b); otherwise
/// through exp(b ln a).
fn pow(a: Dual, b: Dual) -> Dual {
    let v = a.v.powf(b.v);
    if b.dx == 0.0 && b.dy == 0.0 {
        let d = if b.v == 0.0 {
            0.0
        } else {
            b.v * a.v.powf(b.v - 1.0)
        };
        a.chain(v, d)
    } else {
        let la = a.v.ln();
        Dual {
            v,
            dx: v * (b.dx * la + b.v * a.dx / a.v),
            dy: v * (b.dy * la + b.v * a.dy / a.v),
        }
    }
}

/// The operators on dual numbers (the macro generates an undocumented factory type).
#[allow(missing_docs)]
mod ops {
    use super::*;

    ops_factory!(
        DualOps,
        Dual,
        Operator::make_bin(
            "^",
            BinOp {
                apply: pow,
                prio: 4,
                is_commutative: false
            }
        ),
        Operator::make_bin(
            "*",
            BinOp {
                apply: mul,
                prio: 2,
                is_commutative: true
            }
        ),
        Operator::make_bin(
            "/",
            BinOp {
                apply: div,
                prio: 3,
                is_commutative: false
            }
        ),
        Operator::make_bin_unary(
            "+",
            BinOp {
                apply: add,
                prio: 0,
                is_commutative: true
            },
            |a| a
        ),
        Operator::make_bin_unary(
            "-",
            BinOp {
                apply: sub,
                prio: 1,
                is_commutative: false
            },
            |a| Dual {
                v: -a.v,
                dx: -a.dx,
                dy: -a.dy
            }
        ),
        Operator::make_unary("sin", |a| a.chain(a.v.sin(), a.v.cos())),
        Operator::make_unary("cos", |a| a.chain(a.v.cos(), -a.v.sin())),
        Operator::make_unary("tan", |a| a.chain(a.v.tan(), 1.0 / a.v.cos().powi(2))),
        Operator::make_unary("exp", |a| a.chain(a.v.exp(), a.v.exp())),
        Operator::make_unary("ln", |a| a.chain(a.v.ln(), 1.0 / a.v)),
        Operator::make_unary("sqrt", |a| a.chain(a.v.sqrt(), 0.5 / a.v.sqrt())),
        Operator::make_unary("abs", |a| a.chain(a.v.abs(), a.v.signum())),
        Operator::make_constant("PI", Dual::constant(std::f64::consts::PI)),
        Operator::make_constant("pi", Dual::constant(std::f64::consts::PI)),
        Operator::make_constant("E", Dual::constant(std::f64::consts::E))
    );
}
use ops::DualOps;

/// A formula could not be used.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ExprError {
    /// The text does not parse.
    #[error("cannot parse the formula `{formula}`: {message}")]
    Parse {
        /// The formula.
        formula: String,
        /// The parser's message.
        message: String,
    },
    /// A minus sign in front of a power, whose reading differs between conventions.
    ///
    /// The fields are the operand, the power and the formula.
    #[error("write `-({1})` or `(-{0}){rest}` instead of `-{1}` in `{2}`: a leading minus before a power is ambiguous", rest = &.1[.0.len()..])]
    AmbiguousMinus(String, String, String),
    /// The formula uses a variable other than x and y.
    #[error("the formula may use only the variables x and y, not `{0}`")]
    UnknownVariable(String),
    /// A formula over named variables uses a name that is not one of them.
    #[error("the formula may use only the variables {allowed}, not `{name}`")]
    UnknownName {
        /// The unknown name.
        name: String,
        /// The names allowed, comma separated.
        allowed: String,
    },
    /// The value or gradient is not finite at a point.
    #[error("the formula has no finite value or gradient at ({x}, {y})")]
    NotFinite {
        /// The x coordinate of the point.
        x: f64,
        /// The y coordinate of the point.
        y: f64,
    },
    /// The value or gradient is so large at a point that a control value of the surface
    /// would lie beyond ±1e60.
    #[error("the formula's value or gradient at ({}, {}) gives control values beyond ±1e60", crate::text::Short(*x), crate::text::Short(*y))]
    TooLarge {
        /// The x coordinate of the point.
        x: f64,
        /// The y coordinate of the point.
        y: f64,
    },
}

/// A height function z = f(x, y) from a formula.
#[derive(Clone, Debug)]
pub struct HeightFunction {
    expr: FlatEx<Dual, DualOps>,
    /// For each of the expression's variables (alphabetical), 0 for x and 1 for y.
    vars: Vec<usize>,
}

impl HeightFunction {
    /// Parses a formula in x and y.
    ///
    /// ```
    /// use pssurf::expr::HeightFunction;
    /// let f = HeightFunction::parse("x^2 * sin(y)").unwrap();
    /// let d = f.eval(2.0, 0.5).unwrap();
    /// assert!((d.v - 4.0 * 0.5f64.sin()).abs() < 1e-15);
    /// assert!((d.dx - 4.0 * 0.5f64.sin()).abs() < 1e-15 && (d.dy - 4.0 * 0.5f64.cos()).abs() < 1e-15);
    /// assert!(HeightFunction::parse("x + t").is_err());
    /// ```
    pub fn parse(formula: &str) -> Result<Self, ExprError> {
        let expr = parse_checked(formula)?;
        let vars = expr
            .var_names()
            .iter()
            .map(|v| match v.as_str() {
                "x" => Ok(0),
                "y" => Ok(1),
                other => Err(ExprError::UnknownVariable(other.to_string())),
            })
            .collect::<Result<_, _>>()?;
        Ok(HeightFunction { expr, vars })
    }

    /// The value and gradient at (x, y); an error where they are not finite.
    pub fn eval(&self, x: f64, y: f64) -> Result<Dual, ExprError> {
        let inputs = [
            Dual {
                v: x,
                dx: 1.0,
                dy: 0.0,
            },
            Dual {
                v: y,
                dx: 0.0,
                dy: 1.0,
            },
        ];
        let args: Vec<Dual> = self.vars.iter().map(|&k| inputs[k]).collect();
        let d = self
            .expr
            .eval(&args)
            .map_err(|_| ExprError::NotFinite { x, y })?;
        if d.v.is_finite() && d.dx.is_finite() && d.dy.is_finite() {
            Ok(d)
        } else {
            Err(ExprError::NotFinite { x, y })
        }
    }
}

/// A formula over named variables, evaluated for its value only (a field on a surface, say
/// `K * z` or `abs(k1) - abs(k2)`). Same syntax as [`HeightFunction`].
#[derive(Clone, Debug)]
pub struct Formula {
    expr: FlatEx<Dual, DualOps>,
    /// For each of the expression's variables (alphabetical), its index in the caller's names.
    vars: Vec<usize>,
    text: String,
}

impl Formula {
    /// Parses `formula`, which may use the variables `names` (in that order for [`Formula::eval`]).
    ///
    /// ```
    /// use pssurf::expr::Formula;
    /// let f = Formula::parse("K * z + 1", &["z", "K"]).unwrap();
    /// assert_eq!(f.eval(&[2.0, 3.0]), 7.0);
    /// assert!(Formula::parse("K * w", &["z", "K"]).is_err());
    /// ```
    pub fn parse(formula: &str, names: &[&str]) -> Result<Self, ExprError> {
        let expr = parse_checked(formula)?;
        let vars = expr
            .var_names()
            .iter()
            .map(|v| {
                names
                    .iter()
                    .position(|n| n == v)
                    .ok_or_else(|| ExprError::UnknownName {
                        name: crate::text::cut(v),
                        allowed: names.join(", "),
                    })
            })
            .collect::<Result<_, _>>()?;
        Ok(Formula {
            expr,
            vars,
            text: formula.trim().to_string(),
        })
    }

    /// The value for the variables' `values` (in the order of the names given to
    /// [`Formula::parse`]); NaN where the formula is undefined.
    pub fn eval(&self, values: &[f64]) -> f64 {
        let args: Vec<Dual> = self
            .vars
            .iter()
            .map(|&k| Dual::constant(values[k]))
            .collect();
        self.expr.eval(&args).map_or(f64::NAN, |d| d.v)
    }

    /// The formula as written.
    pub fn text(&self) -> &str {
        &self.text
    }
}

/// Parses a formula after the checks of shape and of a minus before a power.
fn parse_checked(formula: &str) -> Result<FlatEx<Dual, DualOps>, ExprError> {
    check_shape(formula)?;
    check_minus_before_power(formula)?;
    FlatEx::<Dual, DualOps>::parse(formula).map_err(|e| ExprError::Parse {
        formula: crate::text::cut(formula),
        message: parse_message(formula, &e.to_string()),
    })
}

/// Refuses a unary minus whose operand is raised to a power (`-x^2`, `2*-y^2`, `(-3^x)`).
/// The longest formula accepted, in bytes.
pub const MAX_FORMULA: usize = 10_000;
/// The deepest nesting of parentheses accepted.
pub const MAX_NESTING: usize = 100;

/// Refuses formulas too long or too deeply nested to parse and evaluate safely (the parser
/// and evaluator recurse), and unbalanced parentheses, in our words.
fn check_shape(formula: &str) -> Result<(), ExprError> {
    let refuse = |message: String| ExprError::Parse {
        formula: crate::text::cut(formula),
        message,
    };
    if formula.len() > MAX_FORMULA {
        return Err(refuse(format!(
            "it is {} characters long, more than {MAX_FORMULA}",
            formula.len()
        )));
    }
    let mut depth = 0usize;
    for c in formula.chars() {
        match c {
            '(' => depth += 1,
            ')' if depth == 0 => return Err(refuse("a `)` closes nothing".into())),
            ')' => depth -= 1,
            _ => {}
        }
        if depth > MAX_NESTING {
            return Err(refuse(format!(
                "parentheses are nested more than {MAX_NESTING} deep"
            )));
        }
    }
    if depth > 0 {
        return Err(refuse(format!("{depth} `(` not closed")));
    }
    Ok(())
}

/// The functions a formula may use.
const FUNCTIONS: [&str; 7] = ["sin", "cos", "tan", "exp", "ln", "sqrt", "abs"];

/// What is wrong with a formula the parser refused, in our words (its own messages describe
/// its internals).
fn parse_message(formula: &str, parser: &str) -> String {
    // A name directly followed by `(` that is not one of ours: an unknown function.
    let bytes = formula.as_bytes();
    let mut k = 0;
    while k < bytes.len() {
        if bytes[k].is_ascii_alphabetic() {
            let start = k;
            while k < bytes.len() && (bytes[k].is_ascii_alphanumeric() || bytes[k] == b'_') {
                k += 1;
            }
            let name = &formula[start..k];
            let next = formula[k..].trim_start().chars().next();
            if next == Some('(') && !FUNCTIONS.contains(&name) {
                return format!(
                    "`{}` is not a function (use {})",
                    crate::text::cut(name),
                    FUNCTIONS.join(", ")
                );
            }
        } else {
            k += 1;
        }
    }
    if parser.contains("parenthes") {
        return "the parentheses do not match".into();
    }
    format!(
        "it is not a formula in x and y (write numbers, x, y, + − * / ^, parentheses and the functions {})",
        FUNCTIONS.join(", ")
    )
}

fn check_minus_before_power(formula: &str) -> Result<(), ExprError> {
    let c: Vec<char> = formula.chars().collect();
    let mut prev: Option<char> = None; // the last non-space character
    let mut k = 0;
    while k < c.len() {
        let ch = c[k];
        if ch.is_whitespace() {
            k += 1;
            continue;
        }
        let unary = ch == '-' && prev.is_none_or(|p| "(+-*/^,".contains(p));
        if unary {
            // The operand: a number, a name (with a call's argument list) or a parenthesis.
            let start = k + 1;
            let mut j = start;
            while j < c.len() && c[j].is_whitespace() {
                j += 1;
            }
            if j < c.len() && c[j] == '(' {
                j = skip_group(&c, j);
            } else {
                while j < c.len() && (c[j].is_alphanumeric() || c[j] == '.' || c[j] == '_') {
                    j += 1;
                }
                if j < c.len() && c[j] == '(' {
                    j = skip_group(&c, j);
                }
            }
            let mut after = j;
            while after < c.len() && c[after].is_whitespace() {
                after += 1;
            }
            if after < c.len() && c[after] == '^' {
                let operand: String = c[start..j].iter().collect::<String>().trim().to_string();
                let mut e = after + 1;
                while e < c.len() && !"+-*/)".contains(c[e]) {
                    e += 1;
                }
                let power: String = c[start..e].iter().collect::<String>().trim().to_string();
                return Err(ExprError::AmbiguousMinus(
                    operand,
                    power,
                    formula.to_string(),
                ));
            }
        }
        prev = Some(ch);
        k += 1;
    }
    Ok(())
}

/// The index after the parenthesised group starting at `open`.
fn skip_group(c: &[char], open: usize) -> usize {
    let mut depth = 0;
    for (k, &ch) in c.iter().enumerate().skip(open) {
        match ch {
            '(' => depth += 1,
            ')' => {
                depth -= 1;
                if depth == 0 {
                    return k + 1;
                }
            }
            _ => {}
        }
    }
    c.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_are_exact() {
        let f = HeightFunction::parse(
            "exp(-(x^2 + y^2)) + sqrt(1 + x*y) / (2 + cos(3*x)) - abs(y - 0.3)^3 + 2^x",
        )
        .unwrap();
        let g = |x: f64, y: f64| {
            (-(x * x + y * y)).exp() + (1.0 + x * y).sqrt() / (2.0 + (3.0 * x).cos())
                - (y - 0.3).abs().powi(3)
                + 2f64.powf(x)
        };
        for &(x, y) in &[(0.1, 0.2), (-0.7, 0.9), (0.5, -0.4)] {
            let d = f.eval(x, y).unwrap();
            assert!((d.v - g(x, y)).abs() < 1e-14);
            let h = 1e-6;
            let dx = (g(x + h, y) - g(x - h, y)) / (2.0 * h);
            let dy = (g(x, y + h) - g(x, y - h)) / (2.0 * h);
            assert!(
                (d.dx - dx).abs() < 1e-8 && (d.dy - dy).abs() < 1e-8,
                "{d:?} vs {dx} {dy}"
            );
        }
        // Precedence: 2*3^2 is 18, 8/2/2 is 2, 1-x^2 is 1 − x²; a leading minus before a power
        // must be written out.
        for f in ["-x^2", "2*-y^2", "(-3^x)", "1 + -sin(x)^2", "- (x+y)^2"] {
            assert!(
                matches!(HeightFunction::parse(f), Err(ExprError::AmbiguousMinus(..))),
                "{f}"
            );
        }
        assert_eq!(
            HeightFunction::parse("-(x^2)")
                .unwrap()
                .eval(3.0, 0.0)
                .unwrap()
                .v,
            -9.0
        );
        assert_eq!(
            HeightFunction::parse("(-x)^2")
                .unwrap()
                .eval(3.0, 0.0)
                .unwrap()
                .v,
            9.0
        );
        assert_eq!(
            HeightFunction::parse("1-x^2")
                .unwrap()
                .eval(3.0, 0.0)
                .unwrap()
                .v,
            -8.0
        );
        assert_eq!(
            HeightFunction::parse("x^-2")
                .unwrap()
                .eval(2.0, 0.0)
                .unwrap()
                .v,
            0.25
        );
        assert_eq!(
            HeightFunction::parse("-x*y")
                .unwrap()
                .eval(2.0, 3.0)
                .unwrap()
                .v,
            -6.0
        );
        assert_eq!(
            HeightFunction::parse("2*3^2")
                .unwrap()
                .eval(0.0, 0.0)
                .unwrap()
                .v,
            18.0
        );
        assert_eq!(
            HeightFunction::parse("8/2/2")
                .unwrap()
                .eval(0.0, 0.0)
                .unwrap()
                .v,
            2.0
        );
        assert!(matches!(
            HeightFunction::parse("sin("),
            Err(ExprError::Parse { .. })
        ));
        assert_eq!(
            HeightFunction::parse("z").unwrap_err(),
            ExprError::UnknownVariable("z".into())
        );
        assert!(matches!(
            HeightFunction::parse("sqrt(x)").unwrap().eval(-1.0, 0.0),
            Err(ExprError::NotFinite { .. })
        ));
        assert!(
            (HeightFunction::parse("PI")
                .unwrap()
                .eval(0.0, 0.0)
                .unwrap()
                .v
                - std::f64::consts::PI)
                .abs()
                < 1e-15
        );
    }

    /// Issue 13: "errors of the expression parser leak its internal wording"; deep nesting
    /// and huge formulas are refused before the (recursive) parser sees them.
    #[test]
    fn formula_errors_are_in_our_words() {
        let message = |f: &str| HeightFunction::parse(f).unwrap_err().to_string();
        let m = message("foo(x)");
        assert!(m.contains("`foo` is not a function (use sin"), "{m}");
        assert!(!m.contains("wlog"), "{m}");
        assert!(message("sin(x").contains("1 `(` not closed"));
        assert!(message("x)").contains("closes nothing"));
        assert!(message("x + * y").contains("not a formula in x and y"));
        let deep = format!("{}x{}", "(".repeat(500), ")".repeat(500));
        assert!(message(&deep).contains("nested more than 100"));
        let long = "x+".repeat(10_000) + "x";
        let m = message(&long);
        assert!(m.contains("more than 10000") && m.len() < 200, "{m}");
        let ok = format!("{}x{}", "(".repeat(100), ")".repeat(100));
        assert!(HeightFunction::parse(&ok).is_ok());
    }
}
