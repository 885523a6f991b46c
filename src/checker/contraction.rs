//! The step `contraction`: the walks of a hand-written automaton's control graph form a
//! complete prefix code from every reachable state, and every walk's product contracts the
//! differences of points in an induced norm, exactly in K.

use super::control_graph::graph;
use super::enclosure::{decimal, enclose};
use super::field::{self, P};
use super::ifs::{barycentric, constraints_hold, instance, Checked, Field, KMat};
use super::Q;
use crate::certificate::{AutomatonClaim, ContractionStep};
use num_traits::{One, Zero};
use std::collections::{BTreeMap, BTreeSet};

/// The most walks of a contraction step, and the longest walk.
const MAX_WALKS: usize = 1 << 20;

const MAX_WALK_LEN: usize = 4096;

/// The restriction of a barycentric `T` (m_q × m_w) to the differences of points, in the
/// coordinates `d = Σ_(i<m−1) d_i (e_i − e_(m−1))`: `A[i][j] = T[i][j] − T[i][m_w − 1]`.
fn restriction(k: &Field, t: &KMat) -> KMat {
    let (r, c) = (t.rows - 1, t.cols - 1);
    let mut data = Vec::with_capacity(r * c);
    for i in 0..r {
        for j in 0..c {
            data.push(k.sub(&t.data[i * t.cols + j], &t.data[i * t.cols + t.cols - 1]));
        }
    }
    KMat {
        rows: r,
        cols: c,
        data,
    }
}

/// The induced norm of `a` (`inf`: max row sum, `1`: max column sum) compared with 1: the
/// largest sum, exactly, when it is below 1.
fn norm_below_one(k: &Field, a: &KMat, inf: bool) -> Result<Option<P>, String> {
    let (outer, inner) = match inf {
        true => (a.rows, a.cols),
        false => (a.cols, a.rows),
    };
    let one = Field::rational(Q::one());
    let mut largest = P::new();
    for o in 0..outer {
        let mut s = P::new();
        for i in 0..inner {
            let x = match inf {
                true => &a.data[o * a.cols + i],
                false => &a.data[i * a.cols + o],
            };
            s = field::add(&s, &k.abs(x)?);
        }
        if k.sign(&k.sub(&s, &one))? >= 0 {
            return Ok(None);
        }
        if k.sign(&k.sub(&s, &largest))? > 0 {
            largest = s;
        }
    }
    Ok(Some(largest))
}

