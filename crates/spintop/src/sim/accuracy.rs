//! How far the truncated and the reduced models stray from the physical
//! solution of (3.4) over a run, estimated before it starts.
//!
//! The physical solution lies on the slow manifold of (3.4), Ω̇ = G₀ + G₁ +
//! G₂ + G₃ + O(τ⁴): G₀ is the free motion, G₀ + G₁ the reduced ALE, and G₂
//! ([`slow_manifold_second_order`]) the first term the reduced ALE leaves
//! out, G₃ ([`slow_manifold_third_order`]) the next. Each estimate is the
//! leading terms carried over the run.
//!
//! **Symmetric top** (I₁ = I₂, d on the axis; units I₁ = 1). On the manifold
//! ż = f(u)z with z = Ω₁ + iΩ₂, u = |z|², k = (I₃/I₁)Ω₃, s = u + k²:
//!
//! ```text
//! Re f = −τs + τ³s(3u + 5k²) − …,    Im f = −Ω̃₃ − 2τ²ks + 14τ⁴ks² − …
//! ```
//!
//! The reduced ALE keeps −τs and −Ω̃₃. Its precession runs 2τ²ks too fast
//! and it decays τ³s(3u + 5k²) too fast; both act on an amplitude A = √u
//! that falls as Ȧ = −τsA. Carried over the run, with dt = −dA/(τsA),
//!
//! ```text
//! ∫ 2τ²ks A dt          = 2τ|k| (A₀ − A_T)
//! ∫ τ³s(3u + 5k²) A dt  = τ²(A₀³ − A_T³) + 5τ²k² (A₀ − A_T)
//! ```
//!
//! and their sum, over |Ω₀|, is the reduced model's estimate. It bounds the
//! real error A(t)·|Δφ(t)| at every t ≤ T (A falls, so A(t)∫₀ᵗ rate ≤ ∫₀ᵗ
//! rate·A), and is at most e times it (the worst case, a long run, where
//! A(t)·2τk ln(A₀/A) peaks at A = A₀/e). The next terms of both series have
//! the opposite sign, so the leading terms overestimate.
//!
//! The truncated model differs from the reduced one at first order, and both
//! have closed forms: its estimate is the largest distance between the two
//! over the run, plus the reduced model's own estimate (the triangle
//! inequality).
//!
//! **Any other top**: no closed form, so the same leading terms are
//! integrated along the run (see [`general_errors`]).
//!
//! **The orientation** a run reports strays by the integral of Ω's error
//! (in the lab, e(t) = ∫₀ᵗ OδΩ dt): its part along L adds up, the rest turns
//! with the figure axis. Each model's orientation error, in radians, is
//! estimated beside its error in Ω ([`symmetric_reduced_orientation_error`],
//! [`symmetric_truncated_orientation_error`], and in [`general_errors`]).
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `a0`, `a_t` | A₀, A_T | Ω⊥ at 0 and at the end (reduced model) | 1/τ |
//! | `k` | (I₃/I₁)Ω₃ | the spin term | 1/τ |
//! | `r` | R(t) | the truncated model's clock (4.6) | – |

use crate::integrate::{AdaptiveOptions, Dop853, IntegrateError, Stepper};
use crate::math::{Real, State, Vec3, directional_derivative};
use crate::physics::full_ale::{slow_manifold_second_order, slow_manifold_third_order};
use crate::physics::general_top::GeneralTop;
use crate::physics::symmetric_top::{
    SymmetricTop, reduced_amplitude, reduced_closed_form, truncated_clock, truncated_closed_form,
};
use crate::sim::secular::{Law, SecularRun, SecularSample, invariants, secular, swing};

/// The estimated largest error of each model over a run, relative to |Ω₀|.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelErrors {
    /// The truncated ALE (3.3) against the physical solution of (3.4).
    pub truncated: Real,
    /// The reduced ALE against the physical solution of (3.4).
    pub reduced: Real,
    /// The truncated ALE's orientation against the physical solution's: the
    /// angle of the rotation between them, in radians (at most π).
    pub truncated_orientation: Real,
    /// The reduced ALE's orientation against the physical solution's, in
    /// radians (at most π).
    pub reduced_orientation: Real,
    /// Nothing radiates (Ω₀ along the axis of a symmetric top, or a steady
    /// spin about a principal axis along the dipole): every model is exact.
    pub exact: bool,
}

