//! What a radiating dipole carries away (paper §2, the flux behind Eq. (2.1),
//! and Larmor's formula of §1): the exact fields of a point dipole whose
//! moment changes in time, the energy and angular momentum they carry through
//! a sphere around it, and Larmor's power.
//!
//! The fields are written in Gaussian units with the speed of light `c`
//! explicit, since the sphere's radius enters through `c/R`; [`larmor_power`]
//! uses the book's κ = 2/(3c³) = 1, as [`super::balance`] does.
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `jet` | [𝔡, 𝔡̇, 𝔡̈, 𝔡⃛] | the dipole and its derivatives at the retarded time t − R/c | charge·length, per time, … |
//! | `r` | r = R n | the field point, from the dipole | length |
//! | `c` | c | the speed of light | length/time |
//! | `e`, `b` | E, B | the electric and magnetic fields at r | Gaussian |
//! | [`larmor_power`] | P = (2/3c³)\|𝔡̈\|² | the power the dipole radiates (κ = 1) | energy/time |
//! | [`SphereFlux::energy_rate`] | −∮ S·n dA | rate of change of the energy inside the sphere | energy/time |
//! | [`SphereFlux::angular_momentum_rate`] | ∮ r × (σ·n) dA | rate of change of the angular momentum inside | angular momentum/time |

use super::balance::Jet;
use crate::math::{Real, Vec3};
use std::f64::consts::PI;

/// The power radiated by a dipole, Larmor's formula (κ = 2/(3c³) = 1).
///
/// Paper: Section 1 (the Larmor formula), the energy counterpart of Eq. (2.1).
///
/// ```text
/// P = (2/3c³) |𝔡̈|²        (κ = 1)
/// ```
pub fn larmor_power(jet: &Jet) -> Real {
    jet[2].norm_squared()
}

/// The electric and magnetic field of a point dipole at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DipoleField {
    /// E at the point.
    pub e: Vec3,
    /// B at the point.
    pub b: Vec3,
}

/// The exact field of a point dipole at the origin, at the point `r`, from the
/// dipole's jet at the retarded time t − |r|/c (Gaussian units).
///
/// Paper: Section 2, the field whose flux gives Eq. (2.1).
///
/// ```text
/// E = [3n(n·𝔡) − 𝔡]/R³ + [3n(n·𝔡̇) − 𝔡̇]/(cR²) + n × (n × 𝔡̈)/(c²R)
/// B = (𝔡̇ × n)/(cR²) + (𝔡̈ × n)/(c²R)                    (all at t − R/c)
/// ```
///
/// The 1/R terms are the radiation field; the 1/R² and 1/R³ terms are the
/// near field, which the angular momentum flux needs (E·n has no 1/R part).
pub fn dipole_field(jet: &Jet, r: &Vec3, c: Real) -> DipoleField {
    let [d, d1, d2, _] = jet;
    let big_r = r.norm();
    let n = r / big_r;
    let e = (3.0 * n * n.dot(d) - d) / big_r.powi(3)
        + (3.0 * n * n.dot(d1) - d1) / (c * big_r * big_r)
        + n.cross(&n.cross(d2)) / (c * c * big_r);
    let b = d1.cross(&n) / (c * big_r * big_r) + d2.cross(&n) / (c * c * big_r);
    DipoleField { e, b }
}

/// What the field carries through a sphere of radius R around the dipole.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereFlux {
    /// The rate of change of the energy inside, −∮ S·n dA with S = (c/4π) E × B.
    pub energy_rate: Real,
    /// The rate of change of the angular momentum inside (charges and field),
    /// ∮ r × (σ·n) dA with the Maxwell stress σ = (1/4π)(EE + BB − ½(E² + B²)1).
    pub angular_momentum_rate: Vec3,
}

