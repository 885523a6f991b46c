//! Compact storage for the numbers of a [`super::SolutionSpace`].
//!
//! The BC-IFS systems have millions of unknowns, and nearly all of their values are small
//! fractions. A `BigRational` is 64 bytes even when it holds `1/2`. A million-unknown solution
//! stored that way is about 200 MB of fresh memory, and writing it cost as much as the whole
//! presolve (issue #34). Here a value takes one machine word, a numerator that fits an `i32` and
//! a denominator that fits a `u32`; the few that do not fit are kept in a side vector. Each read
//! builds a `BigRational`. One word rather than two halves the fresh memory a large solution
//! space is written to: a million-unknown space is mostly its particular solution and its
//! directions, and the kernel maps and clears each new page of them.
//!
//! Both types serialise as before: `particular` as a list of strings, `basis` as a list of lists
//! of `(unknown, string)`.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use serde::{de::Error, Deserialize, Deserializer, Serialize, Serializer};
use std::fmt::Write as _;
use std::ops::Range;

/// A sequence of exact rationals. A value is stored in one word, `n/d` with `n: i32` and
/// `d: u32`, when it fits. Any other value is stored in full beside them. The storage is
/// canonical: equal sequences compare equal.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Rationals {
    /// `(n, d)`. With `d > 0` the value is `n/d`, reduced. With `d == 0`, `n` is an index into
    /// `big`.
    words: Vec<(i32, u32)>,
    /// The values that do not fit a word, in order.
    big: Vec<BigRational>,
}

impl Rationals {
    /// An empty sequence with room for `n` values.
    pub fn with_capacity(n: usize) -> Rationals {
        Rationals {
            words: Vec::with_capacity(n),
            big: vec![],
        }
    }

    /// Number of values.
    pub fn len(&self) -> usize {
        self.words.len()
    }

    /// Whether there are no values.
    pub fn is_empty(&self) -> bool {
        self.words.is_empty()
    }

    /// Appends a value.
    pub fn push(&mut self, r: &BigRational) {
        match (r.numer().to_i32(), r.denom().to_u32()) {
            (Some(n), Some(d)) => self.words.push((n, d)),
            _ => self.push_big(r.clone()),
        }
    }

    /// Appends `n/d`. The caller guarantees `d > 0` and `gcd(n, d) = 1`.
    pub(crate) fn push_small(&mut self, n: i64, d: u64) {
        debug_assert!(d > 0);
        match (i32::try_from(n), u32::try_from(d)) {
            (Ok(n), Ok(d)) => self.words.push((n, d)),
            _ => self.push_big(BigRational::new_raw(BigInt::from(n), BigInt::from(d))),
        }
    }

    /// Appends a value that does not fit a word.
    fn push_big(&mut self, r: BigRational) {
        let k = i32::try_from(self.big.len()).expect("fewer than 2^31 values stored aside");
        self.words.push((k, 0));
        self.big.push(r);
    }

    /// The value at `i`.
    ///
    /// # Panics
    /// If `i ≥ len()`.
    pub fn get(&self, i: usize) -> BigRational {
        match self.words[i] {
            (k, 0) => self.big[k as usize].clone(),
            (n, d) => BigRational::new_raw(BigInt::from(n), BigInt::from(d)),
        }
    }

    /// Whether the value at `i` is 0, without building it. A stored-aside value is never 0.
    ///
    /// # Panics
    /// If `i ≥ len()`.
    pub fn is_zero_at(&self, i: usize) -> bool {
        matches!(self.words[i], (0, d) if d > 0)
    }

    /// The values, in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = BigRational> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }

    /// The values at the indices of `r`.
    ///
    /// # Panics
    /// If `r` reaches past `len()`.
    pub fn range(&self, r: Range<usize>) -> Vec<BigRational> {
        r.map(|i| self.get(i)).collect()
    }

    /// All values.
    pub fn to_vec(&self) -> Vec<BigRational> {
        self.iter().collect()
    }

