//! The rule-compilation step: the checker reads the claim's rule text (Kaandorp's production
//! rules, `docs/FORMATS.md`, "Rule files") with its own parser, compiles it with its own code and
//! requires the claim's automaton to be exactly that compilation — so every verdict about the
//! automaton (constraints, contraction, similarity dimension) is about the rule.
//!
//! **The compilation** (the same definition as lacuna's, written again here): states
//! `initiator` (3 frame points `(0,0)`, `(1,0)`, `(0,1)` and the initiator's points), one per
//! generator reached from the initiator (breadth first, in the order the pieces name them; 3
//! frame points each) and `segment` (2 points). A fertile segment from P to Q of a path laid by
//! the map `m` is an operator into the generator it names whose columns are the barycentric
//! coordinates, in the frame, of the images of the three frame points under
//! `m ∘ (z ↦ P + (Q − P)·ρ(z))`, ρ the flag's reflection (`/y`: `z̄`, `/x`: `1 − z̄`, `/xy`:
//! `1 − z`); a drawn segment (`-`) is an operator into `segment` whose columns are its ends; a gap
//! (`.`) is nothing. The initiator's operators are its fertile segments' generators already laid
//! on them (then the generator's pieces), a generator state's are its own path's pieces; operator
//! `j` of state `S` is `S.Tj`. Every operator is barycentric and a subdivision operator, there is
//! no constraint, and the attractor starts at `initiator` with its points.
//!
//! **The extensions** (`choice.rs`): with an `age` or `random` choice a fertile segment's generator
//! and state are the choice's, and the generator states are one per node met (generator, age,
//! place above the depth), breadth first, named `G`, `G.NAMEa`, `G.atI_J…` or both suffixes;
//! operator `j` of a state is still its `j`-th piece (gaps skipped), while a place counts every
//! segment. The number of states of occurrences is bounded before anything is unrolled.

use super::choice::{Choices, Node, Order, Target, MAX_DEPTH};
use super::field::{self, P};
use super::ifs::{parse_field_matrix, parse_rational_matrix, Field, KMat};
use super::Q;
use crate::certificate::AutomatonClaim;
use num_bigint::BigInt;
use num_traits::{One, Zero};

/// The most characters of a rule text the checker reads.
const MAX_RULE: usize = 1 << 20;

/// How a generator is laid on a segment: none, `/y`, `/x`, `/xy`.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Flip {
    Plain,
    Y,
    X,
    XY,
}

/// What stands between two points of a path.
#[derive(Clone, Copy)]
enum Flag {
    Fertile(Target, Flip),
    Drawn,
    Gap,
}

/// A path: points and the flags between them.
struct Path {
    points: Vec<[P; 2]>,
    flags: Vec<Flag>,
}

/// An affine map of the plane, `(x, y) ↦ (a·x + b·y + e, c·x + d·y + f)`, entries in K.
type Aff = [P; 6];

/// A rational in the rule's spelling: `3`, `-1/2`, `0.25`.
fn number(t: &str) -> Option<Q> {
    if t.is_empty() || t.len() > 200 {
        return None;
    }
    let digits = |s: &str| -> Option<BigInt> {
        match !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()) {
            true => s.parse().ok(),
            false => None,
        }
    };
    let (neg, body) = match t.strip_prefix('-') {
        Some(b) => (true, b),
        None => (false, t),
    };
    let v = if let Some((n, d)) = body.split_once('/') {
        let (n, d) = (digits(n)?, digits(d)?);
        if d.is_zero() {
            return None;
        }
        Q::new(n, d)
    } else if let Some((i, f)) = body.split_once('.') {
        let i = match i.is_empty() {
            true => BigInt::zero(),
            false => digits(i)?,
        };
        Q::from_integer(i) + Q::new(digits(f)?, num_traits::pow(BigInt::from(10), f.len()))
    } else {
        Q::from_integer(digits(body)?)
    };
    Some(if neg { -v } else { v })
}

/// A sum of terms `c`, `c*v`, `c v^e` (no spaces, `c` optional before the variable) into
/// coefficients by degree.
fn terms(t: &str, var: Option<&str>) -> Option<P> {
    let b = t.as_bytes();
    let (mut i, mut first, mut out) = (0usize, true, P::new());
    if b.is_empty() {
        return None;
    }
    while i < b.len() {
        let mut sign = Q::one();
        if b[i] == b'+' || b[i] == b'-' {
            if b[i] == b'-' {
                sign = -sign;
            }
            i += 1;
        } else if !first {
            return None;
        }
        first = false;
        let start = i;
        while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'/' || b[i] == b'.') {
            i += 1;
        }
        let coef = match i > start {
            true => number(&t[start..i])?,
            false => Q::one(),
        };
        if i < b.len() && b[i] == b'*' {
            i += 1;
        }
        let mut exp = 0usize;
        match var.filter(|v| t[i..].starts_with(v)) {
            Some(v) => {
                i += v.len();
                exp = 1;
                if i < b.len() && b[i] == b'^' {
                    i += 1;
                    let s = i;
                    while i < b.len() && b[i].is_ascii_digit() {
                        i += 1;
                    }
                    exp = t[s..i].parse().ok().filter(|e| *e <= 64)?;
                }
            }
            None if i == start => return None,
            None => {}
        }
        if out.len() <= exp {
            out.resize(exp + 1, Q::zero());
        }
        out[exp] += sign * coef;
    }
    Some(field::trim(out))
}

