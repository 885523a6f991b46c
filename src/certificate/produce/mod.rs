//! The certificate producer: writes lacuna's results (closure, solution space, limit ratio) as a
//! [`Certificate`] for the independent checker ([`crate::checker`]).
//!
//! This side may use all of lacuna: the certificate claims what lacuna computed, and the checker
//! re-verifies it without lacuna's code. The only new computations here are the witnesses the
//! checker needs and lacuna does not report: the left Perron eigenvector over Q(ρ) of every class
//! of radius ρ (exact elimination in lacuna's number field), the Collatz–Wielandt vectors of the
//! other classes, and the minimal polynomial of each limit point.

use crate::certificate::format::{
    Adjacency, Algebraic, AutomatonClaim, AutomatonOperator, AutomatonState, Certificate, Claim,
    ClassClaim, ClosureStep, ConflictStep, DegeneracyStep, Edge, Face, FaceHomologyStep, FaceRow,
    FacesClaim, Kind, Origin, Params, Pattern, PointClaim, RadiusWitness, RatioStep, Recipe, Row,
    RuleCompilationStep, SharedFaceClaim, SolidCountRow, SolidHomologyStep, SolidRecurrenceStep,
    SolidRow, SolutionStep, SpokeItem, Step, SubFace, SubstitutionClaim, System, TypeRule, Volume,
    VolumeClosureStep, VolumeCount, VolumeRule, VolumeTypeRule, VolumesClaim, WordEquation,
    WordFactor,
};
use crate::certificate::format::{
    AttractorClaim, ConstraintFailsStep, ConstraintsHoldStep, ContractionStep, FieldCoords,
    NeighbourFails, NeighbourHolds, NeighbourMap, NeighbourMaps, SimilarityPart, SimilarityStep,
    SubVolumePlacement, VolumeSystemStep,
};
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::cmp::Ordering;

