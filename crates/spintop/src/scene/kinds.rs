//! The scenes of the other kinds, one per command beside `simulate`: a dipole
//! trajectory and its balance laws (`balance`), a charge in a central field
//! (`orbit`), the charge as a small shell (`shell`) and a row of the
//! stability suite (`stability`).

use super::format::{At, Key, RawBalance, RawOrbit, RawShell, RawSolve};
use super::keys::{
    Ctx, Read, Refusal, fixed_method, missing_key, named, number, numbers, param, solve_times,
};
use super::table::{Command, DIPOLES, DefaultValue, DipoleKind, FORCES, POTENTIALS};
use super::{Body, Built, plan};
use crate::math::Real;
use crate::output::Format;
use crate::output::balance::{BalanceConfig, BalanceParameters, DipoleChoice};
use crate::output::orbit::check_backward_span;
use crate::output::shell::steps_per_delay;
use crate::physics::balance::{Dumbbell, PlanarLoop, PrecessingDipole};
use crate::physics::central::ChargeInField;
use crate::physics::shell::ShellModel;
use crate::sim::orbit::OrbitConfig;

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

impl BalanceScene {
    /// The `balance` request it stands for, printed in `format`.
    pub fn config(&self, format: Format) -> BalanceConfig {
        let mut p = BalanceParameters::default();
        let dipole = match self.dipole {
            BalanceDipole::Precessing { cone, rate, dipole } => {
                p.cone = Some(cone);
                p.rate = Some(rate);
                DipoleChoice::Precessing(dipole)
            }
            BalanceDipole::Loop { b, eps, dipole } => {
                p.b = Some(b);
                p.eps = Some(eps);
                DipoleChoice::Loop(dipole)
            }
            BalanceDipole::Dumbbell {
                charges,
                masses,
                length,
                rate,
                dipole,
            } => {
                p.charges = Some(charges);
                p.masses = Some(masses);
                p.length = Some(length);
                p.rate = Some(rate);
                p.dipole_amplitude = Some(dipole.amplitude());
                DipoleChoice::Dumbbell(dipole)
            }
        };
        BalanceConfig {
            dipole,
            parameters: p,
            times: self.times.clone(),
            format,
        }
    }
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
    /// RK4 steps per delay (the work checked before the run).
    pub steps: usize,
    /// Output times.
    pub times: Vec<Real>,
}

/// A `stability` scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StabilityScene {
    /// The row, 1 to 6.
    pub row: u8,
}

/// The table's default of a number key of `command`.
fn default_number(ctx: &Ctx, section: &str, key: &str) -> Real {
    ctx.spec(section, key).default.number().unwrap_or(0.0)
}

/// The table's default of a pair key of `command`.
fn default_pair(ctx: &Ctx, section: &str, key: &str) -> [Real; 2] {
    match ctx.spec(section, key).default {
        DefaultValue::Numbers(&[a, b]) => [a, b],
        _ => [0.0; 2],
    }
}

/// The keys of `[balance]` that belong to some trajectories only: each
/// key, where it was given, and the trajectories that take it.
fn balance_owners(raw: &RawBalance) -> [(&'static str, Option<&At>, &'static [DipoleKind]); 7] {
    use DipoleKind::{Dumbbell as D, Loop as L, Precessing as P};
    fn at<T>(k: &Key<T>) -> Option<&At> {
        k.as_ref().map(|g| &g.at)
    }
    [
        ("cone", at(&raw.cone), &[P]),
        ("rate", at(&raw.rate), &[P, D]),
        ("b", at(&raw.b), &[L]),
        ("eps", at(&raw.eps), &[L]),
        ("charges", at(&raw.charges), &[D]),
        ("masses", at(&raw.masses), &[D]),
        ("length", at(&raw.length), &[D]),
    ]
}

