//! Subdivision algorithms as spoke rules (THEORY §3).
//!
//! A spoke rule is a predicate on a junction: its kind and the two boundary edges around it. The
//! built-ins `A1`, `A2`, `A3` are spoke sets; a user writes any other set inline as
//! `{joint gap corner(C,B)}` or names one in an assembly file. A fully custom algorithm implements
//! [`SpokeChooser`], the same interface the spoke sets implement.

use crate::error::{Error, Result, Span};
use crate::topology::edge::{EdgeKind, EdgeType, JunctionKind};
use std::collections::BTreeSet;
use std::fmt;
use std::sync::Arc;

/// A junction of a subdivided boundary, as a spoke rule sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Junction {
    /// Joint, gap or corner.
    pub kind: JunctionKind,
    /// The boundary edge (before subdivision) the junction follows, counter-clockwise.
    pub before: EdgeType,
    /// The boundary edge the junction precedes (the same edge for joints and gaps).
    pub after: EdgeType,
}

/// A pattern on an edge type, used by `corner(P,Q)` items.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EdgePattern {
    /// `*`: any edge.
    Any,
    /// `B` or `C`: any edge of that kind, delayed or not.
    Kind(EdgeKind),
    /// An exact edge type such as `C2` or `B3^2`.
    Exact(EdgeType),
}

impl EdgePattern {
    fn matches(&self, e: &EdgeType) -> bool {
        match self {
            EdgePattern::Any => true,
            EdgePattern::Kind(k) => e.kind == *k,
            EdgePattern::Exact(t) => t == e,
        }
    }
}

/// One item of a spoke set.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SpokeItem {
    /// `joint`: every joint.
    Joint,
    /// `gap`: every gap.
    Gap,
    /// `corner`: every corner.
    Corner,
    /// `delayed-corner`: every corner where at least one of the two edges is delayed.
    DelayedCorner,
    /// `corner(P,Q)`: corners from an edge matching P to an edge matching Q (counter-clockwise).
    CornerBetween(EdgePattern, EdgePattern),
    /// `delayed-corner-not-b`: every corner where at least one of the two edges is delayed and
    /// neither is a non-delayed `Bn` (a delayed edge stays merged with its non-delayed Bézier
    /// neighbours, as in AutoFrac2D's algorithm 1 "surround delay and Bézier").
    DelayedCornerNotB,
}

impl SpokeItem {
    fn holds(&self, j: &Junction) -> bool {
        match (self, j.kind) {
            (SpokeItem::Joint, JunctionKind::Joint) | (SpokeItem::Gap, JunctionKind::Gap) => true,
            (SpokeItem::Corner, JunctionKind::Corner) => true,
            (SpokeItem::DelayedCorner, JunctionKind::Corner) => {
                j.before.is_delayed() || j.after.is_delayed()
            }
            (SpokeItem::CornerBetween(p, q), JunctionKind::Corner) => {
                p.matches(&j.before) && q.matches(&j.after)
            }
            (SpokeItem::DelayedCornerNotB, JunctionKind::Corner) => {
                let plain_b = |e: &EdgeType| e.kind == EdgeKind::B && !e.is_delayed();
                (j.before.is_delayed() || j.after.is_delayed())
                    && !plain_b(&j.before)
                    && !plain_b(&j.after)
            }
            _ => false,
        }
    }
}

/// The interface every subdivision algorithm implements: given the junctions of a subdivided
/// non-delayed face (in counter-clockwise order), say which are spokes.
pub trait SpokeChooser: fmt::Debug + Send + Sync {
    /// A short name, unique among algorithms (it is part of a face type's identity).
    fn name(&self) -> String;
    /// For each junction, whether an adjacency edge runs from it to the central lacuna.
    fn spokes(&self, junctions: &[Junction]) -> Vec<bool>;
}

/// The built-in spoke sets by name; each lists distinct items. A1 = {joint, gap}, A2 = A1 +
/// corner, A3 = A1 + delayed-corner, AF1 = A1 + delayed-corner-not-b.
const BUILTINS: [(&str, &[SpokeItem]); 4] = [
    ("A1", &[SpokeItem::Joint, SpokeItem::Gap]),
    ("A2", &[SpokeItem::Joint, SpokeItem::Gap, SpokeItem::Corner]),
    (
        "A3",
        &[SpokeItem::Joint, SpokeItem::Gap, SpokeItem::DelayedCorner],
    ),
    (
        "AF1",
        &[
            SpokeItem::Joint,
            SpokeItem::Gap,
            SpokeItem::DelayedCornerNotB,
        ],
    ),
];

