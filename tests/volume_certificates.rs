//! Certificates of volumes (THEORY §10, issue #15): the volume-closure step round-trips and
//! checks for every volume of the library, and a certificate with a changed count, a wrong type,
//! a missing type or a forged form of a type is rejected, by `lacuna check` with exit 1, with a
//! reason that names what is wrong.

use lacuna::certificate::{Certificate, Step, VolumeClosureStep, VolumeRule};
use lacuna::checker::{check, Outcome};

mod common;
use common::{
    assert_proved, closed_volumes, lacuna, volume_certificate, volume_certificate_with_system,
};

fn closure_of(cert: &mut Certificate) -> &mut VolumeClosureStep {
    match cert.steps.first_mut() {
        Some(Step::VolumeClosure(c)) => c,
        _ => panic!("the first step is the volume closure"),
    }
}

/// The checker refuses `cert` at the volume-closure step with a message containing `reason`.
fn refused(what: &str, cert: &Certificate, reason: &str) {
    failed_at("volume-closure", what, cert, reason);
}

/// The checker fails `cert` at the step `name` with a message containing `reason`.
fn failed_at(name: &str, what: &str, cert: &Certificate, reason: &str) {
    let report = check(cert);
    let step = report
        .step(name)
        .unwrap_or_else(|| panic!("{what}: no {name} report:\n{}", report.to_text()));
    assert_eq!(
        step.outcome,
        Outcome::Failed,
        "{what}:\n{}",
        report.to_text()
    );
    assert!(
        step.message.contains(reason),
        "{what}: expected `{reason}` in `{}`",
        step.message
    );
    assert!(!report.all_proved());
}

#[test]
fn library_volumes_certify() {
    for name in [
        "cube-B2",
        "tetrahedron-B2",
        "cube-C2",
        "truncated-tetrahedron",
        "two-cubes",
    ] {
        let mut cert = volume_certificate(name);
        assert_proved(name, &cert);
        recurrence_agrees(name, &mut cert);
    }
}

#[test]
fn the_cube_certificate_states_the_hand_counts() {
    // THEORY §10 and docs/VOLUMES.md: the cube has 8 corner pieces W3 (19 corners: 16 of degree
    // 3, 3 of degree 4), W4 has 25 corners (20 and 5), and every volume has one child per
    // corner: 1, 8, 8·19 = 152, 8·(16·19 + 3·25) = 3032 cells. Lacunas: one step of the cube
    // gives its cavity and half of each square's centre: 1 + 6/2 = 4; W3 (3 pentagons, 9
    // squares, a 9-gon, each with one centre) gives 1 + 13/2 = 15/2, W4 1 + 17/2 = 19/2; so
    // N^L_2 = 4 + 8·15/2 = 64 and N^L_3 = 64 + 8·(16·15/2 + 3·19/2) = 64 + 8·(120 + 57/2) = 1252.
    let cert = volume_certificate("cube-B2");
    let report = check(&cert);
    assert!(report.all_proved(), "{}", report.to_text());
    assert!(
        report
            .claims()
            .iter()
            .any(|c| c.contains("N^C = 1, 8, 152, 3032; N^L = 0, 4, 64, 1252")),
        "{:?}",
        report.claims()
    );
}

#[test]
fn the_cube_certificate_proves_r_by_hand() {
    // The dominant class {W3, W4} has M = [[16, 3], [20, 5]], ρ = 20 (λ² − 21λ + 20 = 0), left
    // eigenvector u = (5, 1): cells grow as 20^i·(5 + 1), lacunas add u·c = 5·15/2 + 19/2 = 47
    // per unit, summed over the levels below: 47/19. R = (47/19) / (47/19 + 6) = 47/161.
    let cert = volume_certificate("cube-B2");
    let Some(Step::LimitRatio(r)) = cert.steps.get(1) else {
        panic!("the second step is the limit ratio")
    };
    assert!(r.exists);
    assert_eq!(r.rho.poly, ["-20", "1"]);
    assert_eq!(r.points.len(), 1);
    assert_eq!(r.points[0].value, ["47/161"]);
    let report = check(&cert);
    assert!(report.all_proved(), "{}", report.to_text());
    // A forged limit: 1/3 instead of 47/161.
    let mut bad = cert.clone();
    if let Some(Step::LimitRatio(r)) = bad.steps.get_mut(1) {
        r.points[0].value = vec!["1/3".into()];
    }
    let report = check(&bad);
    let step = report.step("limit-ratio").expect("a limit-ratio report");
    assert_eq!(step.outcome, Outcome::Failed, "{}", report.to_text());
    // Without its volume closure the ratio has no substitution: refused as a whole.
    let mut alone = cert.clone();
    alone.steps.remove(0);
    let report = check(&alone);
    assert_eq!(report.steps[0].step, "structure", "{}", report.to_text());
    // Without the ratio the certificate is partial.
    let mut partial = cert;
    partial.steps.retain(|s| !matches!(s, Step::LimitRatio(_)));
    let report = check(&partial);
    assert!(report.partial(), "{}", report.to_text());
}

