//! The operator analysis on the command line: matrix and number arguments (E0901) and the
//! human-readable report.

use super::*;

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

impl OperatorReport {
    /// A human-readable rendering: eigenvalues, fixed point, contraction and behaviour.
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
