//! The level-one step: a chosen point of the proved solution space at which every cell of level 1
//! has a control polygon of positive signed area (THEORY §7), re-derived from the closure and the
//! solution space.
//!
//! **The point.** The proved solution set is `particular + span(basis)`, each basis vector 1 at
//! its own free unknown; the step gives one value `t_j` per basis vector and the checker forms
//! `x = particular + Σ t_j·basis_j` itself, so the point lies on the solution set by
//! construction: no equation is re-checked here.
//!
//! **The cells.** For face type `t` with `m_t` control points and frame `F_t` (the step's `m_t`
//! rational points), sub-face `k` of type `w` is placed by its operator `T_k`, an `m_t × m_w`
//! block of unknowns (the layout of the `solution-space` step): its control point `c` is
//! `Σ_r x[T_k[r][c]]·F_t[r]`, and its control polygon is its `m_w` control points in boundary
//! order. The central lacuna's polygon is the sub-faces' lacuna sides (origin `Lacuna{side}`),
//! each the control points of that edge from its first to the next edge's first, reversed, taken
//! in side order. A polygon's signed area is the shoelace sum over Q, halved.
//!
//! The step is accepted when every frame, every sub-face polygon and every lacuna polygon has
//! positive area and the counts and the smallest sub-face area are the listed ones. What it proves
//! is a statement about the chosen point in the given frames; which frames and which point
//! lacuna chose (its default templates, the fit, the goals) is not part of the proof.

use super::system::solution_layout;
use super::{rat, within_work, Checked, Q};
use crate::certificate::{ClosureStep, LevelOneStep, Origin, SolutionStep};
use std::collections::HashMap;

type Point = [Q; 2];

fn cross(a: &Point, b: &Point) -> Q {
    &a[0] * &b[1] - &a[1] * &b[0]
}

/// The signed area of a polygon, exactly (shoelace, halved).
pub(super) fn signed_area(pts: &[Point]) -> Q {
    let n = pts.len();
    let twice = (0..n).fold(Q::default(), |s, i| s + cross(&pts[i], &pts[(i + 1) % n]));
    twice / Q::from_integer(2.into())
}

