//! The physical solution of the symmetric top's (3.4), found in the frame
//! that turns with the free precession and kept as a table there.
//!
//! With z = e^{−iΩ̃₃t}w, (3.4) reads τw″ = (1 − 2iτk)w′ + τ(u + k²)w
//! (u = |w|², k = (I₃/I₁)Ω₃): w has nothing fast in it, only the decay and
//! the slow drift of its phase. So the table is cheap where z itself turns
//! fast, and exact where it is read: nodes carry w, w′ and w″, and a quintic
//! Hermite interpolant between nodes no further apart than [`NODE_TURN`]
//! over the rate at which w changes ([`node_rate`]) is within about
//! (0.03)⁶/46080 ≈ 1.6e-14 of w.
//!
//! The solution is built in pieces, each from the state the one before ended
//! in (the slow manifold is invariant, so the pieces join into one physical
//! solution):
//!
//! - **shot**, while u is beyond the reach of the slow series
//!   ([`SlowSeries::holds`]): backward from final data near the manifold, a
//!   margin beyond the piece ([`super::final_margin`]), which integrating
//!   backward damps by e^{−40}; a shoot on the final amplitude matches |w| at
//!   the piece's start, and the phase follows from the symmetry w → e^{iγ}w.
//!   Every shot takes the same steps as the pass that records the nodes, so
//!   the recorded pass is the converged shot itself;
//! - **series**, once u is within the series' reach: w′ = g(u)w with g from
//!   the series, a first-order equation stepped forward by DOP853;
//! - **tail**, once the series is its first two terms to rounding:
//!   w = w₀ exp(c₀Δt + c₁u₀(e^{2 Re c₀ Δt} − 1)/(2 Re c₀)), in closed form.

use super::series::SlowSeries;
use super::{PhysicalError, final_margin, guessed_log_amplitude};
use crate::integrate::{AdaptiveOptions, Dop853, IntegrateError, Stats, Stepper};
use crate::math::{Real, State, Vec3};
use crate::physics::symmetric_top::SymmetricTop;
use nalgebra::Complex;

type C = Complex<Real>;

/// The largest change of ln w between two nodes, in units of |w′/w|·h.
pub const NODE_TURN: Real = 0.03;

/// The most the guessed amplitude may fall (in e-foldings) over one shot,
/// margin included: e^{−250} ≈ 10⁻¹⁰⁹, well inside a double, whatever the
/// guess misses by.
const SEGMENT_E_FOLDINGS: Real = 250.0;

/// One node of the table: w and its first two derivatives at t.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Node {
    t: Real,
    w: C,
    w1: C,
    w2: C,
}

/// The closed form beyond the last node: w = w₀ exp(c₀Δt + c₁u₀E(Δt)).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Tail {
    t0: Real,
    w0: C,
    u0: Real,
    c0: C,
    c1: C,
}

impl Tail {
    fn at(&self, t: Real) -> (C, C) {
        let dt = t - self.t0;
        let r = self.c0.re;
        let decay = (2.0 * r * dt).exp();
        let e = if r != 0.0 {
            (2.0 * r * dt).exp_m1() / (2.0 * r)
        } else {
            dt
        };
        let w = self.w0 * (self.c0 * dt + self.c1 * (self.u0 * e)).exp();
        (w, (self.c0 + self.c1 * (self.u0 * decay)) * w)
    }
}

/// The physical solution of (3.4) in the rotating frame, on [origin, t_end]
/// and, past its last node, in closed form.
#[derive(Clone, Debug, PartialEq)]
pub struct SlowTable {
    origin: Real,
    /// Ω̃₃ = (1 − I₃/I₁)Ω₃: z = e^{−iΩ̃₃t}w.
    alpha: Real,
    omega3: Real,
    k: Real,
    nodes: Vec<Node>,
    tail: Option<Tail>,
    /// Work of every pass, and the number of shots.
    pub stats: Stats,
    /// Backward passes (shots).
    pub shots: u32,
}

impl SlowTable {
    /// The same table starting at `origin` (the motion is autonomous).
    pub fn starting_at(mut self, origin: Real) -> Self {
        self.origin = origin;
        self
    }

    /// The last time of the nodes; beyond it the tail (if any) holds for ever.
    pub fn t_end(&self) -> Real {
        if self.tail.is_some() {
            Real::INFINITY
        } else {
            self.origin + self.nodes.last().map_or(0.0, |n| n.t)
        }
    }

