//! A scene: one question in a TOML file, validated into the objects the core
//! runs on, with the lightest model that answers it chosen before anything runs.
//!
//! A scene names its kind (`top`, `balance`, `orbit`, `shell`, `stability`),
//! gives the same parameters as the matching command, says what to sample in
//! `[solve]`, and may describe a real particle in `[units]` (sphere or
//! cylinder, nm, kg/m³, debye, Hz) instead of the paper's τ units. The format is
//! documented key by key in the book's "Scene files" reference page.
//!
//! Pure like the rest of the core: [`parse`] takes the text and a file name
//! (for messages) and never touches the disk. Every refusal is a
//! [`SceneError`] with the file, the line and what was expected.
//!
//! | code name | meaning |
//! |---|---|
//! | [`Scene`] | a validated scene: name, kind, description, the body, the choice made |
//! | [`Chosen`] | the method `auto` picked (or the one asked for) and why |
//! | [`Orientation`] | whether the orientation is computed, or skipped and why |
//! | [`RealUnits`] | the particle of `[units]`, τ in seconds, the output time unit |

use thiserror::Error;

pub mod answer;
pub mod catalogue;
pub mod choose;
pub mod format;
mod keys;
mod kinds;
pub mod live;
pub mod plan;
pub mod request;
pub mod table;
mod top;
mod units;
pub mod write;

use format::{At, Key, RawFile};
pub use keys::Refusal;
use keys::{Ctx, choice, key_on_line, missing};
pub use kinds::{BalanceDipole, BalanceScene, OrbitScene, ShellScene, StabilityScene};
use kinds::{balance_scene, orbit_scene, shell_scene};
pub use plan::{Chosen, OmegaSample, Orientation, omega_samples, pole_warning};
use table::Command;
pub use table::MODELS;
use top::top_scene;
pub use top::{Frame, TopRequest, TopScene};
pub use units::{GENERAL_SHAPES, GeneralUnits, RealUnits, SHAPES, TIME_UNITS, TimeUnit};

/// A scene file that cannot be run: where, and what was expected.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
#[error("{file}:{line}: {message}")]
pub struct SceneError {
    /// The file name, as given.
    pub file: String,
    /// The line, counting from 1.
    pub line: usize,
    /// What is wrong and what was expected, in one line.
    pub message: String,
}

/// The kinds of scene, one per command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A spinning top: `spintop simulate`.
    Top,
    /// A dipole trajectory and the two balance laws: `spintop balance`.
    Balance,
    /// A charge in a central field: `spintop orbit`.
    Orbit,
    /// The charge as a small shell: `spintop shell`.
    Shell,
    /// One row of the stability suite: `spintop stability --row N`.
    Stability,
}

/// The names of the kinds, in the order of [`Kind`].
pub const KINDS: [&str; 5] = ["top", "balance", "orbit", "shell", "stability"];

impl Kind {
    /// Every kind, in the order of [`KINDS`].
    pub const ALL: [Kind; 5] = [
        Kind::Top,
        Kind::Balance,
        Kind::Orbit,
        Kind::Shell,
        Kind::Stability,
    ];
}

impl Kind {
    /// `top`, `balance`, `orbit`, `shell` or `stability`.
    pub fn name(&self) -> &'static str {
        KINDS[*self as usize]
    }

    /// The command whose keys a scene of this kind takes (`None`: stability).
    fn command(&self) -> Option<Command> {
        match self {
            Kind::Top => Some(Command::Simulate),
            Kind::Balance => Some(Command::Balance),
            Kind::Orbit => Some(Command::Orbit),
            Kind::Shell => Some(Command::Shell),
            Kind::Stability => None,
        }
    }

    /// Its section (`top`, …) and the others it may have.
    fn allowed(&self) -> &'static [&'static str] {
        match self {
            Kind::Top => &["top", "solve", "units"],
            Kind::Balance => &["balance", "solve"],
            Kind::Orbit => &["orbit", "solve"],
            Kind::Shell => &["shell", "solve"],
            Kind::Stability => &["stability"],
        }
    }

    fn sections(&self) -> &'static str {
        match self {
            Kind::Top => "[scene], [top], optionally [solve] and [units]",
            Kind::Balance => "[scene], [balance] and [solve]",
            Kind::Orbit => "[scene], [orbit] and [solve]",
            Kind::Shell => "[scene], [shell] and [solve]",
            Kind::Stability => "[scene] and [stability]",
        }
    }
}

