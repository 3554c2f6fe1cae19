//! An independent reference for the symmetric top under the full ALE (3.4)
//! (its physical, runaway-free solution) and under the reduced ALE
//! (4.12)–(4.14), written here from the derivation and calling nothing of
//! spintop's but its vector types.
//!
//! **The slow manifold.** With z = Ω₁ + iΩ₂ (units I₁ = 1), (3.4) reads
//! τz̈ = ż + iΩ̃₃z + τ(|z|² + Ω₃²)z − 2iτΩ₃ż, Ω₃ constant. In the frame
//! that turns with the free precession, z = e^{−iΩ̃₃t}w, it loses its fast
//! rotation: τw″ = (1 − 2iτk)w′ + τ(u + k²)w, u = |w|², k = (I₃/I₁)Ω₃.
//! Its physical solutions are w′ = g(u)w; with u′ = 2u Re g and
//! w″ = (2ug′ Re g + g²)w, g obeys the invariance equation
//!
//! ```text
//! 2τu g′ Re g = g(1 − 2iτk) + τ(u + k²) − τg²
//! ```
//!
//! Near rest g is the series Σ cₘuᵐ, exact in τk: c₀ is the slow root of
//! τc² − (1 − 2iτk)c − τk² = 0, and for m ≥ 1
//! cₘ[(1 − 2iτk) − 2τc₀ − 2τm Re c₀] = τ[Σ cⱼcₘ₋ⱼ + 2Σ j cⱼ Re cₘ₋ⱼ] − τδₘ₁
//! (sums over 1 ≤ j ≤ m − 1). Where the series stops converging, g is
//! integrated upward in s = ln u by RK4 from the series' last good point
//! (upward the manifold attracts, so the integration is stable). The reduced
//! model is the same picture with g = −τ(u + k²).
//!
//! **The motion.** Along s, t = ∫ ds/(2|Re g|) and the phase of w is
//! Φ = ∫ Im g dt, both by Gauss–Legendre quadrature; a time is turned into
//! s by Newton's method. Then Ω = (e^{−iΩ̃₃t}√u e^{i(χ₀+Φ)}, Ω₃).
//!
//! **The orientation.** O = P·R_z(β) with β = Ω̃₃t − χ₀ − Φ(t): then
//! P′ = P ω̂_P with ω_P = (√u, 0, k + Im g), which has nothing fast in it.
//! P is stepped along s by the fourth-order Magnus method (two Gauss points),
//! and once √u no longer moves P by a rounding, P turns about its third axis
//! at the constant rate k + Im c₀, in closed form.

use nalgebra::{Complex, Rotation3, Unit};
use spintop::math::{Mat3, Real, Vec3};

type C = Complex<Real>;

/// Which slow manifold: the physical solution of (3.4) or the reduced model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Manifold {
    /// (3.4), its physical solution.
    Physical,
    /// (4.12)–(4.14): g = −τ(u + k²).
    Reduced,
}

/// The Magnus steps: at most this far in s, and this many radians.
const MAGNUS_S: Real = 0.01;
const MAGNUS_TURN: Real = 0.05;

/// Terms of the series in u.
const TERMS: usize = 90;

/// Gauss–Legendre nodes and weights on [−1, 1], 10 points.
const GL_X: [Real; 5] = [
    0.148_874_338_981_631_2,
    0.433_395_394_129_247_2,
    0.679_409_568_299_024_4,
    0.865_063_366_688_984_5,
    0.973_906_528_517_171_7,
];
const GL_W: [Real; 5] = [
    0.295_524_224_714_752_9,
    0.269_266_719_309_996_4,
    0.219_086_362_515_982,
    0.149_451_349_150_580_6,
    0.066_671_344_308_688_1,
];

/// One panel of the quadrature of t and Φ along s (descending).
#[derive(Clone, Copy, Debug)]
struct Panel {
    s_top: Real,
    s_bot: Real,
    /// t and Φ at s_top.
    t_top: Real,
    phi_top: Real,
}

