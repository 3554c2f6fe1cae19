//! Section 4's closed forms, (4.5)–(4.7) and (4.15)–(4.16), evaluated anywhere
//! from τΩ⊥₀²t = 1e-30 to 1e6 without cancellation or overflow.
//!
//! References: every value below was computed with mpmath at 60 significant
//! digits from the paper's own formulas, (4.6)–(4.7) generalised to Ω₁₀ ≠ 0 and
//! (4.15)–(4.16) (the printed β, σ form multiplied through by Ω⊥₀²), at the exact binary value of each t
//! (the script is in the comment at the end of this file). They are rounded to
//! 19 digits here.
//!
//! The precession angle α = Ω̃₃t grows with t; its rounding as a double, about
//! ε|α|, is unavoidable for any evaluation that takes t as an f64, so the
//! component check allows 4ε(1 + |α|) on top of a few ulps. Likewise Φ contains
//! e^(−s/2) with s = 2t/σ: rounding s costs ε·s/2 relative (the condition number
//! of the exponential), so Φ is checked to 1e-14 + 4ε·s. The other magnitudes
//! (Ω⊥ and Ω₃ of the truncated model, ϑ) are checked to 1e-14.

use spintop::math::Vec3;
use spintop::physics::symmetric_top::{
    SymmetricTop, reduced_amplitude, reduced_closed_form, truncated_clock, truncated_closed_form,
};

struct Ref {
    omega0: [f64; 3],
    t: f64,
    truncated: [f64; 3],
    vartheta: f64,
    reduced: [f64; 3],
    phi_amp: f64,
}

// The references keep 19 digits on purpose: they are the mpmath values, and the
// compiler rounds each to the nearest double.
#[rustfmt::skip]
#[allow(clippy::excessive_precision)]
const REFS: [Ref; 8] = [
    Ref { omega0: [3.000000e-02, 1.000000e-01, 2.000000e-01], t: 9.174311926605504e-29, truncated: [0.02999999999999999889, 0.1000000000000000056, 0.2000000000000000111], vartheta: 9.174311926605504046e-29, reduced: [0.02999999999999999889, 0.1000000000000000056, 0.2000000000000000111], phi_amp: 1.000000000000000000 }, // tau*Wperp0^2*t = 1e-30
    Ref { omega0: [3.000000e-02, 1.000000e-01, 2.000000e-01], t: 9.174311926605504e-19, truncated: [0.02999999999999999890, 0.1000000000000000055, 0.2000000000000000111], vartheta: 9.174311926605503901e-19, reduced: [0.02999999999999999890, 0.1000000000000000055, 0.2000000000000000111], phi_amp: 1.000000000000000000 }, // tau*Wperp0^2*t = 1e-20
    Ref { omega0: [3.000000e-02, 1.000000e-01, 2.000000e-01], t: 9.174311926605504e-11, truncated: [0.03000000000107091632, 0.09999999999956973032, 0.1999999999998000111], vartheta: 9.174311926600916829e-11, reduced: [0.03000000000105330164, 0.09999999999951101473, 0.2000000000000000111], phi_amp: 0.9999999999984128440 }, // tau*Wperp0^2*t = 1e-12
    Ref { omega0: [3.000000e-02, 1.000000e-01, 2.000000e-01], t: 9.174311926605503e-05, truncated: [0.03000107091400677069, 0.09999956971935598236, 0.1999998000003000106], vartheta: 0.00009174307339454127047, reduced: [0.03000105329927232026, 0.09999951100392310338, 0.2000000000000000111], phi_amp: 0.9999984128468833793 }, // tau*Wperp0^2*t = 1e-6
    Ref { omega0: [3.000000e-02, 1.000000e-01, 2.000000e-01], t: 91.74311926605503, truncated: [0.05299180216827127282, -0.02872633349893671752, 0.1154700538379251613], vartheta: 67.16062454760341224, reduced: [-0.03752111648846414903, 0.01181486220464553561, 0.2000000000000000111], phi_amp: 0.3767832403720867370 }, // tau*Wperp0^2*t = 1
    Ref { omega0: [3.000000e-02, 1.000000e-01, 2.000000e-01], t: 91743.11926605504, truncated: [-0.002065999879871049359, -0.001085781220224360012, 0.004471018340098958939], vartheta: 4012.159494742209261, reduced: [6.179366384259292186e-257, 1.549485076378087771e-257, 0.2000000000000000111], phi_amp: 6.101997936668946142e-256 }, // tau*Wperp0^2*t = 1e3
    Ref { omega0: [3.000000e-02, 1.000000e-01, 1.000000e-04], t: 91743119.26605503, truncated: [0.00007209856262403903481, -0.00001586803524538828389, 7.071066044099185701e-8], vartheta: 129652.6528372881907, reduced: [0.00004951582642752302915, 0.00004729976580311105626, 0.0001000000000000000048], phi_amp: 0.0006558896830372125927 }, // tau*Wperp0^2*t = 1e6, small spin: the printed beta - 1 cancels
    Ref { omega0: [3.000000e-02, 1.000000e-01, 2.000000e-01], t: 78125.0, truncated: [-0.001792943640515329928, -0.001783703313023034842, 0.004844838133444675709], vartheta: 3695.509075301104382, reduced: [3.178470811635140634e-219, 3.219544592933083494e-219, 0.2000000000000000111], phi_amp: 4.333372109644324623e-218 }, // 2t/sigma = 1000: the printed (4.16) overflows
];

