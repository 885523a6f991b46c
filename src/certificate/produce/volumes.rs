//! Certificates of volume sets: the volume claim, its closure and constraint system
//! (`volume-system`), the solid's rows by level and by recurrence, and lacuna's volumes read back
//! from a claim.

use super::faces::{closure_step, edge, face, lacuna_edge, lacuna_face};
use super::systems::{direction, nonzero, ratio_step_in};
use super::{CertifyError, SOLID_CELLS};
use crate::certificate::format::{
    Certificate, Claim, DegeneracyStep, Face, SharedFaceClaim, SolidCountRow, SolidHomologyStep,
    SolidRecurrenceStep, SolidRow, Step, Volume, VolumeClosureStep, VolumeCount, VolumeRule,
    VolumeTypeRule, VolumesClaim,
};
use crate::certificate::format::{SubVolumePlacement, VolumeSystemStep};

/// The certificate of a closed set of volume types (THEORY §10): the claim is the start volumes
/// of `assembly` (with the faces they share) and the number of levels; the steps are the closure
/// of volume types with the counts of the start volumes from level 0 to `levels`, the limit
/// ratio of its substitution, and the topology of the level-n solid from level 0 while its
/// levels have at most [`SOLID_CELLS`] cells and lacuna derives no cavity (the checker proves
/// Betti numbers where F2 shows none).
pub fn certificate_for_volumes(
    input: &str,
    set: &crate::topology::volume::VolumeTypeSet,
    levels: u64,
    assembly: &crate::topology::volume::VolumeAssembly,
) -> Result<Certificate, CertifyError> {
    let types = set
        .types
        .iter()
        .map(|t| {
            Ok(VolumeTypeRule {
                volume: volume(&t.volume)?,
                children: t.children.clone(),
                contribution_quarters: t.volume.contribution_quarters(),
            })
        })
        .collect::<Result<Vec<_>, CertifyError>>()?;
    let volumes = set.start.iter().map(|&s| types[s].volume.clone()).collect();
    let counts = crate::topology::volume::volume_counts(set, levels)
        .into_iter()
        .map(|c| VolumeCount {
            level: c.level,
            cells: c.cells.to_string(),
            lacunas: c.lacunas.to_string(),
        })
        .collect();
    // The substitution: one row per type (children counted), quarters, start multiplicities.
    let matrix: Vec<Vec<(usize, u64)>> = types
        .iter()
        .map(|t| {
            let mut row: std::collections::BTreeMap<usize, u64> = Default::default();
            for &c in &t.children {
                *row.entry(c).or_default() += 1;
            }
            row.into_iter().collect()
        })
        .collect();
    let quarters: Vec<u64> = types.iter().map(|t| t.contribution_quarters).collect();
    let mut start: std::collections::BTreeMap<usize, u64> = Default::default();
    for &s in &set.start {
        *start.entry(s).or_default() += 1;
    }
    let start: Vec<(usize, u64)> = start.into_iter().collect();
    let ratio = ratio_step_in(&matrix, &quarters, &start, 4)?;
    // Volumes glued face to face are written as they were given, so that the shared faces'
    // edge numbers hold; volumes apart in their canonical form.
    let (volumes, shared) = match assembly.shared.is_empty() {
        true => (volumes, Vec::new()),
        false => (
            assembly
                .volumes
                .iter()
                .map(volume)
                .collect::<Result<Vec<_>, _>>()?,
            assembly
                .shared
                .iter()
                .map(|s| SharedFaceClaim {
                    a: [s.a.0, s.a.1, s.a.2],
                    b: [s.b.0, s.b.1, s.b.2],
                })
                .collect(),
        ),
    };
    let solid = crate::topology::volume::solid_topology_of(set, levels, &assembly.start_cells())?;
    let rows = solid_rows(&solid);
    let claim = VolumesClaim {
        volumes,
        levels,
        shared,
    };
    let mut cert = Certificate::new(input, Claim::Volumes(claim));
    cert.steps
        .push(Step::VolumeClosure(VolumeClosureStep { types, counts }));
    cert.steps.push(Step::LimitRatio(ratio));
    if !rows.is_empty() {
        cert.steps
            .push(Step::SolidHomology(SolidHomologyStep { rows }));
    }
    let voids = recurrence_has_voids(set);
    cert.steps.push(Step::SolidRecurrence(SolidRecurrenceStep {
        rows: solid
            .iter()
            .map(|l| solid_count_row(l, l.level == 0 || voids))
            .collect(),
    }));
    Ok(cert)
}