/// The reference for one top and one Ω₀.
pub struct Reference {
    manifold: Manifold,
    tau: Real,
    k: Real,
    alpha: Real,
    omega3: Real,
    chi0: Real,
    s0: Real,
    /// u at t = 0: s is ln(u/u₀), so that a run that hardly decays keeps its
    /// digits in s (ln u itself rounds at 1e-15, which dt/ds turns into 1e-9
    /// of time where u and k² are small).
    u0: Real,
    series: Vec<C>,
    /// The series holds for s ≤ s_sw.
    s_sw: Real,
    /// RK4 nodes (s, g) upward from s_sw to s0.
    nodes: Vec<(Real, C)>,
    h_ode: Real,
    panels: Vec<Panel>,
    /// Below s_tail (k ≠ 0), g = c₀ to rounding: (s_tail, t, Φ there).
    tail: Option<(Real, Real, Real)>,
    /// A top that does not radiate (Ω⊥₀ = 0).
    steady: bool,
    step_scale: Real,
}

impl Reference {
    /// The reference for I₃/I₁ = `ratio`, τ = `tau`, from Ω₀, valid to
    /// `t_max`; `step_scale` scales the steps (1 normally, ½ to check).
    pub fn new(
        manifold: Manifold,
        ratio: Real,
        tau: Real,
        omega0: Vec3,
        t_max: Real,
        step_scale: Real,
    ) -> Self {
        let k = ratio * omega0.z;
        let alpha = (1.0 - ratio) * omega0.z;
        let u0 = omega0.x * omega0.x + omega0.y * omega0.y;
        let mut r = Reference {
            manifold,
            tau,
            k,
            alpha,
            omega3: omega0.z,
            chi0: omega0.y.atan2(omega0.x),
            s0: 0.0,
            u0,
            series: Vec::new(),
            s_sw: Real::NEG_INFINITY,
            nodes: Vec::new(),
            h_ode: 0.0,
            panels: Vec::new(),
            tail: None,
            steady: u0 == 0.0,
            step_scale,
        };
        if r.steady {
            return r;
        }
        if manifold == Manifold::Physical {
            r.series = series(tau, k);
            r.s_sw = (r.series_limit(u0) / u0).ln();
            r.integrate_upward();
        }
        r.build_panels(t_max);
        r
    }

    /// u at s = ln(u/u₀).
    fn u(&self, s: Real) -> Real {
        self.u0 * s.exp()
    }

    /// The largest u ≤ u₀ where the series has converged to 1e-19.
    fn series_limit(&self, u0: Real) -> Real {
        let mut u = u0;
        loop {
            let head = eval_series(&self.series, u).norm();
            let tail = (TERMS - 6..TERMS)
                .map(|m| self.series[m].norm() * u.powi(m as i32))
                .fold(0.0, Real::max);
            if tail <= 1e-19 * head || u < 1e-300 {
                return u;
            }
            u *= 0.9;
        }
    }

    /// dg/ds from the invariance equation.
    fn dg_ds(&self, s: Real, g: C) -> C {
        let u = self.u(s);
        let i = C::new(0.0, 1.0);
        let tau = self.tau;
        let n = g * (C::new(1.0, 0.0) - i * (2.0 * tau * self.k)) + tau * (u + self.k * self.k)
            - g * g * tau;
        n / (2.0 * tau * g.re)
    }

    fn rk4(&self, s: Real, g: C, h: Real) -> C {
        let k1 = self.dg_ds(s, g);
        let k2 = self.dg_ds(s + 0.5 * h, g + k1 * (0.5 * h));
        let k3 = self.dg_ds(s + 0.5 * h, g + k2 * (0.5 * h));
        let k4 = self.dg_ds(s + h, g + k3 * h);
        g + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
    }

    fn integrate_upward(&mut self) {
        if self.s_sw >= self.s0 {
            return;
        }
        let g = eval_series(&self.series, self.u(self.s_sw));
        // Stiffness of the attraction: |∂(dg/ds)/∂g| ≈ |1 − 2iτk − 2τg|/(2τ|Re g|).
        let lam = (C::new(1.0, -2.0 * self.tau * self.k) - g * (2.0 * self.tau)).norm()
            / (2.0 * self.tau * g.re.abs());
        let h = (2e-4 as Real).min(0.1 / lam) * self.step_scale;
        let n = ((self.s0 - self.s_sw) / h).ceil() as usize;
        let h = (self.s0 - self.s_sw) / n as Real;
        self.h_ode = h;
        self.nodes.reserve(n + 1);
        let mut g = g;
        self.nodes.push((self.s_sw, g));
        for j in 0..n {
            let s = self.s_sw + j as Real * h;
            g = self.rk4(s, g, h);
            self.nodes.push((self.s_sw + (j + 1) as Real * h, g));
        }
    }

