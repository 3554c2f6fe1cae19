//! `shell`: the charge as a small shell (Appendix, (A.1)–(A.3)), a neutral
//! delay equation solved by the method of steps and sampled at given times.

use super::{Failure, Format, Output, write_aligned};
use crate::math::Real;
use crate::numbers::{self, table};
use crate::physics::central::abraham_lorentz_oscillator_roots;
use crate::physics::shell::ShellModel;
use crate::sim::shell::{History, ShellError, ShellSample, run_shell};
use serde::Serialize;
use std::io::{self, Write};

/// The most RK4 steps one run may take (about a second of work).
pub const MAX_STEPS: Real = 2e7;

/// A run the method of steps would take too long over: how many RK4 steps it
/// needs, and whether the delay alone is longer than the run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TooMuchWork {
    /// RK4 steps the run needs.
    pub steps: Real,
    /// RK4 steps per delay.
    pub per_delay: Real,
    /// The last output time.
    pub t_last: Real,
    /// True when the delay is longer than the run itself.
    pub delay_too_long: bool,
}

impl std::fmt::Display for TooMuchWork {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::numbers::{fmt_count, fmt_time};
        write!(
            f,
            "the run needs {} RK4 steps ({} per delay up to t = {}), more than {MAX_STEPS}",
            fmt_count(self.steps),
            fmt_count(self.per_delay),
            fmt_time(self.t_last),
            MAX_STEPS = numbers::exponent(MAX_STEPS, 0)
        )
    }
}

/// The RK4 steps per delay a run of `model` up to `t_last` takes, or why it
/// would take too many: the one check the command line and a scene make
/// before a run starts.
pub fn steps_per_delay(model: &ShellModel, t_last: Real) -> Result<usize, TooMuchWork> {
    let per_delay = crate::sim::shell::steps_per_delay_count(model.delta());
    let steps = (t_last / model.delta()).ceil().max(1.0) * per_delay;
    if steps > MAX_STEPS {
        return Err(TooMuchWork {
            steps,
            per_delay,
            t_last,
            delay_too_long: model.delta() > t_last,
        });
    }
    Ok(crate::sim::shell::default_steps_per_delay(model.delta()))
}

/// A validated `shell` request.
#[derive(Clone, Debug, PartialEq)]
pub struct ShellRequest {
    /// The model.
    pub model: ShellModel,
    /// RK4 steps per delay.
    pub steps: usize,
    /// Output times.
    pub times: Vec<Real>,
    /// Output format.
    pub format: Format,
    /// Where the request came from, for advice in its words.
    pub entry: super::Entry,
}

/// The JSON output of `shell` (the contract).
#[derive(Debug, Serialize)]
pub struct ShellOutput {
    /// τ₀.
    pub tau0: Real,
    /// δ = r₀/c.
    pub delay: Real,
    /// Bare mass m₀ = 1 − τ₀/δ.
    pub m0: Real,
    /// Electromagnetic mass m_em = τ₀/δ.
    pub m_em: Real,
    /// True when every characteristic root has Re s < 0.
    pub stable: bool,
    /// `stable`, `growing-oscillation` or `runaway`.
    pub regime: &'static str,
    /// The largest Re s of the characteristic roots (present when unstable).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub growth_rate: Option<Real>,
    /// ln(m_em/|m₀|)/δ, the rate the neutral chain tends to.
    pub chain_rate: Real,
    /// The characteristic root that continues the Abraham–Lorentz one, [re, im].
    pub root_near_al: [Real; 2],
    /// The Abraham–Lorentz physical root, [re, im].
    pub root_al: [Real; 2],
    /// RK4 steps per delay.
    pub steps_per_delay: usize,
    /// One entry per output time.
    pub samples: Vec<ShellSample>,
}

/// The one-line warning of an unstable run (the command line prints it
/// before the run, a scene among its warnings).
pub fn instability_warning(model: &ShellModel, rate: Real) -> String {
    let (m0, m_em) = (model.m0(), model.m_em());
    let why = if m0 < 0.0 {
        format!(
            "the bare mass m0 = {} is negative (delay < tau0): the Abraham-Lorentz runaway is back",
            table(m0)
        )
    } else if m0 < m_em {
        format!(
            "m0 = {} < m_em = {} (delay < 2 tau0): the neutral chain of roots grows",
            table(m0),
            table(m_em)
        )
    } else {
        format!(
            "m0 - m_em = {} is below delay^2/pi^2 = {}: the lowest chain root grows",
            table(m0 - m_em),
            table(model.stability_threshold())
        )
    };
    format!(
        "(A.1) is unstable here: {why}; the solution grows like exp({} t) (predicted growth rate)",
        table(rate)
    )
}

