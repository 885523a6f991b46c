//! Certificates of closed type sets: the closure step, the faces and their origins, the rows of
//! the `face-homology` step, the substitution and its certificate, and lacuna's faces read back
//! from a claim.

use super::systems::{ratio_step, step_of_system, system};
use super::{CertifyError, SOLID_CELLS};
use crate::certificate::format::{
    Adjacency, Certificate, Claim, ClosureStep, DegeneracyStep, Edge, Face, FaceHomologyStep,
    FaceRow, FacesClaim, GluedSides, Kind, Origin, Params, Pattern, Recipe, SpokeItem, Step,
    SubFace, SubstitutionClaim, TypeRule,
};

/// The full certificate of a closed type set: the claim (its start faces and the options of
/// THEORY §6), the closure, the solution space (or conflict) of the generated constraint system,
/// and the limit ratio. `input` is a label for people. For an assembly of several faces, use
/// [`certificate_for_assembly`] with its gluing: without it the start faces are taken apart.
pub fn certificate_for(
    input: &str,
    ts: &crate::topology::TypeSet,
    opts: crate::constraint::GenOptions,
) -> Result<Certificate, CertifyError> {
    certificate_for_assembly(input, ts, &[], opts)
}

/// [`certificate_for`] for start faces glued along `glue` (an assembly's
/// [`crate::input::Assembly::canonical_glue`]): the claim carries the gluing, and the
/// `face-homology` step is about the glued complex.
pub fn certificate_for_assembly(
    input: &str,
    ts: &crate::topology::TypeSet,
    glue: &[crate::topology::component::Glue],
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
        glue: glue
            .iter()
            .map(|&[(fa, a), (fb, b)]| GluedSides {
                a: [fa, a],
                b: [fb, b],
            })
            .collect(),
    });
    let mut cert = Certificate::new(input, claim);
    cert.steps.push(Step::Closure(closure));
    let source = format!(
        "the constraints of the automaton generated from the closure (THEORY §6, Bézier degree {}, Cantor gap/piece ratio {})",
        opts.degree, opts.cantor_gap
    );
    let generated = crate::constraint::automaton_of(ts, opts);
    let (lin, solution) = crate::constraint::solve_system(&generated.automaton)?;
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
    let rows = face_rows(ts, glue)?;
    if !rows.is_empty() {
        cert.steps
            .push(Step::FaceHomology(FaceHomologyStep { rows }));
    }
    Ok(cert)
}

/// The most levels of a face's complex in its `face-homology` step.
pub const FACE_LEVELS: u64 = 6;

/// The rows of the `face-homology` step of a closure: the start faces glued along `glue`, cells
/// by birth ([`crate::topology::volume::faces_cells`]), components as `measure` derives them,
/// and holes b1 = b0 − χ (a complex of cells in the plane encloses no surface: b2 = 0), from
/// level 0 while a level has at most [`SOLID_CELLS`] cells, up to [`FACE_LEVELS`].
pub fn face_rows(
    ts: &crate::topology::TypeSet,
    glue: &[crate::topology::component::Glue],
) -> Result<Vec<FaceRow>, CertifyError> {
    use num_traits::ToPrimitive;
    let faces: Vec<crate::topology::Face> =
        ts.start.iter().map(|&t| ts.types[t].face.clone()).collect();
    let cells = crate::topology::volume::faces_cells(&faces, glue, FACE_LEVELS)?;
    let components: Vec<u64> = match crate::topology::component::components_by_induction(ts, glue) {
        Ok(c) => vec![c as u64; cells.len()],
        Err(_) => match crate::topology::component::components_by_cells(
            ts,
            glue,
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

pub(super) fn edge(e: &crate::topology::EdgeType) -> Edge {
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

pub(super) fn face(f: &crate::topology::Face) -> Result<Face, CertifyError> {
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

pub(super) fn lacuna_edge(e: &Edge) -> crate::topology::EdgeType {
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
        algorithm: crate::topology::Algorithm::spoke_set(items),
        delay: f.delay,
    }
}
