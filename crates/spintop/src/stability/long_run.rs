//! Row 4 of the stability suite: the free asymmetric top (τ = 0) over long
//! times.
//!
//! With no radiation the top keeps its energy E = ½ L·I⁻¹L, its |L| and its
//! lab-frame angular momentum O L (paper §3, (3.1)–(3.2) with zero torque).
//! General-purpose explicit methods keep none of them: RK4 at a fixed step and
//! Dormand–Prince 5(4) at a fixed tolerance make a small systematic error per
//! step, so the energy and |L| errors grow linearly in t (Hairer–Lubich–Wanner,
//! *Geometric Numerical Integration*, Sec. I.2 and IX.8). Splitting the kinetic
//! energy into three exact axis rotations (Strang, Yoshida-4; see
//! [`crate::integrate::splitting`]) gives a symplectic map that keeps |L| and
//! O L to rounding and the energy error bounded at every time.
//!
//! The experiment: I = (1, 2, 3), L₀ = (1, 1, 0.9) in the body frame (Ω₀ =
//! (1, ½, 0.3); |L|²/2E = 1.59 lies between I₁ and I₂, well away from both the
//! axis and the separatrix |L|²/2E = I₂, so the top tumbles), the same step
//! h = 0.05 for RK4 and the splittings and rtol = 1e-8 for DP5. The errors are
//! the largest relative deviations over [0, t] at t = 10², 10³, 10⁴, sampled
//! after every step; a slope is the least-squares slope of log error against
//! log t.

use super::{Outcome, Row, RowError};
use crate::integrate::splitting::Composition;
use crate::integrate::{AdaptiveOptions, Dop853, Dopri5, Rhs, Rk4, Stats, Stepper};
use crate::math::{Mat3, Real, State, Vec3, hat, rot_x, rot_z};
use crate::physics::free_top::{FreeRigidBody, RigidBodyState};
use crate::sim::Method;
use crate::sim::split::RigidBodySplitting;

/// The principal moments of the experiment.
pub const INERTIA: [Real; 3] = [1.0, 2.0, 3.0];
/// L₀ in the body frame.
pub const L_BODY0: [Real; 3] = [1.0, 1.0, 0.9];
/// The fixed step of RK4 and of both splittings.
pub const STEP: Real = 0.05;
/// The relative tolerance of DP5.
pub const DOPRI5_RTOL: Real = 1e-8;
/// The times at which the errors are read.
pub const TIMES: [Real; 3] = [1e2, 1e3, 1e4];
/// A method "keeps" the energy when its error at the last time is at most
/// this factor times its error at the first time (linear growth gives 100).
pub const BOUNDED_RATIO: Real = 3.0;
/// A conserved quantity is "kept to rounding" when its relative error is at
/// most this many machine epsilons times √steps (a random walk of roundings).
pub const ROUNDING_EPS_PER_SQRT_STEP: Real = 8.0;
/// The time span and the two steps of the order measurement.
pub const ORDER_SPAN: Real = 10.0;
/// The coarser step of the order measurement (the finer is half of it).
pub const ORDER_STEP: Real = 0.1;

/// The method of the row as a reader would name it, with its step or
/// tolerance: RK4, DP5 and the two splittings ([`Method::Strang`],
/// [`Method::Yoshida4`]).
pub fn label(method: Method) -> String {
    match method {
        Method::Rk4 => format!("RK4, h = {STEP}"),
        Method::Dopri5 => format!("DP5, rtol = {DOPRI5_RTOL:e}"),
        Method::Strang => format!("Strang splitting, h = {STEP}"),
        Method::Yoshida4 => format!("Yoshida-4 splitting, h = {STEP}"),
        other => other.label().to_string(),
    }
}

/// How one method's errors evolved.
#[derive(Clone, Debug, PartialEq)]
pub struct Drift {
    /// The method.
    pub method: Method,
    /// max over [0, t] of |E − E₀|/E₀, at each of [`TIMES`].
    pub energy_error: [Real; 3],
    /// max over [0, t] of ||L| − |L₀||/|L₀|, at each of [`TIMES`].
    pub l_norm_error: [Real; 3],
    /// max over [0, t] of |O L − L_lab₀|/|L₀|, at each of [`TIMES`].
    pub l_lab_error: [Real; 3],
    /// Log-log slope of `energy_error` against t (1: linear growth, 0: bounded).
    pub energy_slope: Real,
    /// Log-log slope of `l_norm_error`.
    pub l_norm_slope: Real,
    /// Log-log slope of `l_lab_error`.
    pub l_lab_slope: Real,
    /// Work up to the last time: right-hand-side (or sub-flow) evaluations and steps.
    pub stats: Stats,
}