    /// g at s (s ≤ s₀).
    pub fn g(&self, s: Real) -> C {
        match self.manifold {
            Manifold::Reduced => C::new(-self.tau * (self.u(s) + self.k * self.k), 0.0),
            Manifold::Physical => {
                if s <= self.s_sw || self.nodes.is_empty() {
                    return eval_series(&self.series, self.u(s));
                }
                let j = (((s - self.s_sw) / self.h_ode).floor() as usize).min(self.nodes.len() - 1);
                let (sj, gj) = self.nodes[j];
                if s == sj {
                    gj
                } else {
                    self.rk4(sj, gj, s - sj)
                }
            }
        }
    }

    /// dt/d(−s) and dΦ/d(−s) at s.
    fn rates(&self, s: Real) -> (Real, Real) {
        let g = self.g(s);
        let f = -1.0 / (2.0 * g.re);
        (f, g.im * f)
    }

    /// ∫ from a to b (a < b) of the two rates, 10-point Gauss–Legendre.
    fn quad(&self, a: Real, b: Real) -> (Real, Real) {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let (mut t, mut p) = (0.0, 0.0);
        for (x, w) in GL_X.iter().zip(GL_W) {
            for sign in [-1.0, 1.0] {
                let (f, q) = self.rates(mid + sign * half * x);
                t += w * f;
                p += w * q;
            }
        }
        (t * half, p * half)
    }

    fn c0(&self) -> C {
        match self.manifold {
            Manifold::Reduced => C::new(-self.tau * self.k * self.k, 0.0),
            Manifold::Physical => self.series[0],
        }
    }

    /// |c₁|: how fast g leaves c₀.
    fn c1(&self) -> Real {
        match self.manifold {
            Manifold::Reduced => self.tau,
            Manifold::Physical => self.series[1].norm(),
        }
    }

    fn build_panels(&mut self, t_max: Real) {
        let width = 0.02 * self.step_scale;
        let c0 = self.c0();
        // Below this u, g = c₀ to rounding.
        let s_tail = if c0.norm() > 0.0 {
            Some((1e-18 * c0.norm() / self.c1() / self.u0).ln())
        } else {
            None
        };
        let (mut s, mut t, mut phi) = (self.s0, 0.0, 0.0);
        // Neumaier's compensation of the sums (thousands of panels).
        let (mut t_c, mut phi_c) = (0.0, 0.0);
        loop {
            if let Some(st) = s_tail
                && s <= st
            {
                self.tail = Some((s, t + t_c, phi + phi_c));
                return;
            }
            if t + t_c > t_max {
                return;
            }
            let mut bot = s - width;
            if let Some(st) = s_tail
                && bot < st
                && s > st
            {
                bot = st;
            }
            let (dt, dp) = self.quad(bot, s);
            self.panels.push(Panel {
                s_top: s,
                s_bot: bot,
                t_top: t + t_c,
                phi_top: phi + phi_c,
            });
            neumaier(&mut t, &mut t_c, dt);
            neumaier(&mut phi, &mut phi_c, dp);
            s = bot;
        }
    }

    /// s, Φ and t at the s found for time t: Newton's s* is within a
    /// rounding of s, but dt/ds is large where u and k² are small, so the
    /// time t* = t(s*) is returned too, and the callers carry the motion the
    /// remaining t − t* on.
    pub fn s_at(&self, t: Real) -> (Real, Real, Real) {
        if let Some((st, tt, pt)) = self.tail
            && t >= tt
        {
            let c0 = self.c0();
            let f0 = -1.0 / (2.0 * c0.re);
            let ds = (t - tt) / f0;
            return (st - ds, pt + ds * c0.im * f0, t);
        }
        // The panel whose span of t holds t.
        let i = self.panels.partition_point(|p| p.t_top <= t).max(1) - 1;
        let p = self.panels[i];
        // Newton on s within the panel: t(s) = t_top + ∫_s^{s_top} F.
        let mut s = p.s_top;
        for _ in 0..60 {
            let (dt, _) = self.quad(s, p.s_top);
            let miss = p.t_top + dt - t;
            let (f, _) = self.rates(s);
            let next = (s + miss / f).clamp(p.s_bot - 1.0, p.s_top);
            if (next - s).abs() <= 1e-16 * (1e-300 + s.abs()) {
                s = next;
                break;
            }
            s = next;
        }
        let (dt, dp) = self.quad(s, p.s_top);
        (s, p.phi_top + dp, p.t_top + dt)
    }

