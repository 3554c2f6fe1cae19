//! Row 6: the appendix's delay equation (A.1) with a bare mass below the
//! electromagnetic one (m₀ < m_em, a shell smaller than 2τ₀c) grows without
//! bound; spintop finds out from the characteristic roots before the first
//! step, and predicts the growth rate the solver then sees.
//!
//! The experiment: τ₀ = 0.06, δ = 0.1 (m_em = 0.6 > m₀ = 0.4), started on the
//! Abraham–Lorentz physical motion. The method of steps itself is faithful:
//! it reproduces exact modes to 1e-10 (tests/physics/shell_model.rs); what fails is
//! the model, whose neutral chain of roots sits in the right half plane. The
//! deviation from the Abraham–Lorentz motion is measured by its peak over a
//! window of one time unit at t = 2 and at t = 6. For contrast, τ₀ = 0.001
//! (m₀ = 0.99) stays on the Abraham–Lorentz motion.

use super::{Outcome, Row, RowError};
use crate::math::Real;
use crate::physics::shell::{Regime, ShellModel};
use crate::sim::shell::{History, default_steps_per_delay, run_shell};

/// The measurement of row 6.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// τ₀ and δ of the unstable shell.
    pub tau0: Real,
    /// δ.
    pub delta: Real,
    /// m₀ and m_em.
    pub m0: Real,
    /// m_em.
    pub m_em: Real,
    /// The regime decided from the roots, before any step.
    pub regime: Regime,
    /// The predicted growth rate, the largest Re s over the roots.
    pub predicted_rate: Real,
    /// The asymptotic chain rate ln(m_em/m₀)/δ.
    pub chain_rate: Real,
    /// The growth rate the method of steps shows.
    pub measured_rate: Real,
    /// Peak |Z − Z_AL| in the last window of the unstable run.
    pub unstable_peak: Real,
    /// Peak |Z − Z_AL| over the same window for the stable shell (τ₀ = 0.001).
    pub stable_peak: Real,
    /// Regime of the stable shell.
    pub stable_regime: Regime,
}

/// Peak of |Z − Z_AL| over [a, a + 1].
fn peak(model: ShellModel, a: Real) -> Result<Real, RowError> {
    let times: Vec<Real> = (0..=400).map(|k| a + k as Real / 400.0).collect();
    let samples = run_shell(
        model,
        History::abraham_lorentz(model.tau0()),
        default_steps_per_delay(model.delta()),
        &times,
    )
    .map_err(|e| RowError::new(6, e))?;
    Ok(samples
        .iter()
        .map(|s| s.z_minus_z_al[0].hypot(s.z_minus_z_al[1]))
        .fold(0.0, Real::max))
}

/// Run the experiment of row 6.
pub fn measure() -> Result<Measurement, RowError> {
    let (tau0, delta) = (0.06, 0.1);
    let model = ShellModel::new(tau0, delta).map_err(|e| RowError::new(6, e))?;
    let predicted_rate = model
        .growth_rate()
        .ok_or_else(|| RowError::new(6, "the unstable shell was judged stable"))?;
    let (t1, t2) = (2.0, 6.0);
    let p1 = peak(model, t1)?;
    let p2 = peak(model, t2)?;
    let stable = ShellModel::new(1e-3, delta).map_err(|e| RowError::new(6, e))?;
    Ok(Measurement {
        tau0,
        delta,
        m0: model.m0(),
        m_em: model.m_em(),
        regime: model.regime(),
        predicted_rate,
        chain_rate: model.chain_rate(),
        measured_rate: (p2 / p1).ln() / (t2 - t1),
        unstable_peak: p2,
        stable_peak: peak(stable, t2)?,
        stable_regime: stable.regime(),
    })
}

impl Measurement {
    /// The printable row.
    pub fn row(&self) -> Row {
        let agree = (self.measured_rate / self.predicted_rate - 1.0).abs();
        Row {
            number: 6,
            problem: format!(
                "Delay equation (A.1), m0 = {} < m_em = {}",
                self.m0, self.m_em
            ),
            naive: vec![Outcome {
                method: "method of steps, run blind".into(),
                ok: self.measured_rate <= 0.0,
                result: format!(
                    "deviation from Abraham-Lorentz grows at {:.4}/time, |Z - Z_AL| = {:.2e} by t = 7",
                    self.measured_rate, self.unstable_peak
                ),
            }],
            fix: vec![
                Outcome {
                    method: "characteristic roots, before the first step".into(),
                    ok: self.regime != Regime::Stable && agree < 0.05,
                    result: format!(
                        "regime '{}', predicted rate {:.4} (measured within {:.1}%); spintop shell warns before any output",
                        self.regime.name(),
                        self.predicted_rate,
                        100.0 * agree
                    ),
                },
                Outcome {
                    method: "a larger shell, m0 > m_em (tau0 = 0.001)".into(),
                    ok: self.stable_regime == Regime::Stable && self.stable_peak < 1e-2,
                    result: format!(
                        "regime '{}', |Z - Z_AL| <= {:.1e} over [6, 7]",
                        self.stable_regime.name(),
                        self.stable_peak
                    ),
                },
            ],
            notes: vec![format!(
                "chain asymptote ln(m_em/m0)/delay = {:.4}; the lowest chain root grows a little faster",
                self.chain_rate
            )],
        }
    }
}
