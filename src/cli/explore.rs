//! `lacuna explore`: exit 0 when every property holds on every face of the shard, 1 when one
//! fails (a counterexample is a negative verdict), 2 for bad options or an exceeded limit.

use super::*;

/// The `holes` property: the face instantiated with the default parameters, measured at levels
/// 0..=`level` (raster 512, refined up to 4096 for narrow holes); the observed holes must equal the
/// exact count at every level. A geometry that cannot be measured is a skip, not a failure.
fn holes_outcome(
    face: &lacuna::topology::Face,
    level: u32,
    limits: &Limits,
) -> lacuna::analysis::Outcome {
    use lacuna::analysis::{Outcome, Witness};
    let input = lacuna::input::Input {
        name: face.to_string(),
        assembly: lacuna::input::Assembly {
            faces: vec![("0".into(), face.clone())],
            shared: Vec::new(),
            coords: Default::default(),
        },
    };
    let opts = lacuna::geometry::InstantiateOptions {
        limits: limits.clone(),
        ..Default::default()
    };
    let inst = match lacuna::geometry::instantiate(&input, &opts) {
        Ok(i) => i,
        Err(e) => return Outcome::Skip(format!("{}: {e}", e.code())),
    };
    if let Err(e) = lacuna::measure::check_cells(&inst, level, 2_000_000) {
        return Outcome::Skip(format!("{}: {e}", e.code()));
    }
    let mopts = lacuna::measure::MeasureOptions {
        level,
        raster: 512,
        max_raster: 4096,
        density_grid: 0,
        ..Default::default()
    };
    match lacuna::measure::measure(&inst, &mopts) {
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
            if bad.is_empty() {
                Outcome::Pass
            } else {
                Outcome::Fail(Witness {
                    kind: "holes".into(),
                    detail: bad,
                })
            }
        }
    }
}

/// Runs `lacuna explore`.
pub(super) fn run(args: ExploreArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let ExploreArgs {
        edges,
        max_length,
        params,
        algorithm,
        properties,
        random,
        seed,
        shard,
        shrink_budget,
        holes_level,
        max_holes_cells,
        threads,
        json,
    } = args;
    let algorithm = lacuna::topology::Algorithm::parse(algorithm.trim(), 1, &[])
        .map_err(|e| e.within(&lacuna::Source::command_line(&algorithm), 1, 0))?;
    let spec = lacuna::analysis::ExploreSpec {
        edges: lacuna::analysis::parse_edge_list(&edges, "edges")?,
        max_length,
        params: lacuna::analysis::parse_edge_list(&params, "parameters")?,
        algorithm,
        properties: lacuna::analysis::parse_properties(&properties)?,
        random,
        seed,
        shard: match &shard {
            Some(s) => lacuna::analysis::parse_shard(s)?,
            None => (0, 1),
        },
        shrink_budget,
        threads: threads
            .unwrap_or_else(|| {
                std::thread::available_parallelism()
                    .map(|n| n.get())
                    .unwrap_or(1)
            })
            .clamp(1, 256),
    };
    limits.check_level(u64::from(holes_level))?;
    if !(1..=6).contains(&holes_level) {
        return Err(Error::limit(
            "the level of the holes property",
            holes_level,
            6,
            "--holes-level",
        ));
    }
    // The holes property measures every face on a raster refined until its smallest hole is
    // resolved (up to 4096² pixels a level): seconds a face at level 6. Its work is estimated
    // from the family's size before anything is measured.
    if spec.properties.contains(&lacuna::analysis::Property::Holes) {
        spec.check()?;
        let cells = spec.size().saturating_mul(4u64.saturating_pow(holes_level));
        if cells > max_holes_cells {
            return Err(Error::limit(
                "the estimated cells of the holes property (faces × 4^level)",
                cells,
                max_holes_cells,
                "--max-holes-cells",
            ));
        }
    }
    // The certificate layer and the geometry sit above the analysis: their checks are supplied
    // here.
    use lacuna::analysis::{Outcome, Witness};
    let certificate = |_: &lacuna::topology::Face, ts: &lacuna::topology::TypeSet| -> Outcome {
        let cert = match lacuna::certificate::certificate_for(
            "explore",
            ts,
            lacuna::constraint::GenOptions::default(),
        ) {
            Ok(c) => c,
            Err(e) => {
                return Outcome::Fail(Witness {
                    kind: "certificate".into(),
                    detail: vec![format!("no certificate: {e}")],
                })
            }
        };
        let report = lacuna::checker::check(&cert);
        if report.all_proved() {
            Outcome::Pass
        } else {
            Outcome::Fail(Witness {
                kind: "certificate".into(),
                detail: report.to_text().lines().map(String::from).collect(),
            })
        }
    };
    let holes = |face: &lacuna::topology::Face, ts: &lacuna::topology::TypeSet| -> Outcome {
        // A cell forced to zero area has no geometry whose holes could be counted: refused with
        // the reason (the no-collapse property reports it as the failure it is).
        let (flat_faces, flat_lacunas) = ts.flat_cells();
        let flat = lacuna::constraint::Collapses {
            flat_faces,
            flat_lacunas,
            ..Default::default()
        };
        match flat.messages("").first() {
            Some(why) => Outcome::Skip(format!("forced collapse: {why}")),
            None => holes_outcome(face, holes_level, limits),
        }
    };
    let checks = lacuna::analysis::Checks {
        certificate: Some(&certificate),
        holes: Some(&holes),
    };
    // In the text, a minimal counterexample's witness is printed the first time only.
    let mut shown = std::collections::HashSet::new();
    let summary = lacuna::analysis::explore(&spec, limits, &checks, |r| {
        if json {
            out(&(serde_json::to_string(r).expect("results serialise") + "\n"));
        } else if !r.failures.is_empty() {
            let mut o = format!("#{} {}\n", r.index, r.face);
            for f in &r.failures {
                o += &format!(
                    "  FAILS {}: {}\n    shrunk in {} step{} to{} `{}`: {}\n",
                    f.property.name(),
                    f.witness.kind,
                    f.shrunk.steps,
                    if f.shrunk.steps == 1 { "" } else { "s" },
                    if f.shrunk.minimal {
                        " the minimal"
                    } else {
                        " (shrink budget spent)"
                    },
                    f.shrunk.face,
                    f.shrunk.witness.kind
                );
                if shown.insert((f.shrunk.face.clone(), f.property)) {
                    for d in f.shrunk.witness.detail.iter().take(12) {
                        o += &format!("      {d}\n");
                    }
                } else {
                    o += "      (witness above)\n";
                }
            }
            out(&o);
        }
    })?;
    if json {
        out(
            &(serde_json::to_string(&serde_json::json!({ "summary": summary }))
                .expect("summary serialises")
                + "\n"),
        );
    } else {
        let mut o = format!(
            "explore (shard {}): {} faces — {} pass, {} fail, {} refused, {} stopped by a limit\n",
            summary.shard,
            summary.boundaries,
            summary.passed,
            summary.failed,
            summary.refused,
            summary.limit
        );
        for (face, p) in &summary.counterexamples {
            o += &format!("minimal counterexample ({}): {face}\n", p.name());
        }
        out(&o);
    }
    Ok(if summary.failed > 0 {
        ExitCode::from(EXIT_FAILED)
    } else {
        ExitCode::SUCCESS
    })
}
