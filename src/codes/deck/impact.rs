//! The plan of one pair's impact, what every reader's input is written from: the pair, its
//! bodies, the setup its run is read with, the bodies' speeds and the reach between them.

use super::{BodyElasticity, Conventions, DeckBody, DeckContact, Partner, UserDeck};
use crate::codes::{CodeSetup, CodeSphere};
use crate::model::law::{CodeLaw, ContactForce};
use crate::model::scene::SceneKind;

/// One pair's impact as planned, before a code's input is written for it.
#[derive(Clone, Debug)]
pub struct ImpactPlan<'d> {
    /// The pair.
    pub contact: &'d DeckContact,
    /// The moving body.
    pub body: &'d DeckBody,
    /// The second body (`None` at a wall).
    pub other: Option<&'d DeckBody>,
    /// The setup the run is parsed with.
    pub setup: CodeSetup,
    /// The two bodies' velocities in the centre-of-mass frame, m/s.
    pub velocities: (f64, f64),
    /// The distance between the centres at touch (the body's radius at a wall), m.
    pub reach: f64,
    /// The impact speed, m/s.
    pub velocity: f64,
    /// The steps of the deck's own time step the run takes.
    pub steps: u64,
}

impl UserDeck {
    /// The plan of the impact of `self.contacts[contact]` at `velocity` (m/s), run for `steps`
    /// steps of the deck's own time step. Its setup holds the pair's bodies, its law's mass,
    /// stiffness, exponent and clamp, its entered COR and, for the paper's law, its η;
    /// `conventions` as the build measured them, where the driver uses them.
    pub(crate) fn impact_plan(
        &self,
        contact: usize,
        velocity: f64,
        steps: u64,
        elasticity: BodyElasticity,
        conventions: Option<Conventions>,
    ) -> ImpactPlan<'_> {
        let c = &self.contacts[contact];
        let body = &self.bodies[c.body];
        let other = match c.partner {
            Partner::Body(o) => Some(&self.bodies[o]),
            Partner::Wall(_) => None,
        };
        let sphere = |b: &DeckBody| CodeSphere {
            radius: b.radius,
            density: b.density,
            mass: b.mass,
            youngs_modulus: match elasticity {
                BodyElasticity::FromDeck => b.youngs_modulus.unwrap_or(f64::NAN),
                BodyElasticity::Withheld => f64::NAN,
            },
            poisson_ratio: match elasticity {
                BodyElasticity::FromDeck => b.poisson_ratio,
                BodyElasticity::Withheld => None,
            },
        };
        let mut setup = CodeSetup {
            case_name: format!("deck-{contact}-{}-{}", c.types[0], c.types[1]),
            scene: match other {
                Some(_) => SceneKind::BallBall,
                None => SceneKind::BallPlate,
            },
            sphere: sphere(body),
            other_sphere: other.map(sphere),
            plate_material: None,
            effective_modulus: None,
            effective_radius: None,
            reduced_mass: c.law.mass(),
            stiffness: c.law.stiffness(),
            exponent: c.law.exponent(),
            impact_velocity: velocity,
            target_restitution: c.cor_entered.unwrap_or(f64::NAN),
            loss_coefficient: match c.law {
                CodeLaw::Paper(law) => Some(law.loss_coefficient),
                CodeLaw::Dashpot(_) => None,
            },
            timestep: self.timestep,
            steps,
            clamp_attractive: c.law.clamp_attractive(),
            conventions,
        };
        setup.effective_radius = Some(setup.pair_radius());
        let velocities = setup.centre_of_mass_velocities();
        ImpactPlan {
            contact: c,
            body,
            other,
            setup,
            velocities,
            reach: body.radius + other.map_or(0.0, |o| o.radius),
            velocity,
            steps,
        }
    }
}
