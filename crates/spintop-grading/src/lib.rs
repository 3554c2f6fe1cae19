//! Graders for the course assignments of the `spintop-lessons` package.
//!
//! Each grader takes a student's function and a **seed**, draws many random
//! valid inputs from it (a new seed each grading, so that a table of one
//! grading's answers is worth nothing at the next; the seed is printed in
//! every failure, so that it can be replayed), adds the edge cases the
//! assignment needs (a pole, a negative spin, …), compares the answers with
//! spintop's own implementation (or a closed form, or an invariant), and stops
//! at the first failing input with a [`Failed`]: the input, the expected and
//! the actual value, and a **diagnosis** of what is wrong (a sign flip, a
//! factor 2, the Larmor-like law handed in for the torque, one step too many,
//! …). A failure never prints the formula: that is the last rung of the hint
//! ladder (`spintop course hint NAME`).
//!
//! A diagnosis is only given when it is confirmed: a plausible mistake must
//! predict the student's answer on the failing input and on other inputs too.
//!
//! The graders run inside the student's test process (`lessons/tests/*.rs`,
//! through [`graded!`](crate::graded)); whether one passed is then read by
//! `spintop course` from the test's exit status and from a verdict file that
//! only the grader writes ([`verdict`]), never from printed text. The rule
//! about the student's source (no path into spintop's answers, no file or
//! process access) is checked by the course's shell on a parsed syntax tree
//! before anything is compiled; the graders themselves stay in the core, so
//! that a student's build compiles neither a parser nor the terminal UI.
//!
//! The graders, one per assignment, are in `graders/` (one file per chapter)
//! and are re-exported here.

use spintop::math::{Real, State, Vec3};
use spintop::physics::shell::C;
use std::cell::Cell;
use std::fmt;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::rc::Rc;
use std::sync::Once;

mod diagnosis;
mod graders;
mod parts;
pub mod remote;
pub mod verdict;
pub use diagnosis::{factor_words, shape_diagnosis};
pub use graders::*;
pub use remote::{Fault, Remote, grade_remote};
pub use verdict::assert_graded;

pub use spintop::assignment::DynField;

/// Random cases per grader (plus its fixed edge cases).
pub const CASES: usize = 200;

/// The words that start a shortcut's diagnosis.
pub const NO_SHORTCUT: &str = "no shortcut";

/// The words that start the diagnosis of an untouched stub.
pub const STUB: &str = "the stub is still a todo!()";

/// A passed assignment.
#[derive(Clone, Debug, PartialEq)]
pub struct Passed {
    /// The assignment.
    pub assignment: &'static str,
    /// The equation it implements.
    pub equation: &'static str,
    /// How many inputs were checked.
    pub cases: usize,
}

/// A failed assignment, at its first failing input.
#[derive(Clone, Debug, PartialEq)]
pub struct Failed {
    /// The assignment.
    pub assignment: &'static str,
    /// The equation it implements.
    pub equation: &'static str,
    /// The seed the inputs were drawn from (the same seed, the same inputs).
    pub seed: u64,
    /// The input, readable.
    pub input: String,
    /// What the reference gives (or what physics requires).
    pub expected: String,
    /// What the student's function gave.
    pub actual: String,
    /// What is wrong, in words (never the formula).
    pub diagnosis: String,
    /// The `--course DIR` that a replay or a hint must repeat (`None` for the
    /// repository's own lessons, where `spintop course` looks by default).
    pub course: Option<String>,
}

impl Failed {
    /// Whether the function is still the untouched `todo!()` stub.
    pub fn is_stub(&self) -> bool {
        self.diagnosis.starts_with(STUB)
    }
}

/// ` --course DIR` for a command that must repeat the course it was given,
/// or nothing (the repository's own lessons, where `spintop course` looks by
/// default).
pub fn course_arg(course: Option<&str>) -> String {
    course
        .map(|c| format!(" --course {}", shell_word(c)))
        .unwrap_or_default()
}

/// The command that climbs the hint ladder of `assignment`.
pub fn hint_command(assignment: &str, course: Option<&str>) -> String {
    format!("spintop course hint {assignment}{}", course_arg(course))
}

/// `s` as one word of a shell command (quoted when it needs to be).
fn shell_word(s: &str) -> String {
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "/._-+:@%".contains(c))
    {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}

