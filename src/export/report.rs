//! Reports: the verification report (human text and JSON) and the JSON of `closure` and
//! `counts`. Everything here formats results computed elsewhere; nothing is decided here.

use crate::input::library::Input;
use crate::topology::class::ClassStructure;
use crate::topology::closure::{Bound, Closure, Runaway, TypeSet};
use crate::topology::count::{counts_from, LevelCount};
use crate::topology::Face;
use num_rational::BigRational;
use serde::Serialize;
use serde_json::{json, Value};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::sync::Arc;

/// One face type as reported.
#[derive(Clone, Debug, Serialize)]
pub struct TypeRow {
    /// `T0`, `T1`, …
    pub id: String,
    /// Canonical notation.
    pub face: String,
    /// The sub-faces' canonical notations, in order.
    pub subfaces: Vec<String>,
    /// The sub-faces' type ids, in order.
    pub children: Vec<String>,
    /// Lacunas contributed per step, exact.
    pub contribution: String,
    /// The level-1 complex: vertices, edges, sub-faces, holes and valences (THEORY §9).
    pub complex: crate::topology::subdivision::Complex,
}

/// The counts of one start face of an assembly.
#[derive(Clone, Debug, Serialize)]
pub struct FaceCounts {
    /// The face's name in the input.
    pub face: String,
    /// Its counts.
    pub levels: Vec<LevelCount>,
}

/// The verification report.
#[derive(Clone, Debug, Serialize)]
pub struct VerifyReport {
    /// What was verified.
    pub input: String,
    /// Whether every check passed.
    pub verified: bool,
    /// Whether the closure closed.
    pub closed: bool,
    /// The runaway, when it did not close.
    pub runaway: Option<Runaway>,
    /// The stated bound, when there is one.
    pub bound: Option<Bound>,
    /// The first structural identity that failed, if any.
    pub structure_error: Option<String>,
    /// The types.
    pub types: Vec<TypeRow>,
    /// The classes reached, with periods.
    pub classes: Option<ClassStructure>,
    /// Counts of the whole input.
    pub counts: Vec<LevelCount>,
    /// Counts per start face (assemblies of more than one face).
    pub per_face: Vec<FaceCounts>,
    /// The number of shared edges of the assembly.
    pub shared_edges: usize,
    /// The constraint solver's verdict on the generated automaton (THEORY §6).
    pub solver: Option<crate::constraint::automaton::SolveReport>,
    /// The exact limit ratio (THEORY §5).
    pub ratio: Option<crate::analysis::ratio::RatioReport>,
}

/// The exact limit ratio of the start faces of a closed type set (THEORY §5), with `digits`
/// certified decimals.
pub fn ratio_of(
    ts: &TypeSet,
    digits: usize,
) -> crate::error::Result<crate::analysis::ratio::RatioReport> {
    let c: Vec<BigRational> = ts
        .types
        .iter()
        .map(|t| BigRational::new(t.contribution_halves().into(), 2.into()))
        .collect();
    let mut start: Vec<(usize, u64)> = Vec::new();
    for &t in &ts.start {
        match start.iter_mut().find(|(s, _)| *s == t) {
            Some(e) => e.1 += 1,
            None => start.push((t, 1)),
        }
    }
    crate::analysis::ratio::analyse(&ts.matrix(), &c, &start)
        .map(|r| r.with_digits(digits))
        .map_err(|e| crate::error::Error::Analysis(e.to_string()))
}

/// The human-readable limit-ratio section.
pub fn ratio_text(r: &crate::analysis::ratio::RatioReport) -> String {
    let mut o = String::new();
    match (&r.exact, &r.decimal) {
        (Some(exact), Some(dec)) if r.exists => {
            let _ = writeln!(o, "limit ratio R = {exact}");
            let _ = writeln!(o, "              ≈ {dec}");
        }
        _ => {
            let _ = writeln!(
                o,
                "limit ratio: R_i has NO LIMIT; it oscillates with period {} between:",
                r.period
            );
            for p in &r.limit_points {
                let _ = writeln!(
                    o,
                    "  i ≡ {} (mod {}): {} ≈ {}",
                    p.residue, r.period, p.exact, p.decimal
                );
            }
        }
    }
    let _ = writeln!(
        o,
        "Perron root ρ = {} ≈ {}",
        r.perron_root, r.perron_decimal
    );
    let _ = writeln!(o, "  minimal polynomial {}", r.perron_min_poly);
    let _ = writeln!(o, "classes (spectral radius, period):");
    for c in &r.classes {
        let members: Vec<String> = c.members.iter().map(|m| format!("T{m}")).collect();
        let period = c
            .period
            .map_or("transient".to_string(), |p| format!("period {p}"));
        let _ = writeln!(
            o,
            "  {{{}}}  ρ = {}  {}{}",
            members.join(", "),
            c.spectral_radius,
            period,
            if c.dominant { "  (dominant)" } else { "" }
        );
    }
    let _ = writeln!(o, "how it was decided:");
    for reason in &r.reasons {
        let _ = writeln!(o, "  - {reason}");
    }
    o
}

