//! One grader per assignment, in course order. Each takes the grading's
//! `seed` (its random inputs come from it) and the student's function.
//!
//! | grader | equation | the student writes |
//! |---|---|---|
//! | [`larmor_rate`] | (2.1) | the Larmor-like loss rate |
//! | [`schott_angular_momentum`] | (2.4) | L_S |
//! | [`torque_rate`] | (2.2) | the radiation-reaction torque |
//! | [`schott_rate`] | (2.3) | dL_S/dt, the difference of the two laws |
//! | [`axial_schott_rate`] | (2.3)–(2.4) | n · dL_S/dt |
//! | [`precessing_dipole_jet`] | Section 2 | the jet of a precessing dipole |
//! | [`truncated_ale_rhs`] | (3.3) | Ω̇ of a general top |
//! | [`energy_rate`] | (3.3) | dE/dt of a general top |
//! | [`euler_from_rotation`] | (3.5) | Euler angles of a rotation, pole included |
//! | [`truncated_omega_perp`] | (4.5)–(4.6) | Ω⊥(t) of the truncated top |
//! | [`truncated_closed_form`] | (4.7) | Ω(t) of the truncated top |
//! | [`truncated_time_to_factor`] | (4.6) inverted | when Ω has fallen by p |
//! | [`precession_tilt`] | (4.11), corrected | the constant tilt θ, for either sign of Ω₃ |
//! | [`reduced_ale_rhs`] | (4.12)–(4.14) | Ω̇ of the reduced model |
//! | [`reduced_decay_time`] | (4.16) | σ |
//! | [`reduced_closed_form`] | (4.15)–(4.16) | Ω(t) for any Ω₀ |
//! | [`rk4_step`] | – | one classical RK4 step |
//! | [`dp5_step`] | – | one Dormand–Prince 5(4) step and its error estimate |
//! | [`reduced_rk4`] | (4.12)–(4.14) | a whole RK4 run: N classical steps, to rounding |
//! | [`shell_masses`] | (A.1) | m₀ and m_em |
//! | [`shell_acceleration`] | (A.1) | the method-of-steps update Z'' |

mod appendix;
mod ch2;
mod ch3;
mod ch4;
mod numerics;
mod run;
mod tableau;

pub use appendix::{characteristic_root, shell_acceleration, shell_masses};
pub use ch2::{
    axial_schott_rate, larmor_rate, precessing_dipole_jet, schott_angular_momentum, schott_rate,
    torque_rate,
};
pub use ch3::{energy_rate, euler_from_rotation, truncated_ale_rhs};
pub use ch4::{
    precession_tilt, reduced_ale_rhs, reduced_closed_form, reduced_decay_time,
    truncated_closed_form, truncated_omega_perp, truncated_time_to_factor,
};
pub use numerics::{dp5_step, dp5_step_on, rk4_step, rk4_step_on};
pub use run::reduced_rk4;

/// The body-frame rates' names, for reports.
const OMEGA: [&str; 3] = ["Ω₁", "Ω₂", "Ω₃"];