impl fmt::Display for Failed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let course = course_arg(self.course.as_deref());
        writeln!(
            f,
            "{} ({}) is not right yet.",
            self.assignment, self.equation
        )?;
        writeln!(f, "  input:     {}", self.input)?;
        writeln!(f, "  expected:  {}", self.expected)?;
        writeln!(f, "  got:       {}", self.actual)?;
        writeln!(f, "  diagnosis: {}", self.diagnosis)?;
        writeln!(
            f,
            "  seed:      {seed} (these inputs again: SPINTOP_SEED={seed} cargo test, or spintop course --seed {seed}{course})",
            seed = self.seed
        )?;
        write!(
            f,
            "  stuck?     {} (one rung at a time)",
            hint_command(self.assignment, self.course.as_deref())
        )
    }
}

/// The outcome of a grader.
/// (The failure is boxed: it carries several strings.)
pub type Grade = Result<Passed, Box<Failed>>;

/// SplitMix64 (Steele, Lea & Flood 2014): small, seedable, reproducible.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [a, b).
    pub fn uniform(&mut self, a: Real, b: Real) -> Real {
        let u = (self.next_u64() >> 11) as Real / (1u64 << 53) as Real;
        a + (b - a) * u
    }
    /// −1 or +1, evenly.
    pub fn sign(&mut self) -> Real {
        if self.next_u64() >> 63 == 0 {
            -1.0
        } else {
            1.0
        }
    }
    /// A vector with components uniform in [−r, r).
    pub fn vec3(&mut self, r: Real) -> Vec3 {
        Vec3::new(
            self.uniform(-r, r),
            self.uniform(-r, r),
            self.uniform(-r, r),
        )
    }
}

thread_local! {
    /// True while this thread runs a student's function inside a grader.
    static GRADING: Cell<bool> = const { Cell::new(false) };
}

/// Install (once) a panic hook that stays quiet for panics inside a grader,
/// whose message the grader reports itself, and defers to the previous hook
/// for every other panic.
fn quiet_panics_while_grading() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !GRADING.with(Cell::get) {
                previous(info);
            }
        }));
    });
}

/// Call the student's code; a panic (a `todo!()` stub, say) becomes its message.
fn call<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    quiet_panics_while_grading();
    GRADING.with(|g| g.set(true));
    let result = catch_unwind(AssertUnwindSafe(f));
    GRADING.with(|g| g.set(false));
    result.map_err(|payload| {
        let msg = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic".to_string());
        format!("panicked: {msg}")
    })
}

/// The diagnosis of a panic: a stub, or a crash.
fn panic_diagnosis(msg: &str) -> String {
    if msg.starts_with("panicked: not yet implemented")
        || msg.starts_with("panicked: not implemented")
    {
        format!("{STUB}: fill it in.")
    } else {
        "your function panicked on a valid input: an unwrap, an index out of range, or an overflow?"
            .to_string()
    }
}

/// A value as a grader prints it and compares its parts.
pub(crate) trait Answer {
    /// Readable, for the report.
    fn show(&self) -> String;
    /// Its numbers, for the diagnosis.
    fn parts(&self) -> Vec<Real>;
    /// The names of its numbers, for the diagnosis (one per part).
    fn labels() -> Vec<String>;
    /// What kind of number it is: a real or complex scalar has no direction.
    fn kind() -> diagnosis::Kind {
        diagnosis::Kind::Vector
    }
}

impl Answer for Real {
    fn show(&self) -> String {
        format!("{self:e}")
    }
    fn parts(&self) -> Vec<Real> {
        vec![*self]
    }
    fn labels() -> Vec<String> {
        vec!["the value".into()]
    }
    fn kind() -> diagnosis::Kind {
        diagnosis::Kind::Real
    }
}

impl Answer for Vec3 {
    fn show(&self) -> String {
        format!("({:e}, {:e}, {:e})", self.x, self.y, self.z)
    }
    fn parts(&self) -> Vec<Real> {
        self.as_slice().to_vec()
    }
    fn labels() -> Vec<String> {
        ["component 1", "component 2", "component 3"]
            .map(String::from)
            .to_vec()
    }
}

impl Answer for (State<3>, State<3>) {
    fn show(&self) -> String {
        format!("step {}, error estimate {}", self.0.show(), self.1.show())
    }
    fn parts(&self) -> Vec<Real> {
        [self.0.parts(), self.1.parts()].concat()
    }
    fn labels() -> Vec<String> {
        (1..=3)
            .map(|i| format!("the step's component {i}"))
            .chain((1..=3).map(|i| format!("the error estimate's component {i}")))
            .collect()
    }
}

