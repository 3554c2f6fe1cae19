//! What a wrong answer's numbers alone say about it, when no plausible
//! mistake of the grader explains it: not finite, zero, a sign, a simple
//! factor, which components are right and which are not.
//!
//! Two rules: a single number never hears "direction", and a factor is
//! printed with the digits that tell it from 1 ("1.0000 times" is never a
//! diagnosis; "1.0000003 times: close, but more than rounding" is).

use spintop::math::Real;

/// The factor between an angle in degrees and the same angle in radians.
const DEGREES: Real = 180.0 / std::f64::consts::PI;

/// Simple factors a formula can be off by, and how to say them.
const FACTORS: [(Real, &str); 16] = [
    (2.0, "2"),
    (0.5, "1/2"),
    (3.0, "3"),
    (1.0 / 3.0, "1/3"),
    (4.0, "4"),
    (0.25, "1/4"),
    (1.5, "3/2"),
    (2.0 / 3.0, "2/3"),
    (std::f64::consts::PI, "π"),
    (1.0 / std::f64::consts::PI, "1/π"),
    (2.0 * std::f64::consts::PI, "2π"),
    (0.5 / std::f64::consts::PI, "1/(2π)"),
    (std::f64::consts::SQRT_2, "√2"),
    (std::f64::consts::FRAC_1_SQRT_2, "1/√2"),
    (DEGREES, "180/π"),
    (1.0 / DEGREES, "π/180"),
];

/// How close two numbers must be to count as equal in a diagnosis.
const SAME: Real = 1e-9;

/// `k` in words: "−1 times" is a sign, "2 times" a factor 2, and any other
/// factor is printed with the digits that tell it from the nearest simple
/// one ("1.0000003", never "1.0000").
pub fn factor_words(k: Real) -> String {
    if (k - 1.0).abs() < SAME {
        return "1".into();
    }
    if (k + 1.0).abs() < SAME {
        return "−1".into();
    }
    for (f, name) in FACTORS {
        if (k / f - 1.0).abs() < 1e-9 {
            return name.into();
        }
        if (k / -f - 1.0).abs() < 1e-9 {
            return format!("−{name}");
        }
    }
    // Far from 1, in exponent form, so that a small factor is not "0.000".
    if k.abs() < 1e-2 || k.abs() >= 1e4 {
        return format!("{k:.3e}").replace('-', "−");
    }
    // Enough significant digits that the printed number is not 1 (or −1).
    let off = (k.abs() - 1.0).abs().max(1e-16);
    let digits = ((-off.log10()).ceil() as usize + 1).clamp(4, 16);
    let text = format!("{:.*}", digits.saturating_sub(1), k);
    text.replace('-', "−")
}

/// What kind of answer the numbers make.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// One real number: no direction, no components.
    Real,
    /// A complex number (real and imaginary part): a modulus and a phase.
    Complex,
    /// A vector: components of one quantity, with a size and a direction.
    Vector,
    /// Numbers of different meaning side by side (two masses): each is
    /// judged on its own, none has a direction.
    Parts,
}

/// The parts of two answers compared one by one.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Part {
    Right,
    Sign,
    Missing,
    Factor(Real),
    Wrong,
}

fn part(a: Real, e: Real, scale: Real) -> Part {
    let tol = 1e-8 * scale.max(1e-300);
    if (a - e).abs() <= tol {
        Part::Right
    } else if (a + e).abs() <= tol {
        Part::Sign
    } else if a.abs() <= tol {
        Part::Missing
    } else if e.abs() > tol {
        Part::Factor(a / e)
    } else {
        Part::Wrong
    }
}

/// What is wrong with `actual` against `expected`, from their numbers alone
/// (parts named generically; a single number is a scalar).
pub fn shape_diagnosis(actual: &[Real], expected: &[Real]) -> String {
    let labels: Vec<String> = (1..=expected.len())
        .map(|i| format!("component {i}"))
        .collect();
    let kind = if expected.len() == 1 {
        Kind::Real
    } else {
        Kind::Vector
    };
    shape(actual, expected, &labels, kind)
}

