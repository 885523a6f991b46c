//! The claim and the shape of a certificate: the claim as `lacuna check` prints it first, the
//! fixed structure of the steps the claim demands, and the strict grammar of numbers.

use super::Q;
use crate::certificate::{
    AutomatonClaim, Claim, Edge, Face, Kind, Pattern, SpokeItem, Step, SubstitutionClaim, System,
    VolumeRule, VolumesClaim, WordFactor,
};
use num_bigint::BigInt;
use num_traits::Zero;

/// The longest number (in characters) the checker parses: parsing is quadratic in the length,
/// so a hostile certificate must not hand it megabytes of digits. Decimal claims are capped
/// separately (10 000 digits).
pub(super) const MAX_NUMBER_CHARS: usize = 20_000;

/// The longest decimal claim the checker verifies, in digits after the point.
pub(super) const MAX_DIGITS: usize = 10_000;

fn digits_only(s: &str) -> bool {
    !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit())
}

/// A natural number in canonical form: ASCII digits, no leading zero (except `0` itself).
fn natural(s: &str) -> Option<BigInt> {
    if !digits_only(s) || (s.len() > 1 && s.starts_with('0')) {
        return None;
    }
    BigInt::parse_bytes(s.as_bytes(), 10)
}

/// A rational in the certificate's strict, canonical form: `-?N` or `-?N/D` with `N`, `D`
/// digits without leading zeros, `D > 1`, the fraction reduced, no `-0`. Underscores, a `+`,
/// spaces, `1/1` or `2/4` are refused, so every rational has exactly one spelling.
pub fn parse_rational(s: &str) -> Result<Q, String> {
    let bad = || format!("`{}` is not a rational in canonical form", shorten(s));
    if s.len() > MAX_NUMBER_CHARS {
        return Err(format!(
            "a number of {} characters exceeds the checker's limit of {MAX_NUMBER_CHARS}",
            s.len()
        ));
    }
    let (negative, body) = match s.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, s),
    };
    let (num, den) = match body.split_once('/') {
        Some((n, d)) => (natural(n).ok_or_else(bad)?, natural(d).ok_or_else(bad)?),
        None => (natural(body).ok_or_else(bad)?, BigInt::from(1)),
    };
    if den.is_zero() || (negative && num.is_zero()) || (body.contains('/') && den == 1.into()) {
        return Err(bad());
    }
    let num = if negative { -num } else { num };
    let q = Q::new(num.clone(), den.clone());
    match q.numer() == &num && q.denom() == &den {
        true => Ok(q),
        false => Err(bad()),
    }
}

/// A decimal claim in the strict grammar: digits, then (when `digits > 0`) one point and exactly
/// `digits` digits; no leading zero in the integer part (except `0`), a `-` only when the value is
/// negative. Returns the value as an integer scaled by `10^digits`.
pub fn parse_decimal(s: &str, digits: usize) -> Result<BigInt, String> {
    let bad = || format!("`{}` is not a decimal with {digits} digits", shorten(s));
    if digits > MAX_DIGITS {
        return Err(format!(
            "{digits} decimals exceed the checker's limit of {MAX_DIGITS}"
        ));
    }
    if s.len() > MAX_DIGITS + 64 {
        return Err(bad());
    }
    let (negative, body) = match s.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, s),
    };
    let (int, frac) = match (body.split_once('.'), digits) {
        (Some((i, f)), 1..) if digits_only(f) && f.len() == digits => (i, f),
        (None, 0) => (body, ""),
        _ => return Err(bad()),
    };
    natural(int).ok_or_else(bad)?;
    let value = BigInt::parse_bytes(format!("{int}{frac}").as_bytes(), 10).ok_or_else(bad)?;
    match (negative, value.is_zero()) {
        (true, true) => Err(bad()),
        (true, false) => Ok(-value),
        (false, _) => Ok(value),
    }
}