/// Why a certificate could not be produced.
#[derive(Debug, thiserror::Error)]
pub enum CertifyError {
    /// Certificates write algorithms as spoke sets; a custom chooser has no data form.
    #[error("face type `{face}` uses the custom algorithm `{algorithm}`, which certificates cannot express")]
    CustomAlgorithm {
        /// The face.
        face: String,
        /// The algorithm's name.
        algorithm: String,
    },
    /// lacuna itself failed (linearising the automaton).
    #[error(transparent)]
    Lacuna(#[from] crate::Error),
    /// The eigen analysis failed.
    #[error(transparent)]
    Ratio(#[from] crate::analysis::RatioError),
    /// A witness could not be built (a disagreement inside lacuna's own results).
    #[error("no witness for the limit ratio: {0}")]
    Witness(String),
}

impl CertifyError {
    /// As lacuna's error: lacuna's own failure as it is, a custom algorithm as a usage error
    /// (`context` names what asked for the certificate), anything else as a failed analysis.
    pub fn into_error(self, context: &str) -> crate::Error {
        match self {
            CertifyError::Lacuna(e) => e,
            e @ CertifyError::CustomAlgorithm { .. } => {
                crate::Error::Usage(format!("{context}: {e}"))
            }
            e => crate::Error::Analysis(e.to_string()),
        }
    }
}

/// The full certificate of a closed type set: the claim (its start faces and the options of
/// THEORY §6), the closure, the solution space (or conflict) of the generated constraint system,
/// and the limit ratio. `input` is a label for people.
pub fn certificate_for(
    input: &str,
    ts: &crate::topology::TypeSet,
    opts: crate::constraint::GenOptions,
) -> Result<Certificate, CertifyError> {
    let closure = closure_step(ts)?;
    let faces = ts
        .start
        .iter()
        .map(|&t| closure.types[t].face.clone())
        .collect();
    let claim = Claim::Faces(FacesClaim {
        faces,
        degree: opts.degree.max(1),
        cantor_gap: opts.cantor_gap.to_string(),
    });
    let mut cert = Certificate::new(input, claim);
    cert.steps.push(Step::Closure(closure));
    let source = format!(
        "the constraints of the automaton generated from the closure (THEORY §6, Bézier degree {}, Cantor gap/piece ratio {})",
        opts.degree, opts.cantor_gap
    );
    let generated = crate::constraint::automaton_of(ts, opts);
    let (_, lin, solution) = crate::constraint::solve_automaton(&generated.automaton)?;
    let recipe = Recipe {
        unknowns: lin
            .unknown_entries
            .iter()
            .map(|&e| generated.automaton.entry_name(e))
            .collect(),
    };
    cert.steps.push(step_of_system(
        system(&source, &lin.system, Some(recipe)),
        &solution,
    ));
    if let crate::constraint::Solution::Consistent(space) = &solution {
        let found = crate::constraint::collapses(ts, &generated, &lin.offsets, space);
        cert.steps.push(Step::Degeneracy(DegeneracyStep {
            coincide: found.coincide,
            flat_faces: found.flat_faces,
            flat_lacunas: found.flat_lacunas,
        }));
    }
    let (matrix, c, start) = substitution_of(ts);
    cert.steps
        .push(Step::LimitRatio(ratio_step(&matrix, &c, &start)?));
    let rows = face_rows(ts)?;
    if !rows.is_empty() {
        cert.steps
            .push(Step::FaceHomology(FaceHomologyStep { rows }));
    }
    Ok(cert)
}

/// The most levels of a face's complex in its `face-homology` step.
pub const FACE_LEVELS: u64 = 6;

/// The rows of the `face-homology` step of a closure with one start face: cells by birth
/// ([`crate::topology::volume::face_cells`]), components as `measure` derives them, and holes
/// b1 = b0 − χ (a complex of cells in the plane encloses no surface: b2 = 0), from level 0 while
/// a level has at most [`SOLID_CELLS`] cells, up to [`FACE_LEVELS`]. None for an assembly of faces
/// (the claim does not carry their gluing).
pub fn face_rows(ts: &crate::topology::TypeSet) -> Result<Vec<FaceRow>, CertifyError> {
    use num_traits::ToPrimitive;
    let [start] = ts.start[..] else {
        return Ok(Vec::new());
    };
    let cells = crate::topology::volume::face_cells(&ts.types[start].face, FACE_LEVELS)?;
    let components: Vec<u64> = match crate::topology::component::components_by_induction(ts, &[]) {
        Ok(c) => vec![c as u64; cells.len()],
        Err(_) => match crate::topology::component::components_by_cells(
            ts,
            &[],
            FACE_LEVELS as u32,
            SOLID_CELLS as usize,
        ) {
            Some(Ok(v)) => v.into_iter().map(|c| c as u64).collect(),
            _ => return Ok(Vec::new()),
        },
    };
    let mut rows = Vec::new();
    for (level, ([f, e, c], b0)) in cells.iter().zip(components).enumerate() {
        let (Some(f), Some(e), Some(c)) = (f.to_u64(), e.to_u64(), c.to_u64()) else {
            break;
        };
        if f.saturating_add(e).saturating_add(c) > SOLID_CELLS {
            break;
        }
        let euler = c as i64 - e as i64 + f as i64;
        let Ok(holes) = u64::try_from(b0 as i64 - euler) else {
            break;
        };
        rows.push(FaceRow {
            level: level as u64,
            faces: f,
            edges: e,
            corners: c,
            euler,
            components: b0,
            holes,
        });
    }
    Ok(rows)
}

/// The most cells (volumes, faces, edges and corners) of a level of the solid that
/// [`certificate_for_volumes`] puts in its `solid-homology` step: the checker builds every
/// listed level cell by cell and reduces its boundary matrices.
pub const SOLID_CELLS: u64 = 250_000;

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
        particular: space
            .particular
            .iter()
            .enumerate()
            .filter(|(_, x)| !x.is_zero())
            .map(|(i, x)| (i, x.to_string()))
            .collect(),
        free: space.free.clone(),
        basis: space.basis.iter().map(|b| terms(b)).collect(),
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

/// The substitution of a closed type set: matrix rows, contributions in halves, start
/// `(type, multiplicity)` sorted by type.
pub fn substitution_of(ts: &crate::topology::TypeSet) -> SubstitutionParts {
    let matrix = ts.matrix();
    let c: Vec<u64> = ts.types.iter().map(|t| t.contribution_halves()).collect();
    let mut start: Vec<(usize, u64)> = Vec::new();
    for &t in &ts.start {
        match start.iter_mut().find(|(s, _)| *s == t) {
            Some(e) => e.1 += 1,
            None => start.push((t, 1)),
        }
    }
    start.sort_unstable();
    (matrix, c, start)
}

/// A substitution: matrix rows `(type, count)`, contributions in halves, start
/// `(type, multiplicity)`.
pub type SubstitutionParts = (Vec<Vec<(usize, u64)>>, Vec<u64>, Vec<(usize, u64)>);

/// The certificate of a substitution given as a matrix: the claim is the matrix, contributions
/// and start, the one step its limit ratio.
pub fn certificate_for_substitution(
    name: &str,
    matrix: &[Vec<(usize, u64)>],
    contribution_halves: &[u64],
    start: &[(usize, u64)],
) -> Result<Certificate, CertifyError> {
    let claim = Claim::Substitution(SubstitutionClaim {
        matrix: matrix.to_vec(),
        contribution_halves: contribution_halves.to_vec(),
        start: start.to_vec(),
    });
    let mut cert = Certificate::new(name, claim);
    cert.steps.push(Step::LimitRatio(ratio_step(
        matrix,
        contribution_halves,
        start,
    )?));
    Ok(cert)
}

/// The certificate of a hand-written automaton: the claim is the automaton itself (states,
/// operators, words), the one step the solution space or conflict of its system — or, when
/// every operator is given, `constraints-hold` or the first constraint that fails.
pub fn certificate_for_automaton(
    name: &str,
    automaton: &crate::constraint::Automaton,
) -> Result<Certificate, CertifyError> {
    let mut cert = Certificate::new(name, Claim::Automaton(automaton_claim(automaton)));
    if automaton.operators.iter().all(|o| o.value.is_some()) {
        let k = crate::algebra::algebraic::NumberField::new(
            crate::algebra::RealAlgebraic::rational(BigRational::zero()),
        );
        let values: Vec<crate::algebra::kmatrix::KMatrix> = automaton
            .operators
            .iter()
            .map(|o| {
                crate::algebra::kmatrix::KMatrix::from_rational(
                    &k,
                    o.value.as_ref().expect("given"),
                )
            })
            .collect();
        cert.steps.push(given_step(automaton, &k, &values)?);
        return Ok(cert);
    }
    let (_, lin, solution) = crate::constraint::solve_automaton(automaton)?;
    let source = format!("the constraints of the automaton `{name}`");
    cert.steps.push(step_of_system(
        system(&source, &lin.system, None),
        &solution,
    ));
    Ok(cert)
}

/// For an automaton whose every operator is given (`values`, in K): `constraints-hold`, or
/// `constraint-fails` naming the first constraint (then barycentric operator) that fails.
fn given_step(
    a: &crate::constraint::Automaton,
    k: &crate::algebra::algebraic::NumberField,
    values: &[crate::algebra::kmatrix::KMatrix],
) -> Result<Step, CertifyError> {
    use crate::analysis::Failing;
    Ok(match crate::analysis::failures(a, k, values)?.first() {
        Some(Failing::Constraint(n)) => Step::ConstraintFails(ConstraintFailsStep {
            constraint: Some(*n),
            barycentric: None,
        }),
        Some(Failing::Barycentric(o)) => Step::ConstraintFails(ConstraintFailsStep {
            constraint: None,
            barycentric: Some(*o),
        }),
        None => Step::ConstraintsHold(ConstraintsHoldStep {
            constraints: a.constraints.len(),
        }),
    })
}

fn matrix_strings(m: &crate::algebra::Matrix) -> Vec<Vec<String>> {
    (0..m.rows)
        .map(|r| (0..m.cols).map(|c| m.get(r, c).to_string()).collect())
        .collect()
}

/// The automaton as certificate data.
pub fn automaton_claim(a: &crate::constraint::Automaton) -> AutomatonClaim {
    let word = |w: &[crate::constraint::Factor]| -> Vec<WordFactor> {
        w.iter()
            .map(|f| match f {
                crate::constraint::Factor::Op(o) => WordFactor::Op(*o),
                crate::constraint::Factor::Literal(m) => WordFactor::Literal(matrix_strings(m)),
            })
            .collect()
    };
    AutomatonClaim {
        states: a
            .states
            .iter()
            .map(|s| AutomatonState {
                name: s.name.clone(),
                dim: s.dim,
            })
            .collect(),
        operators: a
            .operators
            .iter()
            .map(|o| AutomatonOperator {
                name: o.name.clone(),
                to: o.to,
                from: o.from,
                value: o.value.as_ref().map(matrix_strings),
                field_value: None,
            })
            .collect(),
        constraints: a
            .constraints
            .iter()
            .map(|c| WordEquation {
                lhs: word(&c.lhs),
                rhs: word(&c.rhs),
            })
            .collect(),
        barycentric: a.barycentric.clone(),
        field: None,
        attractor: None,
        rule: None,
    }
}

fn coords(x: &crate::algebra::algebraic::FieldElement) -> FieldCoords {
    strings(x.coords())
}

fn kmatrix_coords(m: &crate::algebra::kmatrix::KMatrix) -> Vec<Vec<FieldCoords>> {
    (0..m.rows)
        .map(|r| (0..m.cols).map(|c| coords(m.get(r, c))).collect())
        .collect()
}

/// An automaton with its modelling lines as certificate data: the automaton of
/// [`automaton_claim`], the field K and the operators given in it, and the attractor (start
/// state, its control points — the default zigzag when the file gives none — and the
/// subdivision operators).
pub fn model_claim(m: &crate::input::AutomatonModel) -> AutomatonClaim {
    let mut claim = automaton_claim(&m.automaton);
    claim.rule = m.rule.clone();
    if m.field.degree() > 1 {
        claim.field = Some(algebraic(m.field.generator()));
    }
    for &o in &m.field_ops {
        if let Some(v) = &m.kvalues[o] {
            claim.operators[o].field_value = Some(kmatrix_coords(v));
        }
    }
    let points = m.points.clone().unwrap_or_else(|| {
        crate::analysis::similarity::default_points(
            m.automaton.states[m.start].dim,
            m.space,
            &m.field,
        )
    });
    claim.attractor = Some(AttractorClaim {
        start: m.start,
        points: points
            .iter()
            .map(|p| p.iter().map(coords).collect())
            .collect(),
        subdivision: m
            .automaton
            .operators
            .iter()
            .enumerate()
            .filter(|(_, o)| o.kind == crate::constraint::OpKind::Sub)
            .map(|(i, _)| i)
            .collect(),
    });
    claim
}

/// Everything `lacuna verify` proves about an automaton, as a certificate: the operators
/// resolved (free parameters 0), the contraction of that instance when it is proven (a cycle
/// that does not contract leaves the step out), and its similarity dimension (30 digits) when it
/// applies. `max_unknowns` and `max_products` are the limits of `resolve` and of the
/// contraction search.
pub fn certify_model(
    name: &str,
    m: &crate::input::AutomatonModel,
    max_unknowns: usize,
    max_products: usize,
) -> Result<Certificate, CertifyError> {
    let a = crate::analysis::analyse_attractor(m, max_unknowns, max_products, 30)?;
    certificate_for_model(name, m, &a)
}

/// u* as an element of K when it is irrational and the dimension is an even integer 2j
/// (`u* = σ^j`), so that the checker can compare powers in K.
fn u_in_field(
    m: &crate::input::AutomatonModel,
    p: &crate::analysis::similarity::PartWitness,
) -> Option<FieldCoords> {
    let r = p.rational.as_ref()?;
    if p.u.as_rational().is_some() || p.sigma.as_rational().is_some() || !r.is_integer() {
        return None;
    }
    let two = num_bigint::BigInt::from(2);
    let s = r.to_integer();
    if (&s % &two) != num_bigint::BigInt::from(0) {
        return None;
    }
    let j: usize = (&s / &two).try_into().ok()?;
    let mut y = m.field.rational(BigRational::one());
    for _ in 0..j {
        y = m.field.mul(&y, &p.sigma);
    }
    Some(coords(&y))
}

/// The neighbour-map witness of a part (its states in order) as certificate data.
fn neighbour_maps(
    states: &[usize],
    w: &crate::analysis::open_set::NeighbourWitness,
) -> NeighbourMaps {
    use crate::analysis::open_set::{Coordinates, NeighbourWitness};
    match w {
        NeighbourWitness::Holds {
            coordinates,
            centres,
            radius,
            margin,
            maps,
            scales,
        } => NeighbourMaps::Holds(NeighbourHolds {
            coordinates: match coordinates {
                Coordinates::Charts => "charts",
                Coordinates::Drawing => "drawing",
            }
            .to_string(),
            centres: centres
                .iter()
                .map(|c| c.iter().map(coords).collect())
                .collect(),
            radius: radius.to_string(),
            margin: margin.to_string(),
            maps: maps
                .iter()
                .map(|m| NeighbourMap {
                    q: states[m.q],
                    r: states[m.r],
                    a: m.a.iter().map(coords).collect(),
                    b: m.b.iter().map(coords).collect(),
                })
                .collect(),
            scales: scales
                .as_ref()
                .map(|c| c.iter().map(ToString::to_string).collect()),
        }),
        NeighbourWitness::Fails { u, v } => NeighbourMaps::Fails(NeighbourFails {
            u: u.clone(),
            v: v.clone(),
        }),
    }
}

/// The certificate of an automaton file (or a compiled rule) with what `verify` proved about
/// it: its constraints (`constraints-hold` when every operator is given, else the solution
/// space over Q), then the contraction of the resolved instance and its similarity dimension
/// when `attractor` (from [`crate::analysis::analyse_attractor`]) decided them.
pub fn certificate_for_model(
    name: &str,
    m: &crate::input::AutomatonModel,
    attractor: &crate::analysis::Attractor,
) -> Result<Certificate, CertifyError> {
    let ops = &attractor.resolved.ops;
    let (contraction, similarity) = (
        attractor.contraction.as_ref(),
        attractor.similarity.as_ref(),
    );
    let claim = model_claim(m);
    let all_given = claim
        .operators
        .iter()
        .all(|o| o.value.is_some() || o.field_value.is_some());
    let instance: Vec<(usize, Vec<Vec<FieldCoords>>)> = claim
        .operators
        .iter()
        .enumerate()
        .filter(|(_, o)| o.value.is_none() && o.field_value.is_none())
        .map(|(i, _)| (i, kmatrix_coords(&ops[i])))
        .collect();
    let mut cert = Certificate::new(name, Claim::Automaton(claim.clone()));
    if all_given {
        // Every operator given: the resolved values are the given ones.
        cert.steps.push(given_step(&m.automaton, &m.field, ops)?);
    } else {
        let (_, lin, solution) = crate::constraint::solve_automaton(&m.automaton)?;
        let source = format!("the constraints of the automaton `{name}`");
        cert.steps.push(step_of_system(
            system(&source, &lin.system, None),
            &solution,
        ));
    }
    if let Some(c) = contraction {
        cert.steps.push(Step::Contraction(ContractionStep {
            instance: instance.clone(),
            norm: c.norm.clone(),
            walks: c.walks.clone(),
        }));
    }
    if let Some(sd) = similarity {
        if !sd.witness.is_empty() {
            let digits = sd.decimal.split('.').nth(1).map_or(0, str::len);
            cert.steps.push(Step::SimilarityDimension(SimilarityStep {
                instance,
                parts: sd
                    .witness
                    .iter()
                    .map(|p| SimilarityPart {
                        states: p.states.clone(),
                        sigma: coords(&p.sigma),
                        exponents: p.exponents.clone(),
                        u: algebraic(&p.u),
                        rational: p.rational.as_ref().map(|r| r.to_string()),
                        u_field: u_in_field(m, p),
                        open_set: p.open_set.as_ref().map(|sets| {
                            sets.iter()
                                .map(|poly| {
                                    poly.iter()
                                        .map(|v| v.iter().map(coords).collect())
                                        .collect()
                                })
                                .collect()
                        }),
                        neighbour_maps: p
                            .neighbour_maps
                            .as_ref()
                            .map(|w| neighbour_maps(&p.states, w)),
                    })
                    .collect(),
                digits,
                decimal: sd.decimal.clone(),
            }));
        }
    }
    // A compiled rule, with or without the age and random extensions: the checker compiles its
    // text again.
    if m.rule.is_some() {
        cert.steps
            .push(Step::RuleCompilation(RuleCompilationStep {}));
    }
    Ok(cert)
}

/// The certificate of an explicit linear system and lacuna's solution of it: the claim is the
/// system.
pub fn certificate_for_system(
    name: &str,
    source: &str,
    sys: &crate::constraint::LinearSystem,
    solution: &crate::constraint::Solution,
) -> Certificate {
    let mut cert = Certificate::new(name, Claim::System(system(source, sys, None)));
    cert.steps.push(solution_step(source, sys, solution));
    cert
}

fn edge(e: &crate::topology::EdgeType) -> Edge {
    let kind = match e.kind {
        crate::topology::EdgeKind::B => Kind::B,
        crate::topology::EdgeKind::C => Kind::C,
    };
    Edge {
        kind,
        n: e.n,
        delay: e.delay,
    }
}

fn pattern(p: &crate::topology::EdgePattern) -> Pattern {
    match p {
        crate::topology::EdgePattern::Any => Pattern::Any,
        crate::topology::EdgePattern::Kind(k) => Pattern::Kind(match k {
            crate::topology::EdgeKind::B => Kind::B,
            crate::topology::EdgeKind::C => Kind::C,
        }),
        crate::topology::EdgePattern::Exact(e) => Pattern::Exact(edge(e)),
    }
}

fn face(f: &crate::topology::Face) -> Result<Face, CertifyError> {
    let algorithm = match &f.algorithm {
        crate::topology::Algorithm::Spokes(items) => items
            .iter()
            .map(|i| match i {
                crate::topology::SpokeItem::Joint => SpokeItem::Joint,
                crate::topology::SpokeItem::Gap => SpokeItem::Gap,
                crate::topology::SpokeItem::Corner => SpokeItem::Corner,
                crate::topology::SpokeItem::DelayedCorner => SpokeItem::DelayedCorner,
                crate::topology::SpokeItem::DelayedCornerNotB => SpokeItem::DelayedCornerNotB,
                crate::topology::SpokeItem::CornerBetween(p, q) => {
                    SpokeItem::CornerBetween(pattern(p), pattern(q))
                }
            })
            .collect(),
        crate::topology::Algorithm::Custom(c) => {
            return Err(CertifyError::CustomAlgorithm {
                face: f.to_string(),
                algorithm: c.name(),
            })
        }
    };
    Ok(Face {
        boundary: f.boundary.iter().map(edge).collect(),
        params: Params {
            ea: edge(&f.params.ea),
            el: edge(&f.params.el),
            ec: edge(&f.params.ec),
        },
        algorithm,
        delay: f.delay,
    })
}

fn origin(o: &crate::topology::Origin) -> Origin {
    match *o {
        crate::topology::Origin::Piece { edge, piece } => Origin::Piece { edge, piece },
        crate::topology::Origin::Spoke { spoke, inward } => Origin::Spoke { spoke, inward },
        crate::topology::Origin::Lacuna { side } => Origin::Lacuna { side },
        crate::topology::Origin::GapSide { edge, gap, after } => {
            Origin::GapSide { edge, gap, after }
        }
    }
}

/// The closure step of a closed type set.
pub fn closure_step(ts: &crate::topology::TypeSet) -> Result<ClosureStep, CertifyError> {
    let types = ts
        .types
        .iter()
        .map(|t| {
            Ok(TypeRule {
                face: face(&t.face)?,
                subfaces: t
                    .subdivision
                    .subfaces
                    .iter()
                    .zip(&t.children)
                    .map(|(s, &c)| SubFace {
                        type_index: c,
                        origins: s.origins.iter().map(origin).collect(),
                    })
                    .collect(),
                adjacencies: t
                    .subdivision
                    .adjacencies
                    .iter()
                    .map(|a| Adjacency {
                        first: a.first,
                        second: a.second,
                    })
                    .collect(),
                contribution_halves: t.contribution_halves(),
            })
        })
        .collect::<Result<_, CertifyError>>()?;
    Ok(ClosureStep { types })
}

fn terms(v: &[(usize, BigRational)]) -> Vec<(usize, String)> {
    v.iter().map(|(i, c)| (*i, c.to_string())).collect()
}

fn system(source: &str, sys: &crate::constraint::LinearSystem, recipe: Option<Recipe>) -> System {
    System {
        recipe,
        source: source.to_string(),
        unknowns: sys.unknowns,
        rows: sys
            .rows
            .iter()
            .map(|r| Row {
                terms: terms(&r.terms),
                rhs: r.rhs.to_string(),
            })
            .collect(),
    }
}

/// The step certifying lacuna's solution of `sys` (a system as given, without recipe): its
/// solution space, or its conflict.
pub fn solution_step(
    source: &str,
    sys: &crate::constraint::LinearSystem,
    solution: &crate::constraint::Solution,
) -> Step {
    step_of_system(system(source, sys, None), solution)
}

fn step_of_system(system: System, solution: &crate::constraint::Solution) -> Step {
    match solution {
        crate::constraint::Solution::Consistent(s) => Step::SolutionSpace(SolutionStep {
            system,
            particular: s
                .particular
                .iter()
                .enumerate()
                .filter(|(_, x)| !x.is_zero())
                .map(|(i, x)| (i, x.to_string()))
                .collect(),
            free: s.free.clone(),
            basis: s.basis.iter().map(|b| terms(b)).collect(),
            pivots: s.pivots.clone(),
            rank: s.rank,
            dof: s.dof(),
        }),
        crate::constraint::Solution::Inconsistent(c) => Step::Inconsistent(ConflictStep {
            system,
            multipliers: terms(&c.multipliers),
            constant: c.constant.to_string(),
        }),
    }
}

/// The limit-ratio step of a substitution (`matrix[t]` lists `(s, k)`), contributions in halves
/// and start `(type, multiplicity)`, with lacuna's verdict and the checker's witnesses.
pub fn ratio_step(
    matrix: &[Vec<(usize, u64)>],
    contribution_halves: &[u64],
    start: &[(usize, u64)],
) -> Result<RatioStep, CertifyError> {
    ratio_step_in(matrix, contribution_halves, start, 2)
}

/// [`ratio_step`] with contributions in `1/unit` lacunas (2 for faces, 4 for volumes).
fn ratio_step_in(
    matrix: &[Vec<(usize, u64)>],
    contributions: &[u64],
    start: &[(usize, u64)],
    unit: u32,
) -> Result<RatioStep, CertifyError> {
    let c: Vec<BigRational> = contributions
        .iter()
        .map(|&h| BigRational::new(h.into(), unit.into()))
        .collect();
    let report = crate::analysis::analyse(matrix, &c, start)?;
    let field = &report.field;
    let rho = separated_rho(&report)?;
    let lo = rho.interval().0.clone();
    // Classes ordered by smallest member.
    let mut order: Vec<usize> = (0..report.classes.len()).collect();
    order.sort_by_key(|&i| report.classes[i].members[0]);
    let classes = order
        .iter()
        .map(|&i| {
            let class = &report.classes[i];
            let radius = match (class.period, class.dominant) {
                (None, _) => RadiusWitness::Transient,
                (Some(_), true) => {
                    RadiusWitness::Perron(perron_vector(field, matrix, &class.members)?)
                }
                (Some(_), false) => {
                    RadiusWitness::Below(collatz_wielandt(&lo, matrix, &class.members)?)
                }
            };
            Ok(ClassClaim {
                members: class.members.clone(),
                period: class.period,
                radius,
            })
        })
        .collect::<Result<_, CertifyError>>()?;
    let points: Vec<PointClaim> = report
        .limit_points
        .iter()
        .map(|p| {
            Ok(PointClaim {
                value: match p.value.coords() {
                    [] => vec!["0".to_string()],
                    c => strings(c),
                },
                real: algebraic(&real_of(field, &p.value)?),
                decimal: p.decimal.clone(),
            })
        })
        .collect::<Result<_, CertifyError>>()?;
    let digits = points
        .first()
        .map_or(0, |p| p.decimal.split_once('.').map_or(0, |(_, f)| f.len()));
    Ok(RatioStep {
        classes,
        rho: algebraic(&rho),
        period: report.period,
        exists: report.exists,
        digits,
        points,
    })
}

fn strings(v: &[BigRational]) -> Vec<String> {
    v.iter().map(|q| q.to_string()).collect()
}

fn algebraic(x: &crate::algebra::RealAlgebraic) -> Algebraic {
    let (lo, hi) = x.interval();
    Algebraic {
        poly: x
            .min_poly()
            .primitive_int()
            .iter()
            .map(|c| c.to_string())
            .collect(),
        lo: lo.to_string(),
        hi: hi.to_string(),
    }
}

/// ρ with an isolating interval whose lower end lies above 1 (when ρ is irrational) and above
/// every smaller class radius, as the Collatz–Wielandt bounds need.
fn separated_rho(
    report: &crate::analysis::RatioReport,
) -> Result<crate::algebra::RealAlgebraic, CertifyError> {
    let mut rho = report.field.generator().clone();
    let others: Vec<&crate::algebra::RealAlgebraic> = report
        .classes
        .iter()
        .filter(|c| !c.dominant)
        .map(|c| &c.radius)
        .collect();
    let one = crate::algebra::RealAlgebraic::rational(BigRational::one());
    let lo_above = |r: &crate::algebra::RealAlgebraic, x: &crate::algebra::RealAlgebraic| {
        r.degree() == 1
            || crate::algebra::RealAlgebraic::rational(r.interval().0.clone()).cmp_exact(x)
                == Ordering::Greater
    };
    let mut rounds = 0;
    while !(lo_above(&rho, &one) && others.iter().all(|x| lo_above(&rho, x))) {
        rounds += 1;
        if rounds > 10_000 {
            return Err(CertifyError::Witness(
                "ρ does not separate from a class".into(),
            ));
        }
        rho.refine();
    }
    Ok(rho)
}

/// The left eigenvector `y` of the block of `members` for ρ (`y·B = ρ·y`), 1 at the first
/// member; positive by Perron–Frobenius.
fn perron_vector(
    field: &crate::algebra::NumberField,
    matrix: &[Vec<(usize, u64)>],
    members: &[usize],
) -> Result<Vec<Vec<String>>, CertifyError> {
    let r = field.generator_element();
    let zero = field.rational(BigRational::zero());
    let size = members.len();
    // Row i of (B − ρI)ᵀ: Σ_j y_j (B[j][i] − ρ δ_ij) = 0.
    let mut rows = vec![vec![zero; size]; size];
    for (j, &t) in members.iter().enumerate() {
        for &(s, k) in &matrix[t] {
            if let Ok(i) = members.binary_search(&s) {
                rows[i][j] = field.add(
                    &rows[i][j],
                    &field.rational(BigRational::from_integer(k.into())),
                );
            }
        }
        rows[j][j] = field.sub(&rows[j][j], &r);
    }
    let y = kernel_vector(field, rows, size)?;
    let scale = field
        .inv(&y[0])
        .ok_or_else(|| CertifyError::Witness("the Perron vector vanishes".into()))?;
    Ok(y.iter()
        .map(|v| strings(field.mul(v, &scale).coords()))
        .collect())
}

/// `x = (lo·I − B)⁻¹·1 > 0` on the block of `members`, so `B·x = lo·x − 1 < lo·x`.
fn collatz_wielandt(
    lo: &BigRational,
    matrix: &[Vec<(usize, u64)>],
    members: &[usize],
) -> Result<Vec<String>, CertifyError> {
    let q = crate::algebra::NumberField::new(crate::algebra::RealAlgebraic::rational(
        BigRational::zero(),
    ));
    let size = members.len();
    let mut rows = vec![vec![q.rational(BigRational::zero()); size + 1]; size];
    for (i, &t) in members.iter().enumerate() {
        rows[i][i] = q.rational(lo.clone());
        for &(s, m) in &matrix[t] {
            if let Ok(j) = members.binary_search(&s) {
                let e = field_sub_int(&q, &rows[i][j], m);
                rows[i][j] = e;
            }
        }
        rows[i][size] = q.rational(BigRational::one());
    }
    let (red, pivots) = rref(&q, rows, size);
    if pivots.len() != size {
        return Err(CertifyError::Witness("lo·I − B is singular".into()));
    }
    Ok(red
        .iter()
        .map(|row| {
            row[size]
                .as_rational()
                .expect("a rational field")
                .to_string()
        })
        .collect())
}

/// `v` as a real algebraic number: its minimal polynomial over Q (the first linear dependence
/// among `1, v, v², …` in Q(ρ), a field) and the isolating interval of its root equal to `v`.
fn real_of(
    field: &crate::algebra::NumberField,
    v: &crate::algebra::FieldElement,
) -> Result<crate::algebra::RealAlgebraic, CertifyError> {
    if let Some(q) = v.as_rational() {
        return Ok(crate::algebra::RealAlgebraic::rational(q));
    }
    let q = crate::algebra::NumberField::new(crate::algebra::RealAlgebraic::rational(
        BigRational::zero(),
    ));
    let deg = field.degree();
    let coord = |x: &crate::algebra::FieldElement, i: usize| q.rational(x.poly().coeff(i));
    let mut powers = vec![field.rational(BigRational::one())];
    for k in 1..=deg {
        powers.push(field.mul(&powers[k - 1], v));
        // Solve Σ_(i<k) a_i·v^i = v^k on the coordinates.
        let rows = (0..deg)
            .map(|i| (0..=k).map(|j| coord(&powers[j], i)).collect())
            .collect();
        let (red, pivots) = rref(&q, rows, k + 1);
        if pivots.contains(&k) {
            continue; // v^k is independent of the lower powers
        }
        let mut coeffs: Vec<BigRational> = vec![BigRational::zero(); k + 1];
        for (row, &p) in red.iter().zip(&pivots) {
            coeffs[p] = -row[k].as_rational().expect("rational");
        }
        coeffs[k] = BigRational::one();
        let f = crate::algebra::Poly::new(coeffs);
        let sign = |x: &BigRational| field.sign(&field.sub(v, &field.rational(x.clone())));
        return crate::algebra::RealAlgebraic::real_roots(&f)
            .into_iter()
            .find(|r| {
                let (lo, hi) = r.interval();
                sign(lo) == Ordering::Greater && sign(hi) == Ordering::Less
            })
            .ok_or_else(|| CertifyError::Witness("no root of the minimal polynomial is R".into()));
    }
    Err(CertifyError::Witness("no minimal polynomial found".into()))
}

fn field_sub_int(
    f: &crate::algebra::NumberField,
    a: &crate::algebra::FieldElement,
    m: u64,
) -> crate::algebra::FieldElement {
    f.sub(a, &f.rational(BigRational::from_integer(m.into())))
}

/// Reduced row echelon form over the field on the first `cols` columns; returns the pivot
/// columns.
fn rref(
    f: &crate::algebra::NumberField,
    mut a: Vec<Vec<crate::algebra::FieldElement>>,
    cols: usize,
) -> (Vec<Vec<crate::algebra::FieldElement>>, Vec<usize>) {
    let mut pivots = Vec::new();
    for col in 0..cols {
        let r = pivots.len();
        let Some(p) = (r..a.len()).find(|&i| !a[i][col].is_zero()) else {
            continue;
        };
        a.swap(r, p);
        let inv = f.inv(&a[r][col]).expect("nonzero pivot");
        a[r] = a[r].iter().map(|x| f.mul(x, &inv)).collect();
        for i in 0..a.len() {
            if i != r && !a[i][col].is_zero() {
                let k = a[i][col].clone();
                let pivot_row = a[r].clone();
                for (x, y) in a[i].iter_mut().zip(&pivot_row) {
                    *x = f.sub(x, &f.mul(&k, y));
                }
            }
        }
        pivots.push(col);
    }
    (a, pivots)
}

/// The one-dimensional kernel of a square matrix, as a vector.
fn kernel_vector(
    f: &crate::algebra::NumberField,
    rows: Vec<Vec<crate::algebra::FieldElement>>,
    n: usize,
) -> Result<Vec<crate::algebra::FieldElement>, CertifyError> {
    let (red, pivots) = rref(f, rows, n);
    let free: Vec<usize> = (0..n).filter(|c| !pivots.contains(c)).collect();
    if free.len() != 1 {
        return Err(CertifyError::Witness(format!(
            "the eigenspace of ρ has dimension {}, expected 1",
            free.len()
        )));
    }
    let mut y = vec![f.rational(BigRational::zero()); n];
    y[free[0]] = f.rational(BigRational::one());
    for (i, &p) in pivots.iter().enumerate() {
        y[p] = f.sub(&f.rational(BigRational::zero()), &red[i][free[0]]);
    }
    Ok(y)
}

fn lacuna_edge(e: &Edge) -> crate::topology::EdgeType {
    let kind = match e.kind {
        Kind::B => crate::topology::EdgeKind::B,
        Kind::C => crate::topology::EdgeKind::C,
    };
    crate::topology::EdgeType::new(kind, e.n).delayed(e.delay)
}

fn lacuna_pattern(p: &Pattern) -> crate::topology::EdgePattern {
    match p {
        Pattern::Any => crate::topology::EdgePattern::Any,
        Pattern::Kind(Kind::B) => crate::topology::EdgePattern::Kind(crate::topology::EdgeKind::B),
        Pattern::Kind(Kind::C) => crate::topology::EdgePattern::Kind(crate::topology::EdgeKind::C),
        Pattern::Exact(e) => crate::topology::EdgePattern::Exact(lacuna_edge(e)),
    }
}

/// A certificate face as lacuna's face.
pub fn lacuna_face(f: &Face) -> crate::topology::Face {
    let items = f
        .algorithm
        .iter()
        .map(|i| match i {
            SpokeItem::Joint => crate::topology::SpokeItem::Joint,
            SpokeItem::Gap => crate::topology::SpokeItem::Gap,
            SpokeItem::Corner => crate::topology::SpokeItem::Corner,
            SpokeItem::DelayedCorner => crate::topology::SpokeItem::DelayedCorner,
            SpokeItem::DelayedCornerNotB => crate::topology::SpokeItem::DelayedCornerNotB,
            SpokeItem::CornerBetween(p, q) => {
                crate::topology::SpokeItem::CornerBetween(lacuna_pattern(p), lacuna_pattern(q))
            }
        })
        .collect();
    crate::topology::Face {
        boundary: f.boundary.iter().map(lacuna_edge).collect(),
        params: crate::topology::Params {
            ea: lacuna_edge(&f.params.ea),
            el: lacuna_edge(&f.params.el),
            ec: lacuna_edge(&f.params.ec),
        },
        algorithm: crate::topology::Algorithm::Spokes(items),
        delay: f.delay,
    }
}

fn rational(s: &str) -> Result<BigRational, CertifyError> {
    s.parse()
        .map_err(|_| CertifyError::Witness(format!("`{s}` is not a rational")))
}

fn lacuna_matrix(m: &[Vec<String>]) -> Result<crate::algebra::Matrix, CertifyError> {
    let rows = m
        .iter()
        .map(|r| r.iter().map(|x| rational(x)).collect())
        .collect::<Result<_, _>>()?;
    Ok(crate::algebra::Matrix::from_rows(rows))
}

/// A claimed automaton as lacuna's automaton (operator kinds are `Other`: only the explicit
/// barycentric list matters to the system).
pub fn lacuna_automaton(a: &AutomatonClaim) -> Result<crate::constraint::Automaton, CertifyError> {
    let mut out = crate::constraint::Automaton::default();
    for s in &a.states {
        out.add_state(s.name.clone(), s.dim);
    }
    for o in &a.operators {
        let value = o.value.as_deref().map(lacuna_matrix).transpose()?;
        out.add_op(
            o.name.clone(),
            crate::constraint::OpKind::Other,
            o.to,
            o.from,
            value,
        );
    }
    let word = |w: &[WordFactor]| -> Result<Vec<crate::constraint::Factor>, CertifyError> {
        w.iter()
            .map(|f| match f {
                WordFactor::Op(o) => Ok(crate::constraint::Factor::Op(*o)),
                WordFactor::Literal(m) => Ok(crate::constraint::Factor::Literal(lacuna_matrix(m)?)),
            })
            .collect()
    };
    for (k, c) in a.constraints.iter().enumerate() {
        out.constraints.push(crate::constraint::Constraint {
            label: format!("constraint {k}"),
            span: None,
            kind: crate::constraint::ConstraintKind::Word,
            lhs: word(&c.lhs)?,
            rhs: word(&c.rhs)?,
        });
    }
    out.barycentric = a.barycentric.clone();
    Ok(out)
}

/// A claimed automaton with an attractor as lacuna's model: the operators (subdivision ones
/// of kind `Sub`), the field, the values given in it, the start state and its points; every
/// state drawn as nothing (certificates do not carry primitives).
pub fn model_of_claim(a: &AutomatonClaim) -> Result<crate::input::AutomatonModel, CertifyError> {
    use crate::algebra::algebraic::{NumberField, RealAlgebraic};
    let bad = |m: String| CertifyError::Lacuna(crate::Error::Usage(m));
    let at = a
        .attractor
        .as_ref()
        .ok_or_else(|| bad("the claim has no attractor".into()))?;
    let mut automaton = lacuna_automaton(a)?;
    for &o in &at.subdivision {
        automaton
            .operators
            .get_mut(o)
            .ok_or_else(|| bad(format!("subdivision operator {o} out of range")))?
            .kind = crate::constraint::OpKind::Sub;
    }
    let field = match &a.field {
        None => NumberField::new(RealAlgebraic::rational(BigRational::zero())),
        Some(k) => {
            let poly = crate::algebra::poly::Poly::new(
                k.poly
                    .iter()
                    .map(|c| rational(c))
                    .collect::<Result<_, _>>()?,
            );
            let (lo, hi) = (rational(&k.lo)?, rational(&k.hi)?);
            let gen = match lo == hi {
                true => RealAlgebraic::rational(lo),
                false => RealAlgebraic::root_in(&poly, &lo, &hi)
                    .ok_or_else(|| bad("the field's interval isolates no root".into()))?,
            };
            NumberField::new(gen)
        }
    };
    let element =
        |c: &FieldCoords| -> Result<crate::algebra::algebraic::FieldElement, CertifyError> {
            let p = crate::algebra::poly::Poly::new(
                c.iter().map(|x| rational(x)).collect::<Result<_, _>>()?,
            );
            Ok(field.element(&p))
        };
    let mut kvalues = Vec::with_capacity(a.operators.len());
    let mut field_ops = Vec::new();
    for (i, o) in a.operators.iter().enumerate() {
        kvalues.push(match (&o.value, &o.field_value) {
            (Some(v), _) => Some(crate::algebra::kmatrix::KMatrix::from_rational(
                &field,
                &lacuna_matrix(v)?,
            )),
            (None, Some(v)) => {
                field_ops.push(i);
                let rows = v.len();
                let cols = v.first().map_or(0, Vec::len);
                let data = v
                    .iter()
                    .flatten()
                    .map(&element)
                    .collect::<Result<Vec<_>, _>>()?;
                if data.len() != rows * cols {
                    return Err(bad(format!("operator {}: a ragged matrix", o.name)));
                }
                Some(crate::algebra::kmatrix::KMatrix { rows, cols, data })
            }
            (None, None) => None,
        });
    }
    let points = at
        .points
        .iter()
        .map(|p| p.iter().map(&element).collect::<Result<Vec<_>, _>>())
        .collect::<Result<Vec<_>, _>>()?;
    let space = points.first().map_or(2, Vec::len);
    let states = automaton.states.len();
    Ok(crate::input::AutomatonModel {
        automaton,
        field,
        field_decl: None,
        kvalues,
        field_ops,
        space,
        start: at.start,
        points: Some(points),
        primitives: vec![crate::input::automaton_model::Primitive::Nothing; states],
        params: Vec::new(),
        rule: a.rule.clone(),
    })
}

/// The certificate lacuna itself produces for a claim: the independent recomputation of
/// everything a checked certificate states (used by the forgery fuzz target and tests: a
/// certificate the checker accepts must state what this one states).
pub fn recertify(
    label: &str,
    claim: &Claim,
    limits: &crate::topology::Limits,
) -> Result<Certificate, CertifyError> {
    match claim {
        Claim::Faces(f) => {
            let faces: Vec<crate::topology::Face> = f.faces.iter().map(lacuna_face).collect();
            let ts = crate::topology::close_or_error(&faces, limits)?;
            let opts = crate::constraint::GenOptions {
                degree: f.degree,
                cantor_gap: rational(&f.cantor_gap)?,
            };
            certificate_for(label, &ts, opts)
        }
        Claim::Automaton(a) if a.attractor.is_some() => {
            let m = model_of_claim(a)?;
            certify_model(label, &m, limits.max_unknowns, limits.max_products)
        }
        Claim::Automaton(a) => certificate_for_automaton(label, &lacuna_automaton(a)?),
        Claim::Substitution(s) => {
            certificate_for_substitution(label, &s.matrix, &s.contribution_halves, &s.start)
        }
        Claim::System(s) => {
            let sys = crate::constraint::LinearSystem {
                unknowns: s.unknowns,
                rows: s
                    .rows
                    .iter()
                    .map(|r| {
                        Ok(crate::constraint::Equation {
                            terms: r
                                .terms
                                .iter()
                                .map(|(v, c)| Ok((*v, rational(c)?)))
                                .collect::<Result<_, CertifyError>>()?,
                            rhs: rational(&r.rhs)?,
                        })
                    })
                    .collect::<Result<_, CertifyError>>()?,
            };
            let solution = crate::constraint::solve(&sys);
            Ok(certificate_for_system(label, &s.source, &sys, &solution))
        }
        Claim::Volumes(c) => {
            let volumes: Vec<_> = c.volumes.iter().map(lacuna_volume).collect();
            for v in &volumes {
                v.surface.check().map_err(crate::Error::Usage)?;
            }
            let assembly = crate::topology::volume::VolumeAssembly {
                volumes: volumes.clone(),
                shared: c
                    .shared
                    .iter()
                    .map(|s| crate::topology::volume::SharedFace {
                        a: (s.a[0], s.a[1], s.a[2]),
                        b: (s.b[0], s.b[1], s.b[2]),
                    })
                    .collect(),
            };
            match crate::topology::volume::VolumeClosure::of(&volumes, limits)? {
                crate::topology::volume::VolumeClosure::Closed(set) => {
                    certificate_for_volumes(label, &set, c.levels, &assembly)
                }
                crate::topology::volume::VolumeClosure::Runaway(r) => {
                    Err(CertifyError::Lacuna(crate::Error::Usage(format!(
                        "the volumes' closure did not close: {}",
                        r.reason
                    ))))
                }
            }
        }
    }
}
