//! Strongly connected classes of a type graph and their periods.
//!
//! The type graph has an arc `t → s` for every sub-face of type `s` in a face of type `t`. Its
//! strongly connected classes (found with petgraph's Tarjan) are what the Perron–Frobenius analysis
//! of the limit ratio works on: each class has a spectral radius and a *period*, the gcd of the
//! lengths of its cycles. petgraph has no periodicity routine, so the period is computed here by
//! the classical BFS argument: with `level` the BFS depth from any member, the period is the gcd of
//! `level(u) + 1 − level(v)` over the arcs `u → v` inside the class.
//!
//! [`strong_components`] numbers the components of any successor-list graph; the limit valences
//! and the automata analyses (cyclic parts, the boundary graph) use it too.

use num_integer::Integer;
use petgraph::graph::{DiGraph, NodeIndex};
use serde::Serialize;
use std::collections::VecDeque;

/// One strongly connected class of the graph reached from the start types.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Class {
    /// Type indices in the class, ascending.
    pub members: Vec<usize>,
    /// The gcd of the cycle lengths; `None` for a transient class (one type, no loop).
    pub period: Option<u64>,
}

/// The classes reached from a set of start types, in topological order: a class is listed
/// before every class it reaches.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ClassStructure {
    /// The classes, sources first.
    pub classes: Vec<Class>,
    /// For each type, the index of its class, or `None` when it is not reached.
    pub class_of: Vec<Option<usize>>,
}

impl ClassStructure {
    /// Computes the classes of the graph `succ` (successor lists; repeated arcs allowed) reached
    /// from `start`.
    pub fn new(succ: &[Vec<usize>], start: &[usize]) -> Self {
        let n = succ.len();
        let mut reached = vec![false; n];
        let mut queue: VecDeque<usize> = VecDeque::new();
        for &s in start {
            if s < n && !reached[s] {
                reached[s] = true;
                queue.push_back(s);
            }
        }
        while let Some(t) = queue.pop_front() {
            for &s in &succ[t] {
                if !reached[s] {
                    reached[s] = true;
                    queue.push_back(s);
                }
            }
        }
        // The reached types, renumbered in ascending order, and the arcs between them.
        let reached_types: Vec<usize> = (0..n).filter(|&t| reached[t]).collect();
        let mut local = vec![usize::MAX; n];
        for (i, &t) in reached_types.iter().enumerate() {
            local[t] = i;
        }
        let sub: Vec<Vec<usize>> = reached_types
            .iter()
            .map(|&t| succ[t].iter().map(|&s| local[s]).collect())
            .collect();
        // Components are numbered sinks first; count down for a topological order.
        let (comp, count) = strong_components(&sub);
        let mut classes: Vec<Class> = (0..count)
            .map(|_| Class {
                members: Vec::new(),
                period: None,
            })
            .collect();
        let mut class_of = vec![None; n];
        for (i, &t) in reached_types.iter().enumerate() {
            let c = count - 1 - comp[i];
            classes[c].members.push(t);
            class_of[t] = Some(c);
        }
        for (c, class) in classes.iter_mut().enumerate() {
            class.period = period(succ, &class_of, c, &class.members);
        }
        ClassStructure { classes, class_of }
    }
}

/// The strongly connected components of the graph `succ` (successor lists; repeated arcs
/// allowed), by petgraph's iterative Tarjan: the component of every node and their number. The
/// components are numbered so that an arc never leads to a component of larger number (sinks
/// first, as petgraph lists them).
pub(crate) fn strong_components(succ: &[Vec<usize>]) -> (Vec<usize>, usize) {
    let mut graph = DiGraph::<(), ()>::new();
    let node: Vec<NodeIndex> = succ.iter().map(|_| graph.add_node(())).collect();
    for (v, ws) in succ.iter().enumerate() {
        for &w in ws {
            graph.add_edge(node[v], node[w], ());
        }
    }
    let sccs = petgraph::algo::tarjan_scc(&graph);
    let mut comp = vec![0; succ.len()];
    for (c, scc) in sccs.iter().enumerate() {
        for v in scc {
            comp[v.index()] = c;
        }
    }
    (comp, sccs.len())
}

/// The period of class `c`, or `None` when it has no arc inside (a transient type).
fn period(
    succ: &[Vec<usize>],
    class_of: &[Option<usize>],
    c: usize,
    members: &[usize],
) -> Option<u64> {
    let root = members[0];
    let mut level: std::collections::HashMap<usize, u64> = std::collections::HashMap::new();
    level.insert(root, 0);
    let mut queue = VecDeque::from([root]);
    let mut g: u64 = 0;
    let mut has_arc = false;
    while let Some(u) = queue.pop_front() {
        let lu = level[&u];
        for &v in &succ[u] {
            if class_of[v] != Some(c) {
                continue;
            }
            has_arc = true;
            match level.get(&v) {
                Some(&lv) => {
                    let diff = (lu + 1).abs_diff(lv);
                    g = g.gcd(&diff);
                }
                None => {
                    level.insert(v, lu + 1);
                    queue.push_back(v);
                }
            }
        }
    }
    has_arc.then_some(g)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn self_loop_is_aperiodic() {
        let s = ClassStructure::new(&[vec![0, 0, 0]], &[0]);
        assert_eq!(s.classes.len(), 1);
        assert_eq!(s.classes[0].period, Some(1));
    }

    #[test]
    fn strong_components_never_number_upwards() {
        // 0 → 1 ⇄ 2 → 3, 3 ↺: components {0}, {1, 2}, {3}; every arc goes down in number.
        let succ = vec![vec![1], vec![2], vec![1, 3], vec![3]];
        let (comp, count) = strong_components(&succ);
        assert_eq!(count, 3);
        assert_eq!(comp[1], comp[2]);
        for (v, s) in succ.iter().enumerate() {
            for &w in s {
                assert!(comp[w] <= comp[v]);
            }
        }
    }

    #[test]
    fn two_cycle_has_period_two_and_transient_has_none() {
        // 0 -> 1 -> 2 -> 1 ; type 3 unreachable.
        let succ = vec![vec![1], vec![2], vec![1], vec![0]];
        let s = ClassStructure::new(&succ, &[0]);
        assert_eq!(s.classes.len(), 2);
        assert_eq!(s.classes[0].members, vec![0]);
        assert_eq!(s.classes[0].period, None);
        assert_eq!(s.classes[1].members, vec![1, 2]);
        assert_eq!(s.classes[1].period, Some(2));
        assert_eq!(s.class_of[3], None);
    }

    #[test]
    fn cycles_of_two_and_three_give_period_one() {
        // 0 -> 1 -> 0 and 0 -> 1 -> 2 -> 0: gcd(2, 3) = 1.
        let succ = vec![vec![1], vec![0, 2], vec![0]];
        let s = ClassStructure::new(&succ, &[0]);
        assert_eq!(s.classes[0].period, Some(1));
        // Cycles of lengths 2 and 4 only: period 2.
        let succ = vec![vec![1], vec![0, 2], vec![3], vec![0]];
        let s = ClassStructure::new(&succ, &[0]);
        assert_eq!(s.classes[0].period, Some(2));
    }
}
