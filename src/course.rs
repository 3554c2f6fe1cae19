//! The course: the assignments of `lessons/` in course order, and their state
//! as `cargo test -p spintop-lessons` grades them.
//!
//! A shared layer below the shells: `spintop course` prints it as text and
//! `spintop learn` can show it in its panel; neither parses the other's output.
//! It runs cargo (a child process) and reads its output, so it is not part of
//! the pure core.
//!
//! The graders' verdicts come from the test harness's own lines
//! (`test eq_2_1_larmor_rate ... ok`) and, for a failure, from the grader's
//! report that the harness prints under `---- eq_2_1_larmor_rate stdout ----`:
//! the equation, the input, what was expected, what came back, and the hint.

use std::path::Path;
use std::process::Command;

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
        "reduced_rk4_converges_at_order_4",
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

/// Where an assignment stands.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum State {
    /// The stub is untouched (it still panics with `todo!()`).
    NotStarted,
    /// The grader rejected the answer; the grader's report.
    Failing(String),
    /// The grader accepted it.
    Passing,
    /// The lessons crate did not compile; the compiler's first error.
    DoesNotCompile(String),
    /// The grader's test did not report (not found in the output).
    Unknown,
}

impl State {
    /// A short word for a status line.
    pub fn word(&self) -> &'static str {
        match self {
            State::NotStarted => "not started",
            State::Failing(_) => "failing",
            State::Passing => "passing",
            State::DoesNotCompile(_) => "does not compile",
            State::Unknown => "not graded",
        }
    }
}

/// The course's state after one grading run.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Status {
    /// Each assignment of [`COURSE`] with its state, in course order.
    pub states: Vec<(Assignment, State)>,
}

impl Status {
    /// How many pass.
    pub fn passing(&self) -> usize {
        self.states
            .iter()
            .filter(|(_, s)| *s == State::Passing)
            .count()
    }

    /// The first assignment in course order that does not pass.
    pub fn next(&self) -> Option<&(Assignment, State)> {
        self.states.iter().find(|(_, s)| *s != State::Passing)
    }
}

/// Reads the harness's output of `cargo test -p spintop-lessons` into the
/// course's state. `output` is stdout and stderr together.
pub fn parse(output: &str) -> Status {
    let compile_error = output
        .lines()
        .find(|l| l.starts_with("error[") || l.starts_with("error: could not compile"))
        .map(|first| {
            // The first real compiler error, not cargo's summary, if there is one.
            output
                .lines()
                .find(|l| {
                    l.starts_with("error[")
                        || (l.starts_with("error:") && !l.contains("could not compile"))
                })
                .unwrap_or(first)
                .to_string()
        });
    let states = COURSE
        .iter()
        .map(|a| {
            let ok = format!("test {} ... ok", a.test);
            let failed = format!("test {} ... FAILED", a.test);
            let state = if output.lines().any(|l| l.trim() == ok) {
                State::Passing
            } else if output.lines().any(|l| l.trim() == failed) {
                let report = report(output, a.test);
                if report.contains("not yet implemented") || report.contains("not implemented") {
                    State::NotStarted
                } else {
                    State::Failing(report)
                }
            } else if let Some(e) = &compile_error {
                State::DoesNotCompile(e.clone())
            } else {
                State::Unknown
            };
            (*a, state)
        })
        .collect();
    Status { states }
}

/// The grader's report for `test`: the lines under `---- TEST stdout ----`
/// up to the next section, without the harness's own noise.
fn report(output: &str, test: &str) -> String {
    let header = format!("---- {test} stdout ----");
    let Some(start) = output.find(&header) else {
        return String::new();
    };
    let body = &output[start + header.len()..];
    let end = [
        body.find("\n---- "),
        body.find("\nfailures:"),
        body.find("\n\nfailures:"),
    ]
    .into_iter()
    .flatten()
    .min()
    .unwrap_or(body.len());
    body[..end]
        .lines()
        .filter(|l| {
            let t = l.trim();
            !(t.starts_with("thread '")
                || t.starts_with("note: run with")
                || t.starts_with("stack backtrace"))
        })
        .collect::<Vec<_>>()
        .join("\n")
        .trim()
        .to_string()
}

/// The lessons crate of the repository at `repo` (where `spintop course`
/// and `spintop learn` look unless told otherwise).
pub fn lessons_dir(repo: &Path) -> std::path::PathBuf {
    repo.join("lessons")
}

/// Why `dir` is not a lessons crate spintop can grade, if it is not.
pub fn check_lessons_dir(dir: &Path) -> Result<(), String> {
    if !dir.join("Cargo.toml").is_file() || !dir.join("src").is_dir() {
        return Err(format!(
            "{} is not a course: it needs a Cargo.toml and a src/ folder (the repository's lessons/, or a copy made by `spintop course export`)",
            dir.display()
        ));
    }
    Ok(())
}

/// The `.rs` files directly in `dir`, sorted (none if it cannot be read).
fn rust_files(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "rs"))
        .collect();
    files.sort();
    files
}