impl Output for ShellOutput {
    /// The table or the CSV (JSON through [`super::write`]).
    fn write_text(&self, out: &mut dyn Write, format: Format) -> io::Result<()> {
        let output = self;
        let mag = |v: [Real; 2]| v[0].hypot(v[1]);
        match format {
            Format::Json => super::write(out, self, format),
            Format::Csv => {
                writeln!(
                    out,
                    "t,x,y,vx,vy,l,j,l_minus_j,l_schott,dx_al,dy_al,l_al,j_change,flux_exact,flux_paper"
                )?;
                for s in &output.samples {
                    let row = [
                        s.t,
                        s.z[0],
                        s.z[1],
                        s.z_dot[0],
                        s.z_dot[1],
                        s.l,
                        s.j,
                        s.l_minus_j,
                        s.l_schott,
                        s.z_minus_z_al[0],
                        s.z_minus_z_al[1],
                        s.l_al,
                        s.j_change,
                        s.flux_exact,
                        s.flux_paper,
                    ];
                    let cells: Vec<String> = row.iter().map(|x| numbers::csv(*x)).collect();
                    writeln!(out, "{}", cells.join(","))?;
                }
                Ok(())
            }
            Format::Table => {
                writeln!(
                    out,
                    "# spintop shell (Eqs. (A.1)-(A.3)): tau0 = {}, delay = {}, m0 = {}, m_em = {}, m = k = 1",
                    crate::numbers::fmt_param(output.tau0),
                    crate::numbers::fmt_param(output.delay),
                    table(output.m0),
                    table(output.m_em)
                )?;
                let growth = output
                    .growth_rate
                    .map_or(String::new(), |g| format!(", growth rate {}", table(g)));
                writeln!(
                    out,
                    "# regime: {}{growth}; chain rate ln(m_em/|m0|)/delay = {}",
                    output.regime,
                    table(output.chain_rate)
                )?;
                writeln!(
                    out,
                    "# roots: near Abraham-Lorentz {} + {} i; Abraham-Lorentz {} + {} i; {} RK4 steps per delay",
                    table(output.root_near_al[0]),
                    table(output.root_near_al[1]),
                    table(output.root_al[0]),
                    table(output.root_al[1]),
                    output.steps_per_delay
                )?;
                let head = ["t", "x", "y", "L", "J", "L-J", "L_S", "|Z-Z_AL|", "L-L_AL"];
                write_aligned(out, head, 14)?;
                for s in &output.samples {
                    let row = [
                        s.t,
                        s.z[0],
                        s.z[1],
                        s.l,
                        s.j,
                        s.l_minus_j,
                        s.l_schott,
                        mag(s.z_minus_z_al),
                        s.l - s.l_al,
                    ];
                    write_aligned(out, row.iter().map(|x| table(*x)), 14)?;
                }
                if let Some(last) = output.samples.last() {
                    writeln!(
                        out,
                        "# at t = {}: J - J(0) = {}; exact flux integral {} (difference {}); paper's (A.2) {}",
                        table(last.t),
                        table(last.j_change),
                        table(last.flux_exact),
                        numbers::exponent(last.j_change - last.flux_exact, 1),
                        table(last.flux_paper)
                    )?;
                }
                Ok(())
            }
        }
    }

    fn advice(&self, _entry: super::Entry) -> String {
        "use a shell radius and times within a few decades of 1".into()
    }
}

/// Run a validated `shell` request (the instability warning is the caller's).
pub fn shell(request: &ShellRequest) -> Result<ShellOutput, Failure> {
    let model = request.model;
    let growth_rate = model.growth_rate();
    let knob = |k: super::Knob| request.entry.name(k);
    // NOTE: the root is sought before anything runs; where Newton's method
    // finds none, tau0 and the delay lie outside what the model answers
    // (bad input, not a failure at some time).
    let near = model.root_near_al().ok_or_else(|| {
        Failure::BadInput(format!(
            "Newton's method found no characteristic root of (A.1) near the Abraham-Lorentz one at tau0 = {} and delay = {}; {}",
            table(model.tau0()),
            table(model.delta()),
            if model.tau0() < 1.0 {
                // Measured: found down to tau0 = 1e-150, lost at 1e-155.
                format!(
                    "use a larger {} (the root is found down to about 1e-150)",
                    knob(super::Knob::ShellTau0)
                )
            } else {
                format!(
                    "use a smaller {} or {}",
                    knob(super::Knob::ShellTau0),
                    knob(super::Knob::Delay)
                )
            }
        ))
    })?;
    let s_al = abraham_lorentz_oscillator_roots(model.tau0()).0;
    let samples = run_shell(
        model,
        History::abraham_lorentz(model.tau0()),
        request.steps,
        &request.times,
    )
    .map_err(|e| match e {
        ShellError::Overflow { .. } => Failure::Stopped(format!(
            "{e}: (A.1) is unstable here (growth rate {}); ask for earlier {} or a delay above 2 tau0",
            growth_rate.map_or("unknown".to_string(), table),
            knob(super::Knob::Times)
        )),
        other => Failure::BadInput(other.to_string()),
    })?;
    Ok(ShellOutput {
        tau0: model.tau0(),
        delay: model.delta(),
        m0: model.m0(),
        m_em: model.m_em(),
        stable: growth_rate.is_none(),
        regime: model.regime().name(),
        growth_rate,
        chain_rate: model.chain_rate(),
        root_near_al: [near.re, near.im],
        root_al: [s_al.re, s_al.im],
        steps_per_delay: request.steps,
        samples,
    })
}