/// The names of the trajectories in `kinds`: `precessing or dumbbell`.
fn dipole_names(kinds: &[DipoleKind]) -> String {
    DIPOLES
        .iter()
        .filter(|c| kinds.contains(&c.value))
        .map(|c| c.name)
        .collect::<Vec<_>>()
        .join(" or ")
}

/// The trajectory of `[balance]`, from its own keys and the table's defaults.
fn balance_dipole(
    ctx: &Ctx,
    raw: &RawBalance,
    own: &At,
    which: DipoleKind,
) -> Result<BalanceDipole, Refusal> {
    let s = "balance";
    let given = |k: &str, v: &Key<Real>| -> Result<(Real, Option<At>), Refusal> {
        Ok(match number(ctx, s, k, v, false)? {
            Some((x, at)) => (x, Some(at)),
            None => (default_number(ctx, s, k), None),
        })
    };
    let pair = |k: &str, v: &Key<[Real; 2]>| -> Result<([Real; 2], Option<At>), Refusal> {
        Ok(match numbers(ctx, s, k, v)? {
            Some((x, at)) => (x, Some(at)),
            None => (default_pair(ctx, s, k), None),
        })
    };
    Ok(match which {
        DipoleKind::Precessing => {
            let ((cone, c_at), (rate, r_at)) =
                (given("cone", &raw.cone)?, given("rate", &raw.rate)?);
            let keys = [
                ("cone", "cone", c_at.as_ref()),
                ("rate", "rate", r_at.as_ref()),
            ];
            BalanceDipole::Precessing {
                cone,
                rate,
                dipole: PrecessingDipole::new(cone, rate)
                    .map_err(|e| param(ctx, e, &keys, own, s))?,
            }
        }
        DipoleKind::Loop => {
            let ((b, b_at), (eps, e_at)) = (given("b", &raw.b)?, given("eps", &raw.eps)?);
            let keys = [("b", "b", b_at.as_ref()), ("eps", "eps", e_at.as_ref())];
            BalanceDipole::Loop {
                b,
                eps,
                dipole: PlanarLoop::new(b, eps).map_err(|e| param(ctx, e, &keys, own, s))?,
            }
        }
        DipoleKind::Dumbbell => {
            let (charges, q_at) = pair("charges", &raw.charges)?;
            let (masses, m_at) = pair("masses", &raw.masses)?;
            let (length, l_at) = given("length", &raw.length)?;
            let (rate, r_at) = given("rate", &raw.rate)?;
            let keys = [
                ("q", "charges", q_at.as_ref()),
                ("m", "masses", m_at.as_ref()),
                ("length", "length", l_at.as_ref()),
                ("rate", "rate", r_at.as_ref()),
            ];
            BalanceDipole::Dumbbell {
                charges,
                masses,
                length,
                rate,
                dipole: Dumbbell::new(charges, masses, length, rate)
                    .map_err(|e| param(ctx, e, &keys, own, s))?,
            }
        }
    })
}

/// A balance question: a trajectory and its sample times.
fn balance_body(
    ctx: &Ctx,
    raw: &RawBalance,
    own: &At,
    solve: Option<(&RawSolve, At)>,
) -> Result<(BalanceScene, Option<At>), Refusal> {
    let s = "balance";
    let (which, _) = named(ctx, s, "dipole", &raw.dipole, &DIPOLES)?
        .ok_or_else(|| missing_key(ctx, own, s, "dipole"))?;
    // Keys of another trajectory are refused, not ignored.
    for (key, at, takes) in balance_owners(raw) {
        if let Some(at) = at
            && !takes.contains(&which)
        {
            let this = DIPOLES
                .iter()
                .find(|c| c.value == which)
                .map_or("", |c| c.name);
            return Err(ctx.at(
                at,
                format!(
                    "{} belongs to {}; expected only the keys of {}",
                    ctx.key(s, key),
                    ctx.set_inline("dipole", &dipole_names(takes)),
                    ctx.set_inline("dipole", this)
                ),
            ));
        }
    }
    let dipole = balance_dipole(ctx, raw, own, which)?;
    fixed_method(
        ctx,
        solve.clone(),
        s,
        "the trajectory is given in closed form",
        false,
    )?;
    let times = solve_times(ctx, solve, own, 1.0)?;
    Ok((
        BalanceScene {
            dipole,
            times: times.times,
        },
        times.at,
    ))
}

