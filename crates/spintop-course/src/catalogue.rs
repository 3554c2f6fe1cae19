//! The catalogue: the course's 22 assignments in the order the book teaches
//! them, each with its grader's test, its place in the book, the file and
//! function the student fills in, and its ladder of hints.

/// The ladder of hints of an assignment: where to look, the idea, and last
/// the formula. A grader's failure never prints the formula; only the third
/// rung (`spintop course hint NAME`, a third time) does.
pub type Hints = [&'static str; 3];

/// One assignment: the grader's test, its place in the book and the file and
/// function the student fills in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Assignment {
    /// The grader's test binary (`lessons/tests/NAME.rs`).
    pub binary: &'static str,
    /// The grader's test function.
    pub test: &'static str,
    /// The equation, as the paper numbers it.
    pub equation: &'static str,
    /// The book chapter that explains it.
    pub chapter: &'static str,
    /// The file and function to fill in.
    pub file: &'static str,
    /// The function's name.
    pub function: &'static str,
    /// The hint ladder.
    pub hints: Hints,
}

macro_rules! assignment {
    ($binary:literal, $test:literal, $equation:literal, $chapter:literal, $function:literal, [$h1:literal, $h2:literal, $h3:literal $(,)?]) => {
        Assignment {
            binary: $binary,
            test: $test,
            equation: $equation,
            chapter: $chapter,
            file: concat!("lessons/src/", $binary, ".rs"),
            function: $function,
            hints: [$h1, $h2, $h3],
        }
    };
}

/// How many assignments the course has.
pub const COURSE_LEN: usize = 22;

