//! Choosing the free parameters from the command line (docs/GEOMETRY.md §1): template files
//! (`--write-template`, `--template`) and LP goals (`--goal`), on the built-in faces.

mod common;
use common::lacuna;
use lacuna::{
    geometry::instantiate, geometry::parse_template, geometry::Goal, geometry::Instance,
    geometry::InstantiateOptions, input::load_input, topology::Origin,
};
use num_rational::BigRational as Q;
use num_traits::{Signed, ToPrimitive, Zero};

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("lacuna-parameters-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn s(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

/// The exact template of an instance as `--write-template` writes it, read back.
fn default_exact(inst: &Instance) -> lacuna::geometry::ExactTemplate {
    let opts = InstantiateOptions::default();
    let text = inst.default_template(&opts);
    // Parsing the written file against the default gives the default: nothing to compare with
    // but itself, so parse it against a template with every target moved away.
    let mut moved = parse_template(&text, "default", &inst.types, 2, &dummy(inst)).unwrap();
    moved.delta = Q::zero();
    moved
}

fn dummy(inst: &Instance) -> lacuna::geometry::ExactTemplate {
    let zero = || [Q::zero(), Q::zero()];
    lacuna::geometry::ExactTemplate {
        types: inst
            .types
            .types
            .iter()
            .enumerate()
            .map(|(t, ty)| lacuna::geometry::TypeTemplate {
                corners: vec![zero(); ty.face.boundary.len()],
                points: vec![zero(); inst.dims[t]],
                targets: ty
                    .children
                    .iter()
                    .map(|&w| vec![zero(); inst.dims[w]])
                    .collect(),
            })
            .collect(),
        delta: Q::from_integer(7.into()),
    }
}

/// Exact level-1 position of control point `c` of sub-face `k` of type `t`, in the exact
/// template of `t`: Σ_r T_k[r][c]·P_r.
fn position(
    inst: &Instance,
    ex: &lacuna::geometry::ExactTemplate,
    t: usize,
    k: usize,
    c: usize,
) -> [Q; 2] {
    let w = inst.types.types[t].children[k];
    let op = inst.operator_exact(t, k);
    let mut pos = [Q::zero(), Q::zero()];
    for (r, p) in ex.types[t].points.iter().enumerate() {
        let v = &op[r * inst.dims[w] + c];
        pos[0] += v * &p[0];
        pos[1] += v * &p[1];
    }
    pos
}

#[test]
fn a_template_in_the_solution_space_is_reproduced_exactly() {
    // Targets generated from exact parameters (the default ones, exact rationals) in the exact
    // default template: the projection must put every level-1 point on its target, residual 0.
    let inst = instantiate(&load_input("F0").unwrap(), &InstantiateOptions::default()).unwrap();
    let mut ex = default_exact(&inst);
    for t in 0..inst.types.types.len() {
        for k in 0..inst.types.types[t].children.len() {
            for c in 0..ex.types[t].targets[k].len() {
                ex.types[t].targets[k][c] = position(&inst, &ex, t, k, c);
            }
        }
    }
    let text = lacuna::geometry::write_template("F0", &inst.types, 2, &ex);
    let path = scratch("in-space.tpl");
    std::fs::write(&path, &text).unwrap();
    let svg = scratch("in-space.svg");
    let (code, out, err) = lacuna(&[
        "render",
        "F0",
        "--level",
        "1",
        "--template",
        s(&path),
        "--svg",
        s(&svg),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("parameters: exact template projection"),
        "{out}"
    );
    assert!(out.contains("template residual Σ|P·c − y|² = 0 "), "{out}");
    assert!(out.contains("T0: largest squared distance 0\n"), "{out}");
    // The written default template, unedited, is reachable up to its 6-decimal rounding.
    let tpl = scratch("default.tpl");
    let (code, out, err) = lacuna(&["render", "F0", "--level", "1", "--write-template", s(&tpl)]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("wrote"), "{out}");
    let (code, out, err) = lacuna(&[
        "render",
        "F0",
        "--level",
        "1",
        "--template",
        s(&tpl),
        "--svg",
        s(&svg),
    ]);
    assert_eq!(code, 0, "{err}");
    let approx: f64 = out
        .split("(≈ ")
        .nth(1)
        .and_then(|r| r.split(')').next())
        .and_then(|r| r.parse().ok())
        .unwrap_or_else(|| panic!("{out}"));
    // 6 decimals: each coordinate within 5·10⁻⁷ of the reachable default, 54 points × 2.
    assert!(approx < 54.0 * 2.0 * 25e-14 + 1e-12, "{out}");
}

#[test]
fn a_bad_template_is_an_error_with_line_and_column() {
    let path = scratch("bad.tpl");
    std::fs::write(&path, "delta 0\ntype T0\nsub 0 0 0; 1 1\n").unwrap();
    let png = scratch("x.png");
    let render = || {
        lacuna(&[
            "render",
            "F0",
            "--level",
            "1",
            "--template",
            s(&path),
            "--png",
            s(&png),
        ])
    };
    let (code, _, err) = render();
    assert_eq!(code, 2);
    assert!(
        err.contains("error[E1023]: sub-face 0 of type T0 has 9 control points; this line gives 2"),
        "{err}"
    );
    assert!(err.contains("bad.tpl:3:1"), "{err}");
    std::fs::write(&path, "type T0\nsub 0 0 0; 1 x\n").unwrap();
    let (code, _, err) = render();
    assert_eq!(code, 2);
    assert!(
        err.contains("error[E1021]") && err.contains("bad.tpl:2:14"),
        "{err}"
    );
    std::fs::write(&path, "type T4\n").unwrap();
    let (code, _, err) = lacuna(&["measure", "F0", "--level", "1", "--template", s(&path)]);
    assert_eq!(code, 2);
    assert!(
        err.contains("error[E1022]") && err.contains("bad.tpl:1:6"),
        "{err}"
    );
}

#[test]
fn a_goal_the_default_meets_keeps_the_default() {
    // The default lacuna points sit at 0.45 of their spoke points (≥ 0.45·cos 30° ≈ 0.39 from
    // the centre), so min-lacuna=0.1 holds already and the answer is the default, unchanged.
    let (a, b) = (scratch("default.json"), scratch("goal.json"));
    let (code, _, err) = lacuna(&["render", "F0", "--level", "2", "--json-out", s(&a)]);
    assert_eq!(code, 0, "{err}");
    let (code, out, err) = lacuna(&[
        "render",
        "F0",
        "--level",
        "2",
        "--goal",
        "min-lacuna=0.1",
        "--json-out",
        s(&b),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("goals min-lacuna=1/10 met exactly by the fit as it was"),
        "{out}"
    );
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}

/// The inequalities of `min-lacuna=S` checked exactly from the instance, independently of
/// lp.rs: every control point of a lacuna edge of a sub-face, in the exact default template.
fn lacuna_points_at_least(inst: &Instance, size: &Q) -> usize {
    let ex = default_exact(inst);
    let mut checked = 0;
    for (t, ty) in inst.types.types.iter().enumerate() {
        let n = Q::from_integer((ex.types[t].corners.len() as i64).into());
        let o: [Q; 2] =
            [0, 1].map(|d| ex.types[t].corners.iter().map(|c| c[d].clone()).sum::<Q>() / &n);
        for (k, sf) in ty.subdivision.subfaces.iter().enumerate() {
            let m = inst.dims[ty.children[k]];
            let mut off = 0;
            for (l, e) in sf.face.boundary.iter().enumerate() {
                let d = if e.kind == lacuna::topology::EdgeKind::B {
                    3
                } else {
                    2
                };
                if matches!(sf.origins[l], Origin::Lacuna { .. }) {
                    for i in 0..d {
                        let c = (off + i) % m;
                        let y = &ex.types[t].targets[k][c];
                        let dir = [0, 1].map(|j| (&y[j] - &o[j]).to_f64().unwrap());
                        let len = dir[0].hypot(dir[1]);
                        let unit = dir.map(|v| {
                            Q::new(
                                ((v / len * 1048576.0).round() as i64).into(),
                                1048576.into(),
                            )
                        });
                        let v = position(inst, &ex, t, k, c);
                        let along = (&v[0] - &o[0]) * &unit[0] + (&v[1] - &o[1]) * &unit[1];
                        assert!(
                            &along >= size,
                            "T{t} sub-face {k} point {c}: {along} < {size}"
                        );
                        checked += 1;
                    }
                }
                off += d - 1;
            }
        }
    }
    checked
}

#[test]
fn a_goal_that_changes_the_answer_is_met_exactly() {
    // Above the default lacuna (≈ 0.39–0.45): the operators must change.
    let input = load_input("F0").unwrap();
    let default = instantiate(&input, &InstantiateOptions::default()).unwrap();
    let size = Q::new(1.into(), 2.into());
    let opts = InstantiateOptions {
        goals: vec![
            Goal::MinLacuna { size: size.clone() },
            Goal::NonNegative { margin: Q::zero() },
        ],
        ..Default::default()
    };
    let inst = instantiate(&input, &opts).unwrap();
    assert_ne!(inst.values, default.values);
    inst.check_exact().unwrap();
    // F0: 6 sub-faces, each with one lacuna edge B2 of 3 control points.
    assert_eq!(lacuna_points_at_least(&inst, &size), 18);
    for t in 0..inst.types.types.len() {
        for k in 0..inst.types.types[t].children.len() {
            assert!(inst.operator_exact(t, k).iter().all(|w| !w.is_negative()));
        }
    }
    // The same from the command line, with the measures still matching the exact counts.
    let (code, out, err) = lacuna(&[
        "measure",
        "F0",
        "--level",
        "2",
        "--raster",
        "512",
        "--goal",
        "min-lacuna=1/2",
        "--goal",
        "nonnegative",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        err.contains("goals min-lacuna=1/2, nonnegative met exactly by the LP; smallest slack "),
        "{err}"
    );
}

#[test]
fn an_infeasible_goal_is_an_error_naming_it() {
    // Non-negative weights keep every level-1 point in the convex hull of the template polygon
    // (circumradius 1): no lacuna point can be 2 from the centre.
    let (code, out, err) = lacuna(&[
        "render",
        "F0",
        "--level",
        "1",
        "--goal",
        "nonnegative",
        "--goal",
        "min-lacuna=2",
        "--png",
        s(&scratch("x.png")),
    ]);
    assert_eq!(code, 1, "{out}");
    assert!(
        err.contains(
            "error[E1031]: the goals `nonnegative`, `min-lacuna=2` cannot be met together"
        ),
        "{err}"
    );
    let (code, _, err) = lacuna(&[
        "render",
        "F0",
        "--goal",
        "positive",
        "--png",
        s(&scratch("x.png")),
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("error[E1030]"), "{err}");
}

/// Issue #36: the chosen point is checked exactly at level 1 before anything is drawn, and a
/// fit that flattens a cell the constraints do not force flat is moved by the automatic area
/// goal. A template whose two lacuna sides of the digon `B2 B2 | B2 B2 B2 | A1` have the same
/// middle control point asks for a slit: the exact projection puts the lacuna's control polygon
/// (both sides' points on the segment x = 0 from (0, −0.1125) to (0, 0.3375)) at area 0. The
/// goal lifts it to at least its margin: 1/64 of T0's frame area shared among T0's 3 cells. The
/// frame, derived by hand: corners (−1, 1/4), (1, 1/4); the Bézier inner point of each edge at
/// the chord's middle (0, 1/4) pushed outwards by ½·4·½·½ = ½ of the chord (length 2), to
/// (0, −3/4) on edge 0 and (0, 5/4) on edge 1 — a kite with diagonals 2 and 2, area 2. So the
/// margin is 2/(64·3) = 1/96, and the lacuna's area, computed here from the exact operators
/// and this frame, must be at least that.
#[test]
fn a_fit_that_flattens_a_level_one_cell_is_moved_off_the_collapse() {
    let digon = "B2 B2 | B2 B2 B2 | A1";
    let written = scratch("digon-template.txt");
    let (code, _, err) = lacuna(&["render", digon, "--write-template", s(&written)]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&written).unwrap();
    // The template as written projects onto a lens (this round trip flattened the digon's
    // frame before: its exact control points were on the chord).
    let svg = scratch("digon-default.svg");
    let (code, out, err) = lacuna(&[
        "render",
        digon,
        "--template",
        s(&written),
        "--level",
        "3",
        "--svg",
        s(&svg),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("automatic area goal"), "{out}");
    // Sub-face 0's lacuna side is points 6, 7, 8 ((0, 0.3375), (0.1125, 0.1125), (0, −0.1125)),
    // sub-face 1's runs back ((0, −0.1125), (−0.1125, 0.1125), (0, 0.3375)): move both middle
    // points onto the segment between the ends.
    let slit = text
        .replace(
            "0 0.3375; 0.1125 0.1125; 0 -0.1125",
            "0 0.3375; 0 0.1125; 0 -0.1125",
        )
        .replace(
            "0 -0.1125; -0.1125 0.1125; 0 0.3375",
            "0 -0.1125; 0 0.1125; 0 0.3375",
        );
    assert_ne!(slit, text, "the template's lacuna sides moved");
    let edited = scratch("digon-slit.txt");
    std::fs::write(&edited, &slit).unwrap();
    let svg = scratch("digon-slit.svg");
    let (code, out, err) = lacuna(&[
        "render",
        digon,
        "--template",
        s(&edited),
        "--level",
        "3",
        "--svg",
        s(&svg),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("automatic area goal") && out.contains("the fit made the lacuna of T0"),
        "{out}"
    );
    assert!(svg.exists(), "the lifted choice was not drawn");
    // The lacuna's area from the exact operators, in the hand-derived frame.
    let input = load_input(digon).unwrap();
    let opts = InstantiateOptions {
        template: Some(lacuna::Source {
            name: "slit".into(),
            text: slit,
        }),
        ..InstantiateOptions::default()
    };
    let inst = instantiate(&input, &opts).unwrap_or_else(|e| panic!("{e}"));
    let q = |n: i64, d: i64| Q::new(n.into(), d.into());
    let frame = [
        [q(-1, 1), q(1, 4)],
        [q(0, 1), q(-3, 4)],
        [q(1, 1), q(1, 4)],
        [q(0, 1), q(5, 4)],
    ];
    let point = |k: usize, c: usize| {
        let op = inst.operator_exact(0, k);
        let m_w = inst.dims[1];
        let mut p = [Q::zero(), Q::zero()];
        for (r, f) in frame.iter().enumerate() {
            p[0] += &op[r * m_w + c] * &f[0];
            p[1] += &op[r * m_w + c] * &f[1];
        }
        p
    };
    // The lacuna's boundary: sub-face 0's side reversed, then sub-face 1's reversed.
    let poly: Vec<[Q; 2]> = [8, 7, 6]
        .iter()
        .map(|&c| point(0, c))
        .chain([8, 7, 6].iter().map(|&c| point(1, c)))
        .collect();
    let twice: Q = (0..poly.len())
        .map(|i| {
            let (a, b) = (&poly[i], &poly[(i + 1) % poly.len()]);
            &a[0] * &b[1] - &a[1] * &b[0]
        })
        .fold(Q::zero(), |x, y| x + y);
    assert!(
        twice / q(2, 1) >= q(1, 96),
        "the lacuna is below its margin"
    );
    // And the lifted point measures as the verified structure at level 2.
    let (code, out, err) = lacuna(&["measure", digon, "--template", s(&edited), "--level", "2"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("verdict: VERIFIED"), "{out}");
    // Two types: T0 (the digon, 2 sub-faces of type T1) and T1 (`B2 B2 B2 B2 B2`, 5 sub-faces
    // of type T1), each with a central lacuna: 2 + 5 sub-faces and 2 lacunas are checked.
    let (code, out, err) = lacuna(&["measure", digon, "--level", "1"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("level-1 cells: 7 sub-faces and 2 lacunas over all types, every control polygon of positive area"),
        "{out}"
    );
}
