//! The four problems of the work-precision sweep, each with its reference.
//!
//! Every problem starts from the paper's Ω₀ = (0, 0.1, 0.2) in units of 1/τ,
//! with O(0) the identity, and is sampled at t = 1, 2, …, 200 (200 output
//! points; T = 200τ is about six turns of Ω⊥ and one decay time of the reduced
//! model, where the tilt has visibly changed).
//!
//! | problem | model | reference for Ω | reference for O(t) |
//! |---|---|---|---|
//! | `truncated` | (4.2)–(4.4), I₃/I₁ = 0.4 | mpmath, 40 digits | mpmath, 40 digits |
//! | `reduced` | (4.12)–(4.14), I₃/I₁ = 0.4 | mpmath, 40 digits | mpmath, 40 digits |
//! | `general` | (3.3), I = (1, 1.5, 0.8), d = (0.2, 0, 1) | mpmath, 40 digits | mpmath, 40 digits |
//! | `full` | (3.4), physical solution, I₃/I₁ = 0.4 | [`physical_solution`] at rtol 1e-13 | – |
//!
//! The mpmath references are stored in `crates/spintop/reference/*.csv`, written by
//! `crates/spintop/reference/make_reference.py`: it integrates Ω and the orientation
//! quaternion together with mpmath's Taylor-series integrator at 40 digits,
//! from the exact binary values of spintop's inputs, and checks Ω against the
//! paper's closed forms (in their printed form) to 1e-30. They are independent
//! of every line of spintop's numerics, so even the closed-form rows have an
//! error to measure (rounding, about 1e-16).
//!
//! The full ALE has no closed form and its physical solution needs a shoot
//! (see [`crate::sim::physical`]); its reference is spintop's own shooting
//! solution at rtol 1e-13, computed when the problem is built. A test
//! (`tests/numerics/workprecision.rs`) checks it against the same at rtol 1e-12 and
//! against the slow-manifold series. Its orientation is not measured: it is
//! driven by an interpolated table of Ω (accurate to about 1e-9), so its error
//! would say more about the table than about the method.

use crate::integrate::{Rhs, Stats};
use crate::math::{Mat3, Quat, Real, State, Vec3};
use crate::physics::general_top::GeneralTop;
use crate::physics::symmetric_top::{SymmetricTop, reduced_ale_rhs, truncated_ale_rhs};
use crate::sim::physical::physical_solution;
use crate::sim::{InitialState, Model};
use nalgebra::Quaternion;

use super::SweepError;

/// The last output time, in τ.
pub const T_END: Real = 200.0;
/// The number of output points, at t = 1, 2, …, [`T_END`].
pub const SAMPLES: usize = 200;
/// The initial body rate of every problem, (Ω₁₀, Ω₂₀, Ω₃₀) in 1/τ: the paper's figures'.
pub const OMEGA0: [Real; 3] = crate::physics::symmetric_top::FIGURE_OMEGA0;
/// I₃/I₁ of the symmetric problems (the paper's figures).
pub const RATIO: Real = crate::physics::symmetric_top::FIGURE_RATIO;
/// Principal moments of the general problem (κ = 1 units).
pub const GENERAL_INERTIA: [Real; 3] = [1.0, 1.5, 0.8];
/// Body dipole of the general problem (κ = 1 units).
pub const GENERAL_DIPOLE: [Real; 3] = [0.2, 0.0, 1.0];
/// The tolerance of the full ALE's reference run.
pub const FULL_REFERENCE_RTOL: Real = 1e-13;

/// Which problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ProblemKind {
    /// The truncated model (4.2)–(4.4).
    Truncated,
    /// The reduced model (4.12)–(4.14).
    Reduced,
    /// The general truncated model (3.3), an asymmetric top.
    General,
    /// The physical solution of the full ALE (3.4).
    Full,
}

impl ProblemKind {
    /// Every problem, in the order of the paper.
    pub const ALL: [ProblemKind; 4] = [
        ProblemKind::Truncated,
        ProblemKind::Reduced,
        ProblemKind::General,
        ProblemKind::Full,
    ];

    /// The name used in tables, CSV files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ProblemKind::Truncated => "truncated",
            ProblemKind::Reduced => "reduced",
            ProblemKind::General => "general",
            ProblemKind::Full => "full",
        }
    }

    /// The problem of that name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// The right-hand side Ω̇ = F(Ω) of a first-order problem, as the integrators
