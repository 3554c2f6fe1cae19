//! Reference solutions, written the way a student would, without calling the
//! spintop functions they are graded against.

pub mod appendix;
pub mod ch2;
pub mod ch3;
pub mod ch4;
pub mod numerics;