/// The rows of the type table.
pub fn type_rows(ts: &TypeSet) -> Vec<TypeRow> {
    ts.types
        .iter()
        .enumerate()
        .map(|(k, t)| TypeRow {
            id: format!("T{k}"),
            face: t.face.to_string(),
            subfaces: {
                // The sub-faces of a step share their interned faces: each is written once.
                let mut names: HashMap<*const Face, String> = HashMap::new();
                t.subdivision
                    .subfaces
                    .iter()
                    .map(|s| {
                        names
                            .entry(Arc::as_ptr(&s.face))
                            .or_insert_with(|| s.face.to_string())
                            .clone()
                    })
                    .collect()
            },
            children: t.children.iter().map(|c| format!("T{c}")).collect(),
            contribution: BigRational::new(t.contribution_halves().into(), 2.into()).to_string(),
            complex: t.subdivision.level1_complex(&t.face),
        })
        .collect()
}

/// Runs the topology checks and builds the report.
pub fn verify_report(
    input: &Input,
    closure: &Closure,
    levels: u64,
    limits: &crate::topology::limits::Limits,
) -> crate::error::Result<VerifyReport> {
    let mut report = closure_report(input, closure);
    let Closure::Closed(ts) = closure else {
        return Ok(report);
    };
    report.counts = crate::topology::count::counts(ts, levels);
    report.per_face = per_face_counts(ts, input, levels);
    match ratio_of(ts, 30) {
        Ok(r) => report.ratio = Some(r),
        Err(e) => report.structure_error = Some(e.to_string()),
    }
    let solver = crate::constraint::generate::solve_closure(
        ts,
        crate::constraint::generate::GenOptions::default(),
        limits,
    );
    if let Err(e @ crate::error::Error::Limit { .. }) = solver {
        return Err(e);
    }
    let solver_ok = match solver {
        Ok(r) => {
            let ok = r.ok();
            report.solver = Some(r);
            ok
        }
        Err(e) => {
            report.structure_error = Some(format!("constraint generation failed: {e}"));
            false
        }
    };
    report.verified = report.structure_error.is_none() && solver_ok;
    Ok(report)
}

/// The closure part of the checks only: closed or runaway, the stated bound, the structural
/// identities and the classes.
pub fn closure_report(input: &Input, closure: &Closure) -> VerifyReport {
    let mut report = VerifyReport {
        input: input.name.clone(),
        verified: false,
        closed: false,
        runaway: None,
        bound: None,
        structure_error: None,
        types: Vec::new(),
        classes: None,
        counts: Vec::new(),
        per_face: Vec::new(),
        shared_edges: input.assembly.shared.len(),
        solver: None,
        ratio: None,
    };
    match closure {
        Closure::Runaway(r) => {
            report.runaway = Some(r.clone());
        }
        Closure::Closed(ts) => {
            report.closed = true;
            report.bound = ts.bound.clone();
            report.structure_error = ts.verify().err();
            report.types = type_rows(ts);
            report.classes = Some(ts.classes());
            report.verified = report.structure_error.is_none();
        }
    }
    report
}

impl VerifyReport {
    /// The human-readable report.
    pub fn to_text(&self) -> String {
        self.text("verify")
    }

    /// The closure part of the report only (`lacuna closure`).
    pub fn closure_text(&self) -> String {
        self.text("closure")
    }

