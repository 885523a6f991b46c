//! `lacuna classify A B`: the topological class of two inputs (THEORY §13).

use super::*;
use lacuna::analysis::{Classification, Invariants};
use lacuna::topology::{LimitValence, TypeSet};
use std::collections::BTreeMap;

/// An input made ready for its invariants.
enum Structure {
    Faces(String, TypeSet, Vec<lacuna::topology::Glue>),
    Volume(
        String,
        lacuna::topology::volume::VolumeTypeSet,
        lacuna::topology::volume::StartCells,
        Box<lacuna::input::VolumeFile>,
    ),
    Automaton(
        String,
        Box<lacuna::input::AutomatonModel>,
        lacuna::analysis::Resolved,
    ),
}

fn load(arg: &str, limits: &Limits) -> Result<Structure, Error> {
    // A volume, or several volumes glued face to face (the level-0 complex counts a shared face
    // once).
    if let Some((name, v)) = lacuna::input::load_volume_file(arg)? {
        return Ok(Structure::Volume(
            name,
            volume::closed(&v.assembly.volumes, limits)?,
            v.assembly.start_cells(),
            Box::new(v),
        ));
    }
    match lacuna::input::load_any(arg)? {
        lacuna::input::Loaded::Faces(input) => {
            let ts = lacuna::topology::close_or_error(&input.faces(), limits)?;
            Ok(Structure::Faces(
                input.name.clone(),
                ts,
                input.assembly.canonical_glue(),
            ))
        }
        lacuna::input::Loaded::Automaton { name, model, .. } => {
            let resolved = lacuna::analysis::resolve(&model, &[], limits.max_unknowns)?;
            Ok(Structure::Automaton(name, model, resolved))
        }
    }
}

/// The order bound of a structure's recurrences (faces with bounded valences only).
fn order(s: &Structure, limits: &Limits) -> Result<Option<usize>, Error> {
    Ok(match s {
        Structure::Faces(_, ts, glue) => {
            lacuna::topology::multiplicity(ts, glue, 0, limits.max_types)?.order
        }
        _ => None,
    })
}

/// For each valence, the corners of one level's complex with that many edges.
type Valences = BTreeMap<usize, u64>;

/// The valences of a volume's level-k complex for k = 0 to `top`, built by the geometry layer
/// after the exact cell count of every level is checked against `max_cells`; empty with the
/// reason when they are not built (no placement: a surface that is no shorthand without
/// coordinates; or a placement that cannot build the cells).
fn volume_valences(
    set: &lacuna::topology::volume::VolumeTypeSet,
    start: &lacuna::topology::volume::StartCells,
    file: &lacuna::input::VolumeFile,
    top: u64,
    max_cells: u64,
) -> Result<(Vec<Valences>, Option<String>), Error> {
    let exact = lacuna::topology::volume::solid_topology_of(set, top, start)?;
    for s in &exact {
        let cells = &s.volumes + &s.faces + &s.edges + &s.corners;
        if cells > num_bigint::BigUint::from(max_cells) {
            return Err(Error::limit(
                "the cells of a volume's level-k complex (--volume-levels)",
                format!("{cells} at level {}", s.level),
                max_cells,
                "--max-cells",
            ));
        }
    }
    let placement =
        match lacuna::geometry::place_assembly(&file.assembly, &file.corners, &file.names) {
            Ok(p) => p,
            Err(e) if matches!(e.code(), "E1210" | "E1215" | "E1216") => {
                return Ok((Vec::new(), Some(format!("volume valences not built: {e}"))));
            }
            Err(e) => return Err(e),
        };
    let mut out = Vec::new();
    for k in 0..=top {
        let level =
            u32::try_from(k).map_err(|_| Error::Usage("--volume-levels too large".into()))?;
        match lacuna::geometry::assembly_valences(&file.assembly, &placement, level) {
            Ok(c) => out.push(c.valences),
            // No default placement, or one that cannot build this volume's cells: not derived.
            Err(e) if matches!(e.code(), "E1210" | "E1211") => {
                return Ok((Vec::new(), Some(format!("volume valences not built: {e}"))));
            }
            Err(e) => return Err(e),
        }
    }
    Ok((out, None))
}

