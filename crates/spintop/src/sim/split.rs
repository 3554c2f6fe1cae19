//! The two problems the splitting methods solve, each cut into parts whose
//! flows the physics gives exactly: the free rigid body (τ = 0) in three
//! rotations about its body axes ([`FreeRigidBody::axis_flow`], (3.1)–(3.2)),
//! and the reduced model (4.12)–(4.14) in the rotation of (Ω₁, Ω₂) and the
//! radial damping ([`reduced_rotation_flow`], [`reduced_damping_flow`]). The
//! composition itself is [`crate::integrate::splitting`]'s, generic over the
//! problem.

use crate::integrate::control::check_t_stop;
use crate::integrate::splitting::{Composition, SplitFlow, Splitting};
use crate::integrate::{IntegrateError, Stats};
use crate::math::{Real, Vec3, all_finite};
use crate::physics::free_top::{FreeRigidBody, RigidBodyState};
use crate::physics::symmetric_top::{SymmetricTop, reduced_damping_flow, reduced_rotation_flow};

impl SplitFlow for FreeRigidBody {
    type State = RigidBodyState;

    fn parts(&self) -> usize {
        3
    }

    fn flow(&self, part: usize, h: Real, state: &RigidBodyState) -> Option<RigidBodyState> {
        Some(self.axis_flow(part, h, state))
    }

    fn is_finite(&self, state: &RigidBodyState) -> bool {
        all_finite(&state.l_body) && all_finite(&state.rotation)
    }
}

/// A fixed-step splitting of the free rigid body (see [`FreeRigidBody`]).
pub type RigidBodySplitting = Splitting<FreeRigidBody>;

/// The reduced model (4.12)–(4.14) of the symmetric top, split into the
/// rotation of (Ω₁, Ω₂) at the rate Ω̃₃ (part 0) and the radial damping
/// (part 1). Ω₃ is constant, so the two parts commute and every composition,
/// Lie–Trotter included, is the exact flow: only rounding separates n steps from
/// the closed form (4.15)–(4.16), whatever the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReducedFlow(pub SymmetricTop);

impl SplitFlow for ReducedFlow {
    type State = Vec3;

    fn parts(&self) -> usize {
        2
    }

    fn flow(&self, part: usize, h: Real, omega: &Vec3) -> Option<Vec3> {
        if part == 0 {
            Some(reduced_rotation_flow(&self.0, omega, h))
        } else {
            reduced_damping_flow(&self.0, omega, h)
        }
    }

    fn is_finite(&self, omega: &Vec3) -> bool {
        all_finite(omega)
    }
}

/// A fixed-step splitting of the reduced model (see [`ReducedFlow`]).
pub type ReducedSplitting = Splitting<ReducedFlow>;

/// Ω(t_end) of the reduced model from Ω(0) = `omega0` in `steps` equal
/// Lie–Trotter steps of the exact rotation/damping split (exact, since the parts
/// commute: equal to [`crate::physics::symmetric_top::reduced_closed_form`] to
/// rounding for any `steps` ≥ 1, that is to a relative error of a few ε per step
/// plus ε|Ω̃₃t| in the phase). Negative `t_end` steps backward.
///
/// Paper: Eq. (4.12), Eq. (4.13), Eq. (4.14).
///
/// Returns [`IntegrateError::InvalidOption`] for `steps == 0` with
/// `t_end ≠ 0`, a non-finite `t_end` or `omega0`; [`IntegrateError::NonFinite`]
/// when a backward run meets the blow-up of Ω⊥.
pub fn reduced_split_solve(
    top: &SymmetricTop,
    omega0: &Vec3,
    t_end: Real,
    steps: u64,
) -> Result<(Vec3, Stats), IntegrateError> {
    check_t_stop(t_end)?;
    if !all_finite(omega0) {
        return Err(IntegrateError::InvalidOption(
            "the initial angular velocity must be finite".into(),
        ));
    }
    if t_end == 0.0 {
        return Ok((*omega0, Stats::default()));
    }
    if steps == 0 {
        return Err(IntegrateError::InvalidOption(
            "at least one step is needed to reach t_end != 0".into(),
        ));
    }
    let h = t_end.abs() / steps as Real;
    let mut stepper =
        ReducedSplitting::new(ReducedFlow(*top), Composition::LieTrotter, 0.0, *omega0, h)?
            .with_max_steps(steps);
    stepper.advance_to(t_end)?;
    Ok((*stepper.state(), stepper.stats()))
}