/// The course, in the order the book teaches it, easy to hard within each
/// chapter.
pub const COURSE: [Assignment; COURSE_LEN] = [
    assignment!(
        "ch2",
        "eq_2_1_larmor_rate",
        "(2.1)",
        "Section 2",
        "larmor_rate",
        [
            "Read 'Section 2: two laws for the loss of angular momentum', the first law, Eq. (2.1). Units: kappa = 2/(3c^3) = 1.",
            "The Larmor-like law uses only the dipole's first and second derivatives, d' and d''. A cross product of two vectors; mind its order and the overall sign.",
            "dL/dt = -d' x d''   (in Rust: -jet[1].cross(&jet[2]))",
        ]
    ),
    assignment!(
        "ch2",
        "eq_2_4_schott_angular_momentum",
        "(2.4)",
        "Section 2",
        "schott_angular_momentum",
        [
            "Read 'Section 2', the Schott term, Eq. (2.4).",
            "L_S is an angular momentum, not a rate: one cross product of the dipole with one of its derivatives. Its time derivative must be the difference of the two laws.",
            "L_S = d x d''   (in Rust: jet[0].cross(&jet[2]))",
        ]
    ),
    assignment!(
        "ch2",
        "eq_2_2_torque_rate",
        "(2.2)",
        "Section 2",
        "torque_rate",
        [
            "Read 'Section 2', the second law, Eq. (2.2): the radiation-reaction torque.",
            "The torque is the dipole crossed with the radiation-reaction field, which is proportional to the third derivative of the dipole.",
            "dL/dt = d x d'''   (in Rust: jet[0].cross(&jet[3]))",
        ]
    ),
    assignment!(
        "ch2",
        "eq_2_3_schott_rate",
        "(2.3)",
        "Section 2",
        "schott_rate",
        [
            "Read 'Section 2', Eq. (2.3): the two laws differ by a total derivative.",
            "Differentiate L_S of (2.4) with the product rule: both factors change in time, and each term keeps the order of the cross product.",
            "dL_S/dt = d' x d'' + d x d'''",
        ]
    ),
    assignment!(
        "ch2",
        "eq_2_3_axial_schott_rate",
        "(2.3)-(2.4)",
        "Section 2",
        "axial_schott_rate",
        [
            "Read 'Section 2', the axial projection of the difference of the two laws (Eqs. (2.3)-(2.4)).",
            "Project dL_S/dt on the unit vector along d. One of its two terms is perpendicular to d and drops out.",
            "n . dL_S/dt = d . (d' x d'') / |d|",
        ]
    ),
    assignment!(
        "ch2",
        "precessing_dipole_jet",
        "Sec. 2 cone",
        "Section 2",
        "precessing_dipole_jet",
        [
            "Read 'Section 2', the example of a dipole that precesses uniformly on a cone about z.",
            "Write d(t) on the cone of half-angle theta turning at rate omega, then differentiate three times: each derivative of cos(omega t) or sin(omega t) brings a factor omega and a quarter turn.",
            "d = (sin th cos wt, sin th sin wt, cos th); d' = w sin th (-sin wt, cos wt, 0); d'' = -w^2 sin th (cos wt, sin wt, 0); d''' = w^3 sin th (sin wt, -cos wt, 0)",
        ]
    ),
    assignment!(
        "ch3",
        "eq_3_3_truncated_ale_rhs",
        "(3.3)",
        "Section 3",
        "truncated_ale_rhs",
        [
            "Read 'Section 3: equations of motion', the truncated ALE (3.3) of a general top, and its derivation from (2.1).",
            "The angular acceleration appears on both sides: move its terms to the left, which gives a 3x3 linear system (the inertia plus a rank-one matrix) to solve. With a zero dipole it must reduce to Euler's equations.",
            "(I + d (d x W)^T) W' = -W x I W - |d x W|^2 W   (W = Omega; solve the 3x3 system, e.g. with .lu().solve())",
        ]
    ),
    assignment!(
        "ch3",
        "eq_3_3_energy_rate",
        "(3.3) energy",
        "Section 3",
        "energy_rate",
        [
            "Read 'Section 3', the truncated ALE (3.3); the kinetic energy of a top is half the rate dotted into the angular momentum.",
            "Differentiate the kinetic energy in time and use your truncated_ale_rhs for the angular acceleration (you may call your own functions in crate::ch3).",
            "dE/dt = W . (I W'), with W' from (3.3)",
        ]
    ),
    assignment!(
        "numerics",
        "eq_3_5_euler_from_rotation",
        "(3.5)",
        "Section 3",
        "euler_from_rotation",
        [
            "Read 'Section 3', the Euler angles of (3.5): z-x-z, theta in [0, pi]; and 'Where methods fail', the pole.",
            "Read theta from the third column and row with a two-argument arctangent (an inverse cosine loses digits near the poles); on a pole only phi + psi (or phi - psi) is defined, so fix psi = 0 there.",
            "theta = atan2(sqrt(O13^2 + O23^2), O33); phi = atan2(O13, -O23); psi = atan2(O31, O32); on a pole psi = 0 and phi from the first column",
        ]
    ),
    assignment!(
        "ch4",
        "eq_4_6_truncated_omega_perp",
        "(4.5)-(4.6)",
        "Section 4.1",
        "truncated_omega_perp",
        [
            "Read 'Section 4.1: the truncated top', Eqs. (4.5)-(4.6).",
            "The perpendicular rate obeys a closed equation of its own, with a loss cubic in the rate: separate the variables and integrate from 0 to t.",
            "Omega_perp(t) = Omega_perp0 / sqrt(1 + 2 tau Omega_perp0^2 t)",
        ]
    ),
    assignment!(
        "ch4",
        "eq_4_7_truncated_closed_form",
        "(4.7)",
        "Section 4.1",
        "truncated_closed_form",
        [
            "Read 'Section 4.1', Eq. (4.7), with the slowed clock of (4.9).",
            "Every component falls by the same factor R(t); Omega_perp also turns in the body, at a rate that falls with R, so its phase is the spin rate times a new time variable.",
            "R = sqrt(1 + 2 tau Wp0^2 t), theta = 2t/(1 + R), a = (1 - ratio) W30 theta; W1 = (W10 cos a + W20 sin a)/R, W2 = (W20 cos a - W10 sin a)/R, W3 = W30/R",
        ]
    ),
    assignment!(
        "ch4",
        "eq_4_6_truncated_time_to_factor",
        "(4.6) inv.",
        "Section 4.1",
        "truncated_time_to_factor",
        [
            "Read 'Section 4.1', Eq. (4.6): every rate falls as 1/R(t).",
            "Set the slowing factor R(t) equal to 1/p and solve for t; R is a square root, so square first.",
            "t = (1/p^2 - 1) / (2 tau Omega_perp0^2)",
        ]
    ),
    assignment!(
        "ch4",
        "eq_4_11_precession_tilt",
        "(4.11)",
        "Section 4.1",
        "precession_tilt",
        [
            "Read 'Section 4.1', the regular precession (4.10)-(4.11), and the Errata page on (4.11).",
            "The angle is between the symmetry axis and the angular momentum L, not the rotation rate: each component of L carries its own moment of inertia.",
            "tan(theta) = I1 Omega_perp0 / (I3 Omega_30), i.e. theta = atan2(Omega_perp0, ratio * Omega_30)",
        ]
    ),
    assignment!(
        "ch4",
        "eq_4_12_reduced_ale_rhs",
        "(4.12)-(4.14)",
        "Section 4.2",
        "reduced_ale_rhs",
        [
            "Read 'Section 4.2: the reduced top', Eqs. (4.12)-(4.14).",
            "The free precession terms are those of the truncated model; the damping of Omega_perp gains the square of the axial angular momentum over I1, and the spin is not damped at all.",
            "W1' = Wt3 W2 - tau (Wp^2 + ratio^2 W3^2) W1; W2' = -Wt3 W1 - tau (Wp^2 + ratio^2 W3^2) W2; W3' = 0; Wt3 = (1 - ratio) W3",
        ]
    ),
    assignment!(
        "ch4",
        "eq_4_16_reduced_decay_time",
        "(4.16) sigma",
        "Section 4.2",
        "reduced_decay_time",
        [
            "Read 'Section 4.2', the late-time decay time sigma of Eq. (4.16).",
            "At late times Omega_perp is small and only the axial part of the damping is left: a linear decay whose rate is tau times the square of the axial angular momentum over I1.",
            "sigma = I1^2 / (I3^2 Omega_3^2 tau) = 1 / (ratio^2 Omega_3^2 tau)",
        ]
    ),
    assignment!(
        "ch4",
        "eq_4_15_eq_4_16_reduced_closed_form",
        "(4.15)-(4.16)",
        "Section 4.2",
        "reduced_closed_form",
        [
            "Read 'Section 4.2', Eqs. (4.15)-(4.16); the paper sets Omega_10 = 0, you must not.",
            "Omega_3 is constant; Omega_perp turns at the constant rate (1 - ratio) Omega_3 and its size obeys an equation that becomes linear in w = 1/Omega_perp^2.",
            "Phi = sqrt((b - 1)/(b e^(2t/sigma) - 1)), b = 1 + (ratio W3)^2 / Wp0^2; W1 = Phi (W10 cos a + W20 sin a), W2 = Phi (W20 cos a - W10 sin a), a = (1 - ratio) W3 t",
        ]
    ),
    assignment!(
        "appendix",
        "eq_a_1_shell_masses",
        "(A.1) masses",
        "Appendix",
        "shell_masses",
        [
            "Read 'Appendix: the charge as a small shell', the masses of (A.1). Units: the whole mass m = 1.",
            "The field's share of the mass is the radiation time over the delay (light crossing the shell); the bare mass is the rest of m = 1.",
            "m_em = tau0 / delta, m0 = 1 - m_em",
        ]
    ),
    assignment!(
        "appendix",
        "eq_a_1_shell_acceleration",
        "(A.1)",
        "Appendix",
        "shell_acceleration",
        [
            "Read 'Appendix', the delay equation (A.1) and the method of steps.",
            "Only the bare mass multiplies the acceleration now; the field's mass acts with the acceleration one delay earlier. Solve for the acceleration now.",
            "Z''(t) = (-Z(t) - m_em Z''(t - delta)) / m0",
        ]
    ),
    assignment!(
        "appendix",
        "eq_a_1_characteristic_root",
        "(A.1) root",
        "Appendix",
        "characteristic_root",
        [
            "Read 'Appendix', the characteristic function of (A.1) with Z proportional to e^(st).",
            "Put Z = e^(st) into (A.1) to get an equation P(s) = 0; without radiation its root is s = i. Polish it with Newton's method, which needs the derivative P'(s).",
            "P(s) = s^2 (m0 + m_em e^(-s delta)) + 1, P'(s) = 2s (m0 + m_em e^(-s delta)) - s^2 m_em delta e^(-s delta); iterate s -= P/P' from s = i",
        ]
    ),
    assignment!(
        "numerics",
        "rk4_step",
        "RK4",
        "Numerical methods",
        "rk4_step",
        [
            "Read 'Numerical methods', the classical Runge-Kutta method.",
            "Four evaluations of f: at the start, twice at the midpoint (each from the previous slope), once at the end; then a weighted mean of the four slopes.",
            "k1 = f(t, y), k2 = f(t + h/2, y + h k1/2), k3 = f(t + h/2, y + h k2/2), k4 = f(t + h, y + h k3); y + h (k1 + 2 k2 + 2 k3 + k4)/6",
        ]
    ),
    assignment!(
        "numerics",
        "dp5_step",
        "DP5",
        "Numerical methods",
        "dp5_step",
        [
            "Read 'Numerical methods', the Dormand-Prince 5(4) pair (Hairer, Norsett & Wanner I, Table II.5.2).",
            "Seven stages with the Dormand-Prince tableau; the step is the fifth-order combination; the last stage is f at the new point, which the fourth-order estimate uses.",
            "y5 = y + h sum b_i k_i; error estimate y5 - y4_hat = h sum (b_i - b_hat_i) k_i, with k7 = f(t + h, y5)",
        ]
    ),
    assignment!(
        "numerics",
        "eq_4_12_reduced_rk4_takes_n_classical_steps",
        "(4.12) RK4",
        "Numerical methods",
        "reduced_rk4",
        [
            "Read 'Numerical methods' and 'Where methods fail': the order of a method, and Section 4.2 for the model.",
            "Use your rk4_step and your reduced_ale_rhs: take `steps` equal steps that end exactly at t_end. Halving the step must cut the error 16 times.",
            "h = t_end/steps; y = omega0; repeat steps times: y = rk4_step(&|_, y| reduced_ale_rhs(ratio, tau, y), t, &y, h), t += h",
        ]
    ),
];

