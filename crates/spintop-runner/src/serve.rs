//! The runner's loop: one call per line in, one answer per line out.

use crate::wire::{self, Wire};
use spintop::assignment::Real;
use std::io::{BufRead, Write};
use std::panic::{AssertUnwindSafe, catch_unwind};

/// The character that starts every line the runner answers with: what the
/// student's code prints (a `println!` left in) is any other line, or text
/// before it on the same line, and is passed over.
pub const MARK: char = '\u{1e}';

/// The first line a runner writes (after [`MARK`]): the protocol and its
/// version.
pub const HELLO: &str = "spintop-runner 1";

/// The longest panic message an answer carries.
const MAX_MESSAGE: usize = 300;

/// The course's functions a runner answers for, by name (its table is
/// [`dispatch!`](crate::dispatch)).
pub const ASSIGNMENTS: [&str; 22] = [
    "larmor_rate",
    "schott_angular_momentum",
    "torque_rate",
    "schott_rate",
    "axial_schott_rate",
    "precessing_dipole_jet",
    "truncated_ale_rhs",
    "energy_rate",
    "euler_from_rotation",
    "truncated_omega_perp",
    "truncated_closed_form",
    "truncated_time_to_factor",
    "precession_tilt",
    "reduced_ale_rhs",
    "reduced_decay_time",
    "reduced_closed_form",
    "rk4_step",
    "dp5_step",
    "reduced_rk4",
    "shell_masses",
    "shell_acceleration",
    "characteristic_root",
];

/// A runner's answer to one call.
#[derive(Debug, Clone, PartialEq)]
pub enum Reply {
    /// The function returned: its answer's numbers.
    Answer(Vec<Real>),
    /// The function panicked: its message (one line, at most 300 characters).
    Panicked(String),
    /// The call was not made: no such function, or arguments that do not
    /// fit it.
    Refused(String),
}

/// A message as one short line: no line breaks, no [`MARK`], no control
/// characters, at most [`MAX_MESSAGE`] characters.
fn one_line(message: &str) -> String {
    message
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .take(MAX_MESSAGE)
        .collect()
}

impl Reply {
    /// The reply as the runner writes it (without the line's end).
    pub fn line(&self) -> String {
        match self {
            Reply::Answer(n) => format!("{MARK}ok {}", wire::text(n)),
            Reply::Panicked(m) => format!("{MARK}panic {}", one_line(m)),
            Reply::Refused(m) => format!("{MARK}refused {}", one_line(m)),
        }
    }
}

/// The reply in a line the runner wrote, if it holds one: what follows the
/// line's last [`MARK`] (text before it is the student's own printing).
pub fn parse_reply(line: &str) -> Option<Reply> {
    let (_, reply) = line.rsplit_once(MARK)?;
    let (kind, rest) = reply.split_once(' ').unwrap_or((reply, ""));
    match kind {
        "ok" => wire::parse(rest).map(Reply::Answer),
        "panic" => Some(Reply::Panicked(rest.to_string())),
        "refused" => Some(Reply::Refused(rest.to_string())),
        _ => None,
    }
}

/// The line that calls `name` with `args` (without the line's end).
pub fn request(name: &str, args: &[Real]) -> String {
    format!("{name} {}", wire::text(args))
}

/// Calls `f` with the value `args` make, and answers with what it returns
/// or the message it panicked with.
pub fn answer<A: Wire, R: Wire>(args: &[Real], f: impl FnOnce(A) -> R) -> Reply {
    let Some(a) = wire::value::<A>(args) else {
        return Reply::Refused("the numbers do not make the function's arguments".into());
    };
    match catch_unwind(AssertUnwindSafe(|| f(a))) {
        Ok(r) => Reply::Answer(wire::numbers(&r)),
        Err(payload) => Reply::Panicked(
            payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic".to_string()),
        ),
    }
}

/// The runner's `main`: says [`HELLO`], then answers every line of its
/// standard input (`NAME NUMBERS…`) with `dispatch(NAME, NUMBERS)` on its
/// standard output, until its input ends.
pub fn serve(dispatch: impl Fn(&str, &[Real]) -> Reply) {
    // The grader reports a panic's message itself; the default hook would
    // print it to the runner's stderr for nobody.
    std::panic::set_hook(Box::new(|_| {}));
    let mut out = std::io::stdout();
    if writeln!(out, "{MARK}{HELLO}")
        .and_then(|()| out.flush())
        .is_err()
    {
        return;
    }
    let stdin = std::io::stdin();
    let mut line = String::new();
    loop {
        line.clear();
        // The lock is not held while the student's function runs.
        match stdin.lock().read_line(&mut line) {
            Ok(0) | Err(_) => return,
            Ok(_) => {}
        }
        let (name, numbers) = line
            .trim_end()
            .split_once(' ')
            .unwrap_or((line.trim_end(), ""));
        let reply = match wire::parse(numbers) {
            Some(args) => dispatch(name, &args),
            None => Reply::Refused("the arguments are not numbers".into()),
        };
        if writeln!(out, "{}", reply.line())
            .and_then(|()| out.flush())
            .is_err()
        {
            return;
        }
    }
}

