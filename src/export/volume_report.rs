//! Text and JSON reports of volumes (THEORY §10): the closure of volume types, counts per level
//! and the limit ratio.

use crate::analysis::ratio::{analyse, RatioReport};
use crate::constraint::{shared_readings, solve_volumes_with_system, GenOptions, SolvedVolumes};
use crate::error::{Error, Result};
use crate::export::report::{aligned_table, ratio_decimal};
use crate::topology::limits::Limits;
use crate::topology::volume::{
    solid_topology_of, volume_counts, SolidLevel, Volume, VolumeAssembly, VolumeClosure,
    VolumeLevelCount, VolumeTypeSet,
};
use num_rational::BigRational;
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::fmt::Write;

/// What `lacuna verify` finds on a closed set of volumes (THEORY §10): every sub-volume's
/// surface a sphere, counts, the level-n solid, R and the constraints (the faces shared between
/// volumes read from both sides).
#[derive(Debug)]
pub struct VolumeVerify {
    /// Every sub-volume whose surface is not a sphere (empty when every one is).
    pub failures: Vec<String>,
    /// Exact counts per level.
    pub counts: Vec<VolumeLevelCount>,
    /// The level-n solid's topology per level.
    pub solid: Vec<SolidLevel>,
    /// The limit ratio, 30 digits.
    pub ratio: RatioReport,
    /// The constraints solved, with their system; the limit that left them undecided otherwise.
    pub solved: std::result::Result<SolvedVolumes, Error>,
}

/// The checks of `lacuna verify` on the closed set `set` of the volumes of `assembly`, levels 0
/// to `levels`. A limit on the solve leaves the constraints undecided (a limit, not a verdict);
/// any other error is the input's.
pub fn volume_verify(
    set: &VolumeTypeSet,
    assembly: &VolumeAssembly,
    levels: u64,
    limits: &Limits,
) -> Result<VolumeVerify> {
    let failures = set.sub_volume_failures();
    let counts = volume_counts(set, levels);
    let solid = solid_topology_of(set, levels, &assembly.start_cells())?;
    let ratio = volume_ratio(set, 30)?;
    let solved = match solve_volumes_with_system(
        set,
        &shared_readings(assembly),
        GenOptions::default(),
        limits,
    ) {
        Ok(s) => Ok(s),
        Err(e @ (Error::Limit { .. } | Error::ProvedAboveLimit { .. })) => Err(e),
        Err(e) => return Err(e),
    };
    Ok(VolumeVerify {
        failures,
        counts,
        solid,
        ratio,
        solved,
    })
}

impl VolumeVerify {
    /// Whether the volume is verified: every sub-volume a sphere and the constraints solved and
    /// consistent.
    pub fn verified(&self) -> bool {
        self.failures.is_empty() && self.solved.as_ref().is_ok_and(|s| s.report.ok())
    }

    /// The report as `lacuna verify --json` prints it for the volumes `name` closing to `set`.
    pub fn json(&self, name: &str, set: &VolumeTypeSet) -> Value {
        let solver = self.solved.as_ref().map(|s| &s.report);
        json!({
            "input": name,
            "verified": self.verified(),
            "volume_types": set.types.len(),
            "failures": self.failures,
            "counts": self.counts,
            "solid": self.solid,
            "ratio": self.ratio,
            "solver": solver.as_ref().ok(),
            "constraints_undecided": solver.as_ref().err().map(|e| e.to_string()),
            "solid_certified_levels": crate::certificate::solid_rows(&self.solid).len(),
        })
    }
}

/// The exact limit ratio of the start volumes of a closed set, with `digits` certified decimals
/// (the eigen analysis of THEORY §5 on the volume substitution and contributions).
pub fn volume_ratio(set: &VolumeTypeSet, digits: usize) -> Result<RatioReport> {
    let m: Vec<Vec<(usize, u64)>> = set
        .types
        .iter()
        .map(|t| {
            let mut row: BTreeMap<usize, u64> = BTreeMap::new();
            for &c in &t.children {
                *row.entry(c).or_default() += 1;
            }
            row.into_iter().collect()
        })
        .collect();
    let c: Vec<BigRational> = set
        .types
        .iter()
        .map(|t| BigRational::new(t.volume.contribution_quarters().into(), 4.into()))
        .collect();
    let mut start: BTreeMap<usize, u64> = BTreeMap::new();
    for &t in &set.start {
        *start.entry(t).or_default() += 1;
    }
    let start: Vec<(usize, u64)> = start.into_iter().collect();
    // The analysis is the faces' (THEORY §4) on the volume types' matrix: its reasons name the
    // types and cells in the words of faces, said here in those of volumes.
    analyse(&m, &c, &start)
        .map(|r| r.with_digits(digits))
        .map(|mut r| {
            for line in &mut r.reasons {
                *line = line
                    .replace("face type", "volume type")
                    .replace("sub-faces", "sub-volumes");
            }
            r
        })
        .map_err(|e| Error::Analysis(e.to_string()))
}

