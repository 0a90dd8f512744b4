//! One type for the figures of an impact: [`Figures`] holds one value per quantity (COR, peak
//! deformation, peak force, the two contact times, the compression and restitution times), of
//! any type: the figure itself, an error, a tolerance, a range, a value that may be missing.
//!
//! Which quantities a set carries is part of its type (the const parameter `Q`, a union of the
//! [`quantity`] bits), so a tolerance has the three checked quantities and no peak force, and
//! an output writes exactly its quantities. A set serialises as a map from the quantity's name
//! to its value, in the order of [`Quantity::ALL`]; flattened into a record
//! (`#[serde(flatten)]`) it gives the record's columns, and [`Figures::suffixed`] names them
//! `cor_vs_paper`, `peak_deformation_vs_paper`, ….
//!
//! ```
//! use millimpact::model::figures::{Checked, Figures, Quantity};
//!
//! let tolerance = Checked { cor: 1e-3, peak_deformation: 2e-3, contact_time: 5e-3, ..Default::default() };
//! let quantities: Vec<&str> = tolerance.iter().map(|(q, _)| q.name()).collect();
//! assert_eq!(quantities, ["cor", "peak_deformation", "contact_time"]);
//! assert_eq!(*tolerance.get(Quantity::ContactTime), 5e-3);
//! let json = serde_json::to_string(&tolerance.suffixed("_tolerance")).unwrap();
//! assert_eq!(json, r#"{"cor_tolerance":0.001,"peak_deformation_tolerance":0.002,"contact_time_tolerance":0.005}"#);
//! let all: Figures = Figures::splat(1.0);
//! assert_eq!(all.iter().count(), 7);
//! ```

use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The bits that name the quantities a [`Figures`] carries.
pub mod quantity {
    /// Coefficient of restitution.
    pub const COR: u8 = 1;
    /// Largest overlap (approach of the centres), m.
    pub const PEAK_DEFORMATION: u8 = 1 << 1;
    /// Largest normal force, N.
    pub const PEAK_FORCE: u8 = 1 << 2;
    /// Contact time by overlap, s.
    pub const CONTACT_TIME: u8 = 1 << 3;
    /// Contact time by force (first touch until the normal force first returns to zero), s.
    pub const FORCE_CONTACT_TIME: u8 = 1 << 4;
    /// Time from first touch to the largest overlap, s.
    pub const COMPRESSION_TIME: u8 = 1 << 5;
    /// Time from the largest overlap to separation, s.
    pub const RESTITUTION_TIME: u8 = 1 << 6;
    /// Every quantity.
    pub const ALL: u8 = (1 << 7) - 1;
    /// The three quantities checked against a tolerance: COR, peak deformation, contact time.
    pub const CHECKED: u8 = COR | PEAK_DEFORMATION | CONTACT_TIME;
    /// What is read from a trajectory: all but the restitution time.
    pub const MEASURED: u8 = ALL & !RESTITUTION_TIME;
    /// The closed form's figures: all but the force contact time (the paper's force is
    /// repulsive all through the contact, so it is the overlap contact time).
    pub const EXACT: u8 = ALL & !FORCE_CONTACT_TIME;
    /// An elastic (undamped) contact's figures: its peak deformation and contact time.
    pub const ELASTIC: u8 = PEAK_DEFORMATION | CONTACT_TIME;
}

/// One quantity of an impact.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Quantity {
    /// Coefficient of restitution.
    Cor,
    /// Largest overlap, m.
    PeakDeformation,
    /// Largest normal force, N.
    PeakForce,
    /// Contact time by overlap, s.
    ContactTime,
    /// Contact time by force, s.
    ForceContactTime,
    /// Compression time, s.
    CompressionTime,
    /// Restitution time, s.
    RestitutionTime,
}

