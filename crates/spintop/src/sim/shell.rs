//! The shell model (A.1) solved by the method of steps, with the bookkeeping of
//! (A.2)–(A.3) along the way.
//!
//! Pure: no clock, no I/O. The two buffers are allocated once; stepping does not
//! allocate.
//!
//! The method: the time axis is cut into intervals [nδ, (n + 1)δ], each into N
//! RK4 steps of h = δ/N. On interval n the delayed acceleration Z''(t − δ) is a
//! known function, stored from interval n − 1, so (A.1) is an ordinary
//! differential equation there.
//!
//! - Each interval stores Z, Ż, Z̈ at its 2N + 1 half-grid points t₀ + jh/2.
//!   RK4 evaluates its forcing at t, t + h/2 and t + h, which one delay earlier
//!   are exactly half-grid points of the previous interval: no interpolation
//!   enters the forcing.
//! - Step ends come from RK4 (Z̈ from (A.1)); midpoints from the quintic
//!   Hermite interpolant of Z through (Z, Ż, Z̈) at the step's two ends, which is
//!   O(h⁶) accurate, two orders above RK4, and then Z̈ from (A.1).
//! - Z̈ jumps at every t = nδ (the jump is multiplied by −m_em/m₀ each time).
//!   An interval keeps the right limit at its left end and the left limit at
//!   its right end, so every step lies inside one smooth piece.
//! - The history on [−δ, 0] is given in closed form and evaluated exactly.

use crate::math::Real;
use crate::physics::central::abraham_lorentz_oscillator_roots;
use crate::physics::shell::{
    C, ShellModel, angular_momentum, bracket_j, flux_exact, flux_paper, l_minus_j,
    schott_angular_momentum,
};
use serde::Serialize;
use thiserror::Error;

/// Z, Ż, Z̈ at one time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet {
    /// Z = x + iy.
    pub z: C,
    /// Ż.
    pub z_dot: C,
    /// Z̈.
    pub z_ddot: C,
}

/// The motion on [−δ, 0], given in closed form: Z = a e^{st}.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct History {
    /// The amplitude a.
    pub amplitude: C,
    /// The exponent s.
    pub s: C,
}

impl History {
    /// The Abraham–Lorentz physical circular mode Z = e^{s_AL t}, the default:
    /// what a point charge would have done.
    pub fn abraham_lorentz(tau0: Real) -> Self {
        Self {
            amplitude: C::new(1.0, 0.0),
            s: abraham_lorentz_oscillator_roots(tau0).0,
        }
    }

    /// The mode e^{st}.
    pub fn mode(s: C) -> Self {
        Self {
            amplitude: C::new(1.0, 0.0),
            s,
        }
    }

    /// Z, Ż, Z̈ at time t.
    pub fn jet(&self, t: Real) -> Jet {
        let z = self.amplitude * (self.s * t).exp();
        Jet {
            z,
            z_dot: z * self.s,
            z_ddot: z * self.s * self.s,
        }
    }
}

/// The smallest number of RK4 steps per delay.
pub const MIN_STEPS_PER_DELAY: usize = 64;
/// The largest RK4 step, in units of the oscillator's 1/ω₀.
pub const MAX_STEP: Real = 0.002;
/// |Z| beyond which a run is stopped as having left the finite range.
pub const OVERFLOW: Real = 1e150;

/// The default number of steps per delay.
///
/// NOTE: N = 64 keeps the RK4 error of a δ = 0.1 run near 1e-12 over 20 time
/// units; for longer delays the step is capped at 0.002 so the oscillation
/// itself (period 2π) stays resolved to the same level (h ≤ 0.002: about
/// 1e-11 at t = 20).
pub fn default_steps_per_delay(delta: Real) -> usize {
    steps_per_delay_count(delta) as usize
}

/// [`default_steps_per_delay`] as a double, which does not saturate: what a
/// run's cost is checked with before it starts (a delay of 1e300 needs
/// 5e302 steps, not the 1.8e19 of the largest `usize`).
pub fn steps_per_delay_count(delta: Real) -> Real {
    (MIN_STEPS_PER_DELAY as Real).max((delta / MAX_STEP).ceil())
}

