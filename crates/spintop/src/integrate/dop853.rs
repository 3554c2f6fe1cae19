//! Hairer's DOP853: an explicit Runge–Kutta method of order 8 with embedded
//! error estimators of orders 5 and 3, and an order-7 dense output.
//!
//! Method: the 12-stage order-8 formula of Dormand & Prince as tuned by Hairer
//! (DOP853), FSAL (the 13th evaluation, `f(t + h, y_new)`, is the first stage of
//! the next step, so an attempt costs 12 evaluations). Global order 8.
//! Reference: E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//! Equations I: Nonstiff Problems*, 2nd ed., Springer 1993, Sec. II.5 and II.10,
//! and Hairer's Fortran code `DOP853`. The coefficients are those of `DOP853`
//! (`dop853.f`), checked against SciPy's copy
//! (`scipy/integrate/_ivp/dop853_coefficients.py`); the order tests in
//! `tests/numerics/integrators.rs` (global order 8, dense order 7) are the proof they are
//! right.
//!
//! Counting ([`Stats`]): `rhs_evals = 12·(steps + rejected) + 1 + g + 3·d`, where
//! the 1 is `f(t0, y0)` before the first step (again after every
//! [`Stepper::reset`]), `g = 1` if the initial step is guessed (`hinit`), and `d`
//! is the number of accepted steps inside which [`Stepper::dense`] was called at
//! least once. The step budget counts accepted plus rejected attempts.
// NOTE: the coefficients are kept digit for digit as Hairer published them (30
// significant digits) so they can be compared with the listing by eye; the
// compiler rounds each to the nearest f64.
#![allow(clippy::excessive_precision)]

use crate::integrate::control::stepper_getters;
use crate::integrate::explicit::{Core, EmbeddedPair, core_accessors};
use crate::integrate::{AdaptiveOptions, IntegrateError, Rhs, Stats, Stepper};
use crate::math::{Real, State};

/// Stages of one step.
const STAGES: usize = 12;
/// Stages including `f(t + h, y_new)` and the 3 extra dense-output stages.
const STAGES_EXT: usize = 16;

/// Fill a matrix from its non-zero entries (keeps the tables below readable in
/// the same `A[i][j] = …` layout as Hairer's listing).
const fn sparse<const R: usize, const C: usize>(
    entries: &[(usize, usize, Real)],
) -> [[Real; C]; R] {
    let mut m = [[0.0; C]; R];
    let mut n = 0;
    while n < entries.len() {
        let (i, j, v) = entries[n];
        m[i][j] = v;
        n += 1;
    }
    m
}

/// Nodes `c_i` (stages 0..12 of the step, 13..15 the dense-output stages).
const C: [Real; STAGES_EXT] = [
    0.0,
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
    1.0,
    0.1,
    0.2,
    0.777777777777777777777777777778,
];

