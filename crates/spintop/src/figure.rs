//! The paper's Figures 1 and 2 as point sets (paper §5 and its two figures).
//!
//! The paper's figure files are missing from its source, so these are the
//! figures a reader sees. Both use the parameters printed in the captions:
//! I₃/I₁ = 2/5 and Ω₀ = (0, 0.1, 0.2) in units of 1/τ.
//!
//! | figure | model | left panel | right panel |
//! |---|---|---|---|
//! | 1 | truncated (4.2)–(4.4) | hodograph of Ω on the cone Ω₃/Ω⊥ = Ω₃₀/Ω⊥₀, (4.7) | θ constant, φ̇ and ψ̇ falling as 1/√t, (4.11) |
//! | 2 | reduced (4.12)–(4.14) | hodograph of Ω in the plane Ω₃ = Ω₃₀, (4.15)–(4.16) | θ → 0 like e^(−t/σ), spin Ω₃ kept, (4.18) |
//!
//! Pure: the points only, no drawing and no files (the ASCII and SVG renderers
//! live in [`crate::plot::figure`]). Every point is a [`Sample`] of a
//! [`Simulation`] with [`MethodChoice::Auto`]: the truncated model is closed
//! form throughout, the reduced model has a closed-form Ω and an orientation
//! integrated on SO(3).
//!
//! The lab frame is the one in which the paper's particular solutions hold:
//! lab z along L for Figure 1 (L keeps its direction, (4.11)), and lab z along
//! the final direction L∞ for Figure 2 (erratum 5: only there does θ → 0).
//!
//! | code name | symbol | meaning | units |
//! |---|---|---|---|
//! | `FIGURE_RATIO` | I₃/I₁ | moment ratio of both figures | – |
//! | `FIGURE_OMEGA0` | Ω₀ | initial body angular velocity | 1/τ |
//! | `sample.omega` | Ω(t) | a point of the hodograph (body frame) | 1/τ |
//! | `Figure::axis` | e₃(t) = O(t)ẑ | the symmetry axis in the lab, a point on the unit sphere | – |
//! | `sample.euler` | (φ, θ, ψ) | z-x-z Euler angles in the figure's lab frame | rad |
//! | `sample.euler_rates` | (φ̇, θ̇, ψ̇) | their rates, (4.8) | 1/τ |
//! | `l_limit` | L∞/\|L∞\| | the direction L tends to (lab z) | – |

use crate::math::{Mat3, Real, Vec3, rot_axis};
use crate::physics::euler_angles::{EulerAngles, frame_with_z_along};
use crate::physics::rigid_body::angular_momentum_body;
use crate::physics::symmetric_top::SymmetricTop;
use crate::sim::{InitialState, MethodChoice, MethodOptions, Model, Sample, SimError, Simulation};
use thiserror::Error;

/// I₃/I₁ and Ω₀ (in units of 1/τ) of both figures.
pub use crate::physics::symmetric_top::{FIGURE_OMEGA0, FIGURE_RATIO};

/// Which of the paper's two figures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FigureNumber {
    /// Figure 1: the truncated model, no Schott term.
    One,
    /// Figure 2: the reduced model, Schott term kept.
    Two,
}

/// A figure number the paper does not have.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum FigureError {
    /// Only 1 and 2 exist.
    #[error("the paper has Figures 1 and 2 only, not {0}")]
    NoSuchFigure(String),
    /// The simulation behind the figure failed (not expected for the paper's parameters).
    #[error(transparent)]
    Sim(#[from] SimError),
}

impl FigureNumber {
    /// Parse "1" or "2".
    pub fn parse(s: &str) -> Result<Self, FigureError> {
        match s.trim() {
            "1" => Ok(Self::One),
            "2" => Ok(Self::Two),
            other => Err(FigureError::NoSuchFigure(other.to_string())),
        }
    }

    /// 1 or 2.
    pub fn number(self) -> u32 {
        match self {
            Self::One => 1,
            Self::Two => 2,
        }
    }

    /// The model the figure shows.
    pub fn model(self) -> Model {
        let top = SymmetricTop::figure();
        match self {
            Self::One => Model::Truncated(top),
            Self::Two => Model::Reduced(top),
        }
    }

