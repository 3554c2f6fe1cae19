//! A top: the keys of `[top]` and `[solve]` (a scene file's, or the flags
//! of `simulate` and `plot`), validated into a [`TopRequest`]; for a scene,
//! also the real particle of `[units]` turned into τ units, and the plan
//! (which model and method answer it, and why).

use super::format::{At, RawSolve, RawTop, RawUnits};
use super::keys::{
    Ctx, Dialect, Refusal, choice, missing, named, not_here, number, numbers, param, solve_times,
};
use super::table::{self, FRAMES, MODELS, ModelAsk, Tier};
use super::units::{GENERAL_SHAPES, GeneralUnits, RealUnits, real_units, rigid_units};
use super::{Body, Built, Orientation, choose, plan};
use crate::math::{Real, Vec3};
use crate::physics::euler_angles::EulerAngles;
use crate::physics::general_top::GeneralTop;
use crate::physics::rigid_body::lab_frame;
use crate::physics::symmetric_top::SymmetricTop;
use crate::sim::{InitialState, MethodChoice, MethodOptions, Model, OptionsError};

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
    /// Tolerance and step (the tolerance `auto` steps at, which may be
    /// tighter than the scene's: see `rtol`).
    pub options: MethodOptions,
    /// The scene's own rtol, which the printed error is held against.
    pub rtol: Real,
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
    /// With `model = "auto"` and a lighter model chosen: its estimated error
    /// against the physical solution of (3.4), added to what the run prints.
    pub model_error: Option<crate::sim::claim::TierEstimate>,
}

/// The keys of a top validated, before any plan: its three models, the one
/// asked for, the method and the times.
#[derive(Clone, Debug, PartialEq)]
pub struct TopRequest {
    /// The top's three models, lightest first ([`Tier`]).
    pub tiers: [Model; 3],
    /// The model asked for; `None` for `auto`.
    pub tier: Option<Tier>,
    /// The method asked for.
    pub method: MethodChoice,
    /// Tolerance and step.
    pub options: MethodOptions,
    /// Ω₀ and O(0).
    pub initial: InitialState,
    /// The Euler angles of O(0).
    pub euler0: [Real; 3],
    /// How O(0) was given.
    pub frame: Frame,
    /// Output times, in the model's unit of time.
    pub times: Vec<Real>,
    /// The real particle of a sphere's or a cylinder's `[units]`.
    pub units: Option<RealUnits>,
    /// The real particle of an ellipsoid's or a molecule's `[units]`.
    pub general_units: Option<GeneralUnits>,
    /// Where the method was asked for (the section's header if not).
    method_at: At,
    /// Where the times were given, if they were.
    times_at: Option<At>,
}

impl TopRequest {
    /// The model asked for; `None` for `auto`.
    pub fn model(&self) -> Option<Model> {
        self.tier.map(|t| self.tiers[t.index()])
    }
}

/// The real particle of `[units]`, if any.
enum Particle {
    None,
    Symmetric(RealUnits),
    Asymmetric(GeneralUnits),
}

impl Particle {
    /// Model time units per output time unit.
    fn scale(&self) -> Real {
        match self {
            Particle::None => 1.0,
            Particle::Symmetric(u) => u.tau_per_unit(),
            Particle::Asymmetric(g) => g.u_per_unit(),
        }
    }
}