impl Drift {
    /// The rounding bound on |L| and lab-L errors for this method's step count.
    pub fn rounding_bound(&self) -> Real {
        ROUNDING_EPS_PER_SQRT_STEP * Real::EPSILON * (self.stats.steps.max(1) as Real).sqrt()
    }

    /// Energy error at the last time over that at the first.
    pub fn energy_ratio(&self) -> Real {
        self.energy_error[2] / self.energy_error[0]
    }

    /// True when the energy error stays bounded and |L| and the lab L are kept
    /// to rounding: what a free top demands of a long run.
    pub fn conserves(&self) -> bool {
        let bound = self.rounding_bound();
        self.energy_ratio() <= BOUNDED_RATIO
            && self.l_norm_error[2] <= bound
            && self.l_lab_error[2] <= bound
    }
}

/// The measurement of row 4.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// RK4 at the fixed step.
    pub rk4: Drift,
    /// DP5 at the fixed tolerance.
    pub dopri5: Drift,
    /// The Strang splitting.
    pub strang: Drift,
    /// Yoshida-4.
    pub yoshida4: Drift,
    /// The Strang splitting's observed order, log₂ of the error ratio at steps
    /// [`ORDER_STEP`] and half of it over [`ORDER_SPAN`], against DOP853 at rtol 1e-13.
    pub strang_order: Real,
    /// Yoshida-4's observed order, measured the same way.
    pub yoshida4_order: Real,
}

/// The free top: `(L, O)` as 12 numbers, L first, then O column by column.
#[derive(Clone, Copy, Debug)]
struct FreeTopRhs(FreeRigidBody);

fn pack(state: &RigidBodyState) -> State<12> {
    let mut y = State::<12>::zeros();
    y.fixed_rows_mut::<3>(0).copy_from(&state.l_body);
    y.fixed_rows_mut::<9>(3)
        .copy_from_slice(state.rotation.as_slice());
    y
}

fn unpack(y: &State<12>) -> RigidBodyState {
    RigidBodyState {
        l_body: y.fixed_rows::<3>(0).into_owned(),
        rotation: Mat3::from_column_slice(&y.as_slice()[3..12]),
    }
}

impl Rhs<12> for FreeTopRhs {
    /// L̇ = L × Ω and Ȯ = O Ω̂ with Ω = I⁻¹L (torque-free (3.1)–(3.2)).
    fn eval(&self, _t: Real, y: &State<12>) -> State<12> {
        let s = unpack(y);
        let omega = self.0.omega(&s.l_body);
        let d = RigidBodyState {
            l_body: self.0.l_dot(&s.l_body),
            rotation: s.rotation * hat(&omega),
        };
        pack(&d)
    }
}

/// The body, its start (O₀ a generic rotation) and the invariants there.
struct Setup {
    body: FreeRigidBody,
    start: RigidBodyState,
    energy0: Real,
    l_norm0: Real,
    l_lab0: Vec3,
}

impl Setup {
    fn new() -> Result<Self, RowError> {
        let body = FreeRigidBody::new(Vec3::from(INERTIA)).map_err(|e| RowError::new(4, e))?;
        let start = RigidBodyState {
            l_body: Vec3::from(L_BODY0),
            rotation: rot_z(0.7) * rot_x(0.4) * rot_z(-1.1),
        };
        Ok(Self {
            body,
            energy0: body.energy(&start.l_body),
            l_norm0: start.l_body.norm(),
            l_lab0: start.l_lab(),
            start,
        })
    }
}

/// Running maxima of the three errors.
#[derive(Clone, Copy, Default)]
struct Worst {
    energy: Real,
    l_norm: Real,
    l_lab: Real,
}

