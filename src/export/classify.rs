//! `classify A B` (THEORY §13): both inputs loaded and closed, their invariants compared at the
//! levels asked and, when faces' recurrence orders say that more levels decide every level, at
//! those too. The command line and the Python package call [`classify_inputs`] and print or wrap
//! its [`ClassifyOutcome`].

use crate::analysis::{AutomatonMultiplicity, Classification, Invariants};
use crate::error::{Error, Result};
use crate::input::{AutomatonModel, VolumeFile};
use crate::topology::volume::{StartCells, VolumeClosure, VolumeTypeSet};
use crate::topology::{Glue, LimitValence, Limits, TypeSet};
use std::collections::BTreeMap;

/// What `classify` is asked besides the two inputs.
#[derive(Clone, Debug)]
pub struct ClassifyOptions {
    /// Compare levels 0 to this at least.
    pub levels: u64,
    /// For a volume: the level-k complexes built, k = 0 to this (at most `levels`).
    pub volume_levels: u64,
    /// Refuse before the work when a volume's level-k complex has more cells than this.
    pub max_cells: u64,
    /// For an automaton, the multiplicity compared.
    pub multiplicity: AutomatonMultiplicity,
}

impl Default for ClassifyOptions {
    fn default() -> Self {
        ClassifyOptions {
            levels: 4,
            volume_levels: 2,
            max_cells: 200_000,
            multiplicity: AutomatonMultiplicity::Coincidences,
        }
    }
}

/// The answer of `classify`: the invariants of both inputs, the limit valences of faces, and the
/// comparison.
#[derive(Clone, Debug)]
pub struct ClassifyOutcome {
    /// The invariants of A (at the levels finally compared).
    pub a: Invariants,
    /// The invariants of B.
    pub b: Invariants,
    /// The valences A's vertices settle at (faces only).
    pub limit_a: Option<LimitValence>,
    /// The valences B's vertices settle at (faces only).
    pub limit_b: Option<LimitValence>,
    /// The comparison.
    pub classification: Classification,
}

impl ClassifyOutcome {
    /// The report as `lacuna classify --json` prints it.
    pub fn to_json(&self) -> serde_json::Value {
        let c = &self.classification;
        serde_json::json!({
            "same_class": c.same_class,
            "differs": c.differs,
            "a": self.a.name,
            "b": self.b.name,
            "levels": c.levels,
            "every_level": c.every_level,
            "limit_valence": {"a": self.limit_a, "b": self.limit_b},
            "limit_shares": {"a": self.a.limit_shares, "b": self.b.limit_shares},
            "notes": c.notes,
        })
    }

