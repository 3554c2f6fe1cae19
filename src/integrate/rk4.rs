//! PLACEHOLDER: being written (see src/integrate.rs for the contract).
use crate::integrate::{IntegrateError, Rhs, Stats, Stepper};
use crate::math::{Real, State};

/// Placeholder.
#[derive(Clone, Debug)]
pub struct Rk4<const N: usize> {
    t: Real,
    y: State<N>,
}

impl<const N: usize> Rk4<N> {
    /// Placeholder.
    pub fn new(t0: Real, y0: State<N>, _h: Real) -> Result<Self, IntegrateError> {
        Ok(Self { t: t0, y: y0 })
    }
}

impl<const N: usize> Stepper<N> for Rk4<N> {
    fn t(&self) -> Real {
        self.t
    }
    fn y(&self) -> &State<N> {
        &self.y
    }
    fn t_prev(&self) -> Real {
        self.t
    }
    fn last_step(&self) -> Real {
        0.0
    }
    fn stats(&self) -> Stats {
        Stats::default()
    }
    fn step<R: Rhs<N>>(&mut self, _rhs: &R, _t_stop: Real) -> Result<(), IntegrateError> {
        todo!()
    }
    fn dense<R: Rhs<N>>(&mut self, _rhs: &R, _t: Real) -> State<N> {
        todo!()
    }
    fn reset(&mut self, y: State<N>) {
        self.y = y;
    }
}
