//! Kaandorp's production rules (issue #17): the exact similarity dimensions of the library rules
//! against hand derivations and an independent series for the logarithms, the open-set verdicts,
//! box counting, the compiled automaton's level n against the rule's replacement drawn directly by
//! an independent implementation (same segments, exactly), every rule through the commands, and
//! the errors of the format.

use lacuna::algebra::{FieldElement, NumberField};
use lacuna::analysis::{resolve, similarity_dimension};
use lacuna::geometry::exact_points;
use lacuna::input::{
    library, load_any, parse_rule, AutomatonModel, Flip, Loaded, Primitive, Rule, Segment, Target,
};
use lacuna::Source;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};
use proptest::prelude::*;

mod common;
use common::lacuna;

const RULES: [&str; 8] = [
    "quadric-koch",
    "koch",
    "sierpinski-arrowhead",
    "heighway-dragon",
    "pythagoras-tree",
    "self-seeding-square",
    "vegetation",
    "random-tree",
];

/// The eleven-piece lattice curve, a test fixture (not a library entry): the reconstruction of
/// the Monkeys tree that turned out not to be Mandelbrot's tree.
const LATTICE_ELEVEN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/lattice-eleven.rule");

fn model(name: &str) -> AutomatonModel {
    match load_any(name).unwrap_or_else(|e| panic!("{name}: {}", e.render())) {
        Loaded::Automaton { model, .. } => *model,
        Loaded::Faces(_) => panic!("{name} is not an automaton"),
    }
}

fn rule_text(name: &str) -> &'static str {
    library()
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
        .expect("library entry")
}

fn rule(text: &str) -> Rule {
    parse_rule(&Source {
        name: "t.rule".into(),
        text: text.into(),
    })
    .unwrap_or_else(|e| panic!("{}", e.render()))
}

// ---------------------------------------------------------------------------------------------
// Logarithms by a series written here: ln x = 2·atanh((x − 1)/(x + 1)) = 2·Σ z^(2j+1)/(2j+1),
// summed in fixed point with scale 10^90. Each term is floored (error < 1 unit each) and the
// tail after the last term is below that term, so the sum is within 200 units of 10^90·ln x.

const SCALE_DIGITS: u32 = 90;

fn ln_fixed(num: u64, den: u64) -> BigInt {
    // z = (x − 1)/(x + 1) = (num − den)/(num + den).
    let (p, q) = (BigInt::from(num - den), BigInt::from(num + den));
    let scale = BigInt::from(10).pow(SCALE_DIGITS);
    let mut sum = BigInt::zero();
    let mut j = 0u32;
    loop {
        let e = 2 * j + 1;
        let term = &scale * p.pow(e) / (q.pow(e) * BigInt::from(e));
        if term.is_zero() {
            break;
        }
        sum += term;
        j += 1;
    }
    sum * 2
}

/// The first 50 decimals of a/b (fixed-point values), truncated, as `I.DDD…`, checking that the
/// neglected digits are far from a carry (the series' error is a few hundred units of 10^-90).
fn decimal50(a: &BigInt, b: &BigInt) -> String {
    let scale = BigInt::from(10).pow(SCALE_DIGITS);
    let r = a * &scale / b; // ≈ 10^90 · a/b
    let cut = BigInt::from(10).pow(SCALE_DIGITS - 50);
    let rest = &r % &cut;
    let margin = BigInt::from(10).pow(10);
    assert!(
        rest > margin && &cut - &rest > margin,
        "too close to a digit boundary"
    );
    let int = &r / &scale;
    let frac = (&r % &scale) / &cut;
    format!("{int}.{:0>50}", frac.to_string())
}

#[test]
fn dimensions_by_hand_to_50_digits_against_a_series() {
    let ln2 = ln_fixed(2, 1);
    let ln3 = &ln2 + ln_fixed(3, 2);
    // Koch: 4 pieces of 1/3, 4·3^-s = 1, s = log 4 / log 3 = 2·ln 2 / ln 3.
    // Arrowhead: 3 pieces of 1/2, s = log 3 / log 2.
    // Quadric Koch: 8 pieces of 1/4, 8·4^-s = 1, 2^(2s) = 2^3, s = 3/2 exactly.
    // Dragon: two states, each with one piece into each state, ratio 1/√2: M(s) = [[r^s, r^s],
    // [r^s, r^s]], spectral radius 2·r^s = 1, 2^(s/2) = 2, s = 2 exactly.
    let zeros = "0".repeat(50);
    let cases = [
        (
            "koch",
            "log 4 / log 3".to_string(),
            decimal50(&(&ln2 * 2), &ln3),
        ),
        (
            "sierpinski-arrowhead",
            "log 3 / log 2".to_string(),
            decimal50(&ln3, &ln2),
        ),
        (
            "quadric-koch",
            "3/2".to_string(),
            format!("1.5{}", &zeros[..49]),
        ),
        ("heighway-dragon", "2".to_string(), format!("2.{zeros}")),
    ];
    for (name, exact, decimal) in cases {
        let m = model(name);
        let r = resolve(&m, &[], 64).expect("resolves");
        let d = similarity_dimension(&m, &r.ops, 50).expect("a similarity dimension");
        assert_eq!(d.exact, exact, "{name}");
        assert_eq!(d.decimal, decimal, "{name}");
    }
    // Sanity of the series itself: ln 2 = 0.69314718055994530941723212145817656807550013436025…
    assert!(decimal50(&ln2, &BigInt::from(10).pow(SCALE_DIGITS))
        .starts_with("0.69314718055994530941723212145817656807550013436025"));
}