impl Quantity {
    /// Every quantity, in the order outputs write them.
    pub const ALL: [Quantity; 7] = [
        Quantity::Cor,
        Quantity::PeakDeformation,
        Quantity::PeakForce,
        Quantity::ContactTime,
        Quantity::ForceContactTime,
        Quantity::CompressionTime,
        Quantity::RestitutionTime,
    ];

    /// The name outputs give it (a JSON key, a CSV column).
    pub const fn name(self) -> &'static str {
        match self {
            Quantity::Cor => "cor",
            Quantity::PeakDeformation => "peak_deformation",
            Quantity::PeakForce => "peak_force",
            Quantity::ContactTime => "contact_time",
            Quantity::ForceContactTime => "force_contact_time",
            Quantity::CompressionTime => "compression_time",
            Quantity::RestitutionTime => "restitution_time",
        }
    }

    /// Its bit in [`quantity`].
    pub(crate) const fn bit(self) -> u8 {
        1 << self as u8
    }

    /// Whether a set of quantities `q` holds it.
    pub const fn in_set(self, q: u8) -> bool {
        q & self.bit() != 0
    }

    /// Whether a record may have been stored without it (a figure added since), read as
    /// missing rather than refused.
    const fn may_be_absent(self) -> bool {
        matches!(self, Quantity::ForceContactTime | Quantity::CompressionTime)
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One value per quantity of an impact; the quantities it carries are `Q` (see [`quantity`]).
/// The fields of quantities outside `Q` are not written, read or iterated (keep them at their
/// default).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Figures<T = f64, const Q: u8 = { quantity::ALL }> {
    /// Coefficient of restitution `-v_out / v_in`.
    pub cor: T,
    /// Largest overlap (approach of the centres), m.
    pub peak_deformation: T,
    /// Largest normal force, N.
    pub peak_force: T,
    /// Contact time by overlap (first touch until the overlap returns to zero), s.
    pub contact_time: T,
    /// Contact time by force (first touch until the normal force first returns to zero), s.
    pub force_contact_time: T,
    /// Time from first touch to the largest overlap, s.
    pub compression_time: T,
    /// Time from the largest overlap to separation, s.
    pub restitution_time: T,
}

/// The three quantities checked against a tolerance: COR, peak deformation, contact time.
pub type Checked<T = f64> = Figures<T, { quantity::CHECKED }>;

/// What is read from a trajectory: all quantities but the restitution time.
pub type Measured<T = f64> = Figures<T, { quantity::MEASURED }>;

/// The closed form's figures: all quantities but the force contact time.
pub type Exact<T = f64> = Figures<T, { quantity::EXACT }>;

/// An elastic (undamped) contact's figures: peak deformation and contact time.
pub type Elastic<T = f64> = Figures<T, { quantity::ELASTIC }>;

impl<T, const Q: u8> Figures<T, Q> {
    /// The quantities this type carries, in output order.
    pub fn quantities() -> impl Iterator<Item = Quantity> {
        Quantity::ALL.into_iter().filter(|q| q.in_set(Q))
    }

    /// The value of `q` (a quantity outside `Q` gives its unused field).
    pub fn get(&self, q: Quantity) -> &T {
        match q {
            Quantity::Cor => &self.cor,
            Quantity::PeakDeformation => &self.peak_deformation,
            Quantity::PeakForce => &self.peak_force,
            Quantity::ContactTime => &self.contact_time,
            Quantity::ForceContactTime => &self.force_contact_time,
            Quantity::CompressionTime => &self.compression_time,
            Quantity::RestitutionTime => &self.restitution_time,
        }
    }

    /// The value of `q`, to change.
    pub fn get_mut(&mut self, q: Quantity) -> &mut T {
        match q {
            Quantity::Cor => &mut self.cor,
            Quantity::PeakDeformation => &mut self.peak_deformation,
            Quantity::PeakForce => &mut self.peak_force,
            Quantity::ContactTime => &mut self.contact_time,
            Quantity::ForceContactTime => &mut self.force_contact_time,
            Quantity::CompressionTime => &mut self.compression_time,
            Quantity::RestitutionTime => &mut self.restitution_time,
        }
    }

