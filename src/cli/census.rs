//! `lacuna census`.

use super::*;

/// Runs `lacuna census`.
pub(super) fn run(args: CensusArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let CensusArgs { spec, json } = args;
    let spec = lacuna::analysis::CensusSpec::parse(
        &spec.edges,
        &spec.params,
        &spec.algorithms,
        spec.max_length,
        spec.threads,
    )?;
    let report = lacuna::analysis::census(&spec, limits);
    if json {
        print_json(&report);
    } else {
        out(&report.to_text());
    }
    Ok(ExitCode::SUCCESS)
}
