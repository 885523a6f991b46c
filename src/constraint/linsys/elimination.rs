//! The core of the solver: fraction-free sparse elimination with Markowitz-style pivots over the
//! rows that presolve left (see the parent module for the method).

use crate::constraint::presolve::{Q, Z};

/// A core row in integer form, columns sorted (local core column ids).
#[derive(Clone, Debug)]
pub(super) struct CRow {
    pub(super) cols: Vec<u32>,
    pub(super) vals: Vec<Z>,
    pub(super) rhs: Z,
}

impl CRow {
    pub(super) fn coef(&self, c: u32) -> Option<&Z> {
        self.cols.binary_search(&c).ok().map(|k| &self.vals[k])
    }
    /// `(a/g)·self − (b/g)·o` with `g = gcd(a, b)`, then divided by its content.
    fn combine(&self, a: &Z, o: &CRow, b: &Z) -> CRow {
        self.combine_with_factors(a, o, b).0
    }

    /// [`CRow::combine`], also returning `(a/g, b/g, content)`.
    fn combine_with_factors(&self, a: &Z, o: &CRow, b: &Z) -> (CRow, Z, Z, Z) {
        let g = a.gcd(b);
        let (a, b) = (a.div_exact(&g), b.div_exact(&g));
        let mut out = CRow {
            cols: vec![],
            vals: vec![],
            rhs: Z::lin(&a, &self.rhs, &b, &o.rhs),
        };
        let (mut i, mut j) = (0, 0);
        let zero = Z::zero();
        while i < self.cols.len() || j < o.cols.len() {
            let ci = self.cols.get(i).copied().unwrap_or(u32::MAX);
            let cj = o.cols.get(j).copied().unwrap_or(u32::MAX);
            let c = ci.min(cj);
            let x = if ci == c {
                i += 1;
                &self.vals[i - 1]
            } else {
                &zero
            };
            let y = if cj == c {
                j += 1;
                &o.vals[j - 1]
            } else {
                &zero
            };
            let v = Z::lin(&a, x, &b, y);
            if !v.is_zero() {
                out.cols.push(c);
                out.vals.push(v);
            }
        }
        let mut g = out.rhs.clone();
        for v in &out.vals {
            if g.is_unit() {
                break;
            }
            g = g.gcd(v);
        }
        if !g.is_zero() && !g.is_unit() {
            out.vals.iter_mut().for_each(|v| *v = v.div_exact(&g));
            out.rhs = out.rhs.div_exact(&g);
        } else {
            g = Z::one();
        }
        (out, a, b, g)
    }
}

/// A combination of core rows, sorted by row.
pub(super) type Combo = Vec<(u32, Q)>;
/// `(row, pivot column, reduced row)` per pivot, in elimination order.
pub(super) type Reduced = Vec<(usize, u32, CRow)>;

