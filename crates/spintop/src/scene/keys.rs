//! Reading the keys of a question, from a scene file or from a command's
//! flags alike: each number finite and in range, each name one of those
//! offered, each key in its own section, and every refusal a [`Refusal`]
//! that names the key as its source does (`[top] ratio = 3` in a file,
//! `--ratio 3` on the command line) and points at where it came from. Also
//! the output times of `[solve]`, which every kind reads the same way.

use super::format::{At, Given, Key, RawSolve};
use super::table::{self, Choice, Command, Range, Spec};
use crate::math::Real;
use crate::numbers::fmt_value;
use crate::physics::ParamError;
use crate::sim::MethodChoice;
use crate::sim::times::{check_times, even_times};
use thiserror::Error;

/// A question refused: where the value came from, and one line that says
/// what is wrong and what was expected, naming the key as its source does.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
#[error("{message}")]
pub struct Refusal {
    /// Where the value at fault was given.
    pub at: At,
    /// What is wrong and what was expected.
    pub message: String,
}

/// A value that was given, with where it came from.
pub(super) type Read<T> = Option<(T, At)>;

/// Where the question came from, which decides how a message names a key.
#[derive(Clone, Copy, Debug)]
pub(super) enum Dialect<'a> {
    /// A scene file: its text (to turn byte offsets into lines).
    File {
        /// Its text.
        text: &'a str,
    },
    /// The flags of a command.
    Flags,
}

/// How to read and name the keys of one question.
#[derive(Clone, Copy, Debug)]
pub(super) struct Ctx<'a> {
    pub(super) dialect: Dialect<'a>,
    /// Whose keys (for the table).
    pub(super) command: Command,
}

impl<'a> Ctx<'a> {
    /// The keys of `command` in a scene file of text `text`.
    pub(super) fn file(text: &'a str, command: Command) -> Self {
        Self {
            dialect: Dialect::File { text },
            command,
        }
    }

    /// The keys of `command` given as flags.
    pub(super) fn flags(command: Command) -> Self {
        Self {
            dialect: Dialect::Flags,
            command,
        }
    }

    /// The same source, for another command's keys.
    pub(super) fn of(self, command: Command) -> Self {
        Self { command, ..self }
    }

    /// The line of a byte offset of the file (1 for a flag).
    pub(super) fn line(&self, at: &At) -> usize {
        match (self.dialect, at) {
            (Dialect::File { text, .. }, At::Text(span)) => {
                let end = span.start.min(text.len());
                1 + text.as_bytes()[..end]
                    .iter()
                    .filter(|b| **b == b'\n')
                    .count()
            }
            _ => 1,
        }
    }

    pub(super) fn at(&self, at: &At, message: impl Into<String>) -> Refusal {
        Refusal {
            at: at.clone(),
            message: message.into(),
        }
    }

    /// The table's entry for a key of this command.
    pub(super) fn spec(&self, section: &str, key: &str) -> &'static Spec {
        table::key(self.command, section, key)
    }

    /// A key as the subject of a message: `[top] ratio`, or `--ratio`.
    pub(super) fn key(&self, section: &str, key: &str) -> String {
        match self.dialect {
            Dialect::File { .. } => format!("[{section}] {key}"),
            Dialect::Flags => table::flag_of(key),
        }
    }

    /// A key named inside a sentence: `ratio`, or `--ratio`.
    pub(super) fn name(&self, key: &str) -> String {
        match self.dialect {
            Dialect::File { .. } => key.to_string(),
            Dialect::Flags => table::flag_of(key),
        }
    }

    /// A key with its value: `[top] ratio = 3`, or `--ratio 3`.
    pub(super) fn set(&self, section: &str, key: &str, value: &str) -> String {
        match self.dialect {
            Dialect::File { .. } => format!("[{section}] {key} = {value}"),
            Dialect::Flags => format!("{} {value}", table::flag_of(key)),
        }
    }

    /// A key with a value inside a sentence: `model = "auto"`, or `--model auto`.
    pub(super) fn set_inline(&self, key: &str, value: &str) -> String {
        match self.dialect {
            Dialect::File { .. } => format!("{key} = {}", self.word(value)),
            Dialect::Flags => format!("{} {value}", table::flag_of(key)),
        }
    }

    /// A name as written in the source: `"auto"` in a file, `auto` on the
    /// command line.
    pub(super) fn word(&self, name: &str) -> String {
        match self.dialect {
            Dialect::File { .. } => format!("\"{name}\""),
            Dialect::Flags => name.to_string(),
        }
    }

    /// Who gives what a message is about, as its subject: `[solve] ` in a
    /// file, `the command line ` for flags (`the command line gives both
    /// --times and --t-end`).
    pub(super) fn giver(&self, section: &str) -> String {
        match self.dialect {
            Dialect::File { .. } => format!("[{section}] "),
            Dialect::Flags => "the command line ".to_string(),
        }
    }

    /// A section as the subject of a message: `[solve]`; nothing for flags.
    pub(super) fn section(&self, section: &str) -> String {
        match self.dialect {
            Dialect::File { .. } => format!("[{section}] "),
            Dialect::Flags => String::new(),
        }
    }
}

