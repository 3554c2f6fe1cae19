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

use crate::math::{Real, Vec3};
use crate::physics::ParamError;
use crate::physics::balance::{Dumbbell, PlanarLoop, PrecessingDipole};
use crate::physics::central::{ChargeInField, Potential};
use crate::physics::euler_angles::{EulerAngles, frame_with_z_along};
use crate::physics::general_top::GeneralTop;
use crate::physics::particle::{
    DEBYE_ESU_CM, Particle, RigidParticle, RigidShape, SECONDS_PER_YEAR, Shape,
};
use crate::physics::rigid_body::angular_momentum_body;
use crate::physics::shell::ShellModel;
use crate::physics::symmetric_top::SymmetricTop;
use crate::sim::orbit::{Force, OrbitConfig};
use crate::sim::{InitialState, MAX_RATE, MethodChoice, MethodOptions, Model};
use std::ops::Range;
use thiserror::Error;
use toml::Spanned;

pub mod catalogue;
mod format;
pub mod plan;

use format::{Key, RawBalance, RawFile, RawOrbit, RawShell, RawSolve, RawTop, RawUnits};
pub use plan::{Chosen, OmegaSample, Orientation, omega_samples, pole_warning};

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
    /// `top`, `balance`, `orbit`, `shell` or `stability`.
    pub fn name(&self) -> &'static str {
        KINDS[*self as usize]
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

/// How the initial orientation was given.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Frame {
    /// Explicit z-x-z Euler angles (default 0, 0, 0).
    Euler,
    /// The paper's frame: lab z along L₀, as in (4.11) and the figures.
    Paper,
}

/// A top: the `simulate` parameters, validated, and the plan.
#[derive(Clone, Debug, PartialEq)]
pub struct TopScene {
    /// The model.
    pub model: Model,
    /// The method asked for (`auto` by default).
    pub method: MethodChoice,
    /// Tolerance and step.
    pub options: MethodOptions,
    /// Ω₀ and O(0).
    pub initial: InitialState,
    /// The Euler angles of O(0).
    pub euler0: [Real; 3],
    /// How O(0) was given.
    pub frame: Frame,
    /// Output times, in τ (κ = 1 units for the general top).
    pub times: Vec<Real>,
    /// The real particle, when `[units]` gives a sphere or a cylinder.
    pub units: Option<RealUnits>,
    /// The asymmetric real particle, when `[units]` gives an ellipsoid or a
    /// molecule.
    pub general_units: Option<GeneralUnits>,
    /// Whether the orientation is computed.
    pub orientation: Orientation,
}

/// A time unit for the output of a real particle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeUnit {
    /// Seconds.
    Second,
    /// Minutes.
    Minute,
    /// Hours.
    Hour,
    /// Days.
    Day,
    /// Julian years, 365.25 days.
    Year,
}

/// The names of the time units, in the order of [`TimeUnit`].
pub const TIME_UNITS: [&str; 5] = ["s", "min", "h", "d", "yr"];

impl TimeUnit {
    /// `s`, `min`, `h`, `d` or `yr`.
    pub fn name(&self) -> &'static str {
        TIME_UNITS[*self as usize]
    }

    /// Seconds per unit.
    pub fn seconds(&self) -> Real {
        match self {
            TimeUnit::Second => 1.0,
            TimeUnit::Minute => 60.0,
            TimeUnit::Hour => 3600.0,
            TimeUnit::Day => 86_400.0,
            TimeUnit::Year => SECONDS_PER_YEAR,
        }
    }
}

/// The `[units]` of a top: a real particle and how to show times.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RealUnits {
    /// The particle.
    pub particle: Particle,
    /// Its spin rate, turns per second.
    pub spin_hz: Real,
    /// The angle between Ω₀ and the symmetry axis, in degrees.
    pub spin_tilt_deg: Real,
    /// The tilt counted as upright, in degrees.
    pub upright_deg: Real,
    /// The unit of `[solve]` times and of the output.
    pub time_unit: TimeUnit,
}

impl RealUnits {
    /// τ in seconds.
    pub fn tau_seconds(&self) -> Real {
        self.particle.tau_seconds()
    }

    /// How many τ make one output time unit.
    pub fn tau_per_unit(&self) -> Real {
        self.time_unit.seconds() / self.tau_seconds()
    }
}

/// The `[units]` of an asymmetric real particle (an ellipsoid or a
/// molecule): the particle, its body-frame rates and how to show times.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneralUnits {
    /// The particle.
    pub particle: RigidParticle,
    /// Body-frame rates Ω₀/2π, turns per second.
    pub omega_hz: [Real; 3],
    /// The unit of `[solve]` times and of the output.
    pub time_unit: TimeUnit,
}

impl GeneralUnits {
    /// τ_f = κ|D|²/min I in seconds, the time unit of its κ = 1 top.
    pub fn fast_time_seconds(&self) -> Real {
        self.particle.fast_time_seconds()
    }

    /// How many τ_f make one output time unit.
    pub fn u_per_unit(&self) -> Real {
        self.time_unit.seconds() / self.fast_time_seconds()
    }
}

/// A dipole trajectory of `balance`, with the parameters as given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BalanceDipole {
    /// A rigid dipole on a cone.
    Precessing {
        /// Cone half-angle θ.
        cone: Real,
        /// Rate ω.
        rate: Real,
        /// The trajectory.
        dipole: PrecessingDipole,
    },
    /// The two-harmonic planar loop.
    Loop {
        /// b.
        b: Real,
        /// ε.
        eps: Real,
        /// The trajectory.
        dipole: PlanarLoop,
    },
    /// A rigid rotating dumbbell.
    Dumbbell {
        /// q₁, q₂.
        charges: [Real; 2],
        /// m₁, m₂.
        masses: [Real; 2],
        /// Rod length.
        length: Real,
        /// Rate.
        rate: Real,
        /// The trajectory.
        dipole: Dumbbell,
    },
}

/// A `balance` scene.
#[derive(Clone, Debug, PartialEq)]
pub struct BalanceScene {
    /// The trajectory.
    pub dipole: BalanceDipole,
    /// Sample times (any finite values).
    pub times: Vec<Real>,
}

/// An `orbit` scene.
#[derive(Clone, Debug, PartialEq)]
pub struct OrbitScene {
    /// The problem.
    pub config: OrbitConfig,
    /// Output times.
    pub times: Vec<Real>,
}

/// A `shell` scene.
#[derive(Clone, Debug, PartialEq)]
pub struct ShellScene {
    /// The model.
    pub model: ShellModel,
    /// Output times.
    pub times: Vec<Real>,
}

/// A `stability` scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StabilityScene {
    /// The row, 1 to 6.
    pub row: u8,
}

