//! Certificates of what `verify` proves about an automaton's attractor (issue #29): the
//! constraints in the automaton's field, the contraction of every walk of its control graph and
//! its similarity dimension. Expected values are derived by hand below; every forgery must be
//! rejected with a message naming its step.

use lacuna::certificate::{Certificate, Step};
use lacuna::checker::{check, check_json};

mod common;
use common::{assert_proved, assert_rejected, automaton_certificate, lacuna};

/// The 30 digits of log 3 / log 2 = log₂ 3 (a mathematical constant, not lacuna's output:
/// 1.584962500721156181453738943947816508759814…).
const LOG2_3: &str = "1.584962500721156181453738943947";
/// log 4 / log 3 = log₃ 4 = 1.261859507142914874199054228685521…
const LOG3_4: &str = "1.261859507142914874199054228685";

fn step<'a>(cert: &'a mut Certificate, name: &str) -> &'a mut Step {
    cert.steps
        .iter_mut()
        .find(|s| s.name() == name)
        .unwrap_or_else(|| panic!("no {name} step"))
}

fn contraction(cert: &mut Certificate) -> &mut lacuna::certificate::ContractionStep {
    match step(cert, "contraction") {
        Step::Contraction(c) => c,
        _ => unreachable!(),
    }
}

fn multiplicity(cert: &mut Certificate) -> &mut lacuna::certificate::MultiplicityStep {
    match step(cert, "multiplicity") {
        Step::Multiplicity(m) => m,
        _ => unreachable!(),
    }
}

fn similarity(cert: &mut Certificate) -> &mut lacuna::certificate::SimilarityStep {
    match step(cert, "similarity-dimension") {
        Step::SimilarityDimension(s) => s,
        _ => unreachable!(),
    }
}

/// A rule in Q(√3) with an irrational dimension root and two coinciding pieces (not a library
/// entry: the reconstruction of the Monkeys tree that is not Mandelbrot's tree).
const LATTICE_ELEVEN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/lattice-eleven.rule");

#[test]
fn sierpinski_triangle_is_certified_as_derived_by_hand() {
    // Three maps of ratio 1/2 towards the corners: squared ratio σ = 1/4, each of exponent 1;
    // M(u) = [3u], det(I − M(u)) = 1 − 3u, u* = 1/3; s = 2·ln(1/3)/ln(1/4) = log 3 / log 2.
    // Every map's restriction to the differences has ∞-norm 1/2: the three one-letter walks
    // are a complete prefix code.
    let mut cert = automaton_certificate("sierpinski-triangle");
    assert_proved("sierpinski-triangle", &cert);
    let names: Vec<&str> = cert.steps.iter().map(Step::name).collect();
    assert_eq!(
        names,
        [
            "constraints-hold",
            "contraction",
            "similarity-dimension",
            "multiplicity"
        ]
    );
    let c = contraction(&mut cert);
    assert_eq!(c.walks, vec![vec![0], vec![1], vec![2]]);
    let s = similarity(&mut cert);
    assert_eq!(s.parts.len(), 1);
    let p = &s.parts[0];
    assert_eq!(p.sigma, vec!["1/4".to_string()]);
    assert_eq!(p.exponents, vec![(0, 1), (1, 1), (2, 1)]);
    assert_eq!((p.u.lo.as_str(), p.u.hi.as_str()), ("1/3", "1/3"));
    assert_eq!(s.decimal, LOG2_3);
    let report = check(&cert);
    assert!(report
        .claims()
        .iter()
        .any(|c| c.contains(&format!("similarity dimension = {LOG2_3}"))));
}

#[test]
fn koch_curve_in_q_sqrt3_is_certified() {
    // Four maps of ratio 1/3 (two of them rotations by ±60°, entries in Q(√3)): σ = 1/9,
    // M(u) = [4u], u* = 1/4, s = log 4 / log 3.
    let mut cert = automaton_certificate("koch");
    assert_proved("koch", &cert);
    let names: Vec<&str> = cert.steps.iter().map(Step::name).collect();
    assert_eq!(
        names,
        [
            "constraints-hold",
            "contraction",
            "similarity-dimension",
            "multiplicity",
            "rule-compilation"
        ]
    );
    let s = similarity(&mut cert);
    assert_eq!(s.parts[0].sigma, vec!["1/9".to_string()]);
    assert_eq!(
        (s.parts[0].u.lo.as_str(), s.parts[0].u.hi.as_str()),
        ("1/4", "1/4")
    );
    assert_eq!(s.decimal, LOG3_4);
}

#[test]
fn contraction_forgeries_are_rejected() {
    let base = automaton_certificate("sierpinski-triangle");
    let mut c = base.clone();
    contraction(&mut c).walks.pop();
    assert_rejected("a walk dropped (incomplete code)", &c, "contraction");
    let mut c = base.clone();
    contraction(&mut c).walks.push(vec![0]);
    assert_rejected("a walk repeated", &c, "contraction");
    let mut c = base.clone();
    contraction(&mut c).walks.push(vec![0, 1]);
    assert_rejected(
        "a walk extending another (not prefix-free)",
        &c,
        "contraction",
    );
    let mut c = base.clone();
    contraction(&mut c).walks[0] = vec![7];
    assert_rejected("an operator out of range", &c, "contraction");
    let mut c = base.clone();
    contraction(&mut c).norm = "2".into();
    assert_rejected("an unknown norm", &c, "contraction");
    let mut c = base.clone();
    contraction(&mut c)
        .instance
        .push((0, vec![vec![vec!["1".into()]]]));
    assert_rejected("an instance for a given operator", &c, "contraction");
    // A claim whose first map is the identity: its walk's norm is 1, not below.
    let mut c = base.clone();
    if let lacuna::certificate::Claim::Automaton(a) = &mut c.claim {
        a.operators[0].value = Some(
            [["1", "0", "0"], ["0", "1", "0"], ["0", "0", "1"]]
                .iter()
                .map(|r| r.iter().map(|x| x.to_string()).collect())
                .collect(),
        );
    }
    assert_rejected("a map of ratio 1", &c, "contraction");
}

