//! The properties of [`crate::analysis::explore`] that stand on layers above the analysis:
//! `certificate` (the certificate layer and the independent checker) and `holes` (the geometry
//! and its measurement). The exploration engine takes them as [`Checks`]; the command line
//! (`lacuna explore`) and the Python package (`lacuna.explore`) both hand it [`checks`], so a face
//! passes or fails the same test from either, with the same witness.

use crate::analysis::{Checks, ExploreSpec, Outcome, Property, Witness};
use crate::error::{Error, Result};
use crate::topology::{Face, Limits, TypeSet};

/// The deepest level the `holes` property measures (a face at level 6 already takes seconds).
pub const MAX_HOLES_LEVEL: u32 = 6;

/// The level the `holes` property measures unless told otherwise.
pub const DEFAULT_HOLES_LEVEL: u32 = 2;

/// The default bound on the `holes` property's estimated work, in cells (the family's faces
/// times 4^level).
pub const DEFAULT_MAX_HOLES_CELLS: u64 = 8192;

/// Above this many cells at the measured level, the `holes` property skips a face rather than
/// build it.
const HOLES_FACE_CELLS: u64 = 2_000_000;

/// The `certificate` property: the certificate of the face's closed type set is produced and
/// every step of it proved by the independent checker (the checker's report is the witness).
pub fn certificate_outcome(_: &Face, ts: &TypeSet) -> Outcome {
    let cert = match crate::certificate::certificate_for(
        "explore",
        ts,
        crate::constraint::GenOptions::default(),
    ) {
        Ok(c) => c,
        Err(e) => {
            return Outcome::Fail(Witness {
                kind: "certificate".into(),
                detail: vec![format!("no certificate: {e}")],
            })
        }
    };
    let report = crate::checker::check(&cert);
    match report.all_proved() {
        true => Outcome::Pass,
        false => Outcome::Fail(Witness {
            kind: "certificate".into(),
            detail: report.to_text().lines().map(String::from).collect(),
        }),
    }
}

/// The `holes` property: the face instantiated with the default parameters and measured at levels
/// 0..=`level` (raster 512, refined up to 4096 for narrow holes); the observed holes must equal
/// the exact count at every level. A face with a cell forced to zero area has no geometry whose
/// holes could be counted (the `no-collapse` property reports it), and a geometry that cannot be
/// measured is a skip with its reason, not a failure.
pub fn holes_outcome(face: &Face, ts: &TypeSet, level: u32, limits: &Limits) -> Outcome {
    let (flat_faces, flat_lacunas) = ts.flat_cells();
    let flat = crate::constraint::Collapses {
        flat_faces,
        flat_lacunas,
        ..Default::default()
    };
    if let Some(why) = flat.messages("").first() {
        return Outcome::Skip(format!("forced collapse: {why}"));
    }
    let input = crate::input::Input {
        name: face.to_string(),
        assembly: crate::input::Assembly {
            faces: vec![("0".into(), face.clone())],
            shared: Vec::new(),
            coords: Default::default(),
        },
    };
    let opts = crate::geometry::InstantiateOptions {
        limits: limits.clone(),
        ..Default::default()
    };
    let inst = match crate::geometry::instantiate(&input, &opts) {
        Ok(i) => i,
        Err(e) => return Outcome::Skip(format!("{}: {e}", e.code())),
    };
    if let Err(e) = crate::measure::check_cells(&inst, level, HOLES_FACE_CELLS) {
        return Outcome::Skip(format!("{}: {e}", e.code()));
    }
    let mopts = crate::measure::MeasureOptions {
        level,
        raster: 512,
        max_raster: 4096,
        density_grid: 0,
        ..Default::default()
    };
    match crate::measure::measure(&inst, &mopts) {
        Err(e) => Outcome::Skip(format!("{}: {e}", e.code())),
        // A boundary of one or two straight-placed edges has no area: nothing to observe.
        Ok(r) if r.levels.first().is_none_or(|l| l.area.abs() < 1e-12) => {
            Outcome::Skip("the default placement of this face has no area".into())
        }
        Ok(r) => {
            let bad: Vec<String> = r
                .levels
                .iter()
                .filter(|l| num_bigint::BigUint::from(l.holes) != l.exact.holes)
                .map(|l| {
                    format!(
                        "level {}: {} holes observed, {} exact",
                        l.level, l.holes, l.exact.holes
                    )
                })
                .collect();
            match bad.is_empty() {
                true => Outcome::Pass,
                false => Outcome::Fail(Witness {
                    kind: "holes".into(),
                    detail: bad,
                }),
            }
        }
    }
}

/// Checks, before any face is explored, what the `holes` property would cost: its level within
/// 1..=[`MAX_HOLES_LEVEL`] and `limits`, and — when the property is asked for — the family's
/// size times 4^level (the cells measured, roughly) at most `max_cells`. `--holes-level` and
/// `--max-holes-cells` name the two settings in the errors.
pub fn check_holes_work(
    spec: &ExploreSpec,
    level: u32,
    max_cells: u64,
    limits: &Limits,
) -> Result<()> {
    limits.check_level(u64::from(level))?;
    if !(1..=MAX_HOLES_LEVEL).contains(&level) {
        return Err(Error::limit(
            "the level of the holes property",
            level,
            MAX_HOLES_LEVEL,
            "--holes-level",
        ));
    }
    // The holes property measures every face on a raster refined until its smallest hole is
    // resolved (up to 4096² pixels a level): seconds a face at level 6. Its work is estimated
    // from the family's size before anything is measured.
    if spec.properties.contains(&Property::Holes) {
        spec.check()?;
        let cells = spec.size().saturating_mul(4u64.saturating_pow(level));
        if cells > max_cells {
            return Err(Error::limit(
                "the estimated cells of the holes property (faces × 4^level)",
                cells,
                max_cells,
                "--max-holes-cells",
            ));
        }
    }
    Ok(())
}

/// Runs `work` with the [`Checks`] of both properties (`holes` measured at `level` within
/// `limits`), as `lacuna explore` and `lacuna.explore` supply them.
pub fn with_checks<T>(level: u32, limits: &Limits, work: impl FnOnce(&Checks<'_>) -> T) -> T {
    let holes = move |face: &Face, ts: &TypeSet| holes_outcome(face, ts, level, limits);
    let checks = Checks {
        certificate: Some(&certificate_outcome),
        holes: Some(&holes),
    };
    work(&checks)
}
