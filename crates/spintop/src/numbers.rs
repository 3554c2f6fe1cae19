//! How numbers are written and read, in one place for every shell and for
//! the core's messages: a time or a value in a message, a parameter echoed
//! in a header, a cell of a table or of a CSV file, an axis label, a count,
//! and a number typed by the user.
//!
//! | function | for | example |
//! |---|---|---|
//! | [`fmt_time`] | a time in a message | `10`, `1.02`, `5.0000e299` |
//! | [`fmt_value`] | a value in a message, exactly | `0.4`, `1e300`, `2.0000000001` |
//! | [`fmt_param`] | a parameter in a header (CLI tables, the live view) | `0.4`, `1e-7`, `4.635` |
//! | [`fmt_exact`] | a parameter to edit: the shortest text that reads back the same | `0.1`, `1e-200` |
//! | [`fmt_num`] | a live number on screen, four significant digits | `0.1281`, `3.200e-14`, `—` |
//! | [`fmt_axis`] | an axis label | `0.25`, `1.235e4` |
//! | [`fmt_count`] | a count in a message | `12000`, `1.8e19` |
//! | [`table`], [`fixed_or_exp`] | a cell of an aligned table | `0.1000000`, `1.000000e-8` |
//! | [`significant`], [`short`], [`csv`] | a real particle's report and its CSV | `4.635e-3`, `50`, `1e-26` |
//! | [`sci`], [`duration`] | the bench table's errors and times | `1.23e-8`, `17.2 µs` |
//! | [`fixed`], [`exponent`], [`signed_fixed`], [`signed_exponent`] | a measured value to the digits its comparison needs: a lesson's tables, a stability row, a figure's summary, a bench's report, an SVG coordinate | `0.12346`, `1.2e-8`, `+0.00031` |
//! | [`parse_number`] | a number the user typed | `'x' is not a number` |
//! | [`non_finite_word`], [`non_finite_in_words`] | a `NaN` or `inf` in prose, found or spelt out | `not-a-number`, `-infinity` |
//!
//! Pure and at the bottom of the crate: it imports nothing of spintop's.

/// The scalar type (the same as [`crate::math::Real`]).
type Real = f64;