/// The `volume-solution-space` step of a solved volume system: the face closure
/// of the surfaces, every face's frame, every sub-volume's placement, and the solution space with
/// the unknowns in the checker's order (face operators type by type, then `V<v>.T<k>` volume
/// by volume, each row-major), then the `degeneracy` step of the surfaces' face types on that
/// solution set. None when the system is inconsistent (lacuna then has no certificate for the
/// volume constraints).
pub fn volume_system_step(
    set: &crate::topology::volume::VolumeTypeSet,
    solved: &crate::constraint::SolvedVolumes,
    opts: &crate::constraint::GenOptions,
) -> Result<Vec<Step>, CertifyError> {
    let crate::constraint::Solution::Consistent(space) = &solved.solution else {
        return Ok(Vec::new());
    };
    let gv = &solved.generated;
    let faces = closure_step(&gv.faces)?;
    let index: std::collections::HashMap<&crate::topology::Face, usize> = gv
        .faces
        .types
        .iter()
        .enumerate()
        .map(|(i, t)| (&t.face, i))
        .collect();
    let mismatch = |what: &str| {
        CertifyError::Lacuna(crate::Error::Usage(format!(
            "the volume system does not have the checker's layout: {what}"
        )))
    };
    let mut frames = Vec::with_capacity(set.types.len());
    for ty in &set.types {
        let mut fr = Vec::new();
        for f in &ty.volume.surface.faces {
            let (c, r) = f.canonical();
            let t = *index
                .get(&c)
                .ok_or_else(|| mismatch("a surface face has no type"))?;
            fr.push((t, r));
        }
        frames.push(fr);
    }
    let subvolumes = set
        .types
        .iter()
        .map(|ty| {
            ty.subdivision
                .subvolumes
                .iter()
                .zip(&ty.children)
                .map(|(sub, &w)| SubVolumePlacement {
                    type_index: w,
                    subfaces: sub
                        .subfaces
                        .iter()
                        .map(|&(sf, p)| (sf, (p.face, p.rotation)))
                        .collect(),
                    sides: sub
                        .sides
                        .iter()
                        .map(|&(side, p)| (side, (p.face, p.rotation)))
                        .collect(),
                })
                .collect()
        })
        .collect();
    // The checker numbers the unknowns face operator by face operator (type, sub-face), then
    // sub-volume operator by sub-volume operator (volume type, sub-volume), entries row-major:
    // lacuna's linearisation must have the same order.
    let a = &gv.generated.automaton;
    let by_name: std::collections::HashMap<&str, usize> = a
        .operators
        .iter()
        .enumerate()
        .map(|(i, o)| (o.name.as_str(), i))
        .collect();
    let mut order: Vec<usize> = gv.generated.sub_ops.iter().flatten().copied().collect();
    for (v, ty) in set.types.iter().enumerate() {
        for k in 0..ty.children.len() {
            let op = by_name
                .get(format!("V{v}.T{k}").as_str())
                .ok_or_else(|| mismatch("a sub-volume operator is missing"))?;
            order.push(*op);
        }
    }
    let mut expected = Vec::with_capacity(solved.linearized.unknown_entries.len());
    for &o in &order {
        let (rows, cols) = (
            a.states[a.operators[o].to].dim,
            a.states[a.operators[o].from].dim,
        );
        expected.extend((0..rows).flat_map(|r| (0..cols).map(move |c| (o, r, c))));
    }
    if expected != solved.linearized.unknown_entries {
        return Err(mismatch("the unknowns are in another order"));
    }
    let found =
        crate::constraint::collapses(&gv.faces, &gv.generated, &solved.linearized.offsets, space);
    let system = Step::VolumeSolutionSpace(VolumeSystemStep {
        degree: opts.degree,
        cantor_gap: opts.cantor_gap.to_string(),
        faces,
        frames,
        subvolumes,
        unknowns: solved.linearized.system.unknowns,
        particular: nonzero(&space.particular),
        free: space.free.clone(),
        basis: space.basis.iter().map(direction).collect(),
        rank: space.rank,
        dof: space.dof(),
    });
    let degeneracy = Step::Degeneracy(DegeneracyStep {
        coincide: found.coincide,
        flat_faces: found.flat_faces,
        flat_lacunas: found.flat_lacunas,
    });
    Ok(vec![system, degeneracy])
}