/// Validate the keys of a top (`[top]`, `[solve]` and `[units]`).
pub(super) fn top_request(
    ctx: &Ctx,
    raw: &RawTop,
    own: &At,
    solve: Option<(&RawSolve, At)>,
    units: Option<(&RawUnits, At)>,
) -> Result<TopRequest, Refusal> {
    let (ask, model_at) = named(ctx, "top", "model", &raw.model, &MODELS)?
        .ok_or_else(|| super::keys::missing_key(ctx, own, "top", "model"))?;
    let general_shape = units
        .as_ref()
        .and_then(|(u, _)| u.shape.as_ref())
        .is_some_and(|s| GENERAL_SHAPES.contains(&s.value.as_str()));
    let asymmetric =
        ask.asymmetric || raw.inertia.is_some() || raw.dipole.is_some() || general_shape;
    let particle = match units {
        Some((u, at)) => read_units(ctx, raw, (ask, &model_at), asymmetric, (u, &at))?,
        None => Particle::None,
    };
    let tiers = if asymmetric {
        asymmetric_tiers(ctx, raw, own, &particle)?
    } else {
        symmetric_tiers(ctx, raw, own, &particle)?
    };
    let omega0 = read_omega0(ctx, raw, &particle)?;
    let (euler, frame) = read_orientation(ctx, raw, &tiers[0], &omega0)?;
    let initial = InitialState::new(omega0, euler)
        .map_err(|e| ctx.at(own, format!("{}{e}", ctx.section("top"))))?;
    let solve_ref = solve.as_ref().map(|(s, _)| *s);
    let (method, method_at) = read_method(ctx, solve_ref, own, ask, &tiers)?;
    let options = read_options(ctx, solve_ref, own, method)?;
    let times = solve_times(ctx, solve, own, particle.scale())?;
    let (units, general_units) = match particle {
        Particle::None => (None, None),
        Particle::Symmetric(u) => (Some(u), None),
        Particle::Asymmetric(g) => (None, Some(g)),
    };
    Ok(TopRequest {
        tiers,
        tier: ask.tier,
        method,
        options,
        initial,
        euler0: [euler.phi, euler.theta, euler.psi],
        frame,
        times: times.times,
        units,
        general_units,
        method_at,
        times_at: times.at,
    })
}

/// `[units]`: refuse the keys of `[top]` the particle decides, and read it.
fn read_units(
    ctx: &Ctx,
    raw: &RawTop,
    (ask, model_at): (ModelAsk, &At),
    asymmetric: bool,
    (u, at): (&RawUnits, &At),
) -> Result<Particle, Refusal> {
    let why = "follows from [units]; remove it";
    if asymmetric {
        if ask.tier == Some(Tier::Physical) {
            return Err(ctx.at(
                model_at,
                "[top] model = \"full\" cannot take [units]: a real particle turns 10^15 times or more before its radiation shows, and the physical solution steps every turn; expected auto, truncated or reduced",
            ));
        }
        let because = [
            ("inertia", "the particle's moments"),
            ("dipole", "dipole_vector_debye"),
            ("omega", "omega_hz"),
        ];
        for (key, source) in because {
            let given = match key {
                "inertia" => raw.inertia.as_ref().map(|g| &g.at),
                "dipole" => raw.dipole.as_ref().map(|g| &g.at),
                _ => raw.omega.as_ref().map(|g| &g.at),
            };
            if let Some(at) = given {
                return Err(ctx.at(at, format!("[top] {key} {why} ({source})")));
            }
        }
        not_here(
            ctx,
            &raw.ratio,
            "top",
            "ratio",
            "belongs to the symmetric models",
        )?;
        return Ok(Particle::Asymmetric(rigid_units(ctx, u, at)?));
    }
    if !matches!(ask.tier, None | Some(Tier::Truncated | Tier::Reduced)) {
        let name = raw.model.as_ref().map_or("", |g| g.value.as_str());
        return Err(ctx.at(
            model_at,
            format!(
                "[top] model = \"{name}\" cannot take [units]; expected auto, truncated or reduced (the closed-form models of a real sphere or cylinder)"
            ),
        ));
    }
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
    Ok(Particle::Symmetric(real_units(ctx, u, at)?))
}

/// The three models of a symmetric top (I₃/I₁ from `ratio`, the particle,
/// or the table's default), lightest first.
fn symmetric_tiers(
    ctx: &Ctx,
    raw: &RawTop,
    own: &At,
    particle: &Particle,
) -> Result<[Model; 3], Refusal> {
    let ratio = number(ctx, "top", "ratio", &raw.ratio, false)?;
    let r = match (particle, &ratio) {
        (Particle::Symmetric(u), _) => u.particle.ratio(),
        (_, Some((r, _))) => *r,
        _ => ctx
            .spec("top", "ratio")
            .default
            .number()
            .unwrap_or(crate::physics::symmetric_top::FIGURE_RATIO),
    };
    let top = SymmetricTop::new(r, 1.0).map_err(|e| {
        let at = ratio.as_ref().map(|(_, at)| at);
        param(ctx, e, &[("I3/I1", "ratio", at)], own, "top")
    })?;
    Ok(Model::Truncated(top).tiers())
}

