//! Graders for the course assignments of the `spintop-lessons` package.
//!
//! Each grader takes a student's function, feeds it many random valid inputs
//! from a fixed seed (so every run and every student sees the same cases),
//! compares the answer with spintop's own implementation (or, where there is
//! one, a closed form or an invariant), and stops at the first failing input
//! with a [`Failed`]: the input, the expected and the actual value, and a
//! **diagnosis** of what is wrong (a sign flip, a factor 2, the Larmor-like law
//! handed in for the torque, right at t = 0 but drifting, …). A failure never
//! prints the formula: that is the last rung of the hint ladder
//! (`spintop course hint NAME`, see [`crate::course`]).
//!
//! A student's file must not call the reference: [`no_shortcut`] reads the
//! assignment file's source and rejects any path into spintop other than
//! [`crate::math`] and [`crate::assignment`].
//!
//! The graders themselves, one per assignment, are in `grading/graders.rs`
//! and are re-exported here.

use crate::math::{Real, State, Vec3};
use crate::physics::shell::C;
use std::cell::Cell;
use std::fmt;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Once;

mod graders;
pub use graders::*;

pub use crate::assignment::DynField;

/// The seed of every grader's random cases.
pub const SEED: u64 = 2026;
/// Random cases per grader (plus its fixed special cases).
pub const CASES: usize = 200;

/// The words that start a shortcut's diagnosis.
pub const NO_SHORTCUT: &str = "no shortcut";

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
    /// The input, readable.
    pub input: String,
    /// What the reference gives (or what physics requires).
    pub expected: String,
    /// What the student's function gave.
    pub actual: String,
    /// What is wrong, in words (never the formula).
    pub diagnosis: String,
}

impl fmt::Display for Failed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{} ({}) is not right yet.",
            self.assignment, self.equation
        )?;
        writeln!(f, "  input:     {}", self.input)?;
        writeln!(f, "  expected:  {}", self.expected)?;
        writeln!(f, "  got:       {}", self.actual)?;
        writeln!(f, "  diagnosis: {}", self.diagnosis)?;
        write!(
            f,
            "  stuck?     spintop course hint {} (one rung at a time)",
            self.assignment
        )
    }
}

/// The outcome of a grader.
/// (The failure is boxed: it carries four strings.)
pub type Grade = Result<Passed, Box<Failed>>;

/// Panic with a readable report unless `grade` passed (for `#[test]`s).
pub fn assert_passes(grade: Grade) {
    if let Err(failed) = grade {
        panic!("\n{failed}\n");
    }
}

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
        "the stub is still a todo!(): fill it in.".to_string()
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
}

impl Answer for Real {
    fn show(&self) -> String {
        format!("{self:e}")
    }
    fn parts(&self) -> Vec<Real> {
        vec![*self]
    }
}

impl Answer for Vec3 {
    fn show(&self) -> String {
        format!("({:e}, {:e}, {:e})", self.x, self.y, self.z)
    }
    fn parts(&self) -> Vec<Real> {
        self.as_slice().to_vec()
    }
}

impl Answer for (State<3>, State<3>) {
    fn show(&self) -> String {
        format!("step {}, error estimate {}", self.0.show(), self.1.show())
    }
    fn parts(&self) -> Vec<Real> {
        [self.0.parts(), self.1.parts()].concat()
    }
}