impl ModelErrors {
    const EXACT: Self = Self {
        truncated: 0.0,
        reduced: 0.0,
        truncated_orientation: 0.0,
        reduced_orientation: 0.0,
        exact: true,
    };
}

// ANCHOR: reduced_error
/// The reduced model's estimated error over [0, `t`], relative to |Ω₀|:
/// its precession and decay drifts carried over the amplitude it loses.
///
/// Paper: Eq. (3.4) (its slow manifold), Eq. (4.15), Eq. (4.16).
///
/// ```text
/// ε_r = [(A₀ − A_T)(2τ|k| + 5τ²k²) + τ²(A₀³ − A_T³)] / |Ω₀|,   A_T = A₀Φ(T)
/// ```
pub fn symmetric_reduced_error(top: &SymmetricTop, omega0: &Vec3, t: Real) -> Real {
    let tau = top.tau();
    let a0 = omega0.x.hypot(omega0.y);
    let k = top.ratio() * omega0.z;
    // NOTE: 1 − Φ and 1 − Φ³ from ln Φ with expm1: Φ is within rounding
    // of 1 for a short run, where the difference is all that matters.
    let ln_phi = reduced_amplitude(top, omega0, t).ln();
    let lost = -a0 * ln_phi.exp_m1();
    let lost3 = -a0 * a0 * a0 * (3.0 * ln_phi).exp_m1();
    // NOTE: abs() only turns the −0 of a zero-length run (expm1(−0) = −0)
    // into +0; every term is ≥ 0.
    ((lost * (2.0 * tau * k.abs() + 5.0 * tau * tau * k * k) + tau * tau * lost3) / omega0.norm())
        .abs()
}
// ANCHOR_END: reduced_error

/// Points of the grid on which the truncated model's distance from the
/// reduced one is taken (geometric in t, from 10⁻⁹T to T: each point 1 % past
/// the one before).
const GRID: usize = 2000;

/// The margin for the largest distance falling between two points of the
/// grid: every factor is a smooth function of ln t, and moves by about 2 %
/// or less from one point to the next.
const GRID_MARGIN: Real = 1.05;

// ANCHOR: truncated_error
/// The truncated model's estimated error over [0, `t`], relative to |Ω₀|:
/// its largest distance from the reduced model (both in closed form), plus
/// the reduced model's own estimate.
///
/// Paper: Eq. (4.7), Eq. (4.15), Eq. (4.16).
///
/// ```text
/// |Ω_trunc − Ω_red|² = Ω₃₀²(1 − 1/R)² + (A₀/R − A₀Φ)² + 4(A₀/R)(A₀Φ) sin²(Δα/2)
/// Δα = Ω̃₃₀ (t − ϑ(t))        (the truncated precession slows with Ω₃ = Ω₃₀/R)
/// ```
///
/// with sin²(Δα/2) ≤ min(Δα, 2)²/4 to take the envelope of the oscillation,
/// the largest value over a geometric grid of times.
pub fn symmetric_truncated_error(top: &SymmetricTop, omega0: &Vec3, t: Real) -> Real {
    let a0 = omega0.x.hypot(omega0.y);
    let precession = top.omega3_tilde(omega0.z).abs();
    let distance = |s: Real| {
        let clock = truncated_clock(top, a0, s);
        // R − 1 = 2x/(1 + R) with x = τΩ⊥₀²s: no cancellation when R ≈ 1.
        let x = top.tau() * a0 * a0 * s;
        let r_minus_1 = 2.0 * x / (1.0 + clock.r);
        let d3 = omega0.z.abs() * r_minus_1 / clock.r;
        let a_trunc = a0 / clock.r;
        let a_red = a0 * reduced_amplitude(top, omega0, s);
        let phase = (precession * (s - clock.vartheta)).min(2.0);
        let da = a_trunc - a_red;
        (d3 * d3 + da * da + a_trunc * a_red * phase * phase).sqrt()
    };
    let worst = (0..=GRID)
        .map(|j| distance(t * (1e-9 as Real).powf(1.0 - j as Real / GRID as Real)))
        .fold(0.0, Real::max);
    GRID_MARGIN * worst / omega0.norm() + symmetric_reduced_error(top, omega0, t)
}
// ANCHOR_END: truncated_error

/// The margin on the orientation estimates: they carry the leading term of
/// each phase, linearised, and bound the turning parts by their chords.
const ORIENTATION_MARGIN: Real = 1.5;

