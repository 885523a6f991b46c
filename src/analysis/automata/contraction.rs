//! Whether an automaton's attractor is defined: the operators along the walks of the control
//! graph (states reachable from the start, one edge `q → w` per subdivision operator `T: q ← w`)
//! must contract the differences of control points.
//!
//! **Necessary: every elementary cycle.** The product of a cycle's operators is barycentric, so 1
//! is an eigenvalue (left eigenvector `(1, …, 1)`); the cycle contracts exactly when the other
//! eigenvalues, the roots of `charpoly / (x − 1)`, lie in the open unit disk — decided exactly by
//! Schur–Cohn in the field ([`crate::algebra::fieldpoly`]). A cycle that fails is refused (E0715).
//!
//! **Sufficient: a norm proof over all walks.** Every barycentric `T: q ← w` maps the difference
//! space `D_w = {d : Σ d_i = 0}` into `D_q` (`1ᵀT = 1ᵀ`), and the points of a node collapse to one
//! point along an infinite walk exactly when the product of the restrictions `T|D` tends to 0. In
//! the coordinates `d = Σ_{i<m−1} d_i (e_i − e_{m−1})` the restriction is the
//! `(m_q − 1) × (m_w − 1)` matrix `A[i][j] = T[i][j] − T[i][m_w − 1]`, and products of operators
//! restrict to products of these. The search walks the tree of walks from every reachable state,
//! breadth first, and closes a walk as soon as its product has induced ∞-norm (max row sum of
//! `|A_ij|`) below 1 — exactly, with signs decided in the field. When every branch closes, every
//! infinite walk is a concatenation of finitely many kinds of closed blocks, each of norm at most
//! c < 1 (the largest of them), so every product tends to 0 at least like `c^(n/k)`, k the
//! deepest block: the attractor is defined (proven). The same search is run with the induced
//! 1-norm (max column sum) when the ∞-norm does not close. A walk that comes back to its first
//! state without closing is a cycle: when the budget runs out, the first 256 such cycles
//! (shortest first) have their product's eigenvalues on `D` tested as above, and one of modulus
//! ≥ 1 refuses the automaton (E0715) naming that cycle — this finds products mixing several
//! elementary cycles that do not contract (the joint spectral radius ≥ 1). When the search
//! has formed `max_products` products without a proof or a refusal (a product of more than 1000
//! scalar multiplications counting as that many thousands), the answer is *undecided*:
//! error E0721 (a limit is not a verdict: the attractor is not said to be undefined, and nothing
//! is drawn from an automaton not proven to contract).

use crate::algebra::algebraic::FieldElement;
use crate::algebra::fieldpoly::{inside_unit_disk, k_divrem};
use crate::algebra::kmatrix::KMatrix;
use crate::analysis::automata::automaton_resolve::coded;
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

/// The most operator products the norm proof forms by default (`--max-products`).
pub const DEFAULT_MAX_PRODUCTS: usize = 20_000;

/// The contraction check's result: the necessary check on elementary cycles and the proof.
#[derive(Clone, Debug, Serialize)]
pub struct ContractionReport {
    /// The cycles examined, each as its operators `T1 · T2 · …`.
    pub cycles: Vec<String>,
    /// The norm of the proof: `"inf"` (max row sum) or `"1"` (max column sum).
    pub norm: String,
    /// The longest walk the proof needed before its product's norm fell below 1.
    pub depth: usize,
    /// The products formed by the proof.
    pub products: usize,
    /// The closed walks of the proof (operator indices), from every reachable state: a
    /// complete prefix code whose products have norm below 1 (the certificate's witness).
    #[serde(skip)]
    pub walks: Vec<Vec<usize>>,
}

