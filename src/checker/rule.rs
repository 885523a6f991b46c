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
//! Rules with the `age` or `random` extensions are not re-compiled here (the step fails, saying
//! so): their states depend on ages and seeded draws.

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
    Fertile(usize, Flip),
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

/// The rule read: the field's generator name (with the polynomial and interval it declares),
/// the initiator's words and each generator's name and words.
struct Read<'a> {
    field: Option<(String, P, Q, Q)>,
    initiator: Option<Vec<&'a str>>,
    generators: Vec<(String, Vec<&'a str>)>,
}

fn read(text: &str) -> Result<Read<'_>, String> {
    let mut r = Read {
        field: None,
        initiator: None,
        generators: Vec::new(),
    };
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
            "generator" if words.len() >= 2 => {
                if r.generators.iter().any(|g| g.0 == words[1]) {
                    return Err(format!("{}: generator {} declared twice", at(), words[1]));
                }
                r.generators
                    .push((words[1].to_string(), words[2..].to_vec()))
            }
            "age" | "random" | "seed" | "depth" => {
                return Err(format!(
                    "{}: the rule uses `{head}`; the checker re-compiles rules without the age \
                     and random extensions only",
                    at()
                ))
            }
            _ => return Err(format!("{}: `{head}` is no line of a rule", at())),
        }
    }
    Ok(r)
}