/// Runge–Kutta matrix; row 12 holds the order-8 weights `b` (FSAL), rows 13–15
/// the extra dense-output stages.
const A: [[Real; STAGES_EXT]; STAGES_EXT] = sparse(&[
    (1, 0, 5.26001519587677318785587544488e-2),
    (2, 0, 1.97250569845378994544595329183e-2),
    (2, 1, 5.91751709536136983633785987549e-2),
    (3, 0, 2.95875854768068491816892993775e-2),
    (3, 2, 8.87627564304205475450678981324e-2),
    (4, 0, 2.41365134159266685502369798665e-1),
    (4, 2, -8.84549479328286085344864962717e-1),
    (4, 3, 9.24834003261792003115737966543e-1),
    (5, 0, 3.7037037037037037037037037037e-2),
    (5, 3, 1.70828608729473871279604482173e-1),
    (5, 4, 1.25467687566822425016691814123e-1),
    (6, 0, 3.7109375e-2),
    (6, 3, 1.70252211019544039314978060272e-1),
    (6, 4, 6.02165389804559606850219397283e-2),
    (6, 5, -1.7578125e-2),
    (7, 0, 3.70920001185047927108779319836e-2),
    (7, 3, 1.70383925712239993810214054705e-1),
    (7, 4, 1.07262030446373284651809199168e-1),
    (7, 5, -1.53194377486244017527936158236e-2),
    (7, 6, 8.27378916381402288758473766002e-3),
    (8, 0, 6.24110958716075717114429577812e-1),
    (8, 3, -3.36089262944694129406857109825),
    (8, 4, -8.68219346841726006818189891453e-1),
    (8, 5, 2.75920996994467083049415600797e1),
    (8, 6, 2.01540675504778934086186788979e1),
    (8, 7, -4.34898841810699588477366255144e1),
    (9, 0, 4.77662536438264365890433908527e-1),
    (9, 3, -2.48811461997166764192642586468),
    (9, 4, -5.90290826836842996371446475743e-1),
    (9, 5, 2.12300514481811942347288949897e1),
    (9, 6, 1.52792336328824235832596922938e1),
    (9, 7, -3.32882109689848629194453265587e1),
    (9, 8, -2.03312017085086261358222928593e-2),
    (10, 0, -9.3714243008598732571704021658e-1),
    (10, 3, 5.18637242884406370830023853209),
    (10, 4, 1.09143734899672957818500254654),
    (10, 5, -8.14978701074692612513997267357),
    (10, 6, -1.85200656599969598641566180701e1),
    (10, 7, 2.27394870993505042818970056734e1),
    (10, 8, 2.49360555267965238987089396762),
    (10, 9, -3.0467644718982195003823669022),
    (11, 0, 2.27331014751653820792359768449),
    (11, 3, -1.05344954667372501984066689879e1),
    (11, 4, -2.00087205822486249909675718444),
    (11, 5, -1.79589318631187989172765950534e1),
    (11, 6, 2.79488845294199600508499808837e1),
    (11, 7, -2.85899827713502369474065508674),
    (11, 8, -8.87285693353062954433549289258),
    (11, 9, 1.23605671757943030647266201528e1),
    (11, 10, 6.43392746015763530355970484046e-1),
    (12, 0, 5.42937341165687622380535766363e-2),
    (12, 5, 4.45031289275240888144113950566),
    (12, 6, 1.89151789931450038304281599044),
    (12, 7, -5.8012039600105847814672114227),
    (12, 8, 3.1116436695781989440891606237e-1),
    (12, 9, -1.52160949662516078556178806805e-1),
    (12, 10, 2.01365400804030348374776537501e-1),
    (12, 11, 4.47106157277725905176885569043e-2),
    (13, 0, 5.61675022830479523392909219681e-2),
    (13, 6, 2.53500210216624811088794765333e-1),
    (13, 7, -2.46239037470802489917441475441e-1),
    (13, 8, -1.24191423263816360469010140626e-1),
    (13, 9, 1.5329179827876569731206322685e-1),
    (13, 10, 8.20105229563468988491666602057e-3),
    (13, 11, 7.56789766054569976138603589584e-3),
    (13, 12, -8.298e-3),
    (14, 0, 3.18346481635021405060768473261e-2),
    (14, 5, 2.83009096723667755288322961402e-2),
    (14, 6, 5.35419883074385676223797384372e-2),
    (14, 7, -5.49237485713909884646569340306e-2),
    (14, 10, -1.08347328697249322858509316994e-4),
    (14, 11, 3.82571090835658412954920192323e-4),
    (14, 12, -3.40465008687404560802977114492e-4),
    (14, 13, 1.41312443674632500278074618366e-1),
    (15, 0, -4.28896301583791923408573538692e-1),
    (15, 5, -4.69762141536116384314449447206),
    (15, 6, 7.68342119606259904184240953878),
    (15, 7, 4.06898981839711007970213554331),
    (15, 8, 3.56727187455281109270669543021e-1),
    (15, 12, -1.39902416515901462129418009734e-3),
    (15, 13, 2.9475147891527723389556272149),
    (15, 14, -9.15095847217987001081870187138),
]);

/// Order-8 weights: the row of `A` that defines the FSAL stage.
const B: [Real; STAGES_EXT] = A[12];

/// Hairer's `bhh1…bhh3`: the order-3 embedded weights on k1, k9, k12.
const BHH: [(usize, Real); 3] = [
    (0, 0.244094488188976377952755905512),
    (8, 0.733846688281611857341361741547),
    (11, 0.220588235294117647058823529412e-1),
];

/// `E3 = b − b̂₃`: the order-3 error estimate is `h Σ E3_i k_i`.
const E3: [Real; STAGES] = {
    let mut e = [0.0; STAGES];
    let mut i = 0;
    while i < STAGES {
        e[i] = B[i];
        i += 1;
    }
    let mut n = 0;
    while n < BHH.len() {
        e[BHH[n].0] -= BHH[n].1;
        n += 1;
    }
    e
};

/// Hairer's `er1…er12`: the order-5 error estimate is `h Σ E5_i k_i`.
const E5: [Real; STAGES] = [
    0.1312004499419488073250102996e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
];