const EPS: f64 = f64::EPSILON;

fn rel(a: f64, b: f64) -> f64 {
    if a == b { 0.0 } else { (a - b).abs() / b.abs() }
}

/// Tolerance for Φ: 1e-14 plus the conditioning of e^(−s/2), s = 2τk²t.
fn phi_tol(top: &SymmetricTop, omega0: &Vec3, t: f64) -> f64 {
    let k = top.ratio() * omega0.z;
    1e-14 + 4.0 * EPS * 2.0 * k * k * t
}

fn check_components(got: Vec3, want: [f64; 3], alpha: f64, what: &str, t: f64) {
    let scale = Vec3::from(want).norm();
    let tol = (8.0 * EPS + 4.0 * EPS * (1.0 + alpha.abs())) * scale;
    for i in 0..3 {
        assert!(
            (got[i] - want[i]).abs() <= tol,
            "{what} component {i} at t = {t:e}: got {:e}, want {:e} (tol {tol:e})",
            got[i],
            want[i]
        );
    }
}

#[test]
fn eq_4_6_to_4_7_truncated_closed_form_is_accurate_from_1e_30_to_1e6() {
    let top = SymmetricTop::figure();
    for r in &REFS {
        let omega0 = Vec3::from(r.omega0);
        let clock = truncated_clock(&top, omega0.x.hypot(omega0.y), r.t);
        assert!(
            rel(clock.vartheta, r.vartheta) < 1e-14,
            "vartheta at t = {:e}",
            r.t
        );
        let got = truncated_closed_form(&top, &omega0, r.t);
        let want = Vec3::from(r.truncated);
        assert!(
            rel(got.xy().norm(), want.xy().norm()) < 1e-14,
            "Omega_perp at t = {:e}",
            r.t
        );
        assert!(rel(got.z, want.z) < 1e-14, "Omega_3 at t = {:e}", r.t);
        let alpha = top.omega3_tilde(omega0.z) * clock.vartheta;
        check_components(got, r.truncated, alpha, "truncated", r.t);
    }
}

#[test]
fn eq_4_15_to_4_16_reduced_closed_form_is_accurate_from_1e_30_to_1e6() {
    let top = SymmetricTop::figure();
    for r in &REFS {
        let omega0 = Vec3::from(r.omega0);
        let phi_amp = reduced_amplitude(&top, &omega0, r.t);
        let tol = phi_tol(&top, &omega0, r.t);
        assert!(
            rel(phi_amp, r.phi_amp) < tol,
            "Phi at t = {:e}: {phi_amp:e}",
            r.t
        );
        let got = reduced_closed_form(&top, &omega0, r.t);
        let alpha = top.omega3_tilde(omega0.z) * r.t;
        check_components(got, r.reduced, alpha, "reduced", r.t);
        let want = Vec3::from(r.reduced);
        assert!(
            rel(got.xy().norm(), want.xy().norm()) < tol,
            "Omega_perp at t = {:e}",
            r.t
        );
        assert_eq!(got.z, omega0.z, "(4.14): Omega_3 is constant");
    }
}

