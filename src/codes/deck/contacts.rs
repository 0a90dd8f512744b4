//! The pairs of a deck: each pair of bodies and each body against each wall, with the law a
//! code's own lines give it ([`PairLaw`]; each reader forms it by its code's rules).

use super::{DeckBody, DeckContact, DeckError, DeckFriction, DeckSource, Partner, TypeRef};
use crate::model::law::CodeLaw;

/// The contact law the user's lines make a code integrate for one pair: the model as the deck
/// names it, the law, the COR the user entered where the model takes one, the convention traps
/// and the lines (or fields) that set it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct PairLaw {
    /// The normal model as the deck names it.
    pub model: String,
    /// The law the code integrates.
    pub law: CodeLaw,
    /// The COR entered, where the model takes one.
    pub cor_entered: Option<f64>,
    /// The convention traps these lines meet.
    pub traps: Vec<String>,
    /// The lines (or fields) that set this pair's contact.
    pub lines: Vec<DeckSource>,
    /// The friction the lines give, where the reader reads it.
    pub friction: Option<DeckFriction>,
}

/// What an oblique impact's case name adds to its normal impact's, so that the two runs at one
/// speed are told apart (a recorded run's key is its case name and speed).
pub(crate) const OBLIQUE_SUFFIX: &str = "-oblique";

impl PairLaw {
    /// The law `law` of the model `model`, with the COR entered and the traps; no lines yet.
    pub(crate) fn new(
        model: impl Into<String>,
        law: impl Into<CodeLaw>,
        cor_entered: Option<f64>,
        traps: Vec<String>,
    ) -> Self {
        Self {
            model: model.into(),
            law: law.into(),
            cor_entered,
            traps,
            lines: Vec::new(),
            friction: None,
        }
    }

    /// The same law, with the friction its lines give.
    pub(crate) fn with_friction(mut self, friction: Option<DeckFriction>) -> Self {
        self.friction = friction;
        self
    }

    /// The same law, set by `lines`.
    pub(crate) fn set_by<L: Into<DeckSource>>(
        mut self,
        lines: impl IntoIterator<Item = L>,
    ) -> Self {
        self.lines = lines.into_iter().map(Into::into).collect();
        self
    }

    /// The contact of `body` (of `types[0]`) with `partner` (of `types[1]`) under this law.
    fn contact(self, body: usize, partner: Partner, types: [TypeRef; 2]) -> DeckContact {
        DeckContact {
            body,
            partner,
            types,
            model: self.model,
            cor_entered: self.cor_entered,
            law: self.law,
            traps: self.traps,
            lines: self.lines,
            friction: self.friction,
        }
    }
}

/// Each pair of bodies (a body with itself, and with each after it) with the law `law` forms
/// for it.
pub(crate) fn body_contacts(
    bodies: &[DeckBody],
    law: impl FnMut(&DeckBody, &DeckBody) -> Result<PairLaw, DeckError>,
) -> Result<Vec<DeckContact>, DeckError> {
    body_contacts_formed(bodies, |_, _| true, law)
}

/// [`body_contacts`] of the pairs `formed` says the deck lets meet (a pair the code could not
/// evaluate, and so the deck never lets meet, has no law to check).
pub(crate) fn body_contacts_formed(
    bodies: &[DeckBody],
    formed: impl Fn(&DeckBody, &DeckBody) -> bool,
    mut law: impl FnMut(&DeckBody, &DeckBody) -> Result<PairLaw, DeckError>,
) -> Result<Vec<DeckContact>, DeckError> {
    let mut contacts = Vec::new();
    for (a, body) in bodies.iter().enumerate() {
        for (b, other) in bodies.iter().enumerate().skip(a) {
            if !formed(body, other) {
                continue;
            }
            let types = [TypeRef::Type(body.type_id), TypeRef::Type(other.type_id)];
            contacts.push(law(body, other)?.contact(a, Partner::Body(b), types));
        }
    }
    Ok(contacts)
}

/// The order a code lists its walls' contacts in (the order its deck's table shows them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum WallOrder {
    /// Each body against every wall, body by body.
    ByBody,
    /// Each wall against every body, wall by wall.
    ByWall,
}

/// Each body against each of `walls`, in `order`, with the law `law` forms for it.
pub(crate) fn wall_contacts<W>(
    bodies: &[DeckBody],
    walls: &[W],
    order: WallOrder,
    law: impl FnMut(&W, &DeckBody) -> Result<PairLaw, DeckError>,
) -> Result<Vec<DeckContact>, DeckError> {
    wall_contacts_formed(bodies, walls, order, |_, _| true, law)
}

/// [`wall_contacts`] of the pairs `formed` says the deck lets meet.
pub(crate) fn wall_contacts_formed<W>(
    bodies: &[DeckBody],
    walls: &[W],
    order: WallOrder,
    formed: impl Fn(&W, &DeckBody) -> bool,
    mut law: impl FnMut(&W, &DeckBody) -> Result<PairLaw, DeckError>,
) -> Result<Vec<DeckContact>, DeckError> {
    let pairs: Vec<(usize, usize)> = match order {
        WallOrder::ByBody => (0..bodies.len())
            .flat_map(|a| (0..walls.len()).map(move |w| (a, w)))
            .collect(),
        WallOrder::ByWall => (0..walls.len())
            .flat_map(|w| (0..bodies.len()).map(move |a| (a, w)))
            .collect(),
    };
    pairs
        .into_iter()
        .filter(|&(a, w)| formed(&walls[w], &bodies[a]))
        .map(|(a, w)| {
            let body = &bodies[a];
            let types = [TypeRef::Type(body.type_id), TypeRef::Wall];
            Ok(law(&walls[w], body)?.contact(a, Partner::Wall(w), types))
        })
        .collect()
}
