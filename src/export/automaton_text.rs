//! An automaton written back in lacuna's own automaton format (`docs/FORMATS.md`, "Automaton
//! files"), for `lacuna export INPUT --format aut`.
//!
//! The writer keeps the order of states, operators, constraints and barycentric conditions, so
//! `lacuna solve` of the written file builds the same linear system (same unknowns, equations, rank
//! and degrees of freedom) as the automaton it came from. Names the format does not accept (`^` in
//! `C2^3`) are rewritten (`C2_d3`), and made unique if a rewrite collides.

use crate::constraint::{Automaton, Factor, OpKind};
use std::collections::{BTreeMap, HashSet};
use std::fmt::Write as _;

/// A name the automaton format accepts: letters, digits, `_`, `.`, `'`, not starting with a digit
/// or a dot. `^` becomes `_d`, anything else `_`.
fn sanitize(name: &str) -> String {
    let mut out = String::new();
    for c in name.chars() {
        match c {
            '^' => out.push_str("_d"),
            c if c.is_ascii_alphanumeric() || c == '_' || c == '.' || c == '\'' => out.push(c),
            _ => out.push('_'),
        }
    }
    if !out
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
    {
        out.insert(0, '_');
    }
    out
}

/// Sanitised, unique names for a list of names.
fn unique_names<'a>(names: impl Iterator<Item = &'a str>) -> Vec<String> {
    let mut used = HashSet::new();
    names
        .map(|n| {
            let base = sanitize(n);
            let mut name = base.clone();
            let mut k = 2;
            while !used.insert(name.clone()) {
                name = format!("{base}_{k}");
                k += 1;
            }
            name
        })
        .collect()
}

/// Writes `a` in lacuna's automaton format. `header` lines become comments at the top; `notes`
/// adds a comment after the declaration of the given states (for instance a face type's
/// notation).
pub fn automaton_text(a: &Automaton, header: &[String], notes: &BTreeMap<usize, String>) -> String {
    let states = unique_names(a.states.iter().map(|s| s.name.as_str()));
    let ops = unique_names(a.operators.iter().map(|o| o.name.as_str()));
    let mut o = String::new();
    for h in header {
        let _ = writeln!(o, "# {h}");
    }
    for (i, s) in a.states.iter().enumerate() {
        let _ = write!(o, "state {} {}", states[i], s.dim);
        match notes.get(&i) {
            Some(n) => {
                let _ = writeln!(o, "    # {n}");
            }
            None => o.push('\n'),
        }
    }
    for (i, op) in a.operators.iter().enumerate() {
        let kind = match op.kind {
            OpKind::Sub => "sub",
            OpKind::Embed => "embed",
            OpKind::Perm => "perm",
            OpKind::Other => "op",
        };
        let _ = write!(
            o,
            "{kind} {} : {} <- {}",
            ops[i], states[op.to], states[op.from]
        );
        match &op.value {
            Some(m) => {
                let _ = writeln!(o, " = {m}");
            }
            None => o.push('\n'),
        }
    }
    // Barycentric conditions name their operators (the bare keyword would add every sub and
    // embed operator, which is not what every automaton asks).
    for chunk in a.barycentric.chunks(8) {
        let names: Vec<&str> = chunk.iter().map(|&k| ops[k].as_str()).collect();
        let _ = writeln!(o, "barycentric {}", names.join(" "));
    }
    let word = |w: &[Factor]| -> String {
        w.iter()
            .map(|f| match f {
                Factor::Op(k) => ops[*k].clone(),
                Factor::Literal(m) => m.to_string(),
            })
            .collect::<Vec<_>>()
            .join(" * ")
    };
    for c in &a.constraints {
        let label = c.label.replace('#', "no.");
        let _ = writeln!(o, "{} = {}    # {label}", word(&c.lhs), word(&c.rhs));
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_made_acceptable_and_unique() {
        assert_eq!(sanitize("C2^3.T0"), "C2_d3.T0");
        assert_eq!(sanitize("2x"), "_2x");
        assert_eq!(
            unique_names(["a^b", "a_db", "a b"].into_iter()),
            ["a_db", "a_db_2", "a_b"]
        );
    }
}
