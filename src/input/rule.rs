//! Kaandorp's production rules: an initiator and generators, written as point lists
//! whose segments carry flags, read from a `.rule` file and compiled to an automaton
//! (documented in `docs/FORMATS.md`, "Rule files").
//!
//! ```text
//! # The Koch curve: every segment becomes four of a third.
//! field s = root of x^2 - 3 in [1, 2]
//! initiator 0,0 koch 1,0
//! generator koch 0,0 koch 1/3,0 koch 1/2,1/6s koch 2/3,0 koch 1,0
//! ```
//!
//! Between two points stands the flag of the segment joining them: a generator's name (the
//! segment is fertile and replaced by that generator), optionally followed by `/y` (mirrored
//! across the segment), `/x` (run backwards) or `/xy` (both); `-` (infertile: the segment stays
//! as drawn); `.` (no segment: the pen jumps, for generators of several parts). The `age`
//! extension chooses the generator by the age of the fractal a segment belongs to; the `random`
//! extension draws it from a seed and the segment's place (reproducible), per occurrence down to
//! a depth and once per generator segment below it.
//!
//! ## The compiled automaton
//! The representation is the affine frame of the plane: every generator state has the three
//! control points `(0,0)`, `(1,0)`, `(0,1)` of its own coordinates, and the operator of a fertile
//! segment from P to Q holds, column by column, the barycentric coordinates of the images of
//! those three points under the similitude `z ↦ P + (Q − P)·ρ(z)` (ρ the segment's reflection:
//! identity, `z̄`, `1 − z̄` or `1 − z`). Three points are the fewest whose barycentric combinations
//! reach the whole plane, so one exact 3×3 matrix carries the rotation, the scaling, the
//! translation and the reflection; two control points (the segment's ends) reach only their line
//! and could not place a generator's bend, nor tell a mirrored copy from the plain one. Because
//! the reflection is composed into the operator, a generator drawn mirrored needs no state of
//! its own: the states are one per generator (per generator and age with `age`, per occurrence
//! above the depth with `random`),
//! plus `initiator` (the start) and `segment` (a two-point leaf drawn as a line, reached through
//! one operator per infertile segment). The initiator's operators are the generators already
//! placed on its segments, so the automaton's level n is the rule's n-th replacement exactly:
//! level 0 draws the initiator, and a generator state reached at depth n is drawn as its segment.

use crate::algebra::algebraic::{FieldElement, NumberField, RealAlgebraic};
use crate::error::{Error, Result, Source};
use crate::input::automaton_model::{
    parse_field_decl, parse_field_element, parse_model, AutomatonModel,
};
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::collections::HashMap;
use std::fmt::Write as _;

/// How a generator is laid on a segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flip {
    /// As drawn (Kaandorp's direction 1).
    Plain,
    /// Mirrored across the segment, `(x, y) ↦ (x, −y)` (direction 2).
    Y,
    /// Run backwards, `(x, y) ↦ (1 − x, y)` (direction 3).
    X,
    /// Both, `(x, y) ↦ (1 − x, −y)` (direction 4).
    XY,
}

/// What replaces a fertile segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A generator, by index.
    Generator(usize),
    /// An age choice, by index: the generator is the choice's entry at the segment's age.
    Age {
        /// The choice's index.
        choice: usize,
        /// True (`NAME!`): the segment starts a new fractal, of age 0.
        restart: bool,
    },
    /// A random choice, by index: the generator is drawn from the seed and the segment's place
    /// (see [`Rule::random_pick`]).
    Random(usize),
}

/// A segment between two consecutive points of a path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Segment {
    /// Replaced at the next step.
    Fertile {
        /// By what.
        target: Target,
        /// Laid how.
        flip: Flip,
    },
    /// Stays as drawn.
    Drawn,
    /// No segment (the pen jumps).
    Gap,
}

/// A point list with the flag of each segment (`segments.len() == points.len() − 1`).
#[derive(Clone, Debug)]
pub struct RulePath {
    /// The points, exact.
    pub points: Vec<[FieldElement; 2]>,
    /// The segments.
    pub segments: Vec<Segment>,
}

/// A production rule.
#[derive(Clone, Debug)]
pub struct Rule {
    /// The field of the coordinates (Q without a `field` line).
    pub field: NumberField,
    /// The generator's name and the declaration, when a field is declared.
    pub field_decl: Option<(String, String)>,
    /// The initiator (level 0).
    pub initiator: RulePath,
    /// The generators: name and path on the unit segment `(0,0)`–`(1,0)`.
    pub generators: Vec<(String, RulePath)>,
    /// Age choices: name and the generator of each age (the age runs modulo the length).
    pub ages: Vec<(String, Vec<usize>)>,
    /// Random choices: name and the generators drawn from.
    pub randoms: Vec<(String, Vec<usize>)>,
    /// The seed of the random choices (`seed N`, default 0).
    pub seed: u64,
    /// The depth down to which random choices are drawn per occurrence (`depth D`, default 4).
    pub depth: usize,
}