    /// The report of `command`; `closure` leaves out the counts, the ratio and the constraints
    /// (its text ends with the closure's verdict), and the per-face counts of its assembly line.
    fn text(&self, command: &str) -> String {
        let per_face: &[FaceCounts] = if command == "closure" {
            &[]
        } else {
            &self.per_face
        };
        let mut o = String::new();
        let _ = writeln!(o, "lacuna {command}: {}", self.input);
        if self.shared_edges > 0 || !per_face.is_empty() {
            let _ = writeln!(
                o,
                "assembly: {} face{}, {} shared edge{} (types and delays match)",
                per_face.len().max(1),
                if per_face.len() > 1 { "s" } else { "" },
                self.shared_edges,
                if self.shared_edges == 1 { "" } else { "s" }
            );
        }
        o.push('\n');
        if let Some(r) = &self.runaway {
            let _ = writeln!(o, "closure: RUNAWAY — {}", r.reason);
            let _ = writeln!(
                o,
                "witness chain (each face is a sub-face of the one before):"
            );
            for (k, w) in r.witness.iter().enumerate() {
                let _ = writeln!(o, "  {k:>3}. {w}");
            }
            let _ = writeln!(
                o,
                "\nverdict: NOT VERIFIED (the recursion did not close within the limits)"
            );
            return o;
        }
        let _ = writeln!(
            o,
            "closure: closed, {} face type{}",
            self.types.len(),
            if self.types.len() == 1 { "" } else { "s" }
        );
        match &self.bound {
            Some(b) => {
                let _ = writeln!(
                    o,
                    "bound: boundary length ≤ {}, types ≤ {} — respected\n  ({})",
                    b.max_length, b.max_types, b.reason
                );
            }
            None => {
                let _ = writeln!(
                    o,
                    "bound: none stated (custom algorithm); closed within the configured limits"
                );
            }
        }
        for t in &self.types {
            let _ = writeln!(o, "  {:<4} {}", t.id, t.face);
            let _ = writeln!(
                o,
                "       → {} sub-face{}: {}   contribution {}",
                t.children.len(),
                if t.children.len() == 1 { "" } else { "s" },
                summarise(&t.children),
                t.contribution
            );
            let c = &t.complex;
            let valences: Vec<String> =
                c.valences.iter().map(|(v, n)| format!("{n}×{v}")).collect();
            let _ = writeln!(
                o,
                "       level-1 complex: V {} − E {} + F {} = {} ({} hole{}), valences {}",
                c.vertices,
                c.edges,
                c.faces,
                c.euler(),
                c.holes,
                if c.holes == 1 { "" } else { "s" },
                valences.join(" ")
            );
        }
        match &self.structure_error {
            None => {
                let _ = writeln!(
                    o,
                    "structure: every sub-edge used once, every gap closed on both sides, every Ea shared by two sub-faces in opposite directions, every lacuna cycle closed, every level-1 complex a disk with its holes (Euler)"
                );
            }
            Some(e) => {
                let _ = writeln!(o, "structure: FAILED — {e}");
            }
        }
        if let Some(cl) = &self.classes {
            let _ = writeln!(o, "\nclasses reached (topological order):");
            for c in &cl.classes {
                let members: Vec<String> = c.members.iter().map(|m| format!("T{m}")).collect();
                let period = match c.period {
                    Some(p) => format!("period {p}"),
                    None => "transient".into(),
                };
                let _ = writeln!(o, "  {{{}}}  {}", members.join(", "), period);
            }
        }
        if command == "closure" {
            let closed = self.structure_error.is_none();
            let _ = writeln!(
                o,
                "\nverdict: {}",
                if closed {
                    "closure CLOSED and checked"
                } else {
                    "NOT VERIFIED"
                }
            );
            return o;
        }
        let _ = writeln!(o, "\ncounts:");
        o += &counts_table(&self.counts);
        for f in &self.per_face {
            let _ = writeln!(o, "\ncounts of face {}:", f.face);
            o += &counts_table(&f.levels);
        }
        if let Some(r) = &self.ratio {
            o.push('\n');
            o += &ratio_text(r);
        }
        if let Some(sv) = &self.solver {
            let _ = writeln!(
                o,
                "\nconstraints (Bézier degree 2; `lacuna solve` for the solution):"
            );
            let _ = writeln!(
                o,
                "  {} unknowns, {} equations, rank {}",
                sv.unknowns,
                sv.equations,
                sv.rank.map_or("-".into(), |r| r.to_string())
            );
            if sv.consistent {
                let _ = writeln!(o, "  consistent: {} degrees of freedom", sv.dof);
                if sv.degenerate.is_empty() {
                    let _ = writeln!(
                        o,
                        "  no forced collapse of distinct corner points or cells (exact; certified by the degeneracy step)"
                    );
                } else {
                    for d in &sv.degenerate {
                        let _ = writeln!(o, "  FORCED COLLAPSE: {d}");
                    }
                }
            } else {
                let _ = writeln!(
                    o,
                    "  INCONSISTENT (run `lacuna solve` for the conflicting constraints)"
                );
            }
        }
        let _ = writeln!(
            o,
            "\nverdict: {}",
            if self.verified && self.bound.is_some() {
                "VERIFIED (closure closed, bound respected, structural identities hold, constraints consistent, no forced collapse)"
            } else if self.verified {
                "VERIFIED (closure closed within the configured limits, no bound stated; structural identities hold, constraints consistent, no forced collapse)"
            } else {
                "NOT VERIFIED"
            }
        );
        o
    }
}

