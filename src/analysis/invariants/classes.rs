//! Topological classes (THEORY §13): the exact invariants of a structure — cardinality (cells per
//! level) and multiplicity (valences of the vertices of each level, and in the limit) — and the
//! comparison of two structures, stopping at the first invariant that differs.
//!
//! **How many levels decide.** For faces and assemblies with bounded valences, every count of the
//! level-k complex is a linear functional of a state that steps linearly (vertex types, edge
//! cells, face types, lacunas: [`Multiplicity::order`]), so it is a linear recurrence of order at
//! most d; the difference of two such sequences is a linear recurrence of order at most d_A + d_B,
//! and one that vanishes on d_A + d_B consecutive terms vanishes for ever. Comparing the first
//! d_A + d_B + 1 levels therefore decides equality at every level. The same holds for the piece
//! counts of an automaton (order: its number of states) and the cell counts of a volume (order:
//! its number of types, plus one for the lacunas). When a valence is unbounded the comparison
//! covers the levels compared only, and the result says so.
//!
//! **Automata** ([`super::automaton`]): the piece counts and seed 002's multiplicity, of order
//! the number of states when the automaton's distinct maps are proved free.

use crate::analysis::invariants::shares::{limit_shares, LimitShare, LimitShares};
use crate::error::{Error, Result};
use crate::topology::volume::{solid_topology_of, volume_counts, StartCells, VolumeTypeSet};
use crate::topology::{counts, multiplicity, Glue, LimitValence, Multiplicity, TypeSet};
use num_bigint::BigUint;
use serde::Serialize;
use std::collections::BTreeMap;

/// A named exact value.
pub type Named = (String, String);

/// The invariants of one structure, in the order `classify` compares them.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Invariants {
    /// The input's name.
    pub name: String,
    /// `faces`, `volume` or `automaton`.
    pub kind: &'static str,
    /// Per level from 0: cell counts (faces and lacunas; volumes' cells; automata's pieces).
    pub cardinality: Vec<Vec<Named>>,
    /// Per level from 0: the number of vertices of each valence (empty where not derived); for
    /// an automaton, seed 002's multiplicity (how many pieces are one exact map).
    pub multiplicity: Vec<Vec<Named>>,
    /// Per level from 0, for an automaton when asked: where its pieces meet at the images of
    /// fixed corners. Shown, never compared: which corners a map fixes depends on how the
    /// automaton is written (the Sierpinski triangle written on its corners has 6 such points
    /// at level 1, written on its centre and two corners 5).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub contacts: Vec<Vec<Named>>,
    /// Invariants of the limit (the valences that vertices settle at, or unbounded).
    pub limit: Vec<Named>,
    /// The limit share of each valence among the vertices of level k, as k grows (exact, or
    /// why it is not decided).
    pub limit_shares: LimitShares,
    /// The order bound of the linear recurrences (see the module doc), when there is one.
    pub order: Option<usize>,
    /// What was not derived, in words.
    pub notes: Vec<String>,
}

/// The first invariant on which two structures differ.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Difference {
    /// `kind`, `cardinality`, `multiplicity` or `limit`.
    pub group: &'static str,
    /// The invariant's name (`faces`, `vertices of valence 3`, …).
    pub invariant: String,
    /// The level, for per-level invariants.
    pub level: Option<u64>,
    /// The value for the first structure.
    pub a: String,
    /// The value for the second structure.
    pub b: String,
}

/// The answer of `classify`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Classification {
    /// Whether the two structures share every invariant compared.
    pub same_class: bool,
    /// The first invariant that differs.
    pub differs: Option<Difference>,
    /// The levels compared, 0 to this.
    pub levels: u64,
    /// Whether equality of the per-level invariants at the levels compared proves equality at
    /// every level (both order bounds known and enough levels compared).
    pub every_level: bool,
    /// What was not compared, in words.
    pub notes: Vec<String>,
}

/// The number of levels that decides the per-level invariants of both structures at every level
/// (`order_a + order_b`), when both have an order bound.
pub fn levels_needed(a: Option<usize>, b: Option<usize>) -> Option<u64> {
    Some((a? + b?) as u64)
}