/// Solves the constraint system of a closed set of volumes (THEORY §10, Bézier degree 2, equal
/// Cantor gaps; with the faces an assembly's volumes share) within `limits` and returns its `volume-solution-space` and `degeneracy`
/// steps (none when the system is inconsistent).
pub fn solve_and_certify_volumes(
    set: &crate::topology::volume::VolumeTypeSet,
    assembly: &crate::topology::volume::VolumeAssembly,
    limits: &crate::topology::Limits,
) -> Result<Vec<Step>, CertifyError> {
    let opts = crate::constraint::GenOptions::default();
    let shared = crate::constraint::shared_readings(assembly);
    let solved = crate::constraint::solve_volumes_with_system(set, &shared, opts.clone(), limits)?;
    volume_system_step(set, &solved, &opts)
}

/// Whether the `solid-recurrence` step claims voids and tunnels past level 0: only without
/// delays. A delayed volume caps its holes, and the checker derives no voids then (the caps are
/// 2-cycles of its complex relative to its surface).
pub fn recurrence_has_voids(set: &crate::topology::volume::VolumeTypeSet) -> bool {
    !set.types
        .iter()
        .any(|t| t.volume.delay >= 2 || t.volume.surface.faces.iter().any(|f| f.delay >= 2))
}

/// The row of the `solid-recurrence` step for one level: its cells and χ, and its Betti numbers
/// where lacuna derives them (voids and tunnels only when `voids`).
fn solid_count_row(l: &crate::topology::volume::SolidLevel, voids: bool) -> SolidCountRow {
    let voids = voids.then_some(l.voids).flatten();
    SolidCountRow {
        level: l.level,
        volumes: l.volumes.to_string(),
        faces: l.faces.to_string(),
        edges: l.edges.to_string(),
        corners: l.corners.to_string(),
        euler: l.euler.to_string(),
        components: l.components,
        voids,
        tunnels: voids.and(l.tunnels.as_ref()).map(|t| t.to_string()),
    }
}

/// The rows of the `solid-homology` step for the table `solid` (from level 0): every level
/// while lacuna derives its Betti numbers, it has no cavity (the checker proves Betti numbers
/// where F2 shows none) and at most [`SOLID_CELLS`] cells.
pub fn solid_rows(solid: &[crate::topology::volume::SolidLevel]) -> Vec<SolidRow> {
    use num_traits::ToPrimitive;
    solid
        .iter()
        .map_while(|l| {
            let row = SolidRow {
                level: l.level,
                volumes: l.volumes.to_u64()?,
                faces: l.faces.to_u64()?,
                edges: l.edges.to_u64()?,
                corners: l.corners.to_u64()?,
                euler: l.euler.to_i64()?,
                components: l.components?,
                voids: l.voids.filter(|&v| v == 0)?,
                tunnels: l.tunnels.as_ref()?.to_u64()?,
            };
            let cells = [row.volumes, row.faces, row.edges, row.corners]
                .iter()
                .try_fold(0u64, |a, &x| a.checked_add(x))?;
            (cells <= SOLID_CELLS).then_some(row)
        })
        .collect()
}

/// A volume as certificate data.
fn volume(v: &crate::topology::volume::Volume) -> Result<Volume, CertifyError> {
    let inside = crate::topology::Face {
        boundary: vec![v.inner],
        params: v.params,
        algorithm: v.algorithm.clone(),
        delay: 1,
    };
    let inside = face(&inside)?;
    Ok(Volume {
        faces: v.surface.faces.iter().map(face).collect::<Result<_, _>>()?,
        glue: v.surface.glue.clone(),
        radial: edge(&v.radial),
        inner: edge(&v.inner),
        params: inside.params,
        algorithm: inside.algorithm,
        rule: match v.rule {
            crate::topology::volume::VolumeRule::V1 => VolumeRule::V1,
            crate::topology::volume::VolumeRule::V2 => VolumeRule::V2,
        },
        delay: v.delay,
    })
}

/// A volume of a certificate as lacuna's volume.
pub fn lacuna_volume(v: &Volume) -> crate::topology::volume::Volume {
    let inside = lacuna_face(&Face {
        boundary: vec![v.inner],
        params: v.params,
        algorithm: v.algorithm.clone(),
        delay: 1,
    });
    crate::topology::volume::Volume {
        surface: crate::topology::volume::Surface {
            faces: v.faces.iter().map(lacuna_face).collect(),
            glue: v.glue.clone(),
        },
        radial: lacuna_edge(&v.radial),
        inner: lacuna_edge(&v.inner),
        params: inside.params,
        algorithm: inside.algorithm,
        rule: match v.rule {
            VolumeRule::V1 => crate::topology::volume::VolumeRule::V1,
            VolumeRule::V2 => crate::topology::volume::VolumeRule::V2,
        },
        delay: v.delay,
    }
}
