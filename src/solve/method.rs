//! The methods and what each one is: its order, how it steps, its knob, its stability limit
//! and the tolerance it is held to. Everything that differs between methods outside the
//! integration itself is read from a method's [`MethodDescriptor`], so that a new method is
//! its integrator plus one line in the registry below.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

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
}

/// RK4's stability region meets the imaginary axis at `ω Δt = 2√2`.
const RK4_LIMIT: f64 = 2.0 * std::f64::consts::SQRT_2;
/// Event-located and adaptive methods must meet this on every figure.
const ACCURATE: f64 = 1e-9;
/// What DEM practice asks of an impact's COR and peak.
const DEM_PRACTICE: f64 = 1e-3;

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
    },
    /// RK4 at a fixed step with the turning point and the contact end located and the
    /// integration restarted there; series start and end over the non-smooth `y^n`.
    Rk4Event => MethodDescriptor {
        name: "rk4-event",
        stepping: Stepping::Fixed { stability_limit: RK4_LIMIT, located_end: true },
        knob: Knob::StepsPerPeriod,
        order: Some(4),
        tolerance: ToleranceRule::Uniform(ACCURATE),
    },
    /// Dormand–Prince 5(4) with error control, the same event location and series treatment.
    Dopri5 => MethodDescriptor {
        name: "dopri5",
        stepping: Stepping::Adaptive,
        knob: Knob::Rtol,
        order: Some(5),
        tolerance: ToleranceRule::Uniform(ACCURATE),
    },
    /// Velocity Verlet at a fixed step, as DEM codes step (the damping sees the half-step
    /// velocity); contact end at the first step with `y < 0`.
    Verlet => MethodDescriptor {
        name: "verlet",
        stepping: Stepping::Fixed { stability_limit: 2.0, located_end: false },
        knob: Knob::StepsPerPeriod,
        order: Some(2),
        tolerance: ToleranceRule::OneStepEnd { figures: DEM_PRACTICE },
    },
    /// The closed forms.
    Exact => MethodDescriptor {
        name: "exact",
        stepping: Stepping::ClosedForm,
        knob: Knob::None,
        order: None,
        tolerance: ToleranceRule::Uniform(ACCURATE),
    },
}

impl Method {
    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        self.descriptor().name
    }

    /// The method called `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Method> {
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
    pub fn stability_limit(self) -> Option<f64> {
        match self.descriptor().stepping {
            Stepping::Fixed {
                stability_limit, ..
            } => Some(stability_limit),
            _ => None,
        }
    }

    /// Whether the method must be accurate everywhere (event-located or adaptive): the
    /// stability grid fails on any inaccuracy of such a method.
    pub fn held_accurate(self) -> bool {
        matches!(self.descriptor().tolerance, ToleranceRule::Uniform(_))
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl Serialize for Method {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Method {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        Method::from_name(&name).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "unknown method `{name}`; known: {}",
                Method::names().join(", ")
            ))
        })
    }
}

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