/// The invariants of faces or an assembly (closed type set, shared edges) to `levels`.
pub fn face_invariants(
    name: &str,
    ts: &TypeSet,
    glue: &[Glue],
    levels: u64,
    max_types: usize,
) -> Result<(Invariants, Multiplicity)> {
    let m = multiplicity(ts, glue, levels, max_types)?;
    let c = counts(ts, levels);
    let cardinality = c
        .iter()
        .map(|l| {
            vec![
                ("faces".to_string(), l.faces.to_string()),
                ("lacunas".to_string(), l.lacunas.to_string()),
            ]
        })
        .collect();
    let multiplicity = m
        .levels
        .iter()
        .map(|l| {
            // The valences give the vertices (their sum) and the edges (half the degree sum).
            l.valences
                .iter()
                .map(|(val, k)| (format!("vertices of valence {val}"), k.clone()))
                .collect()
        })
        .collect();
    let limit = match &m.limit {
        LimitValence::Bounded {
            max_valence,
            valences,
        } => vec![
            ("largest valence".to_string(), max_valence.to_string()),
            (
                "valences of the limit".to_string(),
                valences
                    .iter()
                    .map(|v| v.to_string())
                    .collect::<Vec<_>>()
                    .join(", "),
            ),
        ],
        LimitValence::Unbounded { .. } => {
            vec![("largest valence".to_string(), "unbounded".to_string())]
        }
    };
    let inv = Invariants {
        name: name.to_string(),
        kind: "faces",
        cardinality,
        multiplicity,
        contacts: Vec::new(),
        limit,
        limit_shares: limit_shares(&m)?,
        order: m.order,
        notes: Vec::new(),
    };
    Ok((inv, m))
}

/// The invariants of a volume (or of volumes glued face to face, `start` their level-0 complex)
/// to `levels`: cells and lacunas per level, the cells of each dimension of the level-k solid,
/// and the multiplicity where the caller enumerated it: `valences[k]` gives, for each valence,
/// the corners of the level-k complex with that many edges (levels 0 to `valences.len() − 1`;
/// the geometry layer builds the complex). Those are checked against the exact counts: the
/// corners must number `corners` and their valences sum to twice `edges` of the level-k solid
/// (E1440 otherwise, a bug). The limit of a volume's valences is not decided.
pub fn volume_invariants(
    name: &str,
    set: &VolumeTypeSet,
    start: &StartCells,
    levels: u64,
    valences: &[BTreeMap<usize, u64>],
) -> Result<Invariants> {
    let c = volume_counts(set, levels);
    let solid = solid_topology_of(set, levels, start)?;
    let cardinality = c
        .iter()
        .zip(&solid)
        .map(|(l, s)| {
            vec![
                ("cells".to_string(), l.cells.to_string()),
                ("lacunas".to_string(), l.lacunas.to_string()),
                ("solid faces".to_string(), s.faces.to_string()),
                ("solid edges".to_string(), s.edges.to_string()),
                ("solid corners".to_string(), s.corners.to_string()),
            ]
        })
        .collect();
    let mut multiplicity = vec![Vec::new(); levels as usize + 1];
    for (k, (val, s)) in valences.iter().zip(&solid).enumerate() {
        let corners: u64 = val.values().sum();
        let degree: BigUint = val.iter().map(|(v, n)| BigUint::from(*n) * *v).sum();
        if BigUint::from(corners) != s.corners || degree != &s.edges * 2u32 {
            return Err(Error::Syntax(Box::new(crate::error::Diagnostic {
                code: "E1440",
                message: format!(
                    "the level-{k} complex of `{name}` has {corners} corners and a degree sum of {degree}, but the exact counts give {} corners and {} edges (a bug: please report it with the input)",
                    s.corners, s.edges
                ),
                span: None,
                source: None,
            })));
        }
        multiplicity[k] = val
            .iter()
            .map(|(v, n)| (format!("vertices of valence {v}"), n.to_string()))
            .collect();
    }
    let mut notes = Vec::new();
    if valences.len() as u64 <= levels {
        notes.push(if valences.is_empty() {
            "multiplicity (valences) of this volume is not derived".to_string()
        } else {
            format!(
                "volume valences: levels 0 to {} only, by building the level-k complex",
                valences.len() - 1
            )
        });
    }
    Ok(Invariants {
        name: name.to_string(),
        kind: "volume",
        cardinality,
        multiplicity,
        contacts: Vec::new(),
        limit: Vec::new(),
        limit_shares: LimitShares::NotDecided {
            reason: "the limit of a volume's valences is not decided by enumeration".into(),
        },
        // Cells and lacunas only: the solid's face, edge and corner counts have no order bound
        // here, so a volume's comparison covers the levels compared.
        order: None,
        notes,
    })
}

