//! The same questions asked by flags: `simulate`, `balance`, `orbit`,
//! `shell` and `plot` fill the structures a scene file fills
//! ([`super::format`]) and are validated by the same code as a scene's
//! sections, against the same table ([`super::table`]). A refusal is the
//! scene's message with the keys named as flags (`--ratio` for
//! `[top] ratio`), one line with nothing before it.

pub use super::format::{At, Given, Key, RawBalance, RawOrbit, RawShell, RawSolve, RawTop};
use super::keys::{Ctx, count, number};
pub use super::keys::{Refusal, not_known, overflows};
use super::table::Command;
use super::{BalanceScene, OrbitScene, ShellScene, TopRequest, kinds, top};
use crate::math::Real;

/// The keys of a top (`simulate`'s and `plot`'s flags) validated like a
/// `[top]` scene's.
pub fn top(top: &RawTop, solve: &RawSolve) -> Result<TopRequest, Refusal> {
    top::top_flags(top, solve)
}

/// `balance`'s flags validated like a `[balance]` scene.
pub fn balance(raw: &RawBalance, solve: &RawSolve) -> Result<BalanceScene, Refusal> {
    kinds::balance_flags(raw, solve)
}

/// `orbit`'s flags validated like an `[orbit]` scene.
pub fn orbit(raw: &RawOrbit, solve: &RawSolve) -> Result<OrbitScene, Refusal> {
    kinds::orbit_flags(raw, solve)
}

/// `shell`'s flags validated like a `[shell]` scene.
pub fn shell(raw: &RawShell, solve: &RawSolve) -> Result<ShellScene, Refusal> {
    kinds::shell_flags(raw, solve)
}

/// A number flag of `command` that no constructor checks, against the
/// table's range for `[section] key` (a chart's last time).
pub fn checked_number(
    command: Command,
    section: &str,
    key: &str,
    value: Real,
) -> Result<Real, Refusal> {
    let ctx = Ctx::flags(command);
    let given = Some(Given::flag(value));
    Ok(number(&ctx, section, key, &given, true)?.map_or(value, |(x, _)| x))
}

/// A whole-number flag of `command`, against the table's range for
/// `[section] key` (a chart's width).
pub fn checked_count(
    command: Command,
    section: &str,
    key: &str,
    value: i64,
) -> Result<usize, Refusal> {
    let ctx = Ctx::flags(command);
    let given = Some(Given::flag(value));
    Ok(count(&ctx, section, key, &given)?.map_or(0, |(n, _)| n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::table::{Bound, Range, SPECS, Spec};

    /// Whether the flags of `spec`'s command, a valid question but for
    /// `spec`'s key set to `x`, are accepted.
    fn accepts(spec: &Spec, x: Real) -> bool {
        let g = |v: Real| Some(Given::flag(v));
        let name = |s: &str| Some(Given::flag(s.to_string()));
        let mut solve = RawSolve {
            t_end: g(1.0),
            ..RawSolve::default()
        };
        match (spec.section, spec.key) {
            ("solve", "rtol") if spec.command == Command::Simulate => solve.rtol = g(x),
            ("solve", "rtol") => solve.rtol = g(x),
            ("solve", "step") => {
                solve.method = name("rk4");
                solve.step = g(x);
            }
            ("solve", "t_end") => solve.t_end = g(x),
            ("solve", "samples") => solve.samples = Some(Given::flag(x as i64)),
            _ => {}
        }
        match spec.command {
            Command::Simulate => {
                let mut top = RawTop {
                    model: name("truncated"),
                    ..RawTop::default()
                };
                match spec.key {
                    "ratio" => top.ratio = g(x),
                    "omega" => top.omega = Some(Given::flag([x, 0.0, 0.0])),
                    "dipole" => {
                        top.inertia = Some(Given::flag([1.0, 2.0, 2.5]));
                        top.dipole = Some(Given::flag([0.0, 0.0, x]));
                    }
                    _ => {}
                }
                super::top(&top, &solve).is_ok()
            }
            Command::Balance => {
                let mut raw = RawBalance {
                    dipole: name("precessing"),
                    ..RawBalance::default()
                };
                match spec.key {
                    "cone" => raw.cone = g(x),
                    "rate" => raw.rate = g(x),
                    "masses" | "length" => {
                        raw.dipole = name("dumbbell");
                        if spec.key == "length" {
                            raw.length = g(x);
                        } else {
                            raw.masses = Some(Given::flag([1.0, x]));
                        }
                    }
                    _ => {}
                }
                balance(&raw, &solve).is_ok()
            }
            Command::Orbit => {
                let mut raw = RawOrbit {
                    potential: name("harmonic"),
                    tau0: g(1e-3),
                    ..RawOrbit::default()
                };
                match spec.key {
                    "tau0" => raw.tau0 = g(x),
                    "r0" => raw.r0 = g(x),
                    "eccentricity" => raw.eccentricity = g(x),
                    _ => {}
                }
                orbit(&raw, &solve).is_ok()
            }
            Command::Shell => {
                let mut raw = RawShell {
                    tau0: g(1e-3),
                    delay: g(0.03),
                };
                match spec.key {
                    "tau0" => raw.tau0 = g(x),
                    "delay" => raw.delay = g(x),
                    _ => {}
                }
                // In range but too much work for the method of steps (a
                // delay of 5e-324 takes 5e302 steps per delay): refused
                // for the work, not the range.
                shell(&raw, &solve).map_or_else(|e| e.message.contains("RK4 steps"), |_| true)
            }
            Command::Plot => spec.range.contains(x),
        }
    }

    /// Values at each end of a range, with whether the range holds them:
    /// the end itself and the double just beyond it.
    fn probes(range: &Range) -> Vec<(Real, bool)> {
        let mut out = Vec::new();
        match *range {
            Range::Between(lo, hi) => {
                match lo {
                    Bound::Open(a) => out.extend([(a, false), (a.next_up(), true)]),
                    Bound::Closed(a) => out.extend([(a, true), (a.next_down(), false)]),
                    Bound::None => {}
                }
                match hi {
                    Bound::Open(b) => out.extend([(b, false), (b.next_down(), true)]),
                    Bound::Closed(b) => out.extend([(b, true), (b.next_up(), false)]),
                    Bound::None => {}
                }
            }
            Range::NonZero | Range::EachPositive => out.extend([(0.0, false), (1.0, true)]),
            Range::EachAtMost(m) => out.extend([(m, true), (m.next_up(), false)]),
            Range::Count(lo, hi) => out.extend([
                (lo as Real, true),
                (lo as Real - 1.0, false),
                (hi as Real, true),
                (hi as Real + 1.0, false),
            ]),
            _ => {}
        }
        out
    }

    /// The ranges `--help` states are the ones the checks enforce: at each
    /// end of each key's range, the value the range holds is accepted and
    /// the double beyond it refused, by the validation a flag goes through.
    #[test]
    fn each_range_in_the_table_is_what_the_checks_enforce() {
        let mut wrong = Vec::new();
        let mut probed = 0;
        for spec in SPECS {
            for (x, held) in probes(&spec.range) {
                probed += 1;
                if accepts(spec, x) != held {
                    wrong.push(format!(
                        "{:?} [{}] {} = {x:e}: the table says {}",
                        spec.command,
                        spec.section,
                        spec.key,
                        if held { "in range" } else { "out of range" }
                    ));
                }
            }
        }
        assert!(probed > 40, "{probed}");
        assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    }
}