impl ContractionReport {
    /// One line saying what was proven.
    pub fn text(&self) -> String {
        format!(
            "contraction: proven — every walk of the control graph reaches, within {}, a product of {}-norm < 1 on the differences of points ({}, exact); {} contract{}",
            crate::error::counted(self.depth, "operator", "operators"),
            if self.norm == "inf" { "∞" } else { "1" },
            crate::error::counted(self.products, "product", "products"),
            crate::error::counted(self.cycles.len(), "elementary cycle", "elementary cycles"),
            if self.cycles.len() == 1 { "s" } else { "" }
        )
    }
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

/// [`check_contraction_within`] with [`DEFAULT_MAX_PRODUCTS`].
pub fn check_contraction(m: &AutomatonModel, ops: &[KMatrix]) -> Result<ContractionReport> {
    check_contraction_within(m, ops, DEFAULT_MAX_PRODUCTS)
}

/// Checks every elementary cycle, then proves contraction over all walks (module doc); refuses
/// (E0715) with the first cycle that does not contract, E0716 for a subdivision operator on a
/// cycle that is not barycentric, E0718 beyond [`MAX_CYCLES`] or [`MAX_CYCLE_DIM`], E0721 when
/// `max_products` products leave it undecided.
pub fn check_contraction_within(
    m: &AutomatonModel,
    ops: &[KMatrix],
    max_products: usize,
) -> Result<ContractionReport> {
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
    let mut budget = max_products;
    let mut used = 0usize;
    for norm in [Norm::Inf, Norm::One] {
        match prove(m, ops, norm, &mut budget)? {
            Proof::Proven { depth, walks } => {
                used += max_products - budget;
                return Ok(ContractionReport {
                    cycles: names,
                    norm: match norm {
                        Norm::Inf => "inf",
                        Norm::One => "1",
                    }
                    .into(),
                    depth,
                    products: used,
                    walks,
                });
            }
            Proof::Open => {}
        }
    }
    Err(coded(
        "E0721",
        format!(
            "contraction undecided: every elementary cycle contracts, but {max_products} products of operators along walks of the control graph neither proved that every walk contracts (a product of ∞- or 1-norm < 1 on the differences of points) nor found a cycle that does not; the attractor is not proven to exist, so nothing is drawn (raise --max-products)"
        ),
    ))
}

/// An induced matrix norm on the coordinates of the difference space.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Norm {
    /// Max row sum of absolute values.
    Inf,
    /// Max column sum of absolute values.
    One,
}

enum Proof {
    Proven {
        depth: usize,
        walks: Vec<Vec<usize>>,
    },
    Open,
}

/// The restriction of a barycentric `T` (m_q × m_w) to the difference spaces, in the coordinates
/// of the module doc: `A[i][j] = T[i][j] − T[i][m_w − 1]`, `i < m_q − 1`, `j < m_w − 1`.
pub fn difference_restriction(k: &crate::algebra::algebraic::NumberField, t: &KMatrix) -> KMatrix {
    let (r, c) = (t.rows.saturating_sub(1), t.cols.saturating_sub(1));
    let mut data = Vec::with_capacity(r * c);
    for i in 0..r {
        for j in 0..c {
            data.push(k.sub(t.get(i, j), t.get(i, t.cols - 1)));
        }
    }
    KMatrix {
        rows: r,
        cols: c,
        data,
    }
}

/// Whether the induced norm of `a` is below 1, exactly.
fn norm_below_one(k: &crate::algebra::algebraic::NumberField, a: &KMatrix, norm: Norm) -> bool {
    let zero = || k.rational(BigRational::from_integer(0.into()));
    let abs = |x: &FieldElement| {
        if k.sign(x) == std::cmp::Ordering::Less {
            k.sub(&zero(), x)
        } else {
            x.clone()
        }
    };
    let (outer, inner) = match norm {
        Norm::Inf => (a.rows, a.cols),
        Norm::One => (a.cols, a.rows),
    };
    let one = k.rational(BigRational::one());
    (0..outer).all(|o| {
        let s = (0..inner).fold(zero(), |acc, i| {
            let x = match norm {
                Norm::Inf => a.get(o, i),
                Norm::One => a.get(i, o),
            };
            k.add(&acc, &abs(x))
        });
        k.sign(&k.sub(&s, &one)) == std::cmp::Ordering::Less
    })
}

/// The most open cycles kept for the refusal test when the budget runs out.
const MAX_REFUTATIONS: usize = 256;