    /// w and w′ at time t (clamped to the table).
    pub fn w_at(&self, t: Real) -> (C, C) {
        let t = t - self.origin;
        if let Some(tail) = &self.tail
            && t >= tail.t0
        {
            return tail.at(t);
        }
        let n = &self.nodes;
        let last = n.len() - 1;
        if last == 0 || t <= n[0].t {
            return (n[0].w, n[0].w1);
        }
        if t >= n[last].t {
            return (n[last].w, n[last].w1);
        }
        let i = n.partition_point(|x| x.t <= t) - 1;
        let (a, b) = (&n[i], &n[i + 1]);
        let h = b.t - a.t;
        let s = (t - a.t) / h;
        let (s2, s3) = (s * s, s * s * s);
        let (s4, s5) = (s3 * s, s3 * s2);
        let h0 = 1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5;
        let h1 = s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5;
        let h2 = 0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5;
        let h4 = -4.0 * s3 + 7.0 * s4 - 3.0 * s5;
        let h5 = 0.5 * s3 - s4 + 0.5 * s5;
        let w = a.w * h0
            + a.w1 * (h * h1)
            + a.w2 * (h * h * h2)
            + b.w * (1.0 - h0)
            + b.w1 * (h * h4)
            + b.w2 * (h * h * h5);
        // The derivative of the same polynomial.
        let d0 = (-30.0 * s2 + 60.0 * s3 - 30.0 * s4) / h;
        let d1 = 1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s4;
        let d2 = s - 4.5 * s2 + 6.0 * s3 - 2.5 * s4;
        let d4 = -12.0 * s2 + 28.0 * s3 - 15.0 * s4;
        let d5 = 1.5 * s2 - 4.0 * s3 + 2.5 * s4;
        let w1 = a.w * d0 + a.w1 * d1 + a.w2 * (h * d2) - b.w * d0 + b.w1 * d4 + b.w2 * (h * d5);
        (w, w1)
    }

    /// Ω at time t: (e^{−iΩ̃₃(t − origin)}w, Ω₃).
    pub fn omega_at(&self, t: Real) -> Vec3 {
        let (w, _) = self.w_at(t);
        let z = w * C::from_polar(1.0, -self.alpha * (t - self.origin));
        Vec3::new(z.re, z.im, self.omega3)
    }

    /// Ω̇ at time t.
    pub fn omega_dot_at(&self, t: Real) -> Vec3 {
        let (w, w1) = self.w_at(t);
        let turn = C::from_polar(1.0, -self.alpha * (t - self.origin));
        let v = (w1 - w * C::new(0.0, self.alpha)) * turn;
        Vec3::new(v.re, v.im, 0.0)
    }

    /// The rate of Q where O = Q·R_z(Ω̃₃t) (t from the run's start, not the
    /// table's origin): (Re w, Im w, k) with w in that frame, slow.
    pub fn corotating_rate(&self, t: Real) -> Vec3 {
        let (w, _) = self.w_at(t);
        let w = if self.origin == 0.0 {
            w
        } else {
            w * C::from_polar(1.0, self.alpha * self.origin)
        };
        Vec3::new(w.re, w.im, self.k)
    }

    /// Ω̃₃, the rate of the precession R_z(Ω̃₃t) that O carries.
    pub fn precession(&self) -> Real {
        self.alpha
    }

    /// k = (I₃/I₁)Ω₃: Q's rate once w has gone.
    pub fn spin(&self) -> Real {
        self.k
    }

    /// The time from which w no longer turns Q by a rounding: the rest of
    /// ∫|w| dt is below 1e-17 rad (only in the tail, where |w| decays at
    /// −Re c₀); `None` if never.
    pub fn still_from(&self) -> Option<Real> {
        let tail = self.tail.as_ref()?;
        let rate = -tail.c0.re;
        if rate <= 0.0 {
            return None;
        }
        Some(self.origin + tail.t0 + still_after(tail.u0.sqrt(), rate))
    }
}

/// How long |w| = `a0`, decaying at `rate`, takes to turn Q by less than a
/// rounding for ever after: |w| e^{−rate Δt} ≤ 1e-17·rate (the rest of
/// ∫|w| dt is then below 1e-17 rad).
fn still_after(a0: Real, rate: Real) -> Real {
    let target = 1e-17 * rate;
    if a0 <= target {
        0.0
    } else {
        (a0 / target).ln() / rate
    }
}