/// The step `contraction`.
pub(super) fn check_contraction(a: &AutomatonClaim, s: &ContractionStep) -> Checked {
    let k = Field::of(a)?;
    let ops = instance(&k, a, &s.instance)?;
    constraints_hold(&k, a, &ops).map_err(|e| format!("the instance: {e}"))?;
    let g = graph(a)?;
    let inf = match s.norm.as_str() {
        "inf" => true,
        "1" => false,
        other => return Err(format!("unknown norm `{other}` (inf or 1)")),
    };
    if s.walks.len() > MAX_WALKS {
        return Err(format!(
            "{} walks: the checker reads at most {MAX_WALKS}",
            s.walks.len()
        ));
    }
    let subdivision: BTreeSet<usize> = g.out.iter().flatten().copied().collect();
    // The walks as paths, grouped by their first state.
    let mut leaves: BTreeSet<&[usize]> = BTreeSet::new();
    let mut inner: BTreeSet<(usize, &[usize])> = BTreeSet::new();
    for (n, w) in s.walks.iter().enumerate() {
        if w.is_empty() || w.len() > MAX_WALK_LEN {
            return Err(format!(
                "walk {n} has length {}, not in 1..={MAX_WALK_LEN}",
                w.len()
            ));
        }
        for (i, &o) in w.iter().enumerate() {
            if !subdivision.contains(&o) {
                return Err(format!(
                    "walk {n}: operator {o} is not a subdivision operator"
                ));
            }
            if i > 0 && a.operators[o].to != a.operators[w[i - 1]].from {
                return Err(format!(
                    "walk {n}: {} does not start where {} ends",
                    a.operators[o].name,
                    a.operators[w[i - 1]].name
                ));
            }
        }
        if !g.reachable[a.operators[w[0]].to] {
            return Err(format!(
                "walk {n} starts at a state the start does not reach"
            ));
        }
        if !leaves.insert(w.as_slice()) {
            return Err(format!("walk {n} is listed twice"));
        }
        for l in 0..w.len() {
            inner.insert((a.operators[w[0]].to, &w[..l]));
        }
    }
    // Prefix-free: no walk is a proper prefix of another.
    for &(_, p) in &inner {
        if !p.is_empty() && leaves.contains(p) {
            return Err(format!(
                "the walk {} is a prefix of another walk: the walks are not a prefix code",
                names(a, p)
            ));
        }
    }
    // Complete: from every reachable state, every node of the tree continues along every
    // subdivision operator out of the state it ends in, into a walk or into the tree.
    let reached: Vec<usize> = (0..a.states.len()).filter(|&q| g.reachable[q]).collect();
    for &q in &reached {
        if !g.out[q].is_empty() && !inner.contains(&(q, &[][..])) {
            return Err(format!(
                "no walk starts at state {}, which the start reaches and which has subdivision operators",
                a.states[q].name
            ));
        }
    }
    for &(q, p) in &inner {
        let end = p.last().map_or(q, |&o| a.operators[o].from);
        for &o in &g.out[end] {
            let mut next = p.to_vec();
            next.push(o);
            // A walk into a state without subdivision operators ends there: no infinite walk
            // continues it.
            let dead_end = g.out[a.operators[o].from].is_empty();
            if !dead_end
                && !leaves.contains(next.as_slice())
                && !inner.contains(&(q, next.as_slice()))
            {
                return Err(format!(
                    "the walks from state {} are not complete: the walk {} is neither listed nor extended",
                    a.states[q].name,
                    names(a, &next)
                ));
            }
        }
    }
    // Every operator on a walk is barycentric; every walk's product has norm below 1.
    let used: BTreeSet<usize> = s.walks.iter().flatten().copied().collect();
    let mut restricted = BTreeMap::new();
    for &o in &used {
        if !barycentric(&k, &ops[o]) {
            return Err(format!(
                "operator {} is not barycentric: it need not map differences of points to differences",
                a.operators[o].name
            ));
        }
        restricted.insert(o, restriction(&k, &ops[o]));
    }
    let mut worst = P::new();
    let mut depth = 0;
    for w in &s.walks {
        let first = a.operators[w[0]].to;
        let mut p = Field::identity(a.states[first].dim - 1);
        for o in w {
            p = k.matmul(&p, &restricted[o])?;
        }
        match norm_below_one(&k, &p, inf)? {
            Some(c) => {
                if k.sign(&k.sub(&c, &worst))? > 0 {
                    worst = c;
                }
            }
            None => {
                return Err(format!(
                "the product of the walk {} has {}-norm at least 1 on the differences of points",
                names(a, w),
                s.norm
            ))
            }
        }
        depth = depth.max(w.len());
    }
    let bound = match worst.len() <= 1 {
        true => worst.first().cloned().unwrap_or_else(Q::zero).to_string(),
        false => {
            // An upper bound of four decimals, rounded up (still below 1: the enclosure is
            // finer than the gap to 1 whenever the ceiling reaches 1, the exact test decided).
            let (_, hi) = enclose(&k, &worst, 20)?;
            let up = (hi * Q::from_integer(10_000.into())).ceil() / Q::from_integer(10_000.into());
            match up < Q::one() {
                true => format!("{} (rounded up)", decimal(&up, 4)),
                false => "a number below 1".into(),
            }
        }
    };
    Ok((
        format!(
            "{} of at most {} form a complete prefix code from each of the {}; every operator on them is barycentric and every walk's product on the differences of points has {}-norm ≤ {bound} < 1 (exact in {}), for the instance {}: every infinite walk contracts",
            super::counted(s.walks.len(), "walk", "walks"),
            super::counted(depth, "operator", "operators"),
            super::counted(reached.len(), "reachable state", "reachable states"),
            if inf { "∞" } else { "1" },
            if a.field.is_some() { "K" } else { "Q" },
            match s.instance.is_empty() {
                true => "the claim gives".to_string(),
                false => format!("completed by the step's values of {} (every constraint holds)", super::counted(s.instance.len(), "unknown operator", "unknown operators")),
            }
        ),
        match s.instance.is_empty() {
            true => "contraction: every infinite walk of the control graph contracts: the attractor is defined".to_string(),
            false => "contraction: every infinite walk of the control graph contracts for the instance the step completes (its unknown operators given, every constraint holding): that instance's attractor is defined".to_string(),
        },
    ))
}

fn names(a: &AutomatonClaim, w: &[usize]) -> String {
    w.iter()
        .map(|&o| a.operators.get(o).map_or("?", |x| x.name.as_str()))
        .collect::<Vec<_>>()
        .join(" · ")
}
