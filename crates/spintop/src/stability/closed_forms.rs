//! Row 5: the closed forms of Section 4 evaluated as printed lose every digit
//! or overflow at realistic τ; the rewritten forms spintop uses do not.
//!
//! Three cases, each checked against a third, independent way of writing the
//! same number (not against the careful form itself):
//!
//! | case | printed form | what breaks | independent reference |
//! |---|---|---|---|
//! | τΩ⊥₀²t = 1e-20 | ϑ = (R − 1)/(τΩ⊥₀²), (4.9) | R rounds to 1: ϑ = 0 | the series ϑ = t(1 − x/2 + x²/2 − …), x = τΩ⊥₀²t |
//! | 2t/σ = 1000 | Φ of (4.16) | β e^{2t/σ} overflows: Φ = 0 | Φ = e^{−t/σ} √((β − 1)/(β − e^{−2t/σ})) |
//! | slow spin, β − 1 ≈ 1.5e-7 | Φ of (4.16) | β − 1 keeps ~9 digits | Φ = k/√(k² e^s + Ω⊥₀² expm1(s)), s = 2t/σ |

use super::{Outcome, Row, RowError};
use crate::math::{Real, Vec3};
use crate::physics::symmetric_top::{SymmetricTop, reduced_amplitude, truncated_clock};

// ANCHOR: printed
/// ϑ as the paper prints it.
///
/// Paper: Eq. (4.9) (as printed).
///
/// ```text
/// ϑ = (R − 1)/(τΩ⊥₀²),  R = √(1 + 2τΩ⊥₀²t)
/// ```
pub fn printed_vartheta(top: &SymmetricTop, omega_perp0: Real, t: Real) -> Real {
    let a = top.tau() * omega_perp0 * omega_perp0;
    ((1.0 + 2.0 * a * t).sqrt() - 1.0) / a
}

/// Φ as the paper prints it.
///
/// Paper: Eq. (4.16) (as printed).
///
/// ```text
/// Φ = √((β − 1)/(β e^{2t/σ} − 1)),  β = 1 + (I₃Ω₃)²/(I₁Ω⊥₀)²,  σ = I₁²/(I₃²Ω₃²τ)
/// ```
pub fn printed_amplitude(top: &SymmetricTop, omega0: &Vec3, t: Real) -> Real {
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let k = top.ratio() * omega0.z;
    let beta = 1.0 + k * k / u0;
    let sigma = 1.0 / (k * k * top.tau());
    ((beta - 1.0) / (beta * (2.0 * t / sigma).exp() - 1.0)).sqrt()
}
// ANCHOR_END: printed

/// One closed-form case: the printed value, the careful one, and the
/// independent reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Case {
    /// The quantity ("theta(t)", "Phi(t)").
    pub quantity: &'static str,
    /// Where it is evaluated, e.g. "tau W^2 t = 1e-20".
    pub regime: &'static str,
    /// The printed form's value.
    pub printed: Real,
    /// spintop's value.
    pub careful: Real,
    /// The independent reference.
    pub reference: Real,
}

impl Case {
    /// Relative error of the printed form (1 when it returns 0).
    pub fn printed_error(&self) -> Real {
        rel(self.printed, self.reference)
    }
    /// Relative error of the careful form.
    pub fn careful_error(&self) -> Real {
        rel(self.careful, self.reference)
    }
}

fn rel(x: Real, reference: Real) -> Real {
    if x.is_finite() {
        ((x - reference) / reference).abs()
    } else {
        Real::INFINITY
    }
}

/// The measurement of row 5.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// The three cases.
    pub cases: Vec<Case>,
}

/// Run the experiment of row 5.
pub fn measure() -> Result<Measurement, RowError> {
    let top = SymmetricTop::figure();

    // (4.9) at x = τΩ⊥₀²t = 1e-20: the series t(1 − x/2 + x²/2) is exact to
    // rounding there.
    let w_perp: Real = 0.1;
    let x = 1e-20;
    let t = x / (top.tau() * w_perp * w_perp);
    let vartheta = Case {
        quantity: "theta (4.9)",
        regime: "tau W^2 t = 1e-20",
        printed: printed_vartheta(&top, w_perp, t),
        careful: truncated_clock(&top, w_perp, t).vartheta,
        reference: t * (1.0 - 0.5 * x + 0.5 * x * x),
    };

    // (4.16) at s = 2t/σ = 1000.
    let omega0 = Vec3::new(0.03, 0.1, 0.2);
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let k = top.ratio() * omega0.z;
    let s = 1000.0;
    let t = s / (2.0 * top.tau() * k * k);
    let beta = 1.0 + k * k / u0;
    let overflow = Case {
        quantity: "Phi (4.16)",
        regime: "2t/sigma = 1000",
        printed: printed_amplitude(&top, &omega0, t),
        careful: reduced_amplitude(&top, &omega0, t),
        reference: (-0.5 * s).exp() * ((beta - 1.0) / (beta - (-s).exp())).sqrt(),
    };

    // (4.16) with a slow spin: β − 1 = k²/Ω⊥₀² ≈ 1.5e-7, τΩ⊥₀²t = 1e6.
    let omega0 = Vec3::new(0.03, 0.1, 1e-4);
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let k = top.ratio() * omega0.z;
    let t = 1e6 / (top.tau() * u0);
    let s = 2.0 * top.tau() * k * k * t;
    let slow = Case {
        quantity: "Phi (4.16)",
        regime: "slow spin, beta - 1 = 1.5e-7",
        printed: printed_amplitude(&top, &omega0, t),
        careful: reduced_amplitude(&top, &omega0, t),
        reference: k / (k * k * s.exp() + u0 * s.exp_m1()).sqrt(),
    };
    Ok(Measurement {
        cases: vec![vartheta, overflow, slow],
    })
}

impl Measurement {
    /// The printable row.
    pub fn row(&self) -> Row {
        let show = |c: &Case, x: Real, e: Real, ok: bool| Outcome {
            method: format!("{} at {}", c.quantity, c.regime),
            ok,
            result: format!("value {x:.6e}, relative error {e:.1e}"),
        };
        Row {
            number: 5,
            problem: "Closed forms (4.9), (4.16) at realistic tau".into(),
            naive: self
                .cases
                .iter()
                .map(|c| {
                    let e = c.printed_error();
                    show(c, c.printed, e, e < 1e-12)
                })
                .collect(),
            fix: self
                .cases
                .iter()
                .map(|c| {
                    let e = c.careful_error();
                    show(c, c.careful, e, e < 1e-12)
                })
                .collect(),
            notes: vec![
                "naive = the form the paper prints; fix = spintop's rewritten form".into(),
                "reference = a third, independent rewriting (series, or factored exponentials)"
                    .into(),
            ],
        }
    }
}