/// The course's small state file: hint rungs used and first-passed times.
#[derive(Debug, Default, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Progress {
    /// Hint rungs used so far, by assignment (function name).
    #[serde(default)]
    pub hints: std::collections::BTreeMap<String, u8>,
    /// When each assignment first passed (seconds since the Unix epoch).
    #[serde(default)]
    pub first_passed: std::collections::BTreeMap<String, u64>,
}

/// Where the course in `dir` keeps its [`Progress`]: the repository's
/// `target/spintop-course.json` for its own lessons/, the course's own
/// `target/` for a student's copy. Never anywhere else.
pub fn progress_path(dir: &Path) -> std::path::PathBuf {
    let parent = dir.parent().filter(|p| {
        dir.file_name().is_some_and(|n| n == "lessons") && p.join("Cargo.toml").is_file()
    });
    parent
        .unwrap_or(dir)
        .join("target")
        .join("spintop-course.json")
}

/// The course's [`Progress`]; a missing or unreadable file is a fresh start.
pub fn load_progress(dir: &Path) -> Progress {
    std::fs::read(progress_path(dir))
        .ok()
        .filter(|b| b.len() < 1 << 20)
        .and_then(|b| serde_json::from_slice(&b).ok())
        .unwrap_or_default()
}

/// Writes the course's [`Progress`].
pub fn save_progress(dir: &Path, progress: &Progress) -> Result<(), String> {
    let path = progress_path(dir);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
    }
    let text = serde_json::to_string_pretty(progress).map_err(|e| e.to_string())?;
    std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The assignment called `name` (its function name, its test's name, or its
/// equation as printed, with or without brackets).
pub fn find(name: &str) -> Option<&'static Assignment> {
    let bare = name.trim().trim_start_matches('(').trim_end_matches(')');
    COURSE.iter().find(|a| {
        a.function == bare || a.test == bare || a.equation.trim_matches(['(', ')']) == bare
    })
}

/// One rung of the hint ladder.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Hint {
    /// The assignment.
    pub assignment: &'static Assignment,
    /// The rung, 1 to 3.
    pub rung: usize,
    /// Its text.
    pub text: &'static str,
}

impl Hint {
    /// What the rung gives: where to look, the idea, or the formula.
    pub fn label(&self) -> &'static str {
        ["where to look", "the idea", "the formula"][(self.rung.max(1) - 1).min(2)]
    }

    /// Whether this is the last rung (the formula).
    pub fn is_last(&self) -> bool {
        self.rung == self.assignment.hints.len()
    }
}

/// The hint a student has reached for `a`: `progress`'s rung count plus one
/// (one rung per request, staying on the last), recorded in `progress`.
pub fn next_hint(progress: &mut Progress, a: &'static Assignment) -> Hint {
    let used = progress.hints.entry(a.function.to_string()).or_insert(0);
    let rung = (*used as usize + 1).min(a.hints.len());
    *used = rung as u8;
    Hint {
        assignment: a,
        rung,
        text: a.hints[rung - 1],
    }
}

/// [`record_passes`] at the present time, kept in the course's progress file
/// (a read-only course still grades: a failed write is not an error).
pub fn record_passes_now(dir: &Path, status: &Status) {
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let mut progress = load_progress(dir);
    if record_passes(&mut progress, status, now) {
        let _ = save_progress(dir, &progress);
    }
}

/// Records the first time each assignment of `status` passed (`now` in
/// seconds since the Unix epoch); true when something new was recorded.
pub fn record_passes(progress: &mut Progress, status: &Status, now: u64) -> bool {
    let mut changed = false;
    for (a, s) in &status.states {
        if *s == State::Passing && !progress.first_passed.contains_key(a.function) {
            progress.first_passed.insert(a.function.to_string(), now);
            changed = true;
        }
    }
    changed
}

/// The sources an assignment of `module` is built from, as `(file, text)`:
/// the lessons crate's `src/*.rs` (lib.rs, helpers, the module itself) but
/// not the other assignment modules, and the instructor's
/// `src/solutions/MODULE.rs` when the module hands over to it.
pub fn assignment_sources(manifest_dir: &str, module: &str) -> Vec<(String, String)> {
    let src = std::path::Path::new(manifest_dir).join("src");
    let mut out = Vec::new();
    for path in rust_files(&src) {
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        // Another chapter's assignments are that chapter's business.
        if stem != module && COURSE.iter().any(|a| a.binary == stem) {
            continue;
        }
        if let Ok(text) = std::fs::read_to_string(&path) {
            let own = stem == module && text.contains(&format!("solutions::{module}"));
            out.push((format!("src/{stem}.rs"), text));
            if own {
                let solution = src.join("solutions").join(format!("{module}.rs"));
                if let Ok(text) = std::fs::read_to_string(&solution) {
                    out.push((format!("src/solutions/{module}.rs"), text));
                }
            }
        }
    }
    out
}

