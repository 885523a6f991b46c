//! What `check-mesh` found, as text and as JSON: each check with its failures (counted, and the
//! first few named with triangle and vertex indices and coordinates), the parts with their
//! figures, the expectations compared, and the verdict.

use super::claim::{Claims, PartClaim};
use super::input::Format;
use super::part::{approx, decimal, Part};
use serde::Serialize;
use serde_json::{json, Value};
use std::collections::BTreeMap;

/// The most failures of one check named in full.
pub const MAX_EXAMPLES: usize = 10;

/// One failure, with where it is.
#[derive(Clone, Debug, Serialize)]
pub struct Finding {
    /// What failed (`open edge`, `pinched vertex`, `crossing triangles`, …).
    pub kind: &'static str,
    /// The triangles involved, by index in the file (0-based; for 3MF, in build order).
    pub triangles: Vec<usize>,
    /// The vertices involved, by index in the welded mesh (first appearance in the file).
    pub vertices: Vec<u32>,
    /// The coordinates of those vertices, as in the file.
    pub coordinates: Vec<[f64; 3]>,
    /// The sentence shown.
    pub message: String,
}

/// The failures of one check.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Tally {
    /// How many failures, by kind.
    pub count: BTreeMap<&'static str, u64>,
    /// The first [`MAX_EXAMPLES`] in full.
    pub examples: Vec<Finding>,
}

impl Tally {
    /// Counts a failure of `kind`, building its finding only when it will be shown.
    pub fn add(&mut self, kind: &'static str, f: impl FnOnce() -> Finding) {
        *self.count.entry(kind).or_default() += 1;
        if self.examples.len() < MAX_EXAMPLES {
            self.examples.push(f());
        }
    }

    /// No failure.
    pub fn passed(&self) -> bool {
        self.count.is_empty()
    }

    fn total(&self) -> u64 {
        self.count.values().sum()
    }

    fn summary(&self) -> String {
        let parts: Vec<String> = self
            .count
            .iter()
            .map(|(k, n)| format!("{n} × {k}"))
            .collect();
        parts.join(", ")
    }

    fn lines(&self, out: &mut String) {
        for f in &self.examples {
            *out += &format!("    {}\n", f.message);
        }
        let shown = self.examples.len() as u64;
        if self.total() > shown {
            *out += &format!("    … and {} more\n", self.total() - shown);
        }
    }

    fn json(&self) -> Value {
        json!({ "passed": self.passed(), "count": self.count, "examples": self.examples })
    }
}

/// One expectation (`--expect-euler`, `--expect-parts`, a claim) and what the mesh has.
#[derive(Clone, Debug, Serialize)]
pub struct Expectation {
    /// What is compared (`parts`, `euler`, `triangles`, …) and where the expectation comes from.
    pub what: String,
    /// The expected value.
    pub expected: String,
    /// What the mesh has.
    pub found: String,
    /// Whether they agree.
    pub holds: bool,
}

/// Everything `check-mesh` found.
#[derive(Clone, Debug)]
pub struct Report {
    /// The file's name as given.
    pub file: String,
    /// The format read.
    pub format: Format,
    /// The unit of the coordinates (`mm` for STL).
    pub unit: String,
    /// Triangles in the file.
    pub triangles: usize,
    /// Distinct vertices (by exact coordinates).
    pub vertices: usize,
    /// Degenerate triangles.
    pub degenerate: Tally,
    /// Edges not in exactly two triangles of opposite directions.
    pub edges: Tally,
    /// Pinched vertices; `None` when not checked (the edges failed, so links are not cycles).
    pub links: Option<Tally>,
    /// Crossing triangles.
    pub crossings: Tally,
    /// The pairs of triangles tested for crossing (their bounding boxes meet).
    pub pairs_tested: u64,
    /// Parts enclosing a volume that is not positive (inward or flat).
    pub orientation: Tally,
    /// The parts.
    pub parts: Vec<Part>,
    /// The expectations compared.
    pub expectations: Vec<Expectation>,
    /// Remarks that are not failures.
    pub notes: Vec<String>,
}

/// The unit of a 3MF model as a symbol.
fn unit_symbol(unit: &str) -> &str {
    match unit {
        "millimeter" | "mm" => "mm",
        "micron" => "µm",
        "centimeter" => "cm",
        "inch" => "in",
        "foot" => "ft",
        "meter" => "m",
        other => other,
    }
}

impl Report {
    /// Every edge in two triangles of opposite directions and every vertex link one cycle: the
    /// mesh is a closed oriented 2-manifold (combinatorially).
    pub fn manifold(&self) -> bool {
        self.edges.passed() && self.links.as_ref().is_some_and(Tally::passed)
    }

    /// Every check passes (the mesh is a closed oriented manifold without degenerate or crossing
    /// triangles, each part enclosing a positive volume).
    pub fn checks_pass(&self) -> bool {
        self.manifold()
            && self.degenerate.passed()
            && self.crossings.passed()
            && self.orientation.passed()
    }

