//! The operator analysis on the command line: matrix and number arguments (E0901) and the
//! human-readable report.

use super::*;

/// `0.250000000000` → `0.25`, `1.000000000000` → `1`.
fn trim_decimal(s: &str) -> String {
    if !s.contains('.') {
        return s.to_string();
    }
    let t = s.trim_end_matches('0').trim_end_matches('.');
    if t.is_empty() || t == "-" {
        "0".into()
    } else {
        t.to_string()
    }
}

fn arg_error(text: &str, message: String, col: usize, len: usize) -> Error {
    Error::syntax(
        "E0901",
        message,
        Span { line: 1, col, len },
        Some(&Source::command_line(text)),
    )
}

/// Parses a matrix given on the command line: `[a b; c d]` (brackets optional), rows separated
/// by `;`, entries by spaces or commas, exact numbers (`1/3`, `-2`, `0.25`). Error E0901.
pub fn parse_matrix_arg(text: &str) -> Result<Matrix> {
    // The automaton format's matrix literal, with the brackets optional on the command line;
    // every failure is reported as E0901 (a bad argument), with its column in `text`.
    let t = text.trim_start();
    let lead = text.chars().count() - t.chars().count();
    let wrapped = !t.starts_with('[');
    let line = if wrapped {
        format!("[{t}]")
    } else {
        t.to_string()
    };
    let src = crate::error::Source::command_line(text);
    let parsed =
        crate::input::automaton_format::parse_matrix(&line, 0, 1, &src).and_then(|(m, end)| {
            let rest = line[end..].trim();
            if rest.is_empty() {
                Ok(m)
            } else {
                Err(arg_error(
                    text,
                    format!("unexpected `{rest}` after the matrix"),
                    end + 1,
                    rest.chars().count(),
                ))
            }
        });
    parsed.map_err(|e| match e {
        Error::Syntax(mut d) => {
            d.code = "E0901";
            if let Some(span) = d.span.as_mut() {
                span.col = (span.col + lead)
                    .saturating_sub(usize::from(wrapped))
                    .max(1);
            }
            Error::Syntax(d)
        }
        other => other,
    })
}

/// Parses a list of exact numbers separated by spaces or commas (`1 1/2 1/4`). Error E0901.
pub fn parse_rationals_arg(text: &str) -> Result<Vec<BigRational>> {
    let m = parse_matrix_arg(text)?;
    if m.rows != 1 {
        return Err(arg_error(
            text,
            "expected one list of numbers (no `;`)".into(),
            1,
            text.chars().count(),
        ));
    }
    Ok(m.data)
}

/// Longest exact form printed in the summary; longer ones are replaced by decimals (the full
/// forms are in `--exact` and `--json`).
pub const SHORT: usize = 60;

fn short(s: &str) -> Option<&str> {
    (s.chars().count() <= SHORT).then_some(s)
}

/// A vector for the summary: exact when its rendering is short, else its decimals.
fn vector_summary(exact: &[String], decimals: Option<&[String]>) -> String {
    let full = format!("({})", exact.join(", "));
    if full.chars().count() <= 2 * SHORT {
        return full;
    }
    match decimals {
        Some(d) => format!("≈ ({})", d.join(", ")),
        None => format!("({} coordinates; exact form in --exact)", exact.len()),
    }
}