/// Panic with a readable report unless the assignment passed its grader and
/// its sources take no shortcut (see [`crate::grading::no_shortcut`]); for the graders'
/// `#[test]`s, through the [`graded!`](crate::graded) macro.
pub fn assert_graded(manifest_dir: &str, module: &str, grade: crate::grading::Grade) {
    let sources = assignment_sources(manifest_dir, module);
    let borrowed: Vec<(&str, &str)> = sources
        .iter()
        .map(|(f, t)| (f.as_str(), t.as_str()))
        .collect();
    crate::grading::assert_passes(crate::grading::without_shortcut(grade, &borrowed));
}

/// `graded!("ch2", grading::larmor_rate(ch2::larmor_rate))`: the grader's
/// verdict on the calling crate's module `ch2`, shortcuts rejected (see
/// [`crate::course::assert_graded`]).
#[macro_export]
macro_rules! graded {
    ($module:literal, $grade:expr) => {
        $crate::course::assert_graded(env!("CARGO_MANIFEST_DIR"), $module, $grade)
    };
}

/// A function of time of the course, sampled on the student's code for
/// `spintop learn`, which draws it against the reference on the chapter's
/// chart (the probe `lessons/tests/probe.rs`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeSpec {
    /// The assignment's function.
    pub function: &'static str,
    /// I₃/I₁.
    pub ratio: f64,
    /// τ.
    pub tau: f64,
    /// Ω₀.
    pub omega0: [f64; 3],
    /// The samples span [0, t_end].
    pub t_end: f64,
    /// Intervals between samples.
    pub samples: usize,
}

impl ProbeSpec {
    /// The probe of the chapter titled `title`, if it has one: the closed
    /// form of its model at the scene's parameters (the paper's top,
    /// I₃/I₁ = 2/5, Ω₀ = (0, 0.1, 0.2)).
    pub fn for_chapter(title: &str) -> Option<Self> {
        let (function, t_end) = if title.starts_with("Section 4.1") {
            ("truncated_closed_form", 400.0)
        } else if title.starts_with("Section 4.2") {
            ("reduced_closed_form", 200.0)
        } else {
            return None;
        };
        Some(Self {
            function,
            ratio: 0.4,
            tau: 1.0,
            omega0: [0.0, 0.1, 0.2],
            t_end,
            samples: 200,
        })
    }

    /// The request, as `SPINTOP_PROBE` carries it.
    pub fn request(&self) -> String {
        let [w1, w2, w3] = self.omega0;
        format!(
            "{} {} {} {w1} {w2} {w3} {} {}",
            self.function, self.ratio, self.tau, self.t_end, self.samples
        )
    }
}

/// What the probe found.
#[derive(Debug, Clone, PartialEq)]
pub enum Probed {
    /// The student's Ω(t) at the sample times, as `(t, [Ω₁, Ω₂, Ω₃])`.
    Samples(Vec<(f64, [f64; 3])>),
    /// The function panicked (a `todo!()` stub, or a crash): its message.
    Panicked(String),
}

/// Reads the probe's output.
pub fn parse_probe(output: &str) -> Result<Probed, String> {
    let mut samples = Vec::new();
    for line in output.lines() {
        if let Some(msg) = line.strip_prefix("probe: panicked: ") {
            return Ok(Probed::Panicked(msg.to_string()));
        }
        if let Some(msg) = line.strip_prefix("probe: ") {
            return Err(msg.to_string());
        }
        if let Some(rest) = line.strip_prefix("probe ") {
            let v: Vec<f64> = rest
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect();
            if let [t, a, b, c] = v[..] {
                samples.push((t, [a, b, c]));
            }
        }
    }
    if samples.is_empty() {
        let first_error = output
            .lines()
            .find(|l| l.starts_with("error"))
            .unwrap_or("the probe printed nothing");
        return Err(first_error.to_string());
    }
    Ok(Probed::Samples(samples))
}

/// Runs the probe of `spec` on the lessons crate in `dir` (a cargo child
/// process; about a second once built).
pub fn probe(dir: &Path, spec: &ProbeSpec) -> Result<Probed, String> {
    let mut cmd = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    cmd.current_dir(dir)
        .arg("test")
        .arg("--manifest-path")
        .arg(dir.join("Cargo.toml"))
        .args(["--quiet", "--color", "never", "--test", "probe"])
        .args(["--", "--ignored", "--nocapture", "--exact", "probe"])
        .env("SPINTOP_PROBE", spec.request())
        .env("RUST_BACKTRACE", "0");
    let out = cmd.output().map_err(|e| format!("cannot run cargo: {e}"))?;
    parse_probe(&format!(
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    ))
}