fn invariants(
    s: &Structure,
    levels: u64,
    args: &ClassifyArgs,
    limits: &Limits,
) -> Result<(Invariants, Option<LimitValence>), Error> {
    Ok(match s {
        Structure::Faces(name, ts, glue) => {
            let (i, m) =
                lacuna::analysis::face_invariants(name, ts, glue, levels, limits.max_types)?;
            (i, Some(m.limit))
        }
        Structure::Volume(name, set, start, file) => {
            let top = levels.min(args.volume_levels);
            let (valences, why) = volume_valences(set, start, file, top, args.max_cells)?;
            let mut i = lacuna::analysis::volume_invariants(name, set, start, levels, &valences)?;
            i.notes.extend(why);
            (i, None)
        }
        Structure::Automaton(name, model, resolved) => (
            lacuna::analysis::automaton_invariants(
                name,
                model,
                resolved,
                levels,
                match args.multiplicity {
                    MultiplicityArg::Contacts => lacuna::analysis::AutomatonMultiplicity::Contacts,
                    MultiplicityArg::Coincidences => {
                        lacuna::analysis::AutomatonMultiplicity::Coincidences
                    }
                },
            )?,
            None,
        ),
    })
}

/// Runs `lacuna classify`.
pub(super) fn run(args: ClassifyArgs, limits: &Limits) -> Result<ExitCode, Error> {
    limits.check_level(args.levels)?;
    let a = load(&args.a, limits)?;
    let b = load(&args.b, limits)?;
    // The levels asked first: a difference there is a difference. Only when they agree and the
    // order bounds say that more levels decide every level are those compared too.
    let (mut ia, mut la) = invariants(&a, args.levels, &args, limits)?;
    let (mut ib, mut lb) = invariants(&b, args.levels, &args, limits)?;
    let mut c = lacuna::analysis::classify(&ia, &ib);
    if c.same_class && !c.every_level {
        let (oa, ob) = (order(&a, limits)?, order(&b, limits)?);
        if lacuna::analysis::levels_needed(oa, ob).is_some() {
            let levels = lacuna::analysis::levels_for(args.levels, oa, ob, limits.max_level)?;
            (ia, la) = invariants(&a, levels, &args, limits)?;
            (ib, lb) = invariants(&b, levels, &args, limits)?;
            c = lacuna::analysis::classify(&ia, &ib);
        }
    }
    if args.json {
        print_json(&serde_json::json!({
            "same_class": c.same_class,
            "differs": c.differs,
            "a": ia.name,
            "b": ib.name,
            "levels": c.levels,
            "every_level": c.every_level,
            "limit_valence": {"a": la, "b": lb},
            "limit_shares": {"a": ia.limit_shares, "b": ib.limit_shares},
            "notes": c.notes,
        }));
    } else {
        out(&text(&ia, &ib, &c, la.as_ref(), lb.as_ref()));
    }
    Ok(if c.same_class {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}

fn text(
    a: &Invariants,
    b: &Invariants,
    c: &Classification,
    la: Option<&LimitValence>,
    lb: Option<&LimitValence>,
) -> String {
    let mut s = format!("A: {} ({})\nB: {} ({})\n", a.name, a.kind, b.name, b.kind);
    if let Some(l) = la {
        s += &format!("valence of A: {l}\n");
    }
    if let Some(l) = lb {
        s += &format!("valence of B: {l}\n");
    }
    s += &format!("limit shares of the valences of A: {}\n", a.limit_shares);
    s += &format!("limit shares of the valences of B: {}\n", b.limit_shares);
    s += &format!(
        "levels compared: 0 to {}{}\n",
        c.levels,
        if c.every_level {
            " (enough to decide every level)"
        } else {
            ""
        }
    );
    match &c.differs {
        None => s += "SAME CLASS: every invariant compared is equal\n",
        Some(d) => {
            let at = d.level.map_or(String::new(), |l| format!(" at level {l}"));
            s += &format!(
                "DIFFERENT CLASSES: {} ({}){at}: A has {}, B has {}\n",
                d.invariant, d.group, d.a, d.b
            );
        }
    }
    for n in &c.notes {
        s += &format!("note: {n}\n");
    }
    s
}