/// A path's words: points `x,y` and flags between them.
fn path(
    words: &[&str],
    k: &Field,
    var: Option<&str>,
    names: &[(String, Vec<&str>)],
) -> Result<Path, String> {
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
                let (name, flip) = match w.split_once('/') {
                    None => (*w, Flip::Plain),
                    Some((n, "y")) => (n, Flip::Y),
                    Some((n, "x")) => (n, Flip::X),
                    Some((n, "xy")) => (n, Flip::XY),
                    Some(_) => return Err(format!("`{w}` is no flag")),
                };
                let g = names
                    .iter()
                    .position(|(n, _)| n == name)
                    .ok_or_else(|| format!("`{name}` names no generator"))?;
                Flag::Fertile(g, flip)
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

/// A compiled operator: the state it leaves (row state), the state it enters (column state),
/// and its columns (points in the row state's frame).
enum Piece {
    Fertile(Aff, usize),
    Drawn([P; 2], [P; 2]),
}

fn pieces(k: &Field, p: &Path, m: &Aff) -> Vec<Piece> {
    let mut out = Vec::new();
    for (i, f) in p.flags.iter().enumerate() {
        let (a, b) = (&p.points[i], &p.points[i + 1]);
        match *f {
            Flag::Gap => {}
            Flag::Drawn => out.push(Piece::Drawn(apply(k, m, a), apply(k, m, b))),
            Flag::Fertile(g, flip) => out.push(Piece::Fertile(then(k, m, &onto(k, a, b, flip)), g)),
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
    let init_words = r.initiator.as_ref().ok_or("the rule has no initiator")?;
    let initiator = path(init_words, &k, var, &r.generators)?;
    let gens = r
        .generators
        .iter()
        .map(|(_, w)| path(w, &k, var, &r.generators))
        .collect::<Result<Vec<_>, _>>()?;
    // The initiator's pieces: fertile segments already replaced by their generator.
    let mut init = Vec::new();
    for (i, f) in initiator.flags.iter().enumerate() {
        let (p, q) = (&initiator.points[i], &initiator.points[i + 1]);
        match *f {
            Flag::Gap => {}
            Flag::Drawn => init.push(Piece::Drawn(p.clone(), q.clone())),
            Flag::Fertile(g, flip) => init.extend(pieces(&k, &gens[g], &onto(&k, p, q, flip))),
        }
    }
    // Generator states reached, breadth first.
    let mut order: Vec<usize> = Vec::new();
    let reach = |ps: &[Piece], order: &mut Vec<usize>| {
        for p in ps {
            if let Piece::Fertile(_, g) = p {
                if !order.contains(g) {
                    order.push(*g);
                }
            }
        }
    };
    reach(&init, &mut order);
    let mut all = Vec::new();
    let mut i = 0;
    while i < order.len() {
        let ps = pieces(&k, &gens[order[i]], &identity());
        reach(&ps, &mut order);
        all.push(ps);
        i += 1;
    }
    let n0 = initiator.points.len();
    let mut states: Vec<(String, usize)> = vec![("initiator".into(), 3 + n0)];
    states.extend(order.iter().map(|&g| (r.generators[g].0.clone(), 3)));
    states.push(("segment".into(), 2));
    let segment = states.len() - 1;
    let got: Vec<(String, usize)> = a.states.iter().map(|s| (s.name.clone(), s.dim)).collect();
    if got != states {
        return Err(format!(
            "the claim's states {got:?} are not the compiled ones {states:?}"
        ));
    }
    let frame = [
        [P::new(), P::new()],
        [rational(Q::one()), P::new()],
        [P::new(), rational(Q::one())],
    ];
    let mut expected: Vec<(String, usize, usize, KMat)> = Vec::new();
    let lists =
        std::iter::once((0usize, &init)).chain(all.iter().enumerate().map(|(j, ps)| (j + 1, ps)));
    for (s, ps) in lists {
        let rows = states[s].1;
        for (j, p) in ps.iter().enumerate() {
            let name = format!("{}.T{j}", states[s].0);
            match p {
                Piece::Fertile(m, g) => {
                    let to = 1 + order.iter().position(|x| x == g).unwrap_or(0);
                    let cols: Vec<Vec<P>> = frame
                        .iter()
                        .map(|e| column(&k, &apply(&k, m, e), rows))
                        .collect();
                    expected.push((name, s, to, matrix(&cols)));
                }
                Piece::Drawn(x, y) => {
                    let cols = [column(&k, x, rows), column(&k, y, rows)];
                    expected.push((name, s, segment, matrix(&cols)));
                }
            }
        }
    }
    if a.operators.len() != expected.len() {
        return Err(format!(
            "the claim has {} operators, the compilation {}",
            a.operators.len(),
            expected.len()
        ));
    }
    for (o, (name, to, from, m)) in a.operators.iter().zip(&expected) {
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
    let n = expected.len();
    let every: Vec<usize> = (0..n).collect();
    if !a.constraints.is_empty() || a.barycentric != every {
        return Err("a compiled rule has no constraint and every operator barycentric".into());
    }
    let at = a.attractor.as_ref().ok_or("the claim has no attractor")?;
    let mut points: Vec<[P; 2]> = frame.to_vec();
    points.extend(initiator.points.iter().cloned());
    let same_points = at.points.len() == points.len()
        && at.points.iter().zip(&points).all(|(c, p)| {
            c.len() == 2
                && c.iter().zip(p).all(|(x, y)| {
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
    let msg = format!(
        "the claim's rule read and compiled by the checker: {} states, {n} operators (every \
         fertile segment's similitude with its reflection, in the frame of its state, drawn \
         segments into `segment`), equal to the claim's exactly{}",
        states.len(),
        match var {
            Some(v) => format!(" in K = Q({v})"),
            None => String::new(),
        }
    );
    Ok((
        msg,
        format!(
            "the automaton is the compilation of its rule ({} generator states reached)",
            order.len()
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

    #[test]
    fn the_dragon_piece_by_hand() {
        // The first piece of `left 0,0 left 1/2,1/2 right 1,0`: the similitude taking (0,0) to
        // (0,0) and (1,0) to (1/2,1/2) takes (0,1) to (−1/2, 1/2); in barycentric coordinates
        // of the frame (1 − x − y, x, y): (1,0,0), (0, 1/2, 1/2), (1, −1/2, 1/2).
        let a = AutomatonClaim {
            states: Vec::new(),
            operators: Vec::new(),
            constraints: Vec::new(),
            barycentric: Vec::new(),
            field: None,
            attractor: None::<AttractorClaim>,
            rule: None,
        };
        let k = Field::of(&a).unwrap();
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
}
