//! A top scene: the `simulate` parameters of `[top]` and `[solve]`,
//! validated, the real particle of `[units]` turned into τ units, and the plan
//! (which model and method answer it, and why).

use super::format::{RawSolve, RawTop, RawUnits};
use super::keys::{Ctx, choice, finite_array, missing, not_here, num, param, solve_times};
use super::units::{GENERAL_SHAPES, GeneralUnits, RealUnits, real_units, rigid_units};
use super::{Body, Built, Orientation, SceneError, choose, plan};
use crate::math::{Real, Vec3};
use crate::physics::euler_angles::EulerAngles;
use crate::physics::general_top::GeneralTop;
use crate::physics::rigid_body::lab_frame;
use crate::physics::symmetric_top::SymmetricTop;
use crate::sim::{InitialState, MethodChoice, MethodOptions, Model};
use std::ops::Range;

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
    /// With `model = "auto"` and a lighter model chosen: its estimated error
    /// against the physical solution of (3.4), added to what the run prints.
    pub model_error: Option<crate::sim::claim::TierEstimate>,
}

/// The model names of `[top] model`.
pub const MODELS: [&str; 5] = ["truncated", "reduced", "general", "full", "auto"];
/// The method names of `[solve] method` (see [`MethodChoice::NAMES`]).
pub const METHODS: [&str; MethodChoice::NAMES.len()] = MethodChoice::NAMES;
pub(super) fn top_scene(
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
        Model::Truncated(top).tiers()
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
        Model::General(top).tiers()
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
            let w = Vec3::from(*w);
            crate::sim::check_rate(&w).map_err(|e| ctx.at(span, format!("[top] omega: {e}")))?;
            w
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
        (None, Some(_)) => (lab_frame(&inertia_of_top, &omega0), Frame::Paper),
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
    let method = MethodChoice::ALL[method_key.as_ref().map_or(0, |(m, _)| *m)];
    let method_span = method_key.as_ref().map_or(own.clone(), |(_, s)| s.clone());
    let method_name = method.name();
    if auto_model && method != MethodChoice::Auto {
        return Err(ctx.at(&method_span, format!("[solve] method = \"{method_name}\": model = \"auto\" chooses the model and its method together; remove method, or name the model in [top]")));
    }
    if let Some(tier) = asked_tier {
        tiers[tier].check_method(method).map_err(|e| {
            ctx.at(
                &method_span,
                format!("[solve] method = \"{method_name}\": {e}"),
            )
        })?;
    }
    let (rtol, step) = match s {
        Some(s) => (
            num(
                ctx,
                "solve",
                "rtol",
                &s.rtol,
                "a relative tolerance in [1e-14, 1)",
            )?,
            num(
                ctx,
                "solve",
                "step",
                &s.step,
                "a positive step in units of tau",
            )?,
        ),
        None => (None, None),
    };
    let options = MethodOptions::for_choice(
        method,
        rtol.as_ref().map(|(x, _)| *x),
        step.as_ref().map(|(x, _)| *x),
    )
    .map_err(|e| {
        let at = if e.key() == "rtol" { &rtol } else { &step };
        let span = at.as_ref().map_or(own, |(_, span)| span);
        ctx.at(span, format!("[solve] {e}"))
    })?;
    let scale = match (&units, &general_units) {
        (Some(u), _) => u.tau_per_unit(),
        (None, Some(g)) => g.u_per_unit(),
        (None, None) => 1.0,
    };
    let (times, times_span) =
        solve_times(ctx, solve.clone(), own, Some((100.0, 11)), false, scale)?;
    let t_last = times.last().copied().unwrap_or(0.0);
    let choice = asked_tier
        .is_none()
        .then(|| choose::choose_model(&tiers, method, &omega0, &times, options.rtol()));
    let (mut model, mut model_choice, without_orientation, mut why_physical) = match &choice {
        None => (tiers[asked_tier.unwrap_or(0)], None, None, None),
        Some(c) => (
            tiers[c.tier],
            Some(c.reason.clone()),
            c.without_orientation.clone(),
            c.why_physical.clone(),
        ),
    };
    let mut model_error = choice.as_ref().and_then(|c| c.model_error(c.tier));
    let mut planned = plan::plan_top(&model, method, &options, &initial, t_last, None);
    // The physical solution was chosen for the orientation alone and cannot
    // run: a lighter model answers Omega, without the orientation.
    if let (Err(refusal), Some((tier, why))) = (&planned, &without_orientation)
        && refusal.at == plan::Blame::Times
    {
        model = tiers[*tier];
        model_error = choice.as_ref().and_then(|c| c.model_error(*tier)).map(|e| {
            crate::sim::claim::TierEstimate {
                orientation: None,
                ..e
            }
        });
        model_choice = Some(why.clone());
        why_physical = None;
        let skip = "Omega alone is held within rtol without the physical solution, and the orientation is not";
        planned = plan::plan_top(&model, method, &options, &initial, t_last, Some(skip));
    }
    let mut plan = planned.map_err(|r| {
        let span = match r.at {
            plan::Blame::Method => method_span.clone(),
            plan::Blame::Times => times_span
                .clone()
                .unwrap_or_else(|| solve.as_ref().map_or(own.clone(), |(_, s)| s.clone())),
        };
        match &why_physical {
            Some(why) if r.at == plan::Blame::Times => {
                ctx.at(&span, format!("{}; {why}", r.message))
            }
            _ => ctx.at(&span, r.message),
        }
    })?;
    if let Some(why) = model_choice {
        plan.chosen.reason = format!("{why}; {}", plan.chosen.reason);
    }
    plan.chosen.estimates = choice.as_ref().map(|c| c.estimates);
    // `auto` may step at a tighter tolerance than the scene's (see plan::general_path).
    let options = match plan.rtol {
        Some(r) => options
            .with_rtol(r)
            .map_err(|e| ctx.at(own, format!("[solve] {e}")))?,
        None => options,
    };
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
            model_error,
        })),
        chosen: plan.chosen,
        warnings: plan.warnings,
        times_line: times_span,
    })
}