// ANCHOR: reduced_orientation_error
/// The reduced model's estimated orientation error over [0, `t`], in
/// radians: the angle between its orientation and the physical solution's.
///
/// Paper: Eq. (3.4) (its slow manifold), Eq. (4.15), Eq. (4.16).
///
/// Two models whose body-frame Ω differ by δΩ(t) part in orientation by
/// e(t) = ∫₀ᵗ O(s) δΩ(s) ds (to first order, in the lab). The reduced
/// model's δΩ is a phase Δα of Ω⊥ and a relative amplitude Δ ln A = D/2,
/// both functions of y = ln(u₀/u) along the run; the amplitudes of both
/// models are drawn to the same late-time value, so D relaxes:
///
/// ```text
/// Δα = τ|k| y,   dD/dy = −(u/s) D + τ²(3u + 5k²),  D(0) = 0
/// ```
///
/// The part of δΩ along L adds up: the lab phase about L, from
/// Δ|L| = (u/|L|) Δ ln A. The phase part is O Δα (e₃ × Ω⊥) = Δα ṅ₃, and
/// ∫ Δα ṅ₃ = ∫ Δα̇(s) (n₃(t) − n₃(s)) ds, where the figure axis n₃ lies
/// within θ = atan(A/|k|) of n_L and n_L sweeps θ(s) − θ(t): the chord is
/// at most 2θ(s). The amplitude's turning part, w = (D/2) cos θ along
/// n_L × ṅ₃, the same way. With s = u + k² and dt = dy/(2τs):
///
/// ```text
/// e ≤ ∫₀^Y [D u/(4τ s^(3/2)) + τ|k| c + w θ |k|√u/(2s)] dy + ∫ c |dw|,
/// c = min(2θ(s), 2, ∫ₛᵀ A dt)   (the chord from n₃(s) to n₃(T))
/// ```
///
/// (for k = 0 the lab phase is 3τ[A₀ − A_T(1 + ln(A₀/A_T))], at most 3τA₀).
///
/// Paper: Eq. (4.15), Eq. (4.16) (the reduced model's Ω) and Eq. (3.1) (the
/// orientation it drives); the estimate itself is not in the paper.
pub fn symmetric_reduced_orientation_error(top: &SymmetricTop, omega0: &Vec3, t: Real) -> Real {
    let tau = top.tau();
    let a0 = omega0.x.hypot(omega0.y);
    if a0 == 0.0 || tau == 0.0 || t == 0.0 {
        return 0.0;
    }
    let k = (top.ratio() * omega0.z).abs();
    let k2 = k * k;
    let u0 = a0 * a0;
    // Y = ln(u₀/u_T) ≥ 0, the log of the amplitude's fall squared.
    let big_y = -2.0 * reduced_amplitude(top, omega0, t).ln();
    let a_t = a0 * (-0.5 * big_y).exp();
    let theta_t = a_t.atan2(k);
    // Past u ≪ k² every integrand falls as e^(−y/2) or faster: 80 beyond
    // that point is the whole integral.
    let end = if k2 > 0.0 {
        big_y.min((u0 / k2).ln().max(0.0) + 80.0)
    } else {
        big_y
    };
    // The chord from n₃(s) to n₃(T): within 2θ(s), and within the figure
    // axis's path ∫ₛᵀ A dt = (θ(s) − θ_T)/(τ|k|).
    let chord = |theta: Real| {
        let near = (2.0 * theta).min(2.0);
        if k > 0.0 {
            near.min((theta - theta_t) / (tau * k))
        } else {
            near
        }
    };
    const N: usize = 4000;
    let h = end / N as Real;
    // Along y: u, θ, and the integrands of the lab phase, (Δ ln u/2)(u/√s)
    // dt/dy, and of the phase's turning part, τ|k| chord.
    let point = |y: Real, d_ln_u: Real| {
        let u = u0 * (-y).exp();
        let s = u + k2;
        let theta = u.sqrt().atan2(k);
        let lab = 0.25 * d_ln_u * u / (tau * s * s.sqrt());
        (u, s, theta, lab, tau * k * chord(theta))
    };
    // Δ ln u relaxes: d(Δ ln u)/dy = −(u/s) Δ ln u + τ²(3u + 5k²), by the
    // midpoint rule (each step's rate at its middle).
    let rate = |y: Real, d: Real| {
        let u = u0 * (-y).exp();
        -(u / (u + k2)) * d + tau * tau * (3.0 * u + 5.0 * k2)
    };
    let (mut lab, mut phase, mut amplitude, mut sweep) = (0.0, 0.0, 0.0, 0.0);
    let mut d_ln_u: Real = 0.0;
    let mut before = point(0.0, 0.0);
    let mut w_before: Real = 0.0;
    for j in 0..=N {
        let y = j as Real * h;
        if j > 0 {
            let mid = d_ln_u + 0.5 * h * rate(y - h, d_ln_u);
            d_ln_u += h * rate(y - 0.5 * h, mid);
        }
        let now = point(y, d_ln_u);
        // Simpson's weights for the smooth integrands.
        let weight = if j == 0 || j == N {
            1.0
        } else if j % 2 == 1 {
            4.0
        } else {
            2.0
        };
        lab += weight * now.3;
        phase += weight * now.4;
        // The amplitude's turning part, w = (Δ ln u/2) cos θ: ∫ chord |dw|,
        // each step's change at the larger chord before it, and ∫ w θ |θ̇| dt
        // with −dθ/dy = |k|√u/(2s).
        let w = 0.5 * d_ln_u * now.2.cos();
        if j > 0 {
            amplitude += chord(before.2) * (w - w_before).abs();
        }
        sweep += weight * w * now.2 * k * now.0.sqrt() / (2.0 * now.1);
        (before, w_before) = (now, w);
    }
    let third = h / 3.0;
    (ORIENTATION_MARGIN * (third * (lab + phase + sweep) + amplitude))
        .min(std::f64::consts::PI as Real)
}
// ANCHOR_END: reduced_orientation_error

