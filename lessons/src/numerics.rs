//! Numerical methods: the Euler angles of a rotation, one step of two
//! Runge–Kutta methods, and a whole RK4 run. Book: Section 3, "Numerical
//! methods" and "Where methods fail".

#[cfg(not(feature = "solutions"))]
use spintop::assignment::{DynField, Mat3, State, Vec3};

/// The z-x-z Euler angles (φ, θ, ψ) of a rotation matrix, θ in [0, π],
/// finite on the poles. Paper: Eq. (3.5) (its convention). Book: Section 3.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn euler_from_rotation(m: &Mat3) -> (f64, f64, f64) {
    todo!("Eq. (3.5): see the book, chapter 'Section 3', Euler angles")
}

/// One classical RK4 step of size `h` from `(t, y)` for `y' = f(t, y)`.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn rk4_step(f: DynField, t: f64, y: &State<3>, h: f64) -> State<3> {
    todo!("classical RK4: see the book, chapter 'Numerical methods'")
}

/// One Dormand–Prince 5(4) step: the fifth-order result y₅ and the error
/// estimate y₅ − ŷ₄.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn dp5_step(f: DynField, t: f64, y: &State<3>, h: f64) -> (State<3>, State<3>) {
    todo!("Dormand-Prince 5(4): see the book, chapter 'Numerical methods'")
}

/// Ω(t_end) of the reduced model (4.12)–(4.14) from Ω(0) = `omega0` by
/// `steps` equal steps of your `rk4_step` on your `crate::ch4::reduced_ale_rhs`.
/// The grader checks that the answer is that of `steps` classical RK4 steps,
/// to rounding, and tells a wrong step count, end time, stage or model apart.
/// Book: Numerical methods; Section 4.2.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn reduced_rk4(ratio: f64, tau: f64, omega0: Vec3, t_end: f64, steps: usize) -> Vec3 {
    todo!("RK4 on (4.12)-(4.14): see the book, chapter 'Numerical methods'")
}

#[cfg(feature = "solutions")]
pub use crate::solutions::numerics::*;