/// A declared name: (name, its words).
type Declared<'a> = (String, Vec<&'a str>);

/// The rule read: the field's generator name (with the polynomial and interval it declares),
/// the initiator's words, each generator's name and words, each age and random choice's name
/// and entries, `seed` and `depth`.
#[derive(Default)]
struct Read<'a> {
    field: Option<(String, P, Q, Q)>,
    initiator: Option<Vec<&'a str>>,
    generators: Vec<Declared<'a>>,
    ages: Vec<Declared<'a>>,
    randoms: Vec<Declared<'a>>,
    seed: Option<u64>,
    depth: Option<usize>,
}

impl Read<'_> {
    fn declared(&self, name: &str) -> bool {
        [&self.generators, &self.ages, &self.randoms]
            .iter()
            .any(|list| list.iter().any(|(n, _)| n == name))
    }
}

/// A name of the rule's own: letters, digits and `_`, starting with a letter; not a name of the
/// compiled automaton's fixed states.
fn valid_name(n: &str) -> bool {
    n.starts_with(|c: char| c.is_ascii_alphabetic())
        && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && n != "initiator"
        && n != "segment"
}

fn read(text: &str) -> Result<Read<'_>, String> {
    let mut r = Read::default();
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        let words: Vec<&str> = line.split_whitespace().collect();
        let Some(&head) = words.first() else {
            continue;
        };
        let at = || format!("rule line {}", n + 1);
        match head {
            "field" => {
                let rest = line["field".len()..].trim();
                let bad = || format!("{}: not `field NAME = root of POLY in [LO, HI]`", at());
                let (name, rhs) = rest.split_once('=').ok_or_else(bad)?;
                let name = name.trim();
                let body = rhs.trim().strip_prefix("root of").ok_or_else(bad)?;
                let (poly, interval) = body.rsplit_once(" in ").ok_or_else(bad)?;
                let inner = interval
                    .trim()
                    .strip_prefix('[')
                    .and_then(|s| s.strip_suffix(']'))
                    .ok_or_else(bad)?;
                let (lo, hi) = inner.split_once(',').ok_or_else(bad)?;
                let (lo, hi) = (number(lo.trim()), number(hi.trim()));
                let compact: String = poly.chars().filter(|c| !c.is_whitespace()).collect();
                let p = terms(&compact, Some("x")).or_else(|| terms(&compact, Some(name)));
                let ok = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphabetic());
                match (ok, p, lo, hi, &r.field) {
                    (true, Some(p), Some(lo), Some(hi), None) if p.len() >= 2 && lo <= hi => {
                        r.field = Some((name.to_string(), p, lo, hi))
                    }
                    _ => return Err(bad()),
                }
            }
            "initiator" if r.initiator.is_none() => r.initiator = Some(words[1..].to_vec()),
            "generator" | "age" | "random" if words.len() >= 2 => {
                let name = words[1];
                if !valid_name(name) || r.declared(name) {
                    return Err(format!(
                        "{}: `{name}` is declared twice or is no name (letters, digits, `_`)",
                        at()
                    ));
                }
                if head != "generator" && words.len() < 3 {
                    return Err(format!("{}: the choice {name} lists no generator", at()));
                }
                let list = match head {
                    "generator" => &mut r.generators,
                    "age" => &mut r.ages,
                    _ => &mut r.randoms,
                };
                list.push((name.to_string(), words[2..].to_vec()));
            }
            "seed" | "depth" => {
                let value = match words.len() {
                    2 => words[1].parse::<u64>().ok(),
                    _ => None,
                };
                match (head, value) {
                    ("seed", Some(v)) if r.seed.is_none() => r.seed = Some(v),
                    ("depth", Some(d))
                        if r.depth.is_none() && (1..=MAX_DEPTH as u64).contains(&d) =>
                    {
                        r.depth = Some(d as usize)
                    }
                    _ => {
                        let line =
                            format!("`seed N` (0 to 2^64 − 1) or `depth D` (1 to {MAX_DEPTH})");
                        return Err(format!("{}: not {line}, once", at()));
                    }
                }
            }
            _ => return Err(format!("{}: `{head}` is no line of a rule", at())),
        }
    }
    Ok(r)
}