/// A subdivision algorithm: a set of spoke items (the built-ins are such sets), or a custom
/// [`SpokeChooser`].
#[derive(Clone, Debug)]
pub enum Algorithm {
    /// A spoke set; A1 = {joint, gap}, A2 = A1 + corner, A3 = A1 + delayed-corner,
    /// AF1 = A1 + delayed-corner-not-b. Shared: every sub-face of a closure carries its parent's
    /// algorithm, so a clone is a reference count, not a new set.
    Spokes(Arc<BTreeSet<SpokeItem>>),
    /// A custom algorithm, identified by its name.
    Custom(Arc<dyn SpokeChooser>),
}

impl Algorithm {
    /// The spoke set `items`.
    pub fn spoke_set(items: BTreeSet<SpokeItem>) -> Self {
        Algorithm::Spokes(Arc::new(items))
    }

    /// `A1`: spokes at every joint and gap.
    pub fn a1() -> Self {
        Self::builtin(0)
    }
    /// `A2`: A1 plus every corner.
    pub fn a2() -> Self {
        Self::builtin(1)
    }
    /// `A3`: A1 plus every corner next to a delayed edge.
    pub fn a3() -> Self {
        Self::builtin(2)
    }

    /// `AF1`, AutoFrac2D's algorithm 1 ("surround delay and Bézier"): A1 plus every corner where
    /// at least one of the two edges is delayed and neither is a non-delayed `Bn`. A delayed edge
    /// thus forms one sub-face with the last piece of a Bézier edge before it and the first piece
    /// of a Bézier edge after it; next to a Cantor or another delayed edge it is cut off. Without
    /// delayed edges AF1 = A1.
    pub fn af1() -> Self {
        Self::builtin(3)
    }

    /// The `k`-th entry of [`BUILTINS`] as an algorithm.
    fn builtin(k: usize) -> Self {
        Algorithm::spoke_set(BUILTINS[k].1.iter().copied().collect())
    }

    /// The built-in name (`A1`, `A2`, `A3`, `AF1`) if this is one of them. Compared item by item
    /// against [`BUILTINS`], without building the sets: every face's name asks this, and a wide
    /// closure names some 10⁵ sub-faces.
    pub fn builtin_name(&self) -> Option<&'static str> {
        let Algorithm::Spokes(items) = self else {
            return None;
        };
        BUILTINS
            .iter()
            .find(|(_, b)| items.len() == b.len() && b.iter().all(|i| items.contains(i)))
            .map(|&(n, _)| n)
    }

    /// True for the spoke sets whose closure the tool can bound in advance (A1, A2, A3, AF1).
    pub fn is_builtin(&self) -> bool {
        self.builtin_name().is_some()
    }

    /// The spoke flags for the junctions of a non-delayed face.
    pub fn spokes(&self, junctions: &[Junction]) -> Vec<bool> {
        match self {
            Algorithm::Spokes(items) => junctions
                .iter()
                .map(|j| items.iter().any(|i| i.holds(j)))
                .collect(),
            Algorithm::Custom(c) => c.spokes(junctions),
        }
    }

    /// Parses an algorithm field: `A1`, `A2`, `A3`, an inline set `{joint gap corner(C,B)}`, or a
    /// name defined in `named`. `col` is the 1-based column of the field's first character.
    pub fn parse(text: &str, col: usize, named: &[(String, Algorithm)]) -> Result<Algorithm> {
        let err = |code, msg: String, c: usize, l: usize| {
            Err(Error::syntax(
                code,
                msg,
                Span {
                    line: 1,
                    col: c,
                    len: l.max(1),
                },
                None,
            ))
        };
        match text {
            "A1" => return Ok(Self::a1()),
            "A2" => return Ok(Self::a2()),
            "A3" => return Ok(Self::a3()),
            "AF1" => return Ok(Self::af1()),
            _ => {}
        }
        if let Some((_, a)) = named.iter().find(|(n, _)| n == text) {
            return Ok(a.clone());
        }
        let Some(inner) = text.strip_prefix('{') else {
            return err(
                "E0108",
                format!("unknown algorithm `{text}` (expected A1, A2, A3, AF1, a defined rule name, or a spoke set like {{joint gap corner(C,B)}})"),
                col,
                text.chars().count(),
            );
        };
        let Some(inner) = inner.strip_suffix('}') else {
            return err(
                "E0109",
                "spoke set is not closed by `}`".into(),
                col,
                text.chars().count(),
            );
        };
        let mut items = BTreeSet::new();
        // Items are separated by spaces or commas outside parentheses.
        let mut start = 0usize;
        let mut depth = 0i32;
        let bytes: Vec<(usize, char)> = inner.char_indices().collect();
        let mut pieces: Vec<(usize, &str)> = Vec::new();
        for (k, &(i, ch)) in bytes.iter().enumerate() {
            match ch {
                '(' => depth += 1,
                ')' => depth -= 1,
                _ => {}
            }
            let sep = depth == 0 && (ch == ' ' || ch == ',' || ch == '\t');
            if sep {
                if i > start {
                    pieces.push((start, &inner[start..i]));
                }
                start = i + ch.len_utf8();
            }
            if k + 1 == bytes.len() && start < inner.len() {
                pieces.push((start, &inner[start..]));
            }
        }
        for (off, item) in pieces {
            let icol = col + 1 + inner[..off].chars().count();
            items.insert(parse_item(item, icol)?);
        }
        if items.is_empty() {
            return err(
                "E0109",
                "empty spoke set: no junction could get a spoke".into(),
                col,
                text.chars().count(),
            );
        }
        Ok(Algorithm::spoke_set(items))
    }
}

