//! What the harness concludes: runs against the closed forms, the reference store and its
//! verification, the attribution of each code's difference, and the comparison, precision,
//! stability and sweep studies. Typed options in, typed summaries out; nothing here prints.

pub mod benchmark;
pub mod calibrate;
pub mod compare;
pub mod deck;
pub mod mill;
pub mod precision;
pub mod probe;
pub mod report;
pub mod run;
pub mod source;
pub(crate) mod stability;
pub mod store;
pub mod sweep;
pub(crate) mod tolerance;

/// `items` grouped by `key`, the groups in the order their keys first come, each group's items
/// in their order.
pub(crate) fn groups<'a, T, K: PartialEq>(
    items: impl IntoIterator<Item = &'a T>,
    key: impl Fn(&'a T) -> K,
) -> Vec<(K, Vec<&'a T>)> {
    let mut groups: Vec<(K, Vec<&T>)> = Vec::new();
    for item in items {
        let k = key(item);
        match groups.iter_mut().find(|(g, _)| *g == k) {
            Some((_, members)) => members.push(item),
            None => groups.push((k, vec![item])),
        }
    }
    groups
}