/// The assignment called `name` (its function name, its test's name, or its
/// equation as printed, with or without brackets).
pub fn find(name: &str) -> Option<&'static Assignment> {
    let bare = name.trim().trim_start_matches('(').trim_end_matches(')');
    COURSE.iter().find(|a| {
        a.function == bare || a.test == bare || a.equation.trim_matches(['(', ')']) == bare
    })
}

/// The graders' test binaries (`lessons/tests/NAME.rs`), each once, in course order.
pub fn binaries() -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for a in &COURSE {
        if !out.contains(&a.binary) {
            out.push(a.binary);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_assignment_names_a_real_test_and_function() {
        let root = crate::repository();
        for a in COURSE {
            let tests = std::fs::read_to_string(
                root.join("lessons/tests").join(format!("{}.rs", a.binary)),
            )
            .unwrap();
            assert!(tests.contains(&format!("fn {}()", a.test)), "{a:?}");
            let src = std::fs::read_to_string(root.join(a.file)).unwrap();
            assert!(src.contains(&format!("pub fn {}", a.function)), "{a:?}");
        }
        // Every #[test] but the probe (not a grader: `#[ignore]`d, run by learn).
        let count: usize = std::fs::read_dir(root.join("lessons/tests"))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.file_name().is_some_and(|n| n != "probe.rs"))
            .map(|p| {
                std::fs::read_to_string(p)
                    .unwrap()
                    .matches("#[test]")
                    .count()
            })
            .sum();
        assert_eq!(count, COURSE.len(), "every grader is in the course, once");
    }
}
