//! `lacuna check-mesh`: the independent mesh checker on a file.

use super::*;

/// Reads a file's bytes (`-`: standard input).
fn read_bytes(path: &std::path::Path) -> Result<Vec<u8>, Error> {
    let name = path.display().to_string();
    let io = |e: std::io::Error| Error::Io {
        path: name.clone(),
        reason: e.to_string(),
    };
    if output::is_stdio(path) {
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut std::io::stdin(), &mut bytes).map_err(io)?;
        return Ok(bytes);
    }
    std::fs::read(path).map_err(io)
}

/// Runs `lacuna check-mesh`.
pub(super) fn run(args: CheckMeshArgs) -> Result<ExitCode, Error> {
    let CheckMeshArgs {
        file,
        expect_euler,
        expect_parts,
        claims,
        max_triangles,
        json,
    } = args;
    let claims = match &claims {
        Some(p) => {
            let text = lacuna::input::read_text(&p.to_string_lossy())?;
            Some(lacuna::meshcheck::Claims::parse(
                &text,
                &p.display().to_string(),
            )?)
        }
        None => None,
    };
    let bytes = read_bytes(&file)?;
    let options = lacuna::meshcheck::Options {
        max_triangles,
        expect_euler,
        expect_parts,
        claims,
    };
    let report = lacuna::meshcheck::check(&bytes, &file.display().to_string(), &options)?;
    if json {
        print_json(&report.to_json());
    } else {
        out(&report.to_text());
    }
    Ok(match report.passed() {
        true => ExitCode::SUCCESS,
        false => ExitCode::from(EXIT_FAILED),
    })
}
