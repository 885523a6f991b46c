//! The closure of volume types and their exact counts (THEORY §10).
//!
//! Breadth-first from the start volumes, identifying types by canonical volume, by the closure
//! faces use too (`topology/breadth_first.rs`, THEORY §4). No bound on the closure of volumes is
//! proved yet, so growth past the limits is a runaway with its witness chain: more than
//! `--max-types` volume types, or a volume whose surface has more than `--max-boundary` faces.

use crate::error::Result;
use crate::topology::breadth_first::{close_types, Closable, Outcome, Runaway};
use crate::topology::limits::Limits;
use crate::topology::volume::step::{subdivide_volume, VolumeSubdivision};
use crate::topology::volume::Volume;
use num_bigint::BigUint;
use num_rational::BigRational;
use num_traits::Zero;
use serde::Serialize;

/// One volume type of a closure.
#[derive(Clone, Debug)]
pub struct VolumeType {
    /// The canonical volume.
    pub volume: Volume,
    /// Its subdivision step.
    pub subdivision: VolumeSubdivision,
    /// The type index of each sub-volume, aligned with `subdivision.subvolumes`.
    pub children: Vec<usize>,
    /// The type through which it was first reached (`None` for a start type).
    pub parent: Option<usize>,
}

/// A closed set of volume types.
#[derive(Clone, Debug)]
pub struct VolumeTypeSet {
    /// The types; the start types first.
    pub types: Vec<VolumeType>,
    /// The type index of each start volume.
    pub start: Vec<usize>,
}

impl VolumeTypeSet {
    /// Every sub-volume whose surface is not a sphere, as `V{type} sub-volume {k}: {why}` (the
    /// structure check of `verify`); empty when every one is.
    pub fn sub_volume_failures(&self) -> Vec<String> {
        let mut failures = Vec::new();
        for (i, t) in self.types.iter().enumerate() {
            for (k, s) in t.subdivision.subvolumes.iter().enumerate() {
                if let Err(e) = s.volume.surface.check() {
                    failures.push(format!("V{i} sub-volume {k}: {e}"));
                }
            }
        }
        failures
    }
}

/// The outcome of closing a set of volumes.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)]
pub enum VolumeClosure {
    /// Every sub-volume type is in the set.
    Closed(VolumeTypeSet),
    /// The recursion grew past a limit.
    Runaway(Runaway),
}

impl VolumeClosure {
    /// Closes the given start volumes under subdivision.
    pub fn of(start: &[Volume], limits: &Limits) -> Result<VolumeClosure> {
        for v in start {
            for f in &v.surface.faces {
                limits.check_face(f)?;
            }
        }
        let start = start.iter().map(Volume::canonical);
        Ok(match close_types(start, limits, |_| None)? {
            Outcome::Runaway(r) => VolumeClosure::Runaway(r),
            Outcome::Closed(types, start) => VolumeClosure::Closed(VolumeTypeSet {
                types: types
                    .into_iter()
                    .map(|n| VolumeType {
                        volume: n.item,
                        subdivision: n.step,
                        children: n.children,
                        parent: n.parent,
                    })
                    .collect(),
                start,
            }),
        })
    }
}

impl Closable for Volume {
    type Step = VolumeSubdivision;

    const NOUN: &'static str = "volume";

    fn size(&self) -> usize {
        self.surface.faces.len()
    }

    fn size_reason(size: usize, limit: usize) -> String {
        format!("a sub-volume has {size} faces, above the limit {limit} (--max-boundary)")
    }

    fn step(&self, limits: &Limits) -> Result<VolumeSubdivision> {
        refuse_before_the_step(self, limits)?;
        subdivide_volume(self)
    }

    fn children(step: &VolumeSubdivision) -> Vec<&Volume> {
        step.subvolumes.iter().map(|s| &s.volume).collect()
    }
}