/// The faces of a volume's surface grouped by type: `3×(B2 B2 B2 B2 B2) + 9×(B2 B2 B2 B2)`.
pub fn surface_summary(v: &Volume) -> String {
    let mut groups: BTreeMap<String, usize> = BTreeMap::new();
    for f in &v.surface.faces {
        let (c, _) = f.canonical();
        let edges: Vec<String> = c.boundary.iter().map(|e| e.to_string()).collect();
        *groups.entry(edges.join(" ")).or_default() += 1;
    }
    let mut parts: Vec<(usize, String)> = groups.into_iter().map(|(k, n)| (n, k)).collect();
    parts.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    parts
        .iter()
        .map(|(n, k)| format!("{n}×({k})"))
        .collect::<Vec<_>>()
        .join(" + ")
}

/// The closure of a volume as text, headed `lacuna COMMAND: NAME` (`closure`, or `verify`,
/// which prints it first).
pub fn volume_closure_text(command: &str, name: &str, closure: &VolumeClosure) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "lacuna {command}: {name}\n");
    match closure {
        VolumeClosure::Runaway(r) => {
            let _ = writeln!(o, "closure: RUNAWAY — {}", r.reason);
            let _ = writeln!(
                o,
                "witness chain (each volume is a sub-volume of the one before):"
            );
            for (k, w) in r.witness.iter().enumerate() {
                let _ = writeln!(o, "  {k:>3}. {w}");
            }
            let _ = writeln!(
                o,
                "\nverdict: NOT VERIFIED (the recursion did not close within the limits)"
            );
        }
        VolumeClosure::Closed(set) => {
            let n = set.types.len();
            let _ = writeln!(
                o,
                "closure: closed, {n} volume type{} (no bound is proved for volumes: checked against --max-types and --max-boundary)",
                if n == 1 { "" } else { "s" }
            );
            for (i, t) in set.types.iter().enumerate() {
                let (_, corners) = t.volume.surface.vertices();
                let _ = writeln!(
                    o,
                    "  V{i}  {} faces, {corners} corners, {} edges (a sphere); delay {}; contributes {}",
                    t.volume.surface.faces.len(),
                    t.volume.surface.edge_count(),
                    t.volume.delay,
                    BigRational::new(t.volume.contribution_quarters().into(), 4.into())
                );
                let _ = writeln!(o, "       faces: {}", surface_summary(&t.volume));
                let mut children: BTreeMap<usize, usize> = BTreeMap::new();
                for &c in &t.children {
                    *children.entry(c).or_default() += 1;
                }
                let list: Vec<String> = children.iter().map(|(c, k)| format!("{k}×V{c}")).collect();
                let _ = writeln!(o, "       → {}", list.join(" + "));
            }
        }
    }
    o
}

/// The closure of a volume as JSON.
pub fn volume_closure_json(name: &str, closure: &VolumeClosure) -> Value {
    match closure {
        VolumeClosure::Runaway(r) => json!({"input": name, "closed": false, "runaway": r}),
        VolumeClosure::Closed(set) => json!({
            "input": name,
            "closed": true,
            "start": set.start,
            "types": set.types.iter().map(|t| {
                let (_, corners) = t.volume.surface.vertices();
                json!({
                    "faces": t.volume.surface.faces.len(),
                    "corners": corners,
                    "edges": t.volume.surface.edge_count(),
                    "surface": surface_summary(&t.volume),
                    "delay": t.volume.delay,
                    "contribution": BigRational::new(t.volume.contribution_quarters().into(), 4.into()).to_string(),
                    "children": t.children,
                })
            }).collect::<Vec<_>>(),
        }),
    }
}

/// The counts of volumes as an aligned table.
pub fn volume_counts_table(levels: &[VolumeLevelCount]) -> String {
    let rows: Vec<[String; 5]> = levels
        .iter()
        .map(|l| {
            [
                l.level.to_string(),
                l.cells.to_string(),
                l.lacunas.to_string(),
                l.ratio.to_string(),
                ratio_decimal(&l.ratio, 6),
            ]
        })
        .collect();
    aligned_table(
        &["level", "cells N^C", "lacunas N^L", "R_i", "R_i ≈"],
        &rows,
    )
}

/// The exact topology of the solid per level as an aligned table (`–` where not derived).
pub fn solid_table(levels: &[SolidLevel]) -> String {
    let opt = |x: Option<String>| x.unwrap_or_else(|| "–".into());
    let rows: Vec<[String; 9]> = levels
        .iter()
        .map(|l| {
            [
                l.level.to_string(),
                l.volumes.to_string(),
                l.faces.to_string(),
                l.edges.to_string(),
                l.corners.to_string(),
                l.euler.to_string(),
                opt(l.components.map(|x| x.to_string())),
                opt(l.voids.map(|x| x.to_string())),
                opt(l.tunnels.as_ref().map(|x| x.to_string())),
            ]
        })
        .collect();
    aligned_table(
        &[
            "level",
            "volumes",
            "faces",
            "edges",
            "corners",
            "χ",
            "components",
            "voids",
            "tunnels",
        ],
        &rows,
    )
}