/// (and the peers in `benches/peers.rs`) see it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OmegaRhs {
    /// (4.2)–(4.4).
    Truncated(SymmetricTop),
    /// (4.12)–(4.14).
    Reduced(SymmetricTop),
    /// (3.3).
    General(GeneralTop),
}

impl OmegaRhs {
    /// F(Ω).
    pub fn omega_dot(&self, omega: &Vec3) -> Vec3 {
        match self {
            OmegaRhs::Truncated(top) => truncated_ale_rhs(top, omega),
            OmegaRhs::Reduced(top) => reduced_ale_rhs(top, omega),
            OmegaRhs::General(top) => top.truncated_ale_rhs(omega),
        }
    }
}

impl Rhs<3> for OmegaRhs {
    fn eval(&self, _t: Real, y: &State<3>) -> State<3> {
        self.omega_dot(y)
    }
}

/// The reference a problem's errors are measured against, at its output times.
#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    /// Ω at each output time.
    pub omega: Vec<Vec3>,
    /// O(t) at each output time, where it is measured.
    pub rotation: Option<Vec<Mat3>>,
    /// Where the reference comes from, in one line.
    pub provenance: String,
    /// The work of the reference run, when spintop computed it.
    pub stats: Option<Stats>,
}

/// One problem of the sweep: a model, a start, output times and a reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    kind: ProblemKind,
    model: Model,
    initial: InitialState,
    times: Vec<Real>,
    reference: Reference,
}

/// The stored mpmath references, in the order of [`ProblemKind::ALL`].
const STORED: [(ProblemKind, &str); 3] = [
    (
        ProblemKind::Truncated,
        include_str!("../../reference/truncated.csv"),
    ),
    (
        ProblemKind::Reduced,
        include_str!("../../reference/reduced.csv"),
    ),
    (
        ProblemKind::General,
        include_str!("../../reference/general.csv"),
    ),
];

impl Problem {
    /// Build a problem and its reference. The full ALE's reference is a
    /// shooting solution (tens of milliseconds in a release build).
    pub fn new(kind: ProblemKind) -> Result<Self, SweepError> {
        let times: Vec<Real> = (1..=SAMPLES).map(|i| i as Real).collect();
        let omega0 = Vec3::from(OMEGA0);
        let initial = InitialState {
            omega: omega0,
            rotation: Mat3::identity(),
        };
        let symmetric = SymmetricTop::new(RATIO, 1.0).map_err(SweepError::from_display)?;
        let model = match kind {
            ProblemKind::Truncated => Model::Truncated(symmetric),
            ProblemKind::Reduced => Model::Reduced(symmetric),
            ProblemKind::General => Model::General(
                GeneralTop::new(Vec3::from(GENERAL_INERTIA), Vec3::from(GENERAL_DIPOLE))
                    .map_err(SweepError::from_display)?,
            ),
            ProblemKind::Full => Model::Full(symmetric),
        };
        let reference = match kind {
            ProblemKind::Full => full_reference(&symmetric, &omega0, &times)?,
            _ => {
                let text = STORED
                    .iter()
                    .find(|(k, _)| *k == kind)
                    .map(|(_, text)| *text)
                    .ok_or_else(|| SweepError::Reference(format!("no stored {}", kind.name())))?;
                parse_stored(text, &times, kind.name())
                    .map_err(|e| SweepError::Reference(format!("{}.csv: {e}", kind.name())))?
            }
        };
        Ok(Self {
            kind,
            model,
            initial,
            times,
            reference,
        })
    }

    /// Every problem, in the order of the paper.
    pub fn all() -> Result<Vec<Self>, SweepError> {
        ProblemKind::ALL.into_iter().map(Self::new).collect()
    }

    /// Which problem this is.
    pub fn kind(&self) -> ProblemKind {
        self.kind
    }

