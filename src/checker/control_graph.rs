//! The control graph of a hand-written automaton's attractor: the subdivision operators out of
//! each state, the states the start reaches, and the strongly connected parts that hold a cycle.

use crate::certificate::AutomatonClaim;

/// The control graph: for each state, its subdivision operators `T: q ← w` (edges q → w).
pub(super) struct Graph {
    pub(super) out: Vec<Vec<usize>>,
    pub(super) start: usize,
    pub(super) reachable: Vec<bool>,
}

pub(super) fn graph(a: &AutomatonClaim) -> Result<Graph, String> {
    let at = a
        .attractor
        .as_ref()
        .ok_or("the claim has no attractor (start state, points, subdivision operators)")?;
    if at.start >= a.states.len() {
        return Err(format!("the start state {} is out of range", at.start));
    }
    if at.subdivision.windows(2).any(|w| w[0] >= w[1]) {
        return Err("the subdivision operators are not listed in increasing order".into());
    }
    let mut out = vec![Vec::new(); a.states.len()];
    for &o in &at.subdivision {
        let op = a
            .operators
            .get(o)
            .ok_or_else(|| format!("subdivision operator {o} out of range"))?;
        out[op.to].push(o);
    }
    let mut reachable = vec![false; a.states.len()];
    reachable[at.start] = true;
    let mut stack = vec![at.start];
    while let Some(q) = stack.pop() {
        for &o in &out[q] {
            let w = a.operators[o].from;
            if !reachable[w] {
                reachable[w] = true;
                stack.push(w);
            }
        }
    }
    Ok(Graph {
        out,
        start: at.start,
        reachable,
    })
}

/// The strongly connected parts of the reachable control graph that hold a cycle, each sorted,
/// ordered by smallest state.
pub(super) fn cyclic_parts(a: &AutomatonClaim, g: &Graph) -> Vec<Vec<usize>> {
    let n = a.states.len();
    let succ: Vec<Vec<usize>> = (0..n)
        .map(|q| g.out[q].iter().map(|&o| a.operators[o].from).collect())
        .collect();
    cyclic_components(&succ, |q| g.reachable[q])
}

/// The strongly connected components of the graph `succ` restricted to the nodes `include`
/// accepts that hold a cycle (more than one node, or a loop), each sorted, ordered by smallest
/// node (iterative Kosaraju).
pub(super) fn cyclic_components(
    succ: &[Vec<usize>],
    include: impl Fn(usize) -> bool,
) -> Vec<Vec<usize>> {
    let n = succ.len();
    let mut pred = vec![Vec::new(); n];
    for (q, s) in succ.iter().enumerate() {
        for &w in s {
            pred[w].push(q);
        }
    }
    // First pass: finishing order.
    let mut seen = vec![false; n];
    let mut order = Vec::new();
    for r in (0..n).filter(|&q| include(q)) {
        if seen[r] {
            continue;
        }
        seen[r] = true;
        let mut stack = vec![(r, 0usize)];
        while let Some((v, i)) = stack.pop() {
            if i < succ[v].len() {
                stack.push((v, i + 1));
                let w = succ[v][i];
                if !seen[w] && include(w) {
                    seen[w] = true;
                    stack.push((w, 0));
                }
            } else {
                order.push(v);
            }
        }
    }
    // Second pass on the reversed graph.
    let mut part = vec![usize::MAX; n];
    let mut parts = Vec::new();
    for &r in order.iter().rev() {
        if part[r] != usize::MAX {
            continue;
        }
        let id = parts.len();
        let mut members = vec![r];
        part[r] = id;
        let mut stack = vec![r];
        while let Some(v) = stack.pop() {
            for &w in &pred[v] {
                if include(w) && part[w] == usize::MAX {
                    part[w] = id;
                    members.push(w);
                    stack.push(w);
                }
            }
        }
        members.sort_unstable();
        parts.push(members);
    }
    let mut out: Vec<Vec<usize>> = parts
        .into_iter()
        .filter(|c| c.len() > 1 || succ[c[0]].contains(&c[0]))
        .collect();
    out.sort();
    out
}
