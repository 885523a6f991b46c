//! A rule compiled to an automaton: the exact affine maps of its segments, the states (one per
//! generator, per age, per occurrence of a random choice above the depth) and the automaton
//! file's text, read back as a model.
//!
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

use super::parse::parse_rule;
use super::{splitmix64, Flip, Rule, RulePath, Segment, Target};
use crate::algebra::algebraic::{FieldElement, NumberField};
use crate::error::{Result, Source};
use crate::input::automaton_model::{parse_model, AutomatonModel};
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::collections::HashMap;
use std::fmt::Write as _;

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

/// A field element in the syntax of
/// [`parse_field_element`](crate::input::automaton_model::parse_field_element).
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
    use crate::algebra::algebraic::RealAlgebraic;

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