/// Whether `c` may be printed as it is. Refused: controls (which move the cursor, end the line or
/// drive the terminal), the bidirectional embeddings, overrides and isolates (which reorder what
/// the terminal shows: U+202E turns `fail` into a word read backwards), the line and paragraph
/// separators, and the invisible format characters (zero-width spaces and joiners, word
/// joiners, the byte-order mark, soft hyphen, variation selectors, fillers, tags), which hide
/// text or make two different names look alike.
fn printable(c: char) -> bool {
    let invisible = matches!(
        c,
        '\u{ad}'
            | '\u{34f}'
            | '\u{61c}'
            | '\u{115f}'..='\u{1160}'
            | '\u{17b4}'..='\u{17b5}'
            | '\u{180b}'..='\u{180f}'
            | '\u{200b}'..='\u{200f}'
            | '\u{2028}'..='\u{202e}'
            | '\u{2060}'..='\u{206f}'
            | '\u{3164}'
            | '\u{fe00}'..='\u{fe0f}'
            | '\u{feff}'
            | '\u{ffa0}'
            | '\u{fff0}'..='\u{fffb}'
            | '\u{1bca0}'..='\u{1bca3}'
            | '\u{1d173}'..='\u{1d17a}'
            | '\u{e0000}'..='\u{e0fff}'
    );
    !c.is_control() && !invisible
}

/// Text read from a certificate (a name, a label, a quoted number) as the checker prints it:
/// every character that is not [`printable`] is shown as `\u{…}` (its code point in hex), and a
/// backslash as `\\`, so the escape is unambiguous. What `check` shows is then exactly what the
/// file says: a name cannot end the line and start a fake `proved` line, nor reorder the text
/// around it. The checker escapes every line it reports (claim, messages, verdicts), so no path
/// of a hostile string to the terminal is left open.
pub fn escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '\\' => o.push_str("\\\\"),
            c if printable(c) => o.push(c),
            c => o.push_str(&format!("\\u{{{:x}}}", u32::from(c))),
        }
    }
    o
}

/// At most 40 characters of a hostile string, for messages.
pub(super) fn shorten(s: &str) -> String {
    match s.char_indices().nth(40) {
        Some((at, _)) => format!("{}…", &s[..at]),
        None => s.to_string(),
    }
}

fn edge(e: &Edge) -> String {
    let k = match e.kind {
        Kind::B => 'B',
        Kind::C => 'C',
    };
    match e.delay {
        1 => format!("{k}{}", e.n),
        d => format!("{k}{}^{d}", e.n),
    }
}

fn pattern(p: &Pattern) -> String {
    match p {
        Pattern::Any => "*".into(),
        Pattern::Kind(Kind::B) => "B".into(),
        Pattern::Kind(Kind::C) => "C".into(),
        Pattern::Exact(e) => edge(e),
    }
}

fn item(i: &SpokeItem) -> String {
    match i {
        SpokeItem::Joint => "joint".into(),
        SpokeItem::Gap => "gap".into(),
        SpokeItem::Corner => "corner".into(),
        SpokeItem::DelayedCorner => "delayed-corner".into(),
        SpokeItem::DelayedCornerNotB => "delayed-corner-not-b".into(),
        SpokeItem::CornerBetween(p, q) => format!("corner({},{})", pattern(p), pattern(q)),
    }
}

/// A face in lacuna's notation: `boundary | Ea El Ec | {items}` and ` | d` when delayed.
pub(super) fn face_text(f: &Face) -> String {
    let b: Vec<String> = f.boundary.iter().map(edge).collect();
    let items: Vec<String> = f.algorithm.iter().map(item).collect();
    let p = f.params;
    let mut s = format!(
        "{} | {} {} {} | {{{}}}",
        b.join(" "),
        edge(&p.ea),
        edge(&p.el),
        edge(&p.ec),
        items.join(" ")
    );
    if f.delay != 1 {
        s += &format!(" | {}", f.delay);
    }
    s
}

fn matrix_text(m: &[Vec<String>]) -> String {
    let rows: Vec<String> = m.iter().map(|r| format!("[{}]", r.join(", "))).collect();
    format!("[{}]", rows.join(", "))
}

/// A polynomial in `var` from its coefficients, constant term first, written from the lowest
/// power (`1/2 + 3·α + -1·α^2`) or from the highest (`1·x^2 + -3`).
pub(super) fn power_text(c: &[String], var: &str, descending: bool) -> String {
    let mut terms: Vec<String> = c
        .iter()
        .enumerate()
        .filter(|(_, x)| x.as_str() != "0")
        .map(|(i, x)| match i {
            0 => x.clone(),
            1 => format!("{x}·{var}"),
            _ => format!("{x}·{var}^{i}"),
        })
        .collect();
    if descending {
        terms.reverse();
    }
    match terms.is_empty() {
        true => "0".into(),
        false => terms.join(" + "),
    }
}

