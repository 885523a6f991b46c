//! The age and random choices of a rule (`docs/FORMATS.md`, "Rule files"), for the
//! rule-compilation step: which generator replaces a fertile segment and which state of the
//! compiled automaton that segment opens. Written again from the format's definition; nothing
//! here comes from lacuna's compiler.
//!
//! **States.** A state of the compiled rule is a [`Node`]: a generator; under an age choice, the
//! choice and the age; and, in a rule with random choices, the segment's *place* (the segment
//! indices from the initiator's segment down to it, gaps and drawn segments counted) while the
//! place has fewer than `depth` entries, so that every occurrence down there is a state of its
//! own. Deeper, a node forgets its place and one state serves every occurrence of its generator.
//!
//! **Ages.** The initiator's segments have age 0. A segment flagged with an age choice under a
//! node of the same choice at age `a` has age `a + 1` (modulo the choice's length), or 0 when the
//! flag ends in `!` (a new fractal) or the parent is of another choice or of none. The
//! generator is the choice's entry at that age.
//!
//! **Draws.** A random choice draws entry `h mod n` (n entries), `h` the seed hashed with the
//! segment's place (`h = splitmix64(h ^ x)` for each entry x) while the place has at most
//! `depth` entries; deeper, with `[2^32 − 1, g, j]`, g the parent's generator and j the
//! segment's index, so that each segment of a generator draws once.

use std::collections::HashMap;

/// The most states of occurrences the format allows a rule (lacuna refuses a rule above it, so
/// no honest certificate carries one): `Σ_{d=1}^{depth−1} F0·F^(d−1)`, F0 the initiator's
/// fertile segments and F a generator's most.
pub(super) const MAX_OCCURRENCES: u64 = 4096;

/// The deepest `depth` the format allows.
pub(super) const MAX_DEPTH: usize = 12;

/// The first entry of a place below the depth, `2^32 − 1`.
const BELOW: u64 = (1 << 32) - 1;

/// The generator entry of a place below the depth when the parent is the initiator, `2^32 − 2`.
const UNDER_INITIATOR: u64 = (1 << 32) - 2;

/// What a fertile segment's flag names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Target {
    /// A generator, by index.
    Generator(usize),
    /// An age choice, by index; `restart` for `NAME!`.
    Age { choice: usize, restart: bool },
    /// A random choice, by index.
    Random(usize),
}

/// A state of the compiled rule (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) struct Node {
    /// The generator drawn on the segment.
    pub(super) generator: usize,
    /// The age choice and the age, when the segment was flagged with an age choice.
    pub(super) age: Option<(usize, usize)>,
    /// The segment's place, while occurrences are states of their own.
    pub(super) place: Option<Vec<u64>>,
}

/// A rule's choices, resolved to generator indices.
pub(super) struct Choices {
    /// Each age choice: name and the generator of each age.
    pub(super) ages: Vec<(String, Vec<usize>)>,
    /// Each random choice: name and the generators drawn from.
    pub(super) randoms: Vec<(String, Vec<usize>)>,
    /// `seed N` (0 without the line).
    pub(super) seed: u64,
    /// `depth D` (4 without the line).
    pub(super) depth: usize,
}