impl OperatorReport {
    /// A summary of a few short lines: size, barycentric and contractive, the behaviour, the
    /// eigenvalues as decimals (exact when short, with the minimal polynomial only when short),
    /// the fixed point and the tangent. No line carries a long exact form ([`Self::to_text`]
    /// does, and so does the JSON).
    pub fn summary(&self) -> String {
        let mut out = String::new();
        let name = self.name.as_deref().unwrap_or("matrix");
        let n = self
            .fixed_point
            .as_ref()
            .map_or_else(|| self.matrix.split(';').count(), Vec::len);
        let mut flags = vec![format!("{n}×{n}")];
        flags.push(
            if self.barycentric {
                "barycentric"
            } else {
                "not barycentric"
            }
            .into(),
        );
        flags.push(
            if self.contractive {
                "contractive"
            } else {
                "not contractive"
            }
            .into(),
        );
        let detail = match &self.behaviour {
            Behaviour::Tangent { detail, .. }
            | Behaviour::Oscillating { detail }
            | Behaviour::Spiralling { detail }
            | Behaviour::Degenerate { detail } => detail,
        };
        let detail = if detail.chars().count() > 2 * SHORT {
            let cut: String = detail.chars().take(2 * SHORT).collect();
            format!("{cut}…")
        } else {
            detail.clone()
        };
        out += &format!(
            "{name} ({}): {} — {detail}\n",
            flags.join(", "),
            self.behaviour.label()
        );
        let eig: Vec<String> = self
            .eigenvalues
            .iter()
            .map(|e| {
                let mult = if e.multiplicity > 1 {
                    format!(" (×{})", e.multiplicity)
                } else {
                    String::new()
                };
                let value = if e.real {
                    match e.exact.as_deref().and_then(short) {
                        Some(x) if !x.starts_with("root of") => {
                            if e.min_poly.starts_with("x - ")
                                || e.min_poly == "x"
                                || e.min_poly.starts_with("x + ")
                            {
                                x.to_string()
                            } else {
                                format!("{x} ≈ {}", trim_decimal(&e.approx))
                            }
                        }
                        _ => trim_decimal(&e.approx),
                    }
                } else {
                    let (re, im) = e.approx.split_once(" ± ").unwrap_or((&e.approx, ""));
                    format!(
                        "{} ± {}",
                        trim_decimal(re),
                        trim_decimal(im.trim_end_matches(" i")) + "i"
                    )
                };
                let poly = e.min_poly.chars().count();
                let degree = e
                    .min_poly
                    .split(' ')
                    .next()
                    .and_then(|m| m.strip_prefix("x^"))
                    .unwrap_or("1");
                if degree != "1" && degree != "2" && poly <= SHORT {
                    format!("{value}{mult} [root of {}]", e.min_poly)
                } else if degree != "1" && degree != "2" {
                    format!("{value}{mult} [degree {degree}]")
                } else {
                    format!("{value}{mult}")
                }
            })
            .collect();
        out += "  eigenvalues: ";
        let mut line = 15;
        for (i, e) in eig.iter().enumerate() {
            if i > 0 {
                if line + e.chars().count() > 100 {
                    out += ",\n    ";
                    line = 4;
                } else {
                    out += ", ";
                    line += 2;
                }
            }
            out += e;
            line += e.chars().count();
        }
        out += "\n";
        match (&self.fixed_point, &self.fixed_point_note) {
            (Some(p), _) => {
                let dec: Option<Vec<String>> = self.fixed.as_ref().map(|v| {
                    v.iter()
                        .map(|q| format!("{:.6}", q.to_f64().unwrap_or(f64::NAN)))
                        .collect()
                });
                out += &format!("  fixed point: {}\n", vector_summary(p, dec.as_deref()));
            }
            (None, Some(n)) => out += &format!("  fixed point: none ({n})\n"),
            (None, None) => {}
        }
        if let (Some(l1), Some(v)) = (&self.lambda1, &self.tangent) {
            let l1 = match short(l1) {
                Some(x) => x.to_string(),
                None => self
                    .exact
                    .as_ref()
                    .map_or_else(|| "?".into(), |d| trim_decimal(&d.lambda1.decimal(12))),
            };
            let dec: Option<Vec<String>> = self.exact.as_ref().map(|d| {
                d.v1.iter()
                    .map(|x| format!("{:.6}", f64_of(&d.field, x)))
                    .collect()
            });
            out += &format!(
                "  λ1 = {l1}, tangent v1 = {}\n",
                vector_summary(v, dec.as_deref())
            );
        }
        if let Some(a) = self.alpha_approx {
            out += &match self.behaviour.class() {
                // α = 2 ⇔ the finite class, decided exactly (|λ2| = λ1²).
                Some(CurvatureClass::Finite) => "  α = 2 (exact: |λ2| = λ1²)\n".to_string(),
                _ => format!("  α ≈ {a:.6}\n"),
            };
        }
        out
    }

    /// The full rendering: matrix, characteristic polynomial, every eigenvalue with its exact
    /// form and eigenvectors, fixed point, contraction and behaviour (`--exact`).
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        let name = self.name.as_deref().unwrap_or("matrix");
        out += &format!("{name} = {}\n", self.matrix);
        if !self.barycentric {
            out += "  (not barycentric: some column does not sum to 1)\n";
        }
        out += &format!("  characteristic polynomial: {}\n", self.charpoly);
        out += "  eigenvalues:\n";
        for e in &self.eigenvalues {
            let mult = if e.multiplicity > 1 {
                format!(" (multiplicity {})", e.multiplicity)
            } else {
                String::new()
            };
            if e.real {
                out += &format!(
                    "    {} ≈ {}{mult}  [min poly {}]\n",
                    e.exact.as_deref().unwrap_or("?"),
                    e.approx,
                    e.min_poly
                );
                for v in &e.eigenvectors {
                    out += &format!("      eigenvector ({})\n", v.join(", "));
                }
            } else {
                out +=
                    &format!(
                    "    complex pair {}{}{mult}  [min poly {}; approximation, a root within {}]\n",
                    e.exact.as_ref().map_or(String::new(), |x| format!("{x} ≈ ")),
                    e.approx,
                    e.min_poly,
                    e.radius.as_deref().unwrap_or("?")
                );
            }
        }
        match (&self.fixed_point, &self.fixed_point_note) {
            (Some(p), _) => out += &format!("  fixed point: ({})\n", p.join(", ")),
            (None, Some(n)) => out += &format!("  fixed point: none ({n})\n"),
            (None, None) => {}
        }
        out += &format!(
            "  contractive on the barycentric hyperplane: {}\n",
            if self.contractive { "yes" } else { "no" }
        );
        out += &format!("  behaviour: {}", self.behaviour.label());
        match &self.behaviour {
            Behaviour::Tangent { detail, .. }
            | Behaviour::Oscillating { detail }
            | Behaviour::Spiralling { detail }
            | Behaviour::Degenerate { detail } => out += &format!(" — {detail}\n"),
        }
        if let (Some(l1), Some(v)) = (&self.lambda1, &self.tangent) {
            out += &format!("  λ1 = {l1}, tangent v1 = ({})\n", v.join(", "));
        }
        if let Some(a) = self.alpha_approx {
            out += &format!("  α ≈ {a:.6} (floating point, for illustration)\n");
        }
        out
    }
}