/// When the physical solution through Ω₀ settles, estimated before it is
/// built from the guessed amplitude ([`guessed_log_amplitude`]): from
/// `tail` on it is in closed form (no nodes), from `still` on Ω⊥ no longer
/// turns the body by a rounding (the orientation turns about the axis in
/// closed form). Infinite where it never decays (τ = 0 or no radiation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settling {
    /// From when the table is its closed-form tail.
    pub tail: Real,
    /// From when the orientation is a steady spin about the axis.
    pub still: Real,
    /// |c₀| and |c₁| of w′/w = c₀ + c₁u + … (rotating frame), which space
    /// the nodes until the tail.
    pub c: [Real; 2],
}

/// [`Settling`] of the physical solution of (3.4) through Ω₀.
///
/// Paper: Eq. (3.4) (its physical solution; not in the paper).
pub fn settling(top: &SymmetricTop, omega0: &Vec3) -> Settling {
    let series = SlowSeries::new(top, omega0.z);
    let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
    let rate = -series.coefficient(0).re;
    let c = [series.coefficient(0).norm(), series.coefficient(1).norm()];
    if u0 == 0.0 {
        return Settling {
            tail: 0.0,
            still: 0.0,
            c,
        };
    }
    if !(rate > 0.0 && top.tau() > 0.0) {
        return Settling {
            tail: Real::INFINITY,
            still: Real::INFINITY,
            c,
        };
    }
    let amplitude = |t: Real| guessed_log_amplitude(top, omega0, t).exp();
    let tailed = |t: Real| tail_holds(&series, amplitude(t).powi(2));
    // The guess falls monotonically: double to a bound, then bisect.
    let tail = if tailed(0.0) {
        0.0
    } else {
        let mut hi = top.tau();
        while !tailed(hi) && hi < Real::MAX / 4.0 {
            hi *= 2.0;
        }
        let mut lo = 0.0;
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if tailed(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        hi
    };
    Settling {
        tail,
        still: tail + still_after(amplitude(tail), rate),
        c,
    }
}

/// The rate that spaces the nodes at g = w′/w: |g|, and four times the part
/// of g that changes with u. Where g is constant w is an exponential, whose
/// n-th derivative is gⁿw; where u decays algebraically (k = 0, g ≈ −τu)
/// w ≈ (1 + 2τu₀t)^(−1/2), whose sixth derivative, the one a quintic
/// interpolant misses, is 162(2τu)⁶ w: about (4.7|g|)⁶.
fn node_rate(series: &SlowSeries, g: C) -> Real {
    g.norm() + 4.0 * (g - series.coefficient(0)).norm()
}

/// Where the closed-form tail holds: the series past its first two terms
/// moves ln w by less than 1e-17 over the rest of the decay.
fn tail_holds(series: &SlowSeries, u: Real) -> bool {
    let r = -series.coefficient(0).re;
    if r <= 0.0 {
        return false;
    }
    let (c1, c2) = (series.coefficient(1).norm(), series.coefficient(2).norm());
    (c2 / (4.0 * r) + c1 * c1 / (2.0 * r * r)) * u * u <= 1e-17
}

/// The derivatives of w on the slow manifold, by the series.
fn series_node(series: &SlowSeries, t: Real, w: C) -> Node {
    let u = w.norm_sqr();
    Node {
        t,
        w,
        w1: series.rate(u) * w,
        w2: series.second(u) * w,
    }
}

/// Limits of one build.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// The integrators' tolerance.
    pub rtol: Real,
    /// Steps left (accepted and rejected, over every pass).
    pub steps: u64,
    /// The share of [`NODE_TURN`] the nodes are apart (1, or less for the
    /// second run of an error estimate).
    pub refine: Real,
}

impl Budget {
    fn charge(&mut self, stats: &Stats, t: Real) -> Result<(), PhysicalError> {
        let used = stats.steps + stats.rejected;
        if used > self.steps {
            return Err(PhysicalError::Integrate(IntegrateError::TooManySteps {
                t,
                max_steps: self.steps,
            }));
        }
        self.steps -= used;
        Ok(())
    }
}

