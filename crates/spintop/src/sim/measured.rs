//! The lighter models' errors measured against the physical solution of
//! (3.4), for the symmetric top.
//!
//! In the frame that turns with the free precession the physical solution
//! costs a few thousand steps ([`crate::sim::physical::slow`]), so `auto`
//! does not have to estimate how far the truncated and the reduced models
//! stray from it: it measures it. Ω of all three over a grid of the run
//! (the scene's times, 1,024 even steps and 512 geometric ones from 10⁻⁸T,
//! and at least eight per turn of the body); the orientations of all three
//! from the same start over the same grid where the body turns at most
//! [`DIRECT_TURN`] radians. The largest distance, with a margin for what
//! falls between the grid's points, is the estimate: the truth to the
//! physical solution's own accuracy (it is computed at rtol 1e-12).
//!
//! The leading-order estimates of [`crate::sim::accuracy`] remain for runs
//! longer than that and for every other top.

use super::accuracy::ModelErrors;
use super::cost::MAX_STEPS;
use super::method::{Method, MethodOptions};
use super::model::Model;
use super::physical;
use super::simulation::Simulation;
use super::state::InitialState;
use crate::math::{Mat3, Real, Vec3};
use crate::physics::symmetric_top::{
    SymmetricTop, reduced_closed_form, truncated_closed_form, truncated_orientation,
};

/// Orientations are measured where the body turns at most this much over
/// the run (each is then at most a few times this many steps).
pub const DIRECT_TURN: Real = 2e4;

/// The tolerance of the measuring runs.
const MEASURE_RTOL: Real = 1e-12;

/// The margin for a largest distance that falls between grid points.
const MARGIN: Real = 1.25;

/// What the measuring runs' own errors may add (relative, and radians).
const FLOOR: Real = 1e-12;

/// The grid the models are compared on: `times`, even steps, geometric
/// steps, and at least eight per turn (the body turning at `rate`).
fn grid(times: &[Real], t_last: Real, rate: Real) -> Vec<Real> {
    let turns = (rate * t_last / (2.0 * std::f64::consts::PI as Real)).min(1e5);
    let even = (1024.0 as Real).max(8.0 * turns) as usize;
    let mut g: Vec<Real> = times.to_vec();
    g.extend((0..=even).map(|j| t_last * j as Real / even as Real));
    g.extend((0..=512).map(|j| t_last * (1e-8 as Real).powf(1.0 - j as Real / 512.0)));
    g.retain(|t| t.is_finite() && *t >= 0.0 && *t <= t_last);
    g.sort_by(Real::total_cmp);
    g.dedup();
    g
}

/// The angle of the rotation between two orientations.
fn angle(a: &Mat3, b: &Mat3) -> Real {
    let r = a.transpose() * b;
    let skew = (r[(2, 1)] - r[(1, 2)])
        .hypot(r[(0, 2)] - r[(2, 0)])
        .hypot(r[(1, 0)] - r[(0, 1)]);
    (0.5 * skew).atan2(0.5 * (r.trace() - 1.0))
}

/// The truncated and the reduced models' largest angles from the physical
/// solution of (3.4) over the grid `g`, all from O(0) = 1; `None` where a
/// run cannot be made.
fn orientations(
    top: &SymmetricTop,
    omega0: &Vec3,
    options: &MethodOptions,
    g: &[Real],
) -> Option<(Real, Real)> {
    let t_last = g.last().copied().unwrap_or(0.0);
    let initial = InitialState {
        omega: *omega0,
        rotation: Mat3::identity(),
    };
    let run = |model: Model, method: Method| {
        Simulation::with_method(model, method, *options, initial, Some(t_last)).ok()
    };
    let mut full = run(Model::Full(*top), Method::Physical)?;
    let mut reduced = run(Model::Reduced(*top), Method::ClosedFormDop853)?;
    let (mut ot, mut or) = (0.0 as Real, 0.0 as Real);
    for &t in g {
        let p = full.advance_to(t).ok()?.rotation_matrix();
        let r = reduced.advance_to(t).ok()?.rotation_matrix();
        let o_t = truncated_orientation(top, omega0, &Mat3::identity(), t);
        ot = ot.max(angle(&o_t, &p));
        or = or.max(angle(&r, &p));
    }
    Some((ot, or))
}

/// The truncated and the reduced models' largest distances from the
/// physical solution of (3.4) over `times`' run, measured, and whether the
/// orientations were: only where the body turns at most [`DIRECT_TURN`]
/// (else they are left at π, for the caller to estimate). `None` when the
/// physical solution cannot be computed within the step budget.
pub fn symmetric_measured(
    top: &SymmetricTop,
    omega0: &Vec3,
    times: &[Real],
) -> Option<(ModelErrors, bool)> {
    let t_last = times.last().copied().unwrap_or(0.0);
    let options = MethodOptions::default().with_rtol(MEASURE_RTOL).ok()?;
    let table = physical::physical_table(top, omega0, t_last, &options, MAX_STEPS as u64).ok()?;
    let scale = omega0.norm();
    let rate = scale;
    let g = grid(times, t_last, rate);
    let (mut dt, mut dr) = (0.0 as Real, 0.0 as Real);
    for &t in &g {
        let w = table.omega_at(t);
        dt = dt.max((truncated_closed_form(top, omega0, t) - w).norm());
        dr = dr.max((reduced_closed_form(top, omega0, t) - w).norm());
    }
    let pi = std::f64::consts::PI as Real;
    // NOTE: where the orientations cannot be measured (a run refused or
    // failed), Ω's measurement stands and the caller estimates them.
    let turned = (rate * t_last <= DIRECT_TURN)
        .then(|| orientations(top, omega0, &options, &g))
        .flatten();
    let oriented = turned.is_some();
    let (ot, or) = turned.unwrap_or((pi, pi));
    let e = |d: Real| (MARGIN * d / scale + FLOOR).min(2.0);
    let o = |d: Real| (MARGIN * d + FLOOR).min(pi);
    let errors = ModelErrors {
        truncated: e(dt),
        reduced: e(dr),
        truncated_orientation: o(ot),
        reduced_orientation: o(or),
        exact: false,
    };
    Some((errors, oriented))
}