/// The most states a rule with random choices may unroll to (checked before compiling).
pub const MAX_RANDOM_STATES: u64 = 4096;

/// SplitMix64's finaliser: the hash of the random choices (documented in docs/FORMATS.md so
/// that the drawing is reproducible by any implementation).
pub fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// True when a text is a rule file: one of its lines starts with `initiator` or `generator`
/// (automaton files have no such line; comments and `field` may come first).
pub fn is_rule(text: &str) -> bool {
    text.lines().any(|l| {
        matches!(
            l.split('#').next().unwrap_or("").split_whitespace().next(),
            Some("initiator" | "generator")
        )
    })
}

fn valid_name(n: &str) -> bool {
    n.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
        && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A flag as written, before names are resolved: name, restart, flip.
#[derive(Clone, Debug)]
enum RawSeg {
    Named(String, bool, Flip),
    Drawn,
    Gap,
}

/// A path as written, with the position of each flag for errors.
struct RawPath {
    points: Vec<[FieldElement; 2]>,
    segs: Vec<(RawSeg, usize, usize, usize)>,
}

/// Reads the tokens `P FLAG P FLAG … P` of a path; `toks` are (column, text).
fn read_path(
    toks: &[(usize, &str)],
    k: &NumberField,
    gen: Option<&str>,
    ln: usize,
    line_len: usize,
    src: &Source,
) -> Result<RawPath> {
    if toks.len() < 3 || toks.len() % 2 == 0 {
        let (c, l) = toks
            .first()
            .map_or((line_len.max(1), 1), |(c, _)| (*c, line_len + 1 - *c));
        return Err(Error::at(
            "E1301",
            "a path is `POINT FLAG POINT … POINT`: points `x,y` with one flag between two points (at least one segment)",
            ln,
            c,
            l,
            src,
        ));
    }
    let mut points = Vec::new();
    let mut segs = Vec::new();
    for (i, (c, t)) in toks.iter().enumerate() {
        if i % 2 == 0 {
            let p = t.split_once(',').and_then(|(x, y)| {
                Some([
                    parse_field_element(x, k, gen)?,
                    parse_field_element(y, k, gen)?,
                ])
            });
            let Some(p) = p else {
                return Err(Error::at(
                    "E1302",
                    match gen {
                        Some(g) => format!("`{t}` is not a point `x,y` of exact numbers or polynomials in `{g}` (e.g. 1/2,1/6{g})"),
                        None => format!("`{t}` is not a point `x,y` of exact numbers (e.g. 1/3,0 or 0.5,-0.25)"),
                    },
                    ln,
                    *c,
                    t.chars().count(),
                    src,
                ));
            };
            points.push(p);
        } else {
            let seg = match *t {
                "-" => RawSeg::Drawn,
                "." => RawSeg::Gap,
                _ => {
                    let (head, flip) = match t.split_once('/') {
                        None => (*t, Some(Flip::Plain)),
                        Some((h, "y")) => (h, Some(Flip::Y)),
                        Some((h, "x")) => (h, Some(Flip::X)),
                        Some((h, "xy" | "yx")) => (h, Some(Flip::XY)),
                        Some((h, _)) => (h, None),
                    };
                    let (name, restart) = match head.strip_suffix('!') {
                        Some(n) => (n, true),
                        None => (head, false),
                    };
                    match flip {
                        Some(f) if valid_name(name) => RawSeg::Named(name.to_string(), restart, f),
                        _ => {
                            return Err(Error::at(
                                "E1303",
                                format!("`{t}` is not a segment flag: a generator's name (fertile), optionally with `!` and `/y`, `/x` or `/xy`; `-` (stays); `.` (no segment)"),
                                ln,
                                *c,
                                t.chars().count(),
                                src,
                            ))
                        }
                    }
                }
            };
            segs.push((seg, ln, *c, t.chars().count()));
        }
    }
    Ok(RawPath { points, segs })
}

/// The whitespace-separated words of `line` with their columns (1-based, in characters).
fn words(line: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut start: Option<usize> = None;
    for (b, ch) in line
        .char_indices()
        .chain(std::iter::once((line.len(), ' ')))
    {
        match (ch.is_whitespace(), start) {
            (true, Some(s)) => {
                out.push((line[..s].chars().count() + 1, &line[s..b]));
                start = None;
            }
            (false, None) => start = Some(b),
            _ => {}
        }
    }
    out
}

/// A name as written, with its line and column.
type NamedAt = (String, usize, usize);

/// Parses a rule file.
pub fn parse_rule(src: &Source) -> Result<Rule> {
    let mut field = NumberField::new(RealAlgebraic::rational(BigRational::zero()));
    let mut field_decl: Option<(String, String)> = None;
    let mut initiator: Option<RawPath> = None;
    let mut gens: Vec<(String, RawPath)> = Vec::new();
    let mut ages: Vec<(String, Vec<NamedAt>)> = Vec::new();
    let mut randoms: Vec<(String, Vec<NamedAt>)> = Vec::new();
    let mut seed: Option<u64> = None;
    let mut depth: Option<(usize, usize, usize)> = None;
    let mut names: HashMap<String, (usize, usize)> = HashMap::new();
    for (ln0, raw) in src.text.lines().enumerate() {
        let ln = ln0 + 1;
        let line = raw.split('#').next().unwrap_or("");
        let ws = words(line);
        let Some(&(c0, first)) = ws.first() else {
            continue;
        };
        let gen = field_decl.as_ref().map(|(n, _)| n.clone());
        let len = line.trim_end().chars().count();
        let mut declare = |name: &str, c: usize| -> Result<()> {
            if !valid_name(name) || name == "initiator" || name == "segment" {
                return Err(Error::at(
                    "E1305",
                    format!("`{name}` is not a name for a generator (letters, digits and `_`, starting with a letter; not `initiator` or `segment`)"),
                    ln,
                    c,
                    name.chars().count(),
                    src,
                ));
            }
            if let Some((l, _)) = names.insert(name.to_string(), (ln, c)) {
                return Err(Error::at(
                    "E1305",
                    format!("`{name}` is already declared (line {l})"),
                    ln,
                    c,
                    name.chars().count(),
                    src,
                ));
            }
            Ok(())
        };
        match first {
            "field" => {
                if field_decl.is_some() || initiator.is_some() || !gens.is_empty() {
                    return Err(Error::at(
                        "E1306",
                        "one `field` line, before the paths",
                        ln,
                        c0,
                        len + 1 - c0,
                        src,
                    ));
                }
                let (k, decl) = parse_field_decl(line, line.trim(), ln, src)?;
                field = k;
                field_decl = Some(decl);
            }
            "initiator" => {
                if initiator.is_some() {
                    return Err(Error::at(
                        "E1306",
                        "a second `initiator` line (one per rule)",
                        ln,
                        c0,
                        len + 1 - c0,
                        src,
                    ));
                }
                let p = read_path(&ws[1..], &field, gen.as_deref(), ln, len, src)?;
                if let Some((_, l, c, n)) = p.segs.iter().find(|s| matches!(s.0, RawSeg::Gap)) {
                    return Err(Error::at(
                        "E1310",
                        "the initiator is one connected path: no `.` gap",
                        *l,
                        *c,
                        *n,
                        src,
                    ));
                }
                initiator = Some(p);
            }
            "generator" => {
                let Some(&(c, name)) = ws.get(1) else {
                    return Err(Error::at(
                        "E1301",
                        "expected `generator NAME POINT FLAG POINT …`",
                        ln,
                        c0,
                        len + 1 - c0,
                        src,
                    ));
                };
                declare(name, c)?;
                let p = read_path(&ws[2..], &field, gen.as_deref(), ln, len, src)?;
                gens.push((name.to_string(), p));
            }
            "seed" | "depth" => {
                let v = ws.get(1).map(|(_, t)| *t).unwrap_or("");
                let ok = ws.len() == 2
                    && match first {
                        "seed" => seed.is_none(),
                        _ => depth.is_none(),
                    };
                match (first, v.parse::<u64>()) {
                    ("seed", Ok(n)) if ok => seed = Some(n),
                    ("depth", Ok(d @ 1..=12)) if ok => depth = Some((d as usize, ln, c0)),
                    _ => {
                        return Err(Error::at(
                            "E1311",
                            "expected `seed N` (0 to 2^64 − 1) or `depth D` (1 to 12), once",
                            ln,
                            c0,
                            len + 1 - c0,
                            src,
                        ))
                    }
                }
            }
            "age" | "random" => {
                let Some(&(c, name)) = ws.get(1) else {
                    return Err(Error::at(
                        "E1309",
                        "expected `age NAME GENERATOR …` or `random NAME GENERATOR …`",
                        ln,
                        c0,
                        len + 1 - c0,
                        src,
                    ));
                };
                declare(name, c)?;
                if ws.len() < 3 {
                    return Err(Error::at(
                        "E1309",
                        "a choice names at least one generator",
                        ln,
                        c,
                        name.chars().count(),
                        src,
                    ));
                }
                let entry = (
                    name.to_string(),
                    ws[2..]
                        .iter()
                        .map(|(c, t)| (t.to_string(), ln, *c))
                        .collect(),
                );
                if first == "age" {
                    ages.push(entry);
                } else {
                    randoms.push(entry);
                }
            }
            other => {
                return Err(Error::at(
                    "E1308",
                    format!(
                    "`{other}`: a rule file has `field`, `initiator`, `generator`, `age`, `random`, `seed` and `depth` lines{}",
                    crate::input::suggest::did_you_mean(
                        other,
                        &["field", "initiator", "generator", "age", "random", "seed", "depth"]
                    )
                    .map_or(String::new(), |k| format!(": did you mean `{k}`?"))
                ),
                    ln,
                    c0,
                    other.chars().count(),
                    src,
                ))
            }
        }
    }
    let Some(init) = initiator else {
        return Err(Error::at(
            "E1306",
            "a rule needs an `initiator` line",
            1,
            1,
            1,
            src,
        ));
    };
    let gen_index: HashMap<String, usize> = gens
        .iter()
        .enumerate()
        .map(|(i, (n, _))| (n.clone(), i))
        .collect();
    let age_index: HashMap<String, usize> = ages
        .iter()
        .enumerate()
        .map(|(i, (n, _))| (n.clone(), i))
        .collect();
    let random_index: HashMap<String, usize> = randoms
        .iter()
        .enumerate()
        .map(|(i, (n, _))| (n.clone(), i))
        .collect();
    let mut resolved_ages = Vec::new();
    let mut resolved_randoms = Vec::new();
    for (is_age, (name, entries)) in ages
        .iter()
        .map(|x| (true, x))
        .chain(randoms.iter().map(|x| (false, x)))
    {
        let mut seq = Vec::new();
        for (g, l, c) in entries {
            let Some(&i) = gen_index.get(g) else {
                return Err(Error::at(
                    "E1304",
                    format!("`{g}` is not a generator (a choice lists generators)"),
                    *l,
                    *c,
                    g.chars().count(),
                    src,
                ));
            };
            seq.push(i);
        }
        if is_age {
            resolved_ages.push((name.clone(), seq));
        } else {
            resolved_randoms.push((name.clone(), seq));
        }
    }
    let resolve = |p: RawPath| -> Result<RulePath> {
        let mut segments = Vec::new();
        for (i, (s, l, c, n)) in p.segs.into_iter().enumerate() {
            let seg = match s {
                RawSeg::Drawn => Segment::Drawn,
                RawSeg::Gap => Segment::Gap,
                RawSeg::Named(name, restart, flip) => {
                    let target = match (gen_index.get(&name), age_index.get(&name)) {
                        (Some(&g), _) if !restart => Target::Generator(g),
                        (_, Some(&a)) => Target::Age { choice: a, restart },
                        _ if random_index.contains_key(&name) && !restart => {
                            Target::Random(random_index[&name])
                        }
                        _ if gen_index.contains_key(&name) || random_index.contains_key(&name) => {
                            return Err(Error::at(
                                "E1303",
                                format!("`{name}!`: `!` (a new fractal of age 0) applies to age choices, and `{name}` is not one"),
                                l,
                                c,
                                n,
                                src,
                            ))
                        }
                        _ => {
                            return Err(Error::at(
                                "E1304",
                                format!("no generator, age or random choice `{name}`"),
                                l,
                                c,
                                n,
                                src,
                            ))
                        }
                    };
                    Segment::Fertile { target, flip }
                }
            };
            if seg != Segment::Gap && p.points[i] == p.points[i + 1] {
                return Err(Error::at(
                    "E1307",
                    "a segment of length 0 (its two points are equal): no similitude maps the unit segment onto it",
                    l,
                    c,
                    n,
                    src,
                ));
            }
            segments.push(seg);
        }
        Ok(RulePath {
            points: p.points,
            segments,
        })
    };
    let initiator = resolve(init)?;
    let mut generators = Vec::new();
    for (n, p) in gens {
        generators.push((n, resolve(p)?));
    }
    let depth_at = depth;
    let rule = Rule {
        field,
        field_decl,
        initiator,
        generators,
        ages: resolved_ages,
        randoms: resolved_randoms,
        seed: seed.unwrap_or(0),
        depth: depth.map_or(4, |d| d.0),
    };
    // With random choices every occurrence above the depth is a state of its own: bound their
    // number before compiling (initiator segments × Σ F^d, F the most fertile segments of a
    // generator).
    if !rule.randoms.is_empty() {
        let fertile = |p: &RulePath| {
            p.segments
                .iter()
                .filter(|s| matches!(s, Segment::Fertile { .. }))
                .count() as u64
        };
        let f = rule
            .generators
            .iter()
            .map(|(_, p)| fertile(p))
            .max()
            .unwrap_or(0);
        let mut level = fertile(&rule.initiator);
        let mut total = 0u64;
        for _ in 1..rule.depth {
            total = total.saturating_add(level);
            level = level.saturating_mul(f);
        }
        if total > MAX_RANDOM_STATES {
            let (ln, c) = depth_at.map_or((1, 1), |d| (d.1, d.2));
            return Err(Error::at(
                "E1311",
                format!("random choices drawn per occurrence down to depth {} make up to {total} states (at most {MAX_RANDOM_STATES}): lower `depth`", rule.depth),
                ln,
                c,
                1,
                src,
            ));
        }
    }
    Ok(rule)
}

/// An affine map of the plane, `(x, y) ↦ (a·x + b·y + e, c·x + d·y + f)`, exact.
#[derive(Clone, Debug, PartialEq)]
pub struct Affine(pub [FieldElement; 6]);

impl Affine {
    /// The identity.
    pub fn identity(k: &NumberField) -> Self {
        let (z, o) = (
            k.rational(BigRational::zero()),
            k.rational(BigRational::one()),
        );
        Affine([o.clone(), z.clone(), z.clone(), o, z.clone(), z])
    }

    /// The similitude mapping `(0,0)` to P and `(1,0)` to Q, composed with the reflection.
    pub fn onto(k: &NumberField, p: &[FieldElement; 2], q: &[FieldElement; 2], flip: Flip) -> Self {
        let dx = k.sub(&q[0], &p[0]);
        let dy = k.sub(&q[1], &p[1]);
        let s = Affine([
            dx.clone(),
            k.sub(&k.rational(BigRational::zero()), &dy),
            dy.clone(),
            dx,
            p[0].clone(),
            p[1].clone(),
        ]);
        let (z, o) = (
            k.rational(BigRational::zero()),
            k.rational(BigRational::one()),
        );
        let m = k.rational(-BigRational::one());
        let r = match flip {
            Flip::Plain => return s,
            Flip::Y => Affine([o.clone(), z.clone(), z.clone(), m, z.clone(), z]),
            Flip::X => Affine([m, z.clone(), z.clone(), o.clone(), o, z]),
            Flip::XY => Affine([m.clone(), z.clone(), z.clone(), m, o, z]),
        };
        s.then(k, &r)
    }

    /// `self ∘ other` (other first).
    pub fn then(&self, k: &NumberField, o: &Affine) -> Self {
        let [a, b, c, d, e, f] = &self.0;
        let [a2, b2, c2, d2, e2, f2] = &o.0;
        let mul_add = |x: &FieldElement, y: &FieldElement, u: &FieldElement, v: &FieldElement| {
            k.add(&k.mul(x, y), &k.mul(u, v))
        };
        Affine([
            mul_add(a, a2, b, c2),
            mul_add(a, b2, b, d2),
            mul_add(c, a2, d, c2),
            mul_add(c, b2, d, d2),
            k.add(&mul_add(a, e2, b, f2), e),
            k.add(&mul_add(c, e2, d, f2), f),
        ])
    }

    /// The image of a point.
    pub fn apply(&self, k: &NumberField, p: &[FieldElement; 2]) -> [FieldElement; 2] {
        let [a, b, c, d, e, f] = &self.0;
        [
            k.add(&k.add(&k.mul(a, &p[0]), &k.mul(b, &p[1])), e),
            k.add(&k.add(&k.mul(c, &p[0]), &k.mul(d, &p[1])), f),
        ]
    }
}

/// A state of the compiled automaton: a generator and, with an age choice, (choice, age).
type Key = (usize, Option<(usize, usize)>, Option<Vec<u32>>);

/// One operator out of a state: a fertile piece (map, target state) or a drawn segment (its two
/// ends, in the state's coordinates).
enum Piece {
    Fertile(Affine, Key),
    Drawn([FieldElement; 2], [FieldElement; 2]),
}

impl Rule {
    /// The generator a random choice draws for the segment at `place`: `place` is the list of
    /// segment indices from the initiator down to the segment (per occurrence, down to the
    /// depth), or `[u32::MAX, generator, index]` below the depth (once per generator segment).
    /// The draw is `h mod n` with `h = seed`, then `h = splitmix64(h ^ x)` for each x of
    /// `place`.
    pub fn random_pick(&self, choice: usize, place: &[u32]) -> usize {
        let mut h = self.seed;
        for &x in place {
            h = splitmix64(h ^ u64::from(x));
        }
        let seq = &self.randoms[choice].1;
        seq[(h % seq.len() as u64) as usize]
    }

    /// The state the fertile segment `j` of a state `parent` leads to (`parent` is `None` for the
    /// initiator).
    fn target(&self, t: Target, parent: Option<&Key>, j: usize) -> Key {
        let j = j as u32;
        let ctx = parent.and_then(|k| k.1);
        // The segment's place: per occurrence while the parent knows its own.
        let place: Option<Vec<u32>> = match parent {
            None => Some(vec![j]),
            Some(k) => k.2.as_ref().map(|p| [p.as_slice(), &[j]].concat()),
        };
        let gen = match t {
            Target::Generator(g) => return (g, None, self.keep(place)),
            Target::Age { choice, restart } => {
                let n = self.ages[choice].1.len();
                let age = match ctx {
                    Some((c, a)) if c == choice && !restart => (a + 1) % n,
                    _ => 0,
                };
                return (
                    self.ages[choice].1[age],
                    Some((choice, age)),
                    self.keep(place),
                );
            }
            Target::Random(choice) => match &place {
                Some(p) if p.len() <= self.depth => self.random_pick(choice, p),
                _ => {
                    let g = parent.map_or(u32::MAX - 1, |k| k.0 as u32);
                    self.random_pick(choice, &[u32::MAX, g, j])
                }
            },
        };
        (gen, None, self.keep(place))
    }

    /// A place is kept in the state (one state per occurrence) only for rules with random
    /// choices, above the depth.
    fn keep(&self, place: Option<Vec<u32>>) -> Option<Vec<u32>> {
        place.filter(|p| !self.randoms.is_empty() && p.len() < self.depth)
    }

    /// The pieces of a path laid by `map`, for the state `key` (`None`: the initiator's place).
    fn pieces(&self, path: &RulePath, map: &Affine, key: &Key) -> Vec<Piece> {
        let k = &self.field;
        let mut out = Vec::new();
        for (i, s) in path.segments.iter().enumerate() {
            let (p, q) = (&path.points[i], &path.points[i + 1]);
            match s {
                Segment::Gap => {}
                Segment::Drawn => out.push(Piece::Drawn(map.apply(k, p), map.apply(k, q))),
                Segment::Fertile { target, flip } => out.push(Piece::Fertile(
                    map.then(k, &Affine::onto(k, p, q, *flip)),
                    self.target(*target, Some(key), i),
                )),
            }
        }
        out
    }

    /// The automaton file this rule compiles to (see the module documentation).
    pub fn automaton_text(&self) -> String {
        let k = &self.field;
        let gen = self.field_decl.as_ref().map(|(n, _)| n.as_str());
        let num = |v: &FieldElement| render(k, v, gen);
        // Initiator pieces: each fertile segment already replaced by its generator.
        let mut init_pieces = Vec::new();
        for (i, s) in self.initiator.segments.iter().enumerate() {
            let (p, q) = (&self.initiator.points[i], &self.initiator.points[i + 1]);
            match s {
                Segment::Gap => {}
                Segment::Drawn => init_pieces.push(Piece::Drawn(p.clone(), q.clone())),
                Segment::Fertile { target, flip } => {
                    let key = self.target(*target, None, i);
                    let map = Affine::onto(k, p, q, *flip);
                    init_pieces.extend(self.pieces(&self.generators[key.0].1, &map, &key));
                }
            }
        }
        // The reachable generator states, breadth first.
        let mut keys: Vec<Key> = Vec::new();
        let mut index: HashMap<Key, usize> = HashMap::new();
        let mut push = |key: Key, keys: &mut Vec<Key>| {
            if let std::collections::hash_map::Entry::Vacant(e) = index.entry(key.clone()) {
                e.insert(keys.len());
                keys.push(key);
            }
        };
        for p in &init_pieces {
            if let Piece::Fertile(_, key) = p {
                push(key.clone(), &mut keys);
            }
        }
        let mut all_pieces: Vec<Vec<Piece>> = Vec::new();
        let id = Affine::identity(k);
        let mut i = 0;
        while i < keys.len() {
            let key = keys[i].clone();
            let ps = self.pieces(&self.generators[key.0].1, &id, &key);
            for p in &ps {
                if let Piece::Fertile(_, key) = p {
                    push(key.clone(), &mut keys);
                }
            }
            all_pieces.push(ps);
            i += 1;
        }
        let state_name = |key: &Key| -> String {
            let g = &self.generators[key.0].0;
            let mut n = match key.1 {
                None => g.clone(),
                Some((c, a)) => format!("{g}.{}{a}", self.ages[c].0),
            };
            if let Some(p) = &key.2 {
                let p: Vec<String> = p.iter().map(u32::to_string).collect();
                n += &format!(".at{}", p.join("_"));
            }
            n
        };
        let n0 = self.initiator.points.len();
        let mut t =
            String::from("# compiled from a rule file: see docs/FORMATS.md, \"Rule files\"\n");
        if let Some((_, decl)) = &self.field_decl {
            let _ = writeln!(t, "field {decl}");
        }
        let _ = writeln!(t, "state initiator {}", 3 + n0);
        for key in &keys {
            let _ = writeln!(t, "state {} 3", state_name(key));
        }
        let _ = writeln!(t, "state segment 2");
        // Barycentric coordinates of a point in a state's frame (the first three control points
        // are (0,0), (1,0), (0,1); the initiator's other points get 0).
        let column = |p: &[FieldElement; 2], rows: usize| -> Vec<String> {
            let one = k.rational(BigRational::one());
            let mut v = vec![
                num(&k.sub(&k.sub(&one, &p[0]), &p[1])),
                num(&p[0]),
                num(&p[1]),
            ];
            v.resize(rows, "0".into());
            v
        };
        let frame = [
            [
                k.rational(BigRational::zero()),
                k.rational(BigRational::zero()),
            ],
            [
                k.rational(BigRational::one()),
                k.rational(BigRational::zero()),
            ],
            [
                k.rational(BigRational::zero()),
                k.rational(BigRational::one()),
            ],
        ];
        let matrix = |cols: Vec<Vec<String>>| -> String {
            let rows = cols[0].len();
            let r: Vec<String> = (0..rows)
                .map(|i| {
                    cols.iter()
                        .map(|c| c[i].as_str())
                        .collect::<Vec<_>>()
                        .join(" ")
                })
                .collect();
            format!("[{}]", r.join("; "))
        };
        let write_ops = |t: &mut String, from: &str, rows: usize, pieces: &[Piece]| {
            for (j, p) in pieces.iter().enumerate() {
                match p {
                    Piece::Fertile(map, key) => {
                        let cols = frame
                            .iter()
                            .map(|e| column(&map.apply(k, e), rows))
                            .collect();
                        let _ = writeln!(
                            t,
                            "sub {from}.T{j} : {from} <- {} = {}",
                            state_name(key),
                            matrix(cols)
                        );
                    }
                    Piece::Drawn(a, b) => {
                        let cols = vec![column(a, rows), column(b, rows)];
                        let _ =
                            writeln!(t, "sub {from}.T{j} : {from} <- segment = {}", matrix(cols));
                    }
                }
            }
        };
        write_ops(&mut t, "initiator", 3 + n0, &init_pieces);
        for (key, pieces) in keys.iter().zip(&all_pieces) {
            write_ops(&mut t, &state_name(key), 3, pieces);
        }
        t += "barycentric\nspace 2\nstart initiator\n";
        let mut pts: Vec<String> = frame
            .iter()
            .map(|p| format!("{} {}", num(&p[0]), num(&p[1])))
            .collect();
        pts.extend(
            self.initiator
                .points
                .iter()
                .map(|p| format!("{} {}", num(&p[0]), num(&p[1]))),
        );
        let _ = writeln!(t, "points [{}]", pts.join("; "));
        let idx: Vec<String> = (3..3 + n0).map(|i| i.to_string()).collect();
        let _ = writeln!(t, "primitive initiator polyline {}", idx.join(" "));
        for key in &keys {
            let _ = writeln!(t, "primitive {} polyline 0 1", state_name(key));
        }
        t += "primitive segment polyline 0 1\n";
        t
    }
}

/// A field element in the syntax of [`parse_field_element`].
fn render(k: &NumberField, v: &FieldElement, gen: Option<&str>) -> String {
    if let Some(q) = v.as_rational() {
        return q.to_string();
    }
    let _ = k;
    let g = gen.expect("an element outside Q needs a declared field");
    let mut s = String::new();
    for (e, c) in v.poly().coeffs().iter().enumerate() {
        if c.is_zero() {
            continue;
        }
        let sign = if c < &BigRational::zero() { "-" } else { "+" };
        let a = if c < &BigRational::zero() {
            -c.clone()
        } else {
            c.clone()
        };
        if s.is_empty() && sign == "+" {
        } else {
            s += sign;
        }
        match e {
            0 => s += &a.to_string(),
            1 => {
                let _ = write!(s, "{a}*{g}");
            }
            _ => {
                let _ = write!(s, "{a}*{g}^{e}");
            }
        }
    }
    if s.is_empty() {
        "0".into()
    } else {
        s
    }
}

/// Parses a rule file and compiles it to an automaton model (see the module documentation).
pub fn compile_rule(src: &Source) -> Result<(Rule, AutomatonModel)> {
    let rule = parse_rule(src)?;
    let text = rule.automaton_text();
    let mut model = parse_model(&Source {
        name: format!("{} (compiled)", src.name),
        text,
    })?;
    model.rule = Some(src.text.clone());
    Ok((rule, model))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src(t: &str) -> Source {
        Source {
            name: "a.rule".into(),
            text: t.into(),
        }
    }

    #[test]
    fn koch_compiles_to_one_generator_state() {
        let (rule, m) = compile_rule(&src("field s = root of x^2 - 3 in [1, 2]\ninitiator 0,0 koch 1,0\ngenerator koch 0,0 koch 1/3,0 koch 1/2,1/6s koch 2/3,0 koch 1,0\n")).unwrap();
        assert_eq!(rule.generators.len(), 1);
        let names: Vec<&str> = m.automaton.states.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["initiator", "koch", "segment"]);
        // Initiator: 4 pieces; koch: 4 pieces.
        assert_eq!(m.automaton.operators.len(), 8);
        // The tip's y = √3/6 is outside Q: operators carry field entries.
        assert!(!m.field_ops.is_empty());
    }

    #[test]
    fn a_mirrored_segment_maps_the_unit_frame_exactly() {
        // Segment from (1,0) to (1,1), mirrored: z ↦ (1,0) + i·conj(z). (0,1) ↦ (1,0) + i·(−i) =
        // (2, 0); (1,0) ↦ (1,1); (0,0) ↦ (1,0).
        let k = NumberField::new(RealAlgebraic::rational(BigRational::zero()));
        let q = |n: i64| k.rational(BigRational::from_integer(n.into()));
        let m = Affine::onto(&k, &[q(1), q(0)], &[q(1), q(1)], Flip::Y);
        assert_eq!(m.apply(&k, &[q(0), q(1)]), [q(2), q(0)]);
        assert_eq!(m.apply(&k, &[q(1), q(0)]), [q(1), q(1)]);
        assert_eq!(m.apply(&k, &[q(0), q(0)]), [q(1), q(0)]);
        // Backwards: (0,0) ↦ Q, (1,0) ↦ P.
        let m = Affine::onto(&k, &[q(1), q(0)], &[q(1), q(1)], Flip::X);
        assert_eq!(m.apply(&k, &[q(0), q(0)]), [q(1), q(1)]);
        assert_eq!(m.apply(&k, &[q(1), q(0)]), [q(1), q(0)]);
    }

    #[test]
    fn errors_have_codes_and_columns() {
        let cases = [
            ("initiator 0,0 g\n", "E1301", 1, 11),
            (
                "initiator 0,0 g 1;0\ngenerator g 0,0 g 1,0\n",
                "E1302",
                1,
                17,
            ),
            (
                "initiator 0,0 g/z 1,0\ngenerator g 0,0 g 1,0\n",
                "E1303",
                1,
                15,
            ),
            (
                "initiator 0,0 h 1,0\ngenerator g 0,0 g 1,0\n",
                "E1304",
                1,
                15,
            ),
            (
                "initiator 0,0 g 1,0\ngenerator g 0,0 g 1,0\ngenerator g 0,0 - 1,0\n",
                "E1305",
                3,
                11,
            ),
            ("generator g 0,0 g 1,0\n", "E1306", 1, 1),
            (
                "initiator 0,0 g 0,0\ngenerator g 0,0 g 1,0\n",
                "E1307",
                1,
                15,
            ),
            (
                "initiator 0,0 g 1,0\ngenerator g 0,0 g 1,0\nturtle 3\n",
                "E1308",
                3,
                1,
            ),
            (
                "initiator 0,0 a 1,0\ngenerator g 0,0 g 1,0\nage a h\n",
                "E1304",
                3,
                7,
            ),
            (
                "initiator 0,0 g 1,0 . 2,0\ngenerator g 0,0 g 1,0\n",
                "E1310",
                1,
                21,
            ),
            (
                "initiator 0,0 g! 1,0\ngenerator g 0,0 g 1,0\n",
                "E1303",
                1,
                15,
            ),
            (
                "field s = root of x^2-3 in [1, 2]\ninitiator 0,0 g 1,2t\ngenerator g 0,0 g 1,0\n",
                "E1302",
                2,
                17,
            ),
            ("initiator 0,0 g 1,0\ngenerator g 0,0 g 1,0\nseed x\n", "E1311", 3, 1),
            ("initiator 0,0 g 1,0\ngenerator g 0,0 g 1,0\ndepth 13\n", "E1311", 3, 1),
            // Above depth 12: 1 + 4 + 16 + … + 4^10 = (4^11 − 1)/3 states > 4096.
            ("random r g\ndepth 12\ninitiator 0,0 r 1,0\ngenerator g 0,0 r 1/4,0 r 1/2,0 r 3/4,0 r 1,0\n", "E1311", 2, 1),
            ("random r g\ninitiator 0,0 r! 1,0\ngenerator g 0,0 g 1,0\n", "E1303", 2, 15),
        ];
        for (text, code, line, c) in cases {
            let e = parse_rule(&src(text)).unwrap_err();
            let s = e.span().unwrap();
            assert_eq!((e.code(), s.line, s.col), (code, line, c), "{text}");
        }
    }

    #[test]
    fn age_choices_become_states() {
        // grow at ages 0, 1; seed at age 2; seed's segment restarts a fractal of age 0.
        let (_, m) = compile_rule(&src("initiator 0,0 tree 1,0\ngenerator grow 0,0 tree 1/2,1/2 tree 1,0\ngenerator seed 0,0 tree! 1/2,0 - 1,0\nage tree grow grow seed\n")).unwrap();
        let names: Vec<&str> = m.automaton.states.iter().map(|s| s.name.as_str()).collect();
        // Hand trace: the initiator's `tree` is age 0 (grow), laid flat into the initiator; its
        // `tree` segments are age 1 (grow), theirs age 2 (seed), and seed's `tree!` restarts at
        // age 0 (grow), whose children are age 1 again.
        assert_eq!(
            names,
            [
                "initiator",
                "grow.tree1",
                "seed.tree2",
                "grow.tree0",
                "segment"
            ]
        );
    }
}