/// The generator index of each entry of a choice.
fn entries(
    list: &[Declared],
    generators: &[Declared],
) -> Result<Vec<(String, Vec<usize>)>, String> {
    list.iter()
        .map(|(name, words)| {
            let gens = words
                .iter()
                .map(|w| {
                    generators
                        .iter()
                        .position(|(g, _)| g == w)
                        .ok_or_else(|| format!("the choice {name} lists `{w}`, no generator"))
                })
                .collect::<Result<Vec<_>, _>>()?;
            Ok((name.clone(), gens))
        })
        .collect()
}

/// A path's words: points `x,y` and flags between them; a flag's name is a generator, an age
/// choice (then `!` may follow: a new fractal) or a random choice of `r`.
fn path(words: &[&str], k: &Field, var: Option<&str>, r: &Read) -> Result<Path, String> {
    if words.len() < 3 || words.len() % 2 == 0 {
        return Err("a path is POINT FLAG POINT … POINT, with at least one segment".into());
    }
    let mut p = Path {
        points: Vec::new(),
        flags: Vec::new(),
    };
    for (i, w) in words.iter().enumerate() {
        if i % 2 == 0 {
            let (x, y) = w
                .split_once(',')
                .ok_or_else(|| format!("`{w}` is no point"))?;
            let coord = |t: &str| {
                terms(t, var)
                    .map(|c| k.reduce(&c))
                    .ok_or_else(|| format!("`{t}` is no exact coordinate"))
            };
            p.points.push([coord(x)?, coord(y)?]);
            continue;
        }
        let flag = match *w {
            "-" => Flag::Drawn,
            "." => Flag::Gap,
            _ => {
                let (head, flip) = match w.split_once('/') {
                    None => (*w, Flip::Plain),
                    Some((n, "y")) => (n, Flip::Y),
                    Some((n, "x")) => (n, Flip::X),
                    Some((n, "xy" | "yx")) => (n, Flip::XY),
                    Some(_) => return Err(format!("`{w}` is no flag")),
                };
                let (name, restart) = match head.strip_suffix('!') {
                    Some(n) => (n, true),
                    None => (head, false),
                };
                let find = |list: &[Declared]| list.iter().position(|(n, _)| n == name);
                let target = match (find(&r.generators), find(&r.ages), find(&r.randoms)) {
                    (Some(g), _, _) if !restart => Target::Generator(g),
                    (_, Some(choice), _) => Target::Age { choice, restart },
                    (_, _, Some(c)) if !restart => Target::Random(c),
                    (None, None, None) => return Err(format!("`{name}` names no generator")),
                    _ => return Err(format!("`{w}`: `!` follows age choices only")),
                };
                Flag::Fertile(target, flip)
            }
        };
        p.flags.push(flag);
    }
    Ok(p)
}

fn rational(q: Q) -> P {
    Field::rational(q)
}

/// `u ∘ v` (v first).
fn then(k: &Field, u: &Aff, v: &Aff) -> Aff {
    let [a, b, c, d, e, f] = u;
    let [a2, b2, c2, d2, e2, f2] = v;
    let ma = |x: &P, y: &P, s: &P, t: &P| field::add(&k.mul(x, y), &k.mul(s, t));
    [
        ma(a, a2, b, c2),
        ma(a, b2, b, d2),
        ma(c, a2, d, c2),
        ma(c, b2, d, d2),
        field::add(&ma(a, e2, b, f2), e),
        field::add(&ma(c, e2, d, f2), f),
    ]
}

fn apply(k: &Field, m: &Aff, p: &[P; 2]) -> [P; 2] {
    let [a, b, c, d, e, f] = m;
    [
        field::add(&field::add(&k.mul(a, &p[0]), &k.mul(b, &p[1])), e),
        field::add(&field::add(&k.mul(c, &p[0]), &k.mul(d, &p[1])), f),
    ]
}

fn identity() -> Aff {
    let (z, o) = (P::new(), rational(Q::one()));
    [o.clone(), z.clone(), z.clone(), o, z.clone(), z]
}

/// The similitude taking `(0,0)` to P and `(1,0)` to Q, after the reflection.
fn onto(k: &Field, p: &[P; 2], q: &[P; 2], flip: Flip) -> Aff {
    let (dx, dy) = (k.sub(&q[0], &p[0]), k.sub(&q[1], &p[1]));
    let s = [
        dx.clone(),
        k.sub(&P::new(), &dy),
        dy,
        dx,
        p[0].clone(),
        p[1].clone(),
    ];
    let (z, o, m) = (P::new(), rational(Q::one()), rational(-Q::one()));
    let r = match flip {
        Flip::Plain => return s,
        Flip::Y => [o.clone(), z.clone(), z.clone(), m, z.clone(), z],
        Flip::X => [m, z.clone(), z.clone(), o.clone(), o, z],
        Flip::XY => [m.clone(), z.clone(), z.clone(), m, o, z],
    };
    then(k, &s, &r)
}

