//! The tangential half of an oblique impact in YADE 2023.02a: what `impact.py` gains for a
//! setup with [`CodeSetup::oblique`], and the laws it cannot render.
//!
//! The ball scenes run `Ip2_FrictMat_FrictMat_MindlinPhys` with `Law2_ScGeom_MindlinPhys_Mindlin`
//! (yade `pkg/dem/HertzMindlin.cpp`), whose tangential half is a history spring of Mindlin's
//! tangent stiffness `ks = kso sqrt(uN)`, `kso = 8 sqrt(R*) G*`, `1/G* = Σ (2 − ν)/G` (the
//! case's [`TangentialSpring::Mindlin`]; a rigid plate's `1e30` Pa wall adds nothing to `1/G*`),
//! bounded by `tan(frictionAngle) |F_n|`, plus a shear dashpot `2 betas sqrt(mbar ks)` of
//! Thornton's fit of `es` (given `en` alone, `es = en`), added only while the spring is inside
//! the bound. `es = 1` switches that dashpot off exactly (`betas = 0`), which is the case's
//! undamped law. A constant or a normal-proportional spring, or a tangential dashpot, has no
//! exact rendering beside the damped Hertz normal law: YADE's Cundall–Strack (`FrictPhys`) has a
//! linear normal spring, `Law2_ScGeom_MindlinPhys_HertzWithLinearShear` no normal damping, and
//! the Mindlin law's dashpot acts outside the Coulomb bound and through Thornton's fit.
//!
//! The bound is on the whole normal force, dashpot and clamp included (`Fn =
//! phys->normalForce.norm()` after `phys->normalForce -= phys->normalViscous`). Measured in
//! gross sliding (v_t' against Coulomb's at the run's own COR, as a ratio of the changes): with
//! `es` left at `en` the shear dashpot adds friction while the spring is inside the bound, 1.199
//! at e 0.5 (40 mm steel ball, 1.2 m/s normal, 3 m/s along a steel plate, μ 0.3); with `es = 1`
//! 0.986 there, the Mindlin spring (`ks ∝ sqrt(uN)`, from zero) lagging for the first 45 of 1104
//! steps behind a bound the normal dashpot (`∝ uN^0.25`) raises at first touch; 0.99924 and
//! 0.99975 on the held-out cases (e 0.82 and 0.80). The spin's change falls a further 0.08–0.2 %
//! short: `Ig2_Wall_Sphere_ScGeom` puts the contact point, where the force acts, on the wall's
//! plane (the centre projected onto it), `R − uN` from the centre.

use super::super::template::{exact_number, fill_template};
use super::super::{CodeError, CodeSetup};
use crate::codes::deck::TANGENTIAL_LINE;
use crate::model::scene::SceneKind;
use crate::model::tangential::TangentialSpring;

/// The Python lines that give the ball its tangential motion, the materials their friction
/// and the law no shear dashpot.
const TEMPLATE: &str = include_str!("oblique.py");

/// Where in `impact.py` the oblique set-up goes: before the comment on the timed steps, after
/// the engines and the step (a blank line then parts them).
const STEPS_ANCHOR: &str = "# O.run(STEPS, True) would do the same iterations";

/// `text`, the rendered normal impact of `setup`, with the tangential half of its
/// [`CodeSetup::oblique`] (unchanged for a normal impact), or why YADE cannot run it (`code`
/// names the build).
pub(super) fn with_tangential_half(
    code: &str,
    setup: &CodeSetup,
    text: String,
) -> Result<String, CodeError> {
    let Some(oblique) = setup.oblique else {
        return Ok(text);
    };
    if setup.scene != SceneKind::BallPlate {
        return Err(setup.unsupported(
            code,
            "an oblique impact runs on a plate only (the ball's tangential motion turns the \
             normal of two balls)",
        ));
    }
    let law = oblique.law;
    let spring = match law.spring {
        TangentialSpring::Mindlin => None,
        TangentialSpring::Linear { stiffness } => {
            Some(format!("a constant tangential stiffness ({stiffness} N/m)"))
        }
        TangentialSpring::Proportional { ratio } => Some(format!(
            "a tangential stiffness proportional to the normal one (ratio {ratio})"
        )),
    };
    if let Some(spring) = spring {
        return Err(setup.unsupported(
            code,
            format!(
                "tangential law with {spring}: YADE's Hertz–Mindlin law has Mindlin's spring \
                 only, and its Cundall–Strack law a linear normal spring, not the case's \
                 damped Hertz (YADE renders the Mindlin spring without damping)"
            ),
        ));
    }
    if law.damping_ratio != 0.0 {
        return Err(setup.unsupported(
            code,
            format!(
                "tangential damping ratio {}: YADE's Hertz–Mindlin shear dashpot comes through \
                 Thornton's fit of `es` and acts outside the Coulomb bound (YADE renders the \
                 Mindlin spring without damping)",
                law.damping_ratio
            ),
        ));
    }
    let block = fill_template(
        TEMPLATE,
        &[
            ("friction", exact_number(oblique.friction_coefficient)),
            (
                "tangential_velocity",
                exact_number(oblique.ball.tangential_velocity),
            ),
            (
                "angular_velocity",
                exact_number(oblique.ball.angular_velocity),
            ),
        ],
    )
    .map_err(|reason| setup.unsupported(code, reason.to_string()))?;
    let Some(at) = text.find(STEPS_ANCHOR) else {
        return Err(setup.unsupported(
            code,
            format!("the script has no line starting `{STEPS_ANCHOR}`"),
        ));
    };
    let mut out = String::with_capacity(text.len() + block.len() + 200);
    out.push_str(&text[..at]);
    out.push_str(&block);
    out.push('\n');
    out.push_str(&text[at..]);
    out.push_str(&format!(
        "# The ball's motion along the plane after the steps, in the case's sign convention.\n\
         print(\"{TANGENTIAL_LINE} %r %r\" % (O.bodies[b1].state.vel[0], -O.bodies[b1].state.angVel[1]))\n"
    ));
    Ok(out)
}