#[test]
fn lattice_eleven_and_vegetation_dimensions_are_exact_roots() {
    // The eleven-piece lattice curve: 6 pieces of 1/3 (r² = τ², τ = 1/3) and 5 of 1/(3√3) (r² = τ³); with
    // u = τ^(s/2): 6u² + 5u³ = 1, (u + 1)(5u² + u − 1) = 0, u = (√21 − 1)/10.
    // s = 2·ln u / ln τ; √21 = 4.58257569495584000658…, u = 0.35825756949558400065…,
    // ln u = −1.02649…: s = 2·1.02649…/1.09861… = 1.8687…
    let m = model(LATTICE_ELEVEN);
    let r = resolve(&m, &[], 64).unwrap();
    let d = similarity_dimension(&m, &r.ops, 12).unwrap();
    assert!(
        d.exact.contains("sqrt(21)") && d.exact.contains("1/3"),
        "{}",
        d.exact
    );
    // Independently, in floating point from the closed form (12 digits are plenty here).
    let u = (21f64.sqrt() - 1.0) / 10.0;
    assert!((5.0 * u * u * u + 6.0 * u * u - 1.0).abs() < 1e-12);
    let s = 2.0 * u.ln() / (1.0f64 / 3.0).ln();
    let got: f64 = d.decimal.parse().unwrap();
    assert!((got - s).abs() < 1e-11, "{} {s}", d.decimal);
    // Vegetation: one cycle plant0 → plant1 → plant2 → plant3 → plant0 with 2, 2, 2 branches of
    // r² = 1/2 = τ (τ = 1/2) and 3 new plants of r² = 1/4 = τ²: det(I − M(u)) = 1 − 24u^5,
    // s = 2·ln u / ln τ = (2/5)·log 24 / log 2 = 2·log 24 / log 32.
    let m = model("vegetation");
    let r = resolve(&m, &[], 64).unwrap();
    let d = similarity_dimension(&m, &r.ops, 50).unwrap();
    assert_eq!(d.exact, "2·log 24 / log 32");
    let ln24 = ln_fixed(2, 1) * 3 + ln_fixed(3, 2) + ln_fixed(2, 1);
    let ln32 = ln_fixed(2, 1) * 5;
    assert_eq!(d.decimal, decimal50(&(ln24 * 2), &ln32));
}