/// SplitMix64's output function applied to `z`: add the golden-ratio increment, then two
/// xor-shift-multiply rounds and a final xor-shift. The arithmetic wraps modulo 2^64 by the
/// hash's definition.
pub(super) fn splitmix64(z: u64) -> u64 {
    let z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    let z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Choices {
    /// The hash of a place: the seed, then `h = splitmix64(h ^ x)` for each entry.
    pub(super) fn hash(&self, place: &[u64]) -> u64 {
        place.iter().fold(self.seed, |h, &x| splitmix64(h ^ x))
    }

    /// The generator random choice `choice` draws at `place`.
    fn draw(&self, choice: usize, place: &[u64]) -> usize {
        let entries = &self.randoms[choice].1;
        let n = entries.len() as u64;
        // h mod n < n ≤ the number of entries: the index is in range.
        entries[(self.hash(place) % n) as usize]
    }

    /// The node opened by fertile segment `j` (its index among the path's segments) flagged
    /// `target`, in the path of `parent` (`None`: the initiator's path).
    pub(super) fn child(&self, target: Target, parent: Option<&Node>, j: usize) -> Node {
        let j = j as u64;
        let place = match parent {
            None => Some(vec![j]),
            Some(n) => n.place.as_ref().map(|p| {
                let mut p = p.clone();
                p.push(j);
                p
            }),
        };
        let (generator, age) = match target {
            Target::Generator(g) => (g, None),
            Target::Age { choice, restart } => {
                let entries = &self.ages[choice].1;
                let age = match parent.and_then(|n| n.age) {
                    Some((c, a)) if c == choice && !restart => (a + 1) % entries.len(),
                    _ => 0,
                };
                (entries[age], Some((choice, age)))
            }
            Target::Random(choice) => {
                let g = match &place {
                    Some(p) if p.len() <= self.depth => self.draw(choice, p),
                    _ => {
                        let holder = parent.map_or(UNDER_INITIATOR, |n| n.generator as u64);
                        self.draw(choice, &[BELOW, holder, j])
                    }
                };
                (g, None)
            }
        };
        let place = place.filter(|p| !self.randoms.is_empty() && p.len() < self.depth);
        Node {
            generator,
            age,
            place,
        }
    }

    /// The bound of the format on the states of occurrences, `Σ_{d=1}^{depth−1} F0·F^(d−1)`
    /// (`initiator`: F0, `most`: F); 0 without random choices. An error above
    /// [`MAX_OCCURRENCES`]: lacuna compiles no such rule.
    pub(super) fn occurrences(&self, initiator: u64, most: u64) -> Result<u64, String> {
        if self.randoms.is_empty() {
            return Ok(0);
        }
        let (mut level, mut total) = (initiator, 0u64);
        for _ in 1..self.depth {
            total = total.saturating_add(level);
            level = level.saturating_mul(most);
        }
        match total <= MAX_OCCURRENCES {
            true => Ok(total),
            false => Err(format!(
                "random choices drawn per occurrence down to depth {} make up to {total} \
                 states, above the format's {MAX_OCCURRENCES}",
                self.depth
            )),
        }
    }

    /// A node's state name: the generator's, then `.NAMEa` for age a of choice NAME, then
    /// `.atI_J_…` for its place.
    pub(super) fn name(&self, node: &Node, generators: &[String]) -> String {
        let mut s = generators[node.generator].clone();
        if let Some((c, a)) = node.age {
            s += &format!(".{}{a}", self.ages[c].0);
        }
        if let Some(p) = &node.place {
            let p: Vec<String> = p.iter().map(u64::to_string).collect();
            s += &format!(".at{}", p.join("_"));
        }
        s
    }
}

/// Nodes numbered in the order they are first met.
#[derive(Default)]
pub(super) struct Order {
    pub(super) nodes: Vec<Node>,
    index: HashMap<Node, usize>,
}

impl Order {
    /// The node's number, numbering it when new.
    pub(super) fn number(&mut self, n: &Node) -> usize {
        if let Some(&i) = self.index.get(n) {
            return i;
        }
        self.index.insert(n.clone(), self.nodes.len());
        self.nodes.push(n.clone());
        self.nodes.len() - 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_matches_its_reference_output() {
        // SplitMix64 seeded with 0 (Vigna's splitmix64.c) first returns 0xE220A8397B1DCDAF: the
        // increment added to 0, then mixed — this function at 0.
        assert_eq!(splitmix64(0), 0xE220_A839_7B1D_CDAF);
    }

    #[test]
    fn ages_advance_restart_and_reset() {
        // `age t a b` (generators a = 0, b = 1) and a second choice `u a`.
        let c = Choices {
            ages: vec![("t".into(), vec![0, 1]), ("u".into(), vec![0])],
            randoms: Vec::new(),
            seed: 0,
            depth: 4,
        };
        let t = |restart| Target::Age { choice: 0, restart };
        let at = |g, a| Node {
            generator: g,
            age: Some((0, a)),
            place: None,
        };
        // From the initiator: age 0, a.
        assert_eq!(c.child(t(false), None, 3), at(0, 0));
        // Under age 0: age 1, b; under age 1: age 2 mod 2 = 0, a.
        assert_eq!(c.child(t(false), Some(&at(0, 0)), 0), at(1, 1));
        assert_eq!(c.child(t(false), Some(&at(1, 1)), 0), at(0, 0));
        // `t!` restarts at 0; a parent of the other choice starts at 0 too.
        assert_eq!(c.child(t(true), Some(&at(1, 1)), 0), at(0, 0));
        let under_u = Node {
            generator: 0,
            age: Some((1, 0)),
            place: None,
        };
        assert_eq!(c.child(t(false), Some(&under_u), 1), at(0, 0));
        assert_eq!(c.name(&at(1, 1), &["a".into(), "b".into()]), "b.t1");
    }

    #[test]
    fn the_bound_on_occurrences_is_the_formats() {
        // One initiator segment, four fertile segments per generator, depth 12:
        // 1 + 4 + … + 4^10 = (4^11 − 1)/3 = 1398101 > 4096.
        let mut c = Choices {
            ages: Vec::new(),
            randoms: vec![("r".into(), vec![0])],
            seed: 0,
            depth: 12,
        };
        assert!(c.occurrences(1, 4).unwrap_err().contains("1398101"));
        // Depth 7: 1 + 4 + 16 + 64 + 256 + 1024 = 1365.
        c.depth = 7;
        assert_eq!(c.occurrences(1, 4), Ok(1365));
    }
}
