//! `lacuna explore`: exit 0 when every property holds on every face of the shard, 1 when one
//! fails (a counterexample is a negative verdict), 2 for bad options or an exceeded limit.

use super::*;

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
    lacuna::family::check_holes_work(&spec, holes_level, max_holes_cells, limits)?;
    lacuna::family::with_checks(holes_level, limits, |checks| {
        run_checks(&spec, limits, checks, json)
    })
}

/// Explores the family with `checks` and prints each result (JSON lines, or the failures as
/// text) and the summary.
fn run_checks(
    spec: &lacuna::analysis::ExploreSpec,
    limits: &Limits,
    checks: &lacuna::analysis::Checks<'_>,
    json: bool,
) -> Result<ExitCode, Error> {
    // In the text, a minimal counterexample's witness is printed the first time only.
    let mut shown = std::collections::HashSet::new();
    let summary = lacuna::analysis::explore(spec, limits, checks, |r| {
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
