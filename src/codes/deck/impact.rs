//! The plan of one pair's impact, what every reader's input is written from: the pair, its
//! bodies, the setup its run is read with, the bodies' speeds and the reach between them.

use std::path::Path;

use super::{
    BodyElasticity, Conventions, DeckBody, DeckContact, DeckError, DeckImpactInput, DeckOptions,
    DeckReader, OBLIQUE_SUFFIX, Partner, UserDeck,
};
use crate::codes::{CodeError, CodeSetup, CodeSphere};
use crate::model::law::{CodeLaw, ContactForce};
use crate::model::scene::SceneKind;

/// One pair's impact as planned, before a code's input is written for it.
#[derive(Clone, Debug)]
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
    /// The impact speed, m/s.
    pub velocity: f64,
    /// The steps of the deck's own time step the run takes.
    pub steps: u64,
    /// For an oblique impact, the moving body's centre velocity along the contact plane
    /// relative to its partner's at the start, m/s (a pair's split as the normal one is, so that
    /// the centre of mass stays at rest); `None` for the normal impact.
    pub tangential_velocity: Option<f64>,
}

/// A code's deck reader as a dialect of the one pipeline: its syntax (what it recognises and
/// reads) and how it writes a planned impact; the plan itself is formed once, for all.
pub(crate) trait DeckDialect: Send + Sync {
    /// Whether `text` (the file at `path`) is an input of this code.
    fn recognises(&self, path: &Path, text: &str) -> bool;
    /// What this reader reads, for an error that names it.
    fn reads(&self) -> &'static str;
    /// Read the deck at `path`.
    fn read(&self, path: &Path, options: &DeckOptions) -> Result<UserDeck, DeckError>;
    /// What this code's impact setups are formed with: which elastic constants their bodies
    /// carry, and the conventions the build measured where its driver uses them.
    fn setup_basis(&self) -> (BodyElasticity, Option<Conventions>) {
        (BodyElasticity::FromDeck, None)
    }
    /// The input of a planned impact, in the code's own syntax.
    fn input(&self, deck: &UserDeck, plan: ImpactPlan<'_>) -> Result<DeckImpactInput, CodeError>;
    /// Whether [`DeckDialect::input`] renders an oblique plan (its `tangential_velocity`) and
    /// reads the deck's friction; a dialect that does not runs no tangential impact.
    fn renders_oblique(&self) -> bool {
        false
    }
}

impl<T: DeckDialect> DeckReader for T {
    fn recognises(&self, path: &Path, text: &str) -> bool {
        DeckDialect::recognises(self, path, text)
    }

    fn reads(&self) -> &'static str {
        DeckDialect::reads(self)
    }

    fn read(&self, path: &Path, options: &DeckOptions) -> Result<UserDeck, DeckError> {
        DeckDialect::read(self, path, options)
    }

    fn render(
        &self,
        deck: &UserDeck,
        contact: usize,
        velocity: f64,
        steps: u64,
    ) -> Result<DeckImpactInput, CodeError> {
        let (elasticity, conventions) = self.setup_basis();
        let plan = deck.impact_plan(contact, velocity, steps, elasticity, conventions);
        self.input(deck, plan)
    }

    fn reads_friction(&self) -> bool {
        self.renders_oblique()
    }

    fn render_oblique(
        &self,
        deck: &UserDeck,
        contact: usize,
        velocity: f64,
        tangential_velocity: f64,
        steps: u64,
    ) -> Result<Option<DeckImpactInput>, CodeError> {
        if !self.renders_oblique() {
            return Ok(None);
        }
        let (elasticity, conventions) = self.setup_basis();
        let mut plan = deck.impact_plan(contact, velocity, steps, elasticity, conventions);
        plan.setup.case_name.push_str(OBLIQUE_SUFFIX);
        plan.tangential_velocity = Some(tangential_velocity);
        self.input(deck, plan).map(Some)
    }
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
            oblique: None,
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
            tangential_velocity: None,
        }
    }
}