fn parse_item(item: &str, col: usize) -> Result<SpokeItem> {
    let bad = |msg: String| {
        Err(Error::syntax(
            "E0109",
            msg,
            Span {
                line: 1,
                col,
                len: item.chars().count().max(1),
            },
            None,
        ))
    };
    match item {
        "joint" => Ok(SpokeItem::Joint),
        "gap" => Ok(SpokeItem::Gap),
        "corner" => Ok(SpokeItem::Corner),
        "delayed-corner" => Ok(SpokeItem::DelayedCorner),
        "delayed-corner-not-b" => Ok(SpokeItem::DelayedCornerNotB),
        _ => {
            let Some(args) = item
                .strip_prefix("corner(")
                .and_then(|r| r.strip_suffix(')'))
            else {
                return bad(format!(
                    "unknown spoke item `{item}` (expected joint, gap, corner, delayed-corner, delayed-corner-not-b or corner(P,Q))"
                ));
            };
            let Some((p, q)) = args.split_once(',') else {
                return bad(format!("`{item}`: corner(P,Q) takes two edge patterns"));
            };
            let pcol = col + "corner(".len();
            let qcol = pcol + p.chars().count() + 1;
            Ok(SpokeItem::CornerBetween(
                parse_pattern(p.trim(), pcol)?,
                parse_pattern(q.trim(), qcol)?,
            ))
        }
    }
}

fn parse_pattern(p: &str, col: usize) -> Result<EdgePattern> {
    match p {
        "*" => Ok(EdgePattern::Any),
        "B" => Ok(EdgePattern::Kind(EdgeKind::B)),
        "C" => Ok(EdgePattern::Kind(EdgeKind::C)),
        _ => EdgeType::parse(p, col).map(EdgePattern::Exact),
    }
}

impl PartialEq for Algorithm {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (Algorithm::Spokes(a), Algorithm::Spokes(b)) => a == b,
            (Algorithm::Custom(a), Algorithm::Custom(b)) => a.name() == b.name(),
            _ => false,
        }
    }
}
impl Eq for Algorithm {}

impl std::hash::Hash for Algorithm {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        match self {
            Algorithm::Spokes(s) => s.hash(state),
            Algorithm::Custom(c) => c.name().hash(state),
        }
    }
}

impl fmt::Display for EdgePattern {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EdgePattern::Any => f.write_str("*"),
            EdgePattern::Kind(k) => write!(f, "{k}"),
            EdgePattern::Exact(t) => write!(f, "{t}"),
        }
    }
}

impl fmt::Display for SpokeItem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpokeItem::Joint => f.write_str("joint"),
            SpokeItem::Gap => f.write_str("gap"),
            SpokeItem::Corner => f.write_str("corner"),
            SpokeItem::DelayedCorner => f.write_str("delayed-corner"),
            SpokeItem::DelayedCornerNotB => f.write_str("delayed-corner-not-b"),
            SpokeItem::CornerBetween(p, q) => write!(f, "corner({p},{q})"),
        }
    }
}

