//! The top the live models show, and so their layout: which model each
//! column runs, by which method, and how far.

use super::refusal::Refusal;
use super::stepper::Plan;

/// The narrowest a model's column is drawn; below it, one model at a time.
pub const COLUMN_WIDTH: u16 = 40;

/// True when `n` columns in `width` take turns (one at a time, Tab shows
/// the next): each would be narrower than [`COLUMN_WIDTH`].
pub fn takes_turns(width: u16, n: usize) -> bool {
    n > 1 && usize::from(width) / n < usize::from(COLUMN_WIDTH)
}
use spintop::math::{Real, Vec3};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::general_top::GeneralTop;
use spintop::physics::rigid_body::lab_frame;
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::sim::{InitialState, MethodChoice, Model};

/// Below this τ_f|Ω₀| the live view's physical column runs the reduced model:
/// the two differ by about (τ_f|Ω₀|)² = 1e-4 relative there, a fraction of a
/// character cell of the charts, while the backward shoot's work per unit of
/// time grows like 1/τ_f.
pub const STAND_IN_BELOW: Real = 1e-2;

/// How far the forward run of the full ALE is tabulated, in τ: it runs away
/// within a few τ; this is the chart's window, where it would show no more.
pub const FORWARD_HORIZON: Real = super::columns::WINDOW;

/// The methods `m` cycles through: auto, the closed forms, RK4, DP5,
/// DOP853, Radau IIA 5 and the Taylor method, then auto again (every model
/// the view steps takes each but the closed forms).
pub const METHOD_CYCLE: [MethodChoice; 7] = [
    MethodChoice::Auto,
    MethodChoice::Exact,
    MethodChoice::Rk4,
    MethodChoice::Dopri5,
    MethodChoice::Dop853,
    MethodChoice::Radau5,
    MethodChoice::Taylor,
];

/// The method after `method` in [`METHOD_CYCLE`] that `top` takes and that
/// runs something else than `method` does (auto is the closed forms on a
/// symmetric top: the cycle goes from auto to RK4); auto itself is always
/// in the cycle (on a general top it runs an integrator, and the cycle goes
/// from Taylor to auto); `method` itself when no column takes a method (the
/// full ALE's two columns).
pub fn next_method(method: MethodChoice, top: &Top) -> MethodChoice {
    let at = METHOD_CYCLE.iter().position(|m| *m == method).unwrap_or(0);
    if !top.takes_a_method() {
        return method;
    }
    (1..=METHOD_CYCLE.len())
        .map(|k| METHOD_CYCLE[(at + k) % METHOD_CYCLE.len()])
        .find(|m| {
            top.check_method(*m).is_ok()
                && (*m == MethodChoice::Auto || !top.resolves_same(*m, method))
        })
        .unwrap_or(method)
}

/// The methods `m` visits on `top`, in order, from auto: the one list the
/// help shows and the key walks ([`next_method`]).
pub fn method_cycle(top: &Top) -> Vec<MethodChoice> {
    let mut cycle = vec![MethodChoice::Auto];
    let mut method = MethodChoice::Auto;
    loop {
        method = next_method(method, top);
        if cycle.contains(&method) {
            return cycle;
        }
        cycle.push(method);
    }
}

/// The top the view shows, and so its layout.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Top {
    /// A symmetric top: its truncated (4.2)–(4.4) and reduced (4.12)–(4.14)
    /// models side by side, each with its closed form.
    Symmetric(SymmetricTop),
    /// A symmetric top under the full ALE (3.4): its physical solution beside
    /// the same equation integrated forward, which runs away.
    Full(SymmetricTop),
    /// Any top: the truncated ALE (3.3), the reduced ALE and the physical
    /// solution of the full ALE (3.4), side by side (no closed forms).
    General(GeneralTop),
}

/// One column of a layout: its model, the method it always runs (`None`:
/// the one chosen with `m`) and the last time it can reach.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Slot {
    model: Model,
    fixed: Option<MethodChoice>,
    horizon: Option<Real>,
}

impl Top {
    /// The columns, left to right.
    fn slots(&self) -> Vec<Slot> {
        let slot = |model, fixed, horizon| Slot {
            model,
            fixed,
            horizon,
        };
        match *self {
            Top::Symmetric(top) => vec![
                slot(Model::Truncated(top), None, None),
                slot(Model::Reduced(top), None, None),
            ],
            Top::Full(top) => vec![
                slot(Model::Full(top), Some(MethodChoice::Auto), None),
                slot(
                    Model::Full(top),
                    Some(MethodChoice::Forward),
                    Some(FORWARD_HORIZON),
                ),
            ],
            // The full ALE's physical solution has one method (backward
            // shooting, tabulated ahead chunk by chunk).
            Top::General(top) => vec![
                slot(Model::General(top), None, None),
                slot(Model::GeneralReduced(top), None, None),
                slot(Model::GeneralFull(top), Some(MethodChoice::Auto), None),
            ],
        }
    }

    /// True when some column runs the method chosen with `m`.
    pub fn takes_a_method(&self) -> bool {
        self.slots().iter().any(|s| s.fixed.is_none())
    }

    /// Refuse a method the columns that take one do not take, with the
    /// core's reason.
    pub fn check_method(&self, method: MethodChoice) -> Result<(), Refusal> {
        self.slots()
            .iter()
            .filter(|s| s.fixed.is_none())
            .try_for_each(|s| s.model.check_method(method))
            .map_err(Refusal::from)
    }