/// Far past the last reference, Φ underflows to exactly 0 (the correctly
/// rounded double of e^(−255000)), never NaN.
#[test]
fn eq_4_16_underflows_cleanly_where_phi_is_below_the_smallest_double() {
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.03, 0.1, 0.2);
    for t in [9.174311926605505e7, 1e12, 1e300] {
        let got = reduced_closed_form(&top, &omega0, t);
        assert!(got.iter().all(|x| x.is_finite()), "{got} at t = {t}");
        assert_eq!(got.xy().norm(), 0.0);
        let got = truncated_closed_form(&top, &omega0, t);
        assert!(got.iter().all(|x| x.is_finite()), "{got} at t = {t}");
    }
}

/// The same quantities evaluated the way the paper prints them fail where the
/// careful forms do not: this is why spintop rewrites them.
#[test]
fn eq_4_9_and_eq_4_16_printed_forms_lose_digits_or_overflow() {
    let top = SymmetricTop::figure();
    // (4.9) printed: ϑ = (R − 1)/(τΩ⊥₀²). At τΩ⊥₀²t = 1e-20, R rounds to 1.
    let r = &REFS[1];
    let u0 = r.omega0[0].powi(2) + r.omega0[1].powi(2);
    let big_r = (1.0 + 2.0 * u0 * r.t).sqrt();
    let printed = (big_r - 1.0) / u0;
    assert_eq!(printed, 0.0, "every digit of R − 1 is lost");
    let careful = truncated_clock(&top, u0.sqrt(), r.t).vartheta;
    assert!(rel(careful, r.vartheta) < 1e-15);

    // (4.16) printed at 2t/σ = 1000: β e^{2t/σ} overflows and Φ collapses to 0.
    let r = &REFS[7];
    let omega0 = Vec3::from(r.omega0);
    let k = top.ratio() * omega0.z;
    let beta = 1.0 + k * k / (omega0.x.powi(2) + omega0.y.powi(2));
    let sigma = 1.0 / (k * k);
    let printed = ((beta - 1.0) / (beta * (2.0 * r.t / sigma).exp() - 1.0)).sqrt();
    assert_eq!(printed, 0.0, "the printed form overflows to 1/inf");
    let tol = phi_tol(&top, &omega0, r.t);
    assert!(rel(reduced_amplitude(&top, &omega0, r.t), r.phi_amp) < tol);

    // (4.16) printed with a slow spin: β − 1 = k²/Ω⊥₀² ≈ 1.5e-7 keeps only ~9 digits.
    let r = &REFS[6];
    let omega0 = Vec3::from(r.omega0);
    let k = top.ratio() * omega0.z;
    let beta = 1.0 + k * k / (omega0.x.powi(2) + omega0.y.powi(2));
    let sigma = 1.0 / (k * k);
    let printed = ((beta - 1.0) / (beta * (2.0 * r.t / sigma).exp() - 1.0)).sqrt();
    assert!(
        rel(printed, r.phi_amp) > 1e-11,
        "printed error {:e}",
        rel(printed, r.phi_amp)
    );
    assert!(rel(reduced_amplitude(&top, &omega0, r.t), r.phi_amp) < 1e-14);
}

// The reference script (Python, mpmath), run once to produce REFS:
//
//   from mpmath import mp, mpf, sqrt, exp, sin, cos
//   mp.dps = 60; r = mpf('0.4')
//   def trunc(w, t):
//       w1, w2, w3 = w; u0 = w1*w1 + w2*w2
//       R = sqrt(1 + 2*u0*t); vt = (R - 1)/u0; a = (1 - r)*w3*vt
//       return [(w1*cos(a) + w2*sin(a))/R, (w2*cos(a) - w1*sin(a))/R, w3/R], vt
//   def red(w, t):
//       w1, w2, w3 = w; u0 = w1*w1 + w2*w2; k = r*w3
//       # (beta - 1)/(beta e^{2t/sigma} - 1) with beta = 1 + k²/u0, sigma = 1/k²,
//       # multiplied through by u0:
//       Phi = sqrt(k*k/((u0 + k*k)*exp(2*k*k*t) - u0)); a = (1 - r)*w3*t
//       return [Phi*(w1*cos(a) + w2*sin(a)), Phi*(w2*cos(a) - w1*sin(a)), w3], Phi
//   # t = the double nearest x/u0, converted exactly with mpf(float(...)); omega0
//   # likewise the exact doubles of 0.03, 0.1, 0.2 (and 1e-4).
