//! A rule file read: its grammar (paths of points and segment flags, `field`, `initiator`,
//! `generator`, `age`, `random`, `seed`, `depth`), names resolved, each error placed at its line
//! and column, and the bound on the states of random choices checked before compiling.

use super::{Flip, Rule, RulePath, Segment, Target, MAX_RANDOM_STATES};
use crate::algebra::algebraic::{FieldElement, NumberField, RealAlgebraic};
use crate::error::{Error, Result, Source};
use crate::input::automaton_model::{parse_field_decl, parse_field_element};
use num_rational::BigRational;
use num_traits::Zero;
use std::collections::HashMap;

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
}
