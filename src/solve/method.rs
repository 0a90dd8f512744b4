//! The methods and what each one is: its order, how it steps, its knob, its stability limit
//! and the tolerance it is held to. Everything that differs between methods outside the
//! integration itself is read from a method's [`MethodDescriptor`], so that a new method is
//! its integrator plus one line in the registry below.

use serde::Serialize;

/// How a method steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stepping {
    /// A fixed step `T/N`, or one given in seconds; explicit, so stable only below
    /// `ω Δt = stability_limit`. `located_end`: the turning point and contact end are located
    /// on the step (otherwise the contact ends at the first step past zero).
    Fixed {
        /// The method's limit on `ω Δt` on an undamped oscillator.
        stability_limit: f64,
        /// Whether events are located on the step.
        located_end: bool,
    },
    /// An error-controlled step.
    Adaptive,
    /// No steps: the closed forms.
    ClosedForm,
}

/// The accuracy knob of a method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Knob {
    /// Steps per undamped period (`--steps-per-period`).
    StepsPerPeriod,
    /// Relative tolerance (`--rtol`).
    Rtol,
    /// None (the closed forms).
    None,
}

/// The agreement a method is held to against the closed forms, relative.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ToleranceRule {
    /// Every figure within this relative error.
    Uniform(f64),
    /// COR and peak within `figures`; the contact time within one step (the contact ends at
    /// the first step past zero, so it cannot be placed closer).
    OneStepEnd {
        /// On the COR and the peak deformation.
        figures: f64,
    },
}

/// What a method is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MethodDescriptor {
    /// The name on the command line and in reports.
    pub name: &'static str,
    /// How it steps.
    pub stepping: Stepping,
    /// Its accuracy knob.
    pub knob: Knob,
    /// The formal order of its step (`None` for the closed forms).
    pub order: Option<u32>,
    /// The tolerance `verify` and `stability` hold it to.
    pub tolerance: ToleranceRule,
    /// Its measured COR error against its knob, where it is known well enough to choose a
    /// resolution from a COR tolerance (`None`: the method is never chosen that way).
    pub cor_error_bound: Option<CorErrorBound>,
}

/// A measured bound on a method's relative COR error as a function of its knob:
/// `|COR error| <= Σ constant × s^order` with `s = 1/N` (N steps per undamped period) or
/// `s = rtol`, over every loss coefficient in [0, 1) and both exponents of the scenes (1: the
/// rod, 1.5: the balls). In the dimensionless form of the solver an impact depends on the
/// exponent and η alone, so the bound holds for every case of a scene.
///
/// Measured by `cargo run --release --example cor_error_bounds` (the largest error over 1001
/// loss coefficients on [0, 0.9999] at each resolution, both exponents), and checked by
/// the unit tests of `analysis::precision::choice` on a grid of resolutions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CorErrorBound {
    /// The bound's terms `(constant, order)`.
    pub terms: &'static [(f64, f64)],
    /// The range of the knob the bound was measured over: steps per period from `coarsest`
    /// to `finest`, or rtol from `coarsest` down to `finest`.
    pub coarsest: f64,
    /// See `coarsest`.
    pub finest: f64,
    /// The time of one right-hand-side evaluation (with the stepping around it) relative to
    /// rk4-event's on one chain, measured by `MILLIMPACT_BENCH_REPORT=1 cargo bench --bench
    /// impact`: what a step of the method costs beside its count.
    pub evaluation_cost: f64,
}

impl CorErrorBound {
    /// The bound at knob value `value` (steps per period, or rtol).
    pub fn at(&self, knob: Knob, value: f64) -> f64 {
        let s = match knob {
            Knob::StepsPerPeriod => 1.0 / value,
            _ => value,
        };
        self.terms.iter().map(|&(c, p)| c * s.powf(p)).sum()
    }
}

