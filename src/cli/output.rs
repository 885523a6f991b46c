//! The files a command writes: checked before the work (never an input, never twice, in an
//! existing folder), each written to a temporary file in its own folder and renamed over the
//! target only when complete, every write and the final flush checked. `-` is standard output.
//! A failure is E1005 and names the outputs already written.

use lacuna::Error;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The outputs of one command, and which of them are written so far.
pub(crate) struct Outputs {
    written: Vec<String>,
    /// Whether an output goes to standard output (then status lines go to standard error).
    pub(crate) to_stdout: bool,
    /// Whether the command ends with one JSON object on standard output (`render --json`):
    /// status lines go to standard error.
    pub(crate) json: bool,
    /// The printability of the mesh written, for that JSON object.
    pub(crate) printability: Option<lacuna::mesh::printability::PrintReport>,
}

/// Whether `path` names standard output or input.
pub(crate) fn is_stdio(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// The same file, when both exist (symbolic links and `./` resolved).
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

/// The folder an output is written in (`.` for a bare file name).
fn folder(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

impl Outputs {
    /// Checks the outputs `(flag, path)` against the inputs before the work: an output may not
    /// be an input file (E0504), two outputs may not be one file or both standard output
    /// (E0504), and each must be in an existing folder (E1005).
    pub(crate) fn check(inputs: &[&Path], outputs: &[(&str, &Path)]) -> Result<Outputs, Error> {
        let mut to_stdout = false;
        for (k, (flag, path)) in outputs.iter().enumerate() {
            if is_stdio(path) {
                if to_stdout {
                    return Err(Error::Usage(format!(
                        "{flag} -: another output already goes to standard output"
                    )));
                }
                to_stdout = true;
                continue;
            }
            if let Some(input) = inputs.iter().find(|i| !is_stdio(i) && same_file(i, path)) {
                return Err(Error::Usage(format!(
                    "{flag} `{}` is the input `{}`: refusing to overwrite an input",
                    path.display(),
                    input.display()
                )));
            }
            if let Some((other, _)) = outputs[..k]
                .iter()
                .find(|(_, p)| !is_stdio(p) && (p == path || same_file(p, path)))
            {
                return Err(Error::Usage(format!(
                    "{flag} `{}` is also the output of {other}: give each output its own file",
                    path.display()
                )));
            }
            let dir = folder(path);
            if !dir.is_dir() {
                return Err(Error::Write {
                    path: path.display().to_string(),
                    reason: format!(
                        "the folder `{}` does not exist; nothing was written",
                        dir.display()
                    ),
                });
            }
        }
        Ok(Outputs {
            written: Vec::new(),
            to_stdout,
            json: false,
            printability: None,
        })
    }

    /// Writes one output: `body` writes the content; on success the file is in place (renamed
    /// from a temporary file in the same folder) and its name is remembered.
    pub(crate) fn write(
        &mut self,
        path: &Path,
        body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> Result<(), Error> {
        let result = if is_stdio(path) {
            let mut out = std::io::stdout().lock();
            // A closed pipe (`lacuna render … --svg - | head`) is not an error, as for every
            // other output on standard output.
            match body(&mut out).and_then(|_| out.flush()) {
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
                other => other,
            }
        } else {
            write_file(path, body)
        };
        match result {
            Ok(()) => {
                self.written.push(path.display().to_string());
                Ok(())
            }
            Err(e) => Err(Error::Write {
                path: path.display().to_string(),
                reason: format!(
                    "{e}; {}",
                    if self.written.is_empty() {
                        "nothing was written".to_string()
                    } else {
                        format!("written before: {}", self.written.join(", "))
                    }
                ),
            }),
        }
    }

    /// The outputs written so far.
    pub(crate) fn written(&self) -> &[String] {
        &self.written
    }

    /// A status line (`wrote …`): on standard output, or on standard error when an output
    /// goes to standard output or the command prints JSON.
    pub(crate) fn say(&self, text: &str) {
        if self.to_stdout || self.json {
            eprint!("{text}");
        } else {
            super::out(text);
        }
    }
}

/// Writes a file through a temporary file in its folder, renamed over it when complete. A path
/// that exists and is not a regular file (a device such as `/dev/null`, a pipe) is written in
/// place: renaming over it would replace it.
fn write_file(
    path: &Path,
    body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let target: PathBuf = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
    if target.exists() && !target.is_file() {
        let mut w = std::io::BufWriter::new(std::fs::OpenOptions::new().write(true).open(&target)?);
        body(&mut w)?;
        return w.flush();
    }
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = folder(&target).join(format!(".{name}.{}.lacuna-tmp", std::process::id()));
    let result = (|| {
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        let mut w = std::io::BufWriter::new(file);
        body(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&tmp, &target)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