#[test]
fn a_changed_count_is_rejected() {
    let mut cert = volume_certificate("cube-B2");
    closure_of(&mut cert).counts[2].cells = "153".into();
    refused("cells", &cert, "level 2: 153 cells listed, 152 recounted");
    let mut cert = volume_certificate("cube-B2");
    closure_of(&mut cert).counts[1].lacunas = "9/2".into();
    refused("lacunas", &cert, "level 1: 9/2 lacunas listed, 4 recounted");
    let mut cert = volume_certificate("cube-B2");
    closure_of(&mut cert).counts.pop();
    refused("a level missing", &cert, "counts listed for levels 0 to 3");
    let mut cert = volume_certificate("tetrahedron-B2");
    closure_of(&mut cert).types[0].contribution_quarters += 1;
    refused("contribution", &cert, "is not the one of THEORY §10");
}

#[test]
fn a_wrong_type_is_rejected() {
    // A child listed as the wrong type.
    let mut cert = volume_certificate("cube-B2");
    let c = closure_of(&mut cert);
    // Type 0 (the cube itself) is already numbered, so the breadth-first order still holds and
    // the comparison with the derived sub-volumes is what rejects it.
    c.types[0].children[0] = 0;
    refused("child", &cert, "are not the derived sub-volumes");
    // A child numbered past the next new type: out of breadth-first order.
    let mut cert = volume_certificate("cube-B2");
    let c = closure_of(&mut cert);
    c.types[0].children[0] = 2;
    refused("order", &cert, "canonical breadth-first closure");
    // A listed type whose rule is changed: the cube's corner pieces (rule V1) are then not
    // listed.
    let mut cert = volume_certificate("cube-B2");
    let c = closure_of(&mut cert);
    let t = c.types[0].children[0];
    c.types[t].volume.rule = VolumeRule::V2;
    refused("rule", &cert, "is not a listed type");
    // A start volume that is not the listed one.
    let mut cert = volume_certificate("cube-B2");
    if let lacuna::certificate::Claim::Volumes(v) = &mut cert.claim {
        v.volumes[0].delay = 2;
    }
    refused("start", &cert, "start volume 0 is not a listed type");
}

#[test]
fn a_missing_type_is_rejected() {
    let mut cert = volume_certificate("cube-C2");
    let c = closure_of(&mut cert);
    let last = c.types.len() - 1;
    c.types.pop();
    for t in &mut c.types {
        t.children.retain(|&x| x != last);
    }
    refused("missing", &cert, "is not a listed type");
}

#[test]
fn a_forged_form_is_rejected() {
    // Two entries of one type: the second copy of a type under another index.
    let mut cert = volume_certificate("cube-B2");
    let c = closure_of(&mut cert);
    let (a, b) = (1, 2);
    c.types[b].volume = c.types[a].volume.clone();
    refused(
        "duplicate",
        &cert,
        &format!("types {a} and {b} are the same volume type"),
    );
    // A gluing that is not an involution is not a surface.
    let mut cert = volume_certificate("cube-B2");
    let g = &mut closure_of(&mut cert).types[1].volume.glue;
    g[0][0] = g[0][1];
    refused("gluing", &cert, "not glued back");
    // Re-gluing two pairs of edges crosswise keeps every edge glued once to an edge of its type
    // but makes another surface: the cube's face 0 edge 0 and 1 swap partners. The corners
    // then no longer close up into a sphere (or the type changes), and the certificate fails.
    let mut cert = volume_certificate("cube-B2");
    let v = &mut closure_of(&mut cert).types[0].volume;
    let (p, q) = (v.glue[0][0], v.glue[0][1]);
    v.glue[0][0] = q;
    v.glue[0][1] = p;
    v.glue[p.0][p.1] = (0, 1);
    v.glue[q.0][q.1] = (0, 0);
    let report = check(&cert);
    assert!(report.failed(), "{}", report.to_text());
}