#[test]
fn similarity_forgeries_are_rejected() {
    let base = automaton_certificate("sierpinski-triangle");
    let mut c = base.clone();
    similarity(&mut c).parts[0].sigma = vec!["1/9".into()];
    assert_rejected("σ changed (ratios 1/3)", &c, "similarity-dimension");
    let mut c = base.clone();
    similarity(&mut c).parts[0].exponents[1].1 = 2;
    assert_rejected("an exponent changed", &c, "similarity-dimension");
    let mut c = base.clone();
    similarity(&mut c).parts[0].u = lacuna::certificate::Algebraic {
        poly: vec!["-1".into(), "2".into()],
        lo: "1/2".into(),
        hi: "1/2".into(),
    };
    assert_rejected("u* changed", &c, "similarity-dimension");
    let mut c = base.clone();
    similarity(&mut c).decimal = "1.584962500721156181453738943948".into();
    assert_rejected("the last digit changed", &c, "similarity-dimension");
    let mut c = base.clone();
    similarity(&mut c).parts[0].rational = Some("3/2".into());
    assert_rejected("a rational dimension claimed", &c, "similarity-dimension");
    let mut c = base.clone();
    similarity(&mut c).parts.clear();
    assert_rejected("the part dropped", &c, "similarity-dimension");
    // The eleven-piece lattice curve (a test fixture): u* irrational (a root of 5u² + u − 1),
    // σ = 1/3.
    let base = automaton_certificate(LATTICE_ELEVEN);
    assert_proved("lattice-eleven", &base);
    let mut c = base.clone();
    let s = similarity(&mut c);
    s.parts[0].u.poly = vec!["-1".into(), "1".into(), "4".into()];
    assert_rejected("u*'s polynomial changed", &c, "similarity-dimension");
    // kite-dart: s = 2 with u* = σ irrational, given in K; another element is refused.
    let base = automaton_certificate("kite-dart");
    assert_proved("kite-dart", &base);
    let mut c = base.clone();
    let s = similarity(&mut c);
    assert!(s.parts[0].u_field.is_some(), "kite-dart gives u* in K");
    s.parts[0].u_field = Some(vec!["1/2".into()]);
    assert_rejected("u* in K changed", &c, "similarity-dimension");
}

#[test]
fn seed_002_multiplicity_is_certified_as_counted_by_hand_and_forgeries_fail() {
    // The Sierpinski triangle: three maps of ratio 1/2 towards three different corners, so the
    // 3^k words of level k are 3^k different maps, one piece each. The step lists the levels
    // of at most 4096 pieces: 3^7 = 2187, 3^8 = 6561.
    let mut tri = automaton_certificate("sierpinski-triangle");
    let hand: Vec<Vec<(usize, u64)>> = (1..=7u32).map(|k| vec![(1, 3u64.pow(k))]).collect();
    assert_eq!(multiplicity(&mut tri).levels, hand);
    assert_eq!(
        multiplicity(&mut tri).prime,
        None,
        "rational entries: no field"
    );
    // The lemniscate fractal (seed 002, Fig. 7(a)): four maps and the crossing, one map that
    // two operators have. A word of level k with j letters on the crossing is one of
    // 4^(k−j)·C(k, j) maps, each of 2^j pieces.
    let mut lem = automaton_certificate("lemniscate-fractal");
    assert_proved("lemniscate-fractal", &lem);
    let levels = multiplicity(&mut lem).levels.clone();
    assert!(levels.len() >= 3, "{levels:?}");
    for (i, level) in levels.iter().enumerate() {
        let k = i as u32 + 1;
        let binom = |j: u32| (0..j).fold(1u64, |c, t| c * u64::from(k - t) / u64::from(t + 1));
        let hand: Vec<(usize, u64)> = (0..=k)
            .map(|j| (1usize << j, 4u64.pow(k - j) * binom(j)))
            .collect();
        assert_eq!(level, &hand, "level {k}");
    }
    assert!(multiplicity(&mut lem).prime.is_some(), "entries in a field");
    // Forgeries.
    let mut c = tri.clone();
    multiplicity(&mut c).levels[1] = vec![(1, 8)];
    assert_rejected("a level's count changed", &c, "multiplicity");
    let mut c = tri.clone();
    multiplicity(&mut c).levels[0] = vec![(1, 1), (2, 1)];
    assert_rejected("two pieces claimed one map", &c, "multiplicity");
    let mut c = tri.clone();
    // Level 8 has 3^8 = 6561 pieces, more than the producer lists but within the checker's
    // reach: a right level appended is proved, a wrong one is not.
    multiplicity(&mut c).levels.push(vec![(1, 6561)]);
    assert_proved("level 8 appended, right", &c);
    multiplicity(&mut c).levels[7] = vec![(1, 6560)];
    assert_rejected("level 8 appended, wrong", &c, "multiplicity");
    let mut c = lem.clone();
    let m = multiplicity(&mut c);
    m.levels[0] = vec![(1, 6)];
    assert_rejected("the crossing denied", &c, "multiplicity");
    // The lemniscate's field is Q(√3): modulo 11, x² − 3 splits (5² = 25 ≡ 3), so 11 proves
    // nothing; no prime is no proof.
    let mut c = lem.clone();
    multiplicity(&mut c).prime = Some(11);
    assert_rejected("a prime modulo which x² − 3 splits", &c, "multiplicity");
    let mut c = lem.clone();
    multiplicity(&mut c).prime = None;
    assert_rejected("no prime", &c, "multiplicity");
    let mut c = lem.clone();
    multiplicity(&mut c).prime = Some(4);
    assert_rejected("not a prime", &c, "multiplicity");
}

