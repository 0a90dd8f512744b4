//! An oblique or spinning impact on the plate in the LIGGGHTS deck (both builds): the lines
//! [`super::render_deck`] changes when the setup carries a tangential half.
//!
//! What LIGGGHTS 3.8 does, from its `tangential_model_history.h` and the normal models that
//! feed it (`normal_model_hertz.h`, the paper's `normal_model_paper.h`):
//! - `tangential history` integrates the slip into a shear spring `ξ` and pushes `−k_t ξ`,
//!   with `k_t` what the normal model hands it: `8 G* sqrt(R* δ)` (Mindlin) under both
//!   `model hertz` and `model paper`. Where `k_t |ξ|` passes `μ |F_n|` the force is cut to
//!   that bound and `ξ` with it.
//! - `|F_n|` is the normal model's whole force, its dashpot included (and negative where the
//!   damped Hertz attracts under `limitForce off`: its magnitude then still bounds friction,
//!   which the check's allowance carries).
//! - The tangential dashpot acts only inside the bound, with `gammat` from the normal model:
//!   0 under `model hertz … tangential_damping off` (the stock deck's setting) and always 0
//!   under `model paper`. The case's law has no dashpot, so none is rendered.
//! - The torque's lever is `R − δ/2` at a wall, not `R`: the spin changes by about `δ/2R`
//!   less than a rigid sphere's (1e-4 to 1e-3 of it in the held-out cases).
//!
//! A constant (`linear`) or proportional spring has no place beside these normal laws in
//! LIGGGHTS (`hooke/stiffness` has a constant `k_t`, but with a linear normal spring), and a
//! tangential dashpot set by a damping ratio has none either: such a law is refused.
//!
//! The ball's tangential velocity and spin are set with `set atom 1 vx … omegay …` (at the
//! plane `z = 0` with the ball above, the surface at the contact moves at `v_x − R ω_y`, the
//! case's convention), and after the run one line [`TANGENTIAL_LINE`] prints `vx[1]` and
//! `omegay[1]` as immediate variables (LIGGGHTS prints those with `%.20g`; a `${name}`
//! variable would be cut to 15 digits).

use crate::codes::deck::TANGENTIAL_LINE;
use crate::codes::template::exact_number;
use crate::codes::{CodeError, CodeSetup};
use crate::model::scene::SceneKind;
use crate::model::tangential::{TangentialLaw, TangentialSpring};

/// The deck's comment of what a normal impact leaves out (its input's header lines).
const NORMAL_ABOUT: &str =
    "# Gravity, friction and tangential damping are off; no rotation is driven (no torque acts);
# the only output is the per-step trajectory in traj.txt (time, overlap, approach speed,
# normal force on sphere 1).";

/// The deck's comment for an oblique impact.
const OBLIQUE_ABOUT: &str =
    "# Gravity and tangential damping are off; the ball starts with a velocity along x and a spin
# about y, and friction acts through `tangential history` (Mindlin spring, Coulomb bound);
# the output is the per-step trajectory in traj.txt (time, overlap, approach speed, normal
# force on sphere 1), then one line with the ball's vx and omegay after the run.";

/// Refuses, as `code`'s fault, an oblique setup LIGGGHTS' stock tangential model cannot run
/// exactly: any other scene than a ball on the plate, or a law other than the undamped
/// Mindlin spring. A normal setup passes.
pub(super) fn refuse(code: &str, setup: &CodeSetup) -> Result<(), CodeError> {
    let Some(oblique) = setup.oblique else {
        return Ok(());
    };
    if setup.scene != SceneKind::BallPlate || oblique.partner.is_some() {
        return Err(setup.unsupported(
            code,
            format!(
                "an oblique {} impact: this build runs oblique ball_plate impacts only",
                setup.scene.name()
            ),
        ));
    }
    match oblique.law {
        TangentialLaw {
            spring: TangentialSpring::Mindlin,
            damping_ratio: 0.0,
        } => Ok(()),
        law => Err(setup.unsupported(
            code,
            format!(
                "tangential law {} with damping ratio {}: LIGGGHTS' `tangential history` beside \
                 this build's normal law has only the Mindlin spring k_t = 8 G* sqrt(R* δ) and \
                 no tangential dashpot (spring = \"mindlin\", damping_ratio = 0)",
                spring_name(law.spring),
                law.damping_ratio
            ),
        )),
    }
}

/// The spring as a case names it.
fn spring_name(spring: TangentialSpring) -> String {
    match spring {
        TangentialSpring::Mindlin => "mindlin".into(),
        TangentialSpring::Linear { stiffness } => format!("linear (k_t {stiffness} N/m)"),
        TangentialSpring::Proportional { ratio } => format!("proportional (ratio {ratio})"),
    }
}

/// The tangential model of the deck's `pair_style` and wall lines: `history` for an oblique
/// impact, `no_history` (nothing to integrate in a head-on one) otherwise.
pub(super) fn tangential_model(setup: &CodeSetup) -> &'static str {
    if setup.oblique.is_some() {
        "history"
    } else {
        "no_history"
    }
}

/// The `coefficientFriction` of every type pair: the case's μ, 0 for a normal impact.
pub(super) fn friction(setup: &CodeSetup) -> String {
    setup
        .oblique
        .map_or_else(|| "0".into(), |o| exact_number(o.friction_coefficient))
}

/// A bound on the ball's speed along the plane over the run, m/s, which the box must hold:
/// its own plus its surface's from the spin (friction changes the centre's velocity by less
/// than the slip), 0 for a normal impact (whose box is then as before, to the bit).
pub(super) fn plane_speed_bound(setup: &CodeSetup) -> f64 {
    setup.oblique.map_or(0.0, |o| {
        o.ball.tangential_velocity.abs() + setup.sphere.radius * o.ball.angular_velocity.abs()
    })
}

/// The impact's kind as the deck's first line names it.
pub(super) fn kind(setup: &CodeSetup) -> &'static str {
    if setup.oblique.is_some() {
        "oblique"
    } else {
        "normal"
    }
}

/// The header lines that say what the deck leaves out and prints.
pub(super) fn about(setup: &CodeSetup) -> &'static str {
    if setup.oblique.is_some() {
        OBLIQUE_ABOUT
    } else {
        NORMAL_ABOUT
    }
}

/// The line that starts ball 1 moving along the plane and spinning, after its normal
/// velocity is set; `None` for a normal impact.
pub(super) fn motion_line(setup: &CodeSetup) -> Option<String> {
    setup.oblique.map(|o| {
        format!(
            "set             atom 1 vx {} omegay {}",
            exact_number(o.ball.tangential_velocity),
            exact_number(o.ball.angular_velocity)
        )
    })
}

/// The line after the run with the ball's motion along the plane; `None` for a normal impact.
pub(super) fn printed_line(setup: &CodeSetup) -> Option<String> {
    setup
        .oblique
        .map(|_| format!("print           \"{TANGENTIAL_LINE} $(vx[1]) $(omegay[1])\""))
}
