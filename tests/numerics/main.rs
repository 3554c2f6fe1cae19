//! The numerical methods and what is built on them: the integrators, the implicit method, the splittings, the stability suite, work against precision and the scenes.
//! (One test binary for all of them: each file under tests/ is a binary to link.)

#[path = "../support/mod.rs"]
mod support;

mod cost;
mod implicit;
mod integrators;
mod scenes;
mod splitting;
mod stability;
mod stability_long_run;
mod stability_stiffness;
mod taylor;
mod workprecision;