/// RK4's stability region meets the imaginary axis at `ω Δt = 2√2`.
const RK4_LIMIT: f64 = 2.0 * std::f64::consts::SQRT_2;
/// Event-located and adaptive methods must meet this on every figure.
const ACCURATE: f64 = 1e-9;
/// What DEM practice asks of an impact's COR and peak.
const DEM_PRACTICE: f64 = 1e-3;

/// rk4-event: order 5 (the COR is fixed by the energy, whose error is O(h⁵) over a phase) with
/// an order-4 term of small constant (the contact time's order, through the located events)
/// that the balls' exponent shows from about 500 steps per period. Measured largest errors:
/// 2.0e-10 at 400 steps per period, 9.99e-11 at 458, 2.4e-12 at 1000, 1.7e-14 at 3000; the
/// bound's constants are the smallest of this form above every measured point from 32 to 3000
/// steps per period, rounded up; beyond 3000 the error is rounding (about 5e-15).
const RK4_EVENT_COR: CorErrorBound = CorErrorBound {
    terms: &[(1.85e3, 5.0), (0.9, 4.0)],
    coarsest: 32.0,
    finest: 3000.0,
    evaluation_cost: 1.0,
};

/// dopri5: the COR error follows the tolerance, 0.23 to 0.27 of it from rtol 1e-6 to 1e-13;
/// a step costs six evaluations and the controller's arithmetic: 2.1 times rk4-event's time per
/// evaluation on one chain (`MILLIMPACT_BENCH_REPORT=1 cargo bench --bench impact`, ball_plate:
/// 16.9 µs for 560 evaluations at rtol 1e-10 against 7.3 µs for 500 at 400 steps per period;
/// rk4-event in lanes is cheaper still, so the weight is a lower bound).
const DOPRI5_COR: CorErrorBound = CorErrorBound {
    terms: &[(0.28, 1.0)],
    coarsest: 1e-6,
    finest: 1e-13,
    evaluation_cost: 2.1,
};

/// The registry of methods: one line per method, `Variant => descriptor`. It declares the
/// [`Method`] variant, its place in [`Method::ALL`] and its descriptor.
macro_rules! method_registry {
    ($($(#[$doc:meta])* $variant:ident => $descriptor:expr),+ $(,)?) => {
        /// The integration methods, as named on the command line and in reports.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Method {
            $($(#[$doc])* $variant,)+
        }

        impl Method {
            /// Every method, in report order.
            pub const ALL: &'static [Method] = &[$(Method::$variant),+];

            /// What the method is.
            pub fn descriptor(self) -> &'static MethodDescriptor {
                match self {
                    $(Method::$variant => &$descriptor,)+
                }
            }
        }
    };
}

method_registry! {
    /// The paper's method: classical RK4 at a fixed step `T/N`, contact end at the first step
    /// with `y < 0`, no event location.
    Rk4 => MethodDescriptor {
        name: "rk4",
        stepping: Stepping::Fixed { stability_limit: RK4_LIMIT, located_end: false },
        knob: Knob::StepsPerPeriod,
        order: Some(4),
        tolerance: ToleranceRule::OneStepEnd { figures: DEM_PRACTICE },
        cor_error_bound: None,
    },
    /// RK4 at a fixed step with the turning point and the contact end located and the
    /// integration restarted there; series start and end over the non-smooth `y^n`.
    Rk4Event => MethodDescriptor {
        name: "rk4-event",
        stepping: Stepping::Fixed { stability_limit: RK4_LIMIT, located_end: true },
        knob: Knob::StepsPerPeriod,
        order: Some(4),
        tolerance: ToleranceRule::Uniform(ACCURATE),
        cor_error_bound: Some(RK4_EVENT_COR),
    },
    /// Dormand–Prince 5(4) with error control, the same event location and series treatment.
    Dopri5 => MethodDescriptor {
        name: "dopri5",
        stepping: Stepping::Adaptive,
        knob: Knob::Rtol,
        order: Some(5),
        tolerance: ToleranceRule::Uniform(ACCURATE),
        cor_error_bound: Some(DOPRI5_COR),
    },
    /// Velocity Verlet at a fixed step, as DEM codes step (the damping sees the half-step
    /// velocity); contact end at the first step with `y < 0`.
    Verlet => MethodDescriptor {
        name: "verlet",
        stepping: Stepping::Fixed { stability_limit: 2.0, located_end: false },
        knob: Knob::StepsPerPeriod,
        order: Some(2),
        tolerance: ToleranceRule::OneStepEnd { figures: DEM_PRACTICE },
        cor_error_bound: None,
    },
    /// The closed forms.
    Exact => MethodDescriptor {
        name: "exact",
        stepping: Stepping::ClosedForm,
        knob: Knob::None,
        order: None,
        tolerance: ToleranceRule::Uniform(ACCURATE),
        cor_error_bound: None,
    },
}

impl Method {
    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        self.descriptor().name
    }

    /// The method called `name`, if there is one.
    pub(crate) fn from_name(name: &str) -> Option<Method> {
        Method::ALL.iter().copied().find(|m| m.name() == name)
    }

    /// Every method's name, in report order.
    pub fn names() -> Vec<&'static str> {
        Method::ALL.iter().map(|m| m.name()).collect()
    }

    /// Whether the method steps at a fixed step set by steps per period.
    pub fn is_fixed_step(self) -> bool {
        matches!(self.descriptor().stepping, Stepping::Fixed { .. })
    }

    /// Whether the method integrates (every method but the closed forms).
    pub fn integrates(self) -> bool {
        self.descriptor().stepping != Stepping::ClosedForm
    }

    /// The stability limit on `ω Δt` of a fixed-step method.
    pub(crate) fn stability_limit(self) -> Option<f64> {
        match self.descriptor().stepping {
            Stepping::Fixed {
                stability_limit, ..
            } => Some(stability_limit),
            _ => None,
        }
    }

    /// Whether the method must be accurate everywhere (event-located or adaptive): the
    /// stability grid fails on any inaccuracy of such a method.
    pub(crate) fn held_accurate(self) -> bool {
        matches!(self.descriptor().tolerance, ToleranceRule::Uniform(_))
    }
}