/// A number key: finite, or refused with the key and what it expects.
pub(super) fn num(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<Real>,
    expected: &str,
) -> Result<Read<Real>, Refusal> {
    let Some(Given { value: x, at }) = v else {
        return Ok(None);
    };
    if !x.is_finite() {
        return Err(ctx.at(
            at,
            format!(
                "{} is not a finite number; expected {expected}",
                ctx.set(section, key, &fmt_value(*x))
            ),
        ));
    }
    Ok(Some((*x, at.clone())))
}

/// A number key that must satisfy `ok`.
pub(super) fn num_in(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<Real>,
    ok: impl Fn(Real) -> bool,
    expected: &str,
) -> Result<Read<Real>, Refusal> {
    let got = num(ctx, section, key, v, expected)?;
    if let Some((x, at)) = &got
        && !ok(*x)
    {
        return Err(ctx.at(
            at,
            format!(
                "{} is out of range; expected {expected}",
                ctx.set(section, key, &fmt_value(*x))
            ),
        ));
    }
    Ok(got)
}

/// A number key of the table: finite; in range when `check` (the table's
/// range is the check where no constructor of the core makes it).
pub(super) fn number(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<Real>,
    check: bool,
) -> Result<Read<Real>, Refusal> {
    let spec = ctx.spec(section, key);
    let expected = spec.expected();
    if check {
        num_in(ctx, section, key, v, |x| spec.range.contains(x), &expected)
    } else {
        num(ctx, section, key, v, &expected)
    }
}

/// A whole-number key of the table, in the table's range.
pub(super) fn count(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<i64>,
) -> Result<Read<usize>, Refusal> {
    let Some(Given { value: n, at }) = v else {
        return Ok(None);
    };
    let spec = ctx.spec(section, key);
    let fits = *n >= 0 && spec.range.contains(*n as Real);
    if !fits {
        return Err(ctx.at(
            at,
            format!(
                "{} is out of range; expected {}",
                ctx.set(section, key, &n.to_string()),
                spec.expected()
            ),
        ));
    }
    Ok(Some((*n as usize, at.clone())))
}

/// An array key whose entries must all be finite.
pub(super) fn finite_array<const N: usize>(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<[Real; N]>,
    expected: &str,
) -> Result<Read<[Real; N]>, Refusal> {
    let Some(Given { value: a, at }) = v else {
        return Ok(None);
    };
    if let Some(x) = a.iter().find(|x| !x.is_finite()) {
        return Err(ctx.at(
            at,
            format!(
                "{} holds {x}, which is not a finite number; expected {expected}",
                ctx.key(section, key)
            ),
        ));
    }
    Ok(Some((*a, at.clone())))
}

/// An array key of the table whose entries must all be finite.
pub(super) fn numbers<const N: usize>(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<[Real; N]>,
) -> Result<Read<[Real; N]>, Refusal> {
    finite_array(ctx, section, key, v, &ctx.spec(section, key).expected())
}

/// The one message for a name a key does not take, whoever refuses it (this
/// module for a scene's key, the command line's parser for a flag's name):
/// `set` is the key with its value as the source writes it (`[top] model =
/// "xml"`, `--model xml`).
pub fn not_known(set: &str, options: &[&str]) -> String {
    format!("{set} is not known; expected one of {}", options.join(", "))
}

/// A number written too large for a double, as every entry point refuses
/// it, naming the setting as the entry point spells it (`--b`, `[balance]
/// b`): `--b: 1e400 overflows f64 …`.
pub fn overflows(setting: &str, number: &str) -> String {
    format!(
        "{setting}: {number} overflows f64 (the largest double is about 1.8e308); expected a finite number"
    )
}