impl Worst {
    fn update(&mut self, setup: &Setup, s: &RigidBodyState) {
        let e = (setup.body.energy(&s.l_body) - setup.energy0).abs() / setup.energy0;
        let n = (s.l_body.norm() - setup.l_norm0).abs() / setup.l_norm0;
        let l = (s.l_lab() - setup.l_lab0).norm() / setup.l_norm0;
        self.energy = self.energy.max(e);
        self.l_norm = self.l_norm.max(n);
        self.l_lab = self.l_lab.max(l);
    }
}

/// Least-squares slope of ln y against ln x (NaN if a y is not positive).
pub fn log_log_slope(x: &[Real], y: &[Real]) -> Real {
    crate::math::least_squares_slope(x.iter().zip(y).map(|(a, b)| (a.ln(), b.ln())))
}

fn finish(method: Method, worst: [Worst; 3], stats: Stats) -> Drift {
    let energy_error = worst.map(|w| w.energy);
    let l_norm_error = worst.map(|w| w.l_norm);
    let l_lab_error = worst.map(|w| w.l_lab);
    Drift {
        method,
        energy_slope: log_log_slope(&TIMES, &energy_error),
        l_norm_slope: log_log_slope(&TIMES, &l_norm_error),
        l_lab_slope: log_log_slope(&TIMES, &l_lab_error),
        energy_error,
        l_norm_error,
        l_lab_error,
        stats,
    }
}

/// Run an explicit method through [`TIMES`], watching every accepted step.
fn run_explicit<S: Stepper<12>>(
    setup: &Setup,
    method: Method,
    mut stepper: S,
) -> Result<Drift, RowError> {
    let rhs = FreeTopRhs(setup.body);
    let mut worst = Worst::default();
    let mut at = [Worst::default(); 3];
    for (i, &t) in TIMES.iter().enumerate() {
        while stepper.t() < t {
            stepper.step(&rhs, t).map_err(|e| RowError::new(4, e))?;
            worst.update(setup, &unpack(stepper.y()));
        }
        at[i] = worst;
    }
    Ok(finish(method, at, stepper.stats()))
}

fn run_splitting(
    setup: &Setup,
    method: Method,
    composition: Composition,
) -> Result<Drift, RowError> {
    let mut stepper = RigidBodySplitting::new(setup.body, composition, 0.0, setup.start, STEP)
        .map_err(|e| RowError::new(4, e))?;
    let mut worst = Worst::default();
    let mut at = [Worst::default(); 3];
    for (i, &t) in TIMES.iter().enumerate() {
        while stepper.t() < t {
            stepper.step(t).map_err(|e| RowError::new(4, e))?;
            worst.update(setup, stepper.state());
        }
        at[i] = worst;
    }
    Ok(finish(method, at, stepper.stats()))
}

/// The largest deviation of (L, O) from `reference` after a splitting run of
/// step `h` over [`ORDER_SPAN`].
fn splitting_error(
    setup: &Setup,
    composition: Composition,
    h: Real,
    reference: &RigidBodyState,
) -> Result<Real, RowError> {
    let mut stepper = RigidBodySplitting::new(setup.body, composition, 0.0, setup.start, h)
        .map_err(|e| RowError::new(4, e))?;
    stepper
        .advance_to(ORDER_SPAN)
        .map_err(|e| RowError::new(4, e))?;
    let s = stepper.state();
    Ok((s.l_body - reference.l_body)
        .amax()
        .max((s.rotation - reference.rotation).amax()))
}

/// Observed orders of Strang and Yoshida-4 against a tight DOP853 solution.
fn observed_orders(setup: &Setup) -> Result<(Real, Real), RowError> {
    // NOTE: DOP853 at rtol 1e-13 is accurate to ~1e-12 over t = 10, far below the
    // splittings' errors at h = 0.1 and 0.05 (≳ 1e-7), so it serves as the exact
    // solution here; it is an independent method (Runge–Kutta on (L, O)).
    let opts = AdaptiveOptions::new(1e-13, 1e-15).map_err(|e| RowError::new(4, e))?;
    let mut reference =
        Dop853::new(0.0, pack(&setup.start), opts).map_err(|e| RowError::new(4, e))?;
    let rhs = FreeTopRhs(setup.body);
    while reference.t() < ORDER_SPAN {
        reference
            .step(&rhs, ORDER_SPAN)
            .map_err(|e| RowError::new(4, e))?;
    }
    let reference = unpack(reference.y());
    let order = |c: Composition| -> Result<Real, RowError> {
        let coarse = splitting_error(setup, c, ORDER_STEP, &reference)?;
        let fine = splitting_error(setup, c, 0.5 * ORDER_STEP, &reference)?;
        Ok((coarse / fine).log2())
    };
    Ok((order(Composition::Strang)?, order(Composition::Yoshida4)?))
}