    /// Ω at time t.
    pub fn omega(&self, t: Real) -> Vec3 {
        if self.steady {
            return Vec3::new(0.0, 0.0, self.omega3);
        }
        let (s, phi, t_s) = self.s_at(t);
        let g = self.g(s);
        let w = C::from_polar(self.u(s).sqrt(), self.chi0 + phi) * (g * (t - t_s)).exp();
        let z = w * C::from_polar(1.0, -self.alpha * t);
        Vec3::new(z.re, z.im, self.omega3)
    }

    /// ω_P at s.
    fn omega_p(&self, s: Real) -> Vec3 {
        let g = self.g(s);
        Vec3::new(self.u(s).sqrt(), 0.0, self.k + g.im)
    }

    /// The orientations at `times` (ascending) from O(0) = `o0`.
    pub fn orientations(&self, o0: &Mat3, times: &[Real]) -> Vec<Mat3> {
        let rot = |m: Mat3| Rotation3::from_matrix_unchecked(m);
        if self.steady {
            return times.iter().map(|&t| o0 * rot_z(self.omega3 * t)).collect();
        }
        let targets: Vec<(Real, Real, Real)> = times.iter().map(|&t| self.s_at(t)).collect();
        let mut p = rot(o0 * rot_z(self.chi0));
        let mut s = self.s0;
        // Past this s, √u turns P by less than a rounding: P turns about its
        // third axis at k + Im c₀ alone.
        let c0 = self.c0();
        let s_still = if c0.re < 0.0 {
            let f0 = -1.0 / (2.0 * c0.re);
            Some(((1e-17 / (2.0 * f0)).powi(2) / self.u0).ln())
        } else {
            None
        };
        let mut still: Option<(Real, Rotation3<Real>)> = None;
        let mut out = Vec::with_capacity(times.len());
        for (&t, &(target, phi, t_s)) in times.iter().zip(&targets) {
            while still.is_none() && s > target {
                if let Some(ss) = s_still
                    && s <= ss
                {
                    let (t_here, _) = self.time_at_s(s);
                    still = Some((t_here, p));
                    break;
                }
                let (f, _) = self.rates(s);
                let rate = self.omega_p(s).norm() * f;
                let step = (MAGNUS_S * self.step_scale).min(MAGNUS_TURN * self.step_scale / rate);
                let next = if step >= s - target { target } else { s - step };
                // NOTE: the step is the difference of the rounded ends, so
                // that the steps add up to the span exactly (dt/ds is large
                // where u ≪ k², and a rounding of s per step adds up).
                let h = s - next;
                p *= Rotation3::from_scaled_axis(self.magnus6(s, h));
                s = next;
            }
            let (p_t, phi) = match still {
                Some((t_still, p_still)) => {
                    let rate = self.k + c0.im;
                    let turn = Rotation3::from_axis_angle(
                        &Unit::new_unchecked(Vec3::z()),
                        rate * (t - t_still),
                    );
                    (p_still * turn, phi)
                }
                None => {
                    // Carried from t* = t(s*) to t at the rate there.
                    let dt = t - t_s;
                    let rest = Rotation3::from_scaled_axis(self.omega_p(target) * dt);
                    (p * rest, phi + self.g(target).im * dt)
                }
            };
            let beta = self.alpha * t - self.chi0 - phi;
            out.push(p_t.matrix() * rot_z(beta));
        }
        out
    }

    /// The rotation vector of one sixth-order Magnus step of P′ = P ω̂_P
    /// along σ = −s, from s to s − h (three Gauss points; Blanes, Casas,
    /// Oteo and Ros, Phys. Rep. 470 (2009) 151, Sec. 5). For Y = Pᵀ,
    /// Y′ = −ω̂ Y: the method is written for Y′ = ÂY and P steps by the
    /// transpose.
    fn magnus6(&self, s: Real, h: Real) -> Vec3 {
        let r = 0.15_f64.sqrt();
        let a = |x: Real| -(self.omega_p(x) * self.rates(x).0);
        let (b1, b2, b3) = (a(s - (0.5 - r) * h), a(s - 0.5 * h), a(s - (0.5 + r) * h));
        let al1 = b2 * h;
        let al2 = (b3 - b1) * (15.0_f64.sqrt() * h / 3.0);
        let al3 = (b3 - b2 * 2.0 + b1) * (10.0 * h / 3.0);
        let c12 = al1.cross(&al2);
        let left = -(al1 * 20.0) - al3 + c12;
        let right = al2 - al1.cross(&(al3 * 2.0 + c12)) / 60.0;
        let omega_y = al1 + al3 / 12.0 + left.cross(&right) / 240.0;
        -omega_y
    }