/// [`shape_diagnosis`] with names for the parts, and whether the answer is a
/// single number.
pub(crate) fn shape(actual: &[Real], expected: &[Real], labels: &[String], kind: Kind) -> String {
    if actual.iter().any(|x| !x.is_finite()) {
        return "your answer is not finite (not a number, or infinite): a division by zero, or the square root of a negative number?".into();
    }
    if actual.len() != expected.len() {
        return "your answer has the wrong number of components".into();
    }
    let dot = |a: &[Real], b: &[Real]| a.iter().zip(b).map(|(x, y)| x * y).sum::<Real>();
    let ne = dot(expected, expected).sqrt();
    let na = dot(actual, actual).sqrt();
    if ne == 0.0 {
        return "the answer here is zero and yours is not: a term that should cancel does not"
            .into();
    }
    if na <= 1e-12 * (1.0 + ne) {
        return "your answer is zero where it should not be: a term is missing, or a variable is never used".into();
    }
    let k = dot(actual, expected) / (ne * ne);
    let residual = actual
        .iter()
        .zip(expected)
        .map(|(a, e)| (a - k * e).powi(2))
        .sum::<Real>()
        .sqrt();
    let what = if kind == Kind::Vector {
        "your answer"
    } else {
        "your value"
    };
    if residual <= 1e-8 * (na + ne) && kind != Kind::Parts {
        return proportional(k, what, kind);
    }
    if let Some((i, j)) = swapped(actual, expected) {
        return format!(
            "{} and {} are swapped: check which index goes where",
            labels[i], labels[j]
        );
    }
    // Not proportional (so not a scalar): which parts are right?
    let parts: Vec<Part> = actual
        .iter()
        .zip(expected)
        .map(|(a, e)| part(*a, *e, ne))
        .collect();
    let named = |p: fn(&Part) -> bool| -> Vec<&str> {
        parts
            .iter()
            .zip(labels)
            .filter(|(x, _)| p(x))
            .map(|(_, l)| l.as_str())
            .collect()
    };
    let right = named(|p| *p == Part::Right);
    if !right.is_empty() || kind == Kind::Parts {
        let mut wrong = Vec::new();
        let signs = named(|p| *p == Part::Sign);
        if !signs.is_empty() {
            wrong.push(format!("{} the wrong sign", list(&signs, "has", "have")));
        }
        let missing = named(|p| *p == Part::Missing);
        if !missing.is_empty() {
            wrong.push(format!(
                "{} zero (a term missing)",
                list(&missing, "is", "are")
            ));
        }
        for (p, l) in parts.iter().zip(labels) {
            if let Part::Factor(f) = p {
                wrong.push(format!("{l} is {} times the right one", factor_words(*f)));
            }
        }
        let other = named(|p| *p == Part::Wrong);
        if !other.is_empty() {
            wrong.push(format!("{} wrong", list(&other, "is", "are")));
        }
        if right.is_empty() {
            return format!("{}: look at each of them alone", wrong.join("; "));
        }
        return format!(
            "{} right; {}: look at the terms of the wrong part alone",
            list(&right, "is", "are"),
            wrong.join("; ")
        );
    }
    let angle = (dot(actual, expected) / (na * ne)).clamp(-1.0, 1.0).acos();
    if kind == Kind::Complex {
        if (na - ne).abs() <= 1e-8 * ne {
            return format!(
                "the right modulus with the wrong phase ({:.1}° off): a factor i, or a sign inside an exponential?",
                angle.to_degrees()
            );
        }
        return format!(
            "wrong in modulus and phase: your modulus is {} times the right one, the phase {:.1}° off",
            factor_words(na / ne),
            angle.to_degrees()
        );
    }
    if (na - ne).abs() <= 1e-8 * ne {
        return format!(
            "the right size in the wrong direction ({:.1}° off): a rotation turning the wrong way, or a sign inside one term?",
            angle.to_degrees()
        );
    }
    format!(
        "wrong in size and direction: your answer is {} times as long and {:.1}° off: check each term against the equation",
        factor_words(na / ne),
        angle.to_degrees()
    )
}

