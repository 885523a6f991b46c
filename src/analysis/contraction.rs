//! Whether an automaton's attractor is defined: the operators on every cycle of the control graph
//! (states reachable from the start, one edge `q → w` per subdivision operator `T: q ← w`) must
//! contract. For each elementary cycle the product of its operators is barycentric, so 1 is an
//! eigenvalue (left eigenvector `(1, …, 1)`); the product contracts the differences of points
//! exactly when the other eigenvalues, the roots of `charpoly / (x − 1)`, lie in the open unit
//! disk — decided exactly by Schur–Cohn in the field ([`crate::algebra::fieldpoly`]).
//!
//! This is the condition of the BC-IFS paper ("operators associated with each cycle in the control
//! graph are contractive"), checked on every elementary cycle; products mixing several cycles (the
//! joint spectral radius) are not examined.

use crate::algebra::algebraic::FieldElement;
use crate::algebra::fieldpoly::{inside_unit_disk, k_divrem};
use crate::algebra::kmatrix::KMatrix;
use crate::analysis::automaton_resolve::coded;
use crate::constraint::automaton::OpKind;
use crate::error::Result;
use crate::input::automaton_model::AutomatonModel;
use num_rational::BigRational;
use num_traits::One;
use serde::Serialize;

/// The most elementary cycles examined (refused beyond, before the products are formed).
pub const MAX_CYCLES: usize = 4096;

/// The most steps of the depth-first search for cycles (the simple paths can outnumber the
/// cycles exponentially).
pub const MAX_SEARCH_STEPS: usize = 2_000_000;

/// The most control points of a state on a cycle (the characteristic polynomial of the
/// cycle's product is exact, O(m⁴) field operations).
pub const MAX_CYCLE_DIM: usize = 64;

/// The contraction check's result.
#[derive(Clone, Debug, Serialize)]
pub struct ContractionReport {
    /// The cycles examined, each as its operators `T1 · T2 · …`.
    pub cycles: Vec<String>,
}

/// The subdivision operators reachable from the start state, by state (`out[q]` = operators
/// `T: q ← w`).
pub fn control_graph(m: &AutomatonModel) -> Vec<Vec<usize>> {
    let a = &m.automaton;
    let mut out = vec![Vec::new(); a.states.len()];
    for (o, op) in a.operators.iter().enumerate() {
        if op.kind == OpKind::Sub {
            out[op.to].push(o);
        }
    }
    out
}

/// The states reachable from the start through subdivision operators.
pub fn reachable(m: &AutomatonModel) -> Vec<bool> {
    let a = &m.automaton;
    let g = control_graph(m);
    let mut seen = vec![false; a.states.len()];
    let mut stack = vec![m.start];
    seen[m.start] = true;
    while let Some(q) = stack.pop() {
        for &o in &g[q] {
            let w = a.operators[o].from;
            if !seen[w] {
                seen[w] = true;
                stack.push(w);
            }
        }
    }
    seen
}

/// The elementary cycles among reachable states, each a list of operators, rooted at its
/// smallest state; `None` when there are more than [`MAX_CYCLES`], or the search takes more than
/// [`MAX_SEARCH_STEPS`] steps.
pub fn elementary_cycles(m: &AutomatonModel) -> Option<Vec<Vec<usize>>> {
    let a = &m.automaton;
    let g = control_graph(m);
    let reach = reachable(m);
    let mut cycles = Vec::new();
    let mut steps = 0usize;
    for s in 0..a.states.len() {
        if !reach[s] {
            continue;
        }
        // Depth-first over states > s; `path` holds operators, `on` the states on the path.
        let mut on = vec![false; a.states.len()];
        let mut path: Vec<usize> = Vec::new();
        let mut stack: Vec<(usize, usize)> = vec![(s, 0)];
        on[s] = true;
        while let Some(&mut (q, ref mut i)) = stack.last_mut() {
            steps += 1;
            if steps > MAX_SEARCH_STEPS {
                return None;
            }
            if *i < g[q].len() {
                let o = g[q][*i];
                *i += 1;
                let w = a.operators[o].from;
                if w == s {
                    let mut c = path.clone();
                    c.push(o);
                    cycles.push(c);
                    if cycles.len() > MAX_CYCLES {
                        return None;
                    }
                } else if w > s && !on[w] && reach[w] {
                    on[w] = true;
                    path.push(o);
                    stack.push((w, 0));
                }
            } else {
                on[q] = false;
                stack.pop();
                path.pop();
            }
        }
    }
    Some(cycles)
}

/// Checks every elementary cycle; refuses (E0715) with the first cycle that does not contract,
/// E0716 for a subdivision operator on a cycle that is not barycentric, E0718 beyond
/// [`MAX_CYCLES`] or [`MAX_CYCLE_DIM`].
pub fn check_contraction(m: &AutomatonModel, ops: &[KMatrix]) -> Result<ContractionReport> {
    let a = &m.automaton;
    let k = &m.field;
    let cycles = elementary_cycles(m).ok_or_else(|| {
        coded("E0718", format!("the control graph has more than {MAX_CYCLES} elementary cycles (or more paths than the search allows): too many to check for contraction"))
    })?;
    for c in &cycles {
        let s = &a.states[a.operators[c[0]].to];
        if s.dim > MAX_CYCLE_DIM {
            return Err(coded("E0718", format!(
                "state `{}` lies on a cycle with {} control points: the contraction check handles at most {MAX_CYCLE_DIM}",
                s.name, s.dim
            )));
        }
    }
    let mut names = Vec::new();
    for c in &cycles {
        let text = c
            .iter()
            .map(|&o| a.operators[o].name.as_str())
            .collect::<Vec<_>>()
            .join(" · ");
        for &o in c {
            if !ops[o].is_barycentric(k) {
                return Err(coded("E0716", format!(
                    "operator `{}` on the cycle {text} is not barycentric (a column does not sum to 1): its attractor would depend on the coordinates",
                    a.operators[o].name
                )));
            }
        }
        let mut p = ops[c[0]].clone();
        for &o in &c[1..] {
            p = p.mul(k, &ops[o]).expect("a cycle's shapes chain");
        }
        let chi = p.charpoly(k);
        let one = k.rational(BigRational::one());
        let x_minus_1: Vec<FieldElement> = vec![
            k.sub(&k.rational(BigRational::from_integer(0.into())), &one),
            one,
        ];
        let (rest, rem) = k_divrem(k, &chi, &x_minus_1);
        if !rem.is_empty() || !inside_unit_disk(k, &rest) {
            return Err(coded("E0715", format!(
                "the cycle {text} does not contract: its product has an eigenvalue of modulus ≥ 1 besides the barycentric 1, so the attractor is not defined (state `{}`)",
                a.states[a.operators[c[0]].to].name
            )));
        }
        names.push(text);
    }
    Ok(ContractionReport { cycles: names })
}