/// The physical solution of (3.4) through Ω₀ on [0, span], in the rotating
/// frame. Paper: Eq. (3.4) (its physical solution; not in the paper).
pub fn slow_table(
    top: &SymmetricTop,
    omega0: &Vec3,
    span: Real,
    budget: &mut Budget,
) -> Result<SlowTable, PhysicalError> {
    if top.tau().is_nan() || top.tau() <= 0.0 {
        return Err(PhysicalError::BadInput("the full ALE needs tau > 0"));
    }
    if !(span >= 0.0 && span.is_finite()) {
        return Err(PhysicalError::BadInput("the span must be finite and >= 0"));
    }
    let series = SlowSeries::new(top, omega0.z);
    let mut table = SlowTable {
        origin: 0.0,
        alpha: top.omega3_tilde(omega0.z),
        omega3: omega0.z,
        k: top.ratio() * omega0.z,
        nodes: Vec::new(),
        tail: None,
        stats: Stats::default(),
        shots: 0,
    };
    let w0 = C::new(omega0.x, omega0.y);
    if w0.norm_sqr() == 0.0 || w0.norm() <= 1e-300 * omega0.norm() {
        // z ≡ 0 is the physical solution: the top spins steadily about its axis.
        table.nodes.push(Node {
            t: 0.0,
            w: C::new(0.0, 0.0),
            w1: C::new(0.0, 0.0),
            w2: C::new(0.0, 0.0),
        });
        return Ok(table);
    }
    let (mut t0, mut start) = (0.0, w0);
    loop {
        let u = start.norm_sqr();
        if tail_holds(&series, u) {
            if table.nodes.is_empty() {
                table.nodes.push(series_node(&series, t0, start));
            }
            table.tail = Some(Tail {
                t0,
                w0: start,
                u0: u,
                c0: series.coefficient(0),
                c1: series.coefficient(1),
            });
            break;
        }
        if t0 >= span && !table.nodes.is_empty() {
            break;
        }
        let piece = if series.holds(u) {
            along_series(&series, t0, start, span, budget)?
        } else {
            let (piece, passes) = shoot(top, &series, omega0.z, t0, start, span, budget)?;
            table.shots += passes;
            piece
        };
        let stats = piece.1;
        table.stats += stats;
        let nodes = piece.0;
        let skip = usize::from(!table.nodes.is_empty());
        table.nodes.extend_from_slice(&nodes[skip..]);
        let last = table.nodes[table.nodes.len() - 1];
        if last.t <= t0 && t0 < span {
            return Err(PhysicalError::NoConvergence(
                "a piece of the run made no progress",
            ));
        }
        (t0, start) = (last.t, last.w);
        if t0 >= span && !tail_holds(&series, start.norm_sqr()) {
            break;
        }
    }
    // The first sample is the input itself.
    table.nodes[0].w = w0;
    Ok(table)
}

/// A piece of nodes and the work it took.
type Piece = (Vec<Node>, Stats);

/// w′ = g(u)w stepped forward from (t0, w) until the tail holds or `span`.
fn along_series(
    series: &SlowSeries,
    t0: Real,
    w: C,
    span: Real,
    budget: &mut Budget,
) -> Result<Piece, PhysicalError> {
    let rhs = |_t: Real, y: &State<2>| {
        let w = C::new(y[0], y[1]);
        let v = series.rate(w.norm_sqr()) * w;
        State::<2>::new(v.re, v.im)
    };
    let opts = AdaptiveOptions::new(budget.rtol, budget.rtol * 1e-6 * w.norm())?;
    let mut stepper = Dop853::new(t0, State::<2>::new(w.re, w.im), opts)?;
    let mut nodes = vec![series_node(series, t0, w)];
    while stepper.t() < span {
        let y = *stepper.y();
        let w = C::new(y[0], y[1]);
        let u = w.norm_sqr();
        if tail_holds(series, u) || !series.holds(u) {
            break;
        }
        let rate = node_rate(series, series.rate(u));
        if rate > 0.0 {
            stepper.set_h_max(NODE_TURN * budget.refine / rate);
        }
        stepper.step(&rhs, span)?;
        let y = *stepper.y();
        nodes.push(series_node(series, stepper.t(), C::new(y[0], y[1])));
        if stepper.stats().steps + stepper.stats().rejected > budget.steps {
            break;
        }
    }
    let stats = stepper.stats();
    budget.charge(&stats, stepper.t())?;
    Ok((nodes, stats))
}

/// The rotating-frame (3.4), (w, w′) as four reals.
fn rotating_rhs(tau: Real, k: Real) -> impl Fn(Real, &State<4>) -> State<4> {
    move |_t, y| {
        let (w, v) = (C::new(y[0], y[1]), C::new(y[2], y[3]));
        let acc = (v * C::new(1.0, -2.0 * tau * k) + w * (tau * (w.norm_sqr() + k * k))) / tau;
        State::<4>::new(v.re, v.im, acc.re, acc.im)
    }
}