impl Answer for (Real, Real) {
    fn show(&self) -> String {
        format!("({:e}, {:e})", self.0, self.1)
    }
    fn parts(&self) -> Vec<Real> {
        vec![self.0, self.1]
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
}

impl Answer for C {
    fn show(&self) -> String {
        format!("{:e} + {:e}i", self.re, self.im)
    }
    fn parts(&self) -> Vec<Real> {
        vec![self.re, self.im]
    }
}

/// What is wrong with `actual` against `expected`, from their numbers alone:
/// not finite, zero, a sign flip, a simple factor, the right size in the wrong
/// direction, or neither.
pub fn shape_diagnosis(actual: &[Real], expected: &[Real]) -> String {
    if actual.iter().any(|x| !x.is_finite()) {
        return "your answer is not finite (NaN or infinity): a division by zero, or the square root of a negative number?".into();
    }
    if actual.len() != expected.len() {
        return "your answer has the wrong number of components".into();
    }
    let dot = |a: &[Real], b: &[Real]| a.iter().zip(b).map(|(x, y)| x * y).sum::<Real>();
    let ne = dot(expected, expected).sqrt();
    let na = dot(actual, actual).sqrt();
    if ne == 0.0 {
        return "the answer here is zero and yours is not: a term that should cancel does not"
            .into();
    }
    if na <= 1e-12 * (1.0 + ne) {
        return "your answer is zero where it should not be: a term is missing, or a variable is never used".into();
    }
    let k = dot(actual, expected) / (ne * ne);
    let residual = actual
        .iter()
        .zip(expected)
        .map(|(a, e)| (a - k * e).powi(2))
        .sum::<Real>()
        .sqrt();
    if residual <= 1e-8 * (na + ne) {
        if (k + 1.0).abs() < 1e-6 {
            return "a sign flip: your answer is exactly −1 times the right one".into();
        }
        for (f, name) in [
            (2.0, "2"),
            (0.5, "1/2"),
            (-2.0, "−2"),
            (-0.5, "−1/2"),
            (4.0, "4"),
            (0.25, "1/4"),
            (3.0, "3"),
            (1.0 / 3.0, "1/3"),
        ] {
            if (k / f - 1.0).abs() < 1e-6 {
                return format!(
                    "right up to a factor {name}: your answer is {name} times the right one"
                );
            }
        }
        return format!(
            "right direction, wrong size: your answer is {k:.4} times the right one (a missing parameter, or one used twice?)"
        );
    }
    if (na - ne).abs() <= 1e-8 * ne {
        let angle = (dot(actual, expected) / (na * ne)).clamp(-1.0, 1.0).acos();
        return format!(
            "right size, wrong direction ({:.1}° off): two components swapped, or a rotation turning the wrong way?",
            angle.to_degrees()
        );
    }
    format!(
        "wrong in size and direction (size {:.4} times the right one): check each term against the equation",
        na / ne
    )
}

/// A plausible wrong answer and what it means.
pub(crate) struct Mistake<'a, I, T> {
    pub(crate) diagnosis: &'static str,
    pub(crate) answer: Box<dyn Fn(&I) -> T + 'a>,
}

pub(crate) fn mistake<'a, I, T>(
    diagnosis: &'static str,
    answer: impl Fn(&I) -> T + 'a,
) -> Mistake<'a, I, T> {
    Mistake {
        diagnosis,
        answer: Box::new(answer),
    }
}

/// A comparison of two answers.
pub(crate) type Close<'a, T> = Box<dyn Fn(&T, &T) -> bool + 'a>;

/// A probe: given the failing input and a way to call the student's function
/// on another input, a diagnosis (e.g. "right at t = 0 but drifting").
pub(crate) type Probe<'a, I, T> = Box<dyn Fn(&I, &dyn Fn(&I) -> Option<T>) -> Option<String> + 'a>;

/// One grader: its inputs, the reference, the tolerance, and what it knows
/// of plausible wrong answers.
pub(crate) struct Grader<'a, I, T> {
    pub(crate) name: &'static str,
    pub(crate) equation: &'static str,
    pub(crate) inputs: Vec<I>,
    pub(crate) reference: Box<dyn Fn(&I) -> T + 'a>,
    pub(crate) close: Close<'a, T>,
    pub(crate) mistakes: Vec<Mistake<'a, I, T>>,
    pub(crate) probe: Option<Probe<'a, I, T>>,
}

impl<'a, I: fmt::Debug, T: Answer> Grader<'a, I, T> {
    pub(crate) fn new(
        name: &'static str,
        equation: &'static str,
        inputs: Vec<I>,
        reference: impl Fn(&I) -> T + 'a,
        close: impl Fn(&T, &T) -> bool + 'a,
    ) -> Self {
        Self {
            name,
            equation,
            inputs,
            reference: Box::new(reference),
            close: Box::new(close),
            mistakes: Vec::new(),
            probe: None,
        }
    }

    pub(crate) fn mistakes(mut self, mistakes: Vec<Mistake<'a, I, T>>) -> Self {
        self.mistakes = mistakes;
        self
    }

    pub(crate) fn probe(
        mut self,
        probe: impl Fn(&I, &dyn Fn(&I) -> Option<T>) -> Option<String> + 'a,
    ) -> Self {
        self.probe = Some(Box::new(probe));
        self
    }

    pub(crate) fn fail(
        &self,
        input: String,
        expected: String,
        actual: String,
        diagnosis: String,
    ) -> Box<Failed> {
        Box::new(Failed {
            assignment: self.name,
            equation: self.equation,
            input,
            expected,
            actual,
            diagnosis,
        })
    }

    /// The diagnosis of a wrong `actual` at `input`.
    fn diagnose(&self, input: &I, actual: &T, expected: &T, student: &dyn Fn(&I) -> T) -> String {
        for m in &self.mistakes {
            let wrong = (m.answer)(input);
            if wrong.parts().iter().all(|x| x.is_finite()) && (self.close)(actual, &wrong) {
                return m.diagnosis.to_string();
            }
        }
        if let Some(probe) = &self.probe {
            let again = |i: &I| call(|| student(i)).ok();
            if let Some(d) = probe(input, &again) {
                return d;
            }
        }
        shape_diagnosis(&actual.parts(), &expected.parts())
    }