/// Why a run stopped.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ShellError {
    /// The solution left the finite range.
    #[error(
        "the solution left the finite range (|Z| > 1e150) at t = {}",
        crate::numbers::fmt_time(*t)
    )]
    Overflow {
        /// The end of the interval where it happened.
        t: Real,
    },
    /// A requested time was negative, non-finite or earlier than the last one.
    #[error(
        "output times must be finite, >= 0 and non-decreasing (got {} after {})",
        crate::numbers::fmt_value(*.0),
        crate::numbers::fmt_value(*.1)
    )]
    BadTime(Real, Real),
    /// Fewer than two steps per delay.
    #[error("at least 2 steps per delay are needed, got {0}")]
    TooFewSteps(usize),
}

/// Quintic Hermite interpolation on [0, H] through (p, p′, p″) at both ends:
/// value and first two derivatives at u = t/H.
fn hermite(a: &Jet, b: &Jet, big_h: Real, u: Real) -> Jet {
    let (u2, u3) = (u * u, u * u * u);
    let (u4, u5) = (u3 * u, u3 * u2);
    // Basis functions and their first and second u-derivatives.
    let h0 = [
        1.0 - 10.0 * u3 + 15.0 * u4 - 6.0 * u5,
        -30.0 * u2 + 60.0 * u3 - 30.0 * u4,
        -60.0 * u + 180.0 * u2 - 120.0 * u3,
    ];
    let h1 = [
        u - 6.0 * u3 + 8.0 * u4 - 3.0 * u5,
        1.0 - 18.0 * u2 + 32.0 * u3 - 15.0 * u4,
        -36.0 * u + 96.0 * u2 - 60.0 * u3,
    ];
    let h2 = [
        0.5 * (u2 - 3.0 * u3 + 3.0 * u4 - u5),
        0.5 * (2.0 * u - 9.0 * u2 + 12.0 * u3 - 5.0 * u4),
        0.5 * (2.0 - 18.0 * u + 36.0 * u2 - 20.0 * u3),
    ];
    let h3 = [
        0.5 * (u3 - 2.0 * u4 + u5),
        0.5 * (3.0 * u2 - 8.0 * u3 + 5.0 * u4),
        0.5 * (6.0 * u - 24.0 * u2 + 20.0 * u3),
    ];
    let h4 = [
        -4.0 * u3 + 7.0 * u4 - 3.0 * u5,
        -12.0 * u2 + 28.0 * u3 - 15.0 * u4,
        -24.0 * u + 84.0 * u2 - 60.0 * u3,
    ];
    let h5 = [
        10.0 * u3 - 15.0 * u4 + 6.0 * u5,
        30.0 * u2 - 60.0 * u3 + 30.0 * u4,
        60.0 * u - 180.0 * u2 + 120.0 * u3,
    ];
    let hh = big_h * big_h;
    let p = |k: usize| {
        a.z * h0[k]
            + a.z_dot * (big_h * h1[k])
            + a.z_ddot * (hh * h2[k])
            + b.z * h5[k]
            + b.z_dot * (big_h * h4[k])
            + b.z_ddot * (hh * h3[k])
    };
    Jet {
        z: p(0),
        z_dot: p(1) / big_h,
        z_ddot: p(2) / hh,
    }
}

/// The method of steps for (A.1), one interval of length δ at a time.
#[derive(Clone, Debug)]
pub struct ShellSolver {
    model: ShellModel,
    history: History,
    steps: usize,
    h: Real,
    /// Index n of the current interval [nδ, (n + 1)δ].
    interval: usize,
    /// Interval n − 1 (the history for n = 0), half-grid points.
    prev: Vec<Jet>,
    /// Interval n, half-grid points.
    cur: Vec<Jet>,
    /// ∫₀^{t} of the exact flux (A.2) at the step ends of interval n.
    flux_exact: Vec<Real>,
    /// ∫₀^{t} of the paper's flux (A.2) at the step ends of interval n.
    flux_paper: Vec<Real>,
    /// J(0).
    j0: Real,
}