/// Run the experiment of row 4.
pub fn measure() -> Result<Measurement, RowError> {
    let setup = Setup::new()?;
    let y0 = pack(&setup.start);
    let rk4 = Rk4::new(0.0, y0, STEP).map_err(|e| RowError::new(4, e))?;
    // NOTE: atol only matters for components passing through zero (entries of O,
    // components of L); 1e-3·rtol of an O(1) state keeps the control relative.
    let opts =
        AdaptiveOptions::new(DOPRI5_RTOL, 1e-3 * DOPRI5_RTOL).map_err(|e| RowError::new(4, e))?;
    let dopri5 = Dopri5::new(0.0, y0, opts).map_err(|e| RowError::new(4, e))?;
    let (strang_order, yoshida4_order) = observed_orders(&setup)?;
    Ok(Measurement {
        rk4: run_explicit(&setup, Method::Rk4, rk4)?,
        dopri5: run_explicit(&setup, Method::Dopri5, dopri5)?,
        strang: run_splitting(&setup, Method::Strang, Composition::Strang)?,
        yoshida4: run_splitting(&setup, Method::Yoshida4, Composition::Yoshida4)?,
        strang_order,
        yoshida4_order,
    })
}

/// The time at which `naive`'s linearly growing energy error reaches `fix`'s
/// bounded one, extrapolated linearly from the last measured time (the time
/// after which the splitting is the more accurate, at the same step).
pub fn crossing_time(naive: &Drift, fix: &Drift) -> Real {
    TIMES[2] * fix.energy_error[2] / naive.energy_error[2]
}

fn outcome(d: &Drift) -> Outcome {
    let e = &d.energy_error;
    let result = if d.conserves() {
        format!(
            "energy error {:.1e} / {:.1e} / {:.1e} at t = 1e2 / 1e3 / 1e4 (bounded); |L| {:.0e}, lab L {:.0e} (rounding); {} steps",
            e[0], e[1], e[2], d.l_norm_error[2], d.l_lab_error[2], d.stats.steps
        )
    } else {
        format!(
            "energy error {:.1e} / {:.1e} / {:.1e} at t = 1e2 / 1e3 / 1e4 (slope {:.2}); |L| {:.1e} (slope {:.2}), lab L {:.1e} (slope {:.2}); {} steps",
            e[0],
            e[1],
            e[2],
            d.energy_slope,
            d.l_norm_error[2],
            d.l_norm_slope,
            d.l_lab_error[2],
            d.l_lab_slope,
            d.stats.steps
        )
    };
    Outcome {
        method: label(d.method),
        ok: d.conserves(),
        result,
    }
}

impl Measurement {
    /// The printable row.
    pub fn row(&self) -> Row {
        Row {
            number: 4,
            problem:
                "Free asymmetric top (tau = 0), I = (1, 2, 3), to t = 1e4: energy, |L| and lab L"
                    .into(),
            naive: vec![outcome(&self.rk4), outcome(&self.dopri5)],
            fix: vec![outcome(&self.strang), outcome(&self.yoshida4)],
            notes: vec![
                format!(
                    "observed orders over t = {ORDER_SPAN}, h = {ORDER_STEP} and {}: Strang {:.2}, Yoshida-4 {:.2}",
                    0.5 * ORDER_STEP,
                    self.strang_order,
                    self.yoshida4_order
                ),
                format!(
                    "RK4's energy error passes Strang's bound near t = {:.0e} and Yoshida-4's near t = {:.0e} (linear extrapolation); after that the splitting stays the more accurate",
                    crossing_time(&self.rk4, &self.strang),
                    crossing_time(&self.rk4, &self.yoshida4)
                ),
                format!(
                    "work to t = 1e4: RK4 {} evaluations, DP5 {}, Strang {} sub-flows, Yoshida-4 {}",
                    self.rk4.stats.rhs_evals,
                    self.dopri5.stats.rhs_evals,
                    self.strang.stats.rhs_evals,
                    self.yoshida4.stats.rhs_evals
                ),
            ],
        }
    }
}
