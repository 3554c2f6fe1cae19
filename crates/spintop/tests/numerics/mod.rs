//! The numerical methods and what is built on them: the integrators, the implicit method, the splittings, the stability suite, work against precision and the scenes.

mod cost;
mod implicit;
mod integrators;
mod refusals;
mod scenes;
mod splitting;
mod stability;
mod stability_long_run;
mod stability_stiffness;
mod taylor;
mod workprecision;
