//! Grading functions that run in another process.
//!
//! `spintop course` and `course grade` never call a student's function in
//! the process that holds the references: the student's functions run in a
//! runner (see [`spintop_runner`]), and each grader here is handed a proxy,
//! a closure of the very type the grader takes, that sends the arguments
//! down a pipe and reads the answer back. The grader keeps all its power:
//! fresh inputs, and more calls to probe a wrong answer.

use crate::Grade;
use spintop::assignment::{C, Jet, Mat3, Real, State, Vec3};
use spintop_runner::fields::Field;
use spintop_runner::wire::{self, Wire};

/// Why a call gave no answer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Fault {
    /// The student's function panicked, with this message.
    Panicked(String),
    /// The runner is gone or cannot be trusted (it died, hung, or answered
    /// something that is not an answer); the [`Remote`] knows why.
    Lost,
}

/// The student's functions, reached by name.
pub trait Remote {
    /// Calls the function `name` with the numbers of its arguments: the
    /// numbers of its answer, or why there is none.
    fn call(&self, name: &str, args: &[Real]) -> Result<Vec<Real>, Fault>;
    /// Hears that the numbers of an answer to `name` do not make a value of
    /// the function's type: the runner is not to be trusted after that.
    fn garbled(&self, name: &str);
}

/// What a call to a lost runner panics with (the graders report a panic;
/// the caller then replaces the verdict by what the [`Remote`] knows).
pub const LOST: &str = "the runner was lost";

/// Calls `name` on `to` with `args`: the student's answer, or a panic with
/// the student's message (or [`LOST`]), as if the function had panicked
/// here.
fn remote<A: Wire, R: Wire>(to: &dyn Remote, name: &str, args: A) -> R {
    match to.call(name, &wire::numbers(&args)) {
        Ok(numbers) => match wire::value::<R>(&numbers) {
            Some(answer) => answer,
            None => {
                to.garbled(name);
                std::panic::panic_any(LOST.to_string())
            }
        },
        Err(Fault::Panicked(message)) => std::panic::panic_any(message),
        Err(Fault::Lost) => std::panic::panic_any(LOST.to_string()),
    }
}