    /// The value at `i` as text, the same as `BigRational`'s `Display`.
    fn write(&self, i: usize, out: &mut String) {
        match self.words[i] {
            (k, 0) => write!(out, "{}", self.big[k as usize]),
            (n, 1) => write!(out, "{n}"),
            (n, d) => write!(out, "{n}/{d}"),
        }
        .expect("writing to a String");
    }

    /// The value at `i` as text.
    ///
    /// # Panics
    /// If `i ≥ len()`.
    pub fn text(&self, i: usize) -> String {
        let mut s = String::new();
        self.write(i, &mut s);
        s
    }
}

impl<'a> FromIterator<&'a BigRational> for Rationals {
    fn from_iter<I: IntoIterator<Item = &'a BigRational>>(iter: I) -> Rationals {
        let mut out = Rationals::default();
        iter.into_iter().for_each(|r| out.push(r));
        out
    }
}

impl FromIterator<BigRational> for Rationals {
    fn from_iter<I: IntoIterator<Item = BigRational>>(iter: I) -> Rationals {
        let mut out = Rationals::default();
        iter.into_iter().for_each(|r| out.push(&r));
        out
    }
}

impl Serialize for Rationals {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq((0..self.len()).map(|i| self.text(i)))
    }
}

impl<'de> Deserialize<'de> for Rationals {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Rationals, D::Error> {
        let raw = Vec::<String>::deserialize(d)?;
        let mut out = Rationals::with_capacity(raw.len());
        for s in raw {
            out.push(&s.parse::<BigRational>().map_err(D::Error::custom)?);
        }
        Ok(out)
    }
}

/// The directions of a solution space, each a sparse vector of `(unknown, coefficient)` sorted
/// by unknown. All directions share one array of unknowns and one of coefficients, so there is
/// no allocation per direction.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Directions {
    /// Direction `k` is entries `start[k]..start[k + 1]`; `start[0] = 0`.
    start: Vec<usize>,
    unknowns: Vec<usize>,
    coefs: Rationals,
}

impl Default for Directions {
    fn default() -> Directions {
        Directions::with_capacity(0, 0)
    }
}

impl Directions {
    /// No directions, with room for `dirs` directions of `entries` entries in all.
    pub fn with_capacity(dirs: usize, entries: usize) -> Directions {
        let mut start = Vec::with_capacity(dirs + 1);
        start.push(0);
        Directions {
            start,
            unknowns: Vec::with_capacity(entries),
            coefs: Rationals::with_capacity(entries),
        }
    }

    /// Number of directions.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// Whether there are no directions.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of entries over all directions.
    pub fn entries(&self) -> usize {
        self.unknowns.len()
    }

    /// Direction `k`.
    ///
    /// # Panics
    /// If `k ≥ len()`.
    pub fn get(&self, k: usize) -> Direction<'_> {
        let r = self.start[k]..self.start[k + 1];
        Direction {
            unknowns: &self.unknowns[r.clone()],
            coefs: &self.coefs,
            offset: r.start,
        }
    }

    /// The directions, in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Direction<'_>> + '_ {
        (0..self.len()).map(|k| self.get(k))
    }

    /// Appends a direction given as `(unknown, coefficient)` pairs. The caller keeps them sorted
    /// by unknown ([`super::SolutionSpace::check`] rejects them otherwise).
    pub fn push<I: IntoIterator<Item = (usize, BigRational)>>(&mut self, v: I) {
        for (x, c) in v {
            self.entry(x).push(&c);
        }
        self.close();
    }

    /// Starts an entry of unknown `x` in the direction being built (ended by
    /// [`Directions::close`]); the caller pushes its one coefficient into the returned store.
    pub(crate) fn entry(&mut self, x: usize) -> &mut Rationals {
        self.unknowns.push(x);
        &mut self.coefs
    }

    /// Ends the direction being built.
    pub(crate) fn close(&mut self) {
        self.start.push(self.unknowns.len());
    }

    /// Every direction as a vector of `(unknown, coefficient)`.
    pub fn to_vecs(&self) -> Vec<Vec<(usize, BigRational)>> {
        self.iter().map(|d| d.to_vec()).collect()
    }
}

