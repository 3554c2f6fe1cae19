//! The types an assignment's signature uses, and nothing that computes physics.
//!
//! A file of the `spintop-lessons` crate may import from `spintop` only this
//! module and [`crate::math`] (vectors and matrices): `spintop course` refuses
//! the grades of a copy that reaches into `spintop::physics`, `spintop::sim`,
//! `spintop::integrate` or any other module, where the reference answers
//! live (the source rule, `course::source_rule`; see `lessons/README.md`).

pub use crate::math::{Mat3, Real, State, Vec3};
pub use crate::physics::balance::Jet;
pub use crate::physics::shell::C;

/// A right-hand side `f(t, y)` as the step assignments take it.
pub type DynField<'a> = &'a dyn Fn(Real, &State<3>) -> State<3>;
