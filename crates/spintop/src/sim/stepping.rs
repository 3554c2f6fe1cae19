//! The steppers a simulation drives: the Runge–Kutta pairs on Ω and a
//! rotation vector on SO(3) ([`OnGroup`]), and the Taylor method on Ω and a
//! unit quaternion ([`TaylorRun`]).
//!
//! Orientations are integrated on the group: the state carries a small rotation
//! vector σ with `O = O_base exp(σ̂)` and `dσ/dt = J_r⁻¹(σ) Ω`
//! (Runge–Kutta–Munthe-Kaas). σ is folded into `O_base` (a unit quaternion)
//! before it grows large, so O is only ever changed by multiplying rotations and
//! stays orthonormal to rounding.

use super::method::{Method, MethodOptions};
use super::model::FirstOrder;
use super::state::InitialState;
use crate::integrate::taylor::{
    GeneralReduced, GeneralTruncated, SymmetricReduced, SymmetricTruncated, TaylorRhs,
    WithOrientation,
};
use crate::integrate::{
    AdaptiveOptions, Dop853, Dopri5, IntegrateError, Radau5, Rhs, Rk4, Stats, Stepper, Taylor,
};
use crate::math::{Mat3, Quat, Real, State, Vec3, dexpinv_right, exp_so3};
use crate::physics::rigid_body::BodyDynamics;

/// Fold σ into the base orientation once |σ| exceeds this.
///
/// NOTE: J_r⁻¹(σ) is smooth for |σ| < 2π, but its derivatives grow with |σ|;
/// folding at 0.5 rad keeps the σ equation nearly linear, and costs one extra
/// right-hand-side evaluation (the FSAL stage is lost) every 0.5/|Ω| time units.
const FOLD_ANGLE: Real = 0.5;

/// Cap each step so that the body turns by at most this angle in it.
///
/// NOTE: J_r⁻¹(σ) is singular at |σ| = 2π. Once Ω settles (the reduced top
/// ends spinning steadily) σ grows linearly, the error estimate sees nothing,
/// and unchecked steps would carry σ through the singularity. With the fold at
/// 0.5 rad and at most 1 rad per step, |σ| stays below 1.5 rad.
pub(super) const MAX_TURN_PER_STEP: Real = 1.0;

/// One of the integrators, chosen at run time.
#[derive(Clone, Debug)]
pub(super) enum AnyStepper<const N: usize> {
    Rk4(Rk4<N>),
    Dopri5(Dopri5<N>),
    Dop853(Dop853<N>),
    Radau5(Radau5<N>),
}

impl<const N: usize> AnyStepper<N> {
    /// The stepper of `which`, or `None` when `which` is not one of the four
    /// steppers.
    pub(super) fn new(
        which: Method,
        y0: State<N>,
        options: &MethodOptions,
        scale: Real,
    ) -> Result<Option<Self>, IntegrateError> {
        // NOTE: the absolute tolerance only matters where a component passes
        // through zero; tying it to the size of Ω₀ keeps the control relative
        // for tops of any speed (and positive for a top at rest).
        Self::with_atol(
            which,
            y0,
            options,
            (1e-6 * options.rtol() * scale).max(1e-300),
        )
    }

    pub(super) fn with_atol(
        which: Method,
        y0: State<N>,
        options: &MethodOptions,
        atol: Real,
    ) -> Result<Option<Self>, IntegrateError> {
        let adaptive = || AdaptiveOptions::new(options.rtol(), atol);
        Ok(Some(match which {
            Method::Rk4 => AnyStepper::Rk4(Rk4::new(0.0, y0, options.step())?),
            Method::Dopri5 => AnyStepper::Dopri5(Dopri5::new(0.0, y0, adaptive()?)?),
            Method::Dop853 => AnyStepper::Dop853(Dop853::new(0.0, y0, adaptive()?)?),
            Method::Radau5 => AnyStepper::Radau5(Radau5::new(0.0, y0, adaptive()?)?),
            _ => return Ok(None),
        }))
    }
}

impl<const N: usize> AnyStepper<N> {
    /// Cap the adaptive step (a fixed RK4 step is the user's choice and is kept).
    pub(super) fn set_h_max(&mut self, h_max: Real) {
        match self {
            AnyStepper::Rk4(_) => {}
            AnyStepper::Dopri5(s) => s.set_h_max(h_max),
            AnyStepper::Dop853(s) => s.set_h_max(h_max),
            AnyStepper::Radau5(s) => s.set_h_max(h_max),
        }
    }
}