/// Refuses, before the work, a subdivision step whose size its notation already puts past a
/// limit. The single sub-volume of a delayed volume is bounded by every sub-face of its
/// surface, so their number (each face's spokes, counted by the face subdivision, linear in its
/// sub-edges) is the sub-volume's face count: above `--max-boundary` it is refused at once,
/// instead of after building a surface of thousands of faces (seconds, then the same refusal).
/// The level-1 sub-edges of the surface (what the step's work is linear in, and its canonical
/// code quadratic) are held to `--max-boundary · --max-subedges`.
fn refuse_before_the_step(v: &Volume, limits: &Limits) -> Result<()> {
    let pieces: usize = v
        .surface
        .faces
        .iter()
        .flat_map(|f| &f.boundary)
        .map(|e| if e.delay >= 2 { 1 } else { e.n as usize })
        .fold(0, usize::saturating_add);
    let cap = limits
        .max_boundary
        .saturating_mul(limits.max_subedges as usize);
    if pieces > cap {
        return Err(crate::error::Error::limit(
            "the sub-edges of a volume's level-1 surface (at most --max-boundary × --max-subedges)",
            pieces,
            cap,
            "--max-boundary",
        ));
    }
    if v.delay >= 2 {
        let mut faces = 0usize;
        for f in &v.surface.faces {
            faces += crate::topology::subdivision::subdivide(f)?.subfaces.len();
        }
        if faces > limits.max_boundary {
            return Err(crate::error::Error::limit(
                "the faces of the sub-volume of a delayed volume",
                faces,
                limits.max_boundary,
                "--max-boundary",
            ));
        }
    }
    Ok(())
}

/// The counts of volumes at one level.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct VolumeLevelCount {
    /// The level i.
    pub level: u64,
    /// N^C_i: the number of sub-volumes (cells).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub cells: BigUint,
    /// N^L_i, a multiple of 1/4: cavities count 1, face holes and gaps are shared by two cells.
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub lacunas: BigRational,
    /// R_i = N^L_i / (N^L_i + N^C_i).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub ratio: BigRational,
}

/// The start vector: how many start volumes each type has.
fn start_vector(set: &VolumeTypeSet) -> Vec<BigUint> {
    let mut v = vec![BigUint::zero(); set.types.len()];
    for &t in &set.start {
        v[t] += 1u32;
    }
    v
}

/// One level down: the sub-volumes of each type that the volumes counted in `v` give.
fn next_level(set: &VolumeTypeSet, v: &[BigUint]) -> Vec<BigUint> {
    let mut next = vec![BigUint::zero(); v.len()];
    for (t, vt) in v.iter().enumerate().filter(|(_, x)| !x.is_zero()) {
        for &c in &set.types[t].children {
            next[c] += vt;
        }
    }
    next
}

/// The level-`level` sub-volumes of each type, from the start volumes: the start vector pushed
/// through the children `level` times.
pub fn volumes_by_type(set: &VolumeTypeSet, level: u64) -> Vec<BigUint> {
    (0..level).fold(start_vector(set), |v, _| next_level(set, &v))
}

/// Exact counts of the start volumes from level 0 to `levels`, on the vector of type
/// multiplicities with big integers (lacunas in quarters).
pub fn volume_counts(set: &VolumeTypeSet, levels: u64) -> Vec<VolumeLevelCount> {
    let quarters: Vec<u64> = set
        .types
        .iter()
        .map(|t| t.volume.contribution_quarters())
        .collect();
    let mut v = start_vector(set);
    let mut lacuna_quarters = BigUint::zero();
    let mut out = Vec::new();
    for level in 0..=levels {
        let cells: BigUint = v.iter().sum();
        let lacunas = BigRational::new(lacuna_quarters.clone().into(), 4.into());
        let denom = &lacunas + BigRational::from_integer(cells.clone().into());
        let ratio = if denom.is_zero() {
            BigRational::zero()
        } else {
            &lacunas / denom
        };
        out.push(VolumeLevelCount {
            level,
            cells,
            lacunas,
            ratio,
        });
        if level == levels {
            break;
        }
        for (vt, q) in v.iter().zip(&quarters) {
            lacuna_quarters += vt * q;
        }
        v = next_level(set, &v);
    }
    out
}