// ANCHOR: truncated_orientation_error
/// The truncated model's estimated orientation error over [0, `t`], in
/// radians: its distance from the reduced model's orientation, plus the
/// reduced model's own estimate.
///
/// Paper: Eq. (4.7), Eq. (4.15), Eq. (4.16).
///
/// With δΩ = Ω_trunc − Ω_red (both closed forms) and l̂ the reduced model's
/// L/|L| in the body, e(t) = ∫ O δΩ ds splits into the part along L, which
/// adds up, and the rest q, which turns with the figure axis:
///
/// ```text
/// e ≤ max_t |∫₀ᵗ δΩ·l̂ ds| + min(∫₀ᵀ |q| ds, 3θ₀ max |q|/A_red)
/// ```
///
/// taken on the geometric grid of [`symmetric_truncated_error`].
pub fn symmetric_truncated_orientation_error(top: &SymmetricTop, omega0: &Vec3, t: Real) -> Real {
    let a0 = omega0.x.hypot(omega0.y);
    if a0 == 0.0 || top.tau() == 0.0 || t == 0.0 {
        return 0.0;
    }
    let ratio = top.ratio();
    let theta0 = a0.atan2((ratio * omega0.z).abs());
    let parts = |s: Real| {
        let w_t = truncated_closed_form(top, omega0, s);
        let w_r = reduced_closed_form(top, omega0, s);
        let delta = w_t - w_r;
        let l = Vec3::new(w_r.x, w_r.y, ratio * w_r.z);
        let l_hat = l / l.norm();
        let along = delta.dot(&l_hat);
        let q = (delta - l_hat * along).norm();
        (along, q, w_r.x.hypot(w_r.y))
    };
    let times = std::iter::once(0.0)
        .chain((0..=GRID).map(|j| t * (1e-9 as Real).powf(1.0 - j as Real / GRID as Real)));
    let (mut last_t, mut last) = (0.0, parts(0.0));
    let (mut secular, mut worst_secular, mut path, mut worst_ratio): (Real, Real, Real, Real) =
        (0.0, 0.0, 0.0, 0.0);
    for s in times.skip(1) {
        let now = parts(s);
        let h = s - last_t;
        secular += 0.5 * h * (last.0 + now.0);
        path += 0.5 * h * (last.1 + now.1);
        worst_secular = worst_secular.max(secular.abs());
        if now.2 > 0.0 {
            worst_ratio = worst_ratio.max(now.1 / now.2);
        }
        (last_t, last) = (s, now);
    }
    let turning = path.min(3.0 * theta0 * worst_ratio);
    (GRID_MARGIN * (worst_secular + turning) + symmetric_reduced_orientation_error(top, omega0, t))
        .min(std::f64::consts::PI as Real)
}
// ANCHOR_END: truncated_orientation_error