/// Dense-output coefficients `d4…d7` of Hairer's `DOP853` (rows) over the 16
/// extended stages (columns).
const D: [[Real; STAGES_EXT]; 4] = sparse(&[
    (0, 0, -0.84289382761090128651353491142e1),
    (0, 5, 0.56671495351937776962531783590),
    (0, 6, -0.30689499459498916912797304727e1),
    (0, 7, 0.23846676565120698287728149680e1),
    (0, 8, 0.21170345824450282767155149946e1),
    (0, 9, -0.87139158377797299206789907490),
    (0, 10, 0.22404374302607882758541771650e1),
    (0, 11, 0.63157877876946881815570249290),
    (0, 12, -0.88990336451333310820698117400e-1),
    (0, 13, 0.18148505520854727256656404962e2),
    (0, 14, -0.91946323924783554000451984436e1),
    (0, 15, -0.44360363875948939664310572000e1),
    (1, 0, 0.10427508642579134603413151009e2),
    (1, 5, 0.24228349177525818288430175319e3),
    (1, 6, 0.16520045171727028198505394887e3),
    (1, 7, -0.37454675472269020279518312152e3),
    (1, 8, -0.22113666853125306036270938578e2),
    (1, 9, 0.77334326684722638389603898808e1),
    (1, 10, -0.30674084731089398182061213626e2),
    (1, 11, -0.93321305264302278729567221706e1),
    (1, 12, 0.15697238121770843886131091075e2),
    (1, 13, -0.31139403219565177677282850411e2),
    (1, 14, -0.93529243588444783865713862664e1),
    (1, 15, 0.35816841486394083752465898540e2),
    (2, 0, 0.19985053242002433820987653617e2),
    (2, 5, -0.38703730874935176555105901742e3),
    (2, 6, -0.18917813819516756882830838328e3),
    (2, 7, 0.52780815920542364900561016686e3),
    (2, 8, -0.11573902539959630126141871134e2),
    (2, 9, 0.68812326946963000169666922661e1),
    (2, 10, -0.10006050966910838403183860980e1),
    (2, 11, 0.77771377980534432092869265740),
    (2, 12, -0.27782057523535084065932004339e1),
    (2, 13, -0.60196695231264120758267380846e2),
    (2, 14, 0.84320405506677161018159903784e2),
    (2, 15, 0.11992291136182789328035130030e2),
    (3, 0, -0.25693933462703749003312586129e2),
    (3, 5, -0.15418974869023643374053993627e3),
    (3, 6, -0.23152937917604549567536039109e3),
    (3, 7, 0.35763911791061412378285349910e3),
    (3, 8, 0.93405324183624310003907691704e2),
    (3, 9, -0.37458323136451633156875139351e2),
    (3, 10, 0.10409964950896230045147246184e3),
    (3, 11, 0.29840293426660503123344363579e2),
    (3, 12, -0.43533456590011143754432175058e2),
    (3, 13, 0.96324553959188282948394950600e2),
    (3, 14, -0.39177261675615439165231486172e2),
    (3, 15, -0.14972683625798562581422125276e3),
]);

// Step-size control of Hairer's DOP853 (β = 0: a plain I controller).
// NOTE: Hairer's DOP853 ships with β = 0 (no PI term): at order 8 the steps are
// long and the controller rarely works near the stability boundary, where the PI
// term pays off; the tighter ratio limits [0.333, 6] keep it calm instead.
const SAFETY: Real = 0.9;
/// Smallest step ratio h_new/h (Hairer's `fac1`).
const FAC_MIN: Real = 0.333;
/// Largest step ratio h_new/h (Hairer's `fac2`).
const FAC_MAX: Real = 6.0;
/// Controller exponent 1/(q+1) with q = 7, the order the combined estimate mimics.
const EXPO: Real = 1.0 / 8.0;

/// `Σ_j coeffs[j]·k[j]` over the first `n` stages, skipping zero coefficients.
#[inline(always)]
fn combine<const N: usize>(coeffs: &[Real], k: &[State<N>], n: usize) -> State<N> {
    let mut s = State::<N>::zeros();
    for (c, kj) in coeffs.iter().zip(k.iter()).take(n) {
        if *c != 0.0 {
            s.axpy(*c, kj, 1.0);
        }
    }
    s
}