    /// Grade `student` on every input.
    pub(crate) fn run(&self, student: impl Fn(&I) -> T) -> Grade {
        for input in &self.inputs {
            let expected = (self.reference)(input);
            match call(|| student(input)) {
                Ok(actual) if (self.close)(&actual, &expected) => {}
                Ok(actual) => {
                    let diagnosis = self.diagnose(input, &actual, &expected, &student);
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

/// The modules of spintop an assignment file may name.
pub const ALLOWED_MODULES: [&str; 2] = ["math", "assignment"];

/// Check that an assignment file does not reach spintop's own answers.
///
/// `source` is the file's text; every path that starts with `spintop` must go
/// on with `::math` or `::assignment` (so `use spintop as s`, `use
/// spintop::{physics, …}`, `spintop::physics::…`, `spintop::sim::…`,
/// `spintop::grading::…` are all rejected), and `include!`-like macros and
/// `#[path]` (ways to compile spintop's own sources into the file) are
/// rejected too. Comments are skipped. Returns the offending line.
pub fn no_shortcut(source: &str) -> Result<(), String> {
    let text = strip_comments(source);
    for (number, line) in text.lines().enumerate() {
        for banned in ["include!", "include_str!", "include_bytes!", "#[path"] {
            if line.replace(' ', "").contains(banned) {
                return Err(format!("line {}: {}", number + 1, line.trim()));
            }
        }
        let bytes = line.as_bytes();
        let mut from = 0;
        while let Some(at) = line[from..].find("spintop") {
            let start = from + at;
            let end = start + "spintop".len();
            from = end;
            let ident = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
            if (start > 0 && ident(bytes[start - 1])) || (end < bytes.len() && ident(bytes[end])) {
                continue; // part of another name, e.g. spintop_lessons
            }
            let rest: String = line[end..].chars().filter(|c| !c.is_whitespace()).collect();
            let ok = rest.strip_prefix("::").is_some_and(|after| {
                ALLOWED_MODULES.iter().any(|m| {
                    after.strip_prefix(m).is_some_and(|tail| {
                        !tail.starts_with(|c: char| c.is_alphanumeric() || c == '_')
                    })
                })
            });
            if !ok {
                return Err(format!("line {}: {}", number + 1, line.trim()));
            }
        }
    }
    Ok(())
}

/// The source without `//` and `/* */` comments (line breaks kept).
fn strip_comments(source: &str) -> String {
    let mut out = String::with_capacity(source.len());
    let mut chars = source.chars().peekable();
    let mut in_block = 0usize;
    let mut in_string = false;
    while let Some(c) = chars.next() {
        if in_block > 0 {
            if c == '*' && chars.peek() == Some(&'/') {
                chars.next();
                in_block -= 1;
            } else if c == '/' && chars.peek() == Some(&'*') {
                chars.next();
                in_block += 1;
            } else if c == '\n' {
                out.push('\n');
            }
            continue;
        }
        if in_string {
            out.push(c);
            if c == '\\' {
                if let Some(n) = chars.next() {
                    out.push(n);
                }
            } else if c == '"' {
                in_string = false;
            }
            continue;
        }
        match c {
            '"' => {
                in_string = true;
                out.push(c);
            }
            '/' if chars.peek() == Some(&'/') => {
                for n in chars.by_ref() {
                    if n == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            '/' if chars.peek() == Some(&'*') => {
                chars.next();
                in_block = 1;
            }
            _ => out.push(c),
        }
    }
    out
}

/// `grade`, unless one of the assignment's `sources` (`(file, text)`) takes a
/// shortcut through spintop's own implementation: then a failure whose
/// diagnosis starts with [`NO_SHORTCUT`].
pub fn without_shortcut(grade: Grade, sources: &[(&str, &str)]) -> Grade {
    let (assignment, equation) = match &grade {
        Ok(p) => (p.assignment, p.equation),
        Err(f) => (f.assignment, f.equation),
    };
    for (file, text) in sources {
        if let Err(line) = no_shortcut(text) {
            return Err(Box::new(Failed {
                assignment,
                equation,
                input: format!("the source of {file}"),
                expected: "paths into spintop only through spintop::math and spintop::assignment"
                    .into(),
                actual: line,
                diagnosis: format!(
                    "{NO_SHORTCUT}: this file reaches into spintop itself, where the reference answers live. Write the physics yourself; vectors come from spintop::math, the argument types from spintop::assignment (lessons/README.md says why)."
                ),
            }));
        }
    }
    grade
}
