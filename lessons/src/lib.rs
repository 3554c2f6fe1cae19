//! Course assignments on the polarized spinning top, graded by `cargo test`.
//!
//! Every public function here is a stub that ends in `todo!()`. Fill one in,
//! then run its chapter's grader, for example
//!
//! ```text
//! cargo test -p spintop-lessons --test ch2
//! ```
//!
//! A grader feeds your function 200 reproducible random inputs, compares the
//! answers with spintop's own implementation, and on the first mismatch
//! prints the input, the expected and the actual value, and the equation to
//! read again. The book's chapter "Assignments" walks through one.
//!
//! | module | book chapter | assignments |
//! |---|---|---|
//! | [`ch2`] | Section 2 | (2.1), (2.2), (2.4), the axial part of dL_S/dt |
//! | [`ch3`] | Section 3 | the truncated ALE (3.3) of a general top |
//! | [`ch4`] | Sections 4.1, 4.2 | the reduced closed form (4.15)–(4.16); the tilt (4.11) |
//! | [`numerics`] | Where methods fail | one RK4 step; one DP5 step; Euler angles with the pole |
//! | [`appendix`] | Appendix | the method-of-steps update of (A.1) |

pub mod appendix;
pub mod ch2;
pub mod ch3;
pub mod ch4;
pub mod numerics;

// The instructor's reference solutions: delete this line, the directory
// src/solutions/ and the `solutions` feature before handing out.
#[cfg(feature = "solutions")]
mod solutions;