/// The three models of an asymmetric top (from `inertia` and `dipole`, or
/// the particle), lightest first.
fn asymmetric_tiers(
    ctx: &Ctx,
    raw: &RawTop,
    own: &At,
    particle: &Particle,
) -> Result<[Model; 3], Refusal> {
    not_here(
        ctx,
        &raw.ratio,
        "top",
        "ratio",
        &format!(
            "belongs to the symmetric models; an asymmetric top takes {} and {}",
            ctx.name("inertia"),
            ctx.name("dipole")
        ),
    )?;
    let inertia = numbers(ctx, "top", "inertia", &raw.inertia)?;
    let dipole = numbers(ctx, "top", "dipole", &raw.dipole)?;
    let top = match particle {
        Particle::Asymmetric(g) => g.particle.top(),
        _ => {
            let needs = |key: &str, what: &str, beside: &str| {
                let given = if beside.is_empty() {
                    String::new()
                } else {
                    format!(" (given {})", ctx.name(beside))
                };
                missing(
                    ctx,
                    own,
                    "top",
                    key,
                    &format!(
                        "{}, {what} of an asymmetric top{given}",
                        example(ctx, "top", key)
                    ),
                )
            };
            let beside = |given: bool, key| if given { key } else { "" };
            let (i, i_at) = inertia.clone().ok_or_else(|| {
                needs(
                    "inertia",
                    "the principal moments",
                    beside(dipole.is_some(), "dipole"),
                )
            })?;
            let (d, d_at) = dipole
                .clone()
                .ok_or_else(|| needs("dipole", "the body-frame dipole", beside(true, "inertia")))?;
            GeneralTop::new(Vec3::from(i), Vec3::from(d)).map_err(|e| {
                let keys = [
                    ("inertia", "inertia", Some(&i_at)),
                    ("I", "inertia", Some(&i_at)),
                    ("dipole", "dipole", Some(&d_at)),
                    ("d", "dipole", Some(&d_at)),
                ];
                param(ctx, e, &keys, own, "top")
            })?
        }
    };
    Ok(Model::General(top).tiers())
}

/// A key with its value name, as the source writes it: `inertia = [I1, I2,
/// I3]` in a file, `--inertia I1,I2,I3` on the command line.
fn example(ctx: &Ctx, section: &str, key: &str) -> String {
    let shape = ctx.spec(section, key).value_name;
    match ctx.dialect {
        Dialect::File { .. } => format!("{key} = [{}]", shape.replace(',', ", ")),
        Dialect::Flags => format!("{} {shape}", table::flag_of(key)),
    }
}

/// Ω₀: given, from the particle's spin, or the table's default.
fn read_omega0(ctx: &Ctx, raw: &RawTop, particle: &Particle) -> Result<Vec3, Refusal> {
    let given = numbers(ctx, "top", "omega", &raw.omega)?;
    Ok(match (particle, given) {
        (Particle::Symmetric(u), _) => u
            .particle
            .omega0_per_tau(u.spin_hz, u.spin_tilt_deg.to_radians()),
        (Particle::Asymmetric(g), _) => g.particle.omega0(g.omega_hz),
        (Particle::None, Some((w, at))) => {
            let w = Vec3::from(w);
            crate::sim::check_rate(&w)
                .map_err(|e| ctx.at(&at, format!("{}: {e}", ctx.key("top", "omega"))))?;
            w
        }
        (Particle::None, None) => match ctx.spec("top", "omega").default {
            table::DefaultValue::Numbers(&[w1, w2, w3]) => Vec3::new(w1, w2, w3),
            _ => Vec3::from(crate::physics::symmetric_top::FIGURE_OMEGA0),
        },
    })
}

/// O(0): Euler angles, or the paper's frame (lab z along L₀).
fn read_orientation(
    ctx: &Ctx,
    raw: &RawTop,
    lightest: &Model,
    omega0: &Vec3,
) -> Result<(EulerAngles, Frame), Refusal> {
    let euler = numbers(ctx, "top", "euler", &raw.euler)?;
    let frame = named(ctx, "top", "frame", &raw.frame, &FRAMES)?;
    if let (Some(_), Some((_, at))) = (&euler, &frame) {
        return Err(ctx.at(
            at,
            format!(
                "{}gives both {} and {}; expected one of them",
                ctx.giver("top"),
                ctx.name("euler"),
                ctx.name("frame")
            ),
        ));
    }
    Ok(match (euler, frame) {
        (Some((e, _)), _) => (EulerAngles::new(e[0], e[1], e[2]), Frame::Euler),
        (None, Some(_)) => (lab_frame(&lightest.inertia(), omega0), Frame::Paper),
        (None, None) => (EulerAngles::new(0.0, 0.0, 0.0), Frame::Euler),
    })
}