/// Both estimates for a symmetric top; exact when Ω₀ lies on the axis.
pub fn symmetric_errors(top: &SymmetricTop, omega0: &Vec3, t: Real) -> ModelErrors {
    if omega0.x == 0.0 && omega0.y == 0.0
        || top.tau() == 0.0
        || changes_nothing(top.tau(), omega0, t)
    {
        return ModelErrors::EXACT;
    }
    ModelErrors {
        truncated: symmetric_truncated_error(top, omega0, t).min(2.0),
        reduced: symmetric_reduced_error(top, omega0, t).min(2.0),
        truncated_orientation: symmetric_truncated_orientation_error(top, omega0, t),
        reduced_orientation: symmetric_reduced_orientation_error(top, omega0, t),
        exact: false,
    }
}

/// True when radiation moves no model's Ω or orientation by a rounding
/// over `t`: each model's Ω changes at a relative rate of at most a few
/// τ|Ω|² (τ the fast time), so over t by at most r = 4τ|Ω₀|²t, and the
/// orientations by r|Ω₀|t radians. Below 1e-18 the models are one (a top
/// with |Ω₀| ~ 1e-160 does not move, and the estimates' squares underflow).
pub fn changes_nothing(tau: Real, omega0: &Vec3, t: Real) -> bool {
    let w = omega0.norm();
    let r = 4.0 * tau * w * w * t;
    r < 1e-18 && r * w * t < 1e-18
}

/// The most steps the integrated estimate of a general top takes; a longer
/// run is estimated over the span those steps reach and carried on from
/// there (see [`general_errors`]).
pub const ESTIMATE_MAX_STEPS: u64 = 200_000;

/// The margin on the integrated estimates of a general top: they carry only
/// the leading term, and the next one (O(τ_f³)) is left out.
const GENERAL_MARGIN: Real = 2.0;

/// True when nothing radiates from Ω₀ on: a steady spin about a principal
/// axis that lies along the dipole (d × Ω₀ = 0 and Ω₀ × IΩ₀ = 0), which
/// every model keeps for ever.
pub fn radiates_nothing(inertia: &Vec3, dipole: &Vec3, omega0: &Vec3) -> bool {
    let tiny = 1e-14 * omega0.norm() * dipole.norm();
    dipole.cross(omega0).norm() <= tiny
        && omega0.cross(&inertia.component_mul(omega0)).norm()
            <= 1e-14 * omega0.norm_squared() * inertia.max()
}

