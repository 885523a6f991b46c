//! The independent mesh checker (`lacuna check-mesh`, issue #29): re-checks a printable mesh — a
//! binary or ASCII STL or a 3MF package, lacuna's or anyone's — from the file alone, so that
//! whoever receives a file can verify what its writer claims.
//!
//! **Architecture invariant.** It shares no code with lacuna's mesh writer: it imports nothing of
//! lacuna but [`crate::error`] (the error type and its codes), and reads the files with its own
//! parsers (`stl.rs`; `threemf.rs` over the `zip` and `quick-xml` crates). `tests/architecture.rs`
//! fails on any other path into the crate. It never sees the structure the mesh came from; a
//! claims file ([`Claims`]) is plain data, compared, never trusted.
//!
//! **What is verified**, on the file's own coordinates (STL's `f32`, 3MF's `xs:double` read as the
//! nearest `f64`), exactly: each coordinate is a dyadic rational and every geometric test is an
//! integer computation on them (`exact.rs`: `i128` when the numbers are small enough, big
//! integers otherwise; no floating-point predicate):
//!
//! 1. vertices are identified by exact coordinate equality (`input.rs`);
//! 2. no triangle is degenerate: no two equal corners, no three collinear corners (the exact
//!    normal is not zero) (`incidence.rs`);
//! 3. every undirected edge is in exactly two triangles, which run it in opposite directions:
//!    the surface is closed and consistently oriented (`incidence.rs`);
//! 4. every vertex's link is one cycle: the triangles around it form a single fan, no pinched
//!    vertex (`incidence.rs`; checked when 3 holds);
//! 5. no two triangles cross: triangles meet only in the vertex or edge they share, tested
//!    exactly for every pair whose bounding boxes meet, found through a uniform grid
//!    (`crossing.rs` says exactly what is tested);
//! 6. the parts — connected components through shared edges — with V, E, F, χ = V − E + F, the
//!    genus (2 − χ)/2 when 3 and 4 hold (an orientable closed surface), and the enclosed volume
//!    `Σ det(a, b, c)/6`, exact, which must be positive (triangles counter-clockwise seen from
//!    outside) (`part.rs`).
//!
//! Then the expectations (`--expect-euler`, `--expect-parts`, a claims file) are compared with
//! what was found (`report.rs`).

mod claim;
mod crossing;
mod exact;
mod incidence;
mod input;
mod part;
mod report;
mod stl;
mod threemf;

#[cfg(test)]
mod tests;

pub use self::claim::{Claims, PartClaim, CLAIMS_FORMAT, CLAIMS_VERSION};
pub use self::input::Format;
pub use self::part::Part;
pub use self::report::{Expectation, Finding, Report, Tally, MAX_EXAMPLES};

use self::incidence::{degenerate, finding, links, Edges};
use crate::error::Error;

/// The default `--max-triangles`.
pub const DEFAULT_MAX_TRIANGLES: u64 = 20_000_000;

/// The most triangles `--max-triangles` can allow: indices are `u32`, and a triangle's index
/// carries a direction bit beside it.
pub const MAX_TRIANGLES_CAP: u64 = 1 << 30;

/// What to check the mesh against, and the limit.
#[derive(Clone, Debug)]
pub struct Options {
    /// The most triangles read (checked before the work; E0501, a limit, not a verdict).
    pub max_triangles: u64,
    /// The expected sum of the parts' χ.
    pub expect_euler: Option<i64>,
    /// The expected number of parts.
    pub expect_parts: Option<u64>,
    /// Claims to compare.
    pub claims: Option<Claims>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            max_triangles: DEFAULT_MAX_TRIANGLES,
            expect_euler: None,
            expect_parts: None,
            claims: None,
        }
    }
}

/// Checks a mesh file's bytes (`name` is shown in messages). An error is bad input (a file that
/// is not a mesh, a malformed one, the limit exceeded); a mesh that fails a check is a [`Report`]
/// that does not pass.
pub fn check(bytes: &[u8], name: &str, options: &Options) -> Result<Report, Error> {
    let mesh = input::read(bytes, name, options.max_triangles.min(MAX_TRIANGLES_CAP))?;
    if mesh.triangles.is_empty() {
        return Err(input::malformed(
            "E1501",
            format!("`{name}` holds no triangle: there is nothing to check"),
        ));
    }
    let mut report = Report {
        file: name.to_string(),
        format: mesh.format,
        unit: mesh.unit.clone(),
        triangles: mesh.triangles.len(),
        vertices: mesh.vertices.len(),
        degenerate: Tally::default(),
        edges: Tally::default(),
        links: None,
        crossings: Tally::default(),
        pairs_tested: 0,
        orientation: Tally::default(),
        parts: Vec::new(),
        expectations: Vec::new(),
        notes: mesh.notes.clone(),
    };
    let flat = degenerate(&mesh, &mut report.degenerate);
    let edges = Edges::of(&mesh);
    edges.check(&mesh, &mut report.edges);
    if report.edges.passed() {
        let mut l = Tally::default();
        links(&mesh, &mut l);
        report.links = Some(l);
    }
    report.pairs_tested = crossing::crossings(&mesh, &flat, &mut report.crossings);
    let (of, mut parts) = part::parts(&mesh, &edges);
    drop(edges);
    if report.edges.passed() {
        part::volumes(&mesh, &of, &mut parts);
    }
    let manifold = report.manifold();
    for (i, p) in parts.iter_mut().enumerate() {
        if manifold {
            p.genus = Some((2 - p.euler) / 2);
        }
        if let Some(v) = &p.volume {
            if !num_traits::Signed::is_positive(v) {
                let t = p.first_triangle;
                let tri = mesh.triangles[t];
                report.orientation.add("part not enclosing a positive volume", || {
                    finding(
                        &mesh,
                        "part not enclosing a positive volume",
                        vec![t],
                        tri.to_vec(),
                        format!(
                            "part {i} (from {}) encloses the volume {}: its triangles are not counter-clockwise seen from outside",
                            mesh.triangle_name(t),
                            part::decimal(v, 3).0
                        ),
                    )
                });
            }
        }
    }
    report.parts = parts;
    report.compare(
        options.expect_euler,
        options.expect_parts,
        options.claims.as_ref(),
    );
    Ok(report)
}
