//! Certificates of hand-written automata and automaton models: the automaton claim (operators
//! in Q or in a field K, the attractor, the rule), the constraint and rule-compilation steps,
//! contraction, similarity dimension and open-set witnesses, the boundary dimension of tiles,
//! seed 002's multiplicity of the first levels, and lacuna's automaton and model read back from a
//! claim.

use super::systems::{algebraic, rational, step_of_system, strings, system};
use super::CertifyError;
use crate::certificate::format::{
    AttractorClaim, BoundaryComponent, BoundaryPart, BoundaryState, BoundaryStep,
    ConstraintFailsStep, ConstraintsHoldStep, ContractionStep, FieldCoords, MultiplicityStep,
    NeighbourFails, NeighbourHolds, NeighbourMap, NeighbourMaps, SimilarityPart, SimilarityStep,
};
use crate::certificate::format::{
    AutomatonClaim, AutomatonOperator, AutomatonState, Certificate, Claim, RuleCompilationStep,
    Step, WordEquation, WordFactor,
};
use num_rational::BigRational;
use num_traits::{One, Zero};

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
    let (lin, solution) = crate::constraint::solve_system(automaton)?;
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
        crate::analysis::automata::similarity::default_points(
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
    p: &crate::analysis::automata::similarity::PartWitness,
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
    w: &crate::analysis::automata::open_set::NeighbourWitness,
) -> NeighbourMaps {
    use crate::analysis::automata::open_set::{Coordinates, NeighbourWitness};
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
        let (lin, solution) = crate::constraint::solve_system(&m.automaton)?;
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
                instance: instance.clone(),
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
            if let Some(b) = &attractor.boundary {
                cert.steps
                    .push(Step::BoundaryDimension(boundary_step(b, digits)));
            }
        }
    }
    if let Some(step) = multiplicity_step(m, &attractor.resolved, &claim, instance)? {
        cert.steps.push(Step::Multiplicity(step));
    }
    // A compiled rule, with or without the age and random extensions: the checker compiles its
    // text again.
    if m.rule.is_some() {
        cert.steps
            .push(Step::RuleCompilation(RuleCompilationStep {}));
    }
    Ok(cert)
}

/// Whether the checker can compare the maps of `m` canonically, and how: `Some(None)` for
/// rational entries, `Some(Some(q))` with a prime q modulo which the field's polynomial is
/// irreducible, `None` when no prime below 10⁴ proves it.
fn canonical_prime(claim: &AutomatonClaim) -> Option<Option<u64>> {
    match &claim.field {
        None => Some(None),
        Some(f) => {
            let poly: Option<Vec<num_bigint::BigInt>> =
                f.poly.iter().map(|c| c.parse().ok()).collect();
            poly.and_then(|p| crate::algebra::factor::irreducibility_prime(&p))
                .map(Some)
        }
    }
}

/// Whether `lacuna verify --certificate` certifies seed 002's multiplicity of the first levels
/// of `m` (a `multiplicity` step): its entries are rational, or a prime proves its field's
/// polynomial irreducible.
pub fn multiplicity_certifiable(m: &crate::input::AutomatonModel) -> bool {
    canonical_prime(&model_claim(m)).is_some()
}

/// The most levels a `multiplicity` step lists (it also stops before a level of more than
/// [`MAX_CONTACT_PIECES`](crate::analysis::invariants::automaton::MAX_CONTACT_PIECES) pieces);
/// `classify`'s note names both bounds.
pub const MULTIPLICITY_LEVELS: u64 = 8;

/// Seed 002's multiplicity of the first levels as the step `multiplicity` (levels of at most
/// [`MAX_CONTACT_PIECES`](crate::analysis::invariants::automaton::MAX_CONTACT_PIECES) pieces,
/// at most [`MULTIPLICITY_LEVELS`]); `None` when the claim's field has no prime proving its
/// polynomial irreducible (the checker could not compare maps canonically) or no level is small
/// enough.
fn multiplicity_step(
    m: &crate::input::AutomatonModel,
    resolved: &crate::analysis::automata::automaton_resolve::Resolved,
    claim: &AutomatonClaim,
    instance: Vec<(usize, Vec<Vec<FieldCoords>>)>,
) -> Result<Option<MultiplicityStep>, CertifyError> {
    use crate::analysis::invariants::automaton::{coincidence_histograms, MAX_CONTACT_PIECES};
    let Some(prime) = canonical_prime(claim) else {
        return Ok(None);
    };
    let levels = coincidence_histograms(m, resolved, MULTIPLICITY_LEVELS, MAX_CONTACT_PIECES)?;
    if levels.is_empty() {
        return Ok(None);
    }
    Ok(Some(MultiplicityStep {
        instance,
        prime,
        levels: levels
            .into_iter()
            .map(|h| h.into_iter().collect())
            .collect(),
    }))
}

/// The boundary dimension of the tile parts as the step `boundary-dimension`.
fn boundary_step(b: &crate::analysis::BoundaryDimension, digits: usize) -> BoundaryStep {
    let mut decimals = b.states.iter().map(|s| s.decimal.clone());
    BoundaryStep {
        parts: b
            .graphs
            .iter()
            .map(|g| BoundaryPart {
                part: g.part,
                maps: g
                    .witness
                    .as_ref()
                    .and_then(|w| match neighbour_maps(&g.states, w) {
                        NeighbourMaps::Holds(h) => Some(h),
                        NeighbourMaps::Fails(_) => None,
                    }),
                components: g
                    .components
                    .iter()
                    .map(|c| BoundaryComponent {
                        nodes: c.nodes.clone(),
                        classes: c.classes.clone(),
                        u: algebraic(&c.u),
                        rational: c.rational.as_ref().map(ToString::to_string),
                    })
                    .collect(),
                states: g
                    .dominant
                    .iter()
                    .map(|&component| BoundaryState {
                        component,
                        decimal: decimals.next().unwrap_or_default(),
                    })
                    .collect(),
            })
            .collect(),
        digits,
    }
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
