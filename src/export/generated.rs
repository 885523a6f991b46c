//! The text of `lacuna export`: the automaton generated from the closure of faces, in lacuna's
//! automaton format (with a header saying where it comes from) or as the MODITERE Python model;
//! an automaton file written back in lacuna's format. The command line and the Python package
//! write the same text.

use crate::constraint::{automaton_of, GenOptions};
use crate::input::Loaded;
use crate::topology::{close_or_error, Limits};
use crate::Error;

/// The formats of `lacuna export`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeneratedFormat {
    /// lacuna's automaton format (docs/FORMATS.md).
    Aut,
    /// The MODITERE Python model of AutoFrac2DCLI (docs/FORMATS.md).
    Moditere,
}

/// The text `lacuna export` writes for `loaded` in `format`, the automaton generated with `opts`
/// (Bézier degree, Cantor gap/piece). An automaton file has no MODITERE export (E0504).
pub fn generated_text(
    loaded: Loaded,
    format: GeneratedFormat,
    opts: GenOptions,
    limits: &Limits,
) -> Result<String, Error> {
    let degree = opts.degree;
    let gap = opts.cantor_gap.clone();
    Ok(match loaded {
        Loaded::Automaton {
            name, automaton, ..
        } => {
            if format == GeneratedFormat::Moditere {
                return Err(Error::Usage(format!(
                    "`{name}` is an automaton file: the MODITERE export needs faces (a face, an assembly or an AutoFrac2D file)"
                )));
            }
            super::automaton_text(
                &automaton,
                &[format!("lacuna export of the automaton `{name}`")],
                &Default::default(),
            )
        }
        Loaded::Faces(input) => {
            let ts = close_or_error(&input.faces(), limits)?;
            match format {
                GeneratedFormat::Aut => {
                    let g = automaton_of(&ts, opts);
                    limits.check_unknowns(g.automaton.unknown_count())?;
                    let notes = g
                        .face_state
                        .iter()
                        .zip(&ts.types)
                        .map(|(&s, t)| (s, t.face.to_string()))
                        .collect();
                    super::automaton_text(
                        &g.automaton,
                        &[
                            format!(
                                "lacuna export of `{}`: the automaton generated from its closure ({} face types),",
                                input.name.replace('\n', " "),
                                ts.types.len()
                            ),
                            format!("Bézier degree {degree}, Cantor gap/piece ratio {gap} (THEORY §6)."),
                            "`lacuna solve` of this file gives the unknowns, equations, rank and degrees of freedom".into(),
                            "of `lacuna solve` on the input; the degeneracy check needs the faces, so only the input has it.".into(),
                        ],
                        &notes,
                    )
                }
                GeneratedFormat::Moditere => {
                    let g = automaton_of(&ts, opts);
                    super::moditere_text(&input, &ts, &g, limits)?
                }
            }
        }
    })
}