    /// The report as `lacuna classify` prints it.
    pub fn to_text(&self) -> String {
        let (a, b, c) = (&self.a, &self.b, &self.classification);
        let mut s = format!("A: {} ({})\nB: {} ({})\n", a.name, a.kind, b.name, b.kind);
        if let Some(l) = &self.limit_a {
            s += &format!("valence of A: {l}\n");
        }
        if let Some(l) = &self.limit_b {
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
}

/// An input made ready for its invariants.
enum Structure {
    Faces(String, TypeSet, Vec<Glue>),
    Volume(String, VolumeTypeSet, StartCells, Box<VolumeFile>),
    Automaton(String, Box<AutomatonModel>, crate::analysis::Resolved),
}

/// Loads and closes an input (face notation, a file or a library name).
fn load(arg: &str, limits: &Limits) -> Result<Structure> {
    // A volume, or several volumes glued face to face (the level-0 complex counts a shared face
    // once).
    if let Some((name, v)) = crate::input::load_volume_file(arg)? {
        let set = match VolumeClosure::of(&v.assembly.volumes, limits)? {
            VolumeClosure::Closed(set) => set,
            VolumeClosure::Runaway(r) => {
                return Err(Error::Usage(format!(
                    "the volume's closure did not close: {}",
                    r.reason
                )))
            }
        };
        let start = v.assembly.start_cells();
        return Ok(Structure::Volume(name, set, start, Box::new(v)));
    }
    match crate::input::load_any(arg)? {
        crate::input::Loaded::Faces(input) => {
            let ts = crate::topology::close_or_error(&input.faces(), limits)?;
            Ok(Structure::Faces(
                input.name.clone(),
                ts,
                input.assembly.canonical_glue(),
            ))
        }
        crate::input::Loaded::Automaton { name, model, .. } => {
            let resolved = crate::analysis::resolve(&model, &[], limits.max_unknowns)?;
            Ok(Structure::Automaton(name, model, resolved))
        }
    }
}

/// For each valence, the corners of one level's complex with that many edges.
type Valences = BTreeMap<usize, u64>;

/// The valences of a volume's level-k complex for k = 0 to `top`, built by the geometry layer
/// after the exact cell count of every level is checked against `max_cells`; empty with the
/// reason when they are not built (no placement: a surface that is no shorthand without
/// coordinates; or a placement that cannot build the cells).
fn volume_valences(
    set: &VolumeTypeSet,
    start: &StartCells,
    file: &VolumeFile,
    top: u64,
    max_cells: u64,
) -> Result<(Vec<Valences>, Option<String>)> {
    let exact = crate::topology::volume::solid_topology_of(set, top, start)?;
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
        match crate::geometry::place_assembly(&file.assembly, &file.corners, &file.names) {
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
        match crate::geometry::assembly_valences(&file.assembly, &placement, level) {
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

/// The invariants of a structure to `levels`, with the limit valence of faces.
fn invariants(
    s: &Structure,
    levels: u64,
    opts: &ClassifyOptions,
    limits: &Limits,
) -> Result<(Invariants, Option<LimitValence>)> {
    Ok(match s {
        Structure::Faces(name, ts, glue) => {
            let (i, m) =
                crate::analysis::face_invariants(name, ts, glue, levels, limits.max_types)?;
            (i, Some(m.limit))
        }
        Structure::Volume(name, set, start, file) => {
            let top = levels.min(opts.volume_levels);
            let (valences, why) = volume_valences(set, start, file, top, opts.max_cells)?;
            let mut i = crate::analysis::volume_invariants(name, set, start, levels, &valences)?;
            i.notes.extend(why);
            (i, None)
        }
        Structure::Automaton(name, model, resolved) => (
            crate::analysis::automaton_invariants(
                name,
                model,
                resolved,
                levels,
                opts.multiplicity,
                limits.max_products,
            )?,
            None,
        ),
    })
}

/// What a certificate proves of an automaton's invariants: the multiplicity of its first levels
/// (the `multiplicity` step), not the comparison or its extension to every level.
fn certified_levels(name: &str, model: &crate::input::AutomatonModel) -> String {
    if crate::certificate::multiplicity_certifiable(model) {
        format!(
            "{name}: its multiplicity at the levels of at most {} pieces (up to level {}) is certified by the step `multiplicity` of `lacuna verify {name} --certificate OUT`; the extension to every level (the open-set condition of the merged maps, the recurrence's order) is not in a certificate",
            crate::analysis::invariants::automaton::MAX_CONTACT_PIECES,
            crate::certificate::MULTIPLICITY_LEVELS,
        )
    } else {
        format!(
            "{name}: its multiplicity is not certified: no prime below 10^4 proves its field's polynomial irreducible, which the checker needs to compare maps"
        )
    }
}

/// Classifies two inputs (face notation, files or library names of faces, assemblies, volumes or
/// automata): the levels asked first (a difference there is a difference); only when they agree
/// and the order bounds say that more levels decide every level are those compared too.
pub fn classify_inputs(
    a: &str,
    b: &str,
    opts: &ClassifyOptions,
    limits: &Limits,
) -> Result<ClassifyOutcome> {
    limits.check_level(opts.levels)?;
    let a = load(a, limits)?;
    let b = load(b, limits)?;
    let (mut ia, mut la) = invariants(&a, opts.levels, opts, limits)?;
    let (mut ib, mut lb) = invariants(&b, opts.levels, opts, limits)?;
    let mut c = crate::analysis::classify(&ia, &ib);
    if c.same_class && !c.every_level {
        let (oa, ob) = (ia.order, ib.order);
        if crate::analysis::levels_needed(oa, ob).is_some() {
            let levels = crate::analysis::levels_for(opts.levels, oa, ob, limits.max_level)?;
            (ia, la) = invariants(&a, levels, opts, limits)?;
            (ib, lb) = invariants(&b, levels, opts, limits)?;
            c = crate::analysis::classify(&ia, &ib);
        }
    }
    for s in [&a, &b] {
        if let Structure::Automaton(name, model, _) = s {
            c.notes.push(certified_levels(name, model));
        }
    }
    Ok(ClassifyOutcome {
        a: ia,
        b: ib,
        limit_a: la,
        limit_b: lb,
        classification: c,
    })
}