/// Checks the level-one step against the proved closure (Bézier degree `q`) and solution space.
pub(super) fn check_level_one(
    l: &LevelOneStep,
    c: &ClosureStep,
    q: usize,
    s: &SolutionStep,
) -> Checked {
    let (lay, column) = solution_layout(c, q, s)?;
    if l.parameters.len() != s.basis.len() {
        return Err(format!(
            "{} parameters for a solution space of {} free unknowns",
            l.parameters.len(),
            s.basis.len()
        ));
    }
    if l.frames.len() != c.types.len() {
        return Err(format!(
            "{} frames for {} face types",
            l.frames.len(),
            c.types.len()
        ));
    }
    // The point: particular + Σ t_j·basis_j, sparse (unknowns not touched are 0).
    let entries = s.particular.len() + s.basis.iter().map(Vec::len).sum::<usize>();
    within_work("the level-one step's point", 64 * entries as u128)?;
    let mut x: HashMap<usize, Q> = HashMap::new();
    for (u, v) in &s.particular {
        *x.entry(*u).or_default() += rat(v)?;
    }
    for (b, t) in s.basis.iter().zip(&l.parameters) {
        let t = rat(t)?;
        for (u, v) in b {
            *x.entry(*u).or_default() += rat(v)? * &t;
        }
    }
    let value = |i: usize| x.get(&column[i]).cloned().unwrap_or_default();
    let mut frames: Vec<Vec<Point>> = Vec::with_capacity(c.types.len());
    for (t, f) in l.frames.iter().enumerate() {
        if f.len() != lay.dims[t] {
            return Err(format!(
                "the frame of type {t} has {} points, the type has {} control points",
                f.len(),
                lay.dims[t]
            ));
        }
        let pts: Vec<Point> = f
            .iter()
            .map(|[a, b]| Ok([rat(a)?, rat(b)?]))
            .collect::<Result<_, String>>()?;
        if signed_area(&pts) <= Q::default() {
            return Err(format!(
                "the frame of type {t} has signed area {}, not positive",
                signed_area(&pts)
            ));
        }
        frames.push(pts);
    }
    let mut sub_faces = 0u64;
    let mut lacunas = 0u64;
    let mut smallest: Option<(Q, String)> = None;
    for (t, rule) in c.types.iter().enumerate() {
        let m_t = lay.dims[t];
        let work: usize = rule
            .subfaces
            .iter()
            .map(|sf| m_t * lay.dims.get(sf.type_index).copied().unwrap_or(0))
            .sum();
        within_work("the level-one step's cells", 64 * work as u128)?;
        // Control point `c` of sub-face `k` (of type `w`) in the frame of `t`.
        let point = |k: usize, w: usize, c: usize| -> Point {
            let m_w = lay.dims[w];
            let mut p = [Q::default(), Q::default()];
            for (r, f) in frames[t].iter().enumerate() {
                let v = value(lay.base[t][k] + r * m_w + c);
                p[0] += &v * &f[0];
                p[1] += &v * &f[1];
            }
            p
        };
        let mut lacuna: Vec<(usize, Vec<Point>)> = Vec::new();
        for (k, sf) in rule.subfaces.iter().enumerate() {
            let w = sf.type_index;
            let m_w = lay.dims[w];
            let polygon: Vec<Point> = (0..m_w).map(|c| point(k, w, c)).collect();
            let a = signed_area(&polygon);
            if a <= Q::default() {
                return Err(format!(
                    "sub-face {k} of type {t} has signed area {a} in the frame, not positive"
                ));
            }
            sub_faces += 1;
            if smallest.as_ref().is_none_or(|(s, _)| a < *s) {
                smallest = Some((a, format!("sub-face {k} of type {t}")));
            }
            if sf.origins.len() != lay.offsets[w].len() {
                return Err(format!(
                    "sub-face {k} of type {t} lists {} origins, its type {w} has {} edges",
                    sf.origins.len(),
                    lay.offsets[w].len()
                ));
            }
            for (e, o) in sf.origins.iter().enumerate() {
                if let Origin::Lacuna { side } = *o {
                    let from = lay.offsets[w][e];
                    let to = lay.offsets[w].get(e + 1).copied().unwrap_or(m_w);
                    let mut side_points: Vec<Point> =
                        (from..=to).map(|c| point(k, w, c % m_w)).collect();
                    side_points.reverse();
                    lacuna.push((side, side_points));
                }
            }
        }
        if !lacuna.is_empty() {
            lacuna.sort_by_key(|(side, _)| *side);
            let polygon: Vec<Point> = lacuna.into_iter().flat_map(|(_, p)| p).collect();
            let a = signed_area(&polygon);
            if a <= Q::default() {
                return Err(format!(
                    "the lacuna of type {t} has signed area {a} in the frame, not positive"
                ));
            }
            lacunas += 1;
        }
    }
    if (l.sub_faces, l.lacunas) != (sub_faces, lacunas) {
        return Err(format!(
            "the step lists {} sub-faces and {} lacunas, the closure has {sub_faces} and {lacunas}",
            l.sub_faces, l.lacunas
        ));
    }
    let (least, which) = smallest.ok_or("the closure has no sub-face")?;
    if rat(&l.smallest_area)? != least {
        return Err(format!(
            "the smallest sub-face area is {least} ({which}), the step lists {}",
            l.smallest_area
        ));
    }
    let message = format!(
        "the point particular + Σ t_j·basis_j at {} formed by the checker; {} and {} placed in \
         their parents' frames ({}), signed areas computed exactly",
        super::counted(l.parameters.len(), "parameter", "parameters"),
        super::counted(sub_faces as usize, "sub-face", "sub-faces"),
        super::counted(lacunas as usize, "lacuna", "lacunas"),
        super::counted(frames.len(), "frame", "frames"),
    );
    let verdict = format!(
        "at the chosen point every level-1 control polygon has positive area (smallest sub-face \
         {least}, {which})"
    );
    Ok((message, verdict))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shoelace_of_the_unit_square_is_one() {
        let q = |n: i64| Q::from_integer(n.into());
        let square = [[q(0), q(0)], [q(1), q(0)], [q(1), q(1)], [q(0), q(1)]];
        assert_eq!(signed_area(&square), q(1));
        let mut cw = square.clone();
        cw.reverse();
        assert_eq!(signed_area(&cw), q(-1));
    }
}