macro_rules! dispatch {
    ($self:expr, $s:ident => $body:expr) => {
        match $self {
            AnyStepper::Rk4($s) => $body,
            AnyStepper::Dopri5($s) => $body,
            AnyStepper::Dop853($s) => $body,
            AnyStepper::Radau5($s) => $body,
        }
    };
}

impl<const N: usize> Stepper<N> for AnyStepper<N> {
    fn t(&self) -> Real {
        dispatch!(self, s => s.t())
    }
    fn y(&self) -> &State<N> {
        dispatch!(self, s => s.y())
    }
    fn t_prev(&self) -> Real {
        dispatch!(self, s => s.t_prev())
    }
    fn last_step(&self) -> Real {
        dispatch!(self, s => s.last_step())
    }
    fn stats(&self) -> Stats {
        dispatch!(self, s => s.stats())
    }
    fn step<R: Rhs<N>>(&mut self, rhs: &R, t_stop: Real) -> Result<(), IntegrateError> {
        dispatch!(self, s => s.step(rhs, t_stop))
    }
    fn dense<R: Rhs<N>>(&mut self, rhs: &R, t: Real) -> State<N> {
        dispatch!(self, s => s.dense(rhs, t))
    }
    fn reset(&mut self, y: State<N>) {
        dispatch!(self, s => s.reset(y))
    }
}

/// Ω and σ together: `d(Ω, σ)/dt = (F(Ω), J_r⁻¹(σ) Ω)`, generic in the
/// dynamics so that the step loop is monomorphic in the model (chosen once
/// per advance, see [`Simulation::advance_to`]).
pub(super) struct CoupledRhs<D: BodyDynamics>(pub(super) D);

impl<D: BodyDynamics> Rhs<6> for CoupledRhs<D> {
    fn eval(&self, _t: Real, y: &State<6>) -> State<6> {
        let omega = y.fixed_rows::<3>(0).into_owned();
        let sigma = y.fixed_rows::<3>(3).into_owned();
        let mut out = State::<6>::zeros();
        out.fixed_rows_mut::<3>(0)
            .copy_from(&self.0.omega_dot(&omega));
        out.fixed_rows_mut::<3>(3)
            .copy_from(&dexpinv_right(&sigma, &omega));
        out
    }
}

/// σ alone, driven by a known Ω(t): `dσ/dt = J_r⁻¹(σ) Ω(t)`.
pub(super) struct OrientationRhs<F: Fn(Real) -> Vec3>(pub(super) F);

impl<F: Fn(Real) -> Vec3> Rhs<3> for OrientationRhs<F> {
    fn eval(&self, t: Real, sigma: &State<3>) -> State<3> {
        dexpinv_right(sigma, &(self.0)(t))
    }
}

/// A stepper whose state ends with σ, plus the base orientation σ is relative to.
#[derive(Clone, Debug)]
pub(super) struct OnGroup<const N: usize> {
    pub(super) stepper: AnyStepper<N>,
    pub(super) base: Quat,
    /// The most the body turns in one step, radians ([`MAX_TURN_PER_STEP`],
    /// less for a refined run).
    pub(super) max_turn: Real,
}

impl<const N: usize> OnGroup<N> {
    pub(super) fn sigma(y: &State<N>) -> Vec3 {
        y.fixed_rows::<3>(N - 3).into_owned()
    }

    // ANCHOR: fold
    /// Step once; σ is folded into the base first if it has grown, so that the
    /// base is always the one the last step's continuous output refers to.
    /// `omega` gives the body rate at a time and state, to cap the step.
    pub(super) fn step<R: Rhs<N>>(
        &mut self,
        rhs: &R,
        omega: &impl Fn(Real, &State<N>) -> Vec3,
        t_stop: Real,
    ) -> Result<(), IntegrateError> {
        let y = *self.stepper.y();
        let rate = omega(self.stepper.t(), &y).norm();
        if rate > 0.0 {
            self.stepper.set_h_max(self.max_turn / rate);
        }
        let sigma = Self::sigma(&y);
        if sigma.norm() > FOLD_ANGLE {
            self.base = Quat::new_normalize((self.base * exp_so3(&sigma)).into_inner());
            let mut folded = y;
            folded.fixed_rows_mut::<3>(N - 3).fill(0.0);
            self.stepper.reset(folded);
        }
        self.stepper.step(rhs, t_stop)
    }
    // ANCHOR_END: fold

