//! Ranks over F2 and the Betti numbers of the checker's cell complexes (`solid.rs` builds them,
//! for solids and, through `face_homology.rs`, for faces): column reduction over F2, the check
//! that ∂∂ = 0, and b0, b1, b2, b3 with the argument that makes the F2 numbers the rational ones
//! (see the documentation of `solid.rs`).

use super::solid::{Complex, Parity};
use std::collections::HashMap;

/// The ranks of a matrix over F2 given by its columns (row indices, a repeated one cancels),
/// by column reduction: the work is charged as it goes.
pub(super) fn rank_f2(columns: Vec<Vec<usize>>) -> Result<usize, String> {
    let mut owner: HashMap<usize, Vec<usize>> = HashMap::new();
    let mut rank = 0;
    for col in columns {
        let mut v = col;
        v.sort_unstable();
        // Cancel pairs.
        let mut c: Vec<usize> = Vec::with_capacity(v.len());
        for x in v {
            if c.last() == Some(&x) {
                c.pop();
            } else {
                c.push(x);
            }
        }
        while let Some(&low) = c.last() {
            let Some(p) = owner.get(&low) else {
                break;
            };
            super::within_work(
                "the ranks of the solid's boundary matrices",
                (c.len() + p.len()) as u128,
            )?;
            c = xor(&c, p);
        }
        if let Some(&low) = c.last() {
            owner.insert(low, c);
            rank += 1;
        }
    }
    Ok(rank)
}

/// The sum over F2 of two sorted index sets.
fn xor(a: &[usize], b: &[usize]) -> Vec<usize> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j]);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

/// ∂∂ = 0 over F2: every corner meets a face's boundary, and every edge a volume's
/// boundary, an even number of times. A failure means the cells were not put together as a
/// complex, whatever the counts.
fn chain_complex(c: &Complex, corner: &[usize]) -> Result<(), String> {
    let mut odd: HashMap<usize, bool> = HashMap::new();
    for (g, f) in c.faces.iter().enumerate() {
        odd.clear();
        for &(e, _) in &f.bnd {
            for x in [corner[2 * e], corner[2 * e + 1]] {
                *odd.entry(x).or_insert(false) ^= true;
            }
        }
        if odd.values().any(|&o| o) {
            return Err(format!("face {g} of the solid built is not closed"));
        }
    }
    for (a, v) in c.vols.iter().enumerate() {
        odd.clear();
        for &(g, _) in &v.faces {
            for &(e, _) in &c.faces[g].bnd {
                *odd.entry(e).or_insert(false) ^= true;
            }
        }
        if odd.values().any(|&o| o) {
            return Err(format!("volume {a} of the solid built is not closed"));
        }
    }
    Ok(())
}

/// The cells, χ and Betti numbers of a complex over F2, which are the rational ones (see the
/// module documentation): refused unless b2 = b3 = 0 over F2.
pub(super) struct Betti {
    pub(super) cells: [u64; 4],
    pub(super) euler: i64,
    pub(super) b0: u64,
    pub(super) b1: u64,
}

pub(super) fn betti(c: &Complex, level: u64) -> Result<Betti, String> {
    let (corner, corners) = c.corners();
    // b0: corners joined by edges.
    let mut dsu = Parity::new(corners);
    for e in 0..c.edges.len() {
        let _ = dsu.union(corner[2 * e], corner[2 * e + 1], false);
    }
    let b0 = (0..corners).filter(|&x| dsu.find(x).0 == x).count();
    chain_complex(c, &corner)?;
    let r1 = corners - b0;
    let r2 = rank_f2(
        c.faces
            .iter()
            .map(|f| f.bnd.iter().map(|r| r.0).collect())
            .collect(),
    )?;
    let r3 = rank_f2(
        c.vols
            .iter()
            .map(|v| v.faces.iter().map(|f| f.0).collect())
            .collect(),
    )?;
    let (n0, n1, n2, n3) = (corners, c.edges.len(), c.faces.len(), c.vols.len());
    let [n0, n1, n2, n3, r1, r2, r3] = [n0, n1, n2, n3, r1, r2, r3].map(|x| x as i64);
    let (b3, b2, b1) = (n3 - r3, n2 - r2 - r3, n1 - r1 - r2);
    if b1 < 0 || b2 < 0 {
        return Err(format!(
            "level {level}: the cells built are not a chain complex"
        ));
    }
    if b3 != 0 || b2 != 0 {
        return Err(format!(
            "level {level}: over F2, b2 = {b2} and b3 = {b3}; the step proves rational Betti \
             numbers only where both are 0"
        ));
    }
    Ok(Betti {
        cells: [n3, n2, n1, n0].map(|x| x as u64),
        euler: n0 - n1 + n2 - n3,
        b0: b0 as u64,
        b1: b1 as u64,
    })
}