    /// The quantities of `Q` with their values, in output order.
    pub fn iter(&self) -> impl Iterator<Item = (Quantity, &T)> {
        Self::quantities().map(move |q| (q, self.get(q)))
    }

    /// The same values, each through `f`; the other quantities at their default.
    pub fn map<U: Default>(&self, mut f: impl FnMut(Quantity, &T) -> U) -> Figures<U, Q> {
        let mut out = Figures::<U, Q>::default();
        for q in Self::quantities() {
            *out.get_mut(q) = f(q, self.get(q));
        }
        out
    }

    /// Values built quantity by quantity; the other quantities at their default.
    pub fn from_fn(mut f: impl FnMut(Quantity) -> T) -> Self
    where
        T: Default,
    {
        let mut out = Self::default();
        for q in Self::quantities() {
            *out.get_mut(q) = f(q);
        }
        out
    }

    /// The values of `Q` as a set of other quantities `P` (those of `P` outside `Q` at their
    /// default).
    pub fn select<const P: u8>(&self) -> Figures<T, P>
    where
        T: Clone + Default,
    {
        Figures::<T, P>::from_fn(|q| {
            if q.in_set(Q) {
                self.get(q).clone()
            } else {
                T::default()
            }
        })
    }

    /// A view that serialises each quantity's name followed by `suffix`
    /// (`cor_vs_paper`, …).
    pub fn suffixed(&self, suffix: &'static str) -> Suffixed<'_, T, Q> {
        Suffixed {
            figures: self,
            suffix,
        }
    }
}

impl<T: Clone + Default, const Q: u8> Figures<T, Q> {
    /// Every quantity of `Q` at `value`.
    pub fn splat(value: T) -> Self {
        Self::from_fn(|_| value.clone())
    }
}

impl<T: Serialize, const Q: u8> Serialize for Figures<T, Q> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.suffixed("").serialize(serializer)
    }
}

/// [`Figures`] written with a suffix on each quantity's name: see [`Figures::suffixed`].
pub struct Suffixed<'a, T, const Q: u8> {
    figures: &'a Figures<T, Q>,
    suffix: &'static str,
}

impl<T: Serialize, const Q: u8> Serialize for Suffixed<'_, T, Q> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(Figures::<T, Q>::quantities().count()))?;
        for (q, value) in self.figures.iter() {
            if self.suffix.is_empty() {
                map.serialize_entry(q.name(), value)?;
            } else {
                map.serialize_entry(&format!("{}{}", q.name(), self.suffix), value)?;
            }
        }
        map.end()
    }
}

/// `serialize_with` functions that write a flattened [`Figures`] with a suffix on each name:
/// `#[serde(flatten, serialize_with = "suffix::vs_paper")]`.
pub(crate) mod suffix {
    use super::Figures;
    use serde::{Serialize, Serializer};

    macro_rules! suffixes {
        ($($name:ident: $suffix:literal),* $(,)?) => {$(
            #[doc = concat!("Each quantity's name followed by `", $suffix, "`.")]
            pub fn $name<T: Serialize, const Q: u8, S: Serializer>(
                figures: &Figures<T, Q>,
                serializer: S,
            ) -> Result<S::Ok, S::Error> {
                figures.suffixed($suffix).serialize(serializer)
            }
        )*};
    }

    suffixes!(
        vs_paper: "_vs_paper",
        vs_elastic: "_vs_elastic",
        exact: "_exact",
        error: "_error",
        tolerance: "_tolerance",
        target: "_target",
    );
}

