//! A setup's values as the Python scripts of YADE and Kratos are given them: every number
//! exact ([`exact_number`]), under the names both codes' templates use, and as the Python dict
//! literal a script's list of impacts holds; and the numbers the scripts report back.

use std::str::FromStr;

use super::template::exact_number;
use super::{CodeSetup, ParseError};
use crate::model::scene::SceneKind;

/// The two bodies of `setup` as the scripts take them, in the order they list them: the scene,
/// the time step and the steps, the moving sphere, the other ball (zeros at a wall), the two
/// velocities of the centre-of-mass frame, and the wall's material (`rigid` for a rigid plate,
/// zeros between two balls). A script that needs fewer leaves out the ones it has no use for.
pub(crate) fn body_values(setup: &CodeSetup) -> Vec<(&'static str, String)> {
    let s = setup.sphere;
    let (v1, v2) = setup.centre_of_mass_velocities();
    let (wall_young, wall_poisson) = match setup.scene {
        SceneKind::BallBall => (0.0, 0.0),
        _ => setup.second_material(),
    };
    let other = setup
        .other_sphere
        .filter(|_| setup.scene == SceneKind::BallBall);
    let num = exact_number;
    vec![
        ("scene", setup.scene.name().to_string()),
        ("timestep", num(setup.timestep)),
        ("steps", setup.steps.to_string()),
        ("radius", num(s.radius)),
        ("mass", num(s.mass)),
        ("density", num(s.density)),
        ("young", num(s.youngs_modulus)),
        ("poisson", num(s.poisson_ratio.unwrap_or(0.0))),
        ("velocity", num(v1)),
        ("other_radius", num(other.map_or(0.0, |o| o.radius))),
        ("other_mass", num(other.map_or(0.0, |o| o.mass))),
        ("other_density", num(other.map_or(0.0, |o| o.density))),
        ("other_young", num(other.map_or(0.0, |o| o.youngs_modulus))),
        (
            "other_poisson",
            num(other.and_then(|o| o.poisson_ratio).unwrap_or(0.0)),
        ),
        ("other_velocity", num(v2)),
        ("wall_young", num(wall_young)),
        ("wall_poisson", num(wall_poisson)),
    ]
}

/// `values` less the ones named in `unused`, in their order.
pub(crate) fn without(
    values: Vec<(&'static str, String)>,
    unused: &[&str],
) -> Vec<(&'static str, String)> {
    values
        .into_iter()
        .filter(|(key, _)| !unused.contains(key))
        .collect()
}

/// `values` as a Python dict literal, `{"key": value, …}`: the names among them (the scene,
/// the integration scheme) quoted, the numbers as written.
pub(crate) fn python_dict(values: &[(&str, String)]) -> String {
    let fields: Vec<String> = values
        .iter()
        .map(|(key, value)| match *key {
            "scene" | "scheme" => format!("\"{key}\": \"{value}\""),
            _ => format!("\"{key}\": {value}"),
        })
        .collect();
    format!("{{{}}}", fields.join(", "))
}

/// A number a script reported, `value` as its `MILLIMPACT` line gives it, read as `T`: `None`
/// where it reported none, an error naming `field` where it does not read.
pub(crate) fn reported<T: FromStr>(
    value: Option<&str>,
    field: &'static str,
) -> Result<Option<T>, ParseError> {
    value
        .map(|v| {
            v.parse::<T>().map_err(|_| ParseError::BadValue {
                field,
                value: v.to_string(),
            })
        })
        .transpose()
}
