//! The same questions asked by flags: `simulate`, `balance`, `orbit`,
//! `shell` and `plot` fill the structures a scene file fills
//! ([`super::format`]) and are validated by the same code as a scene's
//! sections, against the same table ([`super::table`]). A refusal is the
//! scene's message with the keys named as flags (`--ratio` for
//! `[top] ratio`), one line with nothing before it.

pub use super::format::{At, Given, Key, RawBalance, RawOrbit, RawShell, RawSolve, RawTop};
pub use super::keys::Refusal;
use super::keys::{Ctx, count, number};
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