/// An element of K from its coordinates on `1, α, α², …`.
pub(super) fn field_text(c: &[String]) -> String {
    power_text(c, "α", false)
}

fn automaton_lines(a: &AutomatonClaim) -> Vec<String> {
    let mut o = Vec::new();
    let states: Vec<String> = a
        .states
        .iter()
        .map(|s| format!("{} (m = {})", s.name, s.dim))
        .collect();
    o.push(format!("automaton: states {}", states.join(", ")));
    let name = |i: usize| a.operators.get(i).map_or("?", |o| o.name.as_str());
    let state = |i: usize| a.states.get(i).map_or("?", |s| s.name.as_str());
    for op in &a.operators {
        let value = match (&op.value, &op.field_value) {
            (Some(m), _) => format!("= {}", matrix_text(m)),
            (None, Some(m)) => {
                let rows: Vec<String> = m
                    .iter()
                    .map(|r| {
                        r.iter()
                            .map(|x| field_text(x))
                            .collect::<Vec<_>>()
                            .join(" ")
                    })
                    .collect();
                format!("= [{}] (in K)", rows.join("; "))
            }
            (None, None) => "unknown".into(),
        };
        o.push(format!(
            "operator {}: {} → {} {value}",
            op.name,
            state(op.from),
            state(op.to)
        ));
    }
    let word = |w: &[WordFactor]| -> String {
        let f: Vec<String> = w
            .iter()
            .map(|f| match f {
                WordFactor::Op(i) => name(*i).to_string(),
                WordFactor::Literal(m) => matrix_text(m),
            })
            .collect();
        f.join(" * ")
    };
    for c in &a.constraints {
        o.push(format!("constraint {} = {}", word(&c.lhs), word(&c.rhs)));
    }
    let bary: Vec<&str> = a.barycentric.iter().map(|&i| name(i)).collect();
    o.push(format!(
        "barycentric (columns sum to 1): {}",
        bary.join(", ")
    ));
    if let Some(k) = &a.field {
        o.push(format!(
            "field K = Q(α), α the root of {} in [{}, {}]",
            power_text(&k.poly, "x", true),
            k.lo,
            k.hi
        ));
    }
    if let Some(at) = &a.attractor {
        let points: Vec<String> = at
            .points
            .iter()
            .map(|p| {
                let c: Vec<String> = p.iter().map(|x| field_text(x)).collect();
                format!("({})", c.join(", "))
            })
            .collect();
        o.push(format!(
            "attractor of state {} with control points {}",
            state(at.start),
            points.join(" ")
        ));
        let subs: Vec<&str> = at.subdivision.iter().map(|&i| name(i)).collect();
        o.push(format!("subdivision operators: {}", subs.join(", ")));
    }
    if let Some(r) = &a.rule {
        // The count only: the text is the certificate's, printed nowhere.
        o.push(format!(
            "compiled from a rule text of {} lines (in the certificate)",
            r.lines().count()
        ));
    }
    o
}

fn substitution_lines(s: &SubstitutionClaim) -> Vec<String> {
    let mut o: Vec<String> = s
        .matrix
        .iter()
        .enumerate()
        .map(|(t, row)| {
            let subs: Vec<String> = row.iter().map(|(s, k)| format!("{k}×{s}")).collect();
            let c = s
                .contribution_halves
                .get(t)
                .map_or("?".into(), |h| Q::new((*h).into(), 2.into()).to_string());
            format!(
                "substitution: type {t} → {} (lacunas {c})",
                match subs.is_empty() {
                    true => "nothing".into(),
                    false => subs.join(" + "),
                }
            )
        })
        .collect();
    let start: Vec<String> = s.start.iter().map(|(t, k)| format!("{k}×{t}")).collect();
    o.push(format!("start: {}", start.join(" + ")));
    if s.contribution_halves.len() != s.matrix.len() {
        o.push(format!(
            "{} contributions for {} types",
            s.contribution_halves.len(),
            s.matrix.len()
        ));
    }
    o
}

