//! Invariant: a certificate the checker accepts states exactly what lacuna's producer states
//! for the same claim — no forgery passes.
//!
//! The input is a mutation script applied to a valid certificate (faces, automata and
//! substitutions of the library): numbers near 2^64, rationals and decimals respelled, array
//! elements repeated or dropped (repeated pairs, missing types, missing rows), steps reordered,
//! duplicated or deleted, the claim of another certificate, and a claim cut back to a prefix
//! of its start faces (so that the closure lists families the claim never reaches). Whenever
//! the checker accepts the result, the target recomputes the certificate of its claim with the
//! producer (`certify::recertify`) and panics if what `check` prints differs (for an automaton,
//! whose contraction and similarity steps are optional: if it proves anything the producer does
//! not state).
#![no_main]
use lacuna::certificate::Certificate;
use lacuna::checker::{check, check_json};
use libfuzzer_sys::fuzz_target;
use serde_json::Value;
use std::sync::OnceLock;

/// The valid certificates mutated, as JSON values.
fn seeds() -> &'static [Value] {
    static SEEDS: OnceLock<Vec<Value>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let mut certs: Vec<Certificate> = Vec::new();
        let limits = lacuna::topology::Limits::default();
        for name in ["F0", "square-B2"] {
            let input = lacuna::input::load_input(name).expect("a library face");
            let ts = lacuna::topology::close_or_error(&input.faces(), &limits).expect("closes");
            let opts = lacuna::constraint::GenOptions::default();
            certs.push(lacuna::certificate::certificate_for(name, &ts, opts).expect("certifies"));
        }
        // F0 and square-B2 closed together: honest for both starts; cutting its claim back to F0
        // (the mutation below, or another seed's claim) appends a closed family F0 never
        // reaches, the forgery of issue #28.
        let union: Vec<_> = ["F0", "square-B2"]
            .iter()
            .flat_map(|n| {
                lacuna::input::load_input(n)
                    .expect("a library face")
                    .faces()
            })
            .collect();
        let ts = lacuna::topology::close_or_error(&union, &limits).expect("closes");
        let opts = lacuna::constraint::GenOptions::default();
        certs.push(lacuna::certificate::certificate_for("union", &ts, opts).expect("certifies"));
        for name in ["spec-edge", "spec-edge-incidence", "chaikin-known"] {
            if let Ok(lacuna::input::Loaded::Automaton { automaton, .. }) =
                lacuna::input::load_any(name)
            {
                certs.push(
                    lacuna::certificate::certificate_for_automaton(name, &automaton)
                        .expect("certifies"),
                );
            }
        }
        // Automata with their attractor steps (contraction, similarity dimension, boundary
        // dimension), the claim carrying the field and the attractor; the dragon's open-set
        // condition is witnessed by neighbour maps (which its boundary step reuses), gasket-4's
        // by convex sets (its boundary step carries maps of its own), the self-seeding square's
        // failure by two words with one map. (penrose-robinson is left out: its boundary step
        // carries 1 061 maps in Q(√5), and checking and recertifying it takes seconds.)
        for name in [
            "sierpinski-triangle",
            "koch",
            "gasket-4",
            "heighway-dragon",
            "self-seeding-square",
        ] {
            if let Ok(lacuna::input::Loaded::Automaton { model, .. }) =
                lacuna::input::load_any(name)
            {
                certs.push(
                    lacuna::certificate::certify_model(
                        name,
                        &model,
                        limits.max_unknowns,
                        limits.max_products,
                    )
                    .expect("certifies"),
                );
            }
        }
        let golden = vec![
            vec![(1, 1)],
            vec![(1, 1), (2, 1)],
            vec![(1, 1), (3, 1)],
            vec![(3, 1)],
        ];
        let periodic = vec![vec![(1, 2)], vec![(0, 8)]];
        for (m, h) in [(golden, vec![2, 1, 3, 0]), (periodic, vec![2, 0])] {
            certs.push(
                lacuna::certificate::certificate_for_substitution("matrix", &m, &h, &[(0, 1)])
                    .expect("analyses"),
            );
        }
        certs
            .iter()
            .map(|c| serde_json::from_str(&c.to_json()).expect("json"))
            .collect()
    })
}

/// Every node of a JSON value, by path: leaves and arrays.
fn nodes(
    v: &Value,
    path: &mut Vec<Value>,
    leaves: &mut Vec<Vec<Value>>,
    arrays: &mut Vec<Vec<Value>>,
) {
    match v {
        Value::Array(a) => {
            arrays.push(path.clone());
            for (i, x) in a.iter().enumerate() {
                path.push(i.into());
                nodes(x, path, leaves, arrays);
                path.pop();
            }
        }
        Value::Object(o) => {
            for (k, x) in o {
                path.push(k.clone().into());
                nodes(x, path, leaves, arrays);
                path.pop();
            }
        }
        _ => leaves.push(path.clone()),
    }
}

fn at<'a>(v: &'a mut Value, path: &[Value]) -> &'a mut Value {
    path.iter().fold(v, |v, k| match k {
        Value::Number(i) => &mut v[i.as_u64().unwrap_or(0) as usize],
        Value::String(s) => &mut v[s.as_str()],
        _ => v,
    })
}