#[test]
fn constraints_hold_forgeries_are_rejected() {
    let base = automaton_certificate("koch");
    let mut c = base.clone();
    if let lacuna::certificate::Claim::Automaton(a) = &mut c.claim {
        let at = a.operators.len() - 2;
        let m = a.operators[at]
            .field_value
            .as_mut()
            .expect("koch.T2 is given in Q(√3)");
        m[0][0] = vec!["1/2".into(), "1/7".into()];
    }
    // The changed operator no longer has columns summing to 1.
    assert_rejected("an entry in K changed", &c, "constraints-hold");
    let mut c = base.clone();
    if let Step::ConstraintsHold(s) = step(&mut c, "constraints-hold") {
        s.constraints += 1;
    }
    assert_rejected("the count of constraints", &c, "constraints-hold");
}

#[test]
fn the_producer_recertifies_every_attractor_claim_alike() {
    // What the checker prints for lacuna's certificate equals what it prints for the producer's
    // certificate of the same claim, recomputed from the claim alone (the forgery fuzz target
    // relies on it).
    for name in [
        "sierpinski-triangle",
        "koch",
        "kite-dart",
        "spec-edge",
        "pythagoras-tree",
        "heighway-dragon",
        "self-seeding-square",
    ] {
        let cert = automaton_certificate(name);
        let again =
            lacuna::certificate::recertify(name, &cert.claim, &lacuna::topology::Limits::default())
                .expect("recertifies");
        assert_eq!(check(&cert).claims(), check(&again).claims(), "{name}");
    }
}