/// Fraction-free sparse elimination with Markowitz-style pivots, then back substitution.
/// `Err` holds the row that became `0 = c ≠ 0` and, when `track`, its combination of input rows.
pub(super) fn eliminate(
    mut rows: Vec<CRow>,
    ncols: usize,
    track: bool,
) -> Result<Reduced, (usize, Combo)> {
    let mut combos: Vec<Combo> = match track {
        true => (0..rows.len() as u32)
            .map(|i| vec![(i, Q::int(Z::one()))])
            .collect(),
        false => vec![],
    };
    // Column lists are lazy (entries may be stale or repeated; validated when used); the counts of
    // active rows per column are exact and drive the pivot choice.
    let terms = rows.iter().map(|r| r.cols.len()).sum();
    let mut col_rows: Lists<u32> = Lists::new(ncols, terms);
    let mut col_count: Vec<u32> = vec![0; ncols];
    let mut buckets: Vec<Vec<u32>> = vec![];
    let mut active = vec![true; rows.len()];
    let mut others: Vec<u32> = vec![];
    for (i, r) in rows.iter().enumerate() {
        for &c in &r.cols {
            col_rows.push(c, i as u32);
            col_count[c as usize] += 1;
        }
        if buckets.len() <= r.cols.len() {
            buckets.resize(r.cols.len() + 1, vec![]);
        }
        buckets[r.cols.len()].push(i as u32);
    }
    let mut pivots: Vec<(usize, u32)> = vec![];
    let mut low = 1;
    'outer: loop {
        // Shortest active row (lazy buckets: stale entries are skipped).
        let i = loop {
            while low < buckets.len() && buckets[low].is_empty() {
                low += 1;
            }
            if low >= buckets.len() {
                break 'outer;
            }
            let i = buckets[low].pop().expect("nonempty") as usize;
            if active[i] && rows[i].cols.len() == low {
                break i;
            }
        };
        let piv = &rows[i];
        let k = (0..piv.cols.len())
            .min_by_key(|&k| (col_count[piv.cols[k] as usize], !piv.vals[k].is_unit()))
            .expect("active rows are nonempty");
        let (p, a) = (piv.cols[k], piv.vals[k].clone());
        active[i] = false;
        piv.cols.iter().for_each(|&c| col_count[c as usize] -= 1);
        col_rows.take(p, &mut others);
        others.sort_unstable();
        others.dedup();
        others.retain(|&j| active[j as usize] && rows[j as usize].coef(p).is_some());
        for j in others.drain(..).map(|j| j as usize) {
            let b = rows[j].coef(p).expect("validated").clone();
            let (new, fa, fb, content) = rows[j].combine_with_factors(&a, &rows[i], &b);
            if track {
                combos[j] = lin_combo(&fa, &combos[j], &fb, &combos[i], &content);
            }
            let old = std::mem::replace(&mut rows[j], new);
            // Exact counts: merge the old and new column sets; new columns join the lists.
            let (oc, nc) = (&old.cols, &rows[j].cols);
            let (mut x, mut y) = (0, 0);
            while x < oc.len() || y < nc.len() {
                let (co, cn) = (
                    oc.get(x).copied().unwrap_or(u32::MAX),
                    nc.get(y).copied().unwrap_or(u32::MAX),
                );
                if co == cn {
                    x += 1;
                    y += 1;
                } else if co < cn {
                    col_count[co as usize] -= 1;
                    x += 1;
                } else {
                    col_count[cn as usize] += 1;
                    col_rows.push(cn, j as u32);
                    y += 1;
                }
            }
            let len = rows[j].cols.len();
            if len == 0 {
                if !rows[j].rhs.is_zero() {
                    return Err((j, combos.get(j).cloned().unwrap_or_default()));
                }
                active[j] = false;
            } else {
                // Fill-in can make a row longer than every row was at the start.
                if len >= buckets.len() {
                    buckets.resize(len + 1, Vec::new());
                }
                buckets[len].push(j as u32);
                low = low.min(len);
            }
        }
        pivots.push((i, p));
    }
    // Back substitution, last pivot first: each reduced row holds its pivot and free columns.
    let mut pivot_of: Vec<Option<usize>> = vec![None; ncols];
    let mut reduced: Vec<Option<CRow>> = vec![None; pivots.len()];
    for (k, &(i, p)) in pivots.iter().enumerate().rev() {
        let mut row = std::mem::replace(
            &mut rows[i],
            CRow {
                cols: vec![],
                vals: vec![],
                rhs: Z::zero(),
            },
        );
        let later: Vec<(u32, usize)> = row
            .cols
            .iter()
            .filter(|&&c| c != p)
            .filter_map(|&c| pivot_of[c as usize].map(|k2| (c, k2)))
            .collect();
        for (c, k2) in later {
            let red = reduced[k2].as_ref().expect("later pivots are reduced");
            let b = row.coef(c).expect("column present").clone();
            row = row.combine(red.coef(c).expect("pivot present"), red, &b);
        }
        pivot_of[p as usize] = Some(k);
        reduced[k] = Some(row);
    }
    Ok(pivots
        .into_iter()
        .zip(reduced)
        .map(|((i, p), r)| (i, p, r.expect("reduced")))
        .collect())
}

/// Lists of items per column, all in one arena (a column's items are linked, newest first): the
/// core of a million-unknown system has few rows over hundreds of thousands of columns, and a
/// vector per column cost an allocation each.
pub(super) struct Lists<T> {
    head: Vec<u32>,
    next: Vec<u32>,
    item: Vec<T>,
}

impl<T: Copy> Lists<T> {
    /// Empty lists for `columns` columns, with room for `capacity` items.
    pub(super) fn new(columns: usize, capacity: usize) -> Lists<T> {
        Lists {
            head: vec![u32::MAX; columns],
            next: Vec::with_capacity(capacity),
            item: Vec::with_capacity(capacity),
        }
    }

    pub(super) fn push(&mut self, c: u32, t: T) {
        let e = u32::try_from(self.item.len())
            .ok()
            .filter(|&e| e != u32::MAX)
            .expect("fewer than 2^32 − 1 list items");
        self.next.push(self.head[c as usize]);
        self.item.push(t);
        self.head[c as usize] = e;
    }

    /// Column `c`'s items, newest first.
    pub(super) fn iter(&self, c: u32) -> impl Iterator<Item = T> + '_ {
        let mut e = self.head.get(c as usize).copied().unwrap_or(u32::MAX);
        std::iter::from_fn(move || {
            (e != u32::MAX).then(|| {
                let t = self.item[e as usize];
                e = self.next[e as usize];
                t
            })
        })
    }

    /// Empties column `c`'s list into `out` (cleared first).
    pub(super) fn take(&mut self, c: u32, out: &mut Vec<T>) {
        out.clear();
        out.extend(self.iter(c));
        self.head[c as usize] = u32::MAX;
    }
}

/// `(fa·x − fb·y) / content` on sparse combinations sorted by row.
fn lin_combo(fa: &Z, x: &Combo, fb: &Z, y: &Combo, content: &Z) -> Combo {
    let (fa, fb, c) = (
        Q::int(fa.clone()),
        Q::int(fb.clone()),
        Q::int(content.clone()),
    );
    let mut out = Vec::with_capacity(x.len() + y.len());
    let (mut i, mut j) = (0, 0);
    while i < x.len() || j < y.len() {
        let (ri, rj) = (
            x.get(i).map_or(u32::MAX, |t| t.0),
            y.get(j).map_or(u32::MAX, |t| t.0),
        );
        let r = ri.min(rj);
        let mut v = Q::zero();
        if ri == r {
            v = v.add(&fa.mul(&x[i].1));
            i += 1;
        }
        if rj == r {
            v = v.sub(&fb.mul(&y[j].1));
            j += 1;
        }
        if !v.is_zero() {
            out.push((r, v.div(&c)));
        }
    }
    out
}