/// One observed time. Serialises to the `shell` JSON contract.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ShellSample {
    /// Time.
    pub t: Real,
    /// Z = x + iy, [re, im].
    pub z: [Real; 2],
    /// Ż, [re, im].
    pub z_dot: [Real; 2],
    /// L = Im(Z̄ Ż).
    pub l: Real,
    /// J = m₀ l(t) + m_em l(t − δ), the bracket of (A.2).
    pub j: Real,
    /// L − J = m_em (l(t) − l(t − δ)), which (A.3) sends to τ₀ L̇.
    pub l_minus_j: Real,
    /// Z − Z_AL with Z_AL = e^{s_AL t}, the Abraham–Lorentz physical mode, [re, im].
    pub z_minus_z_al: [Real; 2],
    /// L_AL = Im(s_AL) e^{2 Re(s_AL) t}.
    pub l_al: Real,
    /// The Schott angular momentum τ₀ L̇ = τ₀ Im(Z̄ Z̈), the limit of L − J.
    pub l_schott: Real,
    /// J(t) − J(0).
    pub j_change: Real,
    /// ∫₀ᵗ m_em Im(conj(Z_ret − Z) Z̈_ret) dt, which equals J(t) − J(0).
    pub flux_exact: Real,
    /// ∫₀ᵗ −τ₀ Im(conj(Ż_ret) Z̈_ret) dt, the paper's right-hand side of (A.2).
    pub flux_paper: Real,
}

impl ShellSolver {
    /// Start from the history on [−δ, 0] and solve the first interval.
    pub fn new(model: ShellModel, history: History, steps: usize) -> Result<Self, ShellError> {
        if steps < 2 {
            return Err(ShellError::TooFewSteps(steps));
        }
        let delta = model.delta();
        let h = delta / steps as Real;
        let prev: Vec<Jet> = (0..=2 * steps)
            .map(|j| history.jet(-delta + j as Real * 0.5 * h))
            .collect();
        let start = history.jet(0.0);
        let start_ret = history.jet(-delta);
        let j0 = bracket_j(
            &model,
            angular_momentum(start.z, start.z_dot),
            angular_momentum(start_ret.z, start_ret.z_dot),
        );
        let mut solver = Self {
            model,
            history,
            steps,
            h,
            interval: 0,
            prev,
            cur: vec![start; 2 * steps + 1],
            flux_exact: vec![0.0; steps + 1],
            flux_paper: vec![0.0; steps + 1],
            j0,
        };
        solver.solve_interval(start.z, start.z_dot, 0.0, 0.0)?;
        Ok(solver)
    }

    /// The model.
    pub fn model(&self) -> &ShellModel {
        &self.model
    }

    /// The history.
    pub fn history(&self) -> &History {
        &self.history
    }

    /// RK4 steps per delay.
    pub fn steps_per_delay(&self) -> usize {
        self.steps
    }

    /// Index n of the current interval [nδ, (n + 1)δ].
    pub fn interval(&self) -> usize {
        self.interval
    }

    /// The start nδ of the current interval.
    pub fn interval_start(&self) -> Real {
        self.interval as Real * self.model.delta()
    }

    /// The jump Z̈(nδ⁺) − Z̈(nδ⁻) at the start of the current interval.
    pub fn jump(&self) -> C {
        self.cur[0].z_ddot - self.prev[2 * self.steps].z_ddot
    }

    /// Z, Ż, Z̈ at the half-grid points of the current interval (Z̈ at its ends
    /// is the one-sided limit from inside).
    pub fn current(&self) -> &[Jet] {
        &self.cur
    }