/// `Display`, `Serialize` and `Deserialize` of a registry's entry (a method, a code) by its
/// `name()`: read back by `from_name`, an unknown name refused with every one of `names()`
/// (`$what` says what it names).
macro_rules! by_name {
    ($type:ty, $what:literal) => {
        impl std::fmt::Display for $type {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl serde::Serialize for $type {
            fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                serializer.serialize_str(self.name())
            }
        }

        impl<'de> serde::Deserialize<'de> for $type {
            fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                let name = <String as serde::Deserialize>::deserialize(deserializer)?;
                <$type>::from_name(&name).ok_or_else(|| {
                    serde::de::Error::custom(format!(
                        concat!("unknown ", $what, " `{}`; known: {}"),
                        name,
                        <$type>::names().join(", ")
                    ))
                })
            }
        }
    };
}

pub(crate) use by_name;

by_name!(Method, "method");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_lists_every_method_once_by_its_own_name() {
        assert_eq!(
            Method::names(),
            ["rk4", "rk4-event", "dopri5", "verlet", "exact"]
        );
        for &method in Method::ALL {
            assert_eq!(Method::from_name(method.name()), Some(method));
        }
    }

    #[test]
    fn stability_limits_are_where_the_regions_meet_the_imaginary_axis() {
        // RK4: |R(iz)|² = 1 − z⁶/72 + z⁸/576 = 1 at z² = 8.
        let z = Method::Rk4.stability_limit().unwrap();
        assert!((1.0 - z.powi(6) / 72.0 + z.powi(8) / 576.0 - 1.0).abs() < 1e-12);
        // Verlet: the leap-frog map of an oscillator is bounded for z ≤ 2.
        assert_eq!(Method::Verlet.stability_limit(), Some(2.0));
        assert_eq!(Method::Dopri5.stability_limit(), None);
    }
}