/// A piece of a laid path: a fertile segment (the map laying it, the number of the node it
/// opens) or a drawn segment (its ends).
enum Piece {
    Fertile(Aff, usize),
    Drawn([P; 2], [P; 2]),
}

/// The pieces of path `p` of node `node` laid by `m`; the nodes they open are numbered in
/// `order` as they are met.
fn pieces(k: &Field, p: &Path, m: &Aff, node: &Node, c: &Choices, order: &mut Order) -> Vec<Piece> {
    let mut out = Vec::new();
    for (i, f) in p.flags.iter().enumerate() {
        let (a, b) = (&p.points[i], &p.points[i + 1]);
        match *f {
            Flag::Gap => {}
            Flag::Drawn => out.push(Piece::Drawn(apply(k, m, a), apply(k, m, b))),
            Flag::Fertile(t, flip) => {
                let to = order.number(&c.child(t, Some(node), i));
                out.push(Piece::Fertile(then(k, m, &onto(k, a, b, flip)), to))
            }
        }
    }
    out
}

/// The barycentric coordinates of a point in a frame of `rows` points (the first three the
/// frame, the rest 0).
fn column(k: &Field, p: &[P; 2], rows: usize) -> Vec<P> {
    let one = rational(Q::one());
    let mut c = vec![
        k.sub(&k.sub(&one, &p[0]), &p[1]),
        p[0].clone(),
        p[1].clone(),
    ];
    c.resize(rows, P::new());
    c
}

fn matrix(cols: &[Vec<P>]) -> KMat {
    let rows = cols.first().map_or(0, Vec::len);
    let data = (0..rows)
        .flat_map(|r| cols.iter().map(move |c| c[r].clone()))
        .collect();
    KMat {
        rows,
        cols: cols.len(),
        data,
    }
}

/// A rule compiled: its states (name, control points), its operators (name, row state,
/// column state, matrix) in order, the attractor's points, and what the message reports.
struct Compiled {
    states: Vec<(String, usize)>,
    operators: Vec<(String, usize, usize, KMat)>,
    points: Vec<[P; 2]>,
    choices: Choices,
    occurrences: usize,
}

/// Compiles a rule read (see the module documentation) in K; `var` names α in the rule's
/// coordinates, `degree` is K's degree (for the work estimate), `claimed` the claim's numbers of
/// states and operators, past which compiling stops.
fn compile(
    r: &Read,
    k: &Field,
    var: Option<&str>,
    degree: usize,
    claimed: (usize, usize),
) -> Result<Compiled, String> {
    let init_words = r.initiator.as_ref().ok_or("the rule has no initiator")?;
    let initiator = path(init_words, k, var, r)?;
    let gens = r
        .generators
        .iter()
        .map(|(_, w)| path(w, k, var, r))
        .collect::<Result<Vec<_>, _>>()?;
    let choices = Choices {
        ages: entries(&r.ages, &r.generators)?,
        randoms: entries(&r.randoms, &r.generators)?,
        seed: r.seed.unwrap_or(0),
        depth: r.depth.unwrap_or(4),
    };
    // Bound the states before unrolling: one per generator, one per (generator, age) and at
    // most the format's bound of occurrences (each place opens one node).
    let fertile = |p: &Path| {
        p.flags
            .iter()
            .filter(|f| matches!(f, Flag::Fertile(..)))
            .count()
    };
    let most = gens.iter().map(fertile).max().unwrap_or(0);
    let occurrences = choices.occurrences(fertile(&initiator) as u64, most as u64)?;
    let bound = (gens.len() as u128)
        + choices
            .ages
            .iter()
            .map(|(_, e)| e.len() as u128)
            .sum::<u128>()
        + u128::from(occurrences);
    // Each piece is a few dozen products in K: charge the most pieces there can be.
    let longest = gens.iter().map(|p| p.flags.len()).max().unwrap_or(0) as u128;
    let laid = (bound + initiator.flags.len() as u128) * (longest + 1);
    let d = degree.max(1) as u128;
    super::within_work("unrolling the rule", laid * d * d * 2048)?;
    // Compiling stops as soon as it passes the claim's states or operators: the claim is then
    // not the compilation, and a short certificate cannot make the checker build a large one.
    let (claim_states, claim_operators) = claimed;
    let mut count = 0usize;
    let mut past_claim = |ps: &[Piece], nodes: usize| {
        count += ps.len();
        match (count > claim_operators, nodes + 2 > claim_states) {
            (true, _) => Err(format!(
                "the compilation has more operators than the claim's {claim_operators}"
            )),
            (_, true) => Err(format!(
                "the compilation has more states than the claim's {claim_states}"
            )),
            _ => Ok(()),
        }
    };
    let mut order = Order::default();
    // The initiator's pieces: fertile segments already replaced by their generator.
    let mut init = Vec::new();
    for (i, f) in initiator.flags.iter().enumerate() {
        let (p, q) = (&initiator.points[i], &initiator.points[i + 1]);
        let ps = match *f {
            Flag::Gap => Vec::new(),
            Flag::Drawn => vec![Piece::Drawn(p.clone(), q.clone())],
            Flag::Fertile(t, flip) => {
                let node = choices.child(t, None, i);
                let m = onto(k, p, q, flip);
                let g = &gens[node.generator];
                pieces(k, g, &m, &node, &choices, &mut order)
            }
        };
        past_claim(&ps, order.nodes.len())?;
        init.extend(ps);
    }
    // The nodes' pieces, breadth first (a node's children are numbered after it).
    let mut all = Vec::new();
    while all.len() < order.nodes.len() {
        let node = order.nodes[all.len()].clone();
        let g = &gens[node.generator];
        let ps = pieces(k, g, &identity(), &node, &choices, &mut order);
        past_claim(&ps, order.nodes.len())?;
        all.push(ps);
    }
    let names: Vec<String> = r.generators.iter().map(|(n, _)| n.clone()).collect();
    let mut states: Vec<(String, usize)> = vec![("initiator".into(), 3 + initiator.points.len())];
    states.extend(order.nodes.iter().map(|n| (choices.name(n, &names), 3)));
    states.push(("segment".into(), 2));
    let segment = states.len() - 1;
    let frame = frame();
    let mut operators = Vec::new();
    for (s, ps) in std::iter::once(&init).chain(&all).enumerate() {
        let rows = states[s].1;
        for (j, p) in ps.iter().enumerate() {
            let name = format!("{}.T{j}", states[s].0);
            match p {
                Piece::Fertile(m, to) => {
                    let cols: Vec<Vec<P>> = frame
                        .iter()
                        .map(|e| column(k, &apply(k, m, e), rows))
                        .collect();
                    operators.push((name, s, 1 + to, matrix(&cols)));
                }
                Piece::Drawn(x, y) => {
                    let cols = [column(k, x, rows), column(k, y, rows)];
                    operators.push((name, s, segment, matrix(&cols)));
                }
            }
        }
    }
    let mut points = frame.to_vec();
    points.extend(initiator.points.iter().cloned());
    let occurrences = order.nodes.iter().filter(|n| n.place.is_some()).count();
    Ok(Compiled {
        states,
        operators,
        points,
        choices,
        occurrences,
    })
}

