//! Strongly connected classes of a type graph and their periods.
//!
//! The type graph has an arc `t → s` for every sub-face of type `s` in a face of type `t`. Its
//! strongly connected classes (found with petgraph's Tarjan) are what the Perron–Frobenius analysis
//! of the limit ratio works on: each class has a spectral radius and a *period*, the gcd of the
//! lengths of its cycles. petgraph has no periodicity routine, so the period is computed here by
//! the classical BFS argument: with `level` the BFS depth from any member, the period is the gcd of
//! `level(u) + 1 − level(v)` over the arcs `u → v` inside the class.

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
        let mut graph: DiGraph<usize, ()> = DiGraph::new();
        let mut node = vec![NodeIndex::end(); n];
        for t in (0..n).filter(|&t| reached[t]) {
            node[t] = graph.add_node(t);
        }
        for t in (0..n).filter(|&t| reached[t]) {
            for &s in &succ[t] {
                graph.add_edge(node[t], node[s], ());
            }
        }
        // tarjan_scc lists sinks first; reverse for a topological order.
        let mut sccs = petgraph::algo::tarjan_scc(&graph);
        sccs.reverse();
        let mut class_of = vec![None; n];
        let mut classes = Vec::with_capacity(sccs.len());
        for (c, scc) in sccs.iter().enumerate() {
            let mut members: Vec<usize> = scc.iter().map(|&v| graph[v]).collect();
            members.sort_unstable();
            for &m in &members {
                class_of[m] = Some(c);
            }
            classes.push(Class {
                members,
                period: None,
            });
        }
        for (c, class) in classes.iter_mut().enumerate() {
            class.period = period(succ, &class_of, c, &class.members);
        }
        ClassStructure { classes, class_of }
    }
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