    /// The last plotted time, in τ.
    ///
    /// NOTE: Figure 1 runs to t = 5000, where every rate has fallen by
    /// R = √101 ≈ 10 and Ω has turned 17 times about the cone; Figure 2 to
    /// t = 600 ≈ 3.8σ, where Ω⊥ is below 1 % of its start and the rest of the
    /// spiral would not show.
    pub fn t_end(self) -> Real {
        match self {
            Self::One => 5000.0,
            Self::Two => 600.0,
        }
    }

    // ANCHOR: figure_times
    /// The plotted times: N + 1 of them from 0 to [`t_end`](Self::t_end).
    ///
    /// NOTE: Figure 1 is sampled evenly in the slowed clock ϑ of (4.9), not in
    /// t: both the turn of Ω about the cone (Ω̃₃₀ϑ) and the precession in space
    /// (|L₀|ϑ/I₁) advance by the same angle between points, about 0.12 rad,
    /// although their rates in t fall as 1/R. Figure 2's rates tend to
    /// constants, so even steps in t do the same there.
    pub fn times(self) -> Vec<Real> {
        const N: usize = 900;
        match self {
            Self::One => {
                // t(ϑ) = ϑ(1 + τΩ⊥₀²ϑ/2), the inverse of ϑ = (R − 1)/(τΩ⊥₀²).
                let u0 = FIGURE_OMEGA0[0].powi(2) + FIGURE_OMEGA0[1].powi(2);
                let t_end = self.t_end();
                let r_end = (1.0 + 2.0 * u0 * t_end).sqrt();
                let vartheta_end = 2.0 * t_end / (1.0 + r_end);
                (0..=N)
                    .map(|i| {
                        if i == N {
                            return t_end;
                        }
                        let vartheta = vartheta_end * i as Real / N as Real;
                        vartheta * (1.0 + 0.5 * u0 * vartheta)
                    })
                    .collect()
            }
            Self::Two => (0..=N)
                .map(|i| self.t_end() * i as Real / N as Real)
                .collect(),
        }
    }
    // ANCHOR_END: figure_times
}

/// One of the paper's figures as points: the hodograph and the motion in space.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// Which figure.
    pub number: FigureNumber,
    /// The model it shows.
    pub model: Model,
    /// Ω₀ in the body frame.
    pub omega0: Vec3,
    /// The plotted points, at [`FigureNumber::times`], in the figure's lab frame.
    pub samples: Vec<Sample>,
    /// The unit vector L tends to as t → ∞ (lab z, by the choice of frame).
    pub l_limit: Vec3,
    /// The orientation at t = 0 (body → lab) that puts lab z along `l_limit`.
    pub initial_rotation: Mat3,
}

/// Where the reduced model's L has settled (in units of τ): L approaches its
/// limit like e^(−t/σ) with σ = 156.25, so by t = 8000 the rest is e^(−51),
/// far below rounding.
pub const SETTLED_TIME: Real = 8000.0;

impl Figure {
    /// Compute the points of Figure `number`.
    pub fn new(number: FigureNumber) -> Result<Self, FigureError> {
        let model = number.model();
        let omega0 = Vec3::from(FIGURE_OMEGA0);
        let inertia = model.inertia();
        let top = SymmetricTop::figure();
        // Start with lab z along L₀, the frame of (4.11).
        let start = frame_with_z_along(&angular_momentum_body(&top.inertia(), &omega0));
        let initial = InitialState::new(omega0, start)?;
        let times = number.times();
        let (samples, l_limit, initial_rotation) = match number {
            FigureNumber::One => {
                // L keeps its direction: the frame of L₀ is already the frame of L∞.
                let mut sim = Simulation::new(
                    model,
                    MethodChoice::Auto,
                    MethodOptions::default(),
                    initial,
                    Some(number.t_end()),
                )?;
                (sim.run(&times)?, Vec3::z(), initial.rotation)
            }
            FigureNumber::Two => {
                // ANCHOR: reduced_frame
                // L turns while the top stands up. Run on to where it has settled,
                // then turn the whole lab so that its final direction is z: all
                // orientations of a free top are equivalent (paper §4.1), so the
                // turned motion is again a solution, started from R·O(0).
                let mut sim = Simulation::new(
                    model,
                    MethodChoice::Auto,
                    MethodOptions::default(),
                    initial,
                    Some(SETTLED_TIME),
                )?;
                let samples = sim.run(&times)?;
                let settled = *sim.advance_to(SETTLED_TIME)?;
                let l_inf = Vec3::from(settled.l_lab).normalize();
                let turn = turn_onto_z(&l_inf);
                let samples = samples
                    .iter()
                    .map(|s| {
                        Sample::new(s.t, &inertia, &(turn * s.rotation_matrix()), &s.omega_vec())
                    })
                    .collect();
                (samples, Vec3::z(), turn * initial.rotation)
                // ANCHOR_END: reduced_frame
            }
        };
        Ok(Self {
            number,
            model,
            omega0,
            samples,
            l_limit,
            initial_rotation,
        })
    }