/// Compute stages 1..12 and the order-8 solution, then `k[12] = f(t_new, y_new)`.
/// `k[0]` must hold `f(t, y)`. Costs 12 evaluations.
#[inline(always)]
fn attempt<const N: usize, R: Rhs<N>>(
    rhs: &R,
    t: Real,
    y: &State<N>,
    h: Real,
    t_new: Real,
    k: &mut [State<N>; STAGES_EXT],
) -> State<N> {
    // NOTE: one stage per line rather than a loop over the stages: with the
    // stage index a literal, the compiler sees each row of A as constants,
    // unrolls the sum and drops the zero entries (a third fewer instructions
    // per step than the loop). The arithmetic is the same, to the bit.
    macro_rules! stage {
        ($($s:literal)*) => {$(
            let dy = combine(&A[$s], &k[..], $s);
            k[$s] = rhs.eval(t + C[$s] * h, &(y + dy * h));
        )*};
    }
    stage!(1 2 3 4 5 6 7 8 9 10 11);
    let y_new = y + combine(&B, &k[..], STAGES) * h;
    k[STAGES] = rhs.eval(t_new, &y_new);
    y_new
}

/// The two raw error vectors `Σ E5_i k_i` and `Σ E3_i k_i` (without the factor h).
#[inline(always)]
fn raw_errors<const N: usize>(k: &[State<N>; STAGES_EXT]) -> (State<N>, State<N>) {
    (combine(&E5, &k[..], STAGES), combine(&E3, &k[..], STAGES))
}

/// Hairer's combined error norm `|h|·‖e5‖² / sqrt(‖e5‖² + 0.01‖e3‖²)` with RMS
/// norms over the components scaled by `scale`.
// NOTE: the order-5 estimate alone (O(h⁶)) would let the controller take steps
// that are too long when it happens to be small by cancellation; blending in the
// order-3 estimate makes the norm behave like O(h⁸) (an order-7 estimate, hence
// the exponent 1/8) while staying robust (HNW I, Sec. II.10, "DOP853").
fn error_norm<const N: usize>(e5: &State<N>, e3: &State<N>, h: Real, scale: &State<N>) -> Real {
    let mut s5 = 0.0;
    let mut s3 = 0.0;
    for i in 0..N {
        if e5[i] != 0.0 {
            s5 += (e5[i] / scale[i]).powi(2);
        }
        if e3[i] != 0.0 {
            s3 += (e3[i] / scale[i]).powi(2);
        }
    }
    let mut deno = s5 + 0.01 * s3;
    if deno <= 0.0 {
        deno = 1.0;
    }
    h.abs() * s5 / (deno * N.max(1) as Real).sqrt()
}

/// DOP853: order 8 with the 5/3 combined error estimate and order-7 dense output.
#[derive(Clone, Debug)]
pub struct Dop853<const N: usize> {
    /// Position, memory and statistics (the shared step loop's).
    core: Core<N>,
    /// The stages of the last accepted step, and the 3 extra ones of its dense output.
    k: [State<N>; STAGES_EXT],
    cont: [State<N>; 7],
    dense_ready: bool,
}

/// The pair as the shared step loop sees it.
struct Pair;

impl<const N: usize> EmbeddedPair<N> for Pair {
    type Stages = [State<N>; STAGES_EXT];
    const HINIT_ORDER: i32 = 8;
    const EVALS: u64 = 12;
    const SAFETY: Real = SAFETY;
    const FAC_MIN: Real = FAC_MIN;
    const FAC_MAX: Real = FAC_MAX;
    const EXPO: Real = EXPO;
    const BETA: Real = 0.0;

    /// err^(1/8) as three square roots: each is correctly rounded, so the
    /// result is within a few units in the last place of `powf(0.125)`,
    /// at a fraction of its cost.
    #[inline(always)]
    fn err_power(err: Real) -> Real {
        err.sqrt().sqrt().sqrt()
    }

    #[inline(always)]
    fn attempt<R: Rhs<N>>(
        rhs: &R,
        t: Real,
        y: &State<N>,
        f0: &State<N>,
        h: Real,
        t_new: Real,
    ) -> (State<N>, Self::Stages) {
        let mut k = [State::<N>::zeros(); STAGES_EXT];
        k[0] = *f0;
        let y_new = attempt(rhs, t, y, h, t_new, &mut k);
        (y_new, k)
    }

    #[inline(always)]
    fn error_norm(k: &Self::Stages, h: Real, scale: &State<N>) -> Real {
        let (e5, e3) = raw_errors(k);
        error_norm(&e5, &e3, h, scale)
    }

    #[inline(always)]
    fn fsal(k: &Self::Stages) -> State<N> {
        k[STAGES]
    }
}

impl<const N: usize> Dop853<N> {
    /// A stepper at `(t0, y0)` with the given tolerances and options.
    ///
    /// Returns [`IntegrateError::InvalidOption`] for a non-finite `t0`/`y0` or an
    /// invalid option.
    pub fn new(t0: Real, y0: State<N>, opts: AdaptiveOptions) -> Result<Self, IntegrateError> {
        Ok(Self {
            core: Core::new(t0, y0, opts)?,
            k: [State::zeros(); STAGES_EXT],
            cont: [State::zeros(); 7],
            dense_ready: false,
        })
    }

