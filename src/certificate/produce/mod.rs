//! The certificate producer: writes lacuna's results (closure, solution space, limit ratio) as a
//! [`Certificate`] for the independent checker ([`crate::checker`]).
//!
//! This side may use all of lacuna: the certificate claims what lacuna computed, and the checker
//! re-verifies it without lacuna's code. The only new computations here are the witnesses the
//! checker needs and lacuna does not report: the left Perron eigenvector over Q(ρ) of every class
//! of radius ρ (exact elimination in lacuna's number field), the Collatz–Wielandt vectors of the
//! other classes, and the minimal polynomial of each limit point.
//!
//! One file per kind of claim: `faces.rs` (closed type sets, their closure and faces'
//! homology, substitutions), `systems.rs` (linear systems, their solution, the limit ratio and
//! its Perron–Frobenius witnesses), `volumes.rs` (volume sets, their constraint system and
//! solid), `automata.rs` (hand-written automata and models, rules); this file holds the error
//! and [`recertify`], which dispatches a claim to them.

mod automata;
mod faces;
mod systems;
mod volumes;

pub use automata::{
    automaton_claim, certificate_for_automaton, certificate_for_model, certify_model,
    lacuna_automaton, model_claim, model_of_claim, multiplicity_certifiable, MULTIPLICITY_LEVELS,
};
pub use faces::{
    certificate_for, certificate_for_assembly, certificate_for_substitution, closure_step,
    face_rows, lacuna_face, substitution_of, SubstitutionParts, FACE_LEVELS,
};
use systems::rational;
pub use systems::{certificate_for_system, ratio_step, solution_step};
pub use volumes::{
    certificate_for_volumes, lacuna_volume, recurrence_has_voids, solid_rows,
    solve_and_certify_volumes, volume_system_step,
};

use crate::certificate::format::{Certificate, Claim};

/// The most cells (volumes, faces, edges and corners) of a level of the solid that
/// [`certificate_for_volumes`] puts in its `solid-homology` step: the checker builds every
/// listed level cell by cell and reduces its boundary matrices.
pub const SOLID_CELLS: u64 = 250_000;

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
            let glue: Vec<crate::topology::component::Glue> = f
                .glue
                .iter()
                .map(|g| [(g.a[0], g.a[1]), (g.b[0], g.b[1])])
                .collect();
            certificate_for_assembly(label, &ts, &glue, opts)
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
            let rows = s
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
                .collect::<Result<Vec<_>, CertifyError>>()?;
            let sys = crate::constraint::LinearSystem::from_equations(s.unknowns, rows);
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