    // ANCHOR: method_of_steps
    /// Fill `cur` for the interval that starts at (z, ż), with `prev` holding
    /// the interval before it.
    fn solve_interval(
        &mut self,
        z: C,
        z_dot: C,
        flux_exact0: Real,
        flux_paper0: Real,
    ) -> Result<(), ShellError> {
        let (m, h, n) = (self.model, self.h, self.steps);
        let acc = |z: C, ret: &Jet| m.acceleration(z, ret.z_ddot);
        let prev = &self.prev;
        let cur = &mut self.cur;
        cur[0] = Jet {
            z,
            z_dot,
            z_ddot: acc(z, &prev[0]),
        };
        self.flux_exact[0] = flux_exact0;
        self.flux_paper[0] = flux_paper0;
        for i in 0..n {
            let (r0, r1, r2) = (&prev[2 * i], &prev[2 * i + 1], &prev[2 * i + 2]);
            let (z0, v0) = (cur[2 * i].z, cur[2 * i].z_dot);
            // Classical RK4 on (Z, Ż); the forcing at t, t + h/2, t + h is
            // Z̈(t − δ) at three stored half-grid points.
            let (k1z, k1v) = (v0, acc(z0, r0));
            let (k2z, k2v) = (v0 + k1v * (0.5 * h), acc(z0 + k1z * (0.5 * h), r1));
            let (k3z, k3v) = (v0 + k2v * (0.5 * h), acc(z0 + k2z * (0.5 * h), r1));
            let (k4z, k4v) = (v0 + k3v * h, acc(z0 + k3z * h, r2));
            let z1 = z0 + (k1z + k2z * 2.0 + k3z * 2.0 + k4z) * (h / 6.0);
            let v1 = v0 + (k1v + k2v * 2.0 + k3v * 2.0 + k4v) * (h / 6.0);
            cur[2 * i + 2] = Jet {
                z: z1,
                z_dot: v1,
                z_ddot: acc(z1, r2),
            };
            let mid = hermite(&cur[2 * i], &cur[2 * i + 2], h, 0.5);
            cur[2 * i + 1] = Jet {
                z_ddot: acc(mid.z, r1),
                ..mid
            };
            // Simpson's rule for the two fluxes of (A.2) over this step.
            let fe = |k: usize| flux_exact(&m, cur[k].z, prev[k].z, prev[k].z_ddot);
            let fp = |k: usize| flux_paper(&m, prev[k].z_dot, prev[k].z_ddot);
            let simpson = |f: &dyn Fn(usize) -> Real| {
                h / 6.0 * (f(2 * i) + 4.0 * f(2 * i + 1) + f(2 * i + 2))
            };
            self.flux_exact[i + 1] = self.flux_exact[i] + simpson(&fe);
            self.flux_paper[i + 1] = self.flux_paper[i] + simpson(&fp);
        }
        let end = &cur[2 * n];
        if !(end.z.norm() <= OVERFLOW && end.z_dot.norm().is_finite()) {
            return Err(ShellError::Overflow {
                t: (self.interval + 1) as Real * m.delta(),
            });
        }
        Ok(())
    }

    /// Move on to the next interval.
    pub fn advance(&mut self) -> Result<(), ShellError> {
        std::mem::swap(&mut self.prev, &mut self.cur);
        self.interval += 1;
        let end = self.prev[2 * self.steps];
        let (fe, fp) = (self.flux_exact[self.steps], self.flux_paper[self.steps]);
        self.solve_interval(end.z, end.z_dot, fe, fp)
    }
    // ANCHOR_END: method_of_steps

    /// Z, Ż, Z̈ at time t inside interval `start` .. `start + δ` stored in `grid`,
    /// by quintic Hermite interpolation between half-grid points.
    fn interpolate(&self, grid: &[Jet], start: Real, t: Real) -> Jet {
        let half = 0.5 * self.h;
        let x = ((t - start) / half).clamp(0.0, (2 * self.steps) as Real);
        let j = (x.floor() as usize).min(2 * self.steps - 1);
        hermite(&grid[j], &grid[j + 1], half, x - j as Real)
    }

    /// Z, Ż, Z̈ at t in the current interval [nδ, (n + 1)δ].
    pub fn jet_at(&self, t: Real) -> Jet {
        self.interpolate(&self.cur, self.interval_start(), t)
    }

    /// Z, Ż, Z̈ at t − δ, for t in the current interval.
    pub fn retarded_jet_at(&self, t: Real) -> Jet {
        let delta = self.model.delta();
        self.interpolate(&self.prev, self.interval_start() - delta, t - delta)
    }