    /// Its name: `truncated`, `reduced`, `general`, `full`.
    pub fn name(&self) -> &'static str {
        self.kind.name()
    }

    /// The model, as [`crate::sim`] runs it.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Ω₀ and O(0).
    pub fn initial(&self) -> &InitialState {
        &self.initial
    }

    /// The output times, t = 1, 2, …, 200.
    pub fn times(&self) -> &[Real] {
        &self.times
    }

    /// The last output time.
    pub fn t_end(&self) -> Real {
        T_END
    }

    /// The reference.
    pub fn reference(&self) -> &Reference {
        &self.reference
    }

    /// Ω̇ = F(Ω) for the first-order models; `None` for the full ALE, whose
    /// state also holds Ω̇.
    pub fn omega_rhs(&self) -> Option<OmegaRhs> {
        match self.model {
            Model::Truncated(top) => Some(OmegaRhs::Truncated(top)),
            Model::Reduced(top) => Some(OmegaRhs::Reduced(top)),
            Model::General(top) => Some(OmegaRhs::General(top)),
            // Not a work-precision problem (yet): no peer measures it.
            Model::GeneralReduced(_) | Model::Full(_) | Model::GeneralFull(_) => None,
        }
    }

    /// Ω(t) from the closed form, for the two models that have one
    /// ([`Model::closed_form`]).
    pub fn closed_form(&self, t: Real) -> Option<Vec3> {
        self.model.closed_form(&self.initial.omega, t)
    }

    /// The absolute tolerance that goes with `rtol` for this problem.
    ///
    /// NOTE: the same rule as `spintop simulate` (1e-6·rtol·|Ω₀|): the control
    /// stays relative, and the absolute part only matters where a component
    /// passes through zero. SciPy and `ode_solvers` get the same pair.
    pub fn atol(&self, rtol: Real) -> Real {
        (1e-6 * rtol * self.initial.omega.norm()).max(1e-300)
    }
}

/// The full ALE's reference: the physical solution at [`FULL_REFERENCE_RTOL`].
fn full_reference(
    top: &SymmetricTop,
    omega0: &Vec3,
    times: &[Real],
) -> Result<Reference, SweepError> {
    let sol = physical_solution(top, omega0, times, FULL_REFERENCE_RTOL)
        .map_err(|e| SweepError::Reference(format!("full ALE reference: {e}")))?;
    Ok(Reference {
        omega: sol
            .z
            .iter()
            .map(|z| Vec3::new(z.re, z.im, omega0.z))
            .collect(),
        rotation: None,
        provenance: format!(
            "physical solution of (3.4) by spintop: DOP853 backward from T + 40 tau, shooting on the final amplitude, rtol {FULL_REFERENCE_RTOL:e} ({} shots)",
            sol.shots
        ),
        stats: Some(sol.stats),
    })
}

/// Read a stored reference: `#` comment lines, a header, then one line per
/// output time `t, Ω₁, Ω₂, Ω₃, q_w, q_x, q_y, q_z`.
fn parse_stored(text: &str, times: &[Real], name: &str) -> Result<Reference, String> {
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header = lines.next().ok_or("empty file")?;
    if header.trim() != "t,omega1,omega2,omega3,qw,qx,qy,qz" {
        return Err(format!("unexpected header '{header}'"));
    }
    let mut omega = Vec::with_capacity(times.len());
    let mut rotation = Vec::with_capacity(times.len());
    for (n, line) in lines.enumerate() {
        let v: Vec<Real> = line
            .split(',')
            .map(|s| s.trim().parse::<Real>())
            .collect::<Result<_, _>>()
            .map_err(|e| format!("line {}: {e}", n + 1))?;
        if v.len() != 8 {
            return Err(format!("line {}: expected 8 numbers", n + 1));
        }
        if times.get(n) != Some(&v[0]) {
            return Err(format!(
                "line {}: time {} is not the expected one",
                n + 1,
                v[0]
            ));
        }
        omega.push(Vec3::new(v[1], v[2], v[3]));
        let q = Quat::from_quaternion(Quaternion::new(v[4], v[5], v[6], v[7]));
        rotation.push(q.to_rotation_matrix().into_inner());
    }
    if omega.len() != times.len() {
        return Err(format!(
            "{} rows for {} output times",
            omega.len(),
            times.len()
        ));
    }
    Ok(Reference {
        omega,
        rotation: Some(rotation),
        provenance: format!(
            "Ω and O(t) by mpmath's Taylor series at 40 digits (crates/spintop/reference/{name}.csv)"
        ),
        stats: None,
    })
}
