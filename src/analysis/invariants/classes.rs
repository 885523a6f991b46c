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
//! **Automata.** The multiplicity of an automaton is read from its exact operators where that is
//! decidable: the corners of a state that one of its sub-operators fixes are points of the
//! attractor; their images under the sub-operators of the start state are the level-1 vertices,
//! and the number of distinct pieces whose images coincide exactly is the multiplicity there (the
//! dyadic point of a curve is where two pieces meet). Pieces that meet at points that are not such
//! images (overlaps, tangencies inside a piece) are not seen: the report says "level 1, at the
//! images of fixed corners" and no more.

use crate::algebra::{FieldElement, KMatrix};
use crate::analysis::invariants::shares::{limit_shares, LimitShare, LimitShares};
use crate::constraint::OpKind;
use crate::error::{Error, Result};
use crate::input::AutomatonModel;
use crate::topology::volume::{solid_topology_of, volume_counts, StartCells, VolumeTypeSet};
use crate::topology::{counts, multiplicity, Glue, LimitValence, Multiplicity, TypeSet};
use num_bigint::BigUint;
use num_rational::BigRational;
use num_traits::Zero;
use serde::Serialize;
use std::collections::{BTreeMap, HashMap};

use crate::analysis::automata::automaton_resolve::Resolved;

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

/// What [`automaton_invariants`] reads besides seed 002's multiplicity, which it always compares.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AutomatonMultiplicity {
    /// Also where pieces meet: how many pieces share each image of a fixed corner (module doc),
    /// shown and never compared.
    Contacts,
    /// Seed 002's (eq. (18)) only: how many pieces of a level are the same map — the points a
    /// curve defines more than once, `L_r` times — whatever the pieces touch.
    #[default]
    Coincidences,
}

/// The invariants of an automaton with its resolved operators: pieces per level from the start
/// state, and seed 002's multiplicity of levels 1 and on — at every level when the distinct maps
/// are proved free ([`free_reduction`], within `max_products` products for the contraction),
/// else by enumeration — and, when `how` asks, the contacts at the images of fixed corners.
pub fn automaton_invariants(
    name: &str,
    model: &AutomatonModel,
    resolved: &Resolved,
    levels: u64,
    how: AutomatonMultiplicity,
    max_products: usize,
) -> Result<Invariants> {
    let a = &model.automaton;
    let n = a.states.len();
    let subs: Vec<usize> = (0..a.operators.len())
        .filter(|&o| a.operators[o].kind == OpKind::Sub)
        .collect();
    let mut v = vec![BigUint::zero(); n];
    v[model.start] = BigUint::from(1u32);
    let mut cardinality = Vec::new();
    for level in 0..=levels {
        let total: BigUint = v.iter().sum();
        cardinality.push(vec![("pieces".to_string(), total.to_string())]);
        if level == levels {
            break;
        }
        let mut next = vec![BigUint::zero(); n];
        for &o in &subs {
            let op = &a.operators[o];
            next[op.from] += &v[op.to];
        }
        v = next;
    }
    // Seed 002's multiplicity: at every level when the distinct maps are proved free (module
    // doc), else enumerated while a level is small enough.
    let (coincidences, order, mut notes) = match free_reduction(
        model,
        resolved,
        &subs,
        max_products,
    )? {
        Ok(free) => {
            let rows = free_levels(model, &free, levels);
            let note = format!(
                "{name}: seed 002's multiplicity (the pieces of a level that are one exact map, eq. (18)) decided at every level: its {} distinct maps satisfy the open-set condition ({}), so no two different words of them are one map, and each count of level k is a linear recurrence of order {} (its states)",
                free.ops.len(),
                free.criterion,
                model.automaton.states.len()
            );
            (rows, Some(model.automaton.states.len()), vec![note])
        }
        Err(why) => {
            let (per_level, cut) = multiplicities(
                model,
                resolved,
                &subs,
                levels,
                MAX_CONTACT_PIECES,
                AutomatonMultiplicity::Coincidences,
            )?;
            let rows = rows_of(&per_level, "distinct maps", "maps of {m} pieces");
            let mut notes = vec![format!(
                "{name}: seed 002's multiplicity (the pieces of a level that are one exact map, eq. (18)) enumerated at levels 1 to {}; deeper coincidences and the limit are not decided: {why}",
                per_level.len()
            )];
            notes.extend(cut);
            (rows, None, notes)
        }
    };
    let mut multiplicity = vec![Vec::new(); levels as usize + 1];
    for (i, row) in coincidences.into_iter().enumerate() {
        multiplicity[i + 1] = row;
    }
    let mut contacts = Vec::new();
    if how == AutomatonMultiplicity::Contacts {
        let (per_level, cut) =
            multiplicities(model, resolved, &subs, levels, MAX_CONTACT_PIECES, how)?;
        contacts = vec![Vec::new(); levels as usize + 1];
        for (i, row) in rows_of(
            &per_level,
            "fixed-corner images",
            "points where {m} pieces meet",
        )
        .into_iter()
        .enumerate()
        {
            contacts[i + 1] = row;
        }
        notes.push(format!(
            "{name}: contacts at the exact images of fixed corners counted at levels 1 to {} (shown, not compared)",
            per_level.len()
        ));
        notes.extend(cut);
    }
    Ok(Invariants {
        name: name.to_string(),
        kind: "automaton",
        cardinality,
        multiplicity,
        contacts,
        limit: Vec::new(),
        limit_shares: LimitShares::NotDecided {
            reason: "the valences of an automaton's levels are not derived".into(),
        },
        order,
        notes,
    })
}