const NEAR_2_64: [u64; 8] = [
    u64::MAX,
    u64::MAX - 1,
    1 << 63,
    (1 << 32) + 1,
    12_297_829_382_473_034_411, // 3^(−1) mod 2^64: 3 times it wraps to 1
    0,
    1,
    2,
];

fn mutate(json: &mut Value, ops: &mut impl Iterator<Item = u8>) {
    let mut next = || ops.next().unwrap_or(0) as usize;
    let (mut leaves, mut arrays) = (Vec::new(), Vec::new());
    nodes(json, &mut Vec::new(), &mut leaves, &mut arrays);
    let pick = |n: usize, r: usize| (r * 251 + r / 7) % n.max(1);
    match next() % 10 {
        9 => {
            // The claim's start faces (or volumes) cut back to a prefix: the steps still list
            // the closure of all of them.
            let keep = next();
            for k in ["faces", "volumes"] {
                if let Some(Value::Array(a)) = json["claim"].get_mut(k).and_then(|c| c.get_mut(k)) {
                    a.truncate(keep % a.len().max(1));
                }
            }
        }
        0 if !leaves.is_empty() => {
            let (p, k) = (pick(leaves.len(), next() * 256 + next()), next());
            let leaf = at(json, &leaves[p]);
            *leaf = match leaf.clone() {
                Value::Number(n) => {
                    let x = n.as_u64().unwrap_or(0);
                    Value::from(match k % 3 {
                        0 => NEAR_2_64[k % NEAR_2_64.len()],
                        1 => x.wrapping_add(1),
                        _ => x.wrapping_sub(1),
                    })
                }
                Value::Bool(b) => Value::Bool(!b),
                Value::Null => Value::from(0),
                other => other,
            }
        }
        1 if !leaves.is_empty() => {
            let (p, k) = (pick(leaves.len(), next() * 256 + next()), next());
            let leaf = at(json, &leaves[p]);
            if let Value::String(s) = leaf.clone() {
                *leaf = Value::from(match k % 8 {
                    0 => format!("{s}0"),
                    1 => format!("-{s}"),
                    2 => format!("{s}/1"),
                    3 => s.replacen('.', "._", 1),
                    4 => s.trim_start_matches('0').to_string(),
                    5 => "18446744073709551617".to_string(),
                    6 => {
                        let mut t = s.clone();
                        t.pop();
                        t
                    }
                    _ => format!("0{s}"),
                });
            }
        }
        2 | 3 if !arrays.is_empty() => {
            let p = pick(arrays.len(), next() * 256 + next());
            let i = next();
            if let Value::Array(a) = at(json, &arrays[p]) {
                if !a.is_empty() {
                    let i = i % a.len();
                    match a.len() % 2 {
                        0 => a.insert(i, a[i].clone()), // repeated element
                        _ => {
                            a.remove(i);
                        }
                    }
                }
            }
        }
        4 | 5 | 6 => {
            let (k, i, j) = (next(), next(), next());
            if let Value::Array(steps) = &mut json["steps"] {
                if !steps.is_empty() {
                    let (i, j) = (i % steps.len(), j % steps.len());
                    match k % 3 {
                        0 => steps.swap(i, j),
                        1 => steps.insert(i, steps[j].clone()),
                        _ => {
                            steps.remove(i);
                        }
                    }
                }
            }
        }
        7 => {
            let other = &seeds()[next() % seeds().len()];
            json["claim"] = other["claim"].clone();
        }
        _ => {
            let other = &seeds()[next() % seeds().len()];
            let (i, j) = (next(), next());
            if let (Value::Array(mine), Value::Array(theirs)) =
                (&mut json["steps"], &other["steps"])
            {
                if !mine.is_empty() && !theirs.is_empty() {
                    let (i, j) = (i % mine.len(), j % theirs.len());
                    mine[i] = theirs[j].clone();
                }
            }
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let seeds = seeds();
    let mut ops = data.iter().copied();
    let mut json = seeds[ops.next().unwrap_or(0) as usize % seeds.len()].clone();
    let rounds = 1 + ops.next().unwrap_or(0) % 3;
    for _ in 0..rounds {
        mutate(&mut json, &mut ops);
    }
    let text = json.to_string();
    let report = check_json(&text);
    if !report.all_proved() {
        return;
    }
    let cert = Certificate::from_json(&text).expect("an accepted certificate parses");
    let limits = lacuna::topology::Limits {
        max_types: 2_000,
        ..lacuna::topology::Limits::default()
    };
    let again = lacuna::certificate::recertify("fuzz", &cert.claim, &limits).unwrap_or_else(|e| {
        panic!("the checker accepted a claim the producer fails on: {e}\n{text}")
    });
    let want = check(&again);
    assert!(
        want.all_proved(),
        "the producer's certificate fails:\n{}",
        want.to_text()
    );
    // Every verdict the accepted certificate proves is one the producer states. Optional steps
    // (an automaton's contraction, similarity dimension and rule compilation, the cells and
    // Betti numbers of a face's complex or of a solid) may be left out: a certificate may prove
    // less, never something else. Every step the claim needs is there (`all_proved`).
    let want_claims = want.claims();
    for c in report.claims() {
        assert!(
            want_claims.contains(&c),
            "FORGERY: the checker accepted a certificate stating something else ({c}):\n{text}"
        );
    }
});
