//! Power series of a power-law contact near zero approach.
//!
//! `y'' = -k y^n` with `y(0) = 0`, `y'(0) = v > 0` has the solution
//! `y(s) = v s C(w)`, `y'(s) = v D(w)`, `w = -k v^(n-1) s^(n+1)`, with `C(w) = Σ c_j w^j`,
//! `D(w) = Σ c_j (j(n+1)+1) w^j`. It is what a one-step method cannot resolve: `y^n` is not
//! smooth at `y = 0` for non-integer `n`, so RK4 across the first or last step of a Hertz
//! contact loses its order. The series is used over the first step of a phase that starts at
//! `y = 0` and, backwards in time, over the last step of a phase that ends there.

use std::cell::RefCell;

/// Terms kept; with `|w| <= MAX_W` the truncation is far below rounding.
const TERMS: usize = 14;
/// Largest `|w|` at which the series is used.
pub(crate) const MAX_W: f64 = 0.2;

/// The coefficients `c_j` for exponent `n`.
#[derive(Clone, Debug)]
pub(crate) struct ContactSeries {
    n: f64,
    c: [f64; TERMS],
    /// Those of `P(w) = C(w)^n` (the last is not needed and left 0).
    p: [f64; TERMS],
}

impl ContactSeries {
    /// Coefficients from `c_{j+1} = p_j / (((j+1)(n+1)+1)(j+1)(n+1))`, where `p_j` are those of
    /// `C(w)^n` (J. C. P. Miller's recurrence for a power of a series).
    pub(crate) fn new(n: f64) -> Self {
        let mut c = [0.0; TERMS];
        let mut p = [0.0; TERMS];
        c[0] = 1.0;
        p[0] = 1.0;
        for j in 0..TERMS - 1 {
            if j > 0 {
                let mut sum = 0.0;
                for i in 1..=j {
                    sum += ((n + 1.0) * i as f64 - j as f64) * c[i] * p[j - i];
                }
                p[j] = sum / j as f64;
            }
            let q = (j + 1) as f64 * (n + 1.0);
            c[j + 1] = p[j] / ((q + 1.0) * q);
        }
        ContactSeries { n, c, p }
    }

    /// [`ContactSeries::new`], remembered per thread for the last exponent asked for: a sweep
    /// or a benchmark would otherwise build the same coefficients for every impact.
    pub(crate) fn for_exponent(n: f64) -> Self {
        thread_local! {
            static LAST: RefCell<Option<ContactSeries>> = const { RefCell::new(None) };
        }
        LAST.with_borrow_mut(|last| match last {
            Some(series) if series.n.to_bits() == n.to_bits() => series.clone(),
            _ => last.insert(ContactSeries::new(n)).clone(),
        })
    }

    fn sums(&self, w: f64) -> (f64, f64) {
        let (mut big_c, mut big_d, mut power) = (0.0, 0.0, 1.0);
        for (j, cj) in self.c.iter().enumerate() {
            big_c += cj * power;
            big_d += cj * (j as f64 * (self.n + 1.0) + 1.0) * power;
            power *= w;
        }
        (big_c, big_d)
    }

    /// `w` for speed `v`, time `s` and stiffness factor `k`.
    pub(crate) fn argument(&self, k: f64, v: f64, s: f64) -> f64 {
        -k * v.powf(self.n - 1.0) * s.powf(self.n + 1.0)
    }

    /// Whether a state `(y, rate)`, `rate < 0`, of `y'' = -k y^n` is within the series' reach
    /// of the contact end: `|w| <= MAX_W` for `w` = [`ContactSeries::argument`] at speed
    /// `-rate` and time `y / -rate`, the test [`ContactSeries::time_to_exit`] starts from.
    ///
    /// `accel` is the acceleration the integrator already has at the state, `-k y^n` to
    /// rounding. It gives the same `|w| = k y^(n+1) / rate²` to a few rounding errors without a
    /// power, which settles every state clearly beyond the reach (all of a phase but its last
    /// steps) or clearly within it; the powers decide the states within 1e-6 of the edge, so
    /// the answer is always theirs. The shortcut is taken only where neither form can overflow
    /// or underflow.
    pub(crate) fn within_reach_of_end(&self, k: f64, y: f64, rate: f64, accel: f64) -> bool {
        let v = -rate;
        let moderate = |x: f64| (1e-30..=1e30).contains(&x);
        let shortcut = (0.0..=3.0).contains(&self.n) && moderate(k) && moderate(y) && moderate(v);
        if shortcut {
            let w = -accel * y / (v * v);
            if w > MAX_W * (1.0 + 1e-6) && w <= 1e30 {
                return false;
            }
        }
        self.near_or_within_reach(k, y, v, accel, shortcut)
    }

    /// The rest of [`ContactSeries::within_reach_of_end`], met once or twice a phase: clearly
    /// within the reach by the acceleration, else `|w| <= MAX_W` by the powers. Kept out of
    /// line: the optimiser may otherwise evaluate the powers on every step, before the
    /// shortcut has been tested.
    #[cold]
    #[inline(never)]
    fn near_or_within_reach(&self, k: f64, y: f64, v: f64, accel: f64, shortcut: bool) -> bool {
        if shortcut && (0.0..MAX_W * (1.0 - 1e-6)).contains(&(-accel * y / (v * v))) {
            return true;
        }
        self.argument(k, v, y / v).abs() <= MAX_W
    }

