//! A Kratos DEM materials file (`MaterialsDEM.json`) as the deck reader takes it, from the
//! typed records of `files.rs`: each material and each relation (two materials' contact
//! settings) with where it is in the file, the assignation table's model parts (particles,
//! inlets or walls, clusters left out), one material per id, and the relation of every pair of
//! materials that meet naming a law the check steps.

use std::collections::BTreeMap;
use std::path::Path;

use super::files::{
    self, LawName, MaterialId, MaterialRef, MaterialVariable, MaterialsFile, SteppedLaw,
};
use crate::codes::deck::{DeckError, DeckOptions, DeckSource};

/// The constitutive laws whose force the harness steps.
pub(crate) const LAWS: &str =
    "DEM_D_Hertz_viscous_Coulomb, DEM_D_Linear_viscous_Coulomb, DEM_D_Linear_Custom_Constants";

/// A field the check needs that is not in the file: where it belongs and what it must hold.
pub(super) fn missing(file: &Path, path: String, key: &str, supported: &str) -> DeckError {
    DeckError::unsupported(
        DeckSource::field(file, path),
        format!("no {key}"),
        supported,
    )
}

/// An entry of one of the materials file's lists and where it is: its file and its index in
/// the list.
#[derive(Debug)]
pub(super) struct Entry<'f, T> {
    pub(super) file: &'f Path,
    pub(super) index: usize,
    pub(super) typed: &'f T,
}

/// Each of `list` (of the file at `file`) with its index.
fn entries<'f, T>(file: &'f Path, list: &'f [T]) -> Vec<Entry<'f, T>> {
    let entry = |(index, typed)| Entry { file, index, typed };
    list.iter().enumerate().map(entry).collect()
}

/// A material of the materials file and where it is.
pub(super) type Material<'f> = Entry<'f, files::Material>;

/// A material relation (the contact settings of two materials) and where it is.
pub(super) type Relation<'f> = Entry<'f, files::Relation>;

impl Material<'_> {
    /// Its `material_id`.
    pub(super) fn id(&self) -> MaterialId {
        self.typed.material_id
    }

    /// Its id, with its `material_name` where it has one.
    pub(super) fn label(&self) -> String {
        match &self.typed.material_name {
            Some(n) => format!("{} ({n})", self.id()),
            None => self.id().to_string(),
        }
    }

    /// Where it is in the file.
    pub(super) fn at(&self) -> DeckSource {
        DeckSource::field(self.file, format!("materials[{}]", self.index))
    }

    /// Its variable `variable`, refused where missing, naming what is `supported`.
    pub(super) fn variable(
        &self,
        variable: MaterialVariable,
        supported: &str,
    ) -> Result<f64, DeckError> {
        self.typed.variables.get(variable).ok_or_else(|| {
            missing(
                self.file,
                format!("materials[{}].Variables.{}", self.index, variable.name()),
                variable.name(),
                supported,
            )
        })
    }
}

impl Relation<'_> {
    /// The two materials it relates.
    pub(super) fn ids(&self) -> [MaterialId; 2] {
        self.typed.material_ids_list
    }

    /// Where it is in the file.
    pub(super) fn at(&self) -> DeckSource {
        DeckSource::field(self.file, format!("material_relations[{}]", self.index))
    }

    /// Where its variable `key` is.
    pub(super) fn variable_path(&self, key: &str) -> String {
        format!("material_relations[{}].Variables.{key}", self.index)
    }

    /// The relation's constitutive law, if the harness steps it.
    pub(super) fn law(&self) -> Result<SteppedLaw, DeckError> {
        const KEY: &str = "DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME";
        match &self.typed.variables.law {
            Some(LawName::Stepped(law)) => Ok(*law),
            Some(LawName::Other(name)) => Err(DeckError::unsupported(
                DeckSource::field(self.file, self.variable_path(KEY)),
                format!("{name}, a law whose force the harness does not step"),
                LAWS,
            )),
            None => Err(missing(
                self.file,
                self.variable_path(KEY),
                KEY,
                &format!("a constitutive law: {LAWS}"),
            )),
        }
    }
}

/// Where a model part of the assignation table lives (clusters are left out before it is asked).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Root {
    Spheres,
    Inlet,
    Walls,
}

/// A model part of the assignation table: its name, where it lives, its entry's index.
#[derive(Clone, Debug)]
pub(super) struct Assigned {
    pub(super) name: String,
    pub(super) root: Root,
    pub(super) index: usize,
}

/// The materials file read: its materials and relations, each with where it is, and the model
/// parts each material is assigned to (particles or walls).
pub(super) struct MaterialsSetup<'f> {
    pub(super) path: &'f Path,
    pub(super) materials: Vec<Material<'f>>,
    pub(super) relations: Vec<Relation<'f>>,
    pub(super) assigned: BTreeMap<MaterialId, Vec<Assigned>>,
}

impl<'f> MaterialsSetup<'f> {
    /// Read `file` (at `path`): one material per id, every assignation naming a material and a
    /// model part the check knows (clusters are left out, with a line in `left_out`), and every
    /// relation of a pair that meets naming a law the check steps, before any size is looked
    /// for.
    pub(super) fn read(
        path: &'f Path,
        file: &'f MaterialsFile,
        left_out: &mut Vec<String>,
    ) -> Result<Self, DeckError> {
        let materials = entries(path, &file.materials);
        for (k, m) in materials.iter().enumerate() {
            if let Some(first) = materials[..k].iter().find(|o| o.id() == m.id()) {
                return Err(DeckError::unsupported(
                    DeckSource::field(path, format!("materials[{k}].material_id")),
                    format!("{}, which materials[{}] has already", m.id(), first.index),
                    "one material per material_id",
                ));
            }
        }
        let relations = entries(path, &file.material_relations);
        let assigned = assign_parts(path, file, &materials, left_out)?;
        let setup = MaterialsSetup {
            path,
            materials,
            relations,
            assigned,
        };
        let role = |id: MaterialId, wall: bool| {
            setup
                .assigned
                .get(&id)
                .is_some_and(|ps| ps.iter().any(|p| (p.root == Root::Walls) == wall))
        };
        for r in &setup.relations {
            let [a, b] = r.ids();
            if (role(a, false) && (role(b, false) || role(b, true)))
                || (role(b, false) && role(a, true))
            {
                r.law()?;
            }
        }
        Ok(setup)
    }

