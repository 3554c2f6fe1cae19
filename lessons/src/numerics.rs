//! Numerical methods: one step of two Runge–Kutta methods, and the Euler
//! angles of a rotation. Book: "Where methods fail" and Section 3.

#[cfg(not(feature = "solutions"))]
use spintop::grading::DynField;
#[cfg(not(feature = "solutions"))]
use spintop::math::{Mat3, State};

/// One classical RK4 step of size `h` from `(t, y)` for `y' = f(t, y)`.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn rk4_step(f: DynField, t: f64, y: &State<3>, h: f64) -> State<3> {
    todo!("classical RK4: see the book, chapter 'Where methods fail'")
}

/// One Dormand–Prince 5(4) step: the fifth-order result y₅ and the error
/// estimate y₅ − ŷ₄.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn dp5_step(f: DynField, t: f64, y: &State<3>, h: f64) -> (State<3>, State<3>) {
    todo!("Dormand-Prince 5(4): see the book, chapter 'Where methods fail'")
}

/// The z-x-z Euler angles (φ, θ, ψ) of a rotation matrix, θ in [0, π],
/// finite on the poles. Paper: Eq. (3.5) (its convention). Book: Section 3.
#[cfg(not(feature = "solutions"))]
#[allow(unused_variables)]
pub fn euler_from_rotation(m: &Mat3) -> (f64, f64, f64) {
    todo!("Eq. (3.5): see the book, chapter 'Section 3', Euler angles")
}

#[cfg(feature = "solutions")]
pub use crate::solutions::numerics::*;