pub(super) fn balance_scene(
    ctx: &Ctx,
    raw: &RawBalance,
    own: &At,
    solve: Option<(&RawSolve, At)>,
) -> Result<Built, Refusal> {
    let (body, times_at) = balance_body(ctx, raw, own, solve)?;
    Ok(Built {
        body: Body::Balance(body),
        chosen: plan::balance_choice(),
        warnings: Vec::new(),
        times_at,
    })
}

/// An orbit question: the charge, its orbit, the tolerance and the times.
fn orbit_body(
    ctx: &Ctx,
    raw: &RawOrbit,
    own: &At,
    solve: Option<(&RawSolve, At)>,
) -> Result<(OrbitScene, Option<At>), Refusal> {
    let s = "orbit";
    let (potential, _) = named(ctx, s, "potential", &raw.potential, &POTENTIALS)?
        .ok_or_else(|| missing_key(ctx, own, s, "potential"))?;
    let (tau0, tau0_at) = number(ctx, s, "tau0", &raw.tau0, false)?
        .ok_or_else(|| missing_key(ctx, own, s, "tau0"))?;
    let force = named(ctx, s, "force", &raw.force, &FORCES)?.map_or(FORCES[0].value, |f| f.0);
    let r0 = number(ctx, s, "r0", &raw.r0, false)?;
    let e = number(ctx, s, "eccentricity", &raw.eccentricity, false)?;
    let at = |x: &Read<Real>| x.as_ref().map(|(_, at)| at.clone());
    let (r0_at, e_at) = (at(&r0), at(&e));
    let keys = [
        ("tau0", "tau0", Some(&tau0_at)),
        ("r0", "r0", r0_at.as_ref()),
        ("eccentricity", "eccentricity", e_at.as_ref()),
    ];
    let charge =
        ChargeInField::new(potential, tau0).map_err(|err| param(ctx, err, &keys, own, s))?;
    let mut config = OrbitConfig::new(
        charge,
        r0.map_or(default_number(ctx, s, "r0"), |x| x.0),
        e.map_or(default_number(ctx, s, "eccentricity"), |x| x.0),
        force,
    )
    .map_err(|err| param(ctx, err, &keys, own, s))?;
    fixed_method(ctx, solve.clone(), s, "its method follows from force", true)?;
    if let Some((sv, _)) = &solve
        && let Some((rtol, at)) = number(ctx, "solve", "rtol", &sv.rtol, true)?
    {
        config = config
            .with_rtol(rtol)
            .map_err(|e| ctx.at(&at, format!("{}: {e}", ctx.key("solve", "rtol"))))?;
    }
    let times = solve_times(ctx, solve, own, 1.0)?;
    let t_last = times.times.last().copied().unwrap_or(0.0);
    check_backward_span(&config, t_last).map_err(|e| {
        let at = times.at.clone().unwrap_or(own.clone());
        ctx.at(
            &at,
            format!(
                "{}{e}; expected {}, or {} (equal to it up to O(tau0^2))",
                ctx.section("solve"),
                times.shorter(ctx),
                ctx.set_inline("force", FORCES[0].name)
            ),
        )
    })?;
    Ok((
        OrbitScene {
            config,
            times: times.times,
        },
        times.at,
    ))
}