/// A string key that must be one of `options`; returns its index.
pub(super) fn choice(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<String>,
    options: &[&str],
) -> Result<Read<usize>, Refusal> {
    let Some(Given { value: s, at }) = v else {
        return Ok(None);
    };
    match options.iter().position(|o| o == s) {
        Some(i) => Ok(Some((i, at.clone()))),
        None => Err(ctx.at(at, not_known(&ctx.set(section, key, &ctx.word(s)), options))),
    }
}

/// A string key that must be a name of `table`; returns what it stands for.
pub(super) fn named<T: Copy>(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<String>,
    table: &[Choice<T>],
) -> Result<Read<T>, Refusal> {
    let names = table::names(table);
    Ok(choice(ctx, section, key, v, &names)?.map(|(i, at)| (table[i].value, at)))
}

/// A key the question needs and does not give.
pub(super) fn missing(ctx: &Ctx, header: &At, section: &str, key: &str, expected: &str) -> Refusal {
    let subject = match ctx.dialect {
        Dialect::File { .. } => format!("[{section}] is missing the key {key}"),
        Dialect::Flags => format!("{} is missing", table::flag_of(key)),
    };
    ctx.at(header, format!("{subject}; expected {expected}"))
}

/// A key the question needs, with what the table says it expects.
pub(super) fn missing_key(ctx: &Ctx, header: &At, section: &str, key: &str) -> Refusal {
    missing(
        ctx,
        header,
        section,
        key,
        &ctx.spec(section, key).expected(),
    )
}

/// A key given where it does not belong.
pub(super) fn not_here<T>(
    ctx: &Ctx,
    v: &Key<T>,
    section: &str,
    key: &str,
    why: &str,
) -> Result<(), Refusal> {
    match v {
        Some(v) => Err(ctx.at(&v.at, format!("{} {why}", ctx.key(section, key)))),
        None => Ok(()),
    }
}

/// Point a refused physical parameter at the key it came from: each
/// parameter's name in the core (`I3/I1`, `m1`) and the key that gave it.
pub(super) fn param(
    ctx: &Ctx,
    e: ParamError,
    keys: &[(&str, &str, Option<&At>)],
    fallback: &At,
    section: &str,
) -> Refusal {
    let name = match &e {
        ParamError::NotFinite { name, .. } | ParamError::OutOfRange { name, .. } => *name,
        ParamError::RatioOutOfRange(_) => "I3/I1",
        ParamError::MomentNotPositive { .. } | ParamError::TriangleInequality(..) => "inertia",
        ParamError::ZeroDipole => "dipole",
        ParamError::NegativeTau(_) => "tau",
    };
    let found = keys
        .iter()
        .find(|(n, _, _)| *n == name || name.starts_with(n));
    match found {
        Some((_, key, Some(at))) => ctx.at(at, format!("{}: {e}", ctx.key(section, key))),
        // A default the other keys given make wrong.
        Some((_, key, None)) => ctx.at(
            fallback,
            format!("{} (its default): {e}", ctx.key(section, key)),
        ),
        None => ctx.at(fallback, format!("{}{e}", ctx.section(section))),
    }
}

/// The bare key that a `key = value` line holding byte `offset` assigns.
pub(super) fn key_on_line(text: &str, offset: usize) -> Option<&str> {
    let offset = offset.min(text.len());
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line = &text[start..];
    let (key, _) = line.split_once('=')?;
    let key = key.trim();
    let bare = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    bare.then_some(key)
}

/// The output times of a question.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Times {
    /// The times, scaled to the model's unit.
    pub(super) times: Vec<Real>,
    /// Where they were given (`times` or `t_end`), if they were.
    pub(super) at: Option<At>,
    /// The key that gave them (`times`, or `t_end` also when they are its
    /// default): what advice to ask for other times names.
    pub(super) key: &'static str,
}

impl Times {
    /// Advice to ask for less time, naming the key that gave the times:
    /// `earlier --times`, `a shorter [solve] t_end`.
    pub(super) fn shorter(&self, ctx: &Ctx) -> String {
        match self.key {
            "times" => format!("earlier {}", ctx.name("times")),
            key => format!("a shorter {}", ctx.name(key)),
        }
    }
}

