//! # spintop
//!
//! The free rotation of a polarized spinning top under radiation reaction, after
//! A. Duviryak, "On the free rotation of a polarized spinning-top as a test of the
//! correct radiation reaction torque". Every equation of the paper that the crate
//! uses is cited in its doc comment as `Paper: Eq. (N.M).`
//!
//! - [`math`]: scalar, vector and rotation types; SO(3) helpers.
//! - [`numbers`]: how numbers are written (messages, headers, tables, CSV, axes) and read.
//! - [`physics`]: the paper, one module per concept (pure: no I/O, no clock).
//! - [`integrate`]: RK4, Dormand–Prince 5(4), DOP853 and Radau IIA 5 over one small trait; Strang and Yoshida-4 splittings.
//! - [`sim`]: a model plus a method, stepped and sampled (pure).
//! - [`scene`]: one question in a TOML file, and the lightest model that answers it (pure).
//! - [`stability`]: where natural methods fail, beside what spintop does instead (pure).
//! - [`figure`]: the paper's Figures 1 and 2 as point sets (pure).
//! - [`workprecision`]: error against cost for every method on the paper's problems (pure;
//!   the clock is injected).
//! - [`output`]: what `simulate`, `balance`, `orbit` and `shell` answer: the request, the
//!   computation, the JSON contract and its table and CSV forms (the scene engine prints the same).
//! - [`plot`]: ASCII charts for the lessons, the book and the command line; the figures as text and SVG.
//! - [`assignment`]: the types a course assignment's signature uses (and nothing that computes).
//!
//! This crate is the core of a workspace and does no I/O: it reads no file, no
//! clock and no terminal, and prints nothing. The graders (`spintop-grading`),
//! the course runner (`spintop-course`), the book server (`spintop-server`) and
//! the `spintop` application (command line, live view, terminal reader) are
//! crates above it; none of them is visible from here.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod assignment;
pub mod figure;
pub mod integrate;
pub mod math;
pub mod numbers;
pub mod output;
pub mod physics;
pub mod plot;
pub mod scene;
pub mod sim;
pub mod stability;
pub mod workprecision;

/// The book's chapters (`book/src`). `cargo test` compiles and runs every Rust
/// block in them as a doctest; `tests/project/book.rs` checks that every chapter in
/// `SUMMARY.md` is listed here or, for the course's chapters, in
/// `spintop-course`'s list.
#[cfg(doctest)]
pub mod book {
    #[doc = include_str!("../../../book/src/preface.md")]
    pub struct Preface;
    #[doc = include_str!("../../../book/src/question-and-scales.md")]
    pub struct QuestionAndScales;
    #[doc = include_str!("../../../book/src/section-2.md")]
    pub struct Section2;
    #[doc = include_str!("../../../book/src/section-3.md")]
    pub struct Section3;
    #[doc = include_str!("../../../book/src/section-4-1.md")]
    pub struct Section4_1;
    #[doc = include_str!("../../../book/src/section-4-2.md")]
    pub struct Section4_2;
    #[doc = include_str!("../../../book/src/section-5.md")]
    pub struct Section5;
    #[doc = include_str!("../../../book/src/appendix.md")]
    pub struct Appendix;
    #[doc = include_str!("../../../book/src/asymmetric-top.md")]
    pub struct AsymmetricTop;
    #[doc = include_str!("../../../book/src/numerical-methods.md")]
    pub struct NumericalMethods;
    #[doc = include_str!("../../../book/src/where-methods-fail.md")]
    pub struct WhereMethodsFail;
    #[doc = include_str!("../../../book/src/real-particles.md")]
    pub struct RealParticles;
    #[doc = include_str!("../../../book/src/speed-accuracy.md")]
    pub struct SpeedAccuracy;
    #[doc = include_str!("../../../book/src/solutions-section-2.md")]
    pub struct SolutionsSection2;
    #[doc = include_str!("../../../book/src/solutions-section-3.md")]
    pub struct SolutionsSection3;
    #[doc = include_str!("../../../book/src/solutions-section-4-1.md")]
    pub struct SolutionsSection4_1;
    #[doc = include_str!("../../../book/src/solutions-section-4-2.md")]
    pub struct SolutionsSection4_2;
    #[doc = include_str!("../../../book/src/solutions-section-5.md")]
    pub struct SolutionsSection5;
    #[doc = include_str!("../../../book/src/solutions-appendix.md")]
    pub struct SolutionsAppendix;
    #[doc = include_str!("../../../book/src/glossary.md")]
    pub struct Glossary;
    #[doc = include_str!("../../../book/src/errata.md")]
    pub struct Errata;
    #[doc = include_str!("../../../book/src/symbols.md")]
    pub struct Symbols;
    #[doc = include_str!("../../../book/src/scene-reference.md")]
    pub struct SceneReference;
    #[doc = include_str!("../../../book/src/using-spintop.md")]
    pub struct UsingSpintop;
    #[doc = include_str!("../../../book/src/bibliography.md")]
    pub struct Bibliography;
}