/// The frame points `(0,0)`, `(1,0)`, `(0,1)`.
fn frame() -> [[P; 2]; 3] {
    let one = rational(Q::one());
    [
        [P::new(), P::new()],
        [one.clone(), P::new()],
        [P::new(), one],
    ]
}

/// Checks the rule-compilation step: the claim's automaton is the compilation of its rule.
pub(super) fn check_rule_compilation(a: &AutomatonClaim) -> Result<(String, String), String> {
    let text = a
        .rule
        .as_deref()
        .ok_or("the claim carries no rule text to compile")?;
    if text.len() > MAX_RULE {
        return Err(format!("the rule text is above {MAX_RULE} characters"));
    }
    super::within_work("compiling the rule", text.len() as u128 * 64)?;
    let r = read(text)?;
    let k = Field::of(a)?;
    // The rule's field must be the claim's: its polynomial vanishes at the claim's α, has
    // exactly one root in its interval (no root at the ends), and α lies in that interval.
    let var = match (&r.field, &a.field) {
        (None, None) => None,
        (Some((name, p, lo, hi)), Some(_)) => {
            let chain = field::sturm_chain(p).ok_or("the rule's field polynomial is constant")?;
            let ends_clear = !field::eval(p, lo).is_zero() && !field::eval(p, hi).is_zero();
            let count =
                field::sign_changes(&chain, lo) as i64 - field::sign_changes(&chain, hi) as i64;
            let (alo, ahi) = k.interval();
            if !ends_clear || count != 1 || alo < *lo || ahi > *hi || !k.vanishes(p) {
                return Err(format!(
                    "the rule's field ({name}: a root in [{lo}, {hi}]) is not the claim's field"
                ));
            }
            Some(name.as_str())
        }
        _ => return Err("the rule and the claim disagree on whether there is a field".into()),
    };
    let degree = a
        .field
        .as_ref()
        .map_or(1, |f| f.poly.len().saturating_sub(1));
    let c = compile(&r, &k, var, degree, (a.states.len(), a.operators.len()))?;
    let got: Vec<(String, usize)> = a.states.iter().map(|s| (s.name.clone(), s.dim)).collect();
    if got != c.states {
        // Name the first state that differs.
        let i = got
            .iter()
            .zip(&c.states)
            .take_while(|(x, y)| x == y)
            .count();
        let show = |s: Option<&(String, usize)>| match s {
            Some((name, dim)) => format!("`{name}` ({dim} points)"),
            None => "none".to_string(),
        };
        return Err(format!(
            "the claim's state {i} is {}, the compiled one {} (the claim has {} states, the \
             compilation {})",
            show(got.get(i)),
            show(c.states.get(i)),
            got.len(),
            c.states.len()
        ));
    }
    if a.operators.len() != c.operators.len() {
        return Err(format!(
            "the claim has {} operators, the compilation {}",
            a.operators.len(),
            c.operators.len()
        ));
    }
    for (o, (name, to, from, m)) in a.operators.iter().zip(&c.operators) {
        let what = format!("operator {}", o.name);
        if o.name != *name || o.to != *to || o.from != *from {
            return Err(format!(
                "{what} ({} ← {}) is not the compiled {name} ({} ← {})",
                o.to, o.from, to, from
            ));
        }
        let claimed = match (&o.value, &o.field_value) {
            (Some(v), None) => parse_rational_matrix(v, &what)?,
            (None, Some(v)) => parse_field_matrix(&k, v, &what)?,
            _ => return Err(format!("{what}: not given once in the claim")),
        };
        if !k.equal(&claimed, m) {
            return Err(format!("{what}: its matrix is not the compiled one"));
        }
    }
    let n = c.operators.len();
    let every: Vec<usize> = (0..n).collect();
    if !a.constraints.is_empty() || a.barycentric != every {
        return Err("a compiled rule has no constraint and every operator barycentric".into());
    }
    let at = a.attractor.as_ref().ok_or("the claim has no attractor")?;
    let same_points = at.points.len() == c.points.len()
        && at.points.iter().zip(&c.points).all(|(q, p)| {
            q.len() == 2
                && q.iter().zip(p).all(|(x, y)| {
                    k.element(x)
                        .map(|x| k.is_zero(&k.sub(&x, y)))
                        .unwrap_or(false)
                })
        });
    if at.start != 0 || at.subdivision != every || !same_points {
        return Err(
            "the claim's attractor is not the initiator's points with every operator".into(),
        );
    }
    let mut extensions: Vec<String> = c
        .choices
        .ages
        .iter()
        .map(|(name, e)| format!("age choice {name}: {} ages", e.len()))
        .collect();
    if !c.choices.randoms.is_empty() {
        extensions.push(format!(
            "random choices drawn with seed {} by splitmix64, per occurrence down to depth {}: \
             {} states of occurrences",
            c.choices.seed, c.choices.depth, c.occurrences
        ));
    }
    let extensions = match extensions.is_empty() {
        true => String::new(),
        false => format!(" ({})", extensions.join("; ")),
    };
    let msg = format!(
        "the claim's rule read and compiled by the checker{extensions}: {} states, {n} operators \
         (every fertile segment's similitude with its reflection, in the frame of its state, \
         drawn segments into `segment`), equal to the claim's exactly{}",
        c.states.len(),
        match var {
            Some(v) => format!(" in K = Q({v})"),
            None => String::new(),
        }
    );
    Ok((
        msg,
        format!(
            "the automaton is the compilation of its rule ({} generator states reached)",
            c.states.len() - 2
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::certificate::{AttractorClaim, AutomatonClaim};

    fn q(n: i64, d: i64) -> P {
        rational(Q::new(n.into(), d.into()))
    }

    /// K = Q: the field of a claim without one.
    fn rationals() -> Field {
        let a = AutomatonClaim {
            states: Vec::new(),
            operators: Vec::new(),
            constraints: Vec::new(),
            barycentric: Vec::new(),
            field: None,
            attractor: None::<AttractorClaim>,
            rule: None,
        };
        Field::of(&a).unwrap()
    }

    /// A rule over Q compiled by the checker.
    fn compiled(text: &str) -> Result<Compiled, String> {
        compile(
            &read(text)?,
            &rationals(),
            None,
            1,
            (usize::MAX, usize::MAX),
        )
    }

    /// The compiled states' names and each operator's (name, row state, column state).
    fn shape(c: &Compiled) -> (Vec<&str>, Vec<(&str, usize, usize)>) {
        (
            c.states.iter().map(|s| s.0.as_str()).collect(),
            c.operators
                .iter()
                .map(|o| (o.0.as_str(), o.1, o.2))
                .collect(),
        )
    }

    #[test]
    fn the_dragon_piece_by_hand() {
        // The first piece of `left 0,0 left 1/2,1/2 right 1,0`: the similitude taking (0,0) to
        // (0,0) and (1,0) to (1/2,1/2) takes (0,1) to (−1/2, 1/2); in barycentric coordinates
        // of the frame (1 − x − y, x, y): (1,0,0), (0, 1/2, 1/2), (1, −1/2, 1/2).
        let k = rationals();
        let m = onto(&k, &[P::new(), P::new()], &[q(1, 2), q(1, 2)], Flip::Plain);
        let frame = [
            [P::new(), P::new()],
            [q(1, 1), P::new()],
            [P::new(), q(1, 1)],
        ];
        let cols: Vec<Vec<P>> = frame
            .iter()
            .map(|e| column(&k, &apply(&k, &m, e), 3))
            .collect();
        assert_eq!(cols[0], vec![q(1, 1), P::new(), P::new()]);
        assert_eq!(cols[1], vec![P::new(), q(1, 2), q(1, 2)]);
        assert_eq!(cols[2], vec![q(1, 1), q(-1, 2), q(1, 2)]);
        // Mirrored (/y), (0,1) goes to the other side: (1/2, −1/2), barycentric (1, 1/2, −1/2).
        let m = onto(&k, &[P::new(), P::new()], &[q(1, 2), q(1, 2)], Flip::Y);
        let c = column(&k, &apply(&k, &m, &frame[2]), 3);
        assert_eq!(c, vec![q(1, 1), q(1, 2), q(-1, 2)]);
    }

    #[test]
    fn numbers_and_terms_in_the_rule_spelling() {
        assert_eq!(number("-0.25"), Some(Q::new((-1).into(), 4.into())));
        assert_eq!(number("3/6"), Some(Q::new(1.into(), 2.into())));
        assert_eq!(number("1/0"), None);
        assert_eq!(number("1.-2"), None);
        // 1/2 + 1/6·s: coefficients 1/2, 1/6.
        let r = |n: i64, d: i64| Q::new(n.into(), d.into());
        assert_eq!(terms("1/2+1/6s", Some("s")), Some(vec![r(1, 2), r(1, 6)]));
        assert_eq!(
            terms("-s^2", Some("s")),
            Some(vec![Q::zero(), Q::zero(), -Q::one()])
        );
        assert_eq!(terms("2x", None), None);
    }

    #[test]
    fn an_age_rule_with_a_restart_by_hand() {
        // `age t a b`: a at even ages, b at odd ones. The initiator's `t` is age 0, so a is laid
        // on it (into the initiator); a's two `t` segments are age 1: b, the state b.t1. b's
        // `t!` restarts at age 0: a, the state a.t0; a.t0's segments are age 1 again: b.t1.
        let c = compiled(
            "age t a b\ninitiator 0,0 t 1,0\ngenerator a 0,0 t 1/2,1/2 t 1,0\n\
             generator b 0,0 t! 1/2,0 - 1,0\n",
        )
        .unwrap();
        let (states, ops) = shape(&c);
        assert_eq!(states, ["initiator", "b.t1", "a.t0", "segment"]);
        assert_eq!(c.states[0].1, 5, "3 frame points and the initiator's 2");
        assert_eq!(
            ops,
            [
                ("initiator.T0", 0, 1),
                ("initiator.T1", 0, 1),
                ("b.t1.T0", 1, 2),
                ("b.t1.T1", 1, 3),
                ("a.t0.T0", 2, 1),
                ("a.t0.T1", 2, 1),
            ]
        );
        // b.t1.T0 lays a on (0,0)–(1/2,0): the frame goes to (0,0), (1/2,0), (0,1/2), columns
        // (1,0,0), (1/2,1/2,0), (1/2,0,1/2). b.t1.T1 is the drawn (1/2,0)–(1,0): columns
        // (1/2,1/2,0), (0,1,0).
        let (z, o, h) = (P::new(), q(1, 1), q(1, 2));
        let t0 = &c.operators[2].3;
        assert_eq!((t0.rows, t0.cols), (3, 3));
        let want = [&o, &h, &h, &z, &h, &z, &z, &z, &h];
        assert!(t0.data.iter().zip(want).all(|(x, y)| x == y));
        let t1 = &c.operators[3].3;
        assert_eq!((t1.rows, t1.cols), (3, 2));
        let want = [&h, &z, &h, &o, &z, &z];
        assert!(t1.data.iter().zip(want).all(|(x, y)| x == y));
    }

    #[test]
    fn a_random_rule_by_hand() {
        // `random r a b`, seed 2, depth 3: entry h mod 2 (even: a, odd: b) of the seed hashed
        // with the place. The hashes, computed apart from lacuna with Python's integers
        // (`m(z)`: z += 0x9E3779B97F4A7C15, z = (z ^ z>>30)·0xBF58476D1CE4E5B9,
        // z = (z ^ z>>27)·0x94D049BB133111EB, z ^ z>>31, all mod 2^64; h = 2, h = m(h ^ x)):
        let below = (1u64 << 32) - 1;
        let draws: [(&[u64], u64); 9] = [
            (&[0], 0x9758_35DE_1C97_56CE),           // even: a on the initiator
            (&[0, 0], 0x6468_4C4F_0FD7_84B4),        // even: a, the state a.at0_0
            (&[0, 1], 0xE06D_D043_328B_D285),        // odd: b, the state b.at0_1
            (&[0, 0, 0], 0x1956_ECD1_A275_EC95),     // odd: b (place of depth 3: state b)
            (&[0, 0, 1], 0x007B_DC61_A85E_2E79),     // odd: b
            (&[0, 1, 0], 0x90B9_6B4D_D23B_D6EB),     // odd: b
            (&[below, 1, 0], 0x3D20_886A_E621_638E), // even: b's segment 0 draws a
            (&[below, 0, 0], 0x54C6_EB96_3AD6_D97B), // odd: a's segment 0 draws b
            (&[below, 0, 1], 0x2C65_9917_0619_C909), // odd: a's segment 1 draws b
        ];
        let c = compiled(
            "random r a b\nseed 2\ndepth 3\ninitiator 0,0 r 1,0\n\
             generator a 0,0 r 1/2,1/2 r 1,0\ngenerator b 0,0 r 1/2,-1/2 - 1,0\n",
        )
        .unwrap();
        for (place, h) in draws {
            assert_eq!(c.choices.hash(place), h, "the hash of {place:?}");
        }
        // Places of 2 entries (below depth 3) are states of their own; places of 3 entries draw
        // per occurrence into the shared states; deeper, once per generator segment.
        let (states, ops) = shape(&c);
        assert_eq!(
            states,
            ["initiator", "a.at0_0", "b.at0_1", "b", "a", "segment"]
        );
        assert_eq!(
            ops,
            [
                ("initiator.T0", 0, 1),
                ("initiator.T1", 0, 2),
                ("a.at0_0.T0", 1, 3),
                ("a.at0_0.T1", 1, 3),
                ("b.at0_1.T0", 2, 3),
                ("b.at0_1.T1", 2, 5),
                ("b.T0", 3, 4),
                ("b.T1", 3, 5),
                ("a.T0", 4, 3),
                ("a.T1", 4, 3),
            ]
        );
        assert_eq!(c.occurrences, 2);
    }

    #[test]
    fn choices_read_as_the_format_says() {
        let base = "initiator 0,0 g 1,0\ngenerator g 0,0 g 1,0\n";
        let refused = [
            (
                "random r g\ninitiator 0,0 r! 1,0\ngenerator g 0,0 g 1,0\n",
                "`!`",
            ),
            ("initiator 0,0 g! 1,0\ngenerator g 0,0 g 1,0\n", "`!`"),
            (
                "age a h\ninitiator 0,0 a 1,0\ngenerator g 0,0 g 1,0\n",
                "no generator",
            ),
            (
                "age g g\ninitiator 0,0 g 1,0\ngenerator g 0,0 g 1,0\n",
                "twice",
            ),
            (
                "age a\ninitiator 0,0 g 1,0\ngenerator g 0,0 g 1,0\n",
                "lists no",
            ),
            ("seed 1\nseed 2\ninitiator 0,0 g 1,0\n", "once"),
            ("depth 13\ninitiator 0,0 g 1,0\n", "depth D"),
            ("depth 0\ninitiator 0,0 g 1,0\n", "depth D"),
            // Above depth 12: 1 + 4 + … + 4^10 = 1398101 states of occurrences > 4096.
            (
                "random r g\ndepth 12\ninitiator 0,0 r 1,0\n\
                 generator g 0,0 r 1/4,0 r 1/2,0 r 3/4,0 r 1,0\n",
                "1398101",
            ),
        ];
        for (text, says) in refused {
            let e = compiled(text)
                .err()
                .unwrap_or_else(|| panic!("{text}: compiled"));
            assert!(e.contains(says), "{text}: {e}");
        }
        // `/yx` is `/xy`; `seed` up to 2^64 − 1.
        assert!(compiled(&base.replace("g 1,0\n", "g/yx 1,0\n")).is_ok());
        assert!(compiled(&format!("seed 18446744073709551615\n{base}")).is_ok());
    }

    #[test]
    fn compiling_stops_past_the_claims_size() {
        // The age rule above compiles to 4 states and 6 operators: a claim of 3 states or 5
        // operators stops it before the rest is built.
        let text = "age t a b\ninitiator 0,0 t 1,0\ngenerator a 0,0 t 1/2,1/2 t 1,0\n\
                    generator b 0,0 t! 1/2,0 - 1,0\n";
        let r = read(text).unwrap();
        let k = rationals();
        let e = compile(&r, &k, None, 1, (3, 100)).err().unwrap();
        assert!(e.contains("more states than the claim's 3"), "{e}");
        let e = compile(&r, &k, None, 1, (100, 5)).err().unwrap();
        assert!(e.contains("more operators than the claim's 5"), "{e}");
        assert!(compile(&r, &k, None, 1, (4, 6)).is_ok());
    }
}