fn system_lines(s: &System) -> Vec<String> {
    let mut o = vec![format!(
        "linear system (as given): {} rows over {} unknowns",
        s.rows.len(),
        s.unknowns
    )];
    for r in &s.rows {
        let terms: Vec<String> = r.terms.iter().map(|(v, c)| format!("{c}·x{v}")).collect();
        let lhs = match terms.is_empty() {
            true => "0".into(),
            false => terms.join(" + "),
        };
        o.push(format!("row {lhs} = {}", r.rhs));
    }
    o
}

/// The claim, one line per item, as `lacuna check` prints it before any step.
pub(super) fn claim_lines(c: &Claim) -> Vec<String> {
    match c {
        Claim::Faces(f) => {
            let mut o: Vec<String> = f
                .faces
                .iter()
                .map(|x| format!("start face {}", face_text(x)))
                .collect();
            for g in &f.glue {
                o.push(format!(
                    "glued: start face {} side {} ~ start face {} side {}, read in opposite \
                     directions",
                    g.a[0], g.a[1], g.b[0], g.b[1]
                ));
            }
            o.push(format!(
                "constraint system of THEORY §6 with Bézier degree {} and Cantor gap/piece {}",
                f.degree, f.cantor_gap
            ));
            o
        }
        Claim::Automaton(a) => automaton_lines(a),
        Claim::Substitution(s) => substitution_lines(s),
        Claim::System(s) => system_lines(s),
        Claim::Volumes(v) => volume_lines(v),
    }
}

/// One line per start volume (G, E, A, rule, delay) and one per face with its gluing
/// (`g.j`: edge j of face g).
fn volume_lines(c: &VolumesClaim) -> Vec<String> {
    let mut o = Vec::new();
    for (i, v) in c.volumes.iter().enumerate() {
        let inside = Face {
            boundary: Vec::new(),
            params: v.params,
            algorithm: v.algorithm.clone(),
            delay: 1,
        };
        let rule = match v.rule {
            VolumeRule::V1 => "V1",
            VolumeRule::V2 => "V2",
        };
        let e = face_text(&inside);
        o.push(format!(
            "start volume {i}: {} faces, G = ({}, {}), inside {}, rule {rule}, delay {}",
            v.faces.len(),
            edge(&v.radial),
            edge(&v.inner),
            e.trim_start_matches(" | "),
            v.delay
        ));
        for (f, face) in v.faces.iter().enumerate() {
            let glue: Vec<String> = v
                .glue
                .get(f)
                .map(|r| r.iter().map(|(g, j)| format!("{g}.{j}")).collect())
                .unwrap_or_default();
            o.push(format!(
                "volume {i} face {f}: {} glued to {}",
                face_text(face),
                glue.join(" ")
            ));
        }
    }
    for s in &c.shared {
        o.push(format!(
            "shared face: volume {} face {} edge {} lies on volume {} face {} edge {}",
            s.a[0], s.a[1], s.a[2], s.b[0], s.b[1], s.b[2]
        ));
    }
    o.push(format!("counts certified at levels 0 to {}", c.levels));
    o
}

/// The steps a complete certificate of this claim has, in order: each slot lists the step
/// names that may fill it, and whether the claim needs it (an optional slot states a further
/// verdict: an automaton's contraction and similarity dimension are certified where lacuna
/// decides them, and a certificate without them proves the rest).
fn slots(c: &Claim) -> &'static [(&'static [&'static str], bool)] {
    const SYSTEM: &[&str] = &["solution-space", "inconsistent"];
    const GIVEN: &[&str] = &["constraints-hold", "constraint-fails"];
    match c {
        Claim::Faces(_) => &[
            (&["closure"], true),
            (SYSTEM, true),
            (&["degeneracy"], false),
            (&["limit-ratio"], true),
            (&["face-homology"], false),
            (&["level-one"], false),
        ],
        // Every operator given: the constraints are evaluated, there is no system to solve.
        Claim::Automaton(a)
            if a.operators
                .iter()
                .all(|o| o.value.is_some() || o.field_value.is_some()) =>
        {
            &[
                (GIVEN, true),
                (&["contraction"], false),
                (&["similarity-dimension"], false),
                (&["boundary-dimension"], false),
                (&["multiplicity"], false),
                (&["rule-compilation"], false),
            ]
        }
        Claim::Automaton(_) => &[
            (SYSTEM, true),
            (&["contraction"], false),
            (&["similarity-dimension"], false),
            (&["boundary-dimension"], false),
            (&["multiplicity"], false),
            (&["rule-compilation"], false),
        ],
        Claim::System(_) => &[(SYSTEM, true)],
        Claim::Substitution(_) => &[(&["limit-ratio"], true)],
        Claim::Volumes(_) => &[
            (&["volume-closure"], true),
            (&["limit-ratio"], true),
            (&["solid-homology"], false),
            (&["solid-recurrence"], false),
            (&["volume-solution-space"], false),
            (&["degeneracy"], false),
        ],
    }
}