/// The cargo command that grades the lessons crate in `dir`: the graders of
/// the given test binaries, or all of them when `binaries` is empty; with
/// `solutions`, the instructor's reference solutions.
fn grade_command(dir: &Path, solutions: bool, binaries: &[&str]) -> Command {
    let mut cmd = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    cmd.current_dir(dir)
        .arg("test")
        .arg("--manifest-path")
        .arg(dir.join("Cargo.toml"))
        .args(["--no-fail-fast", "--color", "never"]);
    if solutions {
        cmd.args(["--features", "solutions"]);
    }
    for b in binaries {
        cmd.args(["--test", b]);
    }
    cmd.args(["--", "--color", "never"])
        .env("RUST_BACKTRACE", "0");
    cmd
}

/// Grades the course of the lessons crate in `dir` (see [`lessons_dir`]):
/// runs `cargo test --no-fail-fast` on it (no backtraces, no colour) and reads
/// its output; with `solutions`, the instructor's reference solutions are
/// graded instead of the student's files. An error is a reason cargo could
/// not be run at all.
pub fn grade(dir: &Path, solutions: bool) -> Result<Status, String> {
    grade_with(grade_command(dir, solutions, &[]))
}

fn grade_with(mut command: Command) -> Result<Status, String> {
    let out = command
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    let text = format!(
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    Ok(parse(&text))
}

/// The modification time of each of the student's files (`src/*.rs` of the
/// lessons crate in `dir`), by file name.
pub fn sources_stamps(dir: &Path) -> std::collections::BTreeMap<String, std::time::SystemTime> {
    rust_files(&dir.join("src"))
        .into_iter()
        .filter_map(|p| {
            let time = std::fs::metadata(&p).ok()?.modified().ok()?;
            Some((p.file_name()?.to_string_lossy().into_owned(), time))
        })
        .collect()
}

/// The test binaries whose graders can change when the files `changed` (names
/// under `src/`) do: those of the assignments in them, or every one (an empty
/// list) when another file changed (`lib.rs`, a helper).
pub fn binaries_for(changed: &[String]) -> Vec<&'static str> {
    let mut binaries = Vec::new();
    for file in changed {
        let mut owners = COURSE
            .iter()
            .filter(|a| a.file.rsplit('/').next() == Some(file.as_str()))
            .map(|a| a.binary)
            .peekable();
        if owners.peek().is_none() {
            return Vec::new();
        }
        binaries.extend(owners);
    }
    binaries.sort_unstable();
    binaries.dedup();
    binaries
}

impl Status {
    /// Whether every assignment has a verdict of its own (none is "does not
    /// compile" or ungraded), so that a partial re-grade can build on it.
    pub fn complete(&self) -> bool {
        self.states
            .iter()
            .all(|(_, s)| !matches!(s, State::DoesNotCompile(_) | State::Unknown))
    }

    /// This status with the assignments graded by `binaries` (all when empty)
    /// taken from `fresh`. A compile error concerns the whole crate, so it is
    /// taken for every assignment.
    pub fn merged(&self, fresh: Status, binaries: &[&str]) -> Status {
        let broken = fresh
            .states
            .iter()
            .any(|(_, s)| matches!(s, State::DoesNotCompile(_)));
        let states = self
            .states
            .iter()
            .zip(fresh.states)
            .map(|((a, old), (_, new))| {
                let regraded = binaries.is_empty() || binaries.contains(&a.binary);
                if regraded || broken {
                    (*a, new)
                } else {
                    (*a, old.clone())
                }
            })
            .collect();
        Status { states }
    }
}

/// What a [`Watch`] reports.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Report {
    /// A grading run started (a file was saved, or the watch began).
    Grading,
    /// A grading run ended.
    Graded(Status),
    /// Cargo could not be run.
    Failed(String),
}