/// What every pass of one shot shares.
struct Shot<'a> {
    top: &'a SymmetricTop,
    series: &'a SlowSeries,
    omega3: Real,
    /// The piece's length (local time 0 to `length`).
    length: Real,
    rtol: Real,
    refine: Real,
}

impl Shot<'_> {
    /// One backward pass: from w(T) = a (real) near the manifold, a margin
    /// beyond `length`, to local time 0, with the steps that also make the
    /// nodes on [0, length]. The state at 0 and, when `record`, the nodes
    /// (descending in time).
    fn pass(
        &self,
        a: Real,
        record: bool,
        max_steps: u64,
    ) -> Result<(State<4>, Vec<Node>, Stats), IntegrateError> {
        let (tau, k) = (self.top.tau(), self.top.ratio() * self.omega3);
        let rhs = rotating_rhs(tau, k);
        let t_final = self.length + final_margin(self.top, self.omega3);
        let u = a * a;
        // NOTE: the final data need not be exact (the margin damps their
        // error by e^{−40}): the series where it holds, else its first two
        // terms (exact in τk; a series in τ would swamp them at τk ≳ 1).
        let g = if self.series.holds(u) {
            self.series.rate(u)
        } else {
            self.series.coefficient(0) + self.series.coefficient(1) * u
        };
        let v = g * a;
        let mut opts = AdaptiveOptions::new(self.rtol, self.rtol * 1e-6 * a.max(1e-300))?;
        opts.max_steps = max_steps.max(1);
        let mut stepper = Dop853::new(t_final, State::<4>::new(a, 0.0, v.re, v.im), opts)?;
        while stepper.t() > self.length {
            stepper.step(&rhs, self.length)?;
        }
        let node = |y: &State<4>, t: Real| {
            let acc = rhs(t, y);
            Node {
                t,
                w: C::new(y[0], y[1]),
                w1: C::new(y[2], y[3]),
                w2: C::new(acc[2], acc[3]),
            }
        };
        let mut nodes = Vec::new();
        if record {
            nodes.push(node(stepper.y(), stepper.t()));
        }
        while stepper.t() > 0.0 {
            let y = stepper.y();
            let rate = node_rate(self.series, C::new(y[2], y[3]) / C::new(y[0], y[1]));
            if rate.is_finite() && rate > 0.0 {
                stepper.set_h_max(NODE_TURN * self.refine / rate);
            }
            stepper.step(&rhs, 0.0)?;
            if record {
                nodes.push(node(stepper.y(), stepper.t()));
            }
        }
        Ok((*stepper.y(), nodes, stepper.stats()))
    }
}