    core_accessors!();

    /// One raw DOP853 step of signed size `h` from `(t, y)`: returns the order-8
    /// solution and the per-component error estimate the controller uses,
    /// `h·e5·|e5| / sqrt(e5² + 0.01·e3²)` (SciPy's `DOP853._estimate_error`; for
    /// `N = 1` its size is exactly the controller's error norm). Thirteen
    /// evaluations, no checks, no counting.
    pub fn step_once<R: Rhs<N>>(rhs: &R, t: Real, y: &State<N>, h: Real) -> (State<N>, State<N>) {
        let mut k = [State::<N>::zeros(); STAGES_EXT];
        k[0] = rhs.eval(t, y);
        let y_new = attempt(rhs, t, y, h, t + h, &mut k);
        let (e5, e3) = raw_errors(&k);
        let err = e5.zip_map(&e3, |a, b| {
            let d = a.hypot(0.1 * b);
            if d > 0.0 { h * a * (a.abs() / d) } else { 0.0 }
        });
        (y_new, err)
    }

    /// Compute the 3 extra stages and the interpolation coefficients of the last
    /// step (3 evaluations).
    fn prepare_dense<R: Rhs<N>>(&mut self, rhs: &R) {
        let c = &mut self.core;
        let h = c.h_last;
        // NOTE: unrolled by stage, as in `attempt`.
        macro_rules! stage {
            ($($s:literal)*) => {$(
                let dy = combine(&A[$s], &self.k[..], $s);
                self.k[$s] = rhs.eval(c.t_prev + C[$s] * h, &(c.y_prev + dy * h));
            )*};
        }
        stage!(13 14 15);
        c.stats.rhs_evals += 3;
        let dy = c.y - c.y_prev;
        let f_old = self.k[0];
        let f_new = self.k[STAGES];
        let bspl = f_old * h - dy;
        self.cont[0] = dy;
        self.cont[1] = bspl;
        self.cont[2] = dy - f_new * h - bspl;
        macro_rules! row {
            ($($i:literal)*) => {$(
                self.cont[3 + $i] = combine(&D[$i], &self.k[..], STAGES_EXT) * h;
            )*};
        }
        row!(0 1 2 3);
        self.dense_ready = true;
    }
}

impl<const N: usize> Stepper<N> for Dop853<N> {
    stepper_getters!(core);

    fn step<R: Rhs<N>>(&mut self, rhs: &R, t_stop: Real) -> Result<(), IntegrateError> {
        if let Some(k) = self.core.step::<Pair, R>(rhs, t_stop)? {
            self.k = k;
            self.dense_ready = false;
        }
        Ok(())
    }

    fn dense<R: Rhs<N>>(&mut self, rhs: &R, t: Real) -> State<N> {
        if self.core.h_last == 0.0 || t == self.core.t {
            return self.core.y;
        }
        // NOTE: the 3 extra stages cost 3 evaluations per step; most steps of a
        // run with sparse output never need them, so they are computed the first
        // time `dense` is called inside a step and reused after that.
        if !self.dense_ready {
            self.prepare_dense(rhs);
        }
        let s = (t - self.core.t_prev) / self.core.h_last;
        let s1 = 1.0 - s;
        let c = &self.cont;
        let inner = c[5] + c[6] * s;
        let inner = c[4] + inner * s1;
        let inner = c[3] + inner * s;
        let inner = c[2] + inner * s1;
        let inner = c[1] + inner * s;
        let inner = c[0] + inner * s1;
        self.core.y_prev + inner * s
    }

    fn reset(&mut self, y: State<N>) {
        self.core.reset(y);
        self.dense_ready = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The controller's err^(1/8) by square roots agrees with `powf` to a few
    /// units in the last place over the whole range an error norm takes.
    #[test]
    fn three_square_roots_are_the_eighth_root_to_rounding() {
        let mut worst: Real = 0.0;
        let mut e: Real = 1e-300;
        while e < 1e300 {
            for x in [e, e * 1.7, e * 3.3] {
                let got = <Pair as EmbeddedPair<3>>::err_power(x);
                let want = x.powf(EXPO);
                worst = worst.max((got / want - 1.0).abs());
            }
            e *= 10.0;
        }
        assert!(worst <= 4.0 * Real::EPSILON, "{worst:e}");
        assert_eq!(<Pair as EmbeddedPair<3>>::err_power(1.0), 1.0);
        assert_eq!(<Pair as EmbeddedPair<3>>::err_power(256.0), 2.0);
    }
}