/// Checks the fixed structure: the steps fill the claim's slots in order, each at most once,
/// the closure first for faces. Returns the needed slots left empty (a partial certificate),
/// or why the certificate is refused as a whole.
pub(super) fn structure(c: &Claim, steps: &[Step]) -> Result<Vec<String>, String> {
    let slots = slots(c);
    let expected: Vec<String> = slots
        .iter()
        .map(|(s, needed)| match needed {
            true => s.join(" or "),
            false => format!("optionally {}", s.join(" or ")),
        })
        .collect();
    let shape = || {
        format!(
            "a certificate of this claim has, in this order, {}",
            expected.join(", then ")
        )
    };
    if steps.is_empty() {
        return Err(format!("the certificate has no step; {}", shape()));
    }
    let mut filled = vec![false; slots.len()];
    let mut next = 0;
    for (i, s) in steps.iter().enumerate() {
        let name = s.name();
        match (next..slots.len()).find(|&j| slots[j].0.contains(&name)) {
            Some(j) => {
                filled[j] = true;
                next = j + 1;
            }
            None => {
                return Err(format!(
                    "step {i} ({name}) is repeated, out of order or foreign to the claim: {}",
                    shape()
                ))
            }
        }
    }
    if let Claim::Faces(f) = c {
        if !f.glue.is_empty() {
            // The gluing is read by face-homology only; a malformed one is refused whatever
            // the steps.
            super::face_homology::start_faces(f).map_err(|e| format!("the claim's gluing: {e}"))?;
        }
    }
    if matches!(c, Claim::Faces(_) | Claim::Volumes(_)) && !filled[0] {
        return Err(format!(
            "no closure step: every other step is tied to it; {}",
            shape()
        ));
    }
    Ok(slots
        .iter()
        .zip(expected)
        .zip(filled)
        .filter(|(((_, needed), _), f)| *needed && !f)
        .map(|((_, e), _)| e)
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rationals_have_one_spelling() {
        for ok in [
            "0",
            "1",
            "-3",
            "1/2",
            "-7/12",
            "123456789012345678901234567890",
        ] {
            assert_eq!(parse_rational(ok).unwrap().to_string(), ok);
        }
        for bad in [
            "", "-", "+1", "1_0", "01", "-0", "1/1", "2/4", "1/0", "1/", "/2", " 1", "1.5", "0/3",
            "1/-2", "--1", "1/01",
        ] {
            assert!(parse_rational(bad).is_err(), "{bad:?} accepted");
        }
    }

    #[test]
    fn decimals_follow_the_strict_grammar() {
        assert_eq!(parse_decimal("0.333", 3).unwrap(), BigInt::from(333));
        assert_eq!(parse_decimal("12", 0).unwrap(), BigInt::from(12));
        assert_eq!(parse_decimal("-1.50", 2).unwrap(), BigInt::from(-150));
        for (bad, k) in [
            ("3._333", 4),
            ("333._3_3_3", 7),
            (".333", 3),
            ("0.333", 4),
            ("0.3333", 3),
            ("+0.333", 3),
            ("-0.000", 3),
            ("00.333", 3),
            ("0.", 0),
            ("0.", 1),
            ("0.33 ", 3),
            ("1e3", 0),
            ("0,333", 3),
        ] {
            assert!(parse_decimal(bad, k).is_err(), "{bad:?} accepted");
        }
        assert!(parse_decimal("0.1", MAX_DIGITS + 1).is_err());
    }
}