/// One row of named counts per level: the total under `total`, and how many are of each size
/// m under `each` (`{m}` replaced).
fn rows_of(per_level: &[Contacts], total: &str, each: &str) -> Vec<Vec<Named>> {
    per_level
        .iter()
        .map(|(hist, points)| {
            let mut row = vec![(total.to_string(), points.to_string())];
            row.extend(
                hist.iter()
                    .map(|(m, k)| (each.replace("{m}", &m.to_string()), k.to_string())),
            );
            row
        })
        .collect()
}

/// An automaton's sub-operators with equal maps merged, proved free: no two different words of
/// the merged maps (of one length, from the start state) are one map.
#[derive(Clone, Debug)]
struct FreeReduction {
    /// Each distinct map: an operator that has it, and how many sub-operators have it (same
    /// states, equal exact matrix).
    ops: Vec<(usize, u64)>,
    /// The open-set criterion that proved it.
    criterion: String,
}

/// Merges the sub-operators with one map (same states, equal exact matrix) and proves the
/// merged system free, or says why it is not proved (the inner `Err`).
///
/// **Why the open-set condition proves it.** Let the merged system be contracting with open
/// sets `U_s ≠ ∅`, `f_o(U_from) ⊂ U_to` and, for two different operators into one state,
/// disjoint images. Two different words u, v of one length from the start state first differ
/// at some letter; below that letter their pieces lie in disjoint images, so
/// `f_u(U) ∩ f_v(U) = ∅` and, both being non-empty, `f_u ≠ f_v` (a word ending in another state
/// is another piece anyway). Every state reached must lie in the one cyclic part whose
/// condition is proved, so that the condition covers every operator a word can use.
fn free_reduction(
    model: &AutomatonModel,
    resolved: &Resolved,
    subs: &[usize],
    max_products: usize,
) -> Result<std::result::Result<FreeReduction, String>> {
    let a = &model.automaton;
    let mut ops: Vec<(usize, u64)> = Vec::new();
    for &o in subs {
        let op = &a.operators[o];
        let same = ops.iter_mut().find(|(r, _)| {
            let rep = &a.operators[*r];
            rep.from == op.from && rep.to == op.to && resolved.ops[*r] == resolved.ops[o]
        });
        match same {
            Some((_, w)) => *w += 1,
            None => ops.push((o, 1)),
        }
    }
    // The merged automaton: its sub-operators only, each distinct map once.
    let mut reduced = model.clone();
    reduced.automaton.operators = ops.iter().map(|&(o, _)| a.operators[o].clone()).collect();
    reduced.automaton.constraints.clear();
    reduced.automaton.barycentric = (0..ops.len())
        .filter(|&i| a.barycentric.contains(&ops[i].0))
        .collect();
    reduced.kvalues = ops
        .iter()
        .map(|&(o, _)| model.kvalues.get(o).cloned().flatten())
        .collect();
    reduced.field_ops = (0..ops.len())
        .filter(|&i| model.field_ops.contains(&ops[i].0))
        .collect();
    let matrices: Vec<KMatrix> = ops.iter().map(|&(o, _)| resolved.ops[o].clone()).collect();
    match crate::analysis::check_contraction_within(&reduced, &matrices, max_products) {
        Ok(_) => {}
        Err(e) if e.code().starts_with("E07") => {
            return Ok(Err(format!("the contraction is not proved ({e})")))
        }
        Err(e) => return Err(e),
    }
    let parts = crate::analysis::similarity::cyclic_parts(&reduced);
    let reach = crate::analysis::contraction::reachable(&reduced);
    let reached = reach.iter().filter(|&&r| r).count();
    if parts.len() != 1 || parts[0].len() != reached {
        return Ok(Err(
            "the states reached are not one strongly connected part".to_string(),
        ));
    }
    let sim = match crate::analysis::similarity_dimension(&reduced, &matrices, 4) {
        Ok(sim) => sim,
        Err(why) => {
            return Ok(Err(format!(
                "no open-set analysis of the distinct maps: {why}"
            )))
        }
    };
    if !sim.open_set_witnessed() {
        return Ok(Err(format!(
            "the open-set condition of the distinct maps is not proved: {}",
            sim.open_set
        )));
    }
    Ok(Ok(FreeReduction {
        ops,
        criterion: sim.open_set,
    }))
}

