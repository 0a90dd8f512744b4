//! One-step methods for the autonomous system `(y, v)' = f(y, v)`: classical RK4 at a fixed
//! step and the Dormand–Prince 5(4) pair with error control.

use nalgebra::Vector2;

/// State `(y, v)`: approach and approach rate (dimensionless inside the solver).
pub(crate) type State = Vector2<f64>;

/// Result of one attempted step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Attempt {
    /// State at the end of the step.
    pub state: State,
    /// Error norm: the step is acceptable when it is at most 1 (0 for fixed-step methods).
    pub error: f64,
    /// `f(state)` when the method computed it anyway (first-same-as-last), else `None`.
    pub end_derivative: Option<State>,
    /// Right-hand-side evaluations the attempt cost.
    pub rhs_evaluations: u64,
}

/// A one-step method together with its step-size policy.
pub(crate) trait Stepper {
    /// Attempt one step of size `h` from `y`, where `fy = f(y)` is already known; generic over
    /// the right-hand side so that a method inlines it into its stages.
    fn attempt<F: Fn(&State) -> State>(
        &mut self,
        rhs: &F,
        y: &State,
        fy: &State,
        h: f64,
    ) -> Attempt;
    /// The step to try first in a new phase.
    fn first_step(&self) -> f64;
    /// The step to try after an attempt of size `h` with error norm `error`.
    fn next_step(&self, h: f64, error: f64) -> f64;
    /// Tell a fixed-step method that the coming phase is `factor` times slower than the one
    /// its step was chosen for (adaptive methods find that out by themselves).
    fn set_phase_time_scale(&mut self, _factor: f64) {}
}

/// Classical fourth-order Runge–Kutta at a fixed step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rk4 {
    /// The step in the phase at hand.
    pub step: f64,
    /// The step chosen for the loading phase.
    pub base_step: f64,
}

impl Rk4 {
    /// RK4 at step `h`.
    pub(crate) fn new(h: f64) -> Self {
        Rk4 {
            step: h,
            base_step: h,
        }
    }
}

impl Stepper for Rk4 {
    #[inline]
    fn attempt<F: Fn(&State) -> State>(
        &mut self,
        rhs: &F,
        y: &State,
        fy: &State,
        h: f64,
    ) -> Attempt {
        Attempt {
            state: rk4_step(rhs, y, fy, h),
            error: 0.0,
            end_derivative: None,
            rhs_evaluations: 3,
        }
    }
    fn first_step(&self) -> f64 {
        self.step
    }
    fn next_step(&self, _h: f64, _error: f64) -> f64 {
        self.step
    }
    fn set_phase_time_scale(&mut self, factor: f64) {
        self.step = self.base_step * factor;
    }
}

/// One classical RK4 step (three new evaluations; `fy` is the first stage).
#[inline]
pub(crate) fn rk4_step<F: Fn(&State) -> State + ?Sized>(
    rhs: &F,
    y: &State,
    fy: &State,
    h: f64,
) -> State {
    let k1 = *fy;
    let k2 = rhs(&(y + 0.5 * h * k1));
    let k3 = rhs(&(y + 0.5 * h * k2));
    let k4 = rhs(&(y + h * k3));
    y + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
}

/// Dormand–Prince 5(4) with the standard step-size controller, advancing the fifth-order
/// solution.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dopri5 {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance, in the solver's dimensionless units.
    pub atol: f64,
}

impl Dopri5 {
    /// A controller at relative tolerance `rtol`; the absolute floor is far below the O(1)
    /// dimensionless scale so that small COR values keep their relative accuracy.
    pub(crate) fn new(rtol: f64) -> Self {
        Dopri5 {
            rtol,
            atol: rtol * 1e-6,
        }
    }
}

const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const B1: f64 = 35.0 / 384.0;
const B3: f64 = 500.0 / 1113.0;
const B4: f64 = 125.0 / 192.0;
const B5: f64 = -2187.0 / 6784.0;
const B6: f64 = 11.0 / 84.0;
// Differences between the fifth- and fourth-order weights.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;

impl Stepper for Dopri5 {
    #[inline]
    fn attempt<F: Fn(&State) -> State>(
        &mut self,
        rhs: &F,
        y: &State,
        fy: &State,
        h: f64,
    ) -> Attempt {
        let k1 = *fy;
        let k2 = rhs(&(y + h * (A21 * k1)));
        let k3 = rhs(&(y + h * (A31 * k1 + A32 * k2)));
        let k4 = rhs(&(y + h * (A41 * k1 + A42 * k2 + A43 * k3)));
        let k5 = rhs(&(y + h * (A51 * k1 + A52 * k2 + A53 * k3 + A54 * k4)));
        let k6 = rhs(&(y + h * (A61 * k1 + A62 * k2 + A63 * k3 + A64 * k4 + A65 * k5)));
        let next = y + h * (B1 * k1 + B3 * k3 + B4 * k4 + B5 * k5 + B6 * k6);
        let k7 = rhs(&next);
        let err = h * (E1 * k1 + E3 * k3 + E4 * k4 + E5 * k5 + E6 * k6 + E7 * k7);
        let mut norm = 0.0f64;
        for i in 0..2 {
            let scale = self.atol + self.rtol * y[i].abs().max(next[i].abs());
            norm = norm.max((err[i] / scale).abs());
        }
        Attempt {
            state: next,
            error: norm,
            end_derivative: Some(k7),
            rhs_evaluations: 6,
        }
    }
    fn first_step(&self) -> f64 {
        // About the step at which the local error of a smooth O(1) solution meets rtol.
        (0.1 * self.rtol.powf(0.2)).min(0.1)
    }
    #[inline]
    fn next_step(&self, h: f64, error: f64) -> f64 {
        let factor = if error == 0.0 {
            5.0
        } else {
            (0.9 * error.powf(-0.2)).clamp(0.2, 5.0)
        };
        h * factor
    }
}

/// One velocity-Verlet step (half kick, drift, half kick) of `y'' = accel(y)` for a force that
/// depends on the position only.
pub(crate) fn verlet_step(accel: &dyn Fn(f64) -> f64, s: &State, h: f64) -> State {
    let half = s[1] + 0.5 * h * accel(s[0]);
    let y = s[0] + h * half;
    State::new(y, half + 0.5 * h * accel(y))
}
