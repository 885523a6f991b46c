//! `lacuna explore`.

use super::*;

/// Runs `lacuna explore`.
pub(super) fn run(_args: ExploreArgs, _limits: &Limits) -> Result<ExitCode, Error> {
    Ok(ExitCode::SUCCESS)
}