impl Answer for (Real, Real) {
    fn show(&self) -> String {
        format!("({:e}, {:e})", self.0, self.1)
    }
    fn parts(&self) -> Vec<Real> {
        vec![self.0, self.1]
    }
    fn labels() -> Vec<String> {
        vec!["the first number".into(), "the second number".into()]
    }
    fn kind() -> diagnosis::Kind {
        diagnosis::Kind::Parts
    }
}

impl Answer for [Vec3; 4] {
    fn show(&self) -> String {
        format!(
            "d = {}, d' = {}, d'' = {}, d''' = {}",
            self[0].show(),
            self[1].show(),
            self[2].show(),
            self[3].show()
        )
    }
    fn parts(&self) -> Vec<Real> {
        self.iter().flat_map(|v| v.parts()).collect()
    }
    fn labels() -> Vec<String> {
        ["d", "d'", "d''", "d'''"]
            .iter()
            .flat_map(|v| ["x", "y", "z"].map(|c| format!("{v}.{c}")))
            .collect()
    }
}

impl Answer for C {
    fn show(&self) -> String {
        format!("{:e} + {:e}i", self.re, self.im)
    }
    fn parts(&self) -> Vec<Real> {
        vec![self.re, self.im]
    }
    fn labels() -> Vec<String> {
        vec!["the real part".into(), "the imaginary part".into()]
    }
    fn kind() -> diagnosis::Kind {
        diagnosis::Kind::Complex
    }
}

/// A plausible wrong answer and what it means.
pub(crate) struct Mistake<'a, I, T> {
    pub(crate) diagnosis: String,
    pub(crate) answer: Rc<dyn Fn(&I) -> T + 'a>,
}

/// A plausible wrong answer, computed directly.
pub(crate) fn mistake<'a, I, T>(
    diagnosis: impl Into<String>,
    answer: impl Fn(&I) -> T + 'a,
) -> Mistake<'a, I, T> {
    Mistake {
        diagnosis: diagnosis.into(),
        answer: Rc::new(answer),
    }
}

/// A comparison of two answers.
pub(crate) type Close<'a, T> = Rc<dyn Fn(&T, &T) -> bool + 'a>;

/// The student's function called again on another input (`None`: it panicked).
pub(crate) type Again<'a, I, T> = dyn Fn(&I) -> Option<T> + 'a;

/// A probe: given the failing input and a way to call the student's function
/// on other inputs, a diagnosis (e.g. "one step too many").
pub(crate) type Probe<'a, I, T> = Box<dyn Fn(&I, &Again<'_, I, T>) -> Option<String> + 'a>;

/// One grader: its inputs, the reference, the tolerance, and what it knows
/// of plausible wrong answers.
pub(crate) struct Grader<'a, I, T> {
    pub(crate) name: &'static str,
    pub(crate) equation: &'static str,
    pub(crate) seed: u64,
    pub(crate) inputs: Vec<I>,
    pub(crate) reference: Rc<dyn Fn(&I) -> T + 'a>,
    pub(crate) close: Close<'a, T>,
    pub(crate) mistakes: Vec<Mistake<'a, I, T>>,
    pub(crate) probes: Vec<Probe<'a, I, T>>,
    pub(crate) labels: Option<Vec<String>>,
}

impl<'a, I: fmt::Debug + 'a, T: Answer + 'a> Grader<'a, I, T> {
    pub(crate) fn new(
        name: &'static str,
        equation: &'static str,
        seed: u64,
        inputs: Vec<I>,
        reference: impl Fn(&I) -> T + 'a,
        close: impl Fn(&T, &T) -> bool + 'a,
    ) -> Self {
        Self {
            name,
            equation,
            seed,
            inputs,
            reference: Rc::new(reference),
            close: Rc::new(close),
            mistakes: Vec::new(),
            probes: Vec::new(),
            labels: None,
        }
    }

    /// Plausible wrong answers, computed directly.
    pub(crate) fn mistakes(mut self, mistakes: Vec<Mistake<'a, I, T>>) -> Self {
        self.mistakes.extend(mistakes);
        self
    }

    /// A plausible wrong answer that is the right formula with a wrong input
    /// (a parameter doubled, two components swapped, …): the reference
    /// evaluated at `change(input)`.
    pub(crate) fn variant(
        mut self,
        diagnosis: &'static str,
        change: impl Fn(&I) -> I + 'a,
    ) -> Self {
        let reference = Rc::clone(&self.reference);
        self.mistakes
            .push(mistake(diagnosis, move |x: &I| reference(&change(x))));
        self
    }