/// `[solve] method`, refused where the model asked for does not take it.
fn read_method(
    ctx: &Ctx,
    solve: Option<&RawSolve>,
    own: &At,
    ask: ModelAsk,
    tiers: &[Model; 3],
) -> Result<(MethodChoice, At), Refusal> {
    let given = match solve {
        Some(s) => choice(ctx, "solve", "method", &s.method, &MethodChoice::NAMES)?,
        None => None,
    };
    let method = MethodChoice::ALL[given.as_ref().map_or(0, |(m, _)| *m)];
    let at = given.map_or(own.clone(), |(_, at)| at);
    let subject = ctx.set("solve", "method", &ctx.word(method.name()));
    match ask.tier {
        None if method != MethodChoice::Auto => Err(ctx.at(
            &at,
            format!(
                "{subject}: {} chooses the model and its method together; remove {}, or name the model",
                ctx.set_inline("model", "auto"),
                ctx.name("method")
            ),
        )),
        None => Ok((method, at)),
        Some(tier) => {
            tiers[tier.index()]
                .check_method(method)
                .map_err(|e| ctx.at(&at, format!("{subject}: {e}")))?;
            Ok((method, at))
        }
    }
}

/// `[solve] rtol` and `step`, for the method they apply to.
fn read_options(
    ctx: &Ctx,
    solve: Option<&RawSolve>,
    own: &At,
    method: MethodChoice,
) -> Result<MethodOptions, Refusal> {
    // The table's ranges are the check, in one message for flag and key.
    let (rtol, step) = match solve {
        Some(s) => (
            number(ctx, "solve", "rtol", &s.rtol, true)?,
            number(ctx, "solve", "step", &s.step, true)?,
        ),
        None => (None, None),
    };
    MethodOptions::for_choice(
        method,
        rtol.as_ref().map(|(x, _)| *x),
        step.as_ref().map(|(x, _)| *x),
    )
    .map_err(|e| {
        let given = if e.key() == "rtol" { &rtol } else { &step };
        let at = given.as_ref().map_or(own, |(_, at)| at);
        ctx.at(at, options_message(ctx, &e))
    })
}

/// An option refused, naming each setting as the entry point spells it
/// (`--rtol`, `[solve] rtol`).
fn options_message(ctx: &Ctx, e: &OptionsError) -> String {
    let (rtol, step) = (ctx.name("rtol"), ctx.name("step"));
    let rk4 = ctx.set_inline("method", "rk4");
    match e {
        OptionsError::RtolForRk4 => format!(
            "{} applies to the adaptive methods; {rk4} takes {step}",
            ctx.key("solve", "rtol")
        ),
        OptionsError::StepNotRk4 => format!(
            "{} sets the fixed step of {rk4} only; the adaptive methods take {rtol}",
            ctx.key("solve", "step")
        ),
        // Out of the table's range: refused by `number` before.
        other => format!("{}: {other}", ctx.key("solve", e.key())),
    }
}

/// A top scene: its keys validated, then planned.
pub(super) fn top_scene(
    ctx: &Ctx,
    raw: &RawTop,
    own: &At,
    solve: Option<(&RawSolve, At)>,
    units: Option<(&RawUnits, At)>,
) -> Result<Built, Refusal> {
    let solve_at = solve.as_ref().map_or(own.clone(), |(_, at)| at.clone());
    let request = top_request(ctx, raw, own, solve, units)?;
    plan_request(ctx, request, own, &solve_at)
}

