//! The core's tests, in one binary: the paper's physics, one module per
//! claim (`physics`), the integrators and the models' numerics
//! (`numerics`), and the parsers of text from outside (`parsers`).

mod support;

mod numerics;
mod parsers;
mod physics;