/// The runner's table of the course's 22 functions in the lessons crate
/// `$lessons`: a closure `(name, numbers) -> Reply` for [`serve`]. The
/// runner that `spintop course` builds is this, and nothing else:
///
/// ```text
/// fn main() {
///     spintop_runner::serve(spintop_runner::dispatch!(spintop_lessons));
/// }
/// ```
#[macro_export]
macro_rules! dispatch {
    ($lessons:ident) => {
        |name: &str, args: &[$crate::Real]| -> $crate::Reply {
            use $crate::fields::Field;
            use $crate::{C, Jet, Mat3, Real, State, Vec3, answer};
            use $lessons::{appendix, ch2, ch3, ch4, numerics};
            match name {
                "larmor_rate" => answer(args, |(j,): (Jet,)| ch2::larmor_rate(&j)),
                "schott_angular_momentum" => {
                    answer(args, |(j,): (Jet,)| ch2::schott_angular_momentum(&j))
                }
                "torque_rate" => answer(args, |(j,): (Jet,)| ch2::torque_rate(&j)),
                "schott_rate" => answer(args, |(j,): (Jet,)| ch2::schott_rate(&j)),
                "axial_schott_rate" => answer(args, |(j,): (Jet,)| ch2::axial_schott_rate(&j)),
                "precessing_dipole_jet" => answer(args, |(a, w, t): (Real, Real, Real)| {
                    ch2::precessing_dipole_jet(a, w, t)
                }),
                "truncated_ale_rhs" => answer(args, |(i, d, w): (Vec3, Vec3, Vec3)| {
                    ch3::truncated_ale_rhs(i, d, w)
                }),
                "energy_rate" => answer(args, |(i, d, w): (Vec3, Vec3, Vec3)| {
                    ch3::energy_rate(i, d, w)
                }),
                "euler_from_rotation" => {
                    answer(args, |(m,): (Mat3,)| numerics::euler_from_rotation(&m))
                }
                "truncated_omega_perp" => answer(args, |(r, s, w, t): (Real, Real, Real, Real)| {
                    ch4::truncated_omega_perp(r, s, w, t)
                }),
                "truncated_closed_form" => {
                    answer(args, |(r, s, w, t): (Real, Real, Vec3, Real)| {
                        ch4::truncated_closed_form(r, s, w, t)
                    })
                }
                "truncated_time_to_factor" => {
                    answer(args, |(r, s, w, p): (Real, Real, Real, Real)| {
                        ch4::truncated_time_to_factor(r, s, w, p)
                    })
                }
                "precession_tilt" => {
                    answer(args, |(r, w): (Real, Vec3)| ch4::precession_tilt(r, w))
                }
                "reduced_ale_rhs" => answer(args, |(r, s, w): (Real, Real, Vec3)| {
                    ch4::reduced_ale_rhs(r, s, w)
                }),
                "reduced_decay_time" => answer(args, |(r, s, w): (Real, Real, Real)| {
                    ch4::reduced_decay_time(r, s, w)
                }),
                "reduced_closed_form" => answer(args, |(r, s, w, t): (Real, Real, Vec3, Real)| {
                    ch4::reduced_closed_form(r, s, w, t)
                }),
                "rk4_step" => answer(args, |(f, t, y, h): (Field, Real, State<3>, Real)| {
                    numerics::rk4_step(&|t: Real, y: &State<3>| f.eval(t, y), t, &y, h)
                }),
                "dp5_step" => answer(args, |(f, t, y, h): (Field, Real, State<3>, Real)| {
                    numerics::dp5_step(&|t: Real, y: &State<3>| f.eval(t, y), t, &y, h)
                }),
                "reduced_rk4" => {
                    answer(args, |(r, s, w, e, n): (Real, Real, Vec3, Real, usize)| {
                        numerics::reduced_rk4(r, s, w, e, n)
                    })
                }
                "shell_masses" => answer(args, |(t, d): (Real, Real)| appendix::shell_masses(t, d)),
                "shell_acceleration" => answer(args, |(t, d, z, r): (Real, Real, C, C)| {
                    appendix::shell_acceleration(t, d, z, r)
                }),
                "characteristic_root" => answer(args, |(t, d): (Real, Real)| {
                    appendix::characteristic_root(t, d)
                }),
                _ => $crate::Reply::Refused(format!("no assignment is called {name}")),
            }
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reply_is_found_after_what_the_student_printed() {
        let ok = Reply::Answer(vec![1.0, -0.5]);
        assert_eq!(parse_reply(&ok.line()), Some(ok.clone()));
        assert_eq!(parse_reply(&format!("debug: x = 3{}", ok.line())), Some(ok));
        assert_eq!(parse_reply("test eq_2_1_larmor_rate ... ok"), None);
        let panic = Reply::Panicked("line one\nline two\u{1e}ok 1".into());
        assert_eq!(
            parse_reply(&panic.line()),
            Some(Reply::Panicked("line one line two ok 1".into()))
        );
    }

    #[test]
    fn an_answer_carries_the_value_or_the_panic() {
        let args = wire::numbers(&(2.0, 3.0));
        assert_eq!(
            answer(&args, |(a, b): (Real, Real)| a * b),
            Reply::Answer(vec![6.0])
        );
        std::panic::set_hook(Box::new(|_| {}));
        assert_eq!(
            answer(&args, |(_, _): (Real, Real)| -> Real { todo!() }),
            Reply::Panicked("not yet implemented".into())
        );
        let _ = std::panic::take_hook();
        assert!(matches!(
            answer(&args[..1], |(a, b): (Real, Real)| a * b),
            Reply::Refused(_)
        ));
    }
}