    /// The fluxes' integrands at t in the current interval.
    fn fluxes_at(&self, t: Real) -> (Real, Real) {
        let (now, ret) = (self.jet_at(t), self.retarded_jet_at(t));
        (
            flux_exact(&self.model, now.z, ret.z, ret.z_ddot),
            flux_paper(&self.model, ret.z_dot, ret.z_ddot),
        )
    }

    /// Advance until the current interval holds t, then observe it.
    pub fn sample(&mut self, t: Real) -> Result<ShellSample, ShellError> {
        let delta = self.model.delta();
        while t > (self.interval + 1) as Real * delta {
            self.advance()?;
        }
        let start = self.interval_start();
        let now = self.jet_at(t);
        let ret = self.retarded_jet_at(t);
        let z_ddot = self.model.acceleration(now.z, ret.z_ddot);
        let l = angular_momentum(now.z, now.z_dot);
        let l_ret = angular_momentum(ret.z, ret.z_dot);
        let j = bracket_j(&self.model, l, l_ret);
        // The flux integrals: stored up to the step end before t, then Simpson
        // over the remaining part of the step.
        let i = (((t - start) / self.h).floor() as usize).min(self.steps - 1);
        let ti = start + i as Real * self.h;
        let (a, b, c) = (
            self.fluxes_at(ti),
            self.fluxes_at(0.5 * (ti + t)),
            self.fluxes_at(t),
        );
        let w = (t - ti) / 6.0;
        let flux_e = self.flux_exact[i] + w * (a.0 + 4.0 * b.0 + c.0);
        let flux_p = self.flux_paper[i] + w * (a.1 + 4.0 * b.1 + c.1);
        let s_al = abraham_lorentz_oscillator_roots(self.model.tau0()).0;
        let z_al = (s_al * t).exp();
        Ok(ShellSample {
            t,
            z: [now.z.re, now.z.im],
            z_dot: [now.z_dot.re, now.z_dot.im],
            l,
            j,
            l_minus_j: l_minus_j(&self.model, l, l_ret),
            z_minus_z_al: [now.z.re - z_al.re, now.z.im - z_al.im],
            l_al: s_al.im * (2.0 * s_al.re * t).exp(),
            l_schott: schott_angular_momentum(&self.model, now.z, z_ddot),
            j_change: j - self.j0,
            flux_exact: flux_e,
            flux_paper: flux_p,
        })
    }
}

/// Solve (A.1) from `history` and sample it at `times` (finite, ≥ 0,
/// non-decreasing), with `steps` RK4 steps per delay.
pub fn run_shell(
    model: ShellModel,
    history: History,
    steps: usize,
    times: &[Real],
) -> Result<Vec<ShellSample>, ShellError> {
    let mut last = 0.0;
    for &t in times {
        if !(t.is_finite() && t >= last) {
            return Err(ShellError::BadTime(t, last));
        }
        last = t;
    }
    let mut solver = ShellSolver::new(model, history, steps)?;
    times.iter().map(|&t| solver.sample(t)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interpolant reproduces a quintic exactly, with its derivatives.
    #[test]
    fn quintic_hermite_is_exact_for_quintics() {
        let p = |t: Real| C::new(1.0 + t - 2.0 * t.powi(3) + 0.5 * t.powi(5), t.powi(4));
        let dp = |t: Real| C::new(1.0 - 6.0 * t * t + 2.5 * t.powi(4), 4.0 * t.powi(3));
        let ddp = |t: Real| C::new(-12.0 * t + 10.0 * t.powi(3), 12.0 * t * t);
        let jet = |t: Real| Jet {
            z: p(t),
            z_dot: dp(t),
            z_ddot: ddp(t),
        };
        let (a, b) = (0.3, 1.1);
        for u in [0.0, 0.2, 0.5, 0.9, 1.0] {
            let got = hermite(&jet(a), &jet(b), b - a, u);
            let t = a + u * (b - a);
            assert!((got.z - p(t)).norm() < 1e-13);
            assert!((got.z_dot - dp(t)).norm() < 1e-12);
            assert!((got.z_ddot - ddp(t)).norm() < 1e-11);
        }
    }
}
