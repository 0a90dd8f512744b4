//! The plan of one pair's impact, what every reader's render starts from: the pair, its
//! bodies, the setup its run is read with and the bodies' speeds.

use super::{BodyElasticity, Conventions, DeckBody, DeckContact, Partner, UserDeck};
use crate::codes::CodeSetup;

/// One pair's impact as planned, before a code's input is written for it.
pub(crate) struct ImpactPlan<'d> {
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
}

impl UserDeck {
    /// The plan of the impact of `self.contacts[contact]` at `velocity` (m/s) for `steps` steps,
    /// its setup as [`UserDeck::impact_setup`] forms it.
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
        let setup = self.impact_setup(contact, velocity, steps, elasticity, conventions);
        let velocities = setup.centre_of_mass_velocities();
        ImpactPlan {
            contact: c,
            body,
            other,
            setup,
            velocities,
            reach: body.radius + other.map_or(0.0, |o| o.radius),
        }
    }
}