#[test]
fn lacuna_check_exits_1_on_a_tampered_volume_certificate() {
    let dir = std::env::temp_dir().join(format!("lacuna-volcert-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = dir.join("cube.json");
    let (code, _, err) = lacuna(&[
        "verify",
        "cube-B2",
        "--levels",
        "3",
        "--certificate",
        good.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let (code, out, _) = lacuna(&["check", good.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("proved  step 0 (volume-closure)"), "{out}");
    let text = std::fs::read_to_string(&good).unwrap();
    // The level-3 count 3032 becomes 3033.
    assert!(text.contains("\"cells\":\"3032\""), "{text}");
    let bad = dir.join("bad.json");
    std::fs::write(
        &bad,
        text.replace("\"cells\":\"3032\"", "\"cells\":\"3033\""),
    )
    .unwrap();
    let (code, out, _) = lacuna(&["check", bad.to_str().unwrap()]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("FAILED") && out.contains("level 3: 3033 cells listed, 3032 recounted"),
        "{out}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The first step of the variant `$v` of a certificate, to change it.
macro_rules! step_mut {
    ($cert:expr, $v:path) => {
        $cert
            .steps
            .iter_mut()
            .find_map(|s| match s {
                $v(x) => Some(x),
                _ => None,
            })
            .expect(stringify!($v))
    };
}

fn solid_of(cert: &mut Certificate) -> &mut lacuna::certificate::SolidHomologyStep {
    step_mut!(cert, Step::SolidHomology)
}

/// The checker fails `cert` at the solid-homology step with a message containing `reason`.
fn solid_refused(what: &str, cert: &Certificate, reason: &str) {
    failed_at("solid-homology", what, cert, reason);
}

#[test]
fn the_solids_of_the_library_are_certified_with_their_hand_figures() {
    // The cube at level 1 (derived by hand in checker/solid.rs): 8 volumes, 80 faces, 156
    // edges, 80 corners, χ = −4, one component, no void, 5 tunnels; every level of the
    // library's volumes up to 250 000 cells is in the step.
    let mut cert = volume_certificate("cube-B2");
    let rows = &solid_of(&mut cert).rows;
    assert_eq!(rows.len(), 4, "levels 0 to 3 of the cube");
    assert_eq!(
        (
            rows[1].volumes,
            rows[1].faces,
            rows[1].edges,
            rows[1].corners
        ),
        (8, 80, 156, 80)
    );
    assert_eq!((rows[1].euler, rows[1].tunnels), (-4, 5));
    // Two cubes glued: the shared face is in the claim, and one component at every level.
    let mut two = volume_certificate("two-cubes");
    match &two.claim {
        lacuna::certificate::Claim::Volumes(v) => assert_eq!(v.shared.len(), 1),
        _ => panic!("a volumes claim"),
    }
    assert!(solid_of(&mut two).rows.iter().all(|r| r.components == 1));
}

fn recurrence_of(cert: &mut Certificate) -> &mut lacuna::certificate::SolidRecurrenceStep {
    step_mut!(cert, Step::SolidRecurrence)
}

/// Where the certificate has both, the recurrence's rows are the solid built cell by cell (two
/// derivations of the checker that share only the one-step code), and its volumes are the
/// closure's counts N^C (a third, from the children alone) at every level.
fn recurrence_agrees(name: &str, cert: &mut Certificate) {
    let built = cert.steps.iter().find_map(|s| match s {
        Step::SolidHomology(h) => Some(h.rows.clone()),
        _ => None,
    });
    let counts = closure_of(cert).counts.clone();
    let rows = recurrence_of(cert).rows.clone();
    assert_eq!(rows.len(), counts.len(), "{name}: one row per level");
    for (r, c) in rows.iter().zip(&counts) {
        assert_eq!(r.volumes, c.cells, "{name}: level {} volumes", r.level);
    }
    for (b, r) in built.iter().flatten().zip(&rows) {
        let cells = [b.volumes, b.faces, b.edges, b.corners].map(|x| x.to_string());
        assert_eq!(
            cells,
            [&r.volumes, &r.faces, &r.edges, &r.corners].map(|x| x.clone()),
            "{name}: level {}",
            b.level
        );
        assert_eq!(b.euler.to_string(), r.euler, "{name}: level {} χ", b.level);
        if let Some(c) = r.components {
            assert_eq!(b.components, c, "{name}: level {} components", b.level);
        }
    }
}

#[test]
fn the_recurrence_agrees_with_the_built_solid_and_forgeries_fail() {
    // The agreement for every library volume is in `library_volumes_certify`.
    // Forged rows are caught by the recurrence itself (at levels 0–3 the solid-homology step
    // would catch them too; past them only the recurrence does, below).
    let honest = volume_certificate("cube-B2");
    let forge = |f: &dyn Fn(&mut lacuna::certificate::SolidRecurrenceStep)| {
        let mut bad = honest.clone();
        f(recurrence_of(&mut bad));
        bad
    };
    let bump = |s: &str, by: i64| (s.parse::<i64>().unwrap() + by).to_string();
    let bad = forge(&|r| r.rows[3].faces = bump(&r.rows[3].faces, 1));
    failed_at(
        "solid-recurrence",
        "a face more at level 3",
        &bad,
        "the row says",
    );
    let bad = forge(&|r| {
        r.rows[2].corners = bump(&r.rows[2].corners, -1);
        r.rows[2].euler = bump(&r.rows[2].euler, -1);
    });
    failed_at(
        "solid-recurrence",
        "a corner fewer and χ with it",
        &bad,
        "corners",
    );
    let bad = forge(&|r| r.rows[3].components = Some(2));
    failed_at("solid-recurrence", "two components", &bad, "level 0 has 1");
    let bad = forge(&|r| {
        r.rows.pop();
    });
    failed_at(
        "solid-recurrence",
        "a level missing",
        &bad,
        "rows for levels 0 to 3",
    );
    let bad = forge(&|r| {
        r.rows[3].voids = Some(1);
        r.rows[3].tunnels = Some(bump(r.rows[3].tunnels.as_deref().unwrap(), 1));
    });
    failed_at(
        "solid-recurrence",
        "a void (and a tunnel with it)",
        &bad,
        "1 void claimed",
    );
    let bad = forge(&|r| r.rows[2].tunnels = Some(bump(r.rows[2].tunnels.as_deref().unwrap(), 1)));
    failed_at(
        "solid-recurrence",
        "a tunnel more",
        &bad,
        "b0 + b2 − χ = 77",
    );
    let bad = forge(&|r| r.rows[1].voids = None);
    failed_at(
        "solid-recurrence",
        "tunnels without voids",
        &bad,
        "without components and voids",
    );
    let bad = forge(&|r| r.rows[2].level = 3);
    failed_at(
        "solid-recurrence",
        "a level out of place",
        &bad,
        "row 2 is for level 3",
    );
    // A delayed cube caps its holes: the checker derives no voids past level 0, and refuses
    // them when claimed.
    let text = "cube B2 | B2 B2 B2 | A1 | B2 B2 | V1 | 2";
    let v = lacuna::topology::volume::parse_volume(text).unwrap();
    let set = closed_volumes(std::slice::from_ref(&v));
    let assembly = lacuna::topology::volume::VolumeAssembly::single(v);
    let mut delayed =
        lacuna::certificate::certificate_for_volumes(text, &set, 2, &assembly).unwrap();
    assert_proved(text, &delayed);
    let r = recurrence_of(&mut delayed);
    assert!(r.rows[2].voids.is_none(), "no voids claimed past level 0");
    r.rows[2].voids = Some(0);
    failed_at(
        "solid-recurrence",
        "voids of a delayed cube",
        &delayed,
        "premises",
    );
    // Level 5 of the cube, past the solid built cell by cell (its 24 million cells are above
    // the solid-homology step's bound): the recurrence alone certifies it.
    let (_, volumes) = lacuna::input::load_volumes("cube-B2").unwrap().unwrap();
    let set = closed_volumes(&volumes.volume_list());
    let mut deep =
        lacuna::certificate::certificate_for_volumes("cube-B2", &set, 5, &volumes).unwrap();
    assert_proved("cube-B2 to level 5", &deep);
    let built = deep.steps.iter().find_map(|s| match s {
        Step::SolidHomology(h) => Some(h.rows.len()),
        _ => None,
    });
    assert_eq!(built, Some(4), "levels 0–3 built cell by cell");
    recurrence_agrees("cube-B2 to level 5", &mut deep);
    let r = recurrence_of(&mut deep);
    r.rows[5].edges = bump(&r.rows[5].edges, 2);
    r.rows[5].faces = bump(&r.rows[5].faces, 2);
    failed_at(
        "solid-recurrence",
        "two edges and two faces more at level 5",
        &deep,
        "the row says",
    );
}

#[test]
fn forged_solids_are_rejected() {
    let honest = volume_certificate("cube-B2");
    // A Betti number changed, and χ with it so that the counts still add up.
    let mut bad = honest.clone();
    let r = &mut solid_of(&mut bad).rows[2];
    r.tunnels += 1;
    solid_refused("one tunnel more", &bad, "the row says");
    // One void claimed (b1 raised with it, so b0 − b1 + b2 = χ still holds).
    let mut bad = honest.clone();
    let r = &mut solid_of(&mut bad).rows[1];
    r.voids += 1;
    r.tunnels += 1;
    solid_refused("a void", &bad, "b2 = 1");
    // A corner fewer and χ with it.
    let mut bad = honest.clone();
    let r = &mut solid_of(&mut bad).rows[2];
    r.corners -= 1;
    r.euler -= 1;
    solid_refused("a corner fewer", &bad, "1339");
    // A level skipped.
    let mut bad = honest.clone();
    solid_of(&mut bad).rows.remove(1);
    solid_refused("a level skipped", &bad, "row 1 is for level 2");
    // The two cubes without their shared face: two components, so the rows do not hold.
    let mut bad = volume_certificate("two-cubes");
    if let lacuna::certificate::Claim::Volumes(v) = &mut bad.claim {
        v.shared.clear();
    }
    solid_refused(
        "the shared face dropped",
        &bad,
        "the solid built has 2 volumes, 12 faces",
    );
    // (Turning the shared square by a quarter is no forgery: it glues the same solid.) A
    // shared face that names no face of its volume is refused.
    let mut bad = volume_certificate("two-cubes");
    if let lacuna::certificate::Claim::Volumes(v) = &mut bad.claim {
        v.shared[0].b[1] = 9;
    }
    solid_refused("a shared face of no face", &bad, "no such volume or face");
}

#[test]
fn the_face_complex_rows_agree_with_measure_and_forgeries_fail() {
    // `measure` counts holes as central lacunas plus closed gaps, by a flag recurrence; the
    // checker by the rank of ∂2 over F2 on the complex it builds: two derivations that must meet.
    for name in ["F0", "delayed-B2-C2", "triangle-C2"] {
        let cert = common::face_certificate(name);
        let rows = match cert.steps.last() {
            Some(Step::FaceHomology(h)) => h.rows.clone(),
            _ => panic!("{name}: no face-homology step"),
        };
        assert_proved(name, &cert);
        let (code, out, err) = lacuna(&["measure", name, "--level", "3", "--json"]);
        assert_eq!(code, 0, "{err}");
        let m: serde_json::Value = serde_json::from_str(&out).unwrap();
        for level in 0..=3usize {
            let exact = &m["levels"][level]["exact"];
            assert_eq!(
                exact["holes"].as_str().unwrap(),
                rows[level].holes.to_string(),
                "{name} level {level}"
            );
            assert_eq!(exact["components"], rows[level].components, "{name}");
            assert_eq!(
                exact["faces"].as_str().unwrap(),
                rows[level].faces.to_string()
            );
        }
        // One hole more (χ kept): refused at the step.
        let mut bad = cert.clone();
        if let Some(Step::FaceHomology(h)) = bad.steps.last_mut() {
            h.rows[2].holes += 1;
        }
        failed_at("face-homology", name, &bad, "the row says");
        // One corner more and χ with it, the holes lowered to match: refused.
        let mut bad = cert.clone();
        if let Some(Step::FaceHomology(h)) = bad.steps.last_mut() {
            h.rows[1].corners += 1;
            h.rows[1].euler += 1;
            h.rows[1].holes -= 1;
        }
        failed_at("face-homology", name, &bad, "the row says");
    }
}

mod random {
    //! The certificate of random small volumes checks, and a changed count is caught.
    use super::*;
    use lacuna::topology::volume::{parse_volume, VolumeClosure};
    use lacuna::topology::Limits;
    use proptest::prelude::*;

    fn notation() -> impl Strategy<Value = String> {
        (
            proptest::sample::select(vec!["tetrahedron", "cube", "prism-3", "octahedron"]),
            proptest::sample::select(vec!["B2", "C2", "B3", "C3"]),
            proptest::sample::select(vec!["B2 B2 B2", "C2 B2 B2", "B2 B2 C2"]),
            proptest::sample::select(vec!["A1", "A2", "A3"]),
            proptest::sample::select(vec!["B2 B2", "C2 B2", "B2 C2"]),
            proptest::sample::select(vec!["V1", "V2"]),
            proptest::sample::select(vec!["", " | 2"]),
        )
            .prop_map(|(s, x, e, a, g, r, d)| format!("{s} {x} | {e} | {a} | {g} | {r}{d}"))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(12))]
        #[test]
        fn random_volumes_certify(text in notation()) {
            let v = parse_volume(&text).unwrap();
            let limits = Limits { max_types: 16, ..Limits::default() };
            let Ok(VolumeClosure::Closed(set)) = VolumeClosure::of(std::slice::from_ref(&v), &limits) else {
                // A refused rule or a closure past the small limit: nothing to certify.
                return Ok(());
            };
            let assembly = lacuna::topology::volume::VolumeAssembly::single(v);
            let cert =
                lacuna::certificate::certificate_for_volumes(&text, &set, 2, &assembly).unwrap();
            let report = check(&cert);
            prop_assert!(report.all_proved(), "{}\n{}", text, report.to_text());
            let mut both = cert.clone();
            recurrence_agrees(&text, &mut both);
            let mut bad = cert.clone();
            let r = recurrence_of(&mut bad);
            let n: u64 = r.rows[2].edges.parse().unwrap();
            r.rows[2].edges = (n + 1).to_string();
            prop_assert!(check(&bad).failed(), "{}", text);
            let mut bad = cert.clone();
            let c = closure_of(&mut bad);
            let n: u64 = c.counts[1].cells.parse().unwrap();
            c.counts[1].cells = (n + 1).to_string();
            prop_assert!(check(&bad).failed());
        }
    }

    proptest! {
        // Each case solves a system of up to a few hundred thousand unknowns and checks it
        // (a few seconds in a debug build): few cases, and a bound on the unknowns.
        #![proptest_config(ProptestConfig::with_cases(6))]
        #[test]
        fn random_volume_systems_certify(text in notation()) {
            let v = parse_volume(&text).unwrap();
            let limits = Limits {
                max_types: 16,
                max_unknowns: 200_000,
                ..Limits::default()
            };
            let Ok(VolumeClosure::Closed(set)) = VolumeClosure::of(std::slice::from_ref(&v), &limits) else {
                return Ok(());
            };
            let assembly = lacuna::topology::volume::VolumeAssembly::single(v);
            let mut cert =
                lacuna::certificate::certificate_for_volumes(&text, &set, 1, &assembly).unwrap();
            match lacuna::certificate::solve_and_certify_volumes(&set, &assembly, &limits) {
                Ok(steps) => cert.steps.extend(steps),
                // Above the bound: a limit, nothing to certify.
                Err(lacuna::certificate::CertifyError::Lacuna(
                    lacuna::Error::Limit { .. } | lacuna::Error::ProvedAboveLimit { .. },
                )) => return Ok(()),
                Err(e) => return Err(TestCaseError::fail(format!("{text}: {e}"))),
            }
            let report = check(&cert);
            prop_assert!(report.all_proved(), "{}\n{}", text, report.to_text());
            // One basis vector dropped (a degree of freedom denied) is caught.
            let mut bad = cert.clone();
            let s = system_of(&mut bad);
            if s.dof > 0 {
                s.free.pop();
                s.basis.pop();
                s.dof -= 1;
                s.rank += 1;
                prop_assert!(check(&bad).failed(), "{}", text);
            }
        }
    }
}

fn system_of(cert: &mut Certificate) -> &mut lacuna::certificate::VolumeSystemStep {
    step_mut!(cert, Step::VolumeSolutionSpace)
}

/// The checker fails `cert` at the volume-solution-space step with a message containing
/// `reason`.
fn system_refused(what: &str, cert: &Certificate, reason: &str) {
    failed_at("volume-solution-space", what, cert, reason);
}

#[test]
fn the_volume_constraints_are_certified_and_agree_with_the_solver() {
    // Two implementations meet: lacuna's generator and sparse solver (constraint/volume.rs,
    // linsys) and the checker's rebuild from its own derivation of the sub-volumes
    // (checker/volume_system.rs). The checker's row count and dof must be the solver's.
    for name in ["cube-B2", "tetrahedron-B2"] {
        let mut cert = volume_certificate_with_system(name);
        assert_proved(name, &cert);
        let (code, out, err) = lacuna(&["solve", name, "--json"]);
        assert_eq!(code, 0, "{err}");
        let solved: serde_json::Value = serde_json::from_str(&out).expect("json");
        let step = system_of(&mut cert).clone();
        assert_eq!(serde_json::json!(step.dof), solved["dof"], "{name}: {out}");
        assert_eq!(serde_json::json!(step.unknowns), solved["unknowns"]);
        let report = check(&cert);
        let msg = &report.step("volume-solution-space").unwrap().message;
        let rows = format!(
            "{} rows over {} unknowns",
            solved["equations"], step.unknowns
        );
        assert!(msg.contains(&rows), "{name}: `{rows}` not in {msg}");
        if name == "cube-B2" {
            // By hand (CERTIFICATES.md): the cube's state has 20 points (8 corners, 12 edge
            // midpoints), the corner piece V1 49 (19 corners, 30 edges), V2 65 (25, 40);
            // V0 → 8 V1, V1 → 16 V1 + 3 V2, V2 → 20 V1 + 5 V2.
            let volume_part = 8 * 20 * 49 + 49 * (16 * 49 + 3 * 65) + 65 * (20 * 49 + 5 * 65);
            assert_eq!(volume_part, 140_636);
            let face_part = step.unknowns - volume_part;
            assert!(
                msg.contains(&format!("({face_part} of face operators")),
                "{msg}"
            );
        }
    }
}

#[test]
fn a_forged_volume_system_is_rejected() {
    let good = volume_certificate_with_system("cube-B2");
    let forge = |f: &dyn Fn(&mut lacuna::certificate::VolumeSystemStep)| {
        let mut c = good.clone();
        f(system_of(&mut c));
        c
    };
    // A changed entry of the particular solution.
    let c = forge(&|s| {
        let x = &mut s.particular[0].1;
        *x = if x == "1" { "2".into() } else { "1".into() };
    });
    system_refused("particular", &c, "the particular solution fails row");
    // A basis vector changed off its free unknown.
    let c = forge(&|s| {
        let b = s
            .basis
            .iter_mut()
            .find(|b| b.len() > 1)
            .expect("a basis vector with a pivot entry");
        let free: std::collections::BTreeSet<usize> = s.free.iter().copied().collect();
        let e = b.iter_mut().find(|(i, _)| !free.contains(i)).unwrap();
        e.1 = format!("{}1", e.1.trim_start_matches('-'));
    });
    system_refused("basis", &c, "fails homogeneous row");
    // One degree of freedom more: an unknown that is not free made free with a unit vector.
    let c = forge(&|s| {
        let free: std::collections::BTreeSet<usize> = s.free.iter().copied().collect();
        let x = (0..s.unknowns).find(|i| !free.contains(i)).unwrap();
        let at = s.free.partition_point(|&f| f < x);
        s.free.insert(at, x);
        s.basis.insert(at, vec![(x, "1".into())]);
        s.dof += 1;
        s.rank -= 1;
    });
    system_refused("extra dof", &c, "fails homogeneous row");
    // One degree of freedom less: a free unknown and its vector dropped. The basis still
    // satisfies the rows, but the unknowns that are not free are then dependent.
    let c = forge(&|s| {
        s.free.pop();
        s.basis.pop();
        s.dof -= 1;
        s.rank += 1;
    });
    system_refused("fewer dof", &c, "are not shown independent");
    // Counts that do not add up.
    let c = forge(&|s| s.rank += 1);
    system_refused("rank", &c, "unknowns");
    let c = forge(&|s| s.unknowns += 1);
    system_refused("unknowns", &c, "unknowns");
    // A face read as another face type: the second face of the corner piece (V1) whose type
    // occurs earlier on its surface, relabelled as the cube's square (type 0), so that the face
    // closure's start order still holds and the frame check is what rejects it.
    let c = forge(&|s| {
        let fr = &mut s.frames[1];
        let f = (1..fr.len())
            .find(|&f| fr[f].0 != 0 && fr[..f].iter().any(|x| x.0 == fr[f].0))
            .expect("a repeated face type other than the square");
        fr[f].0 = 0;
    });
    system_refused("frame type", &c, "is not face type");
    // The start faces of the face closure out of order.
    let c = forge(&|s| s.frames[0][0].0 = s.frames[1].iter().map(|f| f.0).max().unwrap());
    system_refused("frame order", &c, "the face closure");
    // Two sub-volumes of the corner piece placed as each other's type (the children's
    // multiset is unchanged): the derived sub-volume is not the placed type.
    let c = forge(&|s| {
        let list = &mut s.subvolumes[1];
        let a = list.iter().position(|p| p.type_index == 1).unwrap();
        let b = list.iter().position(|p| p.type_index == 2).unwrap();
        list[a].type_index = 2;
        list[b].type_index = 1;
    });
    system_refused("placement type", &c, "faces derived");
    // A sub-face placed on another face of its sub-volume's type.
    let c = forge(&|s| {
        let p = &mut s.subvolumes[0][0];
        p.subfaces[0].1 = p.subfaces[1].1;
    });
    let report = check(&c);
    assert!(report.failed(), "{}", report.to_text());
    // A turned frame of a square face: a symmetry of the square, so the face is still its
    // type, but it would read the type's sub-faces onto other quarters of the face (another
    // system). Frames are the canonical rotation.
    let c = forge(&|s| s.frames[0][0].1 = (s.frames[0][0].1 + 1) % 4);
    system_refused("frame rotation", &c, "is not its canonical rotation");
    // The degeneracy step on the volume system: a pair of corners that do not coincide
    // listed as coinciding (corners 0 of sub-faces 0 and 1 of the square).
    let mut c = good.clone();
    let d = c
        .steps
        .iter_mut()
        .find_map(|s| match s {
            Step::Degeneracy(d) => Some(d),
            _ => None,
        })
        .expect("a degeneracy step");
    assert!(d.coincide.is_empty());
    d.coincide.push([0, 0, 0, 1, 0]);
    failed_at(
        "degeneracy",
        "a false coincidence",
        &c,
        "listed as coinciding",
    );
    // Without the solution space it rests on, the degeneracy step proves nothing.
    let mut c = good.clone();
    c.steps
        .retain(|s| !matches!(s, Step::VolumeSolutionSpace(_)));
    failed_at(
        "degeneracy",
        "no system",
        &c,
        "no proved volume-solution-space step",
    );
    // The unforged certificate still checks.
    assert_proved("cube-B2", &good);
}

#[test]
fn verify_writes_the_volume_system_and_check_proves_it() {
    let dir = std::env::temp_dir().join(format!("lacuna-volsys-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tetra.json");
    let (code, out, err) = lacuna(&[
        "verify",
        "tetrahedron-B2",
        "--certificate",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("certified by the solution space (volume-solution-space)"),
        "{out}"
    );
    let (code, out, _) = lacuna(&["check", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("proved  step 3 (solid-recurrence)")
            && out.contains("proved  step 4 (volume-solution-space)")
            && out.contains("volume constraints: consistent")
            && out.contains("proved  step 5 (degeneracy)"),
        "{out}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_shared_face_of_two_cubes_is_rebuilt_and_binds() {
    // Two cubes glued face to face have the cube's volume types, so the same unknowns; the
    // shared face adds the rows that make its sub-faces one polygon from either side, which
    // the checker rebuilds: the rank rises and fewer degrees of freedom remain.
    let mut one = volume_certificate_with_system("cube-B2");
    let mut two = volume_certificate_with_system("two-cubes");
    assert_proved("two-cubes", &two);
    let (a, b) = (system_of(&mut one).clone(), system_of(&mut two).clone());
    assert_eq!(a.unknowns, b.unknowns);
    assert!(b.dof < a.dof, "{} ≥ {}", b.dof, a.dof);
    let report = check(&two);
    let msg = &report.step("volume-solution-space").unwrap().message;
    assert!(
        msg.contains("of 1 face shared by the start volumes"),
        "{msg}"
    );
    // The cube's own solution space does not satisfy the shared face's rows: a certificate of
    // the assembly carrying it is refused.
    let mut forged = two.clone();
    *system_of(&mut forged) = a;
    let report = check(&forged);
    let step = report.step("volume-solution-space").unwrap();
    assert_eq!(step.outcome, Outcome::Failed, "{}", report.to_text());
}