/// The model names of `[top] model`.
pub const MODELS: [&str; 5] = ["truncated", "reduced", "general", "full", "auto"];
/// The method names of `[solve] method`.
pub const METHODS: [&str; 8] = [
    "auto", "exact", "rk4", "dopri5", "dop853", "radau5", "taylor", "forward",
];
/// The shapes of `[units] shape`.
pub const SHAPES: [&str; 4] = ["sphere", "cylinder", "ellipsoid", "molecule"];
/// The shapes of `[units]` that make an asymmetric top.
pub const GENERAL_SHAPES: [&str; 2] = ["ellipsoid", "molecule"];

/// A value that was given, with the byte range it came from.
type At<T> = Option<(T, Range<usize>)>;

/// The file name and text, to turn byte offsets into lines.
struct Ctx<'a> {
    file: &'a str,
    text: &'a str,
}

impl Ctx<'_> {
    fn line(&self, offset: usize) -> usize {
        let end = offset.min(self.text.len());
        1 + self.text.as_bytes()[..end]
            .iter()
            .filter(|b| **b == b'\n')
            .count()
    }

    fn at(&self, span: &Range<usize>, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.to_string(),
            line: self.line(span.start),
            message: message.into(),
        }
    }
}

/// A plain number key: finite, or refused with the key and what it expects.
fn num(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<Real>,
    expected: &str,
) -> Result<At<Real>, SceneError> {
    let Some(v) = v else { return Ok(None) };
    let x = *v.get_ref();
    if !x.is_finite() {
        return Err(ctx.at(
            &v.span(),
            format!("[{section}] {key} = {x} is not a finite number; expected {expected}"),
        ));
    }
    Ok(Some((x, v.span())))
}

/// A number key that must satisfy `ok`.
fn num_in(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<Real>,
    ok: impl Fn(Real) -> bool,
    expected: &str,
) -> Result<At<Real>, SceneError> {
    let got = num(ctx, section, key, v, expected)?;
    if let Some((x, span)) = &got
        && !ok(*x)
    {
        return Err(ctx.at(
            span,
            format!("[{section}] {key} = {x} is out of range; expected {expected}"),
        ));
    }
    Ok(got)
}

/// An array key whose entries must all be finite.
fn finite_array<const N: usize>(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<[Real; N]>,
    expected: &str,
) -> Result<At<[Real; N]>, SceneError> {
    let Some(v) = v else { return Ok(None) };
    let a = *v.get_ref();
    if let Some(x) = a.iter().find(|x| !x.is_finite()) {
        return Err(ctx.at(
            &v.span(),
            format!("[{section}] {key} holds {x}, not a finite number; expected {expected}"),
        ));
    }
    Ok(Some((a, v.span())))
}

/// A string key that must be one of `options`; returns its index.
fn choice(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<String>,
    options: &[&str],
) -> Result<At<usize>, SceneError> {
    let Some(v) = v else { return Ok(None) };
    let s = v.get_ref();
    match options.iter().position(|o| o == s) {
        Some(i) => Ok(Some((i, v.span()))),
        None => Err(ctx.at(
            &v.span(),
            format!(
                "[{section}] {key} = \"{s}\" is not known; expected one of {}",
                options.join(", ")
            ),
        )),
    }
}

fn missing(
    ctx: &Ctx,
    header: &Range<usize>,
    section: &str,
    key: &str,
    expected: &str,
) -> SceneError {
    ctx.at(
        header,
        format!("[{section}] is missing the key {key}; expected {expected}"),
    )
}

/// A key given where it does not belong.
fn not_here<T>(
    ctx: &Ctx,
    v: &Key<T>,
    section: &str,
    key: &str,
    why: &str,
) -> Result<(), SceneError> {
    match v {
        Some(v) => Err(ctx.at(&v.span(), format!("[{section}] {key} {why}"))),
        None => Ok(()),
    }
}

/// Point a refused physical parameter at the key it came from.
fn param(
    ctx: &Ctx,
    e: ParamError,
    spans: &[(&str, Option<&Range<usize>>)],
    fallback: &Range<usize>,
    section: &str,
) -> SceneError {
    let name = match &e {
        ParamError::NotFinite { name, .. } | ParamError::OutOfRange { name, .. } => *name,
        ParamError::RatioOutOfRange(_) => "I3/I1",
        ParamError::MomentNotPositive { .. } | ParamError::TriangleInequality(..) => "inertia",
        ParamError::ZeroDipole => "dipole",
        ParamError::NegativeTau(_) => "tau",
    };
    let found = spans
        .iter()
        .find(|(n, _)| *n == name || name.starts_with(n))
        .and_then(|(n, s)| s.map(|s| (n, s)));
    match found {
        Some((_, span)) => ctx.at(span, format!("[{section}] {e}")),
        None => ctx.at(fallback, format!("[{section}] {e}")),
    }
}