/// Grades the assignment `name` (its function's name) at `seed` with the
/// student's function reached through `to`; `None` for a name that is no
/// assignment. The same graders as in-process, each given a proxy.
pub fn grade_remote(name: &str, seed: u64, to: &dyn Remote) -> Option<Grade> {
    use crate::graders::*;
    let n = name;
    let grade = match name {
        "larmor_rate" => larmor_rate(seed, |j: &Jet| remote(to, n, (*j,))),
        "schott_angular_momentum" => schott_angular_momentum(seed, |j: &Jet| remote(to, n, (*j,))),
        "torque_rate" => torque_rate(seed, |j: &Jet| remote(to, n, (*j,))),
        "schott_rate" => schott_rate(seed, |j: &Jet| remote(to, n, (*j,))),
        "axial_schott_rate" => axial_schott_rate(seed, |j: &Jet| remote(to, n, (*j,))),
        "precessing_dipole_jet" => {
            precessing_dipole_jet(seed, |a: Real, w: Real, t: Real| remote(to, n, (a, w, t)))
        }
        "truncated_ale_rhs" => {
            truncated_ale_rhs(seed, |i: Vec3, d: Vec3, w: Vec3| remote(to, n, (i, d, w)))
        }
        "energy_rate" => energy_rate(seed, |i: Vec3, d: Vec3, w: Vec3| remote(to, n, (i, d, w))),
        "euler_from_rotation" => euler_from_rotation(seed, |m: &Mat3| remote(to, n, (*m,))),
        "truncated_omega_perp" => {
            truncated_omega_perp(seed, |r: Real, s: Real, w: Real, t: Real| {
                remote(to, n, (r, s, w, t))
            })
        }
        "truncated_closed_form" => {
            truncated_closed_form(seed, |r: Real, s: Real, w: Vec3, t: Real| {
                remote(to, n, (r, s, w, t))
            })
        }
        "truncated_time_to_factor" => {
            truncated_time_to_factor(seed, |r: Real, s: Real, w: Real, p: Real| {
                remote(to, n, (r, s, w, p))
            })
        }
        "precession_tilt" => precession_tilt(seed, |r: Real, w: Vec3| remote(to, n, (r, w))),
        "reduced_ale_rhs" => {
            reduced_ale_rhs(seed, |r: Real, s: Real, w: Vec3| remote(to, n, (r, s, w)))
        }
        "reduced_decay_time" => {
            reduced_decay_time(seed, |r: Real, s: Real, w: Real| remote(to, n, (r, s, w)))
        }
        "reduced_closed_form" => reduced_closed_form(seed, |r: Real, s: Real, w: Vec3, t: Real| {
            remote(to, n, (r, s, w, t))
        }),
        "rk4_step" => rk4_step_on(seed, |f: &Field, t: Real, y: &State<3>, h: Real| {
            remote(to, n, (*f, t, *y, h))
        }),
        "dp5_step" => dp5_step_on(seed, |f: &Field, t: Real, y: &State<3>, h: Real| {
            remote(to, n, (*f, t, *y, h))
        }),
        "reduced_rk4" => reduced_rk4(seed, |r: Real, s: Real, w: Vec3, e: Real, k: usize| {
            remote(to, n, (r, s, w, e, k))
        }),
        "shell_masses" => shell_masses(seed, |t: Real, d: Real| remote(to, n, (t, d))),
        "shell_acceleration" => shell_acceleration(seed, |t: Real, d: Real, z: C, r: C| {
            remote(to, n, (t, d, z, r))
        }),
        "characteristic_root" => {
            characteristic_root(seed, |t: Real, d: Real| remote(to, n, (t, d)))
        }
        _ => return None,
    };
    Some(grade)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// A runner in this process: a fixed function of the numbers that
    /// crossed the wire, its calls counted.
    struct Here<F: Fn(&str, &[Real]) -> Result<Vec<Real>, Fault>> {
        answer: F,
        calls: Cell<usize>,
        garbled: Cell<bool>,
    }

    impl<F: Fn(&str, &[Real]) -> Result<Vec<Real>, Fault>> Remote for Here<F> {
        fn call(&self, name: &str, args: &[Real]) -> Result<Vec<Real>, Fault> {
            self.calls.set(self.calls.get() + 1);
            (self.answer)(name, args)
        }
        fn garbled(&self, _: &str) {
            self.garbled.set(true);
        }
    }

    fn here<F: Fn(&str, &[Real]) -> Result<Vec<Real>, Fault>>(answer: F) -> Here<F> {
        Here {
            answer,
            calls: Cell::new(0),
            garbled: Cell::new(false),
        }
    }

    #[test]
    fn a_right_answer_through_the_wire_passes_and_a_panic_is_a_panic() {
        // (2.1): −d′ × d″, computed from the numbers that crossed the wire.
        let right = here(|_, args| {
            let (j,): (Jet,) = wire::value(args).expect("a jet");
            Ok(wire::numbers(&-j[1].cross(&j[2])))
        });
        assert!(grade_remote("larmor_rate", 7, &right).unwrap().is_ok());
        assert!(right.calls.get() >= crate::CASES);
        let stub = here(|_, _| Err(Fault::Panicked("not yet implemented: Eq. (2.1)".into())));
        let failed = grade_remote("larmor_rate", 7, &stub).unwrap().unwrap_err();
        assert!(failed.is_stub(), "{failed}");
        assert!(grade_remote("no_such_thing", 7, &stub).is_none());
    }

    #[test]
    fn an_answer_of_the_wrong_shape_is_garbled_and_fails() {
        let short = here(|_, _| Ok(vec![1.0, 2.0]));
        let failed = grade_remote("larmor_rate", 7, &short).unwrap().unwrap_err();
        assert!(short.garbled.get());
        assert!(failed.actual.contains(LOST), "{failed}");
    }

    #[test]
    fn every_assignment_of_the_runner_has_a_grader() {
        let lost = here(|_, _| Err(Fault::Lost));
        for name in spintop_runner::ASSIGNMENTS {
            let grade = grade_remote(name, 1, &lost);
            assert!(
                matches!(&grade, Some(Err(f)) if f.actual.contains(LOST)),
                "{name}: {grade:?}"
            );
        }
    }
}