/// Seed 002's multiplicity at levels 1 to `levels` of a free reduction: a map of level k is one
/// word of the distinct maps, and the pieces that are that map number the product of its
/// letters' counts. Counted state by state (how many words end in each state with each
/// product), so the levels cost no enumeration of pieces.
fn free_levels(model: &AutomatonModel, free: &FreeReduction, levels: u64) -> Vec<Vec<Named>> {
    let a = &model.automaton;
    let mut words: Vec<BTreeMap<BigUint, BigUint>> = vec![BTreeMap::new(); a.states.len()];
    words[model.start].insert(BigUint::from(1u32), BigUint::from(1u32));
    let mut rows = Vec::new();
    for _ in 1..=levels {
        let mut next: Vec<BTreeMap<BigUint, BigUint>> = vec![BTreeMap::new(); a.states.len()];
        for &(o, w) in &free.ops {
            let op = &a.operators[o];
            for (m, c) in &words[op.to] {
                *next[op.from].entry(m * w).or_insert_with(BigUint::zero) += c;
            }
        }
        words = next;
        let mut hist: BTreeMap<BigUint, BigUint> = BTreeMap::new();
        for per_state in &words {
            for (m, c) in per_state {
                *hist.entry(m.clone()).or_insert_with(BigUint::zero) += c;
            }
        }
        let total: BigUint = hist.values().sum();
        let mut row = vec![("distinct maps".to_string(), total.to_string())];
        row.extend(
            hist.iter()
                .map(|(m, k)| (format!("maps of {m} pieces"), k.to_string())),
        );
        rows.push(row);
    }
    rows
}

/// The contacts of one level: for each number m of pieces, the points where exactly m meet; and
/// the number of points.
type Contacts = (BTreeMap<usize, u64>, usize);

/// The pieces of one level an automaton's contacts are enumerated for, at most.
pub const MAX_CONTACT_PIECES: usize = 4096;

