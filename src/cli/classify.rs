//! `lacuna classify A B`: the topological class of two inputs (THEORY §13).

use super::*;

/// Runs `lacuna classify`.
pub(super) fn run(args: ClassifyArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let opts = lacuna::export::ClassifyOptions {
        levels: args.levels,
        volume_levels: args.volume_levels,
        max_cells: args.max_cells,
        multiplicity: match args.multiplicity {
            MultiplicityArg::Contacts => lacuna::analysis::AutomatonMultiplicity::Contacts,
            MultiplicityArg::Coincidences => lacuna::analysis::AutomatonMultiplicity::Coincidences,
        },
    };
    let outcome = lacuna::export::classify_inputs(&args.a, &args.b, &opts, limits)?;
    if args.json {
        print_json(&outcome.to_json());
    } else {
        out(&outcome.to_text());
    }
    Ok(if outcome.classification.same_class {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