/// A validated scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The file it came from (for messages).
    pub file: String,
    /// Its name (lower case, digits and dashes).
    pub name: String,
    /// What it asks.
    pub description: String,
    /// The question itself.
    pub body: Body,
    /// The method that will answer it, and why.
    pub chosen: Chosen,
    /// What the question asks beyond what the model can give.
    pub warnings: Vec<String>,
    /// Lines of the file that later checks point at.
    pub lines: Lines,
}

/// Lines of a scene file that the runner may need to point at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lines {
    /// The `[solve]` header, or the kind's section when there is none.
    pub solve: usize,
    /// The `times` or `t_end` key, or `solve`.
    pub times: usize,
}

impl Scene {
    /// The kind.
    pub fn kind(&self) -> Kind {
        match self.body {
            Body::Top(_) => Kind::Top,
            Body::Balance(_) => Kind::Balance,
            Body::Orbit(_) => Kind::Orbit,
            Body::Shell(_) => Kind::Shell,
            Body::Stability(_) => Kind::Stability,
        }
    }

    /// The first sentence of the description, for one-line listings: up to
    /// the first ". " before a capital letter that does not end an
    /// abbreviation such as "Eq." or "Eqs.".
    pub fn summary(&self) -> &str {
        let d = self.description.trim();
        let ends_sentence = |i: usize| {
            let before = &d[..i];
            let word = before.rsplit([' ', '(']).next().unwrap_or("");
            let next = d[i + 2..].chars().next();
            !matches!(word, "Eq" | "Eqs" | "Fig" | "e.g" | "i.e")
                && next.is_some_and(char::is_uppercase)
        };
        match d
            .match_indices(". ")
            .map(|(i, _)| i)
            .find(|&i| ends_sentence(i))
        {
            Some(i) => &d[..=i],
            None => d,
        }
    }

    /// An error at a line of this scene's file.
    pub fn error_at(&self, line: usize, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.clone(),
            line,
            message: message.into(),
        }
    }
}

/// What a scene asks, by kind.
#[derive(Clone, Debug, PartialEq)]
pub enum Body {
    /// A top.
    Top(Box<TopScene>),
    /// A dipole trajectory.
    Balance(BalanceScene),
    /// A charge in a central field.
    Orbit(OrbitScene),
    /// The shell model.
    Shell(ShellScene),
    /// A row of the stability suite.
    Stability(StabilityScene),
}

