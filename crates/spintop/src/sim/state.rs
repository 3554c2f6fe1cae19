//! What a simulation starts from ([`InitialState`]), what it reports at
//! each time ([`Sample`]), and why it may stop ([`SimError`]).

use super::method::MethodRefused;
use super::{cost, physical};
use crate::integrate::IntegrateError;
use crate::math::{Mat3, Real, Vec3, all_finite};
use crate::physics::ParamError;
use crate::physics::euler_angles::{EulerAngles, euler_rates};
use crate::physics::rigid_body::Observables;
use serde::Serialize;
use thiserror::Error;

/// Initial body rate Ω₀ and orientation O(0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InitialState {
    /// Ω₀ in the body frame.
    pub omega: Vec3,
    /// O(0), body → lab.
    pub rotation: Mat3,
}

impl InitialState {
    /// Ω₀ and the z-x-z Euler angles of O(0); refuses non-finite numbers.
    pub fn new(omega: Vec3, euler: EulerAngles) -> Result<Self, SimError> {
        check_rate(&omega)?;
        if !(euler.phi.is_finite() && euler.theta.is_finite() && euler.psi.is_finite()) {
            return Err(SimError::NotFinite("the initial Euler angles"));
        }
        Ok(Self {
            omega,
            rotation: euler.to_rotation(),
        })
    }
}

/// The one check of an initial body rate Ω₀ (every entry point's, through
/// [`InitialState::new`] or, where a scene points at its key, directly):
/// finite, and each component at most [`MAX_RATE`] in units of 1/τ.
pub fn check_rate(omega: &Vec3) -> Result<(), SimError> {
    if !all_finite(omega) {
        return Err(SimError::NotFinite("the initial angular velocity"));
    }
    // NOTE: in units of 1/τ a real top has |Ω| far below 1 (τΩ ~ 1e-20 for a
    // nanoparticle); above 1e100 the products τΩ²t overflow a double.
    if omega.amax() > MAX_RATE {
        return Err(SimError::OutOfRange(
            "each component of the initial angular velocity must be at most 1e100 in units of 1/tau",
        ));
    }
    Ok(())
}

/// Why a simulation could not be built or advanced.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SimError {
    /// A physical parameter was refused.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// An input was NaN or infinite.
    #[error("{0} must be finite numbers")]
    NotFinite(&'static str),
    /// The model does not take the method chosen.
    #[error(transparent)]
    Refused(#[from] MethodRefused),
    /// An input lies beyond what the model can represent.
    #[error("{0}")]
    OutOfRange(&'static str),
    /// A sample came out non-finite although the method reported no failure
    /// (a last guard: spintop never prints a NaN table).
    #[error("the state became non-finite at t = {}", crate::numbers::fmt_time(*.0))]
    NonFiniteSample(Real),
    /// A requested time was negative, non-finite or earlier than the last one.
    #[error(
        "output times must be finite, >= 0 and non-decreasing (got {} after {})",
        crate::numbers::fmt_value(*.0),
        crate::numbers::fmt_value(*.1)
    )]
    BadTime(Real, Real),
    /// The integrator failed; the error carries the time.
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    /// A method named directly ([`Simulation::with_method`]) cannot run the
    /// model.
    #[error("the method {method} does not run the {model} model")]
    MethodNotForModel {
        /// The method's label.
        method: &'static str,
        /// The model's name.
        model: &'static str,
    },
    /// The model needs to know its last time in advance.
    #[error("the {0} model needs the last output time in advance")]
    NeedsHorizon(&'static str),
    /// The physical solution of the full ALE could not be found.
    #[error(transparent)]
    Physical(#[from] physical::PhysicalError),
    /// A forward run of the full ALE ran away before the requested time.
    #[error("{0}")]
    Runaway(physical::Runaway),
    /// The run would take more work than allowed (estimated before it starts).
    #[error(transparent)]
    TooCostly(#[from] cost::TooCostly),
}

/// Everything observed at one time. Serialises to the `simulate` JSON contract.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time, in units of τ.
    pub t: Real,
    /// Body-frame Ω.
    pub omega: [Real; 3],
    /// O(t), body → lab, as rows.
    pub rotation: [[Real; 3]; 3],
    /// z-x-z Euler angles [φ, θ, ψ] of O(t).
    pub euler: [Real; 3],
    /// E = ½ Ω·IΩ.
    pub energy: Real,
    /// L in the lab frame.
    pub l_lab: [Real; 3],
    /// Ω⊥.
    pub omega_perp: Real,
    /// L in the body frame.
    pub l_body: [Real; 3],
    /// Angle between the symmetry axis (body axis 3) and L.
    pub tilt: Real,
    /// [φ̇, θ̇, ψ̇] from (4.8); `None` on a pole, where they are undefined.
    pub euler_rates: Option<[Real; 3]>,
}

impl Sample {
    /// Observe a state.
    pub fn new(t: Real, inertia: &Vec3, rotation: &Mat3, omega: &Vec3) -> Self {
        let obs = Observables::new(inertia, rotation, omega);
        let euler = EulerAngles::from_rotation(rotation);
        let rows = |i: usize| [rotation[(i, 0)], rotation[(i, 1)], rotation[(i, 2)]];
        Self {
            t,
            omega: (*omega).into(),
            rotation: [rows(0), rows(1), rows(2)],
            euler: [euler.phi, euler.theta, euler.psi],
            energy: obs.energy,
            l_lab: obs.l_lab.into(),
            omega_perp: obs.omega_perp,
            l_body: obs.l_body.into(),
            tilt: obs.tilt,
            euler_rates: euler_rates(&euler, omega).map(|r| [r.phi_dot, r.theta_dot, r.psi_dot]),
        }
    }

    /// True when every number of the sample is finite.
    pub fn is_finite(&self) -> bool {
        let finite = |xs: &[Real]| xs.iter().all(|x| x.is_finite());
        finite(&[self.t, self.energy, self.omega_perp, self.tilt])
            && finite(&self.omega)
            && finite(&self.l_lab)
            && finite(&self.l_body)
            && finite(&self.euler)
            && self.rotation.iter().all(|r| finite(r))
            && self.euler_rates.is_none_or(|r| finite(&r))
    }

    /// Ω as a vector.
    pub fn omega_vec(&self) -> Vec3 {
        Vec3::from(self.omega)
    }

    /// O(t) as a matrix.
    pub fn rotation_matrix(&self) -> Mat3 {
        let r = &self.rotation;
        Mat3::new(
            r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2],
        )
    }
}

/// The largest |Ω| component accepted, in units of 1/τ.
pub const MAX_RATE: Real = 1e100;