/// Compares two structures' invariants: kind, then cardinality level by level, then multiplicity
/// level by level, then the limit; the first that differs decides.
pub fn classify(a: &Invariants, b: &Invariants) -> Classification {
    let levels = a
        .cardinality
        .len()
        .min(b.cardinality.len())
        .saturating_sub(1) as u64;
    let needed = levels_needed(a.order, b.order);
    let mut notes: Vec<String> = a.notes.clone();
    for n in &b.notes {
        if !notes.contains(n) {
            notes.push(n.clone());
        }
    }
    let every_level = needed.is_some_and(|n| n <= levels);
    if !a.contacts.is_empty() && !b.contacts.is_empty() {
        let top = levels.min(a.contacts.len().min(b.contacts.len()) as u64 - 1);
        let first = (1..=top as usize)
            .find_map(|l| differ("contacts", Some(l as u64), &a.contacts[l], &b.contacts[l]));
        notes.push(match first {
            Some(d) => format!(
                "contacts at the images of fixed corners differ at level {}: {}: A has {}, B has {} (not a class invariant: which corners a map fixes depends on how each automaton is written)",
                d.level.unwrap_or(0),
                d.invariant,
                d.a,
                d.b
            ),
            None => format!("contacts at the images of fixed corners: equal at levels 1 to {top}"),
        });
    }
    let mut differs = first_difference(a, b, levels);
    if differs.is_none() {
        let (d, share_notes) = share_difference(&a.limit_shares, &b.limit_shares);
        differs = d;
        notes.extend(share_notes);
    }
    // A difference found is a difference at every level count; only an equality is partial.
    if !every_level && differs.is_none() {
        notes.push(format!(
            "the per-level invariants were compared at levels 0 to {levels} only{}",
            match needed {
                Some(n) => format!(" ({n} decide every level)"),
                None => String::from(
                    ": no recurrence order bound (unbounded valence, volume or automaton)"
                ),
            }
        ));
    }
    Classification {
        same_class: differs.is_none(),
        differs,
        levels,
        every_level,
        notes,
    }
}

fn first_difference(a: &Invariants, b: &Invariants, levels: u64) -> Option<Difference> {
    if a.kind != b.kind {
        return Some(Difference {
            group: "kind",
            invariant: "kind".into(),
            level: None,
            a: a.kind.into(),
            b: b.kind.into(),
        });
    }
    for (group, xa, xb) in [
        ("cardinality", &a.cardinality, &b.cardinality),
        ("multiplicity", &a.multiplicity, &b.multiplicity),
    ] {
        for level in 0..=levels as usize {
            if let Some(d) = differ(group, Some(level as u64), &xa[level], &xb[level]) {
                return Some(d);
            }
        }
    }
    differ("limit", None, &a.limit, &b.limit)
}