    /// Every check passes and every expectation holds: exit 0.
    pub fn passed(&self) -> bool {
        self.checks_pass() && self.expectations.iter().all(|e| e.holds)
    }

    /// The sum of the parts' χ.
    pub fn euler(&self) -> i64 {
        self.parts.iter().map(|p| p.euler).sum()
    }

    /// The sum of the parts' genera, when the mesh is a closed oriented manifold.
    pub fn genus(&self) -> Option<i64> {
        self.parts.iter().map(|p| p.genus).sum()
    }

    /// Compares `--expect-euler`, `--expect-parts` and a claims file with the mesh.
    pub fn compare(&mut self, euler: Option<i64>, parts: Option<u64>, claims: Option<&Claims>) {
        let mut list = Vec::new();
        let mut add = |what: String, expected: String, found: String| {
            let holds = expected == found;
            list.push(Expectation {
                what,
                expected,
                found,
                holds,
            });
        };
        let (n, chi, genus) = (self.parts.len(), self.euler(), self.genus());
        let genus_text = genus.map_or("undefined (not a closed oriented manifold)".into(), |g| {
            g.to_string()
        });
        if let Some(x) = euler {
            add("χ (--expect-euler)".into(), x.to_string(), chi.to_string());
        }
        if let Some(p) = parts {
            add(
                "parts (--expect-parts)".into(),
                p.to_string(),
                n.to_string(),
            );
        }
        let Some(c) = claims else {
            self.expectations.extend(list);
            return;
        };
        add(
            "triangles (claims)".into(),
            c.triangles.to_string(),
            self.triangles.to_string(),
        );
        if let Some(p) = c.parts {
            add("parts (claims)".into(), p.to_string(), n.to_string());
        }
        if let Some(x) = c.euler {
            add("χ (claims)".into(), x.to_string(), chi.to_string());
        }
        if let Some(g) = c.genus {
            add("genus (claims)".into(), g.to_string(), genus_text.clone());
        }
        if let Some(per) = &c.per_part {
            let mut want = per.clone();
            want.sort();
            let show = |v: &[PartClaim]| {
                let s: Vec<String> = v
                    .iter()
                    .map(|p| format!("χ {} genus {}", p.euler, p.genus))
                    .collect();
                format!("[{}]", s.join(", "))
            };
            let found = match self.parts.iter().all(|p| p.genus.is_some()) {
                true => {
                    let mut have: Vec<PartClaim> = self
                        .parts
                        .iter()
                        .map(|p| PartClaim {
                            euler: p.euler,
                            genus: p.genus.unwrap_or_default(),
                        })
                        .collect();
                    have.sort();
                    show(&have)
                }
                false => genus_text,
            };
            add(
                "each part's χ and genus (claims)".into(),
                show(&want),
                found,
            );
        }
        self.expectations.extend(list);
        let base = std::path::Path::new(&self.file)
            .file_name()
            .map(|f| f.to_string_lossy().to_string())
            .unwrap_or_default();
        let named = c.meshes.iter().any(|m| {
            std::path::Path::new(m)
                .file_name()
                .is_some_and(|f| f.to_string_lossy() == base)
        });
        if !named {
            self.notes.push(format!(
                "the claims name {} and this file is `{base}` (a renamed file is still compared)",
                c.meshes
                    .iter()
                    .map(|m| format!("`{m}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    }

    fn volume_text(&self, p: &Part) -> Option<String> {
        let v = p.volume.as_ref()?;
        let (d, exact) = decimal(v, 3);
        let side = match num_traits::Signed::is_positive(v) {
            true => "outward",
            false => "NOT OUTWARD",
        };
        Some(format!(
            "volume {}{d} {}³ ({side})",
            if exact { "" } else { "≈ " },
            unit_symbol(&self.unit)
        ))
    }

    /// The verdict line.
    pub fn verdict(&self) -> String {
        let list =
            |f: &dyn Fn(&Part) -> String| self.parts.iter().map(f).collect::<Vec<_>>().join(" + ");
        let figures = format!(
            "{} part{}, χ {}, genus {}",
            self.parts.len(),
            if self.parts.len() == 1 { "" } else { "s" },
            list(&|p| p.euler.to_string()),
            list(&|p| p.genus.map_or("?".into(), |g| g.to_string()))
        );
        if self.checks_pass() {
            let failed: Vec<&str> = self
                .expectations
                .iter()
                .filter(|e| !e.holds)
                .map(|e| e.what.as_str())
                .collect();
            let head = match self.parts.len() {
                1 => "ONE CLOSED ORIENTED MANIFOLD WITHOUT CROSSINGS",
                _ => "CLOSED ORIENTED MANIFOLDS WITHOUT CROSSINGS",
            };
            return match failed.is_empty() {
                true => format!("verdict: {head}: {figures}\n"),
                false => format!(
                    "verdict: EXPECTATION FAILED ({}): the mesh is {}: {figures}\n",
                    failed.join(", "),
                    head.to_lowercase()
                ),
            };
        }
        let mut failed = Vec::new();
        if !self.degenerate.passed() {
            failed.push("degenerate triangles");
        }
        if !self.edges.passed() {
            failed.push("not closed or not consistently oriented");
        }
        if self.links.as_ref().is_some_and(|l| !l.passed()) {
            failed.push("pinched vertices");
        }
        if !self.crossings.passed() {
            failed.push("crossing triangles");
        }
        if !self.orientation.passed() {
            failed.push("inward parts");
        }
        format!("verdict: FAILED ({}): {figures}\n", failed.join(", "))
    }

    /// The report as text.
    pub fn to_text(&self) -> String {
        let mut out = format!(
            "check-mesh: {} ({}, {} triangles, {} vertices)\n",
            self.file,
            self.format.name(),
            self.triangles,
            self.vertices
        );
        let line = |out: &mut String, ok: &str, name: &str, t: &Tally| match t.passed() {
            true => *out += &format!("  {ok}\n"),
            false => {
                *out += &format!("  {name}: FAILED — {}\n", t.summary());
                t.lines(out);
            }
        };
        line(
            &mut out,
            "triangles: none degenerate (no two equal corners, no three on a line)",
            "triangles",
            &self.degenerate,
        );
        line(
            &mut out,
            "closed: every edge has exactly two triangles, opposite directions",
            "closed",
            &self.edges,
        );
        match &self.links {
            Some(l) => line(
                &mut out,
                "manifold: every vertex link is one cycle",
                "manifold",
                l,
            ),
            None => out += "  manifold: not checked (the edges are not closed and oriented)\n",
        }
        match self.crossings.passed() {
            true => {
                out += &format!(
                    "  no crossings: {} candidate pairs tested exactly\n",
                    self.pairs_tested
                )
            }
            false => {
                out += &format!(
                    "  crossings: FAILED — {} of {} candidate pairs\n",
                    self.crossings.summary(),
                    self.pairs_tested
                );
                self.crossings.lines(&mut out);
            }
        }
        if !self.orientation.passed() {
            out += &format!("  orientation: FAILED — {}\n", self.orientation.summary());
            self.orientation.lines(&mut out);
        }
        out += &format!("  parts {}\n", self.parts.len());
        for (i, p) in self.parts.iter().enumerate() {
            let genus = p.genus.map_or(String::new(), |g| format!("  genus {g}"));
            let volume = self
                .volume_text(p)
                .map_or(String::new(), |v| format!("  {v}"));
            out += &format!(
                "    part {i}: V {}  E {}  F {}  χ {}{genus}{volume}\n",
                p.vertices, p.edges, p.triangles, p.euler
            );
        }
        for e in &self.expectations {
            out += &format!(
                "  expected {}: {}, found {}{}\n",
                e.what,
                e.expected,
                e.found,
                if e.holds { "" } else { " — DIFFERS" }
            );
        }
        for n in &self.notes {
            out += &format!("  note: {n}\n");
        }
        out + &self.verdict()
    }

    /// The report as JSON.
    pub fn to_json(&self) -> Value {
        let parts: Vec<Value> = self
            .parts
            .iter()
            .map(|p| {
                json!({
                    "first_triangle": p.first_triangle,
                    "vertices": p.vertices,
                    "edges": p.edges,
                    "triangles": p.triangles,
                    "euler": p.euler,
                    "genus": p.genus,
                    "volume": p.volume.as_ref().map(|v| decimal(v, 3).0),
                    "volume_approx": p.volume.as_ref().map(approx),
                    "volume_exact": p.volume.as_ref().map(|v| v.to_string()),
                    "outward": p.volume.as_ref().map(num_traits::Signed::is_positive),
                })
            })
            .collect();
        json!({
            "file": self.file,
            "format": self.format.tag(),
            "unit": self.unit,
            "triangles": self.triangles,
            "vertices": self.vertices,
            "checks": {
                "degenerate": self.degenerate.json(),
                "closed": self.edges.json(),
                "manifold": self.links.as_ref().map(Tally::json),
                "crossings": {
                    "pairs_tested": self.pairs_tested,
                    "passed": self.crossings.passed(),
                    "count": self.crossings.count,
                    "examples": self.crossings.examples,
                },
                "orientation": self.orientation.json(),
            },
            "parts": parts,
            "euler": self.euler(),
            "genus": self.genus(),
            "expectations": self.expectations,
            "notes": self.notes,
            "checks_pass": self.checks_pass(),
            "passed": self.passed(),
            "verdict": self.verdict().trim_end().trim_start_matches("verdict: "),
        })
    }
}