/// The bare key that a `key = value` line holding byte `offset` assigns.
fn key_on_line(text: &str, offset: usize) -> Option<&str> {
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

/// Parse and validate a scene.
///
/// `file` names the text in messages (a path, or `catalogue:NAME`).
pub fn parse(text: &str, file: &str) -> Result<Scene, SceneError> {
    let ctx = Ctx { file, text };
    let raw: RawFile = toml::from_str(text).map_err(|e| {
        let start = e.span().map_or(0, |s| s.start);
        let mut message = e
            .message()
            .trim()
            .replace('\n', " ")
            .replace("unknown field", "unknown key")
            .replace("expected f64", "expected a number")
            .replace("expected i64", "expected a whole number");
        // NOTE: serde's type errors do not name the key; the line does.
        if message.starts_with("invalid")
            && let Some(key) = key_on_line(text, start)
        {
            message = format!("{key}: {message}");
        }
        SceneError {
            file: file.to_string(),
            line: ctx.line(start),
            message,
        }
    })?;
    let whole = 0..0;
    let Some(scene) = &raw.scene else {
        return Err(ctx.at(
            &whole,
            "there is no [scene] section; expected [scene] with name, kind and description",
        ));
    };
    let header = scene.span();
    let scene = scene.get_ref();
    let name = scene.name.as_ref().ok_or_else(|| {
        missing(
            &ctx,
            &header,
            "scene",
            "name",
            "a name of lower-case letters, digits and dashes",
        )
    })?;
    let name_ok = !name.get_ref().is_empty()
        && name.get_ref().len() <= 60
        && name
            .get_ref()
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-');
    if !name_ok {
        return Err(ctx.at(
            &name.span(),
            format!(
                "[scene] name = \"{}\" is not a scene name; expected 1 to 60 lower-case letters, digits and dashes",
                name.get_ref()
            ),
        ));
    }
    let (kind, _) = choice(&ctx, "scene", "kind", &scene.kind, &KINDS)?.ok_or_else(|| {
        missing(
            &ctx,
            &header,
            "scene",
            "kind",
            &format!("one of {}", KINDS.join(", ")),
        )
    })?;
    let kind = [
        Kind::Top,
        Kind::Balance,
        Kind::Orbit,
        Kind::Shell,
        Kind::Stability,
    ][kind];
    let description = scene.description.as_ref().ok_or_else(|| {
        missing(
            &ctx,
            &header,
            "scene",
            "description",
            "a paragraph saying what the scene asks",
        )
    })?;
    if description.get_ref().trim().is_empty() {
        return Err(ctx.at(
            &description.span(),
            "[scene] description is empty; expected a paragraph saying what the scene asks",
        ));
    }

    // Sections that belong to another kind are refused, not ignored.
    let present: [(&str, Option<Range<usize>>); 7] = [
        ("top", raw.top.as_ref().map(Spanned::span)),
        ("balance", raw.balance.as_ref().map(Spanned::span)),
        ("orbit", raw.orbit.as_ref().map(Spanned::span)),
        ("shell", raw.shell.as_ref().map(Spanned::span)),
        ("stability", raw.stability.as_ref().map(Spanned::span)),
        ("solve", raw.solve.as_ref().map(Spanned::span)),
        ("units", raw.units.as_ref().map(Spanned::span)),
    ];
    let allowed: &[&str] = match kind {
        Kind::Top => &["top", "solve", "units"],
        Kind::Balance => &["balance", "solve"],
        Kind::Orbit => &["orbit", "solve"],
        Kind::Shell => &["shell", "solve"],
        Kind::Stability => &["stability"],
    };
    for (section, span) in &present {
        if let Some(span) = span
            && !allowed.contains(section)
        {
            return Err(ctx.at(
                span,
                format!(
                    "[{section}] does not belong in a scene of kind = \"{}\"; expected {}",
                    kind.name(),
                    kind.sections()
                ),
            ));
        }
    }
    let own = present
        .iter()
        .find(|(s, _)| *s == kind.name())
        .and_then(|(_, span)| span.clone())
        .ok_or_else(|| {
            ctx.at(
                &header,
                format!(
                    "a scene of kind = \"{}\" needs a [{}] section; expected {}",
                    kind.name(),
                    kind.name(),
                    kind.sections()
                ),
            )
        })?;
    let solve_line = raw
        .solve
        .as_ref()
        .map_or(ctx.line(own.start), |s| ctx.line(s.span().start));
    let solve = raw.solve.as_ref().map(|s| (s.get_ref(), s.span()));

    let built = match kind {
        Kind::Top => {
            let top = raw.top.as_ref().expect("checked above");
            let units = raw.units.as_ref().map(|u| (u.get_ref(), u.span()));
            top_scene(&ctx, top.get_ref(), &own, solve, units)?
        }
        Kind::Balance => balance_scene(
            &ctx,
            raw.balance.as_ref().expect("checked").get_ref(),
            &own,
            solve,
        )?,
        Kind::Orbit => orbit_scene(
            &ctx,
            raw.orbit.as_ref().expect("checked").get_ref(),
            &own,
            solve,
        )?,
        Kind::Shell => shell_scene(
            &ctx,
            raw.shell.as_ref().expect("checked").get_ref(),
            &own,
            solve,
        )?,
        Kind::Stability => {
            let raw_row = &raw.stability.as_ref().expect("checked").get_ref().row;
            let row = raw_row
                .as_ref()
                .ok_or_else(|| missing(&ctx, &own, "stability", "row", "a row number, 1 to 6"))?;
            let n = *row.get_ref();
            if !(1..=6).contains(&n) {
                return Err(ctx.at(
                    &row.span(),
                    format!("[stability] row = {n} is out of range; expected a row number, 1 to 6"),
                ));
            }
            let n = n as u8;
            Built {
                body: Body::Stability(StabilityScene { row: n }),
                chosen: plan::stability_choice(n),
                warnings: Vec::new(),
                times_line: None,
            }
        }
    };
    Ok(Scene {
        file: file.to_string(),
        name: name.get_ref().clone(),
        description: description.get_ref().trim().to_string(),
        body: built.body,
        chosen: built.chosen,
        warnings: built.warnings,
        lines: Lines {
            solve: solve_line,
            times: built.times_line.map_or(solve_line, |s| ctx.line(s.start)),
        },
    })
}

/// A validated body with its choice.
struct Built {
    body: Body,
    chosen: Chosen,
    warnings: Vec<String>,
    times_line: Option<Range<usize>>,
}

/// The output times of `[solve]`: `times`, or `t_end` with `samples` evenly
/// spaced from 0, scaled by `scale` (τ per time unit). Returns the times and
/// the span to point at in later complaints.
fn solve_times(
    ctx: &Ctx,
    solve: Option<(&RawSolve, Range<usize>)>,
    section: &Range<usize>,
    default: Option<(Real, usize)>,
    any_order: bool,
    scale: Real,
) -> Result<(Vec<Real>, Option<Range<usize>>), SceneError> {
    let none = RawSolve {
        method: None,
        rtol: None,
        step: None,
        times: None,
        t_end: None,
        samples: None,
    };
    let (s, header) = match &solve {
        Some((s, span)) => (*s, span.clone()),
        None => (&none, section.clone()),
    };
    let t_end_or_samples = s
        .t_end
        .as_ref()
        .map(Spanned::span)
        .or(s.samples.as_ref().map(Spanned::span));
    if s.times.is_some()
        && let Some(other) = t_end_or_samples
    {
        return Err(ctx.at(
            &other,
            "[solve] gives both times and t_end/samples; expected either times = [...] or t_end (with samples)",
        ));
    }
    if let Some(times) = &s.times {
        let list = times.get_ref();
        let span = times.span();
        if list.is_empty() {
            return Err(ctx.at(&span, "[solve] times is empty; expected at least one time"));
        }
        if let Some(t) = list.iter().find(|t| !t.is_finite()) {
            return Err(ctx.at(
                &span,
                format!("[solve] times holds {t}; expected finite numbers"),
            ));
        }
        if !any_order {
            if let Some(t) = list.iter().find(|t| **t < 0.0) {
                return Err(ctx.at(
                    &span,
                    format!("[solve] times holds {t}; expected times >= 0"),
                ));
            }
            if let Some(w) = list.windows(2).find(|w| w[1] < w[0]) {
                return Err(ctx.at(
                    &span,
                    format!(
                        "[solve] times must be non-decreasing, but {} comes after {}; expected times in increasing order",
                        w[1], w[0]
                    ),
                ));
            }
        }
        let scaled: Vec<Real> = list.iter().map(|t| t * scale).collect();
        if scaled.iter().any(|t| !t.is_finite()) {
            return Err(ctx.at(
                &span,
                "[solve] times overflow when converted to units of tau; expected shorter times",
            ));
        }
        return Ok((scaled, Some(span)));
    }
    let t_end = num_in(ctx, "solve", "t_end", &s.t_end, |t| t >= 0.0, "a time >= 0")?;
    let samples = match &s.samples {
        Some(n) => {
            let v = *n.get_ref();
            if !(1..=1_000_000).contains(&v) {
                return Err(ctx.at(
                    &n.span(),
                    format!("[solve] samples = {v} is out of range; expected 1 to 1000000"),
                ));
            }
            Some(v as usize)
        }
        None => None,
    };
    let (t_end, span, n) = match (t_end, default) {
        (Some((t, span)), d) => (t, Some(span), samples.unwrap_or(d.map_or(11, |d| d.1))),
        (None, Some((t, n))) => {
            if let Some(sp) = &s.samples {
                return Err(ctx.at(
                    &sp.span(),
                    "[solve] samples needs t_end; expected t_end = ... beside it",
                ));
            }
            (t, None, samples.unwrap_or(n))
        }
        (None, None) => {
            return Err(ctx.at(
                &header,
                "[solve] gives no output times; expected times = [...] or t_end = ... (with samples)",
            ));
        }
    };
    let t_end = t_end * scale;
    if !t_end.is_finite() {
        return Err(ctx.at(
            &header,
            "[solve] t_end overflows when converted to units of tau; expected a shorter time",
        ));
    }
    let times = if n == 1 {
        vec![t_end]
    } else {
        (0..n)
            .map(|i| t_end * i as Real / (n - 1) as Real)
            .collect()
    };
    Ok((times, span))
}

/// Refuse `method`, `rtol` and `step` where the kind fixes its own method.
fn fixed_method(
    ctx: &Ctx,
    solve: Option<(&RawSolve, Range<usize>)>,
    kind: &str,
    why: &str,
    rtol_ok: bool,
) -> Result<(), SceneError> {
    let Some((s, _)) = solve else { return Ok(()) };
    if let Some((m, span)) = choice(ctx, "solve", "method", &s.method, &METHODS)?
        && m != 0
    {
        return Err(ctx.at(
            &span,
            format!("[solve] method = \"{}\" does not apply to kind = \"{kind}\" ({why}); expected auto", METHODS[m]),
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

fn top_scene(
    ctx: &Ctx,
    raw: &RawTop,
    own: &Range<usize>,
    solve: Option<(&RawSolve, Range<usize>)>,
    units: Option<(&RawUnits, Range<usize>)>,
) -> Result<Built, SceneError> {
    let (model_index, model_span) =
        choice(ctx, "top", "model", &raw.model, &MODELS)?.ok_or_else(|| {
            missing(
                ctx,
                own,
                "top",
                "model",
                &format!("one of {}", MODELS.join(", ")),
            )
        })?;
    let auto_model = model_index == 4;
    let general_shape = units
        .as_ref()
        .and_then(|(u, _)| u.shape.as_ref())
        .is_some_and(|s| GENERAL_SHAPES.contains(&s.get_ref().as_str()));
    let general =
        model_index == 2 || raw.inertia.is_some() || raw.dipole.is_some() || general_shape;
    let mut general_units = None;
    let units = match units {
        Some((u, span)) if general => {
            if model_index == 3 {
                return Err(ctx.at(
                    &model_span,
                    "[top] model = \"full\" cannot take [units]: a real particle turns 10^15 times or more before its radiation shows, and the physical solution steps every turn; expected auto, truncated or reduced",
                ));
            }
            let why = "follows from [units]; remove it";
            not_here(
                ctx,
                &raw.inertia,
                "top",
                "inertia",
                &format!("{why} (the particle's moments)"),
            )?;
            not_here(
                ctx,
                &raw.dipole,
                "top",
                "dipole",
                &format!("{why} (dipole_vector_debye)"),
            )?;
            not_here(
                ctx,
                &raw.omega,
                "top",
                "omega",
                &format!("{why} (omega_hz)"),
            )?;
            not_here(
                ctx,
                &raw.ratio,
                "top",
                "ratio",
                "belongs to the symmetric models",
            )?;
            general_units = Some(rigid_units(ctx, u, &span)?);
            None
        }
        Some((u, span)) => {
            if !(model_index == 0 || model_index == 1 || auto_model) {
                return Err(ctx.at(
                    &model_span,
                    format!(
                        "[top] model = \"{}\" cannot take [units]; expected auto, truncated or reduced (the closed-form models of a real sphere or cylinder)",
                        MODELS[model_index]
                    ),
                ));
            }
            let why = "follows from [units]; remove it";
            not_here(
                ctx,
                &raw.ratio,
                "top",
                "ratio",
                &format!("{why} (I3/I1 of the shape)"),
            )?;
            not_here(
                ctx,
                &raw.omega,
                "top",
                "omega",
                &format!("{why} (spin_hz and spin_tilt_deg)"),
            )?;
            Some(real_units(ctx, u, &span)?)
        }
        None => None,
    };
    let ratio = num(ctx, "top", "ratio", &raw.ratio, "a number in (0, 2]")?;
    let inertia = finite_array(
        ctx,
        "top",
        "inertia",
        &raw.inertia,
        "three positive principal moments",
    )?;
    let dipole = finite_array(
        ctx,
        "top",
        "dipole",
        &raw.dipole,
        "three numbers, the body-frame dipole",
    )?;
    // The three models of this top, lightest first: the truncated ALE, the
    // reduced ALE, the physical solution of (3.4).
    let tiers: [Model; 3] = if !general {
        let general_only = "belongs to an asymmetric top (model = \"general\", or inertia and dipole with any model); the symmetric models take ratio";
        not_here(ctx, &raw.inertia, "top", "inertia", general_only)?;
        not_here(ctx, &raw.dipole, "top", "dipole", general_only)?;
        let r = match (&units, &ratio) {
            (Some(u), _) => u.particle.ratio(),
            (None, Some((r, _))) => *r,
            (None, None) => 0.4,
        };
        let top = SymmetricTop::new(r, 1.0).map_err(|e| {
            let span = ratio.as_ref().map(|(_, s)| s);
            param(ctx, e, &[("I3/I1", span)], own, "top")
        })?;
        [Model::Truncated(top), Model::Reduced(top), Model::Full(top)]
    } else {
        not_here(
            ctx,
            &raw.ratio,
            "top",
            "ratio",
            "belongs to the symmetric models; an asymmetric top takes inertia and dipole",
        )?;
        let top = match &general_units {
            Some(g) => g.particle.top(),
            None => {
                let (i, i_span) = inertia.clone().ok_or_else(|| {
                    missing(
                        ctx,
                        own,
                        "top",
                        "inertia",
                        "inertia = [I1, I2, I3] for an asymmetric top",
                    )
                })?;
                let (d, d_span) = dipole.clone().ok_or_else(|| {
                    missing(
                        ctx,
                        own,
                        "top",
                        "dipole",
                        "dipole = [d1, d2, d3] for an asymmetric top",
                    )
                })?;
                GeneralTop::new(Vec3::from(i), Vec3::from(d)).map_err(|e| {
                    param(
                        ctx,
                        e,
                        &[
                            ("inertia", Some(&i_span)),
                            ("I", Some(&i_span)),
                            ("dipole", Some(&d_span)),
                            ("d", Some(&d_span)),
                        ],
                        own,
                        "top",
                    )
                })?
            }
        };
        [
            Model::General(top),
            Model::GeneralReduced(top),
            Model::GeneralFull(top),
        ]
    };
    let asked_tier = match model_index {
        0 | 2 => Some(0),
        1 => Some(1),
        3 => Some(2),
        _ => None,
    };

    // Ω₀: given, or from the particle's spin.
    let omega_key = finite_array(
        ctx,
        "top",
        "omega",
        &raw.omega,
        "three body-frame rates in 1/tau",
    )?;
    let omega0 = match (&units, &general_units, &omega_key) {
        (Some(u), _, _) => u
            .particle
            .omega0_per_tau(u.spin_hz, u.spin_tilt_deg.to_radians()),
        (None, Some(g), _) => g.particle.omega0(g.omega_hz),
        (None, None, Some((w, span))) => {
            if w.iter().any(|x| x.abs() > MAX_RATE) {
                return Err(ctx.at(span, "[top] omega is out of range; expected each component at most 1e100 in units of 1/tau"));
            }
            Vec3::from(*w)
        }
        (None, None, None) => Vec3::new(0.0, 0.1, 0.2),
    };
    let inertia_of_top = tiers[0].inertia();

    // O(0): Euler angles, or the paper's frame.
    let euler_key = finite_array(
        ctx,
        "top",
        "euler",
        &raw.euler,
        "three z-x-z Euler angles in radians",
    )?;
    let frame_key = choice(ctx, "top", "frame", &raw.frame, &["paper"])?;
    if let (Some(_), Some((_, span))) = (&euler_key, &frame_key) {
        return Err(ctx.at(
            span,
            "[top] gives both euler and frame; expected one of them",
        ));
    }
    let (euler, frame) = match (&euler_key, &frame_key) {
        (Some((e, _)), _) => (EulerAngles::new(e[0], e[1], e[2]), Frame::Euler),
        (None, Some(_)) => (
            frame_with_z_along(&angular_momentum_body(&inertia_of_top, &omega0)),
            Frame::Paper,
        ),
        (None, None) => (EulerAngles::new(0.0, 0.0, 0.0), Frame::Euler),
    };
    let initial =
        InitialState::new(omega0, euler).map_err(|e| ctx.at(own, format!("[top] {e}")))?;

    // [solve]
    let s = solve.as_ref().map(|(s, _)| *s);
    let method_key = match s {
        Some(s) => choice(ctx, "solve", "method", &s.method, &METHODS)?,
        None => None,
    };
    let method = match method_key.as_ref().map_or(0, |(m, _)| *m) {
        0 => MethodChoice::Auto,
        1 => MethodChoice::Exact,
        2 => MethodChoice::Rk4,
        3 => MethodChoice::Dopri5,
        4 => MethodChoice::Dop853,
        5 => MethodChoice::Radau5,
        6 => MethodChoice::Taylor,
        _ => MethodChoice::Forward,
    };
    let method_span = method_key.as_ref().map_or(own.clone(), |(_, s)| s.clone());
    let method_name = METHODS[method_key.as_ref().map_or(0, |(m, _)| *m)];
    if auto_model && method != MethodChoice::Auto {
        return Err(ctx.at(&method_span, format!("[solve] method = \"{method_name}\": model = \"auto\" chooses the model and its method together; remove method, or name the model in [top]")));
    }
    if let Some(tier) = asked_tier {
        match (&tiers[tier], method) {
            (Model::General(_) | Model::GeneralReduced(_), MethodChoice::Exact) => {
                return Err(ctx.at(&method_span, "[solve] method = \"exact\": the asymmetric top has no closed form; expected auto, rk4, dopri5, dop853, radau5 or taylor"));
            }
            (
                Model::Full(_) | Model::GeneralFull(_),
                MethodChoice::Rk4
                | MethodChoice::Dopri5
                | MethodChoice::Radau5
                | MethodChoice::Taylor,
            ) => {
                return Err(ctx.at(&method_span, format!("[solve] method = \"{method_name}\" does not apply to model = \"full\"; expected auto (its physical solution) or forward (the runaway)")));
            }
            (
                Model::Truncated(_)
                | Model::Reduced(_)
                | Model::General(_)
                | Model::GeneralReduced(_),
                MethodChoice::Forward,
            ) => {
                return Err(ctx.at(&method_span, "[solve] method = \"forward\" belongs to model = \"full\"; expected auto, exact, rk4, dopri5, dop853, radau5 or taylor"));
            }
            _ => {}
        }
    }
    let mut options = MethodOptions::default();
    if let Some(s) = s {
        if let Some((rtol, span)) = num_in(
            ctx,
            "solve",
            "rtol",
            &s.rtol,
            |r| (1e-14..1.0).contains(&r),
            "a relative tolerance in [1e-14, 1)",
        )? {
            if method == MethodChoice::Rk4 {
                return Err(ctx.at(&span, "[solve] rtol applies to the adaptive methods; expected step for method = \"rk4\""));
            }
            options.rtol = rtol;
        }
        if let Some((step, span)) = num_in(
            ctx,
            "solve",
            "step",
            &s.step,
            |h| h > 0.0,
            "a positive step in units of tau",
        )? {
            if method != MethodChoice::Rk4 {
                return Err(ctx.at(&span, "[solve] step sets the fixed step of method = \"rk4\" only; expected rtol for the other methods"));
            }
            options.step = step;
        }
    }
    let scale = match (&units, &general_units) {
        (Some(u), _) => u.tau_per_unit(),
        (None, Some(g)) => g.u_per_unit(),
        (None, None) => 1.0,
    };
    let (times, times_span) =
        solve_times(ctx, solve.clone(), own, Some((100.0, 11)), false, scale)?;
    let t_last = times.last().copied().unwrap_or(0.0);
    let (model, model_choice) = match asked_tier {
        Some(tier) => (tiers[tier], None),
        None => {
            let choice = plan::choose_model(&tiers, &omega0, t_last, options.rtol);
            (tiers[choice.tier], Some(choice.reason))
        }
    };
    let mut plan = plan::plan_top(&model, method, &options, &initial, t_last).map_err(|r| {
        let span = match r.at {
            plan::Blame::Method => method_span.clone(),
            plan::Blame::Times => times_span
                .clone()
                .unwrap_or_else(|| solve.as_ref().map_or(own.clone(), |(_, s)| s.clone())),
        };
        ctx.at(&span, r.message)
    })?;
    if let Some(why) = model_choice {
        plan.chosen.reason = format!("{why}; {}", plan.chosen.reason);
    }
    Ok(Built {
        body: Body::Top(Box::new(TopScene {
            model,
            method,
            options,
            initial,
            euler0: [euler.phi, euler.theta, euler.psi],
            frame,
            times,
            units,
            general_units,
            orientation: plan.orientation,
        })),
        chosen: plan.chosen,
        warnings: plan.warnings,
        times_line: times_span,
    })
}

fn real_units(ctx: &Ctx, u: &RawUnits, header: &Range<usize>) -> Result<RealUnits, SceneError> {
    let s = "units";
    let (shape, _) = choice(ctx, s, "shape", &u.shape, &SHAPES)?
        .ok_or_else(|| missing(ctx, header, s, "shape", "sphere or cylinder"))?;
    let shape = if shape == 0 {
        Shape::Sphere
    } else {
        Shape::Cylinder
    };
    let positive = |key: &str, v: &Key<Real>, what: &str| -> Result<Real, SceneError> {
        num_in(ctx, s, key, v, |x| x > 0.0, &format!("a positive {what}"))?
            .map(|(x, _)| x)
            .ok_or_else(|| missing(ctx, header, s, key, &format!("a positive {what}")))
    };
    let radius_nm = positive("radius_nm", &u.radius_nm, "radius in nanometres")?;
    let length_nm = match shape {
        Shape::Sphere => {
            not_here(
                ctx,
                &u.length_nm,
                s,
                "length_nm",
                "belongs to shape = \"cylinder\"; a sphere has only radius_nm",
            )?;
            0.0
        }
        Shape::Cylinder => positive("length_nm", &u.length_nm, "cylinder length in nanometres")?,
    };
    let density = positive("density_kg_m3", &u.density_kg_m3, "density in kg/m^3")?;
    let debye = positive("dipole_debye", &u.dipole_debye, "dipole moment in debye")?;
    let spin_hz = positive("spin_hz", &u.spin_hz, "spin rate in turns per second")?;
    let spin_tilt_deg = num_in(
        ctx,
        s,
        "spin_tilt_deg",
        &u.spin_tilt_deg,
        |x| (0.0..=180.0).contains(&x),
        "an angle in [0, 180] degrees between the spin and the symmetry axis",
    )?
    .map_or(45.0, |(x, _)| x);
    let upright_deg = num_in(
        ctx,
        s,
        "upright_deg",
        &u.upright_deg,
        |x| x > 0.0 && x < 90.0,
        "an angle in (0, 90) degrees",
    )?
    .map_or(1.0, |(x, _)| x);
    let time_unit = time_unit(ctx, u)?;
    let asymmetric_only = "belongs to shape = \"ellipsoid\" or \"molecule\"";
    not_here(ctx, &u.moments_amu_a2, s, "moments_amu_a2", asymmetric_only)?;
    not_here(ctx, &u.semi_axes_nm, s, "semi_axes_nm", asymmetric_only)?;
    not_here(
        ctx,
        &u.dipole_vector_debye,
        s,
        "dipole_vector_debye",
        &format!(
            "{asymmetric_only}; a sphere's or cylinder's dipole lies on its axis: dipole_debye"
        ),
    )?;
    not_here(
        ctx,
        &u.omega_hz,
        s,
        "omega_hz",
        &format!("{asymmetric_only}; a sphere or cylinder gives spin_hz and spin_tilt_deg"),
    )?;
    // NOTE: nm → cm is 1e-7, kg/m³ → g/cm³ is 1e-3: the particle works in Gaussian units.
    let particle = Particle::new(
        shape,
        radius_nm * 1e-7,
        length_nm * 1e-7,
        density * 1e-3,
        debye * DEBYE_ESU_CM,
    )
    .map_err(|e| ctx.at(header, format!("[units] {e}")))?;
    time_scale_fits(ctx, header, "tau", particle.tau_seconds())?;
    Ok(RealUnits {
        particle,
        spin_hz,
        spin_tilt_deg,
        upright_deg,
        time_unit,
    })
}

/// A particle's time scale in seconds must be a positive, finite double.
fn time_scale_fits(
    ctx: &Ctx,
    header: &Range<usize>,
    name: &str,
    seconds: Real,
) -> Result<(), SceneError> {
    if seconds > 0.0 && seconds.is_finite() {
        Ok(())
    } else {
        Err(ctx.at(header, format!("[units] give {name} = {seconds:e} s, which a double cannot hold; expected sizes and a dipole of laboratory scale")))
    }
}

/// The time unit of `[units] time_unit` (seconds by default).
fn time_unit(ctx: &Ctx, u: &RawUnits) -> Result<TimeUnit, SceneError> {
    Ok(
        choice(ctx, "units", "time_unit", &u.time_unit, &TIME_UNITS)?.map_or(
            TimeUnit::Second,
            |(i, _)| {
                [
                    TimeUnit::Second,
                    TimeUnit::Minute,
                    TimeUnit::Hour,
                    TimeUnit::Day,
                    TimeUnit::Year,
                ][i]
            },
        ),
    )
}

/// `[units]` of an ellipsoid or a molecule.
fn rigid_units(ctx: &Ctx, u: &RawUnits, header: &Range<usize>) -> Result<GeneralUnits, SceneError> {
    let s = "units";
    let (shape, _) = choice(ctx, s, "shape", &u.shape, &SHAPES)?
        .ok_or_else(|| missing(ctx, header, s, "shape", "ellipsoid or molecule"))?;
    if !GENERAL_SHAPES.contains(&SHAPES[shape]) {
        return Err(ctx.at(header, format!("[units] shape = \"{}\" is a symmetric top with its dipole on the axis; an asymmetric top (inertia and dipole, or model = \"general\") takes shape = \"ellipsoid\" or \"molecule\"", SHAPES[shape])));
    }
    let symmetric_only = "belongs to shape = \"sphere\" or \"cylinder\"";
    not_here(
        ctx,
        &u.radius_nm,
        s,
        "radius_nm",
        &format!("{symmetric_only}; an ellipsoid has semi_axes_nm, a molecule moments_amu_a2"),
    )?;
    not_here(ctx, &u.length_nm, s, "length_nm", symmetric_only)?;
    not_here(
        ctx,
        &u.dipole_debye,
        s,
        "dipole_debye",
        &format!(
            "{symmetric_only}, whose dipole lies on the axis; give dipole_vector_debye = [D1, D2, D3]"
        ),
    )?;
    not_here(
        ctx,
        &u.spin_hz,
        s,
        "spin_hz",
        &format!("{symmetric_only}; give omega_hz = [f1, f2, f3], the body-frame rates"),
    )?;
    not_here(
        ctx,
        &u.spin_tilt_deg,
        s,
        "spin_tilt_deg",
        &format!("{symmetric_only}; give omega_hz = [f1, f2, f3]"),
    )?;
    not_here(ctx, &u.upright_deg, s, "upright_deg", symmetric_only)?;
    let three = |key: &str, v: &Key<[Real; 3]>, what: &str| -> Result<[Real; 3], SceneError> {
        finite_array(ctx, s, key, v, what)?
            .map(|(x, _)| x)
            .ok_or_else(|| missing(ctx, header, s, key, what))
    };
    let shape = if SHAPES[shape] == "ellipsoid" {
        not_here(
            ctx,
            &u.moments_amu_a2,
            s,
            "moments_amu_a2",
            "belongs to shape = \"molecule\"; an ellipsoid's moments follow from semi_axes_nm and density_kg_m3",
        )?;
        let density = num_in(
            ctx,
            s,
            "density_kg_m3",
            &u.density_kg_m3,
            |x| x > 0.0,
            "a positive density in kg/m^3",
        )?
        .map(|(x, _)| x)
        .ok_or_else(|| {
            missing(
                ctx,
                header,
                s,
                "density_kg_m3",
                "a positive density in kg/m^3",
            )
        })?;
        RigidShape::Ellipsoid {
            semi_axes_nm: three(
                "semi_axes_nm",
                &u.semi_axes_nm,
                "three positive semi-axes in nm, along the body axes",
            )?,
            density_kg_m3: density,
        }
    } else {
        not_here(
            ctx,
            &u.semi_axes_nm,
            s,
            "semi_axes_nm",
            "belongs to shape = \"ellipsoid\"; a molecule gives moments_amu_a2",
        )?;
        not_here(
            ctx,
            &u.density_kg_m3,
            s,
            "density_kg_m3",
            "belongs to shape = \"ellipsoid\"; a molecule gives moments_amu_a2",
        )?;
        let m = three(
            "moments_amu_a2",
            &u.moments_amu_a2,
            "three principal moments in amu A^2",
        )?;
        let total: Real = m.iter().sum();
        for (k, &mk) in m.iter().enumerate() {
            let others = total - mk;
            if mk > others * (1.0 + 1e-12) {
                let span = u
                    .moments_amu_a2
                    .as_ref()
                    .map_or(header.clone(), |v| v.span());
                return Err(ctx.at(&span, format!("[units] moments_amu_a2: I{} = {} exceeds the sum of the other two, {}, by {:.3e} amu A^2, which no rigid body does; measured moments carry the inertia defect of vibration, so give the rigid ones (I_C = I_A + I_B for a planar molecule)", k + 1, mk, others, mk - others)));
            }
        }
        RigidShape::Molecule { moments_amu_a2: m }
    };
    let dipole = three(
        "dipole_vector_debye",
        &u.dipole_vector_debye,
        "three numbers, the body-frame dipole in debye",
    )?;
    let omega_hz = three(
        "omega_hz",
        &u.omega_hz,
        "three body-frame rates in turns per second",
    )?;
    if omega_hz.iter().any(|x| x.abs() > 1e30) {
        return Err(ctx.at(
            header,
            "[units] omega_hz is out of range; expected each rate at most 1e30 Hz",
        ));
    }
    let particle =
        RigidParticle::new(shape, dipole).map_err(|e| ctx.at(header, format!("[units] {e}")))?;
    time_scale_fits(ctx, header, "tau_f", particle.fast_time_seconds())?;
    Ok(GeneralUnits {
        particle,
        omega_hz,
        time_unit: time_unit(ctx, u)?,
    })
}

fn balance_scene(
    ctx: &Ctx,
    raw: &RawBalance,
    own: &Range<usize>,
    solve: Option<(&RawSolve, Range<usize>)>,
) -> Result<Built, SceneError> {
    let s = "balance";
    let kinds = ["precessing", "loop", "dumbbell"];
    let (which, _) = choice(ctx, s, "dipole", &raw.dipole, &kinds)?
        .ok_or_else(|| missing(ctx, own, s, "dipole", "one of precessing, loop, dumbbell"))?;
    let cone = num(ctx, s, "cone", &raw.cone, "a cone angle in [0, pi]")?;
    let rate = num(ctx, s, "rate", &raw.rate, "a non-zero rate")?;
    let b = num(ctx, s, "b", &raw.b, "a number")?;
    let eps = num(ctx, s, "eps", &raw.eps, "a number")?;
    let charges = finite_array(ctx, s, "charges", &raw.charges, "two charges")?;
    let masses = finite_array(ctx, s, "masses", &raw.masses, "two positive masses")?;
    let length = num(ctx, s, "length", &raw.length, "a positive length")?;
    let sp = |x: &At<Real>| x.as_ref().map(|(_, s)| s.clone());
    let spa = |x: &At<[Real; 2]>| x.as_ref().map(|(_, s)| s.clone());
    let (cs, rs, bs, es, qs, ms, ls) = (
        sp(&cone),
        sp(&rate),
        sp(&b),
        sp(&eps),
        spa(&charges),
        spa(&masses),
        sp(&length),
    );
    // Keys of another trajectory are refused, not ignored: each key, where it
    // was given, which trajectories (by index) take it, and their names.
    type Owner<'a> = (&'a str, &'a Option<Range<usize>>, &'a [usize], &'a str);
    let owners: [Owner; 7] = [
        ("cone", &cs, &[0], "precessing"),
        ("rate", &rs, &[0, 2], "precessing or dumbbell"),
        ("b", &bs, &[1], "loop"),
        ("eps", &es, &[1], "loop"),
        ("charges", &qs, &[2], "dumbbell"),
        ("masses", &ms, &[2], "dumbbell"),
        ("length", &ls, &[2], "dumbbell"),
    ];
    for (key, span, belongs, owner) in owners {
        if let Some(span) = span
            && !belongs.contains(&which)
        {
            return Err(ctx.at(
                span,
                format!(
                    "[balance] {key} belongs to dipole = \"{owner}\"; expected only the keys of dipole = \"{}\"",
                    kinds[which]
                ),
            ));
        }
    }
    let spans = [
        ("cone", cs.as_ref()),
        ("rate", rs.as_ref()),
        ("b", bs.as_ref()),
        ("eps", es.as_ref()),
        ("q", qs.as_ref()),
        ("m", ms.as_ref()),
        ("length", ls.as_ref()),
    ];
    let dipole = match which {
        0 => {
            let (c, r) = (cone.map_or(0.5, |x| x.0), rate.map_or(1.0, |x| x.0));
            BalanceDipole::Precessing {
                cone: c,
                rate: r,
                dipole: PrecessingDipole::new(c, r).map_err(|e| param(ctx, e, &spans, own, s))?,
            }
        }
        1 => {
            let (bb, ee) = (b.map_or(0.5, |x| x.0), eps.map_or(0.2, |x| x.0));
            BalanceDipole::Loop {
                b: bb,
                eps: ee,
                dipole: PlanarLoop::new(bb, ee).map_err(|e| param(ctx, e, &spans, own, s))?,
            }
        }
        _ => {
            let q = charges.map_or([1.0, -1.0], |x| x.0);
            let m = masses.map_or([1.0, 1.0], |x| x.0);
            let l = length.map_or(1.0, |x| x.0);
            let r = rate.map_or(1.0, |x| x.0);
            BalanceDipole::Dumbbell {
                charges: q,
                masses: m,
                length: l,
                rate: r,
                dipole: Dumbbell::new(q, m, l, r).map_err(|e| param(ctx, e, &spans, own, s))?,
            }
        }
    };
    fixed_method(
        ctx,
        solve.clone(),
        s,
        "the trajectory is given in closed form",
        false,
    )?;
    let (times, times_span) = solve_times(ctx, solve, own, None, true, 1.0)?;
    Ok(Built {
        body: Body::Balance(BalanceScene { dipole, times }),
        chosen: plan::balance_choice(),
        warnings: Vec::new(),
        times_line: times_span,
    })
}

fn orbit_scene(
    ctx: &Ctx,
    raw: &RawOrbit,
    own: &Range<usize>,
    solve: Option<(&RawSolve, Range<usize>)>,
) -> Result<Built, SceneError> {
    let s = "orbit";
    let (potential, _) = choice(
        ctx,
        s,
        "potential",
        &raw.potential,
        &["coulomb", "harmonic"],
    )?
    .ok_or_else(|| missing(ctx, own, s, "potential", "coulomb or harmonic"))?;
    let potential = if potential == 0 {
        Potential::Coulomb
    } else {
        Potential::Harmonic
    };
    let (tau0, tau0_span) = num(ctx, s, "tau0", &raw.tau0, "a positive tau0 = 2q^2/(3mc^3)")?
        .ok_or_else(|| missing(ctx, own, s, "tau0", "a positive tau0 = 2q^2/(3mc^3)"))?;
    let force = match choice(ctx, s, "force", &raw.force, &["ll", "al", "al-forward"])? {
        None | Some((0, _)) => Force::LandauLifshitz,
        Some((1, _)) => Force::AbrahamLorentz,
        Some(_) => Force::AbrahamLorentzForward,
    };
    let r0 = num(ctx, s, "r0", &raw.r0, "a positive radius")?;
    let e = num(
        ctx,
        s,
        "eccentricity",
        &raw.eccentricity,
        "an eccentricity in [0, 1)",
    )?;
    let r0_span = r0.as_ref().map(|(_, s)| s.clone());
    let e_span = e.as_ref().map(|(_, s)| s.clone());
    let spans = [
        ("tau0", Some(&tau0_span)),
        ("r0", r0_span.as_ref()),
        ("eccentricity", e_span.as_ref()),
    ];
    let charge =
        ChargeInField::new(potential, tau0).map_err(|err| param(ctx, err, &spans, own, s))?;
    let mut config = OrbitConfig::new(
        charge,
        r0.map_or(1.0, |x| x.0),
        e.map_or(0.0, |x| x.0),
        force,
    )
    .map_err(|err| param(ctx, err, &spans, own, s))?;
    fixed_method(ctx, solve.clone(), s, "its method follows from force", true)?;
    if let Some((sv, _)) = &solve
        && let Some((rtol, _)) = num_in(
            ctx,
            "solve",
            "rtol",
            &sv.rtol,
            |r| (1e-14..=1e-3).contains(&r),
            "a relative tolerance in [1e-14, 1e-3]",
        )?
    {
        config.rtol = rtol;
    }
    let (times, times_span) = solve_times(ctx, solve, own, None, false, 1.0)?;
    Ok(Built {
        body: Body::Orbit(OrbitScene { config, times }),
        chosen: plan::orbit_choice(&config),
        warnings: Vec::new(),
        times_line: times_span,
    })
}

fn shell_scene(
    ctx: &Ctx,
    raw: &RawShell,
    own: &Range<usize>,
    solve: Option<(&RawSolve, Range<usize>)>,
) -> Result<Built, SceneError> {
    let s = "shell";
    let (tau0, tau0_span) = num(ctx, s, "tau0", &raw.tau0, "a positive tau0")?
        .ok_or_else(|| missing(ctx, own, s, "tau0", "a positive tau0 = 2q^2/(3mc^3)"))?;
    let (delay, delay_span) = num(ctx, s, "delay", &raw.delay, "a positive delay r0/c")?
        .ok_or_else(|| {
            missing(
                ctx,
                own,
                s,
                "delay",
                "a positive delay r0/c, different from tau0",
            )
        })?;
    let model = ShellModel::new(tau0, delay).map_err(|e| {
        param(
            ctx,
            e,
            &[("tau0", Some(&tau0_span)), ("delay", Some(&delay_span))],
            own,
            s,
        )
    })?;
    fixed_method(
        ctx,
        solve.clone(),
        s,
        "a delay equation is solved by RK4 on each delay interval",
        false,
    )?;
    let (times, times_span) = solve_times(ctx, solve, own, None, false, 1.0)?;
    let mut warnings = Vec::new();
    if let Some(rate) = model.growth_rate() {
        warnings.push(format!(
            "(A.1) is unstable here (m0 = {:.4}, m_em = {:.4}): solutions grow like exp({rate:.4} t)",
            model.m0(),
            model.m_em()
        ));
    }
    Ok(Built {
        body: Body::Shell(ShellScene { model, times }),
        chosen: plan::shell_choice(&model),
        warnings,
        times_line: times_span,
    })
}