/// When the budget runs out: the kept cycles, shortest first, tested for an eigenvalue of
/// modulus ≥ 1 on the differences of points (E0715 naming the first); else still open.
fn refute(m: &AutomatonModel, returns: &[(Vec<usize>, usize, KMatrix)]) -> Result<Proof> {
    let a = &m.automaton;
    let k = &m.field;
    for (w, root, prod) in returns {
        if !inside_unit_disk(k, &prod.charpoly(k)) {
            let text = w
                .iter()
                .map(|&o| a.operators[o].name.as_str())
                .collect::<Vec<_>>()
                .join(" · ");
            return Err(coded("E0715", format!(
                "the cycle {text} does not contract: its product has an eigenvalue of modulus ≥ 1 besides the barycentric 1 (every elementary cycle contracts, but this product of them does not), so the attractor is not defined (state `{}`)",
                a.states[*root].name
            )));
        }
    }
    Ok(Proof::Open)
}

/// The breadth-first search of the module doc for one norm; `budget` counts down the products.
fn prove(m: &AutomatonModel, ops: &[KMatrix], norm: Norm, budget: &mut usize) -> Result<Proof> {
    let a = &m.automaton;
    let k = &m.field;
    let g = control_graph(m);
    let reach = reachable(m);
    let restricted: Vec<Option<KMatrix>> = ops
        .iter()
        .enumerate()
        .map(|(o, t)| (a.operators[o].kind == OpKind::Sub).then(|| difference_restriction(k, t)))
        .collect();
    let mut deepest = 0usize;
    let mut closed: Vec<Vec<usize>> = Vec::new();
    // Walks back to their first state that did not close: tested for a refusal only when the
    // budget runs out (the test, a characteristic polynomial, costs more than the products).
    let mut returns: Vec<(Vec<usize>, usize, KMatrix)> = Vec::new();
    for (root, _) in reach.iter().enumerate().filter(|(_, &r)| r) {
        // Open walks of the current length: (their operators, the state they end in, product).
        let mut open: Vec<(Vec<usize>, usize, KMatrix)> = vec![(
            Vec::new(),
            root,
            KMatrix::identity(k, a.states[root].dim.saturating_sub(1)),
        )];
        let mut depth = 0usize;
        while !open.is_empty() {
            depth += 1;
            let mut next = Vec::new();
            for (walk, q, p) in &open {
                for &o in &g[*q] {
                    let r = restricted[o].as_ref().expect("a subdivision operator");
                    // A product of more than 1000 scalar multiplications counts as that many
                    // thousands: the budget bounds the work, whatever the states' sizes.
                    let cost = (p.rows * p.cols * r.cols).div_ceil(1000).max(1);
                    if *budget < cost {
                        *budget = 0;
                        return refute(m, &returns);
                    }
                    *budget -= cost;
                    let prod = p.mul(k, r).expect("a walk's shapes chain");
                    if norm_below_one(k, &prod, norm) {
                        deepest = deepest.max(depth);
                        let mut w = walk.clone();
                        w.push(o);
                        closed.push(w);
                        continue;
                    }
                    let mut w = walk.clone();
                    w.push(o);
                    let end = a.operators[o].from;
                    if end == root && returns.len() < MAX_REFUTATIONS {
                        returns.push((w.clone(), root, prod.clone()));
                    }
                    next.push((w, end, prod));
                }
            }
            open = next;
        }
    }
    Ok(Proof::Proven {
        depth: deepest,
        walks: closed,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::resolve;
    use crate::error::Source;
    use crate::input::automaton_model::parse_model;

    fn run(text: &str, max_products: usize) -> Result<ContractionReport> {
        let m = parse_model(&Source::command_line(text)).expect("a model");
        let r = resolve(&m, &[], 10_000).expect("resolved");
        check_contraction_within(&m, &r.ops, max_products)
    }

    fn code(e: crate::error::Error) -> String {
        match e {
            crate::error::Error::Syntax(d) => format!("{} {}", d.code, d.message),
            other => format!("{other}"),
        }
    }

    #[test]
    fn one_state_halving_maps_are_proven_at_depth_one() {
        // Two points per node (m = 2): the restriction of T is the 1 × 1 matrix T[0][0] − T[0][1],
        // here 1 − 1/2 = 1/2 and 1/2 − 0 = 1/2: both norms below 1 at once, 2 products.
        let r = run(
            "state e 2\nsub e.T0 : e <- e = [1 1/2; 0 1/2]\nsub e.T1 : e <- e = [1/2 0; 1/2 1]\nbarycentric\nspace 2\n",
            100,
        )
        .unwrap();
        assert_eq!((r.norm.as_str(), r.depth, r.products), ("inf", 1, 2));
    }

    #[test]
    fn two_states_are_proven_at_depth_two() {
        // p.A : p <- q is the identity (restriction 1, not below 1), q.B : q <- p and q.C : q <- q
        // halve (restriction 1/2). From p: A (1, open), then A·B = A·C = 1/2 (closed): depth 2,
        // 3 products; from q: B, C close at once, 2 products. Total 5.
        let r = run(
            "state p 2\nstate q 2\nsub p.A : p <- q = [1 0; 0 1]\nsub q.B : q <- p = [1 1/2; 0 1/2]\nsub q.C : q <- q = [1/2 0; 1/2 1]\nbarycentric\nspace 2\nstart p\n",
            100,
        )
        .unwrap();
        assert_eq!((r.depth, r.products, r.cycles.len()), (2, 5, 2));
    }

    #[test]
    fn an_elementary_cycle_that_does_not_contract_is_named() {
        // One state: the identity keeps its two points apart (eigenvalue 1 twice).
        let e = code(
            run(
                "state e 2\nsub e.T : e <- e = [1 0; 0 1]\nbarycentric\nspace 2\n",
                100,
            )
            .unwrap_err(),
        );
        assert!(e.starts_with("E0715") && e.contains("e.T"), "{e}");
        // Two states swapping the points: the cycle p.A · q.B is the identity.
        let e = code(
            run(
                "state p 2\nstate q 2\nsub p.A : p <- q = [0 1; 1 0]\nsub q.B : q <- p = [0 1; 1 0]\nbarycentric\nspace 2\nstart p\n",
                100,
            )
            .unwrap_err(),
        );
        assert!(e.starts_with("E0715") && e.contains("p.A · q.B"), "{e}");
    }

    #[test]
    fn a_mixed_product_that_does_not_contract_is_found() {
        // Restrictions (A[i][j] = T[i][j] − T[i][2]): A0 = [0 1; 0 0], A1 = [0 0; 1 0], both
        // nilpotent, so T0 and T1 have eigenvalues 1, 0, 0: every elementary cycle (T0 alone, T1
        // alone) contracts. But A0·A1 = [1 0; 0 0] has eigenvalue 1: the word (T0 T1)^n keeps two
        // points apart for ever. Depth 1: both have ∞-norm 1 (open, spectrum inside); depth 2:
        // A0·A0 = 0 closes, A0·A1 refuses.
        let e = code(
            run(
                "state e 3\nsub e.T0 : e <- e = [0 1 0; 0 0 0; 1 0 1]\nsub e.T1 : e <- e = [0 0 0; 1 0 0; 0 1 1]\nbarycentric\nspace 2\n",
                100,
            )
            .unwrap_err(),
        );
        assert!(e.starts_with("E0715") && e.contains("e.T0 · e.T1"), "{e}");
    }

    #[test]
    fn a_slow_contraction_is_undecided_below_its_depth_and_proven_at_it() {
        // T's restriction is A = [1/2 4; 0 1/2] (T = [1/2 4 0; 0 1/2 0; 1/2 −7/2 1], columns
        // summing to 1). A^n = [2^-n, 8n·2^-n; 0, 2^-n], so ‖A^n‖∞ = ‖A^n‖₁ = 2^-n (1 + 8n):
        // 41/32 > 1 at n = 5, 49/64 < 1 at n = 6. One operator, one walk per depth: 6 products
        // prove it; with 5 the ∞ search stops at depth 5 and the 1-norm search has none left.
        let text =
            "state e 3\nsub e.T : e <- e = [1/2 4 0; 0 1/2 0; 1/2 -7/2 1]\nbarycentric\nspace 2\n";
        let e = code(run(text, 5).unwrap_err());
        assert!(e.starts_with("E0721"), "{e}");
        let r = run(text, 6).unwrap();
        assert_eq!((r.depth, r.products), (6, 6));
    }
}