pub(super) fn orbit_scene(
    ctx: &Ctx,
    raw: &RawOrbit,
    own: &At,
    solve: Option<(&RawSolve, At)>,
) -> Result<Built, Refusal> {
    let (body, times_at) = orbit_body(ctx, raw, own, solve)?;
    Ok(Built {
        chosen: plan::orbit_choice(&body.config),
        body: Body::Orbit(body),
        warnings: Vec::new(),
        times_at,
    })
}

/// A shell question: the model and its times.
fn shell_body(
    ctx: &Ctx,
    raw: &RawShell,
    own: &At,
    solve: Option<(&RawSolve, At)>,
) -> Result<(ShellScene, Option<At>), Refusal> {
    let s = "shell";
    let (tau0, tau0_at) = number(ctx, s, "tau0", &raw.tau0, false)?
        .ok_or_else(|| missing_key(ctx, own, s, "tau0"))?;
    let (delay, delay_at) = number(ctx, s, "delay", &raw.delay, false)?
        .ok_or_else(|| missing_key(ctx, own, s, "delay"))?;
    let model = ShellModel::new(tau0, delay).map_err(|e| {
        let keys = [
            ("tau0", "tau0", Some(&tau0_at)),
            ("delay", "delay", Some(&delay_at)),
        ];
        param(ctx, e, &keys, own, s)
    })?;
    fixed_method(
        ctx,
        solve.clone(),
        s,
        "a delay equation is solved by RK4 on each delay interval",
        false,
    )?;
    let times = solve_times(ctx, solve, own, 1.0)?;
    let t_last = times.times.last().copied().unwrap_or(0.0);
    // The work of the method of steps, refused before it starts, advising
    // the key that gave the times (`times`, or `t_end`).
    let steps = steps_per_delay(&model, t_last).map_err(|e| {
        let at = times.at.clone().unwrap_or(own.clone());
        let advice = if e.delay_too_long {
            format!(
                "the delay is longer than the run itself: expected a shorter {}",
                ctx.key("shell", "delay")
            )
        } else {
            format!(
                "expected {} or a longer {}",
                times.shorter(ctx),
                ctx.key("shell", "delay")
            )
        };
        ctx.at(&at, format!("{}{e}; {advice}", ctx.section("solve")))
    })?;
    Ok((
        ShellScene {
            model,
            steps,
            times: times.times,
        },
        times.at,
    ))
}

pub(super) fn shell_scene(
    ctx: &Ctx,
    raw: &RawShell,
    own: &At,
    solve: Option<(&RawSolve, At)>,
) -> Result<Built, Refusal> {
    let (body, times_at) = shell_body(ctx, raw, own, solve)?;
    let mut warnings = Vec::new();
    if let Some(rate) = body.model.growth_rate() {
        warnings.push(crate::output::shell::instability_warning(&body.model, rate));
    }
    Ok(Built {
        chosen: plan::shell_choice(&body.model),
        body: Body::Shell(body),
        warnings,
        times_at,
    })
}

/// `balance`'s flags, validated like a `[balance]` scene.
pub(super) fn balance_flags(raw: &RawBalance, solve: &RawSolve) -> Result<BalanceScene, Refusal> {
    let ctx = Ctx::flags(Command::Balance);
    Ok(balance_body(&ctx, raw, &At::Flag, Some((solve, At::Flag)))?.0)
}

/// `orbit`'s flags, validated like an `[orbit]` scene.
pub(super) fn orbit_flags(raw: &RawOrbit, solve: &RawSolve) -> Result<OrbitScene, Refusal> {
    let ctx = Ctx::flags(Command::Orbit);
    Ok(orbit_body(&ctx, raw, &At::Flag, Some((solve, At::Flag)))?.0)
}

/// `shell`'s flags, validated like a `[shell]` scene.
pub(super) fn shell_flags(raw: &RawShell, solve: &RawSolve) -> Result<ShellScene, Refusal> {
    let ctx = Ctx::flags(Command::Shell);
    Ok(shell_body(&ctx, raw, &At::Flag, Some((solve, At::Flag)))?.0)
}