/// The first valence whose limit shares differ, and notes on what could not be compared exactly.
///
/// Shares in canonical form (rational or quadratic) are equal iff their strings are. Otherwise
/// certified decimals that differ prove a difference (both are truncations of the exact values
/// to the same number of digits), and equal decimals leave the question open: the note says so.
fn share_difference(a: &LimitShares, b: &LimitShares) -> (Option<Difference>, Vec<String>) {
    let lists = |s: &LimitShares| -> Option<(u64, Vec<Vec<LimitShare>>)> {
        match s {
            LimitShares::Exact { shares } => Some((1, vec![shares.clone()])),
            LimitShares::NoLimit { period, residues } => Some((*period, residues.clone())),
            LimitShares::NotDecided { .. } => None,
        }
    };
    let (Some((pa, ra)), Some((pb, rb))) = (lists(a), lists(b)) else {
        let why = [a, b]
            .iter()
            .find_map(|s| match s {
                LimitShares::NotDecided { reason } => Some(reason.clone()),
                _ => None,
            })
            .unwrap_or_default();
        return (None, vec![format!("limit shares not compared: {why}")]);
    };
    let shape = |p: u64| {
        if p == 1 {
            "a limit".to_string()
        } else {
            format!("no limit (period {p})")
        }
    };
    if pa != pb {
        return (
            Some(Difference {
                group: "limit",
                invariant: "limit shares of the valences".into(),
                level: None,
                a: shape(pa),
                b: shape(pb),
            }),
            Vec::new(),
        );
    }
    let mut notes = Vec::new();
    for (r, (sa, sb)) in ra.iter().zip(&rb).enumerate() {
        let mut valences: Vec<usize> = sa.iter().chain(sb).map(|x| x.valence).collect();
        valences.sort_unstable();
        valences.dedup();
        let zero = |v: usize| LimitShare {
            valence: v,
            share: "0".into(),
            decimal: String::new(),
            canonical: true,
        };
        for v in valences {
            let get = |s: &[LimitShare]| {
                s.iter()
                    .find(|x| x.valence == v)
                    .cloned()
                    .unwrap_or_else(|| zero(v))
            };
            let (xa, xb) = (get(sa), get(sb));
            let name = if pa == 1 {
                format!("limit share of valence {v}")
            } else {
                format!("limit share of valence {v} at levels {r} mod {pa}")
            };
            let differ = if xa.canonical && xb.canonical {
                xa.share != xb.share
            } else if xa.decimal.is_empty() || xb.decimal.is_empty() {
                // One side has no vertex of this valence at all (share 0), the other a share
                // that is not rational: an irrational is not 0.
                true
            } else if xa.decimal != xb.decimal {
                true
            } else {
                notes.push(format!(
                    "{name}: equal to {} digits, not decided exactly (different number fields)",
                    xa.decimal.len()
                ));
                false
            };
            if differ {
                return (
                    Some(Difference {
                        group: "limit",
                        invariant: name,
                        level: None,
                        a: xa.share,
                        b: xb.share,
                    }),
                    notes,
                );
            }
        }
    }
    (None, notes)
}

/// The first name whose values differ between two lists (a name missing on one side reads 0).
fn differ(group: &'static str, level: Option<u64>, a: &[Named], b: &[Named]) -> Option<Difference> {
    let get = |l: &[Named], k: &str| {
        l.iter()
            .find(|(n, _)| n == k)
            .map_or_else(|| "0".to_string(), |(_, v)| v.clone())
    };
    let mut names: Vec<&String> = a.iter().map(|(n, _)| n).collect();
    for (n, _) in b {
        if !names.contains(&n) {
            names.push(n);
        }
    }
    for n in names {
        let (va, vb) = (get(a, n), get(b, n));
        if va != vb {
            return Some(Difference {
                group,
                invariant: n.clone(),
                level,
                a: va,
                b: vb,
            });
        }
    }
    None
}