/// Grades the course in the background, once at the start and again each
/// time a file under `src/` of the lessons crate is saved (polled every
/// 200 ms); a save re-grades only the graders of the assignments in the saved
/// file (see [`binaries_for`]). The grading runs stop with the watch:
/// dropping it ends the thread and kills a cargo still running.
pub struct Watch {
    reports: std::sync::mpsc::Receiver<Report>,
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Watch {
    /// Starts watching the lessons crate in `dir`.
    pub fn start(dir: &Path) -> Self {
        use std::sync::atomic::Ordering;
        let (tx, reports) = std::sync::mpsc::channel();
        let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let stop_thread = std::sync::Arc::clone(&stop);
        let dir = dir.to_path_buf();
        let thread = std::thread::spawn(move || {
            let mut graded: Option<(std::collections::BTreeMap<_, _>, Status)> = None;
            while !stop_thread.load(Ordering::Relaxed) {
                let stamps = sources_stamps(&dir);
                let binaries = match &graded {
                    None => Some(Vec::new()),
                    // After a compile error or a failed run, everything again.
                    Some((old, status)) if *old != stamps && !status.complete() => Some(Vec::new()),
                    Some((old, _)) if *old != stamps => {
                        let changed: Vec<String> = stamps
                            .iter()
                            .filter(|(f, t)| old.get(*f) != Some(t))
                            .map(|(f, _)| f.clone())
                            .chain(old.keys().filter(|f| !stamps.contains_key(*f)).cloned())
                            .collect();
                        Some(binaries_for(&changed))
                    }
                    Some(_) => None,
                };
                if let Some(binaries) = binaries {
                    if tx.send(Report::Grading).is_err() {
                        return;
                    }
                    let report = match grade_cancellable(&dir, &binaries, &stop_thread) {
                        Ok(Some(fresh)) => {
                            let status = match &graded {
                                Some((_, old)) => old.merged(fresh, &binaries),
                                None => fresh,
                            };
                            graded = Some((stamps, status.clone()));
                            Report::Graded(status)
                        }
                        Ok(None) => return,
                        Err(e) => {
                            // Try again on the next save, from scratch.
                            graded = Some((stamps, parse("")));
                            Report::Failed(e)
                        }
                    };
                    if tx.send(report).is_err() {
                        return;
                    }
                }
                std::thread::sleep(std::time::Duration::from_millis(200));
            }
        });
        Watch {
            reports,
            stop,
            thread: Some(thread),
        }
    }

    /// The reports since the last call, oldest first.
    pub fn poll(&self) -> Vec<Report> {
        self.reports.try_iter().collect()
    }
}

impl Drop for Watch {
    fn drop(&mut self) {
        self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// [`grade`] of the graders in `binaries` (all when empty) as a child
/// process that is killed when `stop` is set; `None` when it was.
fn grade_cancellable(
    dir: &Path,
    binaries: &[&str],
    stop: &std::sync::atomic::AtomicBool,
) -> Result<Option<Status>, String> {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = grade_command(dir, false, binaries)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    let mut out = child.stdout.take();
    let mut err = child.stderr.take();
    let t_out = std::thread::spawn(move || {
        let mut s = String::new();
        if let Some(o) = out.as_mut() {
            let _ = o.read_to_string(&mut s);
        }
        s
    });
    let t_err = std::thread::spawn(move || {
        let mut s = String::new();
        if let Some(e) = err.as_mut() {
            let _ = e.read_to_string(&mut s);
        }
        s
    });
    loop {
        if stop.load(std::sync::atomic::Ordering::Relaxed) {
            let _ = child.kill();
            let _ = child.wait();
            return Ok(None);
        }
        match child.try_wait() {
            Ok(Some(_)) => break,
            Ok(None) => std::thread::sleep(std::time::Duration::from_millis(50)),
            Err(e) => return Err(e.to_string()),
        }
    }
    let text = format!(
        "{}\n{}",
        t_out.join().unwrap_or_default(),
        t_err.join().unwrap_or_default()
    );
    Ok(Some(parse(&text)))
}

/// A student's file with the instructor's solutions taken out: the
/// `#[cfg(not(feature = "solutions"))]` attributes (always true once the
/// feature is gone), each `#[cfg(feature = "solutions")]` item, and the
/// comment that announces it.
pub fn strip_solutions(source: &str) -> String {
    let mut out = Vec::new();
    let mut skip_next = false;
    for line in source.lines() {
        let t = line.trim();
        if skip_next {
            skip_next = false;
            continue;
        }
        if t == "#[cfg(not(feature = \"solutions\"))]" {
            continue;
        }
        if t == "#[cfg(feature = \"solutions\")]" {
            skip_next = true;
            continue;
        }
        if t.starts_with("// The instructor's reference solutions")
            || (t.starts_with("// src/solutions/") && t.contains("handing out"))
        {
            continue;
        }
        out.push(line);
    }
    let mut text = out.join("\n").trim_end().to_string();
    text.push('\n');
    text
}

/// Grades a student's copy of the course (`submission`, a folder made by
/// [`export`]) with the instructor's graders: a fresh export of `repo` in
/// `scratch` (emptied first) receives the student's `src/*.rs`, so that what
/// is graded is the student's code against the repository's tests, whatever
/// the copy's own tests say. Builds share `target` (spintop is compiled once).
pub fn grade_submission(
    repo: &Path,
    submission: &Path,
    scratch: &Path,
    target: &Path,
) -> Result<Status, String> {
    check_lessons_dir(submission)?;
    if scratch.exists() {
        std::fs::remove_dir_all(scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    }
    export(repo, scratch)?;
    for path in rust_files(&submission.join("src")) {
        let to = scratch
            .join("src")
            .join(path.file_name().unwrap_or_default());
        std::fs::copy(&path, &to).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let mut command = grade_command(scratch, false, &[]);
    command.env("CARGO_TARGET_DIR", target);
    grade_with(command)
}

/// What [`export`] wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Export {
    /// Every file written, relative to the export's folder.
    pub files: Vec<std::path::PathBuf>,
}

/// The student's copy's manifest: the lessons package on its own (its own
/// workspace), depending on spintop at `spintop` (an absolute path).
///
/// NOTE: the package is named after the copy's folder (spintop-lessons-HASH;
/// the library keeps the name `spintop_lessons`). Cargo keys its build
/// artifacts on a path package's name, version and place in its own workspace,
/// not on where the workspace is, so two copies named alike that share a build
/// folder (`CARGO_TARGET_DIR`, as `course grade` and the tests do) would reuse
/// each other's test programs when one copy's sources look unchanged: one
/// student graded with another's code.
fn export_manifest(spintop: &Path, out: &Path) -> String {
    let key = crate::numbers::stable_key(
        &out.canonicalize()
            .unwrap_or_else(|_| out.to_path_buf())
            .to_string_lossy(),
    );
    format!(
        r#"[package]
name = "spintop-lessons-{key:08x}"
version = "0.1.0"
edition = "2024"
publish = false
description = "Course assignments on Duviryak's polarized spinning top, graded by cargo test."

# A course of its own, not a member of any other workspace.
[workspace]

[lib]
name = "spintop_lessons"
path = "src/lib.rs"

[dependencies]
# The core only: grading does not compile the terminal UI, the plots or the command line.
spintop = {{ path = {path:?}, default-features = false }}
"#,
        path = spintop.display().to_string()
    )
}

const EXPORT_README: &str = "# The spintop course

Assignments on A. Duviryak's polarized spinning top, graded by `cargo test`.
Every function under `src/` is a stub that ends in `todo!()`; the chapter of
the book it comes from is named in its doc comment (the assignments page is in
`book/`).

Two commands:

```sh
cargo test                     # grade every assignment
cargo test --test ch2          # grade one chapter's assignments
```

With spintop installed, `spintop course --course .` lists the assignments in
course order with their state and what to do next, and
`spintop learn --course .` opens the book in the terminal and re-grades on
every save.
";

/// Writes a self-contained student's copy of the course in `repo` to `out`
/// (a folder that must not exist yet, or be empty): the stubs without the
/// reference solutions, the graders, the book's assignments page, a README
/// and a manifest that builds on its own against the spintop in `repo`.
pub fn export(repo: &Path, out: &Path) -> Result<Export, String> {
    let lessons = lessons_dir(repo);
    check_lessons_dir(&lessons)?;
    if out.exists() {
        let empty = std::fs::read_dir(out)
            .map_err(|e| format!("{}: {e}", out.display()))?
            .next()
            .is_none();
        if !empty {
            return Err(format!(
                "{} is not empty; give a new folder, so that nothing is overwritten",
                out.display()
            ));
        }
    }
    let spintop = repo
        .canonicalize()
        .map_err(|e| format!("{}: {e}", repo.display()))?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut files: Vec<(std::path::PathBuf, String)> = vec![
        ("Cargo.toml".into(), export_manifest(&spintop, out)),
        ("README.md".into(), EXPORT_README.to_string()),
        (".gitignore".into(), "/target\n".to_string()),
    ];
    for (from, to, strip) in [("src", "src", true), ("tests", "tests", false)] {
        for path in rust_files(&lessons.join(from)) {
            let text =
                std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            let text = if strip { strip_solutions(&text) } else { text };
            let name = path.file_name().unwrap_or_default();
            files.push((Path::new(to).join(name), text));
        }
    }
    let page = repo.join("book/src/assignments.md");
    if let Ok(text) = std::fs::read_to_string(&page) {
        files.push(("book/assignments.md".into(), text));
    }
    if let Ok(lock) = std::fs::read_to_string(repo.join("Cargo.lock")) {
        files.push(("Cargo.lock".into(), lock));
    }
    for (rel, text) in &files {
        let path = out.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
        }
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(Export {
        files: files.into_iter().map(|(p, _)| p).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What libtest printed for a run with one pass, one stub and one wrong
    /// answer (the shape of its output, written out by hand).
    const SAMPLE: &str = "\
running 4 tests
test eq_2_1_larmor_rate ... ok
test eq_2_2_torque_rate ... FAILED
test eq_2_4_schott_angular_momentum ... FAILED
test eq_2_3_axial_schott_rate ... ok

failures:

---- eq_2_2_torque_rate stdout ----

thread 'eq_2_2_torque_rate' panicked at lessons/src/ch2.rs:20:5:
not yet implemented
note: run with `RUST_BACKTRACE=1` environment variable to display a backtrace

---- eq_2_4_schott_angular_momentum stdout ----

thread 'eq_2_4_schott_angular_momentum' panicked at src/grading.rs:88:9:

schott_angular_momentum, Eq. (2.4): wrong answer
  input: ...
  expected: (0, 0, 1)
  got: (0, 0, -1)
  hint: check the sign


failures:
    eq_2_2_torque_rate
    eq_2_4_schott_angular_momentum

test result: FAILED. 2 passed; 2 failed; 0 ignored; 0 measured; 0 filtered out
";

    #[test]
    fn the_harness_output_becomes_one_state_per_assignment() {
        let status = parse(SAMPLE);
        let state = |name: &str| {
            status
                .states
                .iter()
                .find(|(a, _)| a.test == name)
                .unwrap()
                .1
                .clone()
        };
        assert_eq!(state("eq_2_1_larmor_rate"), State::Passing);
        assert_eq!(state("eq_2_2_torque_rate"), State::NotStarted);
        let State::Failing(report) = state("eq_2_4_schott_angular_momentum") else {
            panic!("failing")
        };
        assert!(
            report.starts_with("schott_angular_momentum, Eq. (2.4)") && report.contains("hint:"),
            "{report}"
        );
        assert!(!report.contains("thread '"), "{report}");
        assert_eq!(state("eq_3_3_truncated_ale_rhs"), State::Unknown);
        assert_eq!(status.passing(), 2);
        // Course order: (2.1), then (2.4), which fails.
        assert_eq!(
            status.next().unwrap().0.test,
            "eq_2_4_schott_angular_momentum"
        );
    }

    #[test]
    fn a_compile_error_is_reported_for_every_ungraded_assignment() {
        let status = parse(
            "error[E0308]: mismatched types\n --> lessons/src/ch2.rs:3:5\nerror: could not compile `spintop-lessons`\n",
        );
        assert!(
            status
                .states
                .iter()
                .all(|(_, s)| matches!(s, State::DoesNotCompile(e) if e.contains("E0308")))
        );
        assert_eq!(status.passing(), 0);
    }

    #[test]
    fn every_assignment_names_a_real_test_and_function() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
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

    #[test]
    fn a_save_regrades_only_the_graders_of_the_saved_file() {
        assert_eq!(binaries_for(&["ch2.rs".into()]), vec!["ch2"]);
        // numerics.rs holds three assignments of one grader binary.
        assert_eq!(binaries_for(&["numerics.rs".into()]), vec!["numerics"]);
        assert_eq!(
            binaries_for(&["ch4.rs".into(), "ch2.rs".into()]),
            vec!["ch2", "ch4"]
        );
        // lib.rs (or any file without an assignment) can change every grader.
        assert!(binaries_for(&["lib.rs".into()]).is_empty());
        assert!(binaries_for(&["ch2.rs".into(), "helpers.rs".into()]).is_empty());
    }

    #[test]
    fn a_partial_regrade_keeps_the_other_verdicts() {
        let before = parse(SAMPLE);
        assert_eq!(before.passing(), 2);
        // A run of the ch4 graders alone: one passes, ch2's tests are absent.
        let fresh = parse("test eq_4_11_precession_tilt ... ok\n");
        let after = before.merged(fresh.clone(), &["ch4"]);
        assert_eq!(after.passing(), 3);
        let tilt = after
            .states
            .iter()
            .find(|(a, _)| a.test == "eq_4_11_precession_tilt");
        assert_eq!(tilt.unwrap().1, State::Passing);
        // Merging it as if every grader had run forgets ch2's verdicts.
        assert_eq!(before.merged(fresh, &[]).passing(), 1);
        // A compile error concerns every assignment.
        let broken = parse("error[E0308]: mismatched types\n");
        assert!(!before.merged(broken.clone(), &["ch4"]).complete());
        assert_eq!(before.merged(broken, &["ch4"]).passing(), 0);
    }

    #[test]
    fn an_export_holds_the_stubs_and_graders_and_no_solution() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let out = std::env::temp_dir().join(format!("spintop-export-test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&out);
        let written = export(root, &out).unwrap();
        for a in COURSE {
            let file = a.file.trim_start_matches("lessons/");
            let text = std::fs::read_to_string(out.join(file)).unwrap();
            let start = text.find(&format!("pub fn {}(", a.function)).unwrap();
            let body = &text[start..start + text[start..].find("\n}").unwrap()];
            assert!(
                body.contains("todo!("),
                "{}: the stub, not a solution",
                a.function
            );
            assert!(out.join("tests").join(format!("{}.rs", a.binary)).is_file());
        }
        for rel in &written.files {
            let text = std::fs::read_to_string(out.join(rel)).unwrap();
            if rel.starts_with("src") || rel.ends_with("Cargo.toml") {
                assert!(
                    !text.contains("solutions"),
                    "{} mentions the solutions",
                    rel.display()
                );
            }
        }
        assert!(!out.join("src/solutions").exists());
        // Every solution's body is absent from every exported source file.
        for entry in std::fs::read_dir(root.join("lessons/src/solutions")).unwrap() {
            let solution = std::fs::read_to_string(entry.unwrap().path()).unwrap();
            for body in solution.split("\npub fn ").skip(1) {
                let body = &body[body.find('{').unwrap()..];
                let body = &body[..body.find("\n}").unwrap_or(body.len())];
                if body.lines().count() < 3 {
                    continue;
                }
                for rel in written.files.iter().filter(|p| p.starts_with("src")) {
                    let text = std::fs::read_to_string(out.join(rel)).unwrap();
                    assert!(!text.contains(body), "{} holds a solution", rel.display());
                }
            }
        }
        let manifest = std::fs::read_to_string(out.join("Cargo.toml")).unwrap();
        assert!(
            manifest.contains("[workspace]")
                && manifest.contains("spintop = { path")
                && manifest.contains("default-features = false")
        );
        // A second export into the same folder is refused, nothing overwritten.
        assert!(export(root, &out).unwrap_err().contains("not empty"));
        std::fs::remove_dir_all(&out).unwrap();
    }

    #[test]
    fn stripping_the_solutions_keeps_the_stub() {
        let text = "use a;\n#[cfg(not(feature = \"solutions\"))]\npub fn f() {\n    todo!()\n}\n\n#[cfg(feature = \"solutions\")]\npub use crate::solutions::ch2::*;\n";
        assert_eq!(
            strip_solutions(text),
            "use a;\npub fn f() {\n    todo!()\n}\n"
        );
    }

    #[test]
    fn the_hint_ladder_climbs_one_rung_per_request_and_stays_on_the_formula() {
        let a = find("2.2").unwrap();
        assert_eq!(a.function, "torque_rate");
        assert_eq!(find("(2.2)"), Some(a));
        assert_eq!(find("eq_2_2_torque_rate"), Some(a));
        assert_eq!(find("nope"), None);
        let mut p = Progress::default();
        let rungs: Vec<usize> = (0..4).map(|_| next_hint(&mut p, a).rung).collect();
        assert_eq!(rungs, [1, 2, 3, 3]);
        let last = next_hint(&mut p, a);
        assert!(last.is_last() && last.text == a.hints[2]);
        assert_eq!(p.hints["torque_rate"], 3);
        // Another assignment starts at the bottom.
        assert_eq!(next_hint(&mut p, find("larmor_rate").unwrap()).rung, 1);
    }

    #[test]
    fn the_progress_lives_inside_the_project_and_survives_a_round_trip() {
        let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
        assert_eq!(
            progress_path(&lessons_dir(repo)),
            repo.join("target/spintop-course.json")
        );
        let dir = std::env::temp_dir().join(format!("spintop-progress-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        assert_eq!(progress_path(&dir), dir.join("target/spintop-course.json"));
        assert_eq!(load_progress(&dir), Progress::default());
        let mut p = Progress::default();
        next_hint(&mut p, &COURSE[0]);
        let mut status = parse("");
        status.states[1].1 = State::Passing;
        assert!(record_passes(&mut p, &status, 1234));
        assert!(
            !record_passes(&mut p, &status, 9999),
            "the first pass is kept"
        );
        save_progress(&dir, &p).unwrap();
        assert_eq!(load_progress(&dir), p);
        assert_eq!(p.first_passed[COURSE[1].function], 1234);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_probe_of_a_chapter_is_read_back() {
        assert!(ProbeSpec::for_chapter("Section 2: two laws").is_none());
        let spec = ProbeSpec::for_chapter("Section 4.2: the reduced top").unwrap();
        assert_eq!(
            spec.request(),
            "reduced_closed_form 0.4 1 0 0.1 0.2 200 200"
        );
        let out = "running 1 test\nprobe 0e0 0e0 1e-1 2e-1\nprobe 1e0 1e-2 9e-2 2e-1\ntest probe ... ok\n";
        assert_eq!(
            parse_probe(out),
            Ok(Probed::Samples(vec![
                (0.0, [0.0, 0.1, 0.2]),
                (1.0, [0.01, 0.09, 0.2])
            ]))
        );
        assert_eq!(
            parse_probe("probe: panicked: not yet implemented: Eq. (4.7)\n"),
            Ok(Probed::Panicked("not yet implemented: Eq. (4.7)".into()))
        );
        assert!(parse_probe("error[E0308]: mismatched types\n").is_err());
    }

    #[test]
    fn the_probe_samples_the_reference_solution() {
        // The instructor's solution through the real probe: cargo runs it.
        let spec = ProbeSpec::for_chapter("Section 4.2").unwrap();
        let dir = lessons_dir(Path::new(env!("CARGO_MANIFEST_DIR")));
        let probed = probe(&dir, &spec).unwrap();
        // Without the solutions feature the stub answers: not started.
        assert!(
            matches!(probed, Probed::Panicked(ref m) if m.contains("not yet implemented")),
            "{probed:?}"
        );
    }

    #[test]
    fn two_copies_never_share_a_package_name() {
        // Cargo would otherwise reuse one copy's test programs for the other
        // when they share a build folder (see export_manifest).
        let spintop = Path::new(env!("CARGO_MANIFEST_DIR"));
        let a = export_manifest(spintop, Path::new("/tmp/course/alice"));
        let b = export_manifest(spintop, Path::new("/tmp/course/bob"));
        let name = |m: &str| {
            m.lines()
                .find(|l| l.starts_with("name = \"spintop-lessons"))
                .unwrap()
                .to_string()
        };
        assert_ne!(name(&a), name(&b));
        for m in [&a, &b] {
            assert!(m.contains("[lib]\nname = \"spintop_lessons\""), "{m}");
        }
    }
}
