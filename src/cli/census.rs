//! `lacuna census`.

use super::*;

/// Runs `lacuna census`.
pub(super) fn run(args: CensusArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let CensusArgs { spec, json } = args;
    let mut spec = lacuna::analysis::CensusSpec::parse(
        &spec.edges,
        &spec.params,
        &spec.algorithms,
        spec.max_length,
        spec.threads,
    )?;
    // The JSON lists every face (type count, R, verdict), not only the histogram.
    spec.per_face = json;
    let report = lacuna::analysis::census(&spec, limits);
    if json {
        print_json(&report);
    } else {
        out(&report.to_text());
    }
    Ok(ExitCode::SUCCESS)
}
