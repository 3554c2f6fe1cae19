//! The scenes of the other kinds, one per command beside `simulate`: a dipole
//! trajectory and its balance laws (`balance`), a charge in a central field
//! (`orbit`), the charge as a small shell (`shell`) and a row of the
//! stability suite (`stability`).

use super::format::{RawBalance, RawOrbit, RawShell, RawSolve};
use super::keys::{At, Ctx, choice, finite_array, fixed_method, missing, num, param, solve_times};
use super::{Body, Built, SceneError, plan};
use crate::math::Real;
use crate::physics::balance::{Dumbbell, PlanarLoop, PrecessingDipole};
use crate::physics::central::{ChargeInField, Potential};
use crate::physics::shell::ShellModel;
use crate::sim::orbit::{Force, OrbitConfig};
use std::ops::Range;

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

pub(super) fn balance_scene(
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

pub(super) fn orbit_scene(
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
        && let Some((rtol, span)) = num(ctx, "solve", "rtol", &sv.rtol, "a relative tolerance")?
    {
        config = config
            .with_rtol(rtol)
            .map_err(|e| ctx.at(&span, format!("[solve] {e}")))?;
    }
    let (times, times_span) = solve_times(ctx, solve, own, None, false, 1.0)?;
    Ok(Built {
        body: Body::Orbit(OrbitScene { config, times }),
        chosen: plan::orbit_choice(&config),
        warnings: Vec::new(),
        times_line: times_span,
    })
}

pub(super) fn shell_scene(
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