#[test]
fn verify_and_check_from_the_command_line() {
    let dir = std::env::temp_dir().join(format!("lacuna-attractor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("koch.json");
    let p = path.to_str().unwrap();
    let (code, out, err) = lacuna(&["verify", "koch", "--certificate", p]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("verdict: VERIFIED"), "{out}");
    let (code, out, err) = lacuna(&["check", p]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains(&format!("similarity dimension = {LOG3_4}")),
        "{out}"
    );
    assert!(out.contains("the attractor is defined"), "{out}");
    // A hand-edited digit is caught by `check` (exit 1).
    let text = std::fs::read_to_string(&path).unwrap();
    let forged = text.replace(LOG3_4, "1.261859507142914874199054228686");
    std::fs::write(&path, forged).unwrap();
    let (code, out, _) = lacuna(&["check", p]);
    assert_eq!(code, 1, "{out}");
    assert!(check_json(&std::fs::read_to_string(&path).unwrap()).failed());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn open_set_witnesses_make_the_dimension_hausdorff_and_forgeries_fail() {
    // The Sierpinski triangle's hull is the triangle of its three points: in the chart (the
    // barycentric coordinates of points 1 and 2) the triangle (0, 0), (1, 0), (0, 1); its three
    // images are the corner triangles of half size, which meet only at points.
    let base = automaton_certificate("sierpinski-triangle");
    let report = check(&base);
    assert!(
        report.claims().iter().any(|c| c.contains(&format!(
            "so the Hausdorff dimension of the attractor is {LOG2_3}"
        ))),
        "{}",
        report.to_text()
    );
    let mut c = base.clone();
    let set = similarity(&mut c).parts[0]
        .open_set
        .as_mut()
        .expect("a witness");
    set[0].reverse();
    assert_rejected("a clockwise polygon", &c, "similarity-dimension");
    let mut c = base.clone();
    let set = similarity(&mut c).parts[0]
        .open_set
        .as_mut()
        .expect("a witness");
    set[0].pop();
    assert_rejected("a polygon of two vertices", &c, "similarity-dimension");
    let mut c = base.clone();
    let set = similarity(&mut c).parts[0]
        .open_set
        .as_mut()
        .expect("a witness");
    // Half the triangle towards its first vertex: the other corners' images leave it.
    for v in set[0].iter_mut() {
        for x in v.iter_mut().filter(|x| !x.is_empty()) {
            // Rational coordinates (zero is the empty list).
            let q = lacuna::checker::parse_rational(&x[0]).expect("rational");
            x[0] = (q / num_rational::BigRational::from_integer(2.into())).to_string();
        }
    }
    assert_rejected("a set the images leave", &c, "similarity-dimension");
    // An operator whose first row is changed is no longer barycentric: its columns sum to 3/2
    // and its action on control points is no affine map of the charts, though rows 1 and 2 —
    // all the chart map reads — are untouched. Dropped from the barycentric list so that only
    // the steps that need it can notice.
    let mut c = base.clone();
    if let lacuna::certificate::Claim::Automaton(a) = &mut c.claim {
        let m = a.operators[0].value.as_mut().expect("a rational operator");
        for x in m[0].iter_mut() {
            let q = lacuna::checker::parse_rational(x).expect("rational");
            *x = (q + num_rational::BigRational::new(1.into(), 2.into())).to_string();
        }
        a.barycentric.retain(|&o| o != 0);
    } else {
        panic!("an automaton claim");
    }
    let report = check(&c);
    let s = report.step("similarity-dimension").expect("the step");
    assert!(
        s.outcome == lacuna::checker::Outcome::Failed && s.message.contains("not barycentric"),
        "{}",
        report.to_text()
    );
    // Without a witness the verdict is only an upper bound.
    let mut c = base.clone();
    similarity(&mut c).parts[0].open_set = None;
    let report = check(&c);
    assert!(report.all_proved());
    assert!(report
        .claims()
        .iter()
        .any(|c| c.contains("an upper bound of the Hausdorff dimension")));
}

fn neighbour_maps(cert: &mut Certificate) -> &mut lacuna::certificate::NeighbourMaps {
    similarity(cert).parts[0]
        .neighbour_maps
        .as_mut()
        .expect("a neighbour-map witness")
}

fn holds(cert: &mut Certificate) -> &mut lacuna::certificate::NeighbourHolds {
    match neighbour_maps(cert) {
        lacuna::certificate::NeighbourMaps::Holds(h) => h,
        lacuna::certificate::NeighbourMaps::Fails(_) => panic!("a failure"),
    }
}

fn fails(cert: &mut Certificate) -> &mut lacuna::certificate::NeighbourFails {
    match neighbour_maps(cert) {
        lacuna::certificate::NeighbourMaps::Fails(f) => f,
        lacuna::certificate::NeighbourMaps::Holds(_) => panic!("a closed set"),
    }
}

#[test]
fn neighbour_maps_certify_the_dimension_of_the_dragon_and_the_tree() {
    // Both have two pieces of ratio 1/√2 (σ = 1/2, exponent 1), so s = 2; their pieces' hulls
    // overlap, and the neighbour maps decide the condition. The certificate carries the closed
    // set: every map of it is needed, so each one dropped is missed.
    for name in ["heighway-dragon", "pythagoras-tree"] {
        let mut cert = automaton_certificate(name);
        let count = holds(&mut cert).maps.len();
        assert_proved(name, &cert);
        let report = check(&cert);
        assert!(
            report.claims().iter().any(|c| c.contains(
                "the open-set condition holds (neighbour maps, Bandt–Graf: a finite set closed under refinement, without the identity, checked exactly), so the Hausdorff dimension of the attractor is 2.000"
            )),
            "{name}: {}",
            report.to_text()
        );
        let s = report.step("similarity-dimension").expect("the step");
        assert!(
            s.message
                .contains(&format!("by {count} neighbour maps in the charts")),
            "{}",
            s.message
        );
        let h = holds(&mut cert);
        assert!(h.maps.len() > 2, "{name}: more than the initial maps");
        assert_eq!(h.coordinates, "charts");
        assert!(
            h.scales.is_none(),
            "{name}: every operator contracts as given"
        );
    }
}

#[test]
fn the_kite_and_dart_s_open_set_condition_needs_rescaled_coordinates_and_forgeries_fail() {
    // kite-dart's T0a is the identity (a <- b), so not every operator contracts as given: the
    // certificate rescales each state's coordinates. Every cycle contracts (T1a: r; T0b: r;
    // T0a·T1b: r), so with c_b/c_a in (1, φ) every scaled ratio, c_a/c_b for T0a and r·c_b/c_a
    // for T1b, is below 1.
    let base = automaton_certificate("kite-dart");
    assert_proved("kite-dart", &base);
    let report = check(&base);
    assert!(
        report.claims().iter().any(|c| c.contains(
            "the open-set condition holds (neighbour maps, Bandt–Graf: a finite set closed under refinement, without the identity, checked exactly), so the Hausdorff dimension of the attractor is 2.000"
        )),
        "{}",
        report.to_text()
    );
    let scales = holds(&mut base.clone()).scales.clone().expect("rescaled");
    let q = |x: &str| lacuna::checker::parse_rational(x).expect("rational");
    let ratio = q(&scales[1]) / q(&scales[0]);
    let phi = num_rational::BigRational::new(1618.into(), 1000.into());
    assert!(ratio > num_rational::BigRational::from_integer(1.into()) && ratio < phi);
    let step = "similarity-dimension";
    // Without the scales, T0a (the identity) does not contract.
    let mut c = base.clone();
    holds(&mut c).scales = None;
    assert_rejected("the scales dropped", &c, step);
    // Equal scales: the same.
    let mut c = base.clone();
    holds(&mut c).scales = Some(vec!["1".into(), "1".into()]);
    assert_rejected("equal scales", &c, step);
    // A scale that is not positive, and one scale too few.
    let mut c = base.clone();
    holds(&mut c).scales = Some(vec!["0".into(), "1".into()]);
    assert_rejected("a zero scale", &c, step);
    let mut c = base.clone();
    holds(&mut c).scales = Some(vec!["1".into()]);
    assert_rejected("one scale", &c, step);
    // Other scales that still make every operator contract change every map: the listed ones
    // are no longer the set.
    let mut c = base.clone();
    let h = holds(&mut c);
    let s = h.scales.as_mut().unwrap();
    s[1] = (q(&s[1]) * num_rational::BigRational::new(101.into(), 100.into())).to_string();
    assert_rejected("a scale changed by 1 %", &c, step);
}

#[test]
fn neighbour_map_forgeries_are_rejected_at_the_similarity_step() {
    let base = automaton_certificate("heighway-dragon");
    let step = "similarity-dimension";
    // A map dropped: the first (an initial map), one from the middle, the last.
    let n = holds(&mut base.clone()).maps.len();
    for i in [0, n / 2, n - 1] {
        let mut c = base.clone();
        holds(&mut c).maps.remove(i);
        assert_rejected(&format!("map {i} dropped"), &c, step);
    }
    // The radius halved: the balls no longer hold the attractors.
    let mut c = base.clone();
    let h = holds(&mut c);
    let r = lacuna::checker::parse_rational(&h.radius).expect("rational");
    h.radius = (r / num_rational::BigRational::from_integer(2.into())).to_string();
    assert_rejected("the radius halved", &c, step);
    // A larger margin lets more maps pass the ball test: the set is no longer closed.
    let mut c = base.clone();
    let h = holds(&mut c);
    h.margin = h.radius.clone();
    assert_rejected("the margin raised to R", &c, step);
    // A zero margin proves nothing.
    let mut c = base.clone();
    holds(&mut c).margin = "0".into();
    assert_rejected("a zero margin", &c, step);
    // The identity of a state put in.
    let mut c = base.clone();
    let h = holds(&mut c);
    let mut id = h.maps[0].clone();
    id.r = id.q;
    id.a = vec![vec!["1".into()], vec![], vec![], vec!["1".into()]];
    id.b = vec![vec![], vec![]];
    h.maps.push(id);
    assert_rejected("the identity in the set", &c, step);
    // A map of the set moved: its translation changed (then it is missed where it is needed).
    let mut c = base.clone();
    holds(&mut c).maps[3].b[0] = vec!["1/3".into()];
    assert_rejected("a moved map", &c, step);
    // Unknown coordinates, a centre moved far away (the radius no longer bounds).
    let mut c = base.clone();
    holds(&mut c).coordinates = "polar".into();
    assert_rejected("unknown coordinates", &c, step);
    let mut c = base.clone();
    holds(&mut c).centres[0] = vec![vec!["7".into()], vec![]];
    assert_rejected("a centre moved", &c, step);
    // Both witnesses at once.
    let mut c = base.clone();
    similarity(&mut c).parts[0].open_set = Some(vec![
        vec![
            vec![vec![], vec![]],
            vec![vec!["1".into()], vec![]],
            vec![vec![], vec!["1".into()]],
        ];
        2
    ]);
    assert_rejected("two witnesses", &c, step);
    // A failure claimed for the dragon: left.T0 · left.T1 and left.T1 · right.T1 both go from
    // `left` to `right`, with different first operators, but their maps differ.
    let mut c = base.clone();
    *neighbour_maps(&mut c) =
        lacuna::certificate::NeighbourMaps::Fails(lacuna::certificate::NeighbourFails {
            u: vec![2, 3],
            v: vec![3, 5],
        });
    let report = check(&c);
    assert!(
        report.to_text().contains("have different maps"),
        "{}",
        report.to_text()
    );
    assert_rejected("a failure of the dragon", &c, step);
    // Without the witness the boundary step has no proved tile and fails; without both, the
    // step still checks, as an upper bound.
    let mut c = base.clone();
    similarity(&mut c).parts[0].neighbour_maps = None;
    assert_rejected("a boundary without the witness", &c, "boundary-dimension");
    c.steps.retain(|s| s.name() != "boundary-dimension");
    let report = check(&c);
    assert!(report.all_proved(), "{}", report.to_text());
    assert!(report
        .claims()
        .iter()
        .any(|c| c.contains("similarity dimension = 2.000") && c.contains("an upper bound")));
}

#[test]
fn verify_says_the_neighbour_maps_are_certified() {
    let dir = std::env::temp_dir().join(format!("lacuna-neighbour-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, note) in [
        (
            "heighway-dragon",
            "(with the open-set condition's witness: neighbour maps)",
        ),
        (
            "self-seeding-square",
            "(with the witness that the open-set condition fails: two words with one map)",
        ),
    ] {
        let path = dir.join(format!("{name}.json"));
        let p = path.to_str().unwrap();
        let (code, out, err) = lacuna(&["verify", name, "--certificate", p]);
        assert_eq!(code, 0, "{out}{err}");
        assert!(!out.contains("not certified"), "{out}");
        assert!(format!("{out}{err}").contains(note), "{out}{err}");
        let (code, out, err) = lacuna(&["check", p]);
        assert_eq!(code, 0, "{out}{err}");
        assert!(out.contains("the open-set condition"), "{out}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_dragon_on_a_skew_frame_is_certified_in_the_drawing() {
    // The Heighway dragon f0(z) = (1 + i)/2·z, f1(z) = 1 − (1 − i)/2·z on the points (0, 0),
    // (1, 0), (1/2, 1): column j of T_i is the barycentric coordinates of f_i(P_j), e.g.
    // f0(P_2) = (1 + i)(1/2 + i)/2 = (−1/4, 3/4) = −5/8·P_1 + 3/4·P_2 + 7/8·P_0. In the skew
    // chart the maps are no similitudes, so the producer works in the drawing and the
    // certificate says so.
    let dir = std::env::temp_dir().join(format!("lacuna-skew-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let aut = dir.join("skew-dragon.aut");
    std::fs::write(
        &aut,
        "state t 3\n\
         sub t.T0 : t <- t = [1 1/4 7/8; 0 1/4 -5/8; 0 1/2 3/4]\n\
         sub t.T1 : t <- t = [0 1/4 7/8; 1 1/4 3/8; 0 1/2 -1/4]\n\
         barycentric\nspace 2\npoints [0 0; 1 0; 1/2 1]\nprimitive t polygon\n",
    )
    .unwrap();
    let json = dir.join("skew.json");
    let (code, out, err) = lacuna(&[
        "verify",
        aut.to_str().unwrap(),
        "--certificate",
        json.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let mut cert = Certificate::from_json(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_proved("skew-dragon", &cert);
    assert_eq!(holds(&mut cert).coordinates, "drawing");
    assert!(check(&cert)
        .claims()
        .iter()
        .any(|c| c.contains("the open-set condition holds (neighbour maps")));
    // Read in the charts, the same maps are refused: the operators are no similitudes there.
    holds(&mut cert).coordinates = "charts".into();
    assert_rejected(
        "charts instead of the drawing",
        &cert,
        "similarity-dimension",
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_exact_overlap_is_certified_and_forged_failures_are_rejected() {
    // The self-seeding square: two words from its state with different first operators give
    // the same map (the producer's witness), so two pieces coincide and the condition fails.
    let base = automaton_certificate("self-seeding-square");
    assert_proved("self-seeding-square", &base);
    let report = check(&base);
    assert!(
        report.claims().iter().any(|c| c.contains(
            "an upper bound of the Hausdorff dimension; the open-set condition fails in part {q}"
        )),
        "{}",
        report.to_text()
    );
    let step = "similarity-dimension";
    let (u, v) = {
        let f = fails(&mut base.clone()).clone();
        (f.u, f.v)
    };
    // The same first operator: both words are u.
    let mut c = base.clone();
    fails(&mut c).v = u.clone();
    assert_rejected("the same first operator", &c, step);
    // Words whose maps differ: u and v each cut to their first operator.
    let mut c = base.clone();
    fails(&mut c).v = vec![v[0]];
    fails(&mut c).u = vec![u[0]];
    assert_rejected("first operators only", &c, step);
    // One more operator on each (q's operators start and end at q, so the words chain): the
    // maps then differ.
    let mut c = base.clone();
    fails(&mut c).u.push(u[0]);
    fails(&mut c).v.push(v[0]);
    assert_rejected("one more operator on each", &c, step);
    // An empty word.
    let mut c = base.clone();
    fails(&mut c).u.clear();
    assert_rejected("an empty word", &c, step);
}

#[test]
fn a_failing_constraint_of_given_operators_is_certified_and_cannot_be_forged() {
    // chaikin-known with T0 replaced by T1: the first constraint, T0·[0 0; 1 0; 0 1] =
    // T1·[1 0; 0 1; 0 0], then compares T1's last two columns with its first two, which differ
    // (T1's columns are (1/4, 3/4, 0), (0, 3/4, 1/4), (0, 1/4, 3/4)).
    let honest = automaton_certificate("chaikin-known");
    assert_eq!(honest.steps[0].name(), "constraints-hold");
    let mut claim = match &honest.claim {
        lacuna::certificate::Claim::Automaton(a) => a.clone(),
        _ => unreachable!(),
    };
    claim.operators[0].value = claim.operators[1].value.clone();
    let automaton = lacuna::certificate::lacuna_automaton(&claim).expect("an automaton");
    let cert = lacuna::certificate::certificate_for_automaton("broken", &automaton).unwrap();
    let Step::ConstraintFails(f) = &cert.steps[0] else {
        panic!("expected constraint-fails, got {:?}", cert.steps[0].name())
    };
    assert_eq!((f.constraint, f.barycentric), (Some(0), None));
    let report = check(&cert);
    assert!(report.all_proved(), "{}", report.to_text());
    assert!(report
        .claims()
        .iter()
        .any(|c| c.contains("INCONSISTENT: constraint 0 fails")));
    // The honest automaton's constraint 0 holds: claiming it fails is rejected.
    let mut forged = honest.clone();
    forged.steps[0] = Step::ConstraintFails(lacuna::certificate::ConstraintFailsStep {
        constraint: Some(0),
        barycentric: None,
    });
    assert_rejected("a constraint that holds", &forged, "constraint-fails");
    // A solution-space step is foreign to a claim whose operators are all given.
    let mut foreign = honest.clone();
    foreign.steps[0] = automaton_certificate("spec-edge").steps[0].clone();
    assert!(check(&foreign).failed());
}

#[test]
fn a_malformed_attractor_claim_is_refused_whatever_the_steps() {
    // Found by the forgery fuzz target: a claim whose start state lost a control point, with
    // its similarity step dropped, was accepted (the contraction step does not read the points)
    // while the producer could not even build the frames. The claim itself is now checked.
    let mut c = automaton_certificate("sierpinski-triangle");
    c.steps.truncate(2);
    if let lacuna::certificate::Claim::Automaton(a) = &mut c.claim {
        a.attractor.as_mut().expect("an attractor").points.pop();
    }
    let report = check(&c);
    assert!(report.failed(), "{}", report.to_text());
    assert!(
        report.steps[0]
            .message
            .contains("the attractor needs 3 points"),
        "{}",
        report.to_text()
    );
    // An operator given both in Q and in K is refused too.
    let mut c = automaton_certificate("koch");
    if let lacuna::certificate::Claim::Automaton(a) = &mut c.claim {
        let at = a.operators.len() - 1;
        a.operators[at].field_value = Some(vec![vec![vec!["1".into()]]]);
    }
    assert!(check(&c).failed());
}

fn rule_of(c: &mut Certificate) -> &mut String {
    match &mut c.claim {
        lacuna::certificate::Claim::Automaton(a) => a.rule.as_mut().expect("a rule text"),
        _ => panic!("an automaton claim"),
    }
}

/// The rule → automaton compilation is certified for every rule of the library: the checker
/// compiles the rule text again. A changed coordinate in the rule, a changed flag, a field of
/// another number or a changed matrix in the claim is refused at the step.
#[test]
fn rule_compilations_are_certified_and_forgeries_fail() {
    let with_rule = |name: &str| {
        let c = automaton_certificate(name);
        let has = c.steps.iter().any(|s| s.name() == "rule-compilation");
        (c, has)
    };
    for name in [
        "koch",
        "quadric-koch",
        "sierpinski-arrowhead",
        "heighway-dragon",
        LATTICE_ELEVEN,
        "pythagoras-tree",
        "self-seeding-square",
        "vegetation",
        "random-tree",
    ] {
        let (c, has) = with_rule(name);
        assert!(has, "{name}: no rule-compilation step");
        assert_proved(name, &c);
    }
    let (koch, _) = with_rule("koch");
    // The tip of the Koch generator one sixth of √3 high: moved to one fifth.
    let mut bad = koch.clone();
    let r = rule_of(&mut bad);
    assert!(r.contains("1/2,1/6s"));
    *r = r.replace("1/2,1/6s", "1/2,1/5s");
    assert_rejected("a moved tip", &bad, "rule-compilation");
    // A segment laid mirrored.
    let mut bad = koch.clone();
    let r = rule_of(&mut bad);
    *r = r.replace("koch 1/3,0 koch 1/2", "koch 1/3,0 koch/y 1/2");
    assert_rejected("a mirrored piece", &bad, "rule-compilation");
    // The field of √2 instead of √3 (the same interval holds one root of x² − 2).
    let mut bad = koch.clone();
    let r = rule_of(&mut bad);
    *r = r.replace("x^2 - 3", "x^2 - 2");
    assert_rejected("another field", &bad, "rule-compilation");
    // The claim's matrix changed in one entry (the rule kept).
    let mut bad = koch.clone();
    if let lacuna::certificate::Claim::Automaton(a) = &mut bad.claim {
        let v = a.operators[13].field_value.as_mut().expect("in K");
        v[0][0] = vec!["7/8".into()];
    }
    assert_rejected("a changed matrix", &bad, "rule-compilation");
    // The heighway dragon (rationals): its two generators swapped on a segment.
    let (h, _) = with_rule("heighway-dragon");
    let mut bad = h.clone();
    let r = rule_of(&mut bad);
    assert!(r.contains("generator left 0,0 left 1/2,1/2 right 1,0"));
    *r = r.replace(
        "generator left 0,0 left 1/2,1/2 right 1,0",
        "generator left 0,0 right 1/2,1/2 left 1,0",
    );
    assert_rejected("swapped generators", &bad, "rule-compilation");
    // An age line naming a choice no flag uses changes nothing: still the compilation.
    let mut same = h;
    rule_of(&mut same).push_str("\nage a left right\n");
    assert_proved("an unused age choice", &same);
}

fn automaton_of(c: &mut Certificate) -> &mut lacuna::certificate::AutomatonClaim {
    match &mut c.claim {
        lacuna::certificate::Claim::Automaton(a) => a,
        _ => panic!("an automaton claim"),
    }
}

/// The `age` extension re-compiled (fixtures/vegetation.rule): `age plant grow grow grow seed`.
/// By hand: the initiator's `plant` is age 0, grow laid into the initiator; grow's two `plant`
/// branches are age 1 (grow.plant1), theirs age 2 (grow.plant2), then age 3 (seed.plant3), whose
/// three `plant!` restart at age 0 (grow.plant0), whose branches are age 1 again. Operators: the
/// initiator's 3 (grow's trunk and branches), 3 per grow state and 4 for seed's trunk and plants:
/// 3 + 3·3 + 4 = 16. A reordered age list, states swapped or a changed entry is refused.
#[test]
fn an_age_rule_is_recompiled_and_forgeries_fail() {
    let mut veg = automaton_certificate("vegetation");
    let names: Vec<&str> = veg.steps.iter().map(Step::name).collect();
    assert_eq!(names.last(), Some(&"rule-compilation"));
    assert_proved("vegetation", &veg);
    let a = automaton_of(&mut veg);
    let states: Vec<&str> = a.states.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(
        states,
        [
            "initiator",
            "grow.plant1",
            "grow.plant2",
            "seed.plant3",
            "grow.plant0",
            "segment"
        ]
    );
    assert_eq!(a.operators.len(), 16);
    let report = check(&veg);
    let s = report.step("rule-compilation").expect("the step");
    assert!(
        s.message.contains("age choice plant: 4 ages"),
        "{}",
        s.message
    );
    // The ages reordered: seed first, so the initiator lays seed.
    let mut bad = veg.clone();
    let r = rule_of(&mut bad);
    assert!(r.contains("age plant grow grow grow seed"));
    *r = r.replace(
        "age plant grow grow grow seed",
        "age plant seed grow grow grow",
    );
    assert_rejected("the age list reordered", &bad, "rule-compilation");
    // grow.plant1 and grow.plant2 swapped, every operator's states renumbered with them: the
    // same automaton up to the order of its states, which is not the compilation's.
    let mut bad = veg.clone();
    let a = automaton_of(&mut bad);
    a.states.swap(1, 2);
    let swap = |i: usize| match i {
        1 => 2,
        2 => 1,
        i => i,
    };
    for o in &mut a.operators {
        (o.to, o.from) = (swap(o.to), swap(o.from));
    }
    assert_rejected("two states swapped", &bad, "rule-compilation");
    // One entry of seed.plant3.T1 (a plant of ratio 1/2) changed.
    let mut bad = veg.clone();
    let a = automaton_of(&mut bad);
    let o = a
        .operators
        .iter_mut()
        .find(|o| o.name == "seed.plant3.T1")
        .expect("seed's first plant");
    let v = o.value.as_mut().expect("rational");
    v[1][1] = if v[1][1] == "1/3" { "1/4" } else { "1/3" }.into();
    assert_rejected("an operator entry changed", &bad, "rule-compilation");
}

/// The `random` extension re-compiled (fixtures/random-tree.rule: `random branch both left
/// right`, seed 17, depth 6). By hand (hashes by Python's integers, `h = 17`, then
/// `h = splitmix64(h ^ x)`, entry h mod 3): place [0] hashes to 0x808475F02EE37363 ≡ 0: both is
/// laid into the initiator; its branches are segments 1 and 3, places [0, 1] →
/// 0x7FC9967EA25EA21C ≡ 0 (both) and [0, 3] → 0xEABC74434623261C ≡ 2 (right): the first states
/// are both.at0_1 and right.at0_3. A changed seed, a changed depth or a changed entry is refused.
#[test]
fn a_random_rule_is_recompiled_and_forgeries_fail() {
    let mut tree = automaton_certificate("random-tree");
    assert_proved("random-tree", &tree);
    let a = automaton_of(&mut tree);
    let states: Vec<&str> = a.states.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(states[..3], ["initiator", "both.at0_1", "right.at0_3"]);
    // Places of 2 to 5 entries are states of their own, deeper ones share a state per generator.
    let deep = states.iter().filter(|s| !s.contains(".at")).count();
    assert_eq!(
        deep,
        2 + 3,
        "initiator, segment and one state per generator"
    );
    let report = check(&tree);
    let s = report.step("rule-compilation").expect("the step");
    assert!(
        s.message.contains("seed 17") && s.message.contains("depth 6"),
        "{}",
        s.message
    );
    // Seed 18: place [0] hashes to 0x1120B3D00955F032 ≡ 1, left is laid into the initiator.
    let mut bad = tree.clone();
    let r = rule_of(&mut bad);
    assert!(r.contains("seed 17\n"));
    *r = r.replace("seed 17\n", "seed 18\n");
    assert_rejected("the seed changed", &bad, "rule-compilation");
    // Depth 5: places of 5 entries are no longer states of their own.
    let mut bad = tree.clone();
    let r = rule_of(&mut bad);
    *r = r.replace("depth 6\n", "depth 5\n");
    assert_rejected("the depth changed", &bad, "rule-compilation");
    // One entry of the first operator changed.
    let mut bad = tree.clone();
    let a = automaton_of(&mut bad);
    let v = a.operators[1].value.as_mut().expect("rational");
    v[0][0] = if v[0][0] == "7" { "8" } else { "7" }.into();
    assert_rejected("an operator entry changed", &bad, "rule-compilation");
}

/// lacuna's compiler and the checker's agree on rules mixing both extensions and plain flags:
/// ages with a restart, a random choice over three generators (one laid backwards, one mirrored
/// after a gap), a generator named directly, for several seeds and every depth from 1 to 4: each
/// certificate's rule-compilation step is proved, with states of occurrences from depth 3 on.
#[test]
fn lacuna_and_the_checker_compile_mixed_rules_alike() {
    let rule = |seed: u64, depth: u64| {
        format!(
            "age t a b\nrandom r a b c\nseed {seed}\ndepth {depth}\n\
             initiator 0,0 r 1,0 t 1,1/2\n\
             generator a 0,0 r 1/2,1/2 t! 1,0\n\
             generator b 0,0 t 1/2,-1/2 - 1/2,0 r/x 1,0\n\
             generator c 0,0 . 1/4,0 r/y 3/4,0 a 1,0\n"
        )
    };
    let limits = lacuna::topology::Limits::default();
    for seed in [0, 1, 17, u64::MAX] {
        for depth in 1..=4 {
            let text = rule(seed, depth);
            let src = lacuna::Source {
                name: "mixed.rule".into(),
                text: text.clone(),
            };
            let (_, model) = lacuna::input::compile_rule(&src).expect("compiles");
            // Only the constraints and the compilation: contraction and dimension are not
            // what this test is about.
            let attractor = lacuna::analysis::Attractor {
                resolved: lacuna::analysis::resolve(&model, &[], limits.max_unknowns)
                    .expect("resolves"),
                contraction: None,
                contraction_fails: None,
                similarity: None,
                similarity_note: None,
                boundary: None,
            };
            let cert = lacuna::certificate::certificate_for_model("mixed", &model, &attractor)
                .expect("certifiable");
            let report = check(&cert);
            let s = report.step("rule-compilation").expect("the step");
            assert_eq!(
                s.outcome,
                lacuna::checker::Outcome::Proved,
                "seed {seed}, depth {depth}: {}",
                s.message
            );
            let occurrences = model
                .automaton
                .states
                .iter()
                .filter(|s| s.name.contains(".at"))
                .count();
            assert_eq!(occurrences > 0, depth >= 3, "seed {seed}, depth {depth}");
        }
    }
}
