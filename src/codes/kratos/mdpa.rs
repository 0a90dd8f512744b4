//! The `.mdpa` files of a Kratos DEM setup, as far as the deck reader needs them: the spheres'
//! nodes and nodal `RADIUS`, the sub-model parts with their elements and data (an inlet's
//! `RADIUS` and distribution).

use std::collections::BTreeMap;
use std::path::Path;

use crate::codes::deck::{DeckError, SourceLine};

/// The parts of a `.mdpa` file the check reads: the spheres' nodes and radii and the
/// sub-model parts with their elements and data.
#[derive(Debug, Default)]
pub(super) struct Mdpa {
    radius: BTreeMap<u64, f64>,
    element_node: BTreeMap<u64, u64>,
    pub(super) parts: BTreeMap<String, MdpaPart>,
}

/// A sub-model part: its elements, its data and the line it begins at.
#[derive(Debug, Default)]
pub(super) struct MdpaPart {
    elements: Vec<u64>,
    pub(super) data: BTreeMap<String, String>,
    pub(super) line: usize,
}

/// The blocks of an `.mdpa` whose lines the check reads.
#[derive(Clone, Debug, PartialEq)]
enum Block {
    Elements,
    Radius,
    Part(String),
    PartData(String),
    PartElements(String),
    Other,
}

impl Mdpa {
    /// Read the blocks the check needs from the file at `path`; a line in them that is not what
    /// Kratos writes there is refused with its line.
    pub(super) fn read(path: &Path) -> Result<Self, DeckError> {
        let text = std::fs::read_to_string(path).map_err(|source| DeckError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let mut mdpa = Mdpa::default();
        let mut stack: Vec<Block> = Vec::new();
        for (index, raw) in text.lines().enumerate() {
            let at = SourceLine {
                file: path.to_path_buf(),
                line: index + 1,
            };
            let line = raw.split("//").next().unwrap_or("").trim();
            let words: Vec<&str> = line.split_whitespace().collect();
            let id = |w: &str| -> Result<u64, DeckError> {
                w.parse()
                    .map_err(|_| at.refuse(format!("`{w}` is not an id"), "whole numbers"))
            };
            match words.as_slice() {
                [] => {}
                ["Begin", kind, rest @ ..] => {
                    let parent = stack.iter().rev().find_map(|b| match b {
                        Block::Part(name) => Some(name.clone()),
                        _ => None,
                    });
                    let block = match (*kind, rest.first()) {
                        ("Elements", _) => Block::Elements,
                        ("NodalData", Some(&"RADIUS")) => Block::Radius,
                        ("SubModelPart", Some(name)) => {
                            let full =
                                parent.map_or((*name).to_string(), |p| format!("{p}.{name}"));
                            mdpa.parts.entry(full.clone()).or_default().line = index + 1;
                            Block::Part(full)
                        }
                        ("SubModelPartData", _) => parent.map_or(Block::Other, Block::PartData),
                        ("SubModelPartElements", _) => {
                            parent.map_or(Block::Other, Block::PartElements)
                        }
                        _ => Block::Other,
                    };
                    stack.push(block);
                }
                ["End", ..] => {
                    stack.pop();
                }
                _ => match stack.last() {
                    Some(Block::Elements) => {
                        let node = words.get(2).ok_or_else(|| {
                            at.refuse(
                                format!("`{line}`: an element without its node"),
                                "ID PROPERTIES NODE",
                            )
                        })?;
                        mdpa.element_node.insert(id(words[0])?, id(node)?);
                    }
                    Some(Block::Radius) => {
                        let value = words
                            .last()
                            .and_then(|w| w.parse::<f64>().ok())
                            .filter(|r| *r > 0.0);
                        let value = value.ok_or_else(|| {
                            at.refuse(format!("`{line}`: no positive radius"), "NODE FIXED RADIUS")
                        })?;
                        mdpa.radius.insert(id(words[0])?, value);
                    }
                    Some(Block::PartData(part)) => {
                        let part = part.clone();
                        mdpa.parts
                            .entry(part)
                            .or_default()
                            .data
                            .insert(words[0].to_string(), words[1..].join(" "));
                    }
                    Some(Block::PartElements(part)) => {
                        let part = part.clone();
                        for w in &words {
                            let e = id(w)?;
                            mdpa.parts.entry(part.clone()).or_default().elements.push(e);
                        }
                    }
                    _ => {}
                },
            }
        }
        Ok(mdpa)
    }

    /// The radii of the spheres of `part` (a sub-model part's name below the root, or `None`
    /// for the whole file), each with how many spheres have it.
    pub(super) fn radii(
        &self,
        path: &Path,
        part: Option<&str>,
    ) -> Result<BTreeMap<u64, (f64, usize)>, DeckError> {
        let elements: Vec<u64> = match part {
            None => self.element_node.keys().copied().collect(),
            Some(name) => self
                .parts
                .iter()
                .filter(|(p, _)| *p == name || p.starts_with(&format!("{name}.")))
                .flat_map(|(_, p)| p.elements.iter().copied())
                .collect(),
        };
        let mut radii = BTreeMap::new();
        for e in elements {
            let radius = self
                .element_node
                .get(&e)
                .and_then(|n| self.radius.get(n))
                .ok_or_else(|| DeckError::Lacking {
                    file: path.to_path_buf(),
                    what: format!("element {e} has no nodal RADIUS"),
                    supported: "a `Begin NodalData RADIUS` block with every sphere's node".into(),
                })?;
            radii.entry(radius.to_bits()).or_insert((*radius, 0)).1 += 1;
        }
        Ok(radii)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mdpa_parts_radii_and_inlet_data_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("xDEM.mdpa");
        std::fs::write(
            &path,
            "Begin Properties 0\nEnd Properties\nBegin Nodes\n 1 0 0 0\n 2 1 0 0\n 3 2 0 0\nEnd Nodes\n\
Begin Elements SphericParticle3D // the balls\n 1 0 1\n 2 0 2\n 3 0 3\nEnd Elements\n\
Begin NodalData RADIUS\n 1 0 0.03\n 2 0 0.03\n 3 0 0.02\nEnd NodalData\n\
Begin SubModelPart Big\n Begin SubModelPartData\n  RADIUS 0.5\n End SubModelPartData\n Begin SubModelPartElements\n  1 2\n End SubModelPartElements\n\
 Begin SubModelPart Inner\n  Begin SubModelPartElements\n   3\n  End SubModelPartElements\n End SubModelPart\nEnd SubModelPart\n",
        )
        .unwrap();
        let m = Mdpa::read(&path).unwrap();
        let radii =
            |part| -> Vec<(f64, usize)> { m.radii(&path, part).unwrap().into_values().collect() };
        assert_eq!(radii(None).len(), 2);
        // A part holds its own elements and its sub-parts'.
        assert_eq!(radii(Some("Big")).iter().map(|r| r.1).sum::<usize>(), 3);
        assert_eq!(radii(Some("Big.Inner")), [(0.02, 1)]);
        assert_eq!(m.parts["Big"].data["RADIUS"], "0.5");
        assert_eq!(m.parts["Big.Inner"].line, 25);
    }
}