/// serde writes a float of the wrong type in full (for 1e308, 309 digits
/// after "floating point"): each is written as a message value (`1e308`).
fn short_floats(message: &str) -> String {
    const TAG: &str = "floating point `";
    let mut out = String::new();
    let mut rest = message;
    while let Some(at) = rest.find(TAG) {
        let (head, tail) = rest.split_at(at + TAG.len());
        out.push_str(head);
        let end = tail.find('`').unwrap_or(tail.len());
        match tail[..end].parse::<crate::math::Real>() {
            Ok(x) => out.push_str(&crate::numbers::fmt_value(x)),
            Err(_) => out.push_str(&tail[..end]),
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

/// Parse and validate a scene.
///
/// `file` names the text in messages (a path, or `catalogue:NAME`).
pub fn parse(text: &str, file: &str) -> Result<Scene, SceneError> {
    let raw = read_toml(text, file)?;
    // The kind's command is not known yet; the header reads no table key.
    let ctx = Ctx::file(text, Command::Simulate);
    let located = |r: Refusal| SceneError {
        file: file.to_string(),
        line: ctx.line(&r.at),
        message: r.message,
    };
    let header = read_header(&ctx, &raw).map_err(located)?;
    let own = own_section(&ctx, &raw, header.kind).map_err(located)?;
    let ctx = match header.kind.command() {
        Some(command) => ctx.of(command),
        None => ctx,
    };
    let solve_line = raw
        .solve
        .as_ref()
        .map_or(ctx.line(&own), |s| ctx.line(&s.at));
    let built = build(&ctx, &raw, header.kind, &own).map_err(located)?;
    Ok(Scene {
        file: file.to_string(),
        name: header.name,
        description: header.description,
        body: built.body,
        chosen: built.chosen,
        warnings: built.warnings,
        lines: Lines {
            solve: solve_line,
            times: built.times_at.map_or(solve_line, |at| ctx.line(&at)),
        },
    })
}

/// The TOML of a scene, as serde reads it: a syntax error, an unknown key or
/// a value of the wrong type is refused at its line, naming the key.
fn read_toml(text: &str, file: &str) -> Result<RawFile, SceneError> {
    toml::from_str(text).map_err(|e| {
        let start = e.span().map_or(0, |s| s.start);
        let mut message = e
            .message()
            .trim()
            .replace('\n', " ")
            .replace("unknown field", "unknown key")
            .replace("expected f64", "expected a number")
            .replace("expected i64", "expected a whole number");
        message = short_floats(&message);
        // A number too large for a double: the message every entry point
        // gives, naming the setting (the flag's is the same).
        if message.contains("overflowed")
            && let Some(key) = key_on_line(text, start)
        {
            let section = section_above(text, start);
            let setting = section.map_or(key.to_string(), |s| format!("[{s}] {key}"));
            message = keys::overflows(&setting, &number_at(text, e.span()));
        }
        // NOTE: serde's type errors do not name the key; the line does, and
        // the header above it the section (`[top] ratio`, as every other
        // message of a scene names a key).
        if message.starts_with("invalid")
            && let Some(key) = key_on_line(text, start)
        {
            message = match section_above(text, start) {
                Some(section) => format!("[{section}] {key}: {message}"),
                None => format!("{key}: {message}"),
            };
        }
        SceneError {
            file: file.to_string(),
            line: Ctx::file(text, Command::Simulate).line(&At::Text(start..start)),
            message,
        }
    })
}

/// The number TOML refused at `span`: its text, or the value after the key
/// when the span is not a number's.
fn number_at(text: &str, span: Option<std::ops::Range<usize>>) -> String {
    let spanned = span.and_then(|s| text.get(s)).map(str::trim).filter(|t| {
        !t.is_empty()
            && t.chars()
                .all(|c| c.is_ascii_alphanumeric() || "+-._".contains(c))
    });
    match spanned {
        Some(t) => t.to_string(),
        None => "a number".to_string(),
    }
}

/// The section whose header is the last one before byte `offset` of a
/// scene file (`top` for a key under `[top]`).
fn section_above(text: &str, offset: usize) -> Option<&str> {
    let offset = offset.min(text.len());
    text[..offset].lines().rev().find_map(|line| {
        let line = line.trim();
        line.strip_prefix('[')
            .and_then(|rest| rest.strip_suffix(']'))
            .map(str::trim)
            .filter(|name| !name.starts_with('['))
    })
}

/// `[scene]`, validated.
struct Header {
    name: String,
    kind: Kind,
    description: String,
}

fn read_header(ctx: &Ctx, raw: &RawFile) -> Result<Header, Refusal> {
    let Some(scene) = &raw.scene else {
        return Err(ctx.at(
            &At::Text(0..0),
            "there is no [scene] section; expected [scene] with name, kind and description",
        ));
    };
    let header = &scene.at;
    let scene = &scene.value;
    let name = scene.name.as_ref().ok_or_else(|| {
        missing(
            ctx,
            header,
            "scene",
            "name",
            "a name of lower-case letters, digits and dashes",
        )
    })?;
    let name_ok = !name.value.is_empty()
        && name.value.len() <= 60
        && name
            .value
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-');
    if !name_ok {
        return Err(ctx.at(
            &name.at,
            format!(
                "[scene] name = \"{}\" is not a scene name; expected 1 to 60 lower-case letters, digits and dashes",
                name.value
            ),
        ));
    }
    let (kind, _) = choice(ctx, "scene", "kind", &scene.kind, &KINDS)?.ok_or_else(|| {
        missing(
            ctx,
            header,
            "scene",
            "kind",
            &format!("one of {}", KINDS.join(", ")),
        )
    })?;
    let description = scene.description.as_ref().ok_or_else(|| {
        missing(
            ctx,
            header,
            "scene",
            "description",
            "a paragraph saying what the scene asks",
        )
    })?;
    if description.value.trim().is_empty() {
        return Err(ctx.at(
            &description.at,
            "[scene] description is empty; expected a paragraph saying what the scene asks",
        ));
    }
    Ok(Header {
        name: name.value.clone(),
        kind: Kind::ALL[kind],
        description: description.value.trim().to_string(),
    })
}

/// The section of the scene's kind (where its refusals point when no key
/// does); a section of another kind is refused, not ignored.
fn own_section(ctx: &Ctx, raw: &RawFile, kind: Kind) -> Result<At, Refusal> {
    fn at<T>(k: &Key<T>) -> Option<&At> {
        k.as_ref().map(|g| &g.at)
    }
    let present: [(&str, Option<&At>); 7] = [
        ("top", at(&raw.top)),
        ("balance", at(&raw.balance)),
        ("orbit", at(&raw.orbit)),
        ("shell", at(&raw.shell)),
        ("stability", at(&raw.stability)),
        ("solve", at(&raw.solve)),
        ("units", at(&raw.units)),
    ];
    for (section, given) in &present {
        if let Some(given) = given
            && !kind.allowed().contains(section)
        {
            return Err(ctx.at(
                given,
                format!(
                    "[{section}] does not belong in a scene of kind = \"{}\"; expected {}",
                    kind.name(),
                    kind.sections()
                ),
            ));
        }
    }
    present
        .iter()
        .find(|(s, _)| *s == kind.name())
        .and_then(|(_, at)| at.cloned())
        .ok_or_else(|| {
            let header = at(&raw.scene).cloned().unwrap_or(At::Text(0..0));
            ctx.at(
                &header,
                format!(
                    "a scene of kind = \"{}\" needs a [{}] section; expected {}",
                    kind.name(),
                    kind.name(),
                    kind.sections()
                ),
            )
        })
}

/// The body of a scene of `kind`, validated and planned.
fn build(ctx: &Ctx, raw: &RawFile, kind: Kind, own: &At) -> Result<Built, Refusal> {
    let solve = raw.solve.as_ref().map(|s| (&s.value, s.at.clone()));
    // own_section has found the kind's section.
    let absent = || {
        ctx.at(
            own,
            format!("a scene of kind = \"{}\" needs its section", kind.name()),
        )
    };
    match kind {
        Kind::Top => {
            let units = raw.units.as_ref().map(|u| (&u.value, u.at.clone()));
            let top = raw.top.as_ref().ok_or_else(absent)?;
            top_scene(ctx, &top.value, own, solve, units)
        }
        Kind::Balance => {
            let b = raw.balance.as_ref().ok_or_else(absent)?;
            balance_scene(ctx, &b.value, own, solve)
        }
        Kind::Orbit => {
            let o = raw.orbit.as_ref().ok_or_else(absent)?;
            orbit_scene(ctx, &o.value, own, solve)
        }
        Kind::Shell => {
            let s = raw.shell.as_ref().ok_or_else(absent)?;
            shell_scene(ctx, &s.value, own, solve)
        }
        Kind::Stability => {
            let raw_row = raw.stability.as_ref().and_then(|s| s.value.row.as_ref());
            let row = raw_row
                .ok_or_else(|| missing(ctx, own, "stability", "row", "a row number, 1 to 6"))?;
            let n = row.value;
            if !(1..=6).contains(&n) {
                return Err(ctx.at(
                    &row.at,
                    format!("[stability] row = {n} is out of range; expected a row number, 1 to 6"),
                ));
            }
            let n = n as u8;
            Ok(Built {
                body: Body::Stability(StabilityScene { row: n }),
                chosen: plan::stability_choice(n),
                warnings: Vec::new(),
                times_at: None,
            })
        }
    }
}

/// A validated body with its choice.
struct Built {
    body: Body,
    chosen: Chosen,
    warnings: Vec<String>,
    times_at: Option<At>,
}