impl FromIterator<Vec<(usize, BigRational)>> for Directions {
    fn from_iter<I: IntoIterator<Item = Vec<(usize, BigRational)>>>(iter: I) -> Directions {
        let mut out = Directions::default();
        iter.into_iter().for_each(|v| out.push(v));
        out
    }
}

impl Serialize for Directions {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.iter().map(|d| {
            (0..d.len())
                .map(|j| (d.unknowns[j], d.text(j)))
                .collect::<Vec<_>>()
        }))
    }
}

impl<'de> Deserialize<'de> for Directions {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Directions, D::Error> {
        let raw = Vec::<Vec<(usize, String)>>::deserialize(d)?;
        let mut out = Directions::default();
        for dir in raw {
            for (x, s) in dir {
                out.entry(x)
                    .push(&s.parse::<BigRational>().map_err(D::Error::custom)?);
            }
            out.close();
        }
        Ok(out)
    }
}

/// One direction of [`Directions`]: its unknowns (a slice) and their coefficients.
#[derive(Clone, Copy, Debug)]
pub struct Direction<'a> {
    unknowns: &'a [usize],
    coefs: &'a Rationals,
    offset: usize,
}

impl<'a> Direction<'a> {
    /// Number of entries.
    pub fn len(&self) -> usize {
        self.unknowns.len()
    }

    /// Whether the direction has no entry.
    pub fn is_empty(&self) -> bool {
        self.unknowns.is_empty()
    }