/// The flux of energy and angular momentum of the dipole's field through the
/// sphere |r| = `radius`, by quadrature: Gauss–Legendre in cos θ (`nodes`
/// points) times the trapezoid rule in φ (2·`nodes` points). The integrands
/// are polynomials of low degree in n, so 4 nodes are already exact.
///
/// Paper: Eq. (2.1) (its derivation: L&L §72, Problem 2).
///
/// ```text
/// dL/dt = ∮ r × (σ·n) R² dΩ  →  −(2/3c³) 𝔡̇ × 𝔡̈   as R → ∞
/// ```
///
/// `jet` is the dipole's at the retarded time t − R/c, the same for every
/// point of the sphere. At a finite radius the exact results are
///
/// ```text
/// dL/dt = −(2/3c³) [𝔡̇ × 𝔡̈ + (c/R) 𝔡 × 𝔡̈]
/// dE/dt = −(2/3c³) [|𝔡̈|² + (c/R) d|𝔡̇|²/dt + (c/R)² d(𝔡·𝔡̇)/dt + (c/R)³ ½ d|𝔡|²/dt]
/// ```
///
/// so the flux of angular momentum differs from (2.1) by (c/R) times the Schott
/// angular momentum (2.4), and the difference dies away as the sphere grows.
pub fn sphere_flux(jet: &Jet, radius: Real, c: Real, nodes: usize) -> SphereFlux {
    let (mu, w) = gauss_legendre(nodes.max(1));
    let n_phi = 2 * nodes.max(1);
    let d_phi = 2.0 * PI / n_phi as Real;
    let mut energy = 0.0;
    let mut torque = Vec3::zeros();
    for (&cos_t, &weight) in mu.iter().zip(&w) {
        let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
        for k in 0..n_phi {
            let (s, co) = (k as Real * d_phi).sin_cos();
            let n = Vec3::new(sin_t * co, sin_t * s, cos_t);
            let f = dipole_field(jet, &(radius * n), c);
            let area = weight * d_phi * radius * radius;
            // Poynting: (c/4π) (E × B)·n leaves through the surface.
            energy -= c / (4.0 * PI) * f.e.cross(&f.b).dot(&n) * area;
            // r × (σ·n); the isotropic part of σ is along n and drops out.
            let stress_n = (f.e * f.e.dot(&n) + f.b * f.b.dot(&n)) / (4.0 * PI);
            torque += (radius * n).cross(&stress_n) * area;
        }
    }
    SphereFlux {
        energy_rate: energy,
        angular_momentum_rate: torque,
    }
}