/// The multiplicity of an automaton's start state at levels 1 to `levels`, read as `how` says.
///
/// A piece of level k is a word `o_1 … o_k` of sub-operators chained from the start state, with
/// the exact map `M_{o_1} ⋯ M_{o_k}`. For each level, for each number m, how many:
/// - `Contacts`: points have exactly m pieces meeting there (a piece's points are the images of
///   the corners of its last state that one of that state's own sub-operators fixes: points of
///   the attractor), and the number of points looked at;
/// - `Coincidences` (seed 002, eq. (18)): distinct exact maps (with their state) exactly m pieces
///   of the level are, and the number of distinct maps — two pieces with one map are the same
///   points of the attractor at every depth, the paper's point "defined L times" by its curve.
///
/// Levels whose pieces number more than `max_pieces` are not enumerated (the note says so).
fn multiplicities(
    model: &AutomatonModel,
    resolved: &Resolved,
    subs: &[usize],
    levels: u64,
    max_pieces: usize,
    how: AutomatonMultiplicity,
) -> Result<(Vec<Contacts>, Option<String>)> {
    let limits = (levels, max_pieces);
    match how {
        AutomatonMultiplicity::Contacts => {
            let fixed = fixed_corners(model, resolved, subs);
            let dim0 = model.automaton.states[model.start].dim;
            per_level(model, resolved, subs, limits, "contacts", |pieces| {
                let mut at: HashMap<Vec<FieldElement>, Vec<usize>> = HashMap::new();
                for (w, (m, s)) in pieces.iter().enumerate() {
                    for &j in &fixed[*s] {
                        let col: Vec<FieldElement> =
                            (0..dim0).map(|r| m.get(r, j).clone()).collect();
                        let meeting = at.entry(col).or_default();
                        if !meeting.contains(&w) {
                            meeting.push(w);
                        }
                    }
                }
                (histogram(at.values().map(Vec::len)), at.len())
            })
        }
        AutomatonMultiplicity::Coincidences => {
            per_level(model, resolved, subs, limits, "coincidences", |pieces| {
                let mut maps: HashMap<(usize, &[FieldElement]), u64> = HashMap::new();
                for (m, s) in pieces {
                    *maps.entry((*s, m.data.as_slice())).or_default() += 1;
                }
                (histogram(maps.values().map(|&n| n as usize)), maps.len())
            })
        }
    }
}

/// For each size m, how many of `sizes` are m.
fn histogram(sizes: impl Iterator<Item = usize>) -> BTreeMap<usize, u64> {
    let mut hist = BTreeMap::new();
    for m in sizes {
        *hist.entry(m).or_default() += 1;
    }
    hist
}

/// The pieces of the start state level by level, from 1 to `levels`, each level measured by
/// `measure`; levels whose pieces number more than `max_pieces` are not enumerated (the note
/// says so, naming `what` was not).
fn per_level(
    model: &AutomatonModel,
    resolved: &Resolved,
    subs: &[usize],
    (levels, max_pieces): (u64, usize),
    what: &str,
    mut measure: impl FnMut(&[(KMatrix, usize)]) -> Contacts,
) -> Result<(Vec<Contacts>, Option<String>)> {
    let a = &model.automaton;
    let dim0 = a.states[model.start].dim;
    let mut pieces: Vec<(KMatrix, usize)> =
        vec![(KMatrix::identity(&model.field, dim0), model.start)];
    let mut out = Vec::new();
    for level in 1..=levels {
        let count: usize = pieces
            .iter()
            .map(|(_, s)| subs.iter().filter(|&&o| a.operators[o].to == *s).count())
            .sum();
        if count > max_pieces {
            let note = format!(
                "automaton {what} not enumerated from level {level}: {count} pieces, above {max_pieces}"
            );
            return Ok((out, Some(note)));
        }
        pieces = step(model, resolved, subs, &pieces)?;
        out.push(measure(&pieces));
    }
    Ok((out, None))
}

/// The pieces of the next level: each piece's map times every sub-operator into its state.
fn step(
    model: &AutomatonModel,
    resolved: &Resolved,
    subs: &[usize],
    pieces: &[(KMatrix, usize)],
) -> Result<Vec<(KMatrix, usize)>> {
    let a = &model.automaton;
    let mut next = Vec::new();
    for (m, s) in pieces {
        for &o in subs {
            let op = &a.operators[o];
            if op.to != *s {
                continue;
            }
            let p = m.mul(&model.field, &resolved.ops[o]).ok_or_else(|| {
                Error::Analysis(format!("operator {o} does not chain with its state's maps"))
            })?;
            next.push((p, op.from));
        }
    }
    Ok(next)
}