/// The output times of `[solve]`: `times`, or `t_end` with `samples` evenly
/// spaced from 0 (the table's defaults where the command has them), scaled
/// by `scale` (model time units per time unit).
pub(super) fn solve_times(
    ctx: &Ctx,
    solve: Option<(&RawSolve, At)>,
    section: &At,
    scale: Real,
) -> Result<Times, Refusal> {
    let none = RawSolve::default();
    let (s, header) = match &solve {
        Some((s, at)) => (*s, at.clone()),
        None => (&none, section.clone()),
    };
    let t_end_or_samples = s
        .t_end
        .as_ref()
        .map(|g| g.at.clone())
        .or(s.samples.as_ref().map(|g| g.at.clone()));
    if s.times.is_some()
        && let Some(other) = t_end_or_samples
    {
        return Err(ctx.at(
            &other,
            format!(
                "{}gives both {times} and {t_end}/{samples}; expected either {times} or {t_end} (with {samples})",
                ctx.giver("solve"),
                times = ctx.name("times"),
                t_end = ctx.name("t_end"),
                samples = ctx.name("samples"),
            ),
        ));
    }
    if let Some(Given { value: list, at }) = &s.times {
        return listed_times(ctx, list, at, scale);
    }
    let t_end = number(ctx, "solve", "t_end", &s.t_end, true)?;
    let samples = count(ctx, "solve", "samples", &s.samples)?;
    let n = match (&samples, ctx.spec("solve", "samples").default) {
        (Some((n, _)), _) => *n,
        (None, table::DefaultValue::Count(n)) => n,
        (None, _) => 1,
    };
    let (t_end, at) = match (t_end, ctx.spec("solve", "t_end").default.number()) {
        (Some((t, at)), _) => (t, Some(at)),
        (None, Some(t)) => {
            if let Some((_, at)) = &samples {
                return Err(ctx.at(
                    at,
                    format!(
                        "{} needs {t_end}; expected {t_end} beside it",
                        ctx.key("solve", "samples"),
                        t_end = ctx.name("t_end")
                    ),
                ));
            }
            (t, None)
        }
        (None, None) => {
            return Err(ctx.at(
                &header,
                format!(
                    "{}gives no output times; expected {} or {} (with {})",
                    ctx.giver("solve"),
                    ctx.name("times"),
                    ctx.name("t_end"),
                    ctx.name("samples")
                ),
            ));
        }
    };
    let scaled = t_end * scale;
    if !scaled.is_finite() {
        return Err(ctx.at(
            &header,
            format!(
                "{} overflows when converted to units of tau; expected a shorter time",
                ctx.key("solve", "t_end")
            ),
        ));
    }
    Ok(Times {
        times: even_times(scaled, n),
        at,
        key: "t_end",
    })
}

/// Times given as a list, checked by the core's one rule and scaled.
fn listed_times(ctx: &Ctx, list: &[Real], at: &At, scale: Real) -> Result<Times, Refusal> {
    let range = &ctx.spec("solve", "times").range;
    let forward = matches!(range, Range::Times { forward: true });
    check_times(list, forward).map_err(|e| {
        let rest = e.to_string();
        let rest = rest.strip_prefix("times").unwrap_or(&rest);
        ctx.at(
            at,
            format!(
                "{}{rest}; expected {}",
                ctx.key("solve", "times"),
                range.expected("")
            ),
        )
    })?;
    let scaled: Vec<Real> = list.iter().map(|t| t * scale).collect();
    if scaled.iter().any(|t| !t.is_finite()) {
        return Err(ctx.at(
            at,
            format!(
                "{} overflow when converted to units of tau; expected shorter times",
                ctx.key("solve", "times")
            ),
        ));
    }
    Ok(Times {
        times: scaled,
        at: Some(at.clone()),
        key: "times",
    })
}

/// Refuse `method`, `rtol` and `step` where the kind fixes its own method.
pub(super) fn fixed_method(
    ctx: &Ctx,
    solve: Option<(&RawSolve, At)>,
    kind: &str,
    why: &str,
    rtol_ok: bool,
) -> Result<(), Refusal> {
    let Some((s, _)) = solve else { return Ok(()) };
    if let Some((m, at)) = choice(ctx, "solve", "method", &s.method, &MethodChoice::NAMES)?
        && m != 0
    {
        return Err(ctx.at(
            &at,
            format!(
                "{} does not apply to kind = \"{kind}\" ({why}); expected auto",
                ctx.set("solve", "method", &ctx.word(MethodChoice::NAMES[m]))
            ),
        ));
    }
    not_here(
        ctx,
        &s.step,
        "solve",
        "step",
        &format!(
            "does not apply to kind = \"{kind}\"; it sets the fixed step of method = \"rk4\" for a top"
        ),
    )?;
    if !rtol_ok {
        not_here(
            ctx,
            &s.rtol,
            "solve",
            "rtol",
            &format!("does not apply to kind = \"{kind}\" ({why})"),
        )?;
    }
    Ok(())
}
