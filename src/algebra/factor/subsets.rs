//! The order in which Zassenhaus's recombination tries subsets of the modular factors, shared
//! by the recombination and by the replay of its order at another scale.

use super::BUDGET;

/// Advances `subset` (increasing indices below `k`) to the next subset of {0..k} of its size in
/// lexicographic order; `None` after the last one.
fn next_subset(subset: &mut [usize], k: usize) -> Option<()> {
    let size = subset.len();
    let pos = (0..size).rev().find(|&j| subset[j] < k - size + j)?;
    subset[pos] += 1;
    for j in pos + 1..size {
        subset[j] = subset[j - 1] + 1;
    }
    Some(())
}

/// Zassenhaus's order of trials over a pool of modular factors: subsets by increasing size (up to
/// half the pool), each size in lexicographic order. `found(pool, subset)` tries one subset; when
/// it says yes the subset leaves the pool and the search goes on at the same size. Returns the
/// pool left, or `None` once a trial would exceed [`BUDGET`]. [`super::recombine`] and the replay of its
/// order ([`super::scaled::replay_recombination`]) both run this one search, so they visit the same
/// subsets in the same order.
pub(super) fn subsets_in_order<T>(
    mut pool: Vec<T>,
    mut found: impl FnMut(&[T], &[usize]) -> bool,
) -> Option<Vec<T>> {
    let mut trials = 0u64;
    let mut size = 1;
    'search: while 2 * size <= pool.len() {
        let k = pool.len();
        let mut subset: Vec<usize> = (0..size).collect();
        loop {
            trials += 1;
            if trials > BUDGET {
                return None;
            }
            if found(&pool, &subset) {
                let mut i = 0;
                pool.retain(|_| {
                    i += 1;
                    !subset.contains(&(i - 1))
                });
                continue 'search;
            }
            if next_subset(&mut subset, k).is_none() {
                break;
            }
        }
        size += 1;
    }
    Some(pool)
}
