//! One breadth-first closure of types under subdivision, for faces and volumes alike (THEORY §4,
//! §10).
//!
//! A type is anything [`Closable`]: a canonical value with one subdivision step whose children
//! are canonical values of the same kind, and a size held to `--max-boundary`. [`close_types`]
//! numbers the types in the order they are first met (the start types first, in the order
//! given), builds every type's step and child list (one entry per child, so a child met twice
//! counts twice), and stops at the first new type that breaks a limit: `--max-boundary` on its
//! size, then `--max-types` on the number of types. Such a stop is a [`Runaway`] with the chain of
//! types that led to it, unless the caller has proved the closure finite and turns it into a
//! limit error instead. What a kind refuses before the work is refused by its own
//! [`Closable::step`], before the step is built.

use crate::error::{Error, Result};
use crate::topology::limits::Limits;
use serde::Serialize;
use std::collections::HashMap;
use std::fmt::Display;
use std::hash::Hash;

/// A type closed under subdivision: a face or a volume, in canonical form (two values are the
/// same type exactly when they are equal).
pub trait Closable: Clone + Eq + Hash + Display {
    /// One subdivision step of a type, holding its children.
    type Step;

    /// What the types are called in a runaway's reason (`face`, `volume`).
    const NOUN: &'static str;

    /// The size held to `--max-boundary`: the edges of a face's boundary, the faces of a
    /// volume's surface.
    fn size(&self) -> usize;

    /// The reason of a runaway whose new type has `size`, above `limit` (`--max-boundary`).
    fn size_reason(size: usize, limit: usize) -> String;

    /// The subdivision step of this type; what the limits refuse before the work is refused
    /// here, before the step is built.
    fn step(&self, limits: &Limits) -> Result<Self::Step>;

    /// The children of a step, in order, each in canonical form.
    fn children(step: &Self::Step) -> Vec<&Self>;
}

/// A closure that did not close within the limits: the chain of types from a start face to the
/// type that broke a limit.
#[derive(Clone, Debug, Serialize)]
pub struct Runaway {
    /// The limit that was hit.
    pub reason: String,
    /// The witness chain: each face is a sub-face of the previous one.
    pub witness: Vec<String>,
}

impl Runaway {
    /// The runaway whose witness ends with `last`, the new type that broke the limit, found in
    /// the subdivision of type `from`; `link(t)` gives type t's name and its parent.
    pub(crate) fn chain(
        reason: String,
        last: String,
        from: usize,
        link: impl Fn(usize) -> (String, Option<usize>),
    ) -> Self {
        let mut witness = vec![last];
        let mut cur = Some(from);
        while let Some(c) = cur {
            let (name, parent) = link(c);
            witness.push(name);
            cur = parent;
        }
        witness.reverse();
        Runaway { reason, witness }
    }
}

/// The limit a new type met (the size is checked first).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitMet {
    /// Its size is above `--max-boundary`.
    Size(usize),
    /// It would be a type beyond `--max-types`; the number of types already built.
    Types(usize),
}

/// One type of a closed set.
pub struct Node<T: Closable> {
    /// The type, in canonical form.
    pub item: T,
    /// Its subdivision step.
    pub step: T::Step,
    /// The type index of each child, aligned with [`Closable::children`] of the step.
    pub children: Vec<usize>,
    /// The type through which it was first reached (`None` for a start type).
    pub parent: Option<usize>,
}

/// The outcome of [`close_types`].
pub enum Outcome<T: Closable> {
    /// Every child's type is in the set: the types in the order they were met, and the type
    /// index of each start value.
    Closed(Vec<Node<T>>, Vec<usize>),
    /// A new type broke a limit.
    Runaway(Runaway),
}

/// Closes the canonical `start` values under subdivision, breadth first.
///
/// `proved(met)` is asked when a new type meets a limit: `Some(error)` when the caller has proved
/// the closure finite (the limit is then a resource bound, and the error is returned), `None` for
/// a runaway.
pub fn close_types<T: Closable>(
    start: impl IntoIterator<Item = T>,
    limits: &Limits,
    proved: impl Fn(LimitMet) -> Option<Error>,
) -> Result<Outcome<T>> {
    let mut items: Vec<T> = Vec::new();
    let mut parents: Vec<Option<usize>> = Vec::new();
    let mut index: HashMap<T, usize> = HashMap::new();
    let mut start_idx = Vec::new();
    for c in start {
        let id = *index.entry(c).or_insert_with_key(|c| {
            items.push(c.clone());
            parents.push(None);
            items.len() - 1
        });
        start_idx.push(id);
    }
    // The queue: every type is queued once, when it is numbered, so the queue is the types in
    // index order and type `steps.len()` is the next one to subdivide.
    let mut steps: Vec<T::Step> = Vec::new();
    let mut child_lists: Vec<Vec<usize>> = Vec::new();
    while steps.len() < items.len() {
        let t = steps.len();
        let step = items[t].step(limits)?;
        let subs = T::children(&step);
        let mut children = Vec::with_capacity(subs.len());
        for s in subs {
            if let Some(&id) = index.get(s) {
                children.push(id);
                continue;
            }
            let id = items.len();
            let size = s.size();
            let met = if size > limits.max_boundary {
                Some(LimitMet::Size(size))
            } else if id >= limits.max_types {
                Some(LimitMet::Types(id))
            } else {
                None
            };
            if let Some(met) = met {
                if let Some(e) = proved(met) {
                    return Err(e);
                }
                let reason = match met {
                    LimitMet::Size(size) => T::size_reason(size, limits.max_boundary),
                    LimitMet::Types(_) => format!(
                        "more than {} {} types (--max-types)",
                        limits.max_types,
                        T::NOUN
                    ),
                };
                return Ok(Outcome::Runaway(Runaway::chain(
                    reason,
                    s.to_string(),
                    t,
                    |c| (items[c].to_string(), parents[c]),
                )));
            }
            index.insert(s.clone(), id);
            items.push(s.clone());
            parents.push(Some(t));
            children.push(id);
        }
        steps.push(step);
        child_lists.push(children);
    }
    let types = items
        .into_iter()
        .zip(steps)
        .zip(child_lists)
        .zip(parents)
        .map(|(((item, step), children), parent)| Node {
            item,
            step,
            children,
            parent,
        })
        .collect();
    Ok(Outcome::Closed(types, start_idx))
}