// ANCHOR: general_errors
/// Both estimates for any top, integrated along the run.
///
/// Paper: Eq. (3.3), Eq. (3.4) (its slow manifold to third order).
///
/// ```text
/// Ω̇   = F₃(Ω) = G₀ + G₁ + G₂ + G₃          (the physical solution to O(τ_f³))
/// ė_r = DF_red(Ω)·e_r − G₂(Ω) − G₃(Ω)       (the reduced model's error, linearised)
/// Ω̇_t = F_trunc(Ω_t),  ė_t = DF_trunc(Ω)·e_t + F_trunc(Ω) − F₃(Ω)
/// ```
///
/// G₃ ([`slow_manifold_third_order`]) is small in Ω where G₂ is not (a spin
/// term), but it carries the drift of the invariants the reduced ALE gets
/// wrong, and that adds up along L into the orientation's phase: with G₂
/// alone Ω₀ across the dipole had its orientation error claimed 2 to 6
/// times too small.
///
/// The reduced model's error is e_r; the truncated model's is e_t while it
/// is small (a few per cent of |Ω₀|) and Ω_t − Ω once it is not, plus the
/// reduced model's (the truncated model's error is first order, e_r second).
/// Both get a margin of 2 for the terms left out. Derivatives along e are
/// central differences; e_r and e_t are integrated in units of their own
/// scale (τ_f|Ω₀|)ⁿ|Ω₀|, so a tolerance relative to each holds however small
/// it is.
///
/// A run longer than [`ESTIMATE_MAX_STEPS`] is estimated over the span they
/// reach, φ_b radians, and carried on to φ as (φ/φ_b)²: the fastest an
/// error of Ω grows over many turns (a drift of the invariants shifts the
/// frequency, and the phase error grows as its integral).
pub fn general_errors(top: &GeneralTop, omega0: &Vec3, t: Real) -> ModelErrors {
    let tau = crate::sim::physical::general::fast_time(top);
    if radiates_nothing(&top.inertia(), &top.dipole(), omega0) || changes_nothing(tau, omega0, t) {
        return ModelErrors::EXACT;
    }
    let scale = omega0.norm();
    let eps = crate::sim::physical::general::fast_time(top) * scale;
    let (sigma_r, sigma_t) = (eps * eps * scale, eps * scale);
    // The slow manifold past the reduced ALE: G₂ + G₃ (G₃ carries the drift
    // of the invariants that adds up in the orientation's phase).
    let beyond = |w: &Vec3| slow_manifold_second_order(top, w) + slow_manifold_third_order(top, w);
    let along = |f: &dyn Fn(&Vec3) -> Vec3, at: &Vec3, e: &Vec3| -> Vec3 {
        directional_derivative(f, at, e, 1e-6)
    };
    let reduced = |w: &Vec3| top.reduced_ale_rhs(w);
    let truncated = |w: &Vec3| top.truncated_ale_rhs(w);
    let part = |y: &State<18>, i: usize| Vec3::new(y[i], y[i + 1], y[i + 2]);
    // The truncated model's error in units of σ_t: e_t while it is small,
    // Ω_t − Ω once it is not (the linearisation's reach); it drives both the
    // estimate of Ω and the orientation's.
    let truncated_error = |et: Vec3, wt: Vec3, w: Vec3| -> Vec3 {
        if et.norm() * sigma_t / scale < 0.05 {
            et
        } else {
            (wt - w) / sigma_t
        }
    };
    // The orientation errors o_r, o_t in the body frame, ȯ = δΩ − Ω × o, in
    // units of σ/|Ω₀| (radians per σ/|Ω₀|).
    let rhs = |_t: Real, y: &State<18>| -> State<18> {
        let (w, er, wt, et) = (part(y, 0), part(y, 3), part(y, 6), part(y, 9));
        let (or, ot) = (part(y, 12), part(y, 15));
        let g2 = beyond(&w);
        let f2 = reduced(&w) + g2;
        let der = along(&reduced, &w, &er) - g2 / sigma_r;
        let det = along(&truncated, &w, &et) + (truncated(&w) - f2) / sigma_t;
        let dwt = truncated(&wt);
        let dor = er * scale - w.cross(&or);
        let dot = truncated_error(et, wt, w) * scale - w.cross(&ot);
        let mut out = State::<18>::zeros();
        for (i, v) in [f2, der, dwt, det, dor, dot].iter().enumerate() {
            out.fixed_rows_mut::<3>(3 * i).copy_from(v);
        }
        out
    };
    let mut y0 = State::<18>::zeros();
    y0.fixed_rows_mut::<3>(0).copy_from(omega0);
    y0.fixed_rows_mut::<3>(6).copy_from(omega0);
    // NOTE: rtol 1e-8 on states of order one (the errors in their own units):
    // the estimate needs two digits, the margin for its reach is generous.
    let mut options = AdaptiveOptions::new(1e-8, 1e-10 * scale.min(1.0)).expect("valid tolerances");
    options.max_steps = ESTIMATE_MAX_STEPS;
    let mut worst = [0.0 as Real; 4];
    let mut take = |y: &State<18>| {
        let (w, er, wt, et) = (part(y, 0), part(y, 3), part(y, 6), part(y, 9));
        let e_r = er.norm() * sigma_r / scale;
        let e_t = truncated_error(et, wt, w).norm() * sigma_t / scale;
        worst[0] = worst[0].max(e_t);
        worst[1] = worst[1].max(e_r);
        worst[2] = worst[2].max(part(y, 15).norm() * sigma_t / scale);
        worst[3] = worst[3].max(part(y, 12).norm() * sigma_r / scale);
    };
    let reached = match Dop853::new(0.0, y0, options) {
        Ok(mut stepper) => {
            let mut reached = 0.0;
            while stepper.t() < t {
                if stepper.step(&rhs, t).is_err() {
                    break;
                }
                take(stepper.y());
                reached = stepper.t();
            }
            reached
        }
        Err(_) => 0.0,
    };
    // Beyond the span reached, the error grows at most like the square of
    // the turning (the first step's span stands in when none was taken).
    // The orientation's error is the integral of Ω's: one power more.
    let (stretch, stretch_o) = if reached >= t {
        (1.0, 1.0)
    } else {
        let over = t / reached.max(t * 1e-12).max(Real::MIN_POSITIVE);
        (over.powi(2), over.powi(3))
    };
    let [e_t, e_r] = [worst[0], worst[1]].map(|e| (GENERAL_MARGIN * e * stretch).min(2.0));
    let pi = std::f64::consts::PI as Real;
    let [o_t, o_r] = [worst[2], worst[3]].map(|e| (GENERAL_MARGIN * e * stretch_o).min(pi));
    ModelErrors {
        truncated: (e_t + e_r).min(2.0),
        reduced: e_r,
        truncated_orientation: (o_t + o_r).min(pi),
        reduced_orientation: o_r,
        exact: false,
    }
}
// ANCHOR_END: general_errors