/// For each state, its corners that one of its own sub-operators fixes (column j is e_j).
fn fixed_corners(model: &AutomatonModel, resolved: &Resolved, subs: &[usize]) -> Vec<Vec<usize>> {
    let a = &model.automaton;
    let k = &model.field;
    let one = k.rational(BigRational::from_integer(1.into()));
    let mut fixed: Vec<Vec<usize>> = vec![Vec::new(); a.states.len()];
    for &o in subs {
        let op = &a.operators[o];
        if op.to != op.from {
            continue;
        }
        let m = &resolved.ops[o];
        for j in 0..a.states[op.to].dim {
            let is_unit = (0..a.states[op.to].dim).all(|r| {
                if r == j {
                    *m.get(r, j) == one
                } else {
                    m.get(r, j).is_zero()
                }
            });
            if is_unit && !fixed[op.to].contains(&j) {
                fixed[op.to].push(j);
            }
        }
    }
    fixed
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

    fn automaton(text: &str) -> Invariants {
        let model = crate::input::parse_model(&crate::Source {
            name: "test".into(),
            text: text.into(),
        })
        .unwrap();
        let resolved = crate::analysis::resolve(&model, &[], 1_000_000).unwrap();
        automaton_invariants(
            "test",
            &model,
            &resolved,
            2,
            AutomatonMultiplicity::Contacts,
            100_000,
        )
        .unwrap()
    }

    fn lib_text(name: &str) -> &'static str {
        crate::input::library()
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, t)| *t)
            .expect("a library entry")
    }

    fn model(text: &str) -> (AutomatonModel, Resolved) {
        let model = crate::input::parse_model(&crate::Source {
            name: "test".into(),
            text: text.into(),
        })
        .unwrap();
        let resolved = crate::analysis::resolve(&model, &[], 1_000_000).unwrap();
        (model, resolved)
    }

    #[test]
    fn coinciding_pieces_are_counted_level_by_level() {
        // Three maps of ratio 1/2 on [0, 1]: T0 and T1 the same (x/2), T2 = x/2 + 1/2. Level 1:
        // two maps, x/2 of 2 pieces and x/2 + 1/2 of 1. Level 2 (words ab, the map T_a T_b):
        // a, b in {0, 1} give x/4 (4 pieces); a in {0, 1}, b = 2 give x/4 + 1/4 (2); a = 2,
        // b in {0, 1} give x/4 + 1/2 (2); 22 gives x/4 + 3/4 (1): four maps, of 1, 2, 2, 4 pieces.
        let text = "state e 2\nsub e.T0 : e <- e = [1 1/2; 0 1/2]\nsub e.T1 : e <- e = [1 1/2; 0 1/2]\nsub e.T2 : e <- e = [1/2 0; 1/2 1]\nspace 2\npoints [0 0; 1 0]\n";
        let model = crate::input::parse_model(&crate::Source {
            name: "test".into(),
            text: text.into(),
        })
        .unwrap();
        let resolved = crate::analysis::resolve(&model, &[], 1_000_000).unwrap();
        let i = automaton_invariants(
            "test",
            &model,
            &resolved,
            2,
            AutomatonMultiplicity::Coincidences,
            100_000,
        )
        .unwrap();
        // The two distinct maps are free (the open interval (0, 1) is an open set), so these
        // rows come from counting words of the distinct maps, not from enumerating pieces.
        assert_eq!(i.order, Some(1), "{:?}", i.notes);
        let named = |v: &[(&str, &str)]| -> Vec<Named> {
            v.iter()
                .map(|(a, b)| (a.to_string(), b.to_string()))
                .collect()
        };
        assert_eq!(
            i.multiplicity[1],
            named(&[
                ("distinct maps", "2"),
                ("maps of 1 pieces", "1"),
                ("maps of 2 pieces", "1")
            ])
        );
        assert_eq!(
            i.multiplicity[2],
            named(&[
                ("distinct maps", "4"),
                ("maps of 1 pieces", "1"),
                ("maps of 2 pieces", "2"),
                ("maps of 4 pieces", "1")
            ])
        );
        assert_eq!(i.cardinality[2], named(&[("pieces", "9")]));
    }

    #[test]
    fn automaton_contacts_stop_at_the_piece_limit() {
        // Sierpinski has 3 pieces at level 1 and 9 at level 2: with at most 5 a level, level 1 is
        // enumerated and level 2 is not, with a note (a limit, not a verdict).
        let model = crate::input::parse_model(&crate::Source {
            name: "test".into(),
            text: include_str!("../../../fixtures/sierpinski-triangle.aut").into(),
        })
        .unwrap();
        let resolved = crate::analysis::resolve(&model, &[], 1_000_000).unwrap();
        let subs: Vec<usize> = (0..model.automaton.operators.len())
            .filter(|&o| model.automaton.operators[o].kind == OpKind::Sub)
            .collect();
        let (levels, note) = multiplicities(
            &model,
            &resolved,
            &subs,
            3,
            5,
            AutomatonMultiplicity::Contacts,
        )
        .unwrap();
        assert_eq!(levels.len(), 1);
        assert_eq!(levels[0].1, 6);
        assert!(note.unwrap().contains("from level 2: 9 pieces"));
    }

    #[test]
    fn automaton_contacts_at_levels_1_and_2() {
        // Sierpinski: T_i fixes corner i, and each T_i maps the three corners to its own corner
        // and two midpoints: T0 → (1,0,0), (1/2,1/2,0), (1/2,0,1/2); T1 → (1/2,1/2,0), (0,1,0),
        // (0,1/2,1/2); T2 → (1/2,0,1/2), (0,1/2,1/2), (0,0,1). Six points: the three midpoints
        // where two pieces meet, the three corners with one. Pieces per level: 3^k.
        let s = automaton(include_str!("../../../fixtures/sierpinski-triangle.aut"));
        assert_eq!(
            s.cardinality[2],
            vec![("pieces".to_string(), "9".to_string())]
        );
        assert_eq!(
            s.contacts[1],
            vec![
                ("fixed-corner images".to_string(), "6".to_string()),
                ("points where 1 pieces meet".to_string(), "3".to_string()),
                ("points where 2 pieces meet".to_string(), "3".to_string()),
            ]
        );
        // Level 2: 9 triangles with 3 corners each, the 15 points of the level-2 triangle grid
        // that are corners of a small triangle (3·(3^2 + 1)/2): the 3 outer corners lie in one
        // piece, the other 12 in two (27 = 3 + 2·12 corner incidences).
        assert_eq!(
            s.contacts[2],
            vec![
                ("fixed-corner images".to_string(), "15".to_string()),
                ("points where 1 pieces meet".to_string(), "3".to_string()),
                ("points where 2 pieces meet".to_string(), "12".to_string()),
            ]
        );
        assert!(
            s.notes
                .iter()
                .any(|n| n.contains("fixed corners counted at levels 1 to 2")),
            "{:?}",
            s.notes
        );
        // Cantor: T0 fixes end 0, T1 end 1; images (1,0), (2/3,1/3), (1/3,2/3), (0,1): four
        // points, no two pieces meet.
        let c = automaton(include_str!("../../../fixtures/cantor-set.aut"));
        assert_eq!(
            c.contacts[1],
            vec![
                ("fixed-corner images".to_string(), "4".to_string()),
                ("points where 1 pieces meet".to_string(), "4".to_string()),
            ]
        );
        // Level 2: 4 intervals of length 1/9, 8 distinct ends (the gaps keep them apart).
        assert_eq!(
            c.contacts[2],
            vec![
                ("fixed-corner images".to_string(), "8".to_string()),
                ("points where 1 pieces meet".to_string(), "8".to_string()),
            ]
        );
    }

    #[test]
    fn free_counts_agree_with_enumerated_pieces() {
        // Two independent computations of seed 002's multiplicity: words of the distinct maps
        // (each of product weight) against every piece of the level with its exact map. They
        // must agree wherever the distinct maps are proved free.
        for name in [
            "lemniscate-fractal",
            "rose-fractal",
            "gasket-5",
            "sierpinski-carpet",
            "penrose-robinson",
        ] {
            let text = lib_text(name);
            let (m, r) = model(text);
            let subs: Vec<usize> = (0..m.automaton.operators.len())
                .filter(|&o| m.automaton.operators[o].kind == OpKind::Sub)
                .collect();
            let free = free_reduction(&m, &r, &subs, 100_000)
                .unwrap()
                .unwrap_or_else(|why| panic!("{name}: {why}"));
            let (enumerated, cut) = multiplicities(
                &m,
                &r,
                &subs,
                3,
                MAX_CONTACT_PIECES,
                AutomatonMultiplicity::Coincidences,
            )
            .unwrap();
            assert!(cut.is_none(), "{name}");
            assert_eq!(
                free_levels(&m, &free, 3),
                rows_of(&enumerated, "distinct maps", "maps of {m} pieces"),
                "{name}"
            );
        }
    }

    #[test]
    fn the_lemniscate_multiplies_its_crossing_level_by_level() {
        // Hand count: five distinct maps, the crossing of weight 2 and four of weight 1. A word
        // of k letters with j crossings is the map of 2^j pieces, and there are C(k, j)·4^(k−j)
        // such words: level 2 gives 16 of 1 piece, 8 of 2 and 1 of 4 (25 maps, 36 pieces).
        let (m, r) = model(lib_text("lemniscate-fractal"));
        let i = automaton_invariants(
            "lemniscate",
            &m,
            &r,
            2,
            AutomatonMultiplicity::Coincidences,
            100_000,
        )
        .unwrap();
        let named = |v: &[(&str, &str)]| -> Vec<Named> {
            v.iter()
                .map(|(a, b)| (a.to_string(), b.to_string()))
                .collect()
        };
        assert_eq!(
            i.multiplicity[2],
            named(&[
                ("distinct maps", "25"),
                ("maps of 1 pieces", "16"),
                ("maps of 2 pieces", "8"),
                ("maps of 4 pieces", "1")
            ])
        );
        assert_eq!(i.cardinality[2], named(&[("pieces", "36")]));
        assert_eq!(i.order, Some(1));
    }

    #[test]
    fn words_that_coincide_deeper_leave_the_limit_open() {
        // Three maps x/2 + t on [0, 1], t = 0, 1/4, 1/2: all distinct at level 1, but the words
        // (t = 0 then 1/2) and (1/4 then 0) are both x/4 + 1/4 at level 2 (0 + 1/2·1/2 = 1/4 +
        // 0). Their ratios sum to 3/2 > 1, so no open set exists: the limit is not decided and
        // level 2's coincidence is found by enumeration, never claimed for every level.
        let text = "state e 2\nsub e.T0 : e <- e = [1 1/2; 0 1/2]\nsub e.T1 : e <- e = [3/4 1/4; 1/4 3/4]\nsub e.T2 : e <- e = [1/2 0; 1/2 1]\nspace 2\npoints [0 0; 1 0]\n";
        let (m, r) = model(text);
        let i = automaton_invariants("t", &m, &r, 2, AutomatonMultiplicity::Coincidences, 100_000)
            .unwrap();
        assert_eq!(i.order, None);
        assert!(i.notes[0].contains("not decided"), "{:?}", i.notes);
        assert_eq!(
            i.multiplicity[1][0],
            ("distinct maps".to_string(), "3".to_string())
        );
        // Level 2: 9 words x/4 + t1 + t2/2, 7 distinct maps: t1 + t2/2 is one of 0, 1/8, 1/4,
        // 3/8, 1/2, 5/8, 3/4, and 1/4 (0 + 1/4 = 1/4 + 0) and 1/2 (1/4 + 1/4 = 1/2 + 0) twice.
        assert_eq!(
            i.multiplicity[2][0],
            ("distinct maps".to_string(), "7".to_string())
        );
    }

    #[test]
    fn presentations_of_one_set_are_one_class() {
        // The Sierpinski triangle written on its corners and written on its centre and two
        // corners (gasket-3): the same three maps, so one class at every level — though their
        // fixed corners differ (6 and 5 images at level 1), which is why contacts only show.
        let lib = |n: &str| model(lib_text(n));
        let inv = |n: &str| {
            let (m, r) = lib(n);
            automaton_invariants(n, &m, &r, 4, AutomatonMultiplicity::Contacts, 100_000).unwrap()
        };
        let (a, b) = (inv("sierpinski-triangle"), inv("gasket-3"));
        assert_ne!(a.contacts[1], b.contacts[1]);
        let c = classify(&a, &b);
        assert!(c.same_class && c.every_level, "{c:?}");
        assert!(
            c.notes.iter().any(|n| n.contains("not a class invariant")),
            "{c:?}"
        );
    }
}