/// How long a shot piece from amplitude |w| = `a0` runs: until the guessed
/// u falls to half the series' reach (then the series takes over), with at
/// most [`SEGMENT_E_FOLDINGS`] of fall over the piece and its margin; at
/// least τ, at most `left`.
fn piece_length(
    top: &SymmetricTop,
    series: &SlowSeries,
    a0: Real,
    omega3: Real,
    left: Real,
) -> Real {
    let start = Vec3::new(a0, 0.0, omega3);
    let margin = final_margin(top, omega3);
    let fall = |len: Real| a0.ln() - guessed_log_amplitude(top, &start, len);
    let reach = series.reach_u();
    let wanted = if reach > 0.0 {
        0.5 * (a0 * a0 / (0.5 * reach)).ln()
    } else {
        Real::INFINITY
    };
    // The guess falls monotonically: bisect for each bound.
    let first = |ok: &dyn Fn(Real) -> bool| {
        if ok(left) {
            return left;
        }
        let (mut lo, mut hi) = (0.0, left);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if ok(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    };
    let to_series = first(&|len| fall(len) < wanted);
    let within = first(&|len| fall(len + margin) <= SEGMENT_E_FOLDINGS);
    to_series.min(within).max(top.tau().min(left))
}

/// The root of `miss` (increasing in x, +∞ where a pass blew up) from
/// `x0`: bracketed by doubling steps (not below `floor`), then regula falsi
/// (Illinois), bisecting while a side is infinite. The best point found and
/// its miss.
fn bracketed_root(
    mut miss: impl FnMut(Real) -> Result<Real, PhysicalError>,
    x0: Real,
    floor: Real,
) -> Result<(Real, Real), PhysicalError> {
    let f0 = miss(x0)?;
    // Bracket: lo with miss < 0, hi with miss > 0, widening by doubling.
    let (mut lo, mut flo, mut hi, mut fhi) = if f0 < 0.0 {
        (x0, f0, Real::NAN, Real::INFINITY)
    } else {
        (Real::NAN, Real::NEG_INFINITY, x0, f0)
    };
    let mut widen = 1.0;
    while lo.is_nan() {
        let x = (hi - widen).max(floor);
        let f = miss(x)?;
        if f < 0.0 {
            (lo, flo) = (x, f);
        } else {
            (hi, fhi) = (x, f);
            if x <= floor {
                return Err(PhysicalError::NoConvergence("no lower bracket"));
            }
        }
        widen *= 2.0;
    }
    while hi.is_nan() {
        let x = lo + widen;
        let f = miss(x)?;
        if f > 0.0 {
            (hi, fhi) = (x, f);
        } else {
            (lo, flo) = (x, f);
        }
        widen *= 2.0;
        if widen > 1e4 {
            return Err(PhysicalError::NoConvergence("no upper bracket"));
        }
    }
    // Regula falsi (Illinois), bisecting while a side is infinite.
    let mut best = if -flo < fhi { (lo, flo) } else { (hi, fhi) };
    let mut side = 0;
    for _ in 0..200 {
        if best.1.abs() <= 4.0 * Real::EPSILON || hi - lo <= 2.0 * Real::EPSILON * (1.0 + lo.abs())
        {
            break;
        }
        let x = if fhi.is_finite() {
            let x = lo - flo * (hi - lo) / (fhi - flo);
            if x > lo && x < hi { x } else { 0.5 * (lo + hi) }
        } else {
            0.5 * (lo + hi)
        };
        let f = miss(x)?;
        if f.abs() < best.1.abs() {
            best = (x, f);
        }
        if f < 0.0 {
            (lo, flo) = (x, f);
            if side == -1 && fhi.is_finite() {
                fhi *= 0.5;
            }
            side = -1;
        } else {
            (hi, fhi) = (x, f);
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        }
    }
    Ok(best)
}

/// A shot piece from (t0, start): the nodes (ascending, the first at t0
/// with w = start exactly), the work, and the number of passes.
fn shoot(
    top: &SymmetricTop,
    series: &SlowSeries,
    omega3: Real,
    t0: Real,
    start: C,
    span: Real,
    budget: &mut Budget,
) -> Result<(Piece, u32), PhysicalError> {
    let a0 = start.norm();
    let length = piece_length(top, series, a0, omega3, span - t0);
    let shot = Shot {
        top,
        series,
        omega3,
        length,
        rtol: budget.rtol,
        refine: budget.refine,
    };
    let target = a0.ln();
    let mut stats = Stats::default();
    let mut passes = 0;
    // ln|w(0)| − ln|start| for the final amplitude e^x; a pass that blows up
    // backward asked for too large an amplitude: +∞.
    let miss = |x: Real| -> Result<Real, PhysicalError> {
        passes += 1;
        match shot.pass(x.exp(), false, budget.steps) {
            Ok((y, _, s)) => {
                stats += s;
                budget.charge(&s, t0)?;
                Ok(y[0].hypot(y[1]).ln() - target)
            }
            Err(IntegrateError::NonFinite { .. } | IntegrateError::StepSizeUnderflow { .. }) => {
                Ok(Real::INFINITY)
            }
            Err(e) => Err(e.into()),
        }
    };
    let start3 = Vec3::new(a0, 0.0, omega3);
    let guess = guessed_log_amplitude(top, &start3, length + final_margin(top, omega3));
    let floor = Real::MIN_POSITIVE.ln();
    let x0 = guess.max(floor + 1.0);
    let best = bracketed_root(miss, x0, floor)?;
    if best.1.is_nan() || best.1.abs() > 1e-10 {
        return Err(PhysicalError::NoConvergence(
            "the shoot on the final amplitude",
        ));
    }
    passes += 1;
    let (y0, mut nodes, s) = shot.pass(best.0.exp(), true, budget.steps)?;
    stats += s;
    budget.charge(&s, t0)?;
    // The phase by the symmetry w → e^{iγ}w; the nodes in ascending time.
    let at0 = C::new(y0[0], y0[1]);
    let turn = (start / a0) / (at0 / at0.norm());
    nodes.reverse();
    for n in &mut nodes {
        n.t += t0;
        n.w *= turn;
        n.w1 *= turn;
        n.w2 *= turn;
    }
    nodes[0].w = start;
    nodes[0].t = t0;
    Ok(((nodes, stats), passes))
}