/// Which model and method answer a validated top, and why; the refusal of
/// what no method can do, at the key to change.
fn plan_request(ctx: &Ctx, request: TopRequest, own: &At, solve_at: &At) -> Result<Built, Refusal> {
    let TopRequest {
        tiers,
        tier,
        method,
        options,
        initial,
        times,
        ..
    } = &request;
    let t_last = times.last().copied().unwrap_or(0.0);
    let choice = tier
        .is_none()
        .then(|| choose::choose_model(tiers, *method, &initial.omega, times, options.rtol()));
    let (mut model, mut model_choice, without_orientation, mut why_physical) = match (tier, &choice)
    {
        (Some(tier), _) => (tiers[tier.index()], None, None, None),
        (None, Some(c)) => (
            tiers[c.tier],
            Some(c.reason.clone()),
            c.without_orientation.clone(),
            c.why_physical.clone(),
        ),
        (None, None) => (tiers[0], None, None, None),
    };
    let mut model_error = choice.as_ref().and_then(|c| c.model_error(c.tier));
    let mut planned = plan::plan_top(&model, *method, options, initial, t_last, None);
    // The physical solution was chosen and cannot run: a lighter model
    // answers Omega (a closed form), or E and |L| (a general top's secular
    // model), without the orientation, as `auto` would at a longer horizon.
    // The secular fallback's own error is in E and |L| (its drift), not the
    // Ω estimate (phase included) that `auto` made for stepping this tier.
    let mut secular_drift = None;
    let without_orientation = match (&planned, &choice) {
        (Err(refusal), Some(c)) if refusal.at == plan::Blame::Times && c.tier == 2 => {
            without_orientation.or_else(|| {
                choose::secular_fallback(tiers, &initial.omega, times, options.rtol()).map(
                    |(tier, why, drift)| {
                        secular_drift = Some(drift);
                        (tier, why)
                    },
                )
            })
        }
        _ => without_orientation,
    };
    if let (Err(refusal), Some((tier, why))) = (&planned, &without_orientation)
        && refusal.at == plan::Blame::Times
    {
        model = tiers[*tier];
        model_error = match secular_drift {
            Some(drift) => Some(crate::sim::claim::TierEstimate {
                omega: drift,
                orientation: None,
            }),
            None => choice.as_ref().and_then(|c| c.model_error(*tier)).map(|e| {
                crate::sim::claim::TierEstimate {
                    orientation: None,
                    ..e
                }
            }),
        };
        model_choice = Some(why.clone());
        why_physical = None;
        let skip = if model.has_closed_form() {
            "Omega alone is held within rtol without the physical solution, and the orientation is not"
        } else {
            "E and |L| alone are held within rtol without the physical solution, and the orientation is not"
        };
        planned = plan::plan_top(&model, *method, options, initial, t_last, Some(skip));
    }
    let mut plan = planned.map_err(|r| {
        let at = match r.at {
            plan::Blame::Method => request.method_at.clone(),
            plan::Blame::Times => request.times_at.clone().unwrap_or(solve_at.clone()),
        };
        match &why_physical {
            Some(why) if r.at == plan::Blame::Times => ctx.at(&at, format!("{}; {why}", r.message)),
            _ => ctx.at(&at, r.message),
        }
    })?;
    if let Some(why) = model_choice {
        plan.chosen.reason = format!("{why}; {}", plan.chosen.reason);
    }
    plan.chosen.estimates = choice.as_ref().map(|c| c.estimates);
    // `auto` may step at a tighter tolerance than the scene's (see plan::general_path).
    let rtol = options.rtol();
    let options = match plan.rtol {
        Some(r) => options
            .with_rtol(r)
            .map_err(|e| ctx.at(own, format!("{}{e}", ctx.section("solve"))))?,
        None => *options,
    };
    let times_at = request.times_at.clone();
    Ok(Built {
        body: Body::Top(Box::new(TopScene {
            model,
            method: request.method,
            options,
            rtol,
            initial: request.initial,
            euler0: request.euler0,
            frame: request.frame,
            times: request.times,
            units: request.units,
            general_units: request.general_units,
            orientation: plan.orientation,
            model_error,
        })),
        chosen: plan.chosen,
        warnings: plan.warnings,
        times_at,
    })
}

/// A top asked by flags: the keys of `[top]` and `[solve]` the flags fill,
/// validated like a scene's, with messages that name the flags.
pub(super) fn top_flags(raw: &RawTop, solve: &RawSolve) -> Result<TopRequest, Refusal> {
    let ctx = Ctx::flags(table::Command::Simulate);
    top_request(&ctx, raw, &At::Flag, Some((solve, At::Flag)), None)
}