    /// The symmetric top both figures share.
    pub fn top(&self) -> SymmetricTop {
        SymmetricTop::figure()
    }

    /// The initial orientation as z-x-z Euler angles (to start another run there).
    pub fn initial_euler(&self) -> EulerAngles {
        EulerAngles::from_rotation(&self.initial_rotation)
    }

    /// The symmetry axis e₃ = O(t)ẑ of a sample, in the lab.
    pub fn axis(sample: &Sample) -> Vec3 {
        let r = &sample.rotation;
        Vec3::new(r[0][2], r[1][2], r[2][2])
    }

    /// The caption, in the paper's words reworded.
    pub fn caption(&self) -> &'static str {
        match self.number {
            FigureNumber::One => {
                "Figure 1, truncated ALE (4.2)-(4.4), no Schott term: Omega spirals down its cone to 0; \
                 the axis keeps its tilt theta from L while precession and spin slow as 1/sqrt(t)."
            }
            FigureNumber::Two => {
                "Figure 2, reduced ALE (4.12)-(4.14), Schott term kept: Omega spirals in the plane \
                 Omega_3 = 0.2 to (0, 0, 0.2); the axis stands up along L (theta -> 0 like exp(-t/sigma)) \
                 and keeps spinning at Omega_3."
            }
        }
    }
}

/// The smallest rotation that takes the unit vector `n` onto lab z.
fn turn_onto_z(n: &Vec3) -> Mat3 {
    let axis = n.cross(&Vec3::z());
    let angle = axis.norm().atan2(n.z);
    if axis.norm() == 0.0 {
        // n is ±z already; turn about x when it points down.
        return rot_axis(&Vec3::x(), if n.z < 0.0 { angle } else { 0.0 });
    }
    rot_axis(&axis, angle)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn figure_numbers_parse_and_refuse() {
        assert_eq!(FigureNumber::parse("1"), Ok(FigureNumber::One));
        assert_eq!(FigureNumber::parse(" 2"), Ok(FigureNumber::Two));
        for bad in ["3", "0", "one", ""] {
            assert!(FigureNumber::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn turn_onto_z_takes_the_vector_to_z() {
        for n in [
            Vec3::new(0.3, -0.4, 0.5),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.0, 0.0, -2.0),
            Vec3::new(1.0, 0.0, 0.0),
        ] {
            let n = n.normalize();
            let m = turn_onto_z(&n);
            assert_relative_eq!(m * n, Vec3::z(), epsilon = 1e-15);
            assert_relative_eq!(m.determinant(), 1.0, epsilon = 1e-14);
        }
    }

    #[test]
    fn figure_times_are_even_in_the_slowed_clock() {
        let times = FigureNumber::One.times();
        assert_eq!(times.len(), 901);
        assert_eq!(times[0], 0.0);
        assert_eq!(*times.last().unwrap(), 5000.0);
        let vartheta = |t: Real| 2.0 * t / (1.0 + (1.0 + 0.02 * t).sqrt());
        let steps: Vec<Real> = times
            .windows(2)
            .map(|w| vartheta(w[1]) - vartheta(w[0]))
            .collect();
        for s in &steps {
            assert_relative_eq!(*s, steps[0], max_relative = 1e-9);
        }
    }
}