#[test]
fn the_open_set_condition_is_proved_only_where_it_is_decided() {
    // Koch, arrowhead, quadric Koch: the hull of each curve is a triangle (resp. the
    // parallelogram (0,0), (1/3,1/3), (1,0), (2/3,−1/3) for the quadric curve: the fixed points of
    // its 1st, 3rd, 8th and 6th maps) and the pieces' hulls meet in points or edges only.
    for name in ["koch", "sierpinski-arrowhead", "quadric-koch"] {
        let m = model(name);
        let r = resolve(&m, &[], 64).unwrap();
        let d = similarity_dimension(&m, &r.ops, 10).unwrap();
        assert!(!d.upper_bound, "{name}: {}", d.open_set);
        assert!(d.open_set.starts_with("holds"), "{name}");
    }
    // The dragon and the 45° Pythagoras tree: the hulls overlap, but the neighbour maps decide.
    // Both hold: the dragon's two pieces tile the plane (the twin dragon is a lattice tile:
    // Heighway's dragon is a copy of half of it), and the tree's two maps i + (1+i)/2·z,
    // (1+3i)/2 + (1−i)/2·z are similar to the Lévy C curve's (any two maps a·z + t1, ā·z + t2
    // with t1·(1 − ā) ≠ t2·(1 − a), here i·(1+i)/2 ≠ (1+3i)/2·(1−i)/2, i.e. (−1+i)/2 ≠ (2+i)/2,
    // are conjugate by a similitude), which has interior points, so positive area, and a
    // self-similar set of similarity dimension 2 with positive area satisfies the condition
    // (Schief 1994). Hence the dimension 2 is the Hausdorff dimension for both.
    for name in ["heighway-dragon", "pythagoras-tree"] {
        let m = model(name);
        let r = resolve(&m, &[], 64).unwrap();
        let d = similarity_dimension(&m, &r.ops, 10).unwrap();
        assert!(!d.upper_bound, "{name}: {}", d.open_set);
        assert!(
            d.open_set.contains("neighbour maps"),
            "{name}: {}",
            d.open_set
        );
    }
    // The eleven-piece lattice curve (coordinates in Q(√3), s = √3): two pieces coincide exactly. With the
    // segments numbered from 0 along the generator, T3: (5/6, s/6) → (2/3, s/3), T9: (7/6, s/18)
    // → (1, s/9), T1: (1/3, 0) → (2/3, 0), T10: (1, s/9) → (1, 0), each z ↦ P + (Q − P)·z:
    // T9∘T3 has linear part (−1/6 + i·s/18)(−1/6 + i·s/6) = 1/36 − 3/108 − i·s·(1/36 + 1/108) =
    // −i·s/27, and T10∘T1 has (−i·s/9)(1/3) = −i·s/27; translations T9(P3) = 7/6 + i·s/18 +
    // (−1/6 + i·s/18)(5/6 + i·s/6) = 1 + i·2s/27 and T10(P1) = 1 + i·s/9 − i·s/27 = 1 + i·2s/27.
    // So T9∘T3 = T10∘T1 (also found by a word search in Python): the condition fails.
    let m = model(LATTICE_ELEVEN);
    let r = resolve(&m, &[], 64).unwrap();
    let d = similarity_dimension(&m, &r.ops, 10).unwrap();
    assert!(
        d.upper_bound && d.open_set.starts_with("fails"),
        "{}",
        d.open_set
    );
    assert!(
        d.open_set.contains("m.T9") && d.open_set.contains("m.T10"),
        "{}",
        d.open_set
    );
    // Squares, vegetation, random tree: upper bounds (never the dimension).
    for name in ["self-seeding-square", "vegetation", "random-tree"] {
        let m = model(name);
        let r = resolve(&m, &[], 64).unwrap();
        let d = similarity_dimension(&m, &r.ops, 10).unwrap();
        assert!(d.upper_bound, "{name}");
    }
    // The self-seeding square fails, by an exact overlap found independently (a search over
    // words written in Python, redone here in Gaussian rationals from the rule's segments):
    // with the seven fertile segments P→Q of the generator taken as z ↦ P + (Q − P)·z in order
    // (T1..T3 the side in thirds, T4..T7 the square), T4∘T6∘T7∘T6 = T5∘T6∘T3∘T2, two words whose
    // first letters differ. So the condition fails, and lacuna must say so.
    type G = (BigRational, BigRational);
    let g = |x: i64, y: i64, d: i64| -> G {
        (
            BigRational::new(x.into(), d.into()),
            BigRational::new(y.into(), d.into()),
        )
    };
    let gmul = |a: &G, b: &G| -> G { (&a.0 * &b.0 - &a.1 * &b.1, &a.0 * &b.1 + &a.1 * &b.0) };
    let pts = [
        g(0, 0, 6),
        g(2, 0, 6),
        g(4, 0, 6),
        g(6, 0, 6),
        g(2, -1, 6),
        g(4, -1, 6),
        g(4, -3, 6),
        g(2, -3, 6),
        g(2, -1, 6),
    ];
    // Segments 0→1, 1→2, 2→3 (the side), then 4→5, 5→6, 6→7, 7→8 (the square after the jump).
    let seg: Vec<(G, G)> = [(0, 1), (1, 2), (2, 3), (4, 5), (5, 6), (6, 7), (7, 8)]
        .iter()
        .map(|&(i, j)| {
            let (p, q) = (&pts[i], &pts[j]);
            ((&q.0 - &p.0, &q.1 - &p.1), p.clone())
        })
        .collect();
    let word = |w: &[usize]| -> (G, G) {
        // f_w = f_(w1) ∘ … ∘ f_(wn): z ↦ a·z + b, composed from the right.
        let mut m: (G, G) = (g(1, 0, 1), g(0, 0, 1));
        for &i in w.iter().rev() {
            let (a, b) = &seg[i - 1];
            let nb = gmul(a, &m.1);
            m = (gmul(a, &m.0), (&nb.0 + &b.0, &nb.1 + &b.1));
        }
        m
    };
    assert_eq!(word(&[4, 6, 7, 6]), word(&[5, 6, 3, 2]));
    let m = model("self-seeding-square");
    let r = resolve(&m, &[], 64).unwrap();
    let d = similarity_dimension(&m, &r.ops, 10).unwrap();
    assert!(d.open_set.starts_with("fails"), "{}", d.open_set);
    // A segment drawn twice with the same generator is the same map twice: the condition fails
    // (the two pieces coincide), reported as such and as an upper bound.
    let r = rule("initiator 0,0 g 1,0\ngenerator g 0,0 g 1/2,0 g 1,0 . 0,0 g 1/2,0\n");
    let m = lacuna::input::parse_model(&Source {
        name: "c".into(),
        text: r.automaton_text(),
    })
    .unwrap();
    let res = resolve(&m, &[], 64).unwrap();
    let d = similarity_dimension(&m, &res.ops, 10).unwrap();
    assert!(
        d.upper_bound && d.open_set.starts_with("fails"),
        "{}",
        d.open_set
    );
}

