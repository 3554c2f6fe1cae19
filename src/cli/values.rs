//! clap's value parsers and help lines over the core's tables: the names a
//! flag accepts, its help line, its range and its default are the core's
//! ([`spintop::scene::table`]: one table for the flag, the scene key and the
//! live view), never restated here. Numbers are read as numbers only; what
//! a value must be (finite, in range) is the core's to say, in the same
//! words for a flag as for a scene's key.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use spintop::math::Real;
use spintop::output::Format;
use spintop::scene::table::{self, Choice, Command};
use spintop::sim::MethodChoice;

/// `--method NAME` for a command whose methods are `command`'s `[solve]
/// method` row of the table (the live view takes `plot`'s: every method but
/// `forward`).
pub fn method(command: Command) -> impl TypedValueParser<Value = MethodChoice> {
    method_name_of(command, "solve", "method")
        .map(|name| MethodChoice::from_name(&name).unwrap_or(MethodChoice::Auto))
}

/// A method's help line, naming the flag of the setting it takes
/// (`Fixed-step classical RK4 (--step)`) where `command` has that flag.
fn method_help(m: MethodChoice, command: Command) -> String {
    let flag = m.setting().and_then(|key| {
        table::keys_of(command)
            .find(|s| s.section == "solve" && s.key == key)
            .map(|s| s.flag())
    });
    match flag {
        Some(flag) => format!("{} ({flag})", m.help()),
        None => m.help().to_string(),
    }
}

/// `--method NAME` as a name, for the structures a scene file fills: the
/// methods the table offers for `[section] key` of `command` (`plot` takes
/// every method but `forward`).
pub fn method_name_of(command: Command, section: &str, key: &str) -> PossibleValuesParser {
    let offered = match table::key(command, section, key).range {
        table::Range::Names(names) => names,
        _ => &MethodChoice::NAMES,
    };
    PossibleValuesParser::new(
        MethodChoice::ALL
            .iter()
            .filter(|m| offered.contains(&m.name()))
            .map(|m| PossibleValue::new(m.name()).help(method_help(*m, command))),
    )
}

/// `--format NAME`: the names of [`Format::NAMES`].
pub fn format() -> impl TypedValueParser<Value = Format> {
    PossibleValuesParser::new(Format::ALL.map(|f| PossibleValue::new(f.name()).help(f.help())))
        .map(|name| Format::from_name(&name).unwrap_or(Format::Table))
}

/// The names of a table of the core that `keep` keeps, each with its help line.
pub fn names<T>(
    table: &'static [Choice<T>],
    keep: impl Fn(&Choice<T>) -> bool,
) -> PossibleValuesParser {
    PossibleValuesParser::new(
        table
            .iter()
            .filter(|c| keep(c))
            .map(|c| PossibleValue::new(c.name).help(c.help)),
    )
}

/// The help line of `[section] key` of `command`: what it is, its range and
/// its default, from the table.
pub fn help(command: Command, section: &str, key: &str) -> String {
    table::key(command, section, key).help_line()
}

/// The value name of `[section] key` of `command` in `--help`.
pub fn value_name(command: Command, section: &str, key: &str) -> &'static str {
    table::key(command, section, key).value_name
}

/// A value a flag could not read as numbers.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ValueError {
    /// Not a number, or the wrong count of them: clap's report says so.
    #[error("{0}")]
    Malformed(String),
    /// A number written too large for a double (`1e400`, which Rust reads
    /// as infinity): refused in the words a scene's key gets
    /// ([`spintop::scene::request::overflows`]), with the flag named.
    #[error("{0} overflows f64")]
    Overflow(String),
}

/// A number as typed: any double, `nan` and `inf` included (what a value
/// must be is the core's to check, in the words a scene's key gets); a
/// number beyond the largest double is refused, not read as infinity.
pub fn real(s: &str) -> Result<Real, ValueError> {
    let t = s.trim();
    let x: Real = t
        .parse()
        .map_err(|_| ValueError::Malformed(format!("'{s}' is not a number")))?;
    let spelled_infinite = t
        .trim_start_matches(['+', '-'])
        .to_ascii_lowercase()
        .starts_with("inf");
    if x.is_infinite() && !spelled_infinite {
        return Err(ValueError::Overflow(t.to_string()));
    }
    Ok(x)
}

/// Numbers separated by commas.
pub fn reals(s: &str) -> Result<Vec<Real>, ValueError> {
    s.split(',').map(real).collect()
}

/// Exactly `N` numbers separated by commas.
pub fn array<const N: usize>(s: &str) -> Result<[Real; N], ValueError> {
    let v = reals(s)?;
    let n = v.len();
    <[Real; N]>::try_from(v).map_err(|_| {
        let words = ["no", "one", "two", "three"];
        let want = words.get(N).copied().unwrap_or("N");
        ValueError::Malformed(format!("expected {want} comma-separated numbers, got {n}"))
    })
}

/// A whole number as typed, in plain or exponent form, a sign allowed (its
/// range is the core's to check).
pub fn whole(s: &str) -> Result<i64, String> {
    let t = s.trim();
    let (negative, digits) = match t.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, t),
    };
    let n: u64 = spintop::numbers::parse_count(digits).map_err(|e: String| {
        if e.ends_with("too large") {
            format!("'{s}' is too large")
        } else {
            format!("'{s}' is not a whole number")
        }
    })?;
    let n = i64::try_from(n).map_err(|_| format!("'{s}' is too large"))?;
    Ok(if negative { -n } else { n })
}
