//! What every shell shows the same way: the lab frame the live views draw
//! in, and how numbers are read from the user and written on axes.
//!
//! The shells (the command line, the live view, the book server, the course)
//! stand side by side above the core and never import each other; what two
//! of them need lives here, below all of them. Nothing here does physics
//! beyond choosing a frame from the core's own functions.

use crate::math::{Real, Vec3};
use crate::physics::euler_angles::{EulerAngles, frame_with_z_along};
use crate::physics::rigid_body::angular_momentum_body;
use crate::physics::symmetric_top::SymmetricTop;

/// The initial orientation that puts the lab z axis along L₀, as in the
/// paper's particular solution (4.11) and its figures: then θ is the tilt
/// between the axis and L, and φ̇ and ψ̇ are the precession and spin rates.
///
/// The third row of O = R_z(φ)R_x(θ)R_z(ψ) is (sin θ sin ψ, sin θ cos ψ,
/// cos θ) = Oᵀẑ, the lab z axis seen from the body; setting it to L₀/|L₀|
/// gives θ = the tilt and ψ = atan2(L₁, L₂) (φ = 0). L₀ = 0 keeps O = 1.
pub fn paper_frame(top: &SymmetricTop, omega0: [Real; 3]) -> EulerAngles {
    lab_frame(&top.inertia(), omega0)
}

/// [`paper_frame`] for any principal moments: the lab z axis along
/// L₀ = I Ω₀. The general top uses it too, so that both layouts show L
/// starting straight up; its Ω(t) does not depend on the orientation, so this
/// choice changes only the picture of the top in space.
pub fn lab_frame(inertia: &Vec3, omega0: [Real; 3]) -> EulerAngles {
    frame_with_z_along(&angular_momentum_body(inertia, &Vec3::from(omega0)))
}

/// A finite number from the user, or one line saying why not.
pub fn parse_number(s: &str) -> Result<Real, String> {
    let x: Real = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("'{s}' is not a finite number"))
    }
}

/// A number for the screen: four significant digits, an exponent outside
/// [1e-3, 1e5), "—" when undefined.
pub fn fmt_num(x: Real) -> String {
    if !x.is_finite() {
        return "—".into();
    }
    let a = x.abs();
    if a == 0.0 {
        "0".into()
    } else if (1e-3..1e5).contains(&a) {
        let digits = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.3e}")
    }
}

/// The smallest of 1, 2, 2.5, 5 times a power of ten that is at least `x`
/// (1 for zero or non-finite `x`): a round axis bound.
pub fn nice_ceiling(x: Real) -> Real {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let p = (10.0 as Real).powf(x.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|b| *b >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// An axis label: the shortest exact form when it is short, else [`fmt_num`].
pub fn fmt_axis(x: Real) -> String {
    let plain = format!("{x}");
    if plain.len() <= 6 { plain } else { fmt_num(x) }
}

/// A count for a message: in full below ten million, else in exponent form
/// (`1.8e19`), never a saturated integer's twenty digits.
pub fn fmt_count(n: f64) -> String {
    if n.is_finite() && n.abs() < 1e7 {
        format!("{n:.0}")
    } else {
        format!("{n:.1e}")
    }
}

/// An input parameter echoed in a header: as the user would write it
/// (`0.4`, `0.001`, `250`), in exponent form outside 10⁻⁴…10⁷ (`1e300`,
/// `1.5e-8`) instead of hundreds of digits, and never `-0`.
pub fn fmt_param(x: f64) -> String {
    crate::math::fmt_value(x)
}

/// A short key that is the same for the same text on every run and machine
/// (FNV-1a, 32 bits): names derived from a folder's path, so that two folders
/// never share a name (the scratch program of `spintop book`, the package of
/// an exported course).
pub fn stable_key(text: &str) -> u32 {
    let h = text.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    (h & 0xffff_ffff) as u32
}