    /// True when the choices `a` and `b` run the same methods in every
    /// column that takes a method (auto and the closed forms on a symmetric
    /// top).
    pub fn resolves_same(&self, a: MethodChoice, b: MethodChoice) -> bool {
        let options = spintop::sim::MethodOptions::default();
        self.slots().iter().filter(|s| s.fixed.is_none()).all(|s| {
            let (ma, mb) = (s.model.method(a, &options), s.model.method(b, &options));
            ma.is_ok() && ma == mb
        })
    }

    /// The unit of time: τ for a symmetric top (Section 4's unit), "u" for a
    /// general one, whose numbers are in units where κ = 2/(3c³) = 1.
    pub fn time_unit(&self) -> &'static str {
        self.slots()[0].model.time_unit()
    }

    /// I₃/I₁ of a symmetric top; `None` for a general one.
    pub fn ratio(&self) -> Option<Real> {
        match self {
            Top::Symmetric(top) | Top::Full(top) => Some(top.ratio()),
            Top::General(_) => None,
        }
    }

    /// The same layout for a symmetric top of another I₃/I₁.
    pub(super) fn with_ratio(&self, ratio: Real) -> Result<Top, Refusal> {
        let top = SymmetricTop::new(ratio, 1.0)?;
        match self {
            Top::Full(_) => Ok(Top::Full(top)),
            _ => Ok(Top::Symmetric(top)),
        }
    }

    /// How each column runs from `omega0` by `method`, from the orientation
    /// `euler0` (z-x-z; the paper's frame, lab z along L₀, when `None`), and
    /// why a column runs a lighter model than its title's, if it does.
    pub(super) fn plans(
        &self,
        method: MethodChoice,
        omega0: [Real; 3],
        euler0: Option<[Real; 3]>,
    ) -> Result<Vec<(Plan, Option<String>)>, Refusal> {
        self.slots()
            .into_iter()
            .map(|slot| {
                // Model no more than the view can show: the physical solution
                // of a general top differs from its reduced model by
                // O((τ_f|Ω|)²) relative, and costs work in proportion to 1/τ_f
                // per unit of time.
                let mut stand_in = None;
                let mut model = slot.model;
                let mut fixed = slot.fixed;
                if let Model::GeneralFull(top) = model {
                    let small = spintop::sim::physical::general::fast_time(&top)
                        * Vec3::from(omega0).norm();
                    if small < STAND_IN_BELOW {
                        stand_in = Some(format!(
                            "τ_f|Ω₀| = {}: the physical solution is the reduced model to about {}, so the reduced model stands in",
                            spintop::numbers::fmt_num(small),
                            spintop::numbers::fmt_num(small * small)
                        ));
                        model = Model::GeneralReduced(top);
                        fixed = None;
                    }
                }
                let orientation = match euler0 {
                    Some([phi, theta, psi]) => EulerAngles::new(phi, theta, psi),
                    None => lab_frame(&model.inertia(), &Vec3::from(omega0)),
                };
                let initial = InitialState::new(Vec3::from(omega0), orientation)?;
                let plan = Plan {
                    model,
                    choice: fixed.unwrap_or(method),
                    initial,
                    horizon: slot.horizon,
                };
                Ok((plan, stand_in))
            })
            .collect()
    }
}

/// The name of a method choice on the screen, the same in the header, the
/// columns and the messages: `auto` says what it runs here.
pub fn method_title(method: MethodChoice, top: &Top) -> String {
    let same = (method == MethodChoice::Auto)
        .then(|| {
            METHOD_CYCLE[1..]
                .iter()
                .find(|m| top.resolves_same(MethodChoice::Auto, **m))
        })
        .flatten();
    match same {
        Some(MethodChoice::Exact) => "auto (closed form)".into(),
        Some(m) => format!("auto ({})", m.title()),
        None => method.title().into(),
    }
}

/// The classical RK4's stability interval on the negative real axis
/// (|R(z)| ≤ 1 for −2.785 ≤ z ≤ 0).
const RK4_STABILITY: Real = 2.78;

/// Why the fixed-step `method` would blow up on its first step from the
/// states `omegas` (Ω₀, where `m` restarts the models), if it would: RK4's step h must keep
/// h·λ inside its stability interval (2.78 on the negative real axis), and
/// the radiation damps Ω⊥ at λ ≈ 3τ|Ω|² (Ω⊥′ = −τΩ⊥³ and its like), so `m`
/// skips it while 3τ|Ω|²h > 2.78 (Ω₁₀ = 1000: h·λ = 3.0e4).
pub fn fixed_step_unstable(
    method: MethodChoice,
    top: &Top,
    omegas: impl Iterator<Item = [Real; 3]>,
) -> Option<String> {
    if method != MethodChoice::Rk4 {
        return None;
    }
    let tau = match top {
        Top::Symmetric(top) | Top::Full(top) => top.tau(),
        // κ = 1 units: the general top's damping is of the same order.
        Top::General(_) => 1.0,
    };
    let h = spintop::sim::MethodOptions::default().step();
    let omega2 = omegas
        .map(|w| w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
        .fold(0.0, Real::max);
    let h_lambda = 3.0 * tau * omega2 * h;
    (h_lambda > RK4_STABILITY).then(|| {
        format!(
            "RK4 skipped: its fixed step {}τ is unstable here (h·3τ|Ω|² = {}, beyond its limit {RK4_STABILITY}); a smaller Ω₀ lets it run",
            spintop::numbers::fmt_num(h),
            spintop::numbers::fmt_num(h_lambda)
        )
    })
}