    /// The longest time from contact at speed `v` over which the series may be used.
    pub(crate) fn reach(&self, k: f64, v: f64) -> f64 {
        (MAX_W / (k * v.powf(self.n - 1.0))).powf(1.0 / (self.n + 1.0))
    }

    /// `(y, y')` a time `s` after contact starts at speed `v` under `y'' = -k y^n`.
    pub(crate) fn advance(&self, k: f64, v: f64, s: f64) -> (f64, f64) {
        let (big_c, big_d) = self.sums(self.argument(k, v, s));
        (v * s * big_c, v * big_d)
    }

    /// From a state `(y > 0, y' < 0)` approaching contact end under `y'' = -k y^n`, the time
    /// left until `y = 0` and the speed there, `(s, v)`; `None` if the state is too far from
    /// the end for the series.
    ///
    /// Out of line: inlined into an integrator's loop, its powers may be hoisted above the test
    /// that decides whether it is called at all, and paid on every step.
    #[inline(never)]
    pub(crate) fn time_to_exit(&self, k: f64, y: f64, rate: f64) -> Option<(f64, f64)> {
        if y <= 0.0 {
            return Some((0.0, -rate));
        }
        if rate >= 0.0 {
            return None;
        }
        // With v = r / D(w) and s = y / (v C(w)) (r = -rate), w = -k v^(n-1) s^(n+1) becomes
        // one equation in w alone, G(w) = w C(w)^(n+1) + q D(w)^2 = 0, q = k y^(n+1) / r^2,
        // whose series C^(n+1) = C P needs no power. Newton's method from w = -q (the answer
        // to first order) converges quadratically: once a step is below 1e-9 of w, the error
        // left is below 1e-18 of it, and further steps would only chase rounding.
        let r = -rate;
        let q = -self.argument(k, r, y / r);
        let mut w = -q;
        for _ in 0..50 {
            if w.abs() > MAX_W || !w.is_finite() {
                return None;
            }
            let ([c, dc], [d, dd], [p, dp]) = self.sums_with_slopes(w);
            let g = w * c * p + q * d * d;
            let slope = c * p + w * (dc * p + c * dp) + 2.0 * q * d * dd;
            let step = g / slope;
            w -= step;
            if step.abs() <= 1e-9 * w.abs() {
                break;
            }
        }
        if w.abs() > MAX_W || !w.is_finite() {
            return None;
        }
        let (big_c, big_d) = self.sums(w);
        let v = r / big_d;
        Some((y / (v * big_c), v))
    }

    /// `C`, `D` and `P` at `w`, each with its derivative in `w` (Horner's scheme).
    fn sums_with_slopes(&self, w: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
        let (mut c, mut d, mut p) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        for j in (0..TERMS).rev() {
            let dj = self.c[j] * (j as f64 * (self.n + 1.0) + 1.0);
            for (sum, coefficient) in [(&mut c, self.c[j]), (&mut d, dj), (&mut p, self.p[j])] {
                sum[1] = sum[1] * w + sum[0];
                sum[0] = sum[0] * w + coefficient;
            }
        }
        (c, d, p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_series_is_the_sine() {
        let series = ContactSeries::new(1.0);
        let (k, v, s) = (2.0f64, 0.7, 0.3);
        let (y, rate) = series.advance(k, v, s);
        let omega = k.sqrt();
        approx::assert_relative_eq!(y, v * (omega * s).sin() / omega, max_relative = 1e-15);
        approx::assert_relative_eq!(rate, v * (omega * s).cos(), max_relative = 1e-15);
    }

    #[test]
    fn exit_inverts_advance() {
        let series = ContactSeries::new(1.5);
        let (k, v, s) = (1.25, 0.8, 0.05);
        let (y, rate) = series.advance(k, v, s);
        let (s_found, v_found) = series.time_to_exit(k, y, -rate).unwrap();
        approx::assert_relative_eq!(s_found, s, max_relative = 1e-14);
        approx::assert_relative_eq!(v_found, v, max_relative = 1e-14);
    }

    /// Over most of the reach (beyond 0.8 of it the first guess |w| = k y^(n+1) / rate^2
    /// exceeds the reach and `time_to_exit` declines), for linear, Hertz and a stiffer
    /// exponent, across stiffness and speed: the exit found from a state the series advanced
    /// to is that state's time and speed, to rounding.
    #[test]
    fn exit_inverts_advance_over_the_reach() {
        for n in [1.0, 1.5, 2.5] {
            let series = ContactSeries::new(n);
            for k in [0.01, 0.3, 1.25, 1e3] {
                for v in [1e-3, 0.7, 30.0] {
                    let reach = series.reach(k, v);
                    for i in 1..=40 {
                        let s = reach * i as f64 / 50.0;
                        let (y, rate) = series.advance(k, v, s);
                        let (s_found, v_found) = series.time_to_exit(k, y, -rate).unwrap();
                        approx::assert_relative_eq!(s_found, s, max_relative = 1e-15);
                        approx::assert_relative_eq!(v_found, v, max_relative = 1e-15);
                    }
                }
            }
        }
    }
}
