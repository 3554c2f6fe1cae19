//! Where a top leaves the regime its equations were derived for.
//!
//! The paper's laws (2.1) and (2.2), and so (3.3) and (3.4), expand the
//! radiation of a slowly turning dipole: the radiation time τ (τ_f for a
//! general top, [`fast_time`]) is taken short against the time the top needs
//! to turn through a radian. Where τ times the top's rate is of order 1 or
//! more, the charges of any real top would move at speeds near that of light
//! (or the top would be smaller than its classical radius), and the answers
//! are those of the equations, no longer of a top. This module says so, once,
//! for every entry point.

use super::Model;
use super::physical::general::fast_time;
use crate::math::{Real, Vec3};

/// τ times the top's rate at and above which the note is given.
pub const FAST_SPIN: Real = 1.0;

/// τ times the top's fastest rate: τ·max(|Ω₀|, |k|), k = (I₃/I₁)Ω₃, for
/// the symmetric models (τk is the spin term of (4.10)–(4.12)); τ_f|Ω₀| for
/// a general top.
pub fn spin_share(model: &Model, omega0: &Vec3) -> Real {
    match model {
        Model::Truncated(top) | Model::Reduced(top) | Model::Full(top) => {
            top.tau() * omega0.norm().max((top.ratio() * omega0.z).abs())
        }
        Model::General(top) | Model::GeneralReduced(top) | Model::GeneralFull(top) => {
            fast_time(top) * omega0.norm()
        }
    }
}

/// The note for a top spun at τ|Ω| ≥ [`FAST_SPIN`]; `None` below it.
pub fn fast_spin_note(model: &Model, omega0: &Vec3) -> Option<String> {
    let share = spin_share(model, omega0);
    let tau = match model {
        Model::General(_) | Model::GeneralReduced(_) | Model::GeneralFull(_) => "tau_f",
        _ => "tau",
    };
    (share >= FAST_SPIN).then(|| {
        format!(
            "{tau} times the spin rate is {}: the top turns a radian in less than the radiation time, outside the slow rotation the paper's radiation laws (2.1)-(2.2) are expanded for (a real top would need its charges near the speed of light); the numbers answer {}, not a real top",
            crate::numbers::fmt_about(share),
            model.equations()
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::general_top::GeneralTop;
    use crate::physics::symmetric_top::SymmetricTop;

    /// The symmetric top's share is τk where the spin dominates, τ|Ω₀|
    /// where the tumbling does; a general top
    /// top gives τ_f|Ω₀| (τ_f = |d|²/min I = 1 here).
    #[test]
    fn the_share_is_tau_times_the_fastest_rate() {
        let top = SymmetricTop::figure();
        let spin = Vec3::new(0.1, 0.0, 1e6);
        let share = spin_share(&Model::Full(top), &spin);
        assert_eq!(
            share,
            top.tau() * (top.ratio() * 1e6_f64).abs().max(spin.norm())
        );
        assert!(fast_spin_note(&Model::Full(top), &spin).is_some());
        assert!(fast_spin_note(&Model::Full(top), &Vec3::new(0.0, 0.1, 0.2)).is_none());
        let general = GeneralTop::new(Vec3::new(1.0, 1.2, 1.5), Vec3::new(0.0, 0.0, 1.0)).unwrap();
        let w = Vec3::new(3.0, 0.0, 0.0);
        assert_eq!(spin_share(&Model::General(general), &w), 3.0);
        assert!(fast_spin_note(&Model::General(general), &w).is_some());
    }
}