/// A time for a message: as written below 10⁷ (and above 10⁻³, or 0), in
/// exponent form outside that (`5.0000e299`, not three hundred digits).
pub fn fmt_time(t: Real) -> String {
    if t == 0.0 || (1e-3..1e7).contains(&t.abs()) {
        let s = format!("{t:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format!("{t:.4e}")
    }
}

/// A value for a message, exactly: as written between 10⁻⁴ and 10⁷ (`0.4`,
/// `250`), in exponent form outside (`1e300`, `1.5e-8`), and `0` for zero.
pub fn fmt_value(x: Real) -> String {
    if x == 0.0 {
        "0".into()
    } else if (1e-4..1e7).contains(&x.abs()) || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A parameter as the user would type it: the shortest text that parses
/// back to the same double (`0.1`, `1e-200`, never 200 zeros). The edit
/// field of the live view starts from it.
pub fn fmt_exact(x: Real) -> String {
    let plain = format!("{x}");
    if plain.len() <= 12 {
        plain
    } else {
        format!("{x:e}")
    }
}

/// The most characters a parameter is shown exactly in by [`fmt_param`].
const PARAM_EXACT_CHARS: usize = 8;

/// An input parameter echoed in a header, the command line's tables and the
/// live view alike: exactly as typed when that is short (`0.4`, `0.001`,
/// `250`, `1e-7`, `6.02e23`), else to four significant digits (a real
/// particle's I₃/I₁ = 4.634615384615384 reads `4.635`), so that a header
/// fits 80 columns; never `-0`.
pub fn fmt_param(x: Real) -> String {
    let x = if x == 0.0 { 0.0 } else { x };
    let plain = format!("{x}");
    let exp = format!("{x:e}");
    // A round number is written as it would be typed: `1e7`, not
    // `10000000` (which the refusals and status lines, echoing the typed
    // text, would then disagree with); `250` and `0.001` stay as they are.
    let (plain_len, exp_len) = (plain.chars().count(), exp.chars().count());
    if plain_len <= PARAM_EXACT_CHARS && !(plain_len >= 6 && exp_len < plain_len) {
        return plain;
    }
    if exp_len <= PARAM_EXACT_CHARS {
        return exp;
    }
    fmt_num(x)
}

/// A number for the screen: four significant digits, an exponent outside
/// [1e-3, 1e5), "—" when undefined.
pub fn fmt_num(x: Real) -> String {
    in_digits(x, 4, 1e-3)
}

/// A number for a narrow column: three significant digits (`1.28e-12`,
/// `0.0773`, `12000`), an exponent outside [1e-2, 1e5), "—" when
/// undefined.
pub fn fmt_short(x: Real) -> String {
    in_digits(x, 3, 1e-2)
}

/// `x` in `sig` significant digits, plainly in [`lower`, 1e5) and with an
/// exponent outside; "—" when undefined.
fn in_digits(x: Real, sig: i32, lower: Real) -> String {
    if !x.is_finite() {
        return "—".into();
    }
    let a = x.abs();
    if a == 0.0 {
        "0".into()
    } else if (lower..1e5).contains(&a) {
        let most = sig - 1 - lower.log10().floor() as i32;
        let digits = (sig - 1 - a.log10().floor() as i32).clamp(0, most) as usize;
        format!("{x:.digits$}")
    } else {
        let digits = (sig - 1) as usize;
        format!("{x:.digits$e}")
    }
}

/// The smallest of 1, 2, 2.5, 5 times a power of ten that is at least `x`
/// (1 for zero or non-finite `x`): a round axis bound.
pub fn nice_ceiling(x: Real) -> Real {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let p = (10.0 as Real).powf(x.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|b| *b >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// An axis label: the shortest exact form when it is short, else [`fmt_num`].
pub fn fmt_axis(x: Real) -> String {
    let plain = format!("{x}");
    if plain.len() <= 6 { plain } else { fmt_num(x) }
}

/// A count for a message: in full below ten million, else in exponent form
/// (`1.8e19`), never a saturated integer's twenty digits; a count beyond the
/// largest double is `more than 1e308`, never `inf`.
pub fn fmt_count(n: Real) -> String {
    if !n.is_finite() {
        "more than 1e308".into()
    } else if n.abs() < 1e7 {
        format!("{n:.0}")
    } else {
        format!("{n:.1e}")
    }
}

/// A step budget in a message (`1e7`, `1e6` a second): every refusal over a
/// budget, on the command line, in a scene and in the live view, writes its
/// limit so, and the steps it would take with [`fmt_about`].
pub fn fmt_budget(limit: Real) -> String {
    format!("{limit:.0e}")
}

/// An estimate for a message (steps, radians, an error): `about 8.9e299`,
/// or `more than 1e308` when it overflows a double, never `about inf`.
pub fn fmt_about(x: Real) -> String {
    if x.is_finite() {
        format!("about {x:.1e}")
    } else {
        "more than 1e308".into()
    }
}

/// A quantity written into a worked formula (a conversion with its numbers
/// put in): five significant digits in exponent form (`2.1476e-28`).
pub fn worked(x: Real) -> String {
    format!("{x:.4e}")
}

/// A cell of the commands' aligned tables: seven decimals where that reads
/// well, else exponent notation.
pub fn table(x: Real) -> String {
    fixed_or_exp(x, 7, 6, 1e6)
}

/// `x` with `digits` decimals when it is 0 or 1e-3 ≤ |x| < `upper`, else in
/// exponent notation with `exp_digits` decimals in the mantissa; never `-0`.
pub fn fixed_or_exp(x: Real, digits: usize, exp_digits: usize, upper: Real) -> String {
    if x == 0.0 || (1e-3..upper).contains(&x.abs()) {
        fixed(x, digits)
    } else {
        exponent(x, exp_digits)
    }
}

/// A measured value with `decimals` decimals, the digits its comparison
/// needs (a lesson's column read against a closed form, a row's notes);
/// never `-0`: a value that rounds to zero is written `0.000`.
pub fn fixed(x: Real, decimals: usize) -> String {
    let s = format!("{x:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

/// A measured value in exponent form with `decimals` decimals in the
/// mantissa (`1.2e-8` for one); never `-0e0`.
pub fn exponent(x: Real, decimals: usize) -> String {
    let x = if x == 0.0 { 0.0 } else { x };
    format!("{x:.decimals$e}")
}

/// [`fixed`] with its sign always written (`+0.00031`, `-2.5`): a difference.
pub fn signed_fixed(x: Real, decimals: usize) -> String {
    signed(fixed(x, decimals))
}

/// [`exponent`] with its sign always written (`+1.2e-8`): a difference.
pub fn signed_exponent(x: Real, decimals: usize) -> String {
    signed(exponent(x, decimals))
}

/// A `+` before a number written without its sign (not before `NaN`).
fn signed(s: String) -> String {
    if s.starts_with('-') || s == "NaN" {
        s
    } else {
        format!("+{s}")
    }
}

/// A number with four significant digits, in whichever notation reads better.
pub fn significant(x: Real) -> String {
    fixed_or_exp(x, 4, 4, 1e5)
}

/// A cell of a real particle's table: six decimals, never wider than 14
/// characters.
pub fn cell(x: Real) -> String {
    fixed_or_exp(x, 6, 6, 1e5)
}

/// A CSV cell, lossless: plain digits for ordinary sizes, exponent notation
/// for the tiny rates and huge times of real particles (both round-trip).
pub fn csv(x: Real) -> String {
    let a = x.abs();
    if x == 0.0 || (1e-4..1e15).contains(&a) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}

/// A number as given: up to six significant digits, trailing zeros dropped.
pub fn short(x: Real) -> String {
    let a = x.abs();
    let trim = |m: &str| -> String {
        if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            m.to_string()
        }
    };
    if x == 0.0 || (1e-3..1e6).contains(&a) {
        let decimals = (5 - a.log10().floor().max(-3.0) as i32).max(0) as usize;
        trim(&format!("{x:.decimals$}"))
    } else {
        let s = format!("{x:.5e}");
        match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim(m)),
            None => s,
        }
    }
}

/// A number in 3 significant digits with an exponent (`1.23e-8`), or `-`.
pub fn sci(x: Option<Real>) -> String {
    match x {
        Some(0.0) => "0".into(),
        Some(v) if v.is_finite() => format!("{v:.2e}"),
        Some(v) => v.to_string(),
        None => "-".into(),
    }
}

/// A duration in seconds as µs or ms, 3 significant digits, or `-`.
pub fn duration(x: Option<Real>) -> String {
    match x {
        Some(s) if s < 1e-3 => format!("{:.3} µs", s * 1e6),
        Some(s) if s < 1.0 => format!("{:.3} ms", s * 1e3),
        Some(s) => format!("{s:.3} s"),
        None => "-".into(),
    }
}

/// A finite number from the user, or one line saying why not.
pub fn parse_number(s: &str) -> Result<Real, String> {
    let x: Real = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if !x.is_finite() {
        return Err(format!("'{s}' is not a finite number"));
    }
    if underflows(s, x) {
        return Err(underflow_message(s.trim()));
    }
    Ok(x)
}

/// Whether the literal `text`, read as `x`, underflowed: it is not zero (a
/// digit 1–9 before its exponent) yet reads as 0. The one rule every entry
/// point refuses by (flags, a scene's keys, the live view's editor).
// NOTE: the parser reads a number below the smallest double (1e-400) as 0;
// a value the user typed must not silently become another one.
pub fn underflows(text: &str, x: Real) -> bool {
    let mantissa = text.trim().split(['e', 'E']).next().unwrap_or("");
    x == 0.0 && mantissa.chars().any(|c| ('1'..='9').contains(&c))
}

/// The one wording for a literal that [`underflows`]: `1e-400 underflows to
/// 0 in f64 …` (an entry point that names settings puts the setting first).
pub fn underflow_message(number: &str) -> String {
    format!(
        "{number} underflows to 0 in f64 (the smallest double is about 4.9e-324); write 0 if zero is meant"
    )
}

/// A count the user typed (`--samples 1e3` as well as `1000`): a whole number
/// in plain or exponent form that fits `T`, or one line saying what is wrong
/// ("invalid digit found in string" was all `1e12` got).
pub fn parse_count<T: TryFrom<u64>>(s: &str) -> Result<T, String> {
    let not_whole = || format!("'{s}' is not a whole number");
    let too_large = || format!("'{s}' is too large");
    // NOTE: read as decimal digits, not through a double, so that
    // 2.0000000000000001 is refused rather than rounded to 2.
    let t = s.trim();
    let t = t.strip_prefix('+').unwrap_or(t);
    let (mantissa, exp) = match t.find(['e', 'E']) {
        Some(i) => (&t[..i], t[i + 1..].parse::<i64>().map_err(|_| not_whole())?),
        None => (t, 0),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits_only = int.chars().chain(frac.chars()).all(|c| c.is_ascii_digit());
    if (int.is_empty() && frac.is_empty()) || !digits_only {
        return Err(not_whole());
    }
    let all = format!("{int}{frac}");
    let all = all.trim_start_matches('0');
    let significant = all.trim_end_matches('0');
    if significant.is_empty() {
        return T::try_from(0).map_err(|_| too_large());
    }
    // The value is significant × 10^shift.
    let shift = exp - frac.len() as i64 + (all.len() - significant.len()) as i64;
    if shift < 0 {
        return Err(not_whole());
    }
    if significant.len() as i64 + shift > 20 {
        return Err(too_large());
    }
    let n = significant
        .parse::<u128>()
        .ok()
        .and_then(|m| m.checked_mul(10u128.checked_pow(shift as u32)?))
        .and_then(|n| u64::try_from(n).ok())
        .ok_or_else(too_large)?;
    T::try_from(n).map_err(|_| too_large())
}

/// A short key that is the same for the same text on every run and machine
/// (FNV-1a, 32 bits): names derived from a folder's path, so that two folders
/// never share a name (the scratch program of `spintop book`, the package of
/// an exported course).
pub fn stable_key(text: &str) -> u32 {
    let h = text.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    (h & 0xffff_ffff) as u32
}

/// The characters besides white space that end a word of prose, where a
/// number printed as `NaN` or `inf` is looked for.
const WORD_ENDS: &str = ",;:()[]{}=|/<>\"'";

fn word_end(c: char) -> bool {
    c.is_whitespace() || WORD_ENDS.contains(c)
}

/// The first word of `text` that is how Rust prints a non-finite number
/// (`NaN`, `inf`, `-inf`, `+inf`), if any: what the CLI's gate refuses to
/// print as if it were a result.
pub fn non_finite_word(text: &str) -> Option<&str> {
    text.split(word_end)
        .find(|w| matches!(*w, "NaN" | "-NaN" | "inf" | "-inf" | "+inf"))
}

/// `text` with each word that is a non-finite number spelt out
/// (`not-a-number`, `infinity`, `-infinity`): for a message that must name
/// one, such as a grader's report of an answer that is not finite.
pub fn non_finite_in_words(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        out.push_str(match word.as_str() {
            "NaN" | "-NaN" => "not-a-number",
            "inf" | "+inf" => "infinity",
            "-inf" => "-infinity",
            other => other,
        });
        word.clear();
    };
    for c in text.chars() {
        if word_end(c) {
            flush(&mut word, &mut out);
            out.push(c);
        } else {
            word.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

#[cfg(test)]
mod tests {

    /// A count is a whole number in plain or exponent form that fits its
    /// type; anything else is one line naming it.
    #[test]
    fn a_count_is_a_whole_number_in_either_form_that_fits() {
        assert_eq!(parse_count::<usize>("1000"), Ok(1000));
        assert_eq!(parse_count::<usize>("1e3"), Ok(1000));
        assert_eq!(parse_count::<u64>("1e12"), Ok(1_000_000_000_000));
        assert_eq!(parse_count::<u32>(" 7 "), Ok(7));
        assert_eq!(parse_count::<u32>("1230e-1"), Ok(123));
        assert_eq!(parse_count::<u32>("0e5"), Ok(0));
        assert_eq!(parse_count::<u32>("2.50e1"), Ok(25));
        for bad in [
            "2.5",
            "-3",
            "nan",
            "inf",
            "",
            "x",
            "1e-3",
            "1e-400",
            ".",
            "15.99999999999999999",
            "2.0000000000000001",
        ] {
            assert_eq!(
                parse_count::<u32>(bad),
                Err(format!("'{bad}' is not a whole number"))
            );
        }
        for big in [
            "4294967297",
            "1e30",
            "1e300",
            "1e400",
            "99999999999999999999999",
        ] {
            assert_eq!(
                parse_count::<u32>(big),
                Err(format!("'{big}' is too large"))
            );
        }
    }

    use super::*;

    /// A number below the smallest double is refused, not read as 0; a
    /// zero typed in any form is still 0.
    #[test]
    fn an_underflowing_number_is_refused_not_read_as_zero() {
        for tiny in ["1e-400", "-2.5e-330", "0.0001e-320"] {
            let e = parse_number(tiny).unwrap_err();
            assert_eq!(e, underflow_message(tiny));
        }
        for zero in ["0", "-0", "0.0", "0e-400", "000"] {
            assert_eq!(parse_number(zero), Ok(0.0), "{zero}");
        }
        assert_eq!(parse_number("5e-324"), Ok(5e-324));
    }

    #[test]
    fn an_estimate_beyond_a_double_is_said_in_words() {
        assert_eq!(fmt_about(8.9e299), "about 8.9e299");
        assert_eq!(fmt_about(19378.0), "about 1.9e4");
        assert_eq!(fmt_about(Real::INFINITY), "more than 1e308");
        assert_eq!(fmt_count(Real::INFINITY), "more than 1e308");
    }

    #[test]
    fn non_finite_numbers_in_prose_are_found_and_spelt_out() {
        let text = format!(
            "got: ({:e}, {:e}, {}), x={}",
            f64::NAN,
            -f64::INFINITY,
            1.5,
            f64::INFINITY
        );
        assert_eq!(non_finite_word(&text), Some("NaN"));
        let words = non_finite_in_words(&text);
        assert_eq!(words, "got: (not-a-number, -infinity, 1.5), x=infinity");
        assert_eq!(non_finite_word(&words), None);
        assert_eq!(
            non_finite_in_words("an infinite loop, info"),
            "an infinite loop, info"
        );
    }

    #[test]
    fn times_in_messages_are_short() {
        assert_eq!(fmt_time(10.0), "10");
        assert_eq!(fmt_time(0.0), "0");
        assert_eq!(fmt_time(1.02), "1.02");
        assert_eq!(fmt_time(5e299), "5.0000e299");
        assert_eq!(fmt_time(124999737.03362894), "1.2500e8");
        assert_eq!(fmt_time(1e-9), "1.0000e-9");
    }

    /// One rule for a parameter in a header, where the command line's tables
    /// and the live view used to disagree: exact when short, in whichever
    /// notation is short, else four significant digits; a long value shown
    /// short still reads back to within 5e-4 of itself.
    #[test]
    fn header_parameters_are_exact_when_short_and_four_digits_when_long() {
        for (x, shown) in [
            (0.1, "0.1"),
            (1.5, "1.5"),
            (1e-3, "0.001"),
            (0.4, "0.4"),
            (250.0, "250"),
            (-0.0, "0"),
            (1e300, "1e300"),
            (1.5e-8, "1.5e-8"),
            (1e-7, "1e-7"),
            (6.02e23, "6.02e23"),
            (4.634615384615384, "4.635"),
            (0.216_346_153_846_153_85, "0.2163"),
            (1.0 / 3.0, "0.3333"),
            (1.234_567_891e-7, "1.235e-7"),
            (12_345_678.9, "1.235e7"),
            (1e7, "1e7"),
            (1e5, "1e5"),
            (250_000.0, "2.5e5"),
            (123_456.0, "123456"),
            (-1e6, "-1e6"),
        ] {
            assert_eq!(fmt_param(x), shown, "{x}");
            let back: Real = fmt_param(x).parse().unwrap();
            assert!((back - x).abs() <= 5e-4 * x.abs(), "{x}");
            assert!(fmt_param(x).chars().count() <= PARAM_EXACT_CHARS);
        }
    }

    #[test]
    fn exact_parameters_read_back_to_the_same_double() {
        for x in [0.1, 1e-200, 4.634615384615384, -2.5e17, 1.0 / 3.0] {
            assert_eq!(fmt_exact(x).parse::<Real>().unwrap(), x);
        }
        assert_eq!(fmt_exact(1e-200), "1e-200");
    }

    #[test]
    fn numbers_are_formatted_for_reading() {
        assert_eq!(fmt_num(0.0), "0");
        assert_eq!(fmt_num(0.128062), "0.1281");
        assert_eq!(fmt_num(-12.3456), "-12.35");
        assert_eq!(fmt_num(1234.5), "1234");
        assert_eq!(fmt_num(3.2e-14), "3.200e-14");
        assert_eq!(fmt_num(Real::NAN), "—");
    }

    /// The narrow column's three digits: plainly in [1e-2, 1e5), else with
    /// an exponent (the live view's columns at 80×24).
    #[test]
    fn short_numbers_keep_three_significant_digits() {
        assert_eq!(fmt_short(0.0), "0");
        assert_eq!(fmt_short(0.00773), "7.73e-3");
        assert_eq!(fmt_short(0.0773), "0.0773");
        assert_eq!(fmt_short(-12.3456), "-12.3");
        assert_eq!(fmt_short(12000.4), "12000");
        assert_eq!(fmt_short(1.2806e-12), "1.28e-12");
        assert_eq!(fmt_short(Real::INFINITY), "—");
    }

    #[test]
    fn nice_ceiling_rounds_up_to_a_round_bound() {
        assert_eq!(nice_ceiling(0.2236 * 1.05), 0.25);
        assert_eq!(nice_ceiling(0.2), 0.2);
        assert_eq!(nice_ceiling(3.0), 5.0);
        assert_eq!(nice_ceiling(0.0), 1.0);
        assert!((nice_ceiling(7e-30) - 1e-29).abs() < 1e-40);
    }

    #[test]
    fn table_and_csv_cells_never_print_minus_zero_and_csv_round_trips() {
        assert_eq!(table(-1e-12 * 0.0), "0.0000000");
        assert_eq!(table(-4e-9), "-4.000000e-9");
        assert_eq!(fixed_or_exp(-1e-9, 3, 3, 1e5), "-1.000e-9");
        assert_eq!(fixed_or_exp(-0.0004, 3, 3, 1e5), "-4.000e-4");
        assert_eq!(fixed_or_exp(-0.00049, 3, 3, 1.0), "-4.900e-4");
        for x in [1e-26, 3.5e17, -0.25, 0.0, 123.456] {
            assert_eq!(csv(x).parse::<Real>().unwrap(), x);
        }
        assert_eq!(short(50.0), "50");
        assert_eq!(short(2200.0), "2200");
        assert_eq!(short(1e-9), "1e-9");
        assert_eq!(short(1.23456789e9), "1.23457e9");
        assert_eq!(sci(Some(1.234e-8)), "1.23e-8");
        assert_eq!(sci(Some(0.0)), "0");
        assert_eq!(sci(None), "-");
        assert_eq!(duration(Some(17.2e-6)), "17.200 µs");
        assert_eq!(duration(Some(0.25)), "250.000 ms");
        assert_eq!(fmt_count(12000.0), "12000");
        assert_eq!(fmt_count(1.8e19), "1.8e19");
    }

    /// The measured-value roles write what the format would, but never a
    /// `-0`, and a sign when asked.
    #[test]
    fn measured_values_keep_their_digits_and_never_read_minus_zero() {
        assert_eq!(fixed(0.123456, 4), "0.1235");
        assert_eq!(fixed(-2.5, 1), "-2.5");
        assert_eq!(fixed(-1e-9, 3), "0.000");
        assert_eq!(fixed(-0.0, 0), "0");
        assert_eq!(fixed(Real::NAN, 2), "NaN");
        assert_eq!(exponent(1.234e-8, 1), "1.2e-8");
        assert_eq!(exponent(-0.0, 2), "0.00e0");
        assert_eq!(exponent(1e6, 0), "1e6");
        assert_eq!(signed_fixed(3.1e-4, 5), "+0.00031");
        assert_eq!(signed_fixed(-1e-9, 2), "+0.00");
        assert_eq!(signed_exponent(-1.5e-3, 1), "-1.5e-3");
        assert_eq!(signed_exponent(Real::NAN, 1), "NaN");
        assert_eq!(signed_exponent(Real::INFINITY, 1), "+inf");
    }

    #[test]
    fn typed_numbers_are_finite_or_refused_in_one_line() {
        assert_eq!(parse_number(" 0.5 "), Ok(0.5));
        assert_eq!(parse_number("x"), Err("'x' is not a number".to_string()));
        assert!(
            parse_number("inf")
                .unwrap_err()
                .contains("not a finite number")
        );
        assert!(parse_number("NaN").is_err());
    }
}