/// The margin on the secular estimates: the drift differences are measured,
/// the swings are first-order averaging's own bound.
const SECULAR_MARGIN: Real = 1.5;

// ANCHOR: secular_errors
/// Both estimates for a run the secular model answers, where only E and |L|
/// are reported: how far each model's invariants stray from the physical
/// solution's, relative.
///
/// Beyond the paper (the secular drift of (3.3), the reduced (3.4) and the
/// slow manifold of (3.4) to second order).
///
/// ```text
/// ε_t = max |X_trunc − X₃|/X₃(0) + swing(T_trunc − T₃),   ε_r = max |X_red − X₃|/X₃(0) + swing(I(G₂ + G₃))
/// ```
///
/// X is E or |L| along the secular run of each law at `times` (the slow
/// manifold to third order, [`Law::Manifold`], in place of the physical
/// solution), relative to its value at the start (as the run's own error,
/// [`crate::sim::claim::secular_error`]), and the swing ([`swing`]) what the
/// torque difference moves the invariants within one turn, which averaging
/// leaves out. The runs are taken at a tolerance 100 times below `rtol` (at
/// most 10⁻¹²) so that their differences stand clear of it.
pub fn secular_errors(
    top: &GeneralTop,
    omega0: &Vec3,
    times: &[Real],
    rtol: Real,
) -> Result<ModelErrors, IntegrateError> {
    if radiates_nothing(&top.inertia(), &top.dipole(), omega0) {
        return Ok(ModelErrors::EXACT);
    }
    let tight = (rtol * 1e-2).clamp(1e-12, 1e-4);
    let run = |law| secular(top, law, omega0, times, tight);
    let (trunc, red, manifold) = (
        run(Law::Truncated)?,
        run(Law::Reduced)?,
        run(Law::Manifold)?,
    );
    let i = top.inertia();
    let scale = invariants(&i, omega0);
    let gap = |a: &SecularRun| secular_gap(&a.samples, &manifold.samples, scale);
    let beyond = |w: &Vec3| {
        i.component_mul(&(slow_manifold_second_order(top, w) + slow_manifold_third_order(top, w)))
    };
    let swing_r = swing(&i, omega0, beyond);
    let swing_t = swing(&i, omega0, |w| {
        top.truncated_torque(w) - top.reduced_torque(w) - beyond(w)
    });
    let reduced = (SECULAR_MARGIN * (gap(&red) + swing_r)).min(2.0);
    let truncated = (SECULAR_MARGIN * (gap(&trunc) + swing_t)).min(2.0);
    // NOTE: the secular model reports no orientation.
    Ok(ModelErrors {
        truncated: truncated.max(reduced),
        reduced,
        truncated_orientation: 0.0,
        reduced_orientation: 0.0,
        exact: false,
    })
}
// ANCHOR_END: secular_errors

/// The largest distance between two secular runs at the same times, in E
/// and in |L|, each relative to its value at the start, `scale` = (E₀, |L₀|)
/// ([`crate::sim::secular::invariants`]; 1 for a top at rest, whose
/// invariants stay 0).
pub fn secular_gap(a: &[SecularSample], b: &[SecularSample], scale: (Real, Real)) -> Real {
    let unit = |x: Real| if x > 0.0 { x } else { 1.0 };
    let (e0, l0) = (unit(scale.0), unit(scale.1));
    a.iter()
        .zip(b)
        .map(|(x, y)| ((x.energy - y.energy).abs() / e0).max((x.l_norm - y.l_norm).abs() / l0))
        .fold(0.0, Real::max)
}