/// The diagnosis of an answer `k` times the right one.
fn proportional(k: Real, what: &str, kind: Kind) -> String {
    if (k + 1.0).abs() < 1e-6 {
        return format!("a sign flip: {what} is exactly −1 times the right one");
    }
    let words = factor_words(k);
    let simple = FACTORS
        .iter()
        .any(|(f, _)| (k.abs() / f - 1.0).abs() < 1e-9);
    if simple && ((k.abs() / DEGREES - 1.0).abs() < 1e-9 || (k.abs() * DEGREES - 1.0).abs() < 1e-9)
    {
        let (yours, right) = if k.abs() > 1.0 {
            ("degrees", "radians")
        } else {
            ("radians", "degrees")
        };
        return format!(
            "{what} is {words} times the right one: an angle in {yours} where {right} belong (Rust's sin, cos and atan2 work in radians)"
        );
    }
    if simple && (k - 0.5).abs() < 1e-9 {
        return format!(
            "right up to a factor {words}: {what} is half the right one (a factor 2 missing?)"
        );
    }
    if simple && (k - 2.0).abs() < 1e-9 {
        return format!(
            "right up to a factor {words}: {what} is twice the right one (a factor 2 too many?)"
        );
    }
    if simple {
        return format!("right up to a factor {words}: {what} is {words} times the right one");
    }

    let off = (k - 1.0).abs();
    if off < 1e-3 {
        return format!(
            "close, but not within the tolerance: {what} is {words} times the right one, more than rounding: a constant rounded, a series cut short, or an iteration stopped too early?"
        );
    }
    if k < 0.0 {
        return format!("the wrong sign and the wrong size: {what} is {words} times the right one");
    }
    if kind != Kind::Vector {
        format!("{what} is {words} times the right one: a missing parameter, or one used twice?")
    } else {
        format!(
            "the right direction, the wrong size: {what} is {words} times the right one (a missing parameter, or one used twice?)"
        )
    }
}

/// "a is", "a and b are", "a, b and c are".
fn list(items: &[&str], one: &str, many: &str) -> String {
    match items {
        [] => String::new(),
        [a] => format!("{a} {one}"),
        [rest @ .., last] => format!("{} and {last} {many}", rest.join(", ")),
    }
}

/// Two parts exchanged, the others right.
fn swapped(actual: &[Real], expected: &[Real]) -> Option<(usize, usize)> {
    let scale = expected.iter().map(|x| x * x).sum::<Real>().sqrt();
    let same = |a: Real, b: Real| (a - b).abs() <= 1e-8 * scale;
    for i in 0..actual.len() {
        for j in i + 1..actual.len() {
            let ok = (0..actual.len()).all(|m| {
                let n = if m == i {
                    j
                } else if m == j {
                    i
                } else {
                    m
                };
                same(actual[m], expected[n])
            });
            if ok && !same(expected[i], expected[j]) {
                return Some((i, j));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_factor_is_printed_with_the_digits_that_tell_it_from_one() {
        assert_eq!(factor_words(2.0), "2");
        assert_eq!(factor_words(-0.5), "−1/2");
        assert_eq!(factor_words(std::f64::consts::PI), "π");
        assert_eq!(factor_words(1.7), "1.700");
        let k = factor_words(1.000_000_3);
        assert!(k.starts_with("1.0000003"), "{k}");
        assert_ne!(k.trim_end_matches('0'), "1.");
    }

    #[test]
    fn a_factor_far_from_one_is_never_printed_as_zero() {
        assert_eq!(factor_words(3.2e-5), "3.200e−5");
        assert_eq!(factor_words(-2.5e6), "−2.500e6");
        assert_eq!(factor_words(180.0 / std::f64::consts::PI), "180/π");
    }

    #[test]
    fn degrees_for_radians_and_two_unrelated_numbers_are_named() {
        let d = shape_diagnosis(&[0.7_f64.to_degrees()], &[0.7]);
        assert!(d.contains("degrees where radians belong"), "{d}");
        let labels = ["m₀".to_string(), "m_em".to_string()];
        let d = shape(&[0.8, 0.2], &[0.9, 0.1], &labels, Kind::Parts);
        assert!(!d.contains("direction"), "{d}");
        assert!(d.contains("m_em is 2 times the right one"), "{d}");
    }

    #[test]
    fn a_scalar_never_hears_direction() {
        for a in [1.7, -3.0, 1.000_01, -0.999] {
            let d = shape_diagnosis(&[a], &[1.0]);
            assert!(!d.contains("direction"), "{d}");
        }
        let d = shape_diagnosis(&[1.7, -3.4, 0.85], &[1.0, -2.0, 0.5]);
        assert!(d.contains("direction") && d.contains("1.700 times"), "{d}");
    }
}