    /// t and Φ at s (s ≤ s₀).
    fn time_at_s(&self, s: Real) -> (Real, Real) {
        if let Some((st, tt, pt)) = self.tail
            && s <= st
        {
            let c0 = self.c0();
            let f0 = -1.0 / (2.0 * c0.re);
            return (tt + (st - s) * f0, pt + (st - s) * f0 * c0.im);
        }
        let i = self
            .panels
            .partition_point(|p| p.s_bot > s)
            .min(self.panels.len() - 1);
        let p = self.panels[i];
        let (dt, dp) = self.quad(s, p.s_top);
        (p.t_top + dt, p.phi_top + dp)
    }
}

/// sum += x with Neumaier's compensation in `comp`.
fn neumaier(sum: &mut Real, comp: &mut Real, x: Real) {
    let t = *sum + x;
    *comp += if sum.abs() >= x.abs() {
        (*sum - t) + x
    } else {
        (x - t) + *sum
    };
    *sum = t;
}

fn rot_z(a: Real) -> Mat3 {
    let (s, c) = a.sin_cos();
    Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// The series of g in u, exact in τk.
fn series(tau: Real, k: Real) -> Vec<C> {
    let one = C::new(1.0, 0.0);
    let a = C::new(1.0, -2.0 * tau * k);
    let root = C::new(1.0, -4.0 * tau * k).sqrt();
    // The slow root −k²/c_fast, with no cancellation as τk → 0.
    let fast = (a + root) / (2.0 * tau);
    let c0 = if k == 0.0 {
        C::new(0.0, 0.0)
    } else {
        -(k * k) / fast
    };
    let mut c = vec![c0];
    for m in 1..TERMS {
        let d = a - c0 * (2.0 * tau) - one * (2.0 * tau * m as Real * c0.re);
        let mut rhs = C::new(0.0, 0.0);
        for j in 1..m {
            rhs += c[j] * c[m - j] + c[j] * (2.0 * j as Real * c[m - j].re);
        }
        rhs *= tau;
        if m == 1 {
            rhs -= tau;
        }
        c.push(rhs / d);
    }
    c
}

fn eval_series(c: &[C], u: Real) -> C {
    c.iter()
        .rev()
        .fold(C::new(0.0, 0.0), |acc, cm| acc * u + cm)
}

/// The angle of the rotation between two orientations.
pub fn angle_between(a: &Mat3, b: &Mat3) -> Real {
    let r = a.transpose() * b;
    let skew = Vec3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    );
    let cos = 0.5 * (r.trace() - 1.0);
    (0.5 * skew.norm()).atan2(cos)
}

/// The truncated model (4.2)–(4.4) in closed form, (4.6)–(4.7), and its
/// orientation, O(t) = Rot(n_L, |L₀|ϑ)·O(0)·R_z(Ω̃₃₀ϑ) (the physics notes),
/// written here from the paper (τ and I₁ as given, I₁ = 1).
pub fn truncated(ratio: Real, tau: Real, omega0: Vec3, o0: &Mat3, t: Real) -> (Vec3, Mat3) {
    let a0sq = omega0.x * omega0.x + omega0.y * omega0.y;
    let x = 2.0 * tau * a0sq * t;
    let r = (1.0 + x).sqrt();
    // ϑ = (R − 1)/(τΩ⊥₀²) = 2t/(R + 1), no cancellation.
    let vartheta = 2.0 * t / (r + 1.0);
    let alpha0 = (1.0 - ratio) * omega0.z;
    let z0 = C::new(omega0.x, omega0.y);
    let z = z0 * C::from_polar(1.0 / r, -alpha0 * vartheta);
    let omega = Vec3::new(z.re, z.im, omega0.z / r);
    let l0 = o0 * Vec3::new(omega0.x, omega0.y, ratio * omega0.z);
    let lab = if l0.norm() > 0.0 {
        Rotation3::from_axis_angle(&Unit::new_normalize(l0), l0.norm() * vartheta).into_inner()
    } else {
        Mat3::identity()
    };
    (omega, lab * o0 * rot_z(alpha0 * vartheta))
}