#[test]
fn box_counting_agrees_where_the_dimension_is_proved_and_stays_below_the_bounds() {
    for name in RULES {
        let (code, out, err) = lacuna(&["measure", name, "--level", "2", "--json"]);
        assert_eq!(code, 0, "{name}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let s: f64 = v["similarity_dimension"]["decimal"]
            .as_str()
            .unwrap()
            .parse()
            .unwrap();
        let bound = v["similarity_dimension"]["upper_bound"].as_bool().unwrap();
        let b = v["box_dimension"]["value"]
            .as_f64()
            .expect("a box dimension");
        // The dragon and the Pythagoras tree's canopy have dimension 2 (proved by neighbour maps),
        // but at level 2 box counting sees a curve of 4 segments and a tree of 4 squares: it is
        // only held below the value there (getting within 0.05 needs finer levels, outside this
        // test).
        if bound || ["heighway-dragon", "pythagoras-tree"].contains(&name) {
            assert!(b < s + 0.05, "{name}: box {b} above the bound {s}");
        } else {
            assert!((b - s).abs() < 0.05, "{name}: box {b} against {s}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The replacement drawn directly, independently of the compiler: a placement is the pair of end
// points (A, B) and whether it mirrors; a generator point z goes to A + (B − A)·c(z), c the
// identity or the complex conjugate. A segment p→q with flag f is laid as (p, q, plain),
// (p, q, mirrored) for /y, (q, p, mirrored) for /x, (q, p, plain) for /xy; laid by a placement
// Φ it becomes (Φ(start), Φ(end), its mirror XOR Φ's).

type P = [FieldElement; 2];

struct Place {
    a: P,
    b: P,
    mirror: bool,
}

fn place_point(k: &NumberField, ph: &Place, z: &P) -> P {
    let y = if ph.mirror {
        k.sub(&k.rational(BigRational::zero()), &z[1])
    } else {
        z[1].clone()
    };
    let dx = k.sub(&ph.b[0], &ph.a[0]);
    let dy = k.sub(&ph.b[1], &ph.a[1]);
    [
        k.add(&ph.a[0], &k.sub(&k.mul(&dx, &z[0]), &k.mul(&dy, &y))),
        k.add(&ph.a[1], &k.add(&k.mul(&dx, &y), &k.mul(&dy, &z[0]))),
    ]
}

fn lay(k: &NumberField, ph: &Place, p: &P, q: &P, f: Flip) -> Place {
    let (s, e, m) = match f {
        Flip::Plain => (p, q, false),
        Flip::Y => (p, q, true),
        Flip::X => (q, p, true),
        Flip::XY => (q, p, false),
    };
    Place {
        a: place_point(k, ph, s),
        b: place_point(k, ph, e),
        mirror: m != ph.mirror,
    }
}

/// SplitMix64's finaliser, written from its published constants (docs/FORMATS.md names it as
/// the hash of random choices).
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Which generator a fertile segment uses, and the age context its own segments see. `place`:
/// the segment indices from the initiator down to this segment, while they are tracked
/// (`None` below the depth); `parent`: the generator holding the segment (`None`: initiator).
fn pick(
    r: &Rule,
    t: Target,
    ctx: Option<(usize, usize)>,
    place: Option<&[u32]>,
    parent: Option<usize>,
    j: usize,
) -> (usize, Option<(usize, usize)>) {
    match t {
        Target::Generator(g) => (g, None),
        Target::Age { choice, restart } => {
            let seq = &r.ages[choice].1;
            let age = match ctx {
                Some((c, a)) if c == choice && !restart => (a + 1) % seq.len(),
                _ => 0,
            };
            (seq[age], Some((choice, age)))
        }
        Target::Random(choice) => {
            let frozen = [
                u32::MAX,
                parent.map_or(u32::MAX - 1, |g| g as u32),
                j as u32,
            ];
            let key: &[u32] = match place {
                Some(p) if p.len() <= r.depth => p,
                _ => &frozen,
            };
            let h = key.iter().fold(r.seed, |h, &x| mix(h ^ u64::from(x)));
            let seq = &r.randoms[choice].1;
            (seq[(h % seq.len() as u64) as usize], None)
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn draw(
    r: &Rule,
    g: usize,
    ctx: Option<(usize, usize)>,
    place: Option<Vec<u32>>,
    ph: &Place,
    depth: u32,
    level: u32,
    out: &mut Vec<(P, P)>,
) {
    let k = &r.field;
    let path = &r.generators[g].1;
    for (i, s) in path.segments.iter().enumerate() {
        let (p, q) = (&path.points[i], &path.points[i + 1]);
        match *s {
            Segment::Gap => {}
            Segment::Drawn => out.push((place_point(k, ph, p), place_point(k, ph, q))),
            Segment::Fertile { target, flip } => {
                let child = lay(k, ph, p, q, flip);
                if depth == level {
                    out.push((child.a, child.b));
                } else {
                    let cp = place.as_ref().map(|p| [p.as_slice(), &[i as u32]].concat());
                    let (g2, c2) = pick(r, target, ctx, cp.as_deref(), Some(g), i);
                    let keep = cp.filter(|p| p.len() < r.depth);
                    draw(r, g2, c2, keep, &child, depth + 1, level, out);
                }
            }
        }
    }
}

fn replacement(r: &Rule, level: u32) -> Vec<(P, P)> {
    let k = &r.field;
    let init = &r.initiator;
    let (z, o) = (
        k.rational(BigRational::zero()),
        k.rational(BigRational::one()),
    );
    let id = Place {
        a: [z.clone(), z.clone()],
        b: [o, z],
        mirror: false,
    };
    let mut out = Vec::new();
    for (i, s) in init.segments.iter().enumerate() {
        let (p, q) = (&init.points[i], &init.points[i + 1]);
        match *s {
            Segment::Gap => {}
            Segment::Fertile { target, flip } if level > 0 => {
                let cp = vec![i as u32];
                let (g, c) = pick(r, target, None, Some(&cp), None, i);
                let keep = Some(cp).filter(|p| p.len() < r.depth);
                draw(r, g, c, keep, &lay(k, &id, p, q, flip), 1, level, &mut out);
            }
            _ => out.push((p.clone(), q.clone())),
        }
    }
    out
}

/// The level-n segments of the compiled automaton, exact: every leaf of the evaluation tree
/// (depth n, or a state without operators) drawn as its primitive's consecutive points.
fn automaton_segments(m: &AutomatonModel, level: u32) -> Vec<(P, P)> {
    let a = &m.automaton;
    let r = resolve(m, &[], 64).unwrap();
    let mut out = Vec::new();
    let mut stack: Vec<(usize, Vec<usize>)> = vec![(m.start, Vec::new())];
    while let Some((q, word)) = stack.pop() {
        let subs: Vec<usize> = (0..a.operators.len())
            .filter(|&o| a.operators[o].to == q)
            .collect();
        if word.len() as u32 == level || subs.is_empty() {
            let pts = exact_points(m, &r, &word).unwrap();
            let idx = match &m.primitives[q] {
                Primitive::Polyline(v) => v.clone(),
                other => panic!("a rule's states are polylines, not {other:?}"),
            };
            for w in idx.windows(2) {
                out.push((
                    [pts[w[0]][0].clone(), pts[w[0]][1].clone()],
                    [pts[w[1]][0].clone(), pts[w[1]][1].clone()],
                ));
            }
            continue;
        }
        for o in subs {
            stack.push((a.operators[o].from, [word.clone(), vec![o]].concat()));
        }
    }
    out
}

/// A multiset of unordered segments as sorted canonical keys (the exact coordinates of each
/// point in the field's power basis).
fn keys(v: &[(P, P)]) -> Vec<String> {
    let key = |p: &P| format!("{:?}|{:?}", p[0].coords(), p[1].coords());
    let mut out: Vec<String> = v
        .iter()
        .map(|(a, b)| {
            let (x, y) = (key(a), key(b));
            if x <= y {
                format!("{x} — {y}")
            } else {
                format!("{y} — {x}")
            }
        })
        .collect();
    out.sort();
    out
}

#[test]
fn each_rules_automaton_draws_the_replacement_exactly() {
    for name in RULES {
        let r = rule(rule_text(name));
        let m = model(name);
        for level in 0..=3u32 {
            let direct = replacement(&r, level);
            if direct.len() > 3000 {
                break;
            }
            let auto = automaton_segments(&m, level);
            assert_eq!(keys(&auto), keys(&direct), "{name} at level {level}");
        }
    }
}

/// Kaandorp's fig. 12: the arrowhead from disconnected triangles. Level n of the rule is the
/// boundary of the 3^n triangles of the Sierpinski triangle at depth n, computed here directly
/// (each triangle replaced by the three half-size triangles at its corners), exactly.
#[test]
fn the_arrowhead_from_triangles_draws_the_sides_of_the_sierpinski_triangles() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/sierpinski-arrowhead-triangles.rule"
    );
    let r = rule(&std::fs::read_to_string(path).unwrap());
    let m = model(path);
    let k = &r.field;
    let q = |n: i64, d: i64| k.rational(BigRational::new(n.into(), d.into()));
    let half = q(1, 2);
    let mid = |a: &P, b: &P| -> P {
        [
            k.mul(&half, &k.add(&a[0], &b[0])),
            k.mul(&half, &k.add(&a[1], &b[1])),
        ]
    };
    // s = √3 is the field's generator: the apex is (1/2, s/2).
    let s = k.generator_element();
    let mut triangles: Vec<[P; 3]> = vec![[
        [q(0, 1), q(0, 1)],
        [q(1, 1), q(0, 1)],
        [q(1, 2), k.mul(&half, &s)],
    ]];
    for level in 0..=4u32 {
        let sides: Vec<(P, P)> = triangles
            .iter()
            .flat_map(|t| (0..3).map(move |i| (t[i].clone(), t[(i + 1) % 3].clone())))
            .collect();
        assert_eq!(sides.len(), 3usize.pow(level + 1));
        let drawn = automaton_segments(&m, level);
        assert_eq!(keys(&drawn), keys(&sides), "level {level}");
        triangles = triangles
            .iter()
            .flat_map(|[a, b, c]| {
                let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
                [
                    [a.clone(), ab.clone(), ca.clone()],
                    [ab, b.clone(), bc.clone()],
                    [ca, bc, c.clone()],
                ]
            })
            .collect();
    }
}

#[test]
fn random_choices_are_reproducible_per_occurrence_and_frozen_below_the_depth() {
    // depth 2: the initiator's segment (place [0]) and its children (places [0, j]) draw on their
    // own; deeper segments draw once per (generator, segment). Levels 3 and 4 reach the frozen
    // part: the automaton must still be the direct replacement.
    let text = |seed: u64| {
        format!("random b s t\nseed {seed}\ndepth 2\ninitiator 0,0 b 0,1\ngenerator s 0,0 - 1/2,0 b 1,1/2 . 1/2,0 b 1,-1/2\ngenerator t 0,0 - 1/2,0 b 1/2,1/2 . 1/2,0 b 1,0\n")
    };
    let mut drawings = Vec::new();
    for seed in [1u64, 2, 3, 4, 5] {
        let r = rule(&text(seed));
        let m = lacuna::input::parse_model(&Source {
            name: "c".into(),
            text: r.automaton_text(),
        })
        .unwrap();
        for level in 0..=4 {
            assert_eq!(
                keys(&automaton_segments(&m, level)),
                keys(&replacement(&r, level)),
                "seed {seed}, level {level}"
            );
        }
        drawings.push(keys(&replacement(&r, 4)));
    }
    // The same seed draws the same; among five seeds the draws differ.
    assert_eq!(drawings[0], keys(&replacement(&rule(&text(1)), 4)));
    assert!(drawings.iter().any(|d| d != &drawings[0]));
}

#[test]
fn replacement_counts_by_hand() {
    // Koch snowflake: 3·4^n segments; quadric Koch island: 4·8^n; arrowhead: 3^n; dragon: 2^n.
    // Pythagoras tree: each fertile side becomes 3 drawn sides (left, right, bottom) and 2
    // fertile ones, and drawn sides stay: a(n) = 3·(2^n − 1) + 2^n, a(1) = 5, a(2) = 13.
    let count = |name: &str, n: u32| replacement(&rule(rule_text(name)), n).len();
    assert_eq!(count("koch", 2), 3 * 16);
    assert_eq!(count("quadric-koch", 1), 4 * 8);
    assert_eq!(count("sierpinski-arrowhead", 3), 27);
    assert_eq!(count("heighway-dragon", 4), 16);
    assert_eq!(count("pythagoras-tree", 1), 5);
    assert_eq!(count("pythagoras-tree", 2), 13);
}

fn small_point() -> impl Strategy<Value = (i64, i64)> {
    (-4i64..=8, -4i64..=4)
}

fn flag() -> impl Strategy<Value = &'static str> {
    prop_oneof![
        Just("a"),
        Just("a/y"),
        Just("a/x"),
        Just("a/xy"),
        Just("b"),
        Just("b/y"),
        Just("-"),
        Just("."),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// Random two-generator rules with rational points in eighths: the automaton's levels 0–2
    /// are the direct replacement, segment for segment.
    #[test]
    fn random_rules_compile_to_their_replacement(
        ga in proptest::collection::vec((small_point(), flag()), 1..4),
        gb in proptest::collection::vec((small_point(), flag()), 1..3),
        init_flag in prop_oneof![Just("a"), Just("b/x"), Just("-")],
    ) {
        let path = |g: &[((i64, i64), &str)]| {
            let mut s = String::from("0,0");
            for ((x, y), f) in g {
                s += &format!(" {f} {x}/8,{y}/8");
            }
            s + &format!(" {} 1,0", if g.len() % 2 == 0 { "a" } else { "b" })
        };
        let text = format!(
            "initiator 0,0 {init_flag} 1,1\ngenerator a {}\ngenerator b {}\n",
            path(&ga),
            path(&gb)
        );
        let src = Source { name: "p.rule".into(), text: text.clone() };
        // Zero-length segments are refused (E1307); skip those draws.
        let Ok(r) = parse_rule(&src) else { return Ok(()); };
        let m = lacuna::input::parse_model(&Source { name: "c".into(), text: r.automaton_text() })
            .expect("the compiled text parses");
        for level in 0..=2 {
            prop_assert_eq!(keys(&automaton_segments(&m, level)), keys(&replacement(&r, level)), "{}", text);
        }
    }
}

#[test]
fn every_rule_goes_through_the_commands() {
    let dir = std::env::temp_dir().join(format!("lacuna-rules-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in RULES {
        let svg = dir.join(format!("{name}.svg"));
        let png = dir.join(format!("{name}.png"));
        let html = dir.join(format!("{name}.html"));
        let (code, _, err) = lacuna(&[
            "render",
            name,
            "--level",
            "3",
            "--svg",
            svg.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{name}: {err}");
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(
            text.starts_with("<?xml") || text.starts_with("<svg"),
            "{name}"
        );
        assert!(
            text.contains("<polyline") || text.contains("<path"),
            "{name}"
        );
        assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
        let (code, _, err) = lacuna(&[
            "report",
            name,
            "--level",
            "2",
            "--out",
            html.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{name}: {err}");
        let page = std::fs::read_to_string(&html).unwrap();
        assert!(page.contains("open-set condition"), "{name}");
        let (code, out, err) = lacuna(&["solve", name]);
        assert_eq!(code, 0, "{name}: {out}{err}");
        let (code, _, err) = lacuna(&["operators", name]);
        assert_eq!(code, 0, "{name}: {err}");
        // A rule file on disk is detected by its content, like the library entry.
        let file = dir.join(format!("{name}.rule"));
        std::fs::write(&file, rule_text(name)).unwrap();
        let (code, out, err) = lacuna(&["measure", file.to_str().unwrap(), "--level", "1"]);
        assert_eq!(code, 0, "{name}: {err}");
        assert!(out.contains("similarity dimension"), "{name}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_library_lists_kinds() {
    let (code, out, _) = lacuna(&["library", "--json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let kind = |n: &str| {
        v.as_array()
            .unwrap()
            .iter()
            .find(|e| e["name"] == n)
            .map(|e| e["kind"].as_str().unwrap().to_string())
    };
    for name in RULES {
        assert_eq!(kind(name).as_deref(), Some("rule"), "{name}");
    }
    assert_eq!(kind("cube-B2").as_deref(), Some("volume"));
    assert_eq!(kind("tetrahedron-B2").as_deref(), Some("volume"));
    assert_eq!(kind("sierpinski-triangle").as_deref(), Some("automaton"));
    assert_eq!(kind("two-quads").as_deref(), Some("assembly"));
    assert_eq!(kind("F0").as_deref(), Some("face"));
    let (_, text, _) = lacuna(&["library"]);
    assert!(text
        .lines()
        .any(|l| l.starts_with("koch ") && l.contains(" rule ")));
}

#[test]
fn bad_rule_files_exit_2_with_code_line_and_column() {
    let dir = std::env::temp_dir().join(format!("lacuna-bad-rules-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        (
            "initiator 0,0 g 1,0\ngenerator g 0,0 g 1/2,x g 1,0\n",
            "E1302",
            "2:19",
        ),
        (
            "initiator 0,0 h 1,0\ngenerator g 0,0 g 1,0\n",
            "E1304",
            "1:15",
        ),
        (
            "# c\ninitiator 0,0 g 1,0\ngenerator g 0,0 g 1,0\nstep 3\n",
            "E1308",
            "4:1",
        ),
        // A misspelt `initiator` (issue #32): still the rule grammar's error, with the keyword
        // it is closest to, not the automaton grammar's.
        (
            "initator 0,0 g 1,0\ngenerator g 0,0 g 1,0\n",
            "did you mean `initiator`?",
            "1:1",
        ),
    ];
    for (i, (text, code, at)) in cases.iter().enumerate() {
        let f = dir.join(format!("bad{i}.rule"));
        std::fs::write(&f, text).unwrap();
        let (exit, _, err) = lacuna(&["render", f.to_str().unwrap(), "--svg", "/dev/null"]);
        assert_eq!(exit, 2, "{err}");
        assert!(err.contains(code), "{err}");
        assert!(err.contains(at), "{at}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    /// Any text with an `initiator` line is a rule file: it parses and compiles, or it is an
    /// error with a code and a span; never a panic.
    #[test]
    fn hostile_rule_texts_are_errors_not_panics(
        lines in proptest::collection::vec(
            prop_oneof![
                "[ -~]{0,30}",
                Just("field s = root of x^2 - 3 in [1, 2]".to_string()),
                Just("generator g 0,0 g 1/2,1/2s g/xy 1,0".to_string()),
                Just("age a g g h".to_string()),
                Just("random r g".to_string()),
                "generator [a-h] ([-0-9/,.s ]{1,8} [gh.\\-!/xy]{1,3} ){1,4}1,0",
            ],
            0..6,
        ),
        init in "initiator( [-0-9/,s]{1,6} [gra!/xy.\\-]{1,3}){0,3} [0-9],[0-9]",
    ) {
        let mut text = lines.join("\n");
        text += "\n";
        text += &init;
        let src = Source { name: "h.rule".into(), text };
        match lacuna::input::compile_rule(&src) {
            Ok(_) => {}
            Err(e) => prop_assert!(e.code().starts_with('E'), "{}", e.render()),
        }
    }
}

#[test]
fn neighbour_maps_through_the_command_prove_the_dragon_and_refute_an_exact_overlap() {
    // The dragon: proved by neighbour maps (see the open-set test above), so `measure` calls 2
    // the dimension, not an upper bound.
    let (code, out, err) = lacuna(&["measure", "heighway-dragon", "--level", "1", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["similarity_dimension"]["upper_bound"], false);
    assert_eq!(v["similarity_dimension"]["exact"], "2");
    // Three collinear halves of the segment at 0, 1/4, 1/2: z ↦ z/2, z/2 + 1/4, z/2 + 1/2 (the
    // third piece starts at 1/2 and ends at 1). By hand, f2∘f1 = z/4 + 1/4 = f1∘f3: two words
    // with different first letters give the same map, so two pieces coincide and the condition
    // fails (besides, log 3 / log 2 > 1 for a set on a segment). The hull is a segment (no
    // interior) and the squares overlap, so only the neighbour maps can refute it.
    let dir = std::env::temp_dir().join(format!("lacuna-osc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("halves.rule");
    std::fs::write(
        &path,
        "initiator 0,0 g 1,0\ngenerator g 0,0 g 1/2,0 . 1/4,0 g 3/4,0 . 1/2,0 g 1,0\n",
    )
    .unwrap();
    let (code, out, err) = lacuna(&["measure", path.to_str().unwrap(), "--level", "1", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let s = &v["similarity_dimension"];
    assert_eq!(s["exact"], "log 3 / log 2");
    assert_eq!(s["upper_bound"], true);
    let why = s["open_set"].as_str().unwrap();
    assert!(
        why.starts_with("fails") && why.contains("identity"),
        "{why}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn neighbour_maps_work_in_the_frames_of_a_skew_automaton() {
    // Heighway's dragon g1(z) = (1+i)/2·z, g2(z) = 1 + (−1+i)/2·z (the condition holds: the
    // dragon tiles the plane) written as a one-state automaton on the skew frame P0 = (0,0),
    // P1 = (2,0), P2 = (1,1), whose charts are not orthonormal (so the operators are no
    // similitudes in the charts and the search must work in the frame). Barycentric coordinates
    // of (x, y) there: y2 = y, y1 = (x − y)/2, y0 = 1 − y1 − y2. Images of the frame points:
    // g1: 0 → (0,0) = (1,0,0), 2 → (1,1) = (0,0,1), 1+i → i = (0,1) = (1/2,−1/2,1);
    // g2: 0 → (1,0) = (1/2,1/2,0), 2 → i = (1/2,−1/2,1), 1+i → 1 − 1 = (0,0) = (1,0,0).
    // Columns of T are those images; two maps of ratio 1/√2: dimension 2, proved.
    let dir = std::env::temp_dir().join(format!("lacuna-osc-skew-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("dragon-skew.aut");
    std::fs::write(
        &path,
        "state t 3\n\
         sub t.T0 : t <- t = [1 0 1/2; 0 0 -1/2; 0 1 1]\n\
         sub t.T1 : t <- t = [1/2 1/2 1; 1/2 -1/2 0; 0 1 0]\n\
         barycentric\nspace 2\npoints [0 0; 2 0; 1 1]\nprimitive t polygon\n",
    )
    .unwrap();
    let (code, out, err) = lacuna(&["measure", path.to_str().unwrap(), "--level", "1", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let s = &v["similarity_dimension"];
    assert_eq!(s["exact"], "2");
    assert_eq!(s["upper_bound"], false, "{}", s["open_set"]);
    assert!(s["open_set"].as_str().unwrap().contains("neighbour maps"));
    std::fs::remove_dir_all(&dir).ok();
}