/// `T0×6` style summary of a list of type ids, in first-appearance order.
fn summarise(children: &[String]) -> String {
    let mut order: Vec<(&String, usize)> = Vec::new();
    for c in children {
        match order.iter_mut().find(|(x, _)| *x == c) {
            Some(e) => e.1 += 1,
            None => order.push((c, 1)),
        }
    }
    order
        .iter()
        .map(|(c, k)| format!("{k}×{c}"))
        .collect::<Vec<_>>()
        .join(" + ")
}

/// The counts as an aligned table.
pub fn counts_table(levels: &[LevelCount]) -> String {
    let rows: Vec<[String; 5]> = levels
        .iter()
        .map(|l| {
            let approx = ratio_decimal(&l.ratio, 6);
            [
                l.level.to_string(),
                l.faces.to_string(),
                l.lacunas.to_string(),
                l.ratio.to_string(),
                approx,
            ]
        })
        .collect();
    aligned_table(
        &["level", "faces N^C", "lacunas N^L", "R_i", "R_i ≈"],
        &rows,
    )
}

/// A table of right-aligned columns under their headings, one space of margin and one between
/// columns (the counts tables of faces and volumes, the solid's table).
pub(crate) fn aligned_table<const N: usize>(heads: &[&str; N], rows: &[[String; N]]) -> String {
    let mut w = heads.map(|h| h.chars().count());
    for r in rows {
        for (k, c) in r.iter().enumerate() {
            w[k] = w[k].max(c.chars().count());
        }
    }
    let line = |cells: &[String]| {
        let mut s = String::from(" ");
        for (k, c) in cells.iter().enumerate() {
            s += &format!(" {}{}", " ".repeat(w[k] - c.chars().count()), c);
        }
        s + "\n"
    };
    let mut o = line(&heads.map(String::from));
    for r in rows {
        o += &line(r);
    }
    o
}

/// A rational to `digits` decimal places, truncated (exact integer arithmetic).
pub fn ratio_decimal(r: &BigRational, digits: usize) -> String {
    use num_traits::Signed;
    let scale = num_bigint::BigInt::from(10u32).pow(digits as u32);
    // In integers: a rational product would reduce by a gcd of numbers of thousands of digits.
    let scaled = r.numer().abs() * &scale / r.denom();
    let int = &scaled / &scale;
    let frac = (&scaled % &scale).to_string();
    let sign = if r.is_negative() { "-" } else { "" };
    if digits == 0 {
        return format!("{sign}{int}");
    }
    format!(
        "{sign}{int}.{}{frac}",
        "0".repeat(digits.saturating_sub(frac.len()))
    )
}

/// JSON of `lacuna closure`.
pub fn closure_json(closure: &Closure) -> Value {
    match closure {
        Closure::Closed(ts) => json!({
            "closed": true,
            "start": ts.start.iter().map(|t| format!("T{t}")).collect::<Vec<_>>(),
            "bound": ts.bound,
            "types": type_rows(ts),
            "classes": ts.classes(),
        }),
        Closure::Runaway(r) => json!({ "closed": false, "runaway": r }),
    }
}

/// The counts of each start face of an assembly of more than one face (empty otherwise).
fn per_face_counts(ts: &TypeSet, input: &Input, levels: u64) -> Vec<FaceCounts> {
    if ts.start.len() < 2 {
        return Vec::new();
    }
    input
        .assembly
        .faces
        .iter()
        .zip(&ts.start)
        .map(|((name, _), &t)| FaceCounts {
            face: name.clone(),
            levels: counts_from(ts, &[(t, 1)], levels),
        })
        .collect()
}

/// JSON of `lacuna counts`.
pub fn counts_json(ts: &TypeSet, input: &Input, levels: u64) -> Value {
    // `cells` (the faces, N^C) beside `faces`, as the counts of volumes name their sub-volumes.
    let mut rows =
        serde_json::to_value(crate::topology::count::counts(ts, levels)).unwrap_or(Value::Null);
    if let Some(rows) = rows.as_array_mut() {
        for row in rows {
            let faces = row["faces"].clone();
            row["cells"] = faces;
        }
    }
    let mut v = json!({
        "types": ts.types.len(),
        "levels": rows,
    });
    let per = per_face_counts(ts, input, levels);
    if !per.is_empty() {
        v["per_face"] = serde_json::to_value(per).unwrap_or(Value::Null);
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals_truncate_exactly() {
        let r = BigRational::new(5.into(), 17.into());
        assert_eq!(ratio_decimal(&r, 6), "0.294117");
        assert_eq!(
            ratio_decimal(&BigRational::new(1.into(), 1.into()), 3),
            "1.000"
        );
        assert_eq!(
            ratio_decimal(&BigRational::new(1.into(), 100.into()), 3),
            "0.010"
        );
    }
}