/// The level count for comparing two face structures: the requested levels, or the levels that
/// decide every level when that is more, as long as it stays within `max_level` (a limit error
/// beyond, never a verdict).
pub fn levels_for(
    requested: u64,
    order_a: Option<usize>,
    order_b: Option<usize>,
    max_level: u64,
) -> Result<u64> {
    match levels_needed(order_a, order_b) {
        Some(n) if n > requested => {
            if n > max_level {
                return Err(Error::limit(
                    "the number of levels that decides every level",
                    n,
                    max_level,
                    "--max-level",
                ));
            }
            Ok(n)
        }
        _ => Ok(requested),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::{close_or_error, Face, Limits};

    fn inv(text: &str, levels: u64) -> Invariants {
        let ts = close_or_error(&[Face::parse(text).unwrap()], &Limits::default()).unwrap();
        face_invariants(text, &ts, &[], levels, 10_000).unwrap().0
    }

    #[test]
    fn the_same_face_twice_is_one_class() {
        let a = inv("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1", 4);
        let c = classify(&a, &a.clone());
        assert!(c.same_class);
        assert_eq!(c.differs, None);
    }

    #[test]
    fn different_face_counts_differ_in_cardinality_at_level_1() {
        // F0 splits into 6 faces, the B2 square into 4 (THEORY §5, count.rs tests).
        let a = inv("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1", 2);
        let b = inv("B2 B2 B2 B2 | B2 B2 B2 | A1", 2);
        let d = classify(&a, &b).differs.unwrap();
        assert_eq!(
            (d.group, d.invariant.as_str(), d.level),
            ("cardinality", "faces", Some(1))
        );
        assert_eq!((d.a.as_str(), d.b.as_str()), ("6", "4"));
    }

    #[test]
    fn equal_counts_different_multiplicity() {
        // P = `B2 B2 C2 | B2 B2 B2 | {joint corner}` and Q = `B2 B2^2 C2 | B2 B2 B2 | A2`.
        // Level 1 by hand. P: spokes at its 2 joints and 3 corners (not at the C2 gap): 5
        // sub-faces, lacunas 1 + 1/2 (the gap) = 3/2. Q: spokes at the B2 joint, the C2 gap and
        // the 3 corners (the delayed B2^2 has no joint yet): 5 sub-faces, lacunas 3/2.
        // Valences of P: 3 corners (two pieces and a spoke) 3, 2 joints 3, 5 lacuna corners 3;
        // the gap has no spoke, so its two ends (a piece, an Ec, the outside) and its middle (two
        // Ec and the outside) have valence 2: {2: 3, 3: 10}. Q: corners 3, the joint 3, lacuna
        // corners 3, the gap's middle (two Ec and a spoke) 3, its two ends 2: {2: 2, 3: 10}.
        let p = inv("B2 B2 C2 | B2 B2 B2 | {joint corner}", 3);
        let q = inv("B2 B2^2 C2 | B2 B2 B2 | A2", 3);
        assert_eq!(p.cardinality[1], q.cardinality[1]);
        assert_eq!(p.cardinality[1][0].1, "5");
        assert_eq!(p.cardinality[1][1].1, "3/2");
        let c = classify(&p, &q);
        assert!(!c.same_class);
        let d = c.differs.unwrap();
        assert_eq!(
            (
                d.group,
                d.invariant.as_str(),
                d.level,
                d.a.as_str(),
                d.b.as_str()
            ),
            ("multiplicity", "vertices of valence 2", Some(1), "3", "2")
        );
        // Corner spokes: both valences unbounded, so the verdict covers the levels compared.
        assert!(!c.every_level);
    }

    #[test]
    fn equal_counts_at_every_level_different_multiplicity() {
        // Q = `B2 B2 B2 C2 | B2 B2 B2 | {joint}` and T = `B2 B2 C2 | B2 B2 B2 | A1`. Level 1 by
        // hand: Q has spokes at its 3 joints (none at the C2 gap), T at its 2 joints and its gap:
        // 3 sub-faces each, and 1 + 1/2 = 3/2 lacunas each. Neither puts a spoke at a corner, so
        // both have bounded valences and order bounds: their cardinality agrees on the levels that
        // decide every level. But Q has 4 corners and T 3: level 0 has 4 vertices of valence 2
        // against 3.
        let q = inv("B2 B2 B2 C2 | B2 B2 B2 | {joint}", 1);
        let t = inv("B2 B2 C2 | B2 B2 B2 | A1", 1);
        assert_eq!(q.cardinality[1][0].1, "3");
        assert_eq!(q.cardinality[1][1].1, "3/2");
        let l = levels_for(1, q.order, t.order, 1000).unwrap();
        let q = inv("B2 B2 B2 C2 | B2 B2 B2 | {joint}", l);
        let t = inv("B2 B2 C2 | B2 B2 B2 | A1", l);
        assert_eq!(q.cardinality, t.cardinality, "equal counts at every level");
        let c = classify(&q, &t);
        assert!(c.every_level);
        let d = c.differs.unwrap();
        assert_eq!(
            (
                d.group,
                d.invariant.as_str(),
                d.level,
                d.a.as_str(),
                d.b.as_str()
            ),
            ("multiplicity", "vertices of valence 2", Some(0), "4", "3")
        );
    }

    #[test]
    fn different_faces_with_equal_invariants_are_one_class() {
        // `B2 C2 B2 C2 | C2 B2 B2 | A1` and `B2 B2 C2 C2 | C2 B2 B2 | A1`: A1 puts no spoke at a
        // corner, so each face has 2 joints and 2 gaps: 4 spokes, 4 sub-faces, and contributes
        // 1 + 2·1/2 = 2 lacunas. Level 1, by hand, for both: 4 corners of valence 2; 2 joints
        // (two pieces and a spoke) 3; 2 gaps with a spoke: the ends 2, the middle 3; 4 lacuna
        // corners 3: {2: 8, 3: 8}. The valences stay bounded (no corner spoke), so the
        // comparison at the levels of both order bounds decides every level.
        let a = inv("B2 C2 B2 C2 | C2 B2 B2 | A1", 1);
        let b = inv("B2 B2 C2 C2 | C2 B2 B2 | A1", 1);
        let want: Vec<Named> = vec![
            ("vertices of valence 2".into(), "8".into()),
            ("vertices of valence 3".into(), "8".into()),
        ];
        assert_eq!(a.multiplicity[1], want);
        assert_eq!(b.multiplicity[1], want);
        let l = levels_for(1, a.order, b.order, 1000).unwrap();
        let a = inv("B2 C2 B2 C2 | C2 B2 B2 | A1", l);
        let b = inv("B2 B2 C2 C2 | C2 B2 B2 | A1", l);
        let c = classify(&a, &b);
        assert_eq!(c.differs, None);
        assert!(c.same_class && c.every_level);
    }

    #[test]
    fn equal_levels_different_limit_shares() {
        // The square `B2 B2 B2 B2 | B2 B2 B2 | A1` and the same square with lacuna sides El = C2.
        // Level 1 is the same for both: 4 pentagons around a 4-sided lacuna (the C2 sides' gaps
        // open only at level 2), 4 corners of valence 2, 4 joints and 4 lacuna corners of
        // valence 3; both have limit valences 2, 3, 4. The limit shares differ: in the square
        // only its 4 corners ever have valence 2, share 0 (analysis::shares derives 0, 4/5,
        // 1/5); with El = C2 every lacuna side opens a gap towards the hole, and both gap ends
        // have a sub-face and the hole, valence 2, one per lacuna side, as many as the faces up
        // to a constant: a share strictly between 0 and 1.
        let a = inv("B2 B2 B2 B2 | B2 C2 B2 | A1", 1);
        let b = inv("B2 B2 B2 B2 | B2 B2 B2 | A1", 1);
        assert_eq!(a.cardinality, b.cardinality);
        assert_eq!(a.multiplicity, b.multiplicity);
        assert_eq!(a.limit, b.limit);
        let c = classify(&a, &b);
        let d = c.differs.expect("the limit shares differ");
        assert_eq!(
            (d.group, d.invariant.as_str(), d.b.as_str()),
            ("limit", "limit share of valence 2", "0")
        );
        let LimitShares::Exact { shares } = &a.limit_shares else {
            panic!("{:?}", a.limit_shares)
        };
        let x: f64 = shares[0].decimal.parse().unwrap();
        assert!(
            shares[0].valence == 2 && x > 0.0 && x < 1.0,
            "{:?}",
            shares[0]
        );
    }
}