/// Reads the quantities of `Q` from a map: `null` is NaN (JSON has no NaN), and a figure
/// added since older records were stored (the force contact time, the compression time) is
/// NaN when absent; any other missing quantity is an error. Other keys are left to the
/// enclosing record.
impl<'de, const Q: u8> Deserialize<'de> for Figures<f64, Q> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct FiguresVisitor<const Q: u8>(PhantomData<[(); 0]>);

        impl<'de, const Q: u8> Visitor<'de> for FiguresVisitor<Q> {
            type Value = Figures<f64, Q>;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a map of impact figures")
            }

            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
                let mut figures = Figures::<Option<f64>, Q>::default();
                let mut seen = 0u8;
                while let Some(key) = map.next_key::<String>()? {
                    match Figures::<f64, Q>::quantities().find(|q| q.name() == key) {
                        Some(q) => {
                            if seen & q.bit() != 0 {
                                return Err(de::Error::duplicate_field(q.name()));
                            }
                            seen |= q.bit();
                            *figures.get_mut(q) =
                                Some(map.next_value::<Option<f64>>()?.unwrap_or(f64::NAN));
                        }
                        None => {
                            map.next_value::<de::IgnoredAny>()?;
                        }
                    }
                }
                let mut out = Figures::<f64, Q>::default();
                for (q, value) in figures.iter() {
                    *out.get_mut(q) = match value {
                        Some(v) => *v,
                        None if q.may_be_absent() => f64::NAN,
                        None => return Err(de::Error::missing_field(q.name())),
                    };
                }
                Ok(out)
            }
        }

        deserializer.deserialize_map(FiguresVisitor::<Q>(PhantomData))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_writes_and_reads_its_own_quantities_only() {
        let exact = Exact::<f64>::from_fn(|q| q.bit() as f64);
        let json = serde_json::to_value(exact).unwrap();
        let keys: Vec<&String> = json.as_object().unwrap().keys().collect();
        assert_eq!(
            keys,
            [
                "compression_time",
                "contact_time",
                "cor",
                "peak_deformation",
                "peak_force",
                "restitution_time"
            ]
        );
        let back: Exact = serde_json::from_value(json).unwrap();
        assert_eq!(back, exact);
        assert_eq!(back.force_contact_time.to_bits(), 0.0f64.to_bits());
    }

    #[test]
    fn null_is_nan_and_only_the_later_figures_may_be_absent() {
        let read: Measured = serde_json::from_str(
            r#"{"cor":null,"peak_deformation":1,"peak_force":2,"contact_time":3,"other":"x"}"#,
        )
        .unwrap();
        assert!(
            read.cor.is_nan() && read.force_contact_time.is_nan() && read.compression_time.is_nan()
        );
        assert_eq!(read.contact_time.to_bits(), 3.0f64.to_bits());
        let missing =
            serde_json::from_str::<Measured>(r#"{"cor":1,"peak_force":2,"contact_time":3}"#)
                .unwrap_err();
        assert!(
            missing
                .to_string()
                .contains("missing field `peak_deformation`"),
            "{missing}"
        );
    }

    #[test]
    fn a_flattened_set_keeps_the_record_s_order_and_its_suffix() {
        #[derive(Serialize)]
        struct Record {
            name: &'static str,
            #[serde(flatten)]
            figures: Checked,
            #[serde(flatten, serialize_with = "suffix::error")]
            error: Checked,
            wall_time: f64,
        }
        let r = Record {
            name: "a",
            figures: Checked::splat(1.0),
            error: Checked::splat(0.5),
            wall_time: 2.0,
        };
        assert_eq!(
            serde_json::to_string(&r).unwrap(),
            r#"{"name":"a","cor":1.0,"peak_deformation":1.0,"contact_time":1.0,"cor_error":0.5,"peak_deformation_error":0.5,"contact_time_error":0.5,"wall_time":2.0}"#
        );
    }

    #[test]
    fn select_moves_values_between_sets() {
        let exact = Exact::<f64>::splat(2.0);
        let checked: Checked = exact.select();
        assert_eq!(checked, Checked::splat(2.0));
        let measured: Measured = exact.select();
        assert_eq!(measured.force_contact_time.to_bits(), 0.0f64.to_bits());
        assert_eq!(measured.compression_time.to_bits(), 2.0f64.to_bits());
    }
}