/// Gauss–Legendre nodes and weights on [−1, 1], by Newton's method on the
/// Legendre polynomial from the usual cosine guesses (exact for polynomials of
/// degree 2n − 1).
fn gauss_legendre(n: usize) -> (Vec<Real>, Vec<Real>) {
    let mut x = Vec::with_capacity(n);
    let mut w = Vec::with_capacity(n);
    for i in 0..n {
        let mut z = (PI * (i as Real + 0.75) / (n as Real + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // P_n(z) and P_n'(z) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as Real * z * p1 - (k - 1) as Real * p0) / k as Real;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { z } else { p1 };
            let pn_1 = if n == 1 { 1.0 } else { p0 };
            derivative = n as Real * (z * pn - pn_1) / (z * z - 1.0);
            let step = pn / derivative;
            z -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        x.push(z);
        w.push(2.0 / ((1.0 - z * z) * derivative * derivative));
    }
    (x, w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::balance::{
        DipoleTrajectory, PrecessingDipole, larmor_rate, schott_angular_momentum,
    };
    use approx::assert_relative_eq;

    /// A jet with no special symmetry.
    fn jet() -> Jet {
        [
            Vec3::new(0.3, -1.2, 0.7),
            Vec3::new(1.1, 0.4, -0.5),
            Vec3::new(-0.8, 0.9, 0.2),
            Vec3::new(0.6, -0.3, 1.4),
        ]
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_of_degree_2n_minus_1() {
        let (x, w) = gauss_legendre(5);
        for k in 0..10 {
            let quad: Real = x.iter().zip(&w).map(|(x, w)| w * x.powi(k)).sum();
            let exact = if k % 2 == 1 {
                0.0
            } else {
                2.0 / (k as Real + 1.0)
            };
            assert!(
                (quad - exact).abs() < 1e-14,
                "degree {k}: {quad} vs {exact}"
            );
        }
    }

    /// Two properties of any dipole field: B has no radial part, and the flux
    /// of E through a sphere around the dipole is zero (Gauss: no net charge).
    #[test]
    fn dipole_field_has_no_radial_b_and_no_net_charge() {
        let j = jet();
        let r = Vec3::new(0.4, -2.0, 1.1);
        let f = dipole_field(&j, &r, 1.0);
        assert!(f.b.dot(&r).abs() < 1e-15);
        let (mu, w) = gauss_legendre(6);
        let mut flux = 0.0;
        for (&c_t, &wt) in mu.iter().zip(&w) {
            let s_t = (1.0 - c_t * c_t).sqrt();
            for k in 0..12 {
                let phi = k as Real * PI / 6.0;
                let n = Vec3::new(s_t * phi.cos(), s_t * phi.sin(), c_t);
                flux += dipole_field(&j, &(3.0 * n), 1.0).e.dot(&n) * 9.0 * wt * PI / 6.0;
            }
        }
        assert!(flux.abs() < 1e-13, "{flux}");
    }

    /// Eq. (2.1) is the angular momentum the field carries off through a large
    /// sphere: the quadrature of the Maxwell stress tends to −(2/3c³) 𝔡̇ × 𝔡̈,
    /// and at every radius it is (2.1) minus (c/R) L_S.
    #[test]
    fn eq_2_1_is_the_flux_of_angular_momentum_through_a_large_sphere() {
        let c: Real = 1.3;
        let kappa = 2.0 / (3.0 * c.powi(3));
        let j = jet();
        for radius in [0.5, 2.0, 40.0, 1e4] {
            let flux = sphere_flux(&j, radius, c, 6).angular_momentum_rate;
            let closed = kappa * (larmor_rate(&j) - (c / radius) * schott_angular_momentum(&j));
            assert!(
                (flux - closed).norm() < 1e-12 * closed.norm(),
                "R = {radius}"
            );
        }
        // Far out the near-field products cancel to rounding (~1e-11 here).
        let far = sphere_flux(&j, 1e8, c, 6).angular_momentum_rate;
        assert_relative_eq!(far, kappa * larmor_rate(&j), max_relative = 1e-7);
        // And with too few nodes the quadrature is not exact, so the check can fail.
        let coarse = sphere_flux(&j, 2.0, c, 1).angular_momentum_rate;
        let closed = kappa * (larmor_rate(&j) - (c / 2.0) * schott_angular_momentum(&j));
        assert!((coarse - closed).norm() > 1e-3 * closed.norm());
    }

    /// Larmor's power is the energy the field carries off through a large
    /// sphere; at a finite radius the extra terms are time derivatives.
    #[test]
    fn larmor_power_is_the_energy_flux_through_a_large_sphere() {
        let c: Real = 0.7;
        let kappa = 2.0 / (3.0 * c.powi(3));
        let [d, d1, d2, d3] = jet();
        for radius in [0.5, 3.0, 1e4] {
            let flux = sphere_flux(&[d, d1, d2, d3], radius, c, 6).energy_rate;
            let x = c / radius;
            let closed = -kappa
                * (larmor_power(&[d, d1, d2, d3])
                    + x * 2.0 * d1.dot(&d2)
                    + x * x * (d.dot(&d2) + d1.norm_squared())
                    + x * x * x * d.dot(&d1));
            assert!(
                (flux - closed).abs() < 1e-12 * closed.abs().max(1.0),
                "R = {radius}"
            );
        }
    }

    /// The precessing dipole of Section 2 radiates ω⁴ sin²θ (κ = 1).
    #[test]
    fn larmor_power_of_the_precessing_dipole() {
        let (theta, omega): (Real, Real) = (0.7, 1.3);
        let dipole = PrecessingDipole::new(theta, omega).unwrap();
        for t in [0.0, 0.4, 2.5] {
            let p = larmor_power(&dipole.jet(t));
            assert_relative_eq!(p, omega.powi(4) * theta.sin().powi(2), max_relative = 1e-14);
        }
    }
}