impl fmt::Display for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(n) = self.builtin_name() {
            return f.write_str(n);
        }
        match self {
            Algorithm::Spokes(items) => {
                let parts: Vec<String> = items.iter().map(|i| i.to_string()).collect();
                write!(f, "{{{}}}", parts.join(" "))
            }
            Algorithm::Custom(c) => f.write_str(&c.name()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(s: &str) -> EdgeType {
        EdgeType::parse(s, 1).unwrap()
    }

    #[test]
    fn builtins_parse_and_print() {
        for n in ["A1", "A2", "A3", "AF1"] {
            assert_eq!(Algorithm::parse(n, 1, &[]).unwrap().to_string(), n);
        }
        // A spoke set equal to a built-in is that built-in.
        assert_eq!(
            Algorithm::parse("{gap,joint}", 1, &[]).unwrap().to_string(),
            "A1"
        );
        let a = Algorithm::parse("{joint corner(C,B2)  gap}", 1, &[]).unwrap();
        assert_eq!(a.to_string(), "{joint gap corner(C,B2)}");
        // A subset or a superset of a built-in is not it: {joint} and {joint gap corner
        // delayed-corner} (A2 and A3 together) have no name; A2 with corner replaced is A3.
        for (text, name) in [
            ("{joint}", None),
            ("{joint gap corner delayed-corner}", None),
            ("{gap joint delayed-corner}", Some("A3")),
            ("{delayed-corner-not-b joint gap}", Some("AF1")),
            ("{corner gap joint}", Some("A2")),
        ] {
            let a = Algorithm::parse(text, 1, &[]).unwrap();
            assert_eq!(a.builtin_name(), name, "{text}");
        }
    }

    #[test]
    fn rules_decide_junctions_as_the_spec_says() {
        let corner = |a: &str, b: &str| Junction {
            kind: JunctionKind::Corner,
            before: t(a),
            after: t(b),
        };
        let plain = corner("C2", "B2");
        let delayed = corner("C2^2", "B2");
        let a1 = Algorithm::a1();
        let a2 = Algorithm::a2();
        let a3 = Algorithm::a3();
        assert_eq!(a1.spokes(&[plain, delayed]), vec![false, false]);
        assert_eq!(a2.spokes(&[plain, delayed]), vec![true, true]);
        assert_eq!(a3.spokes(&[plain, delayed]), vec![false, true]);
        let custom = Algorithm::parse("{corner(C,B)}", 1, &[]).unwrap();
        assert_eq!(
            custom.spokes(&[plain, corner("B2", "C2")]),
            vec![true, false]
        );
    }

    #[test]
    fn af1_keeps_delayed_edges_with_plain_bezier_neighbours() {
        let corner = |a: &str, b: &str| Junction {
            kind: JunctionKind::Corner,
            before: t(a),
            after: t(b),
        };
        let af1 = Algorithm::af1();
        let js = [
            corner("B2", "C2^2"),   // a plain Bn next to the delayed edge: merged
            corner("C2^2", "B3"),   // idem, after it
            corner("C2", "C2^2"),   // a Cantor neighbour: cut off
            corner("B2^2", "C3^3"), // two delayed edges: cut off
            corner("B2^2", "C2"),   // a delayed Bn is not a plain Bn: cut off
            corner("B2", "C2"),     // no delay: as A1
        ];
        assert_eq!(af1.spokes(&js), vec![false, false, true, true, true, false]);
        assert_eq!(Algorithm::parse("AF1", 1, &[]).unwrap(), af1);
        assert_eq!(
            Algorithm::parse("{joint gap delayed-corner-not-b}", 1, &[])
                .unwrap()
                .to_string(),
            "AF1"
        );
    }

    #[test]
    fn bad_rules_have_codes() {
        assert_eq!(Algorithm::parse("A4", 1, &[]).unwrap_err().code(), "E0108");
        assert_eq!(
            Algorithm::parse("{joint", 1, &[]).unwrap_err().code(),
            "E0109"
        );
        assert_eq!(Algorithm::parse("{}", 1, &[]).unwrap_err().code(), "E0109");
        assert_eq!(
            Algorithm::parse("{elbow}", 1, &[]).unwrap_err().code(),
            "E0109"
        );
        let e = Algorithm::parse("{joint corner(X,B)}", 10, &[]).unwrap_err();
        assert_eq!(e.code(), "E0103");
        assert_eq!(e.span().unwrap().col, 10 + 1 + 6 + 7);
    }
}