    /// The material of `id` (every assigned id has one: [`assign_parts`] checked it).
    pub(super) fn material(&self, id: MaterialId) -> &Material<'f> {
        self.materials
            .iter()
            .find(|m| m.id() == id)
            .expect("assigned materials exist")
    }

    /// The relation of the materials `a` and `b`, in either order.
    pub(super) fn relation(
        &self,
        a: MaterialId,
        b: MaterialId,
    ) -> Result<&Relation<'f>, DeckError> {
        self.relations
            .iter()
            .find(|r| r.ids() == [a, b] || r.ids() == [b, a])
            .ok_or_else(|| DeckError::Lacking {
                file: self.path.to_path_buf(),
                what: format!(
                    "no material_relations entry for the materials {} and {}",
                    self.material(a).label(),
                    self.material(b).label()
                ),
                supported: "a relation (law, COEFFICIENT_OF_RESTITUTION) for every pair of \
                            materials that meet, as Kratos needs"
                    .into(),
            })
    }

    /// Each `--particle` names a particle material, with the density Kratos forms its mass
    /// from.
    pub(super) fn check_given(&self, options: &DeckOptions) -> Result<(), DeckError> {
        for p in &options.particles {
            let parts = self.assigned.get(&p.type_id).filter(|ps| {
                ps.iter()
                    .any(|part| matches!(part.root, Root::Spheres | Root::Inlet))
            });
            if parts.is_none() {
                return Err(DeckError::Lacking {
                    file: self.path.to_path_buf(),
                    what: format!(
                        "--particle {}:{}:{}: material {} is assigned to no particles (SpheresPart, DEMInletPart)",
                        p.type_id, p.radius, p.density, p.type_id
                    ),
                    supported: "the material id of a particle material of the assignation table"
                        .into(),
                });
            }
            let material = self.material(p.type_id);
            let density =
                material.variable(MaterialVariable::ParticleDensity, "PARTICLE_DENSITY, kg/m³")?;
            #[allow(clippy::float_cmp)] // the density given must be the material's, bit for bit
            if p.density != density {
                return Err(DeckError::Lacking {
                    file: self.path.to_path_buf(),
                    what: format!(
                        "--particle {}:{}:{}: material {} has PARTICLE_DENSITY {density}, and Kratos forms the mass from it",
                        p.type_id,
                        p.radius,
                        p.density,
                        material.label()
                    ),
                    supported: format!("--particle {}:{}:{density}", p.type_id, p.radius),
                });
            }
        }
        Ok(())
    }
}

/// Which model parts are particles and which walls, each with its material: the assignation
/// table read, a material named by name or id, clusters left out with a line in `left_out`.
fn assign_parts(
    path: &Path,
    file: &MaterialsFile,
    materials: &[Material<'_>],
    left_out: &mut Vec<String>,
) -> Result<BTreeMap<MaterialId, Vec<Assigned>>, DeckError> {
    let parts_supported = "SpheresPart, DEMInletPart and RigidFacePart (ClusterPart is left out), or their sub-model parts";
    let mut assigned: BTreeMap<MaterialId, Vec<Assigned>> = BTreeMap::new();
    for (index, entry) in file.material_assignation_table.iter().enumerate() {
        let entry_at =
            |k: usize| DeckSource::field(path, format!("material_assignation_table[{index}][{k}]"));
        let material = match &entry.material {
            MaterialRef::Name(n) => materials
                .iter()
                .find(|m| m.typed.material_name.as_deref() == Some(n.as_str()))
                .map(Material::id)
                .ok_or_else(|| {
                    DeckError::unsupported(
                        entry_at(1),
                        format!("material `{n}` is in no material_name"),
                        "the name or id of a material of the file",
                    )
                })?,
            MaterialRef::Id(id) => *id,
        };
        if !materials.iter().any(|m| m.id() == material) {
            return Err(DeckError::unsupported(
                entry_at(1),
                format!("material {material} is in no material_id"),
                "the name or id of a material of the file",
            ));
        }
        let root = match entry.part.split('.').next().unwrap_or_default() {
            "SpheresPart" => Root::Spheres,
            "DEMInletPart" => Root::Inlet,
            "RigidFacePart" => Root::Walls,
            "ClusterPart" => {
                left_out.push(format!(
                    "clusters ({}, {}): particles of several spheres are not checked",
                    entry.part,
                    DeckSource::field(path, format!("material_assignation_table[{index}]"))
                ));
                continue;
            }
            other => {
                return Err(DeckError::unsupported(
                    entry_at(0),
                    format!("model part `{other}`"),
                    parts_supported,
                ));
            }
        };
        assigned.entry(material).or_default().push(Assigned {
            name: entry.part.clone(),
            root,
            index,
        });
    }
    Ok(assigned)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The laws named in messages are the ones the typed reader takes.
    #[test]
    fn the_laws_named_are_the_laws_read() {
        let names: Vec<&str> = SteppedLaw::ALL.iter().map(|l| l.name()).collect();
        assert_eq!(names.join(", "), LAWS);
    }
}
