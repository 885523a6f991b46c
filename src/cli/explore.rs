//! `lacuna explore`: exit 0 when every property holds on every face of the shard, 1 when one
//! fails (a counterexample is a negative verdict), 2 for bad options or an exceeded limit.

use super::*;

fn list(text: &str, what: &str) -> Result<Vec<lacuna::topology::EdgeType>, Error> {
    let mut out = Vec::new();
    let mut col = 1;
    for item in text.split(',') {
        let t = item.trim();
        if t.is_empty() {
            return Err(Error::syntax(
                "E0112",
                format!("empty item in the list of {what}"),
                lacuna::Span {
                    line: 1,
                    col,
                    len: 1,
                },
                Some(&lacuna::Source::command_line(text)),
            ));
        }
        let lead = item.len() - item.trim_start().len();
        out.push(
            lacuna::topology::EdgeType::parse(t, col + lead)
                .map_err(|e| e.within(&lacuna::Source::command_line(text), 1, 0))?,
        );
        col += item.chars().count() + 1;
    }
    Ok(out)
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
        json,
    } = args;
    let algorithm = lacuna::topology::Algorithm::parse(algorithm.trim(), 1, &[])
        .map_err(|e| e.within(&lacuna::Source::command_line(&algorithm), 1, 0))?;
    let spec = lacuna::analysis::ExploreSpec {
        edges: list(&edges, "edges")?,
        max_length,
        params: list(&params, "parameters")?,
        algorithm,
        properties: lacuna::analysis::parse_properties(&properties)?,
        random,
        seed,
        shard: match &shard {
            Some(s) => lacuna::analysis::parse_shard(s)?,
            None => (0, 1),
        },
        shrink_budget,
    };
    // The certificate layer sits above the analysis: its check is supplied here.
    let check = |ts: &lacuna::topology::TypeSet| -> Result<(), String> {
        let cert = lacuna::certificate::certificate_for(
            "explore",
            ts,
            lacuna::constraint::GenOptions::default(),
        )
        .map_err(|e| format!("no certificate: {e}"))?;
        let report = lacuna::checker::check(&cert);
        if report.all_proved() {
            Ok(())
        } else {
            Err(report.to_text())
        }
    };
    // In the text, a minimal counterexample's witness is printed the first time only.
    let mut shown = std::collections::HashSet::new();
    let summary = lacuna::analysis::explore(&spec, limits, Some(&check), |r| {
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