    pub(crate) fn probe(
        mut self,
        probe: impl Fn(&I, &Again<'_, I, T>) -> Option<String> + 'a,
    ) -> Self {
        self.probes.push(Box::new(probe));
        self
    }

    /// Names for the parts of an answer, for the diagnosis.
    pub(crate) fn labels(mut self, labels: &[&str]) -> Self {
        self.labels = Some(labels.iter().map(|s| s.to_string()).collect());
        self
    }

    pub(crate) fn fail(
        &self,
        input: String,
        expected: String,
        actual: String,
        diagnosis: String,
    ) -> Box<Failed> {
        // An answer that is not finite is reported in words, so that the
        // report reaches the student (the CLI prints no bare `NaN`).
        let words = |s: String| spintop::numbers::non_finite_in_words(&s);
        Box::new(Failed {
            assignment: self.name,
            equation: self.equation,
            seed: self.seed,
            input: words(input),
            expected: words(expected),
            actual: words(actual),
            diagnosis: words(diagnosis),
            course: None,
        })
    }

    /// Whether the mistake `m` explains the student's answers: it predicts
    /// `actual` at the failing input, and (where it differs from the right
    /// answer) the student's answers at two more inputs.
    fn confirmed(
        &self,
        m: &Mistake<'a, I, T>,
        at: usize,
        actual: &T,
        again: &Again<'_, I, T>,
    ) -> bool {
        let wrong = (m.answer)(&self.inputs[at]);
        if !wrong.parts().iter().all(|x| x.is_finite()) || !(self.close)(actual, &wrong) {
            return false;
        }
        let mut seen = 0;
        for other in self
            .inputs
            .iter()
            .cycle()
            .skip(at + 1)
            .take(self.inputs.len() - 1)
        {
            let wrong = (m.answer)(other);
            let right = (self.reference)(other);
            if !wrong.parts().iter().all(|x| x.is_finite()) || (self.close)(&wrong, &right) {
                continue; // this input cannot tell the mistake from the right answer
            }
            match again(other) {
                Some(theirs) if (self.close)(&theirs, &wrong) => seen += 1,
                _ => return false,
            }
            if seen == 2 {
                break;
            }
        }
        true
    }

    /// The diagnosis of a wrong `actual` at input number `at`.
    fn diagnose(&self, at: usize, actual: &T, expected: &T, student: &dyn Fn(&I) -> T) -> String {
        let again = |i: &I| call(|| student(i)).ok();
        for m in &self.mistakes {
            if self.confirmed(m, at, actual, &again) {
                return m.diagnosis.clone();
            }
        }
        for probe in &self.probes {
            if let Some(d) = probe(&self.inputs[at], &again) {
                return d;
            }
        }
        let labels = self.labels.clone().unwrap_or_else(T::labels);
        diagnosis::shape(&actual.parts(), &expected.parts(), &labels, T::kind())
    }

    /// Grade `student` on every input.
    pub(crate) fn run(&self, student: impl Fn(&I) -> T) -> Grade {
        for (at, input) in self.inputs.iter().enumerate() {
            let expected = (self.reference)(input);
            match call(|| student(input)) {
                Ok(actual) if (self.close)(&actual, &expected) => {}
                Ok(actual) => {
                    let diagnosis = self.diagnose(at, &actual, &expected, &student);
                    return Err(self.fail(
                        format!("{input:?}"),
                        expected.show(),
                        actual.show(),
                        diagnosis,
                    ));
                }
                Err(msg) => {
                    let diagnosis = panic_diagnosis(&msg);
                    return Err(self.fail(format!("{input:?}"), expected.show(), msg, diagnosis));
                }
            }
        }
        Ok(self.passed())
    }

    pub(crate) fn passed(&self) -> Passed {
        Passed {
            assignment: self.name,
            equation: self.equation,
            cases: self.inputs.len(),
        }
    }
}

/// |a − b| ≤ tol·(1 + |b|) over all the numbers of two answers.
pub(crate) fn close<T: Answer>(a: &T, b: &T, tol: Real) -> bool {
    let (a, b) = (a.parts(), b.parts());
    let diff: Real = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<Real>()
        .sqrt();
    let nb: Real = b.iter().map(|y| y * y).sum::<Real>().sqrt();
    a.len() == b.len() && a.iter().all(|x| x.is_finite()) && diff <= tol * (1.0 + nb)
}