    /// Step until `t` lies in the last step, then read the state and O there.
    pub(super) fn advance<R: Rhs<N>>(
        &mut self,
        rhs: &R,
        omega: &impl Fn(Real, &State<N>) -> Vec3,
        t: Real,
        horizon: Real,
    ) -> Result<(State<N>, Mat3), IntegrateError> {
        // NOTE: Radau5's continuous extension is only of order 3 and not
        // error-controlled, so it steps exactly onto every output time.
        let stop = if matches!(self.stepper, AnyStepper::Radau5(_)) {
            t
        } else {
            horizon
        };
        while self.stepper.t() < t {
            self.step(rhs, omega, stop)?;
        }
        let y = if t == self.stepper.t() {
            *self.stepper.y()
        } else {
            self.stepper.dense(rhs, t)
        };
        let q = self.base * exp_so3(&Self::sigma(&y));
        Ok((y, q.to_rotation_matrix().into_inner()))
    }
}

/// The Taylor method on (Ω, q), with one model's recurrences.
///
/// NOTE: a unit quaternion, not σ on the group as the Runge–Kutta methods
/// carry: q̇ = ½ q ⊗ (0, Ω) is a polynomial in (q, Ω), so the series takes it
/// as it takes Ω, and its linearity means rounding only scales q, which is
/// normalised as it is read.
// NOTE: the variants differ by their auxiliary series (a few kB); the whole
// enum is boxed once in `Engine`, so boxing each variant would buy nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub(super) enum TaylorRun {
    Truncated(Taylor<7, WithOrientation<SymmetricTruncated>>),
    Reduced(Taylor<7, WithOrientation<SymmetricReduced>>),
    General(Taylor<7, WithOrientation<GeneralTruncated>>),
    GeneralReduced(Taylor<7, WithOrientation<GeneralReduced>>),
}

macro_rules! taylor_dispatch {
    ($self:expr, $s:ident => $body:expr) => {
        match $self {
            TaylorRun::Truncated($s) => $body,
            TaylorRun::Reduced($s) => $body,
            TaylorRun::General($s) => $body,
            TaylorRun::GeneralReduced($s) => $body,
        }
    };
}

impl TaylorRun {
    /// At Ω₀ and O(0) = `base`, with the tolerances of the other integrators.
    pub(super) fn new(
        dynamics: FirstOrder,
        initial: &InitialState,
        base: &Quat,
        options: &MethodOptions,
    ) -> Result<Self, IntegrateError> {
        let mut y0 = State::<7>::zeros();
        y0.fixed_rows_mut::<3>(0).copy_from(&initial.omega);
        let q = base.quaternion();
        y0.fixed_rows_mut::<4>(3)
            .copy_from(&nalgebra::Vector4::new(q.w, q.i, q.j, q.k));
        // NOTE: relative control all the way down (the step rule floors the
        // state's size at atol/rtol). An atol tied to |Ω₀|, as the Runge–Kutta
        // pairs take, lets a top that collapses far below |Ω₀| (the truncated
        // top from |Ω⊥| = 10²⁰) be stepped past the series' radius of
        // convergence: its Ω flipped sign every step, within that atol, and
        // the run crawled at the stability limit instead of finishing.
        let atol = 1e-300;
        let opts = AdaptiveOptions::new(options.rtol(), atol)?;
        fn build<M: TaylorRhs<3>>(
            m: M,
            y0: State<7>,
            opts: AdaptiveOptions,
        ) -> Result<Taylor<7, WithOrientation<M>>, IntegrateError> {
            Taylor::new(WithOrientation(m), 0.0, y0, opts)
        }
        Ok(match dynamics {
            FirstOrder::Truncated(top) => {
                TaylorRun::Truncated(build(SymmetricTruncated(top), y0, opts)?)
            }
            FirstOrder::Reduced(top) => TaylorRun::Reduced(build(SymmetricReduced(top), y0, opts)?),
            FirstOrder::General(top) => TaylorRun::General(build(GeneralTruncated(top), y0, opts)?),
            FirstOrder::GeneralReduced(top) => {
                TaylorRun::GeneralReduced(build(GeneralReduced(top), y0, opts)?)
            }
        })
    }

    pub(super) fn stats(&self) -> Stats {
        taylor_dispatch!(self, s => s.stats())
    }

    pub(super) fn last_step(&self) -> Real {
        taylor_dispatch!(self, s => s.last_step())
    }

    /// Step until `t` lies in the last step (toward `horizon`), then read Ω
    /// and O there from the step's polynomial.
    pub(super) fn advance(
        &mut self,
        t: Real,
        horizon: Real,
    ) -> Result<(Vec3, Mat3), IntegrateError> {
        let y = taylor_dispatch!(self, s => {
            while s.t() < t {
                s.advance(horizon)?;
            }
            s.value_at(t)
        });
        let q = Quat::from_quaternion(nalgebra::Quaternion::new(y[3], y[4], y[5], y[6]));
        Ok((
            Vec3::new(y[0], y[1], y[2]),
            q.to_rotation_matrix().into_inner(),
        ))
    }
}