    /// The unknowns of the entries, in stored order (sorted by unknown).
    pub fn unknowns(&self) -> &'a [usize] {
        self.unknowns
    }

    /// The coefficient of entry `j`.
    ///
    /// # Panics
    /// If `j ≥ len()`.
    pub fn coef(&self, j: usize) -> BigRational {
        self.coefs.get(self.offset + j)
    }

    /// Whether the coefficient of entry `j` is 0.
    pub fn is_zero_at(&self, j: usize) -> bool {
        self.coefs.is_zero_at(self.offset + j)
    }

    /// The coefficient of entry `j` as text.
    pub fn text(&self, j: usize) -> String {
        self.coefs.text(self.offset + j)
    }

    /// The coefficient of unknown `x`: 0 when `x` has no entry. Found by binary search, so the
    /// entries must be sorted.
    pub fn at(&self, x: usize) -> BigRational {
        self.unknowns
            .binary_search(&x)
            .map_or_else(|_| BigRational::zero(), |j| self.coef(j))
    }

    /// The `(unknown, coefficient)` entries.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = (usize, BigRational)> + 'a {
        let this = *self;
        (0..this.len()).map(move |j| (this.unknowns[j], this.coef(j)))
    }

    /// The entries as a vector.
    pub fn to_vec(&self) -> Vec<(usize, BigRational)> {
        self.iter().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn big(s: &str) -> BigRational {
        s.parse().expect("rational")
    }

    /// Numerators and denominators around the edges of the one-word form and of the solver's
    /// two-word numbers.
    fn value() -> impl Strategy<Value = BigRational> {
        let n = prop_oneof![
            -5i128..5,
            Just(i32::MIN as i128),
            Just(i32::MAX as i128),
            Just(i32::MIN as i128 - 1),
            Just(i32::MAX as i128 + 1),
            any::<i32>().prop_map(|v| v as i128),
            Just(i64::MIN as i128),
            Just(i64::MAX as i128),
            Just(i64::MIN as i128 - 1),
            Just(i64::MAX as i128 + 1),
            any::<i64>().prop_map(|v| v as i128),
            any::<i128>(),
        ];
        let d = prop_oneof![
            1u128..5,
            Just(u32::MAX as u128),
            Just(u32::MAX as u128 + 1),
            any::<u32>().prop_map(|v| v as u128 + 1),
            Just(u64::MAX as u128),
            Just(u64::MAX as u128 + 1),
            any::<u64>().prop_map(|v| v as u128 + 1),
            1u128..u128::MAX,
        ];
        (n, d).prop_map(|(n, d)| BigRational::new(BigInt::from(n), BigInt::from(d)))
    }

    proptest! {
        /// Every value reads back as written, prints as `BigRational` prints it, and survives
        /// serde; the one-word form is used exactly when the value fits it.
        #[test]
        fn rationals_read_back_what_was_written(vals in proptest::collection::vec(value(), 0..12)) {
            let r: Rationals = vals.iter().collect();
            prop_assert_eq!(r.len(), vals.len());
            prop_assert_eq!(r.to_vec(), vals.clone());
            for (i, v) in vals.iter().enumerate() {
                prop_assert_eq!(r.text(i), v.to_string());
                prop_assert_eq!(r.is_zero_at(i), v.is_zero());
                let fits = v.numer().to_i32().is_some() && v.denom().to_u32().is_some();
                prop_assert_eq!(r.words[i].1 > 0, fits);
            }
            let json = serde_json::to_string(&r).expect("serialise");
            let want: Vec<String> = vals.iter().map(|v| v.to_string()).collect();
            prop_assert_eq!(&json, &serde_json::to_string(&want).expect("serialise"));
            prop_assert_eq!(serde_json::from_str::<Rationals>(&json).expect("parse"), r);
        }

        /// A reduced `n/d` from the solver's machine words is stored exactly as the same value
        /// given as a `BigRational`: in a word when it fits one, aside when not, so that
        /// equality of the stores stays equality of the values.
        #[test]
        fn small_pushes_store_as_big_ones_do(
            n in prop_oneof![any::<i64>(), -70_000i64..70_000, Just(i64::MIN)],
            d in prop_oneof![1u64..70_000, any::<u64>().prop_map(|d| d | 1)],
        ) {
            let v = BigRational::new(BigInt::from(n), BigInt::from(d));
            let (Some(rn), Some(rd)) = (v.numer().to_i64(), v.denom().to_u64()) else {
                return Ok(());
            };
            let mut small = Rationals::default();
            small.push_small(rn, rd);
            let mut big = Rationals::default();
            big.push(&v);
            prop_assert_eq!(&small, &big);
            prop_assert_eq!(small.get(0), v);
        }

        /// Directions keep their entries apart and in order, and serialise as a list of lists.
        #[test]
        fn directions_hold_their_entries(
            dirs in proptest::collection::vec(proptest::collection::vec((0usize..50, value()), 0..5), 0..6),
        ) {
            let d: Directions = dirs.iter().cloned().collect();
            prop_assert_eq!(d.len(), dirs.len());
            prop_assert_eq!(d.entries(), dirs.iter().map(Vec::len).sum::<usize>());
            prop_assert_eq!(d.to_vecs(), dirs.clone());
            let as_text: Vec<Vec<(usize, String)>> = dirs
                .iter()
                .map(|v| v.iter().map(|(x, c)| (*x, c.to_string())).collect())
                .collect();
            let json = serde_json::to_string(&d).expect("serialise");
            prop_assert_eq!(&json, &serde_json::to_string(&as_text).expect("serialise"));
            prop_assert_eq!(serde_json::from_str::<Directions>(&json).expect("parse"), d);
        }
    }

    #[test]
    fn a_sorted_direction_answers_by_unknown() {
        let d: Directions = vec![vec![(1, big("1/2")), (4, big("-3"))], vec![]]
            .into_iter()
            .collect();
        let first = d.get(0);
        assert_eq!(first.unknowns(), &[1, 4]);
        assert_eq!(first.at(4), big("-3"));
        assert_eq!(first.at(2), BigRational::zero());
        assert!(d.get(1).is_empty());
        assert_eq!(Directions::default().len(), 0);
    }
}
