//! Closed forms of the paper's impact (physics.md §3) and of the elastic Hertz impact.

use serde::{Deserialize, Serialize};

use crate::model::figures::{Elastic, Exact, Quantity};
use crate::model::law::PaperLaw;
use crate::model::trajectory::TrajectoryMetrics;

/// `J(n) = ∫0^1 (1 - u^(n+1))^(-1/2) du = sqrt(π) Γ(1 + 1/(n+1)) / Γ(1/2 + 1/(n+1))`:
/// a quarter period of the undamped oscillation in units of `y_max / v0`. Remembered per
/// thread for the last exponent asked for: every impact of a sweep asks for it, and the two
/// gamma functions cost more than the rest of the closed forms.
pub fn j_integral(n: f64) -> f64 {
    thread_local! {
        static LAST: std::cell::Cell<Option<(u64, f64)>> = const { std::cell::Cell::new(None) };
    }
    LAST.with(|last| match last.get() {
        Some((bits, j)) if bits == n.to_bits() => j,
        _ => {
            let p = 1.0 / (n + 1.0);
            let j = std::f64::consts::PI.sqrt() * libm::tgamma(1.0 + p) / libm::tgamma(0.5 + p);
            last.set(Some((n.to_bits(), j)));
            j
        }
    })
}

/// The COR of the paper's law: `e = sqrt((1 - η)/(1 + η))`, whatever `n`, `M`, `C` and `v0`.
pub fn restitution(loss_coefficient: f64) -> f64 {
    ((1.0 - loss_coefficient) / (1.0 + loss_coefficient)).sqrt()
}

/// The loss coefficient that gives COR `e`: `η = (1 - e²)/(1 + e²)`.
pub fn loss_coefficient(restitution: f64) -> f64 {
    let e2 = restitution * restitution;
    (1.0 - e2) / (1.0 + e2)
}

/// The figures of one impact, SI units: the closed form's set of figures ([`Exact`]: COR, peak
/// deformation, peak force, contact, compression and restitution times), and the kinetic
/// energy it absorbed.
///
/// The absorbed energy sits beside the set rather than in it: it is no figure of the
/// trajectory a code writes, and it cannot be had from the other figures without the mass
/// and the approach speed. It reads as the set does (`f.cor`, `f.iter()`, through
/// [`Deref`](std::ops::Deref)), and is written as one flat object, the set's keys then
/// `absorbed_energy`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImpactFigures {
    /// The impact's figures.
    #[serde(flatten)]
    pub figures: Exact,
    /// Kinetic energy lost, J.
    pub absorbed_energy: f64,
}

impl std::ops::Deref for ImpactFigures {
    type Target = Exact;

    fn deref(&self) -> &Exact {
        &self.figures
    }
}

impl ImpactFigures {
    /// The figures in the form a trajectory's are read: the paper's force is repulsive all
    /// through the contact, so its force contact time is its overlap contact time.
    pub(crate) fn metrics(&self) -> TrajectoryMetrics {
        TrajectoryMetrics::from_fn(|q| match q {
            Quantity::ForceContactTime => self.contact_time,
            q => *self.get(q),
        })
    }
}

/// The exact impact of the paper's law at approach speed `v0` (m/s).
///
/// For a linear spring (n = 1) the figures are those of a half oscillation, loading at
/// ω = sqrt(C (1+η) / M) and unloading at sqrt(C (1-η) / M):
///
/// ```
/// use millimpact::model::law::PaperLaw;
/// use millimpact::paper_impact;
///
/// let law = PaperLaw { mass: 2.0, stiffness: 8.0, exponent: 1.0, loss_coefficient: 0.28 };
/// let f = paper_impact(&law, 3.0);
/// let (w_in, w_out) = ((8.0f64 * 1.28 / 2.0).sqrt(), (8.0f64 * 0.72 / 2.0).sqrt());
/// let pi = std::f64::consts::PI;
/// assert!((f.cor - (0.72f64 / 1.28).sqrt()).abs() < 1e-15);
/// assert!((f.peak_deformation - 3.0 / w_in).abs() < 1e-14);
/// assert!((f.contact_time - (pi / (2.0 * w_in) + pi / (2.0 * w_out))).abs() < 1e-14);
/// ```
pub fn paper_impact(law: &PaperLaw, impact_velocity: f64) -> ImpactFigures {
    let (n, eta, v0) = (law.exponent, law.loss_coefficient, impact_velocity);
    let e = restitution(eta);
    let peak = ((n + 1.0) * law.mass * v0 * v0 / (2.0 * law.stiffness * (1.0 + eta)))
        .powf(1.0 / (n + 1.0));
    let j = j_integral(n);
    let compression_time = j * peak / v0;
    let restitution_time = compression_time / e;
    ImpactFigures {
        figures: Exact {
            cor: e,
            peak_deformation: peak,
            peak_force: law.stiffness * (1.0 + eta) * peak.powf(n),
            contact_time: compression_time + restitution_time,
            compression_time,
            restitution_time,
            ..Exact::default()
        },
        absorbed_energy: 0.5 * law.mass * v0 * v0 * (1.0 - e * e),
    }
}

/// The elastic Hertz impact of physics.md §3 for reduced mass `M` (kg), `E*` (Pa), `R*` (m)
/// and speed `v0` (m/s): its peak deformation `δ_max = (15 M v0² / (16 E* sqrt(R*)))^(2/5)`
/// (m) and contact time `t_c = 2 J(1.5) δ_max / v0` (s).
pub fn hertz_elastic(
    mass: f64,
    effective_modulus: f64,
    effective_radius: f64,
    impact_velocity: f64,
) -> Elastic {
    let v0 = impact_velocity;
    let peak =
        (15.0 * mass * v0 * v0 / (16.0 * effective_modulus * effective_radius.sqrt())).powf(0.4);
    Elastic {
        peak_deformation: peak,
        contact_time: 2.0 * j_integral(1.5) * peak / v0,
        ..Elastic::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn j_integral_known_values() {
        assert_relative_eq!(
            j_integral(1.0),
            std::f64::consts::FRAC_PI_2,
            max_relative = 1e-15
        );
        assert_relative_eq!(j_integral(1.5), 1.4716376, max_relative = 1e-7);
    }

    #[test]
    fn impact_figures_write_one_flat_object_and_read_it_back() {
        let law = PaperLaw {
            mass: 2.0,
            stiffness: 8.0,
            exponent: 1.5,
            loss_coefficient: 0.35,
        };
        let f = paper_impact(&law, 3.0);
        let json = serde_json::to_value(f).unwrap();
        let keys: Vec<&str> = json
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        assert_eq!(
            keys,
            [
                "absorbed_energy",
                "compression_time",
                "contact_time",
                "cor",
                "peak_deformation",
                "peak_force",
                "restitution_time"
            ]
        );
        let back: ImpactFigures = serde_json::from_value(json).unwrap();
        assert_eq!(back, f);
        // The paper's force is repulsive until the overlap closes: one contact time.
        let m = f.metrics();
        assert_eq!(m.force_contact_time.to_bits(), f.contact_time.to_bits());
        assert_eq!(m.compression_time.to_bits(), f.compression_time.to_bits());
    }

    #[test]
    fn restitution_and_loss_are_inverse() {
        for eta in [0.0, 0.01, 0.35, 0.7, 0.99] {
            assert_relative_eq!(loss_coefficient(restitution(eta)), eta, epsilon = 1e-15);
        }
    }
}
