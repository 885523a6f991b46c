//! What the command line and the Python package say of a mesh they built: the claims file of
//! `render --claims` and the measures of a volume's level-n solid (`measure --json`).

use crate::mesh::threemf::Colours;
use crate::mesh::volume::{VolumeSizes, VolumeSolid};
use crate::mesh::Targets;
use crate::meshcheck::{Claims, PartClaim, CLAIMS_FORMAT, CLAIMS_VERSION};
use crate::topology::volume::VolumeTypeSet;
use serde_json::Value;

/// The 3MF colours of a volume's level-n solid by volume type: a material `V{k}` of the type's
/// picture colour per type of `set`, and the type of every triangle.
pub fn volume_type_colours(vs: &VolumeSolid, set: &VolumeTypeSet) -> crate::error::Result<Colours> {
    Ok(Colours {
        materials: (0..set.types.len())
            .map(|k| (format!("V{k}"), crate::export::palette::type_colour(k)))
            .collect(),
        per_triangle: vs.triangle_types(set)?,
    })
}

/// What a mesh written to `targets` is claimed to be: `source` names what was rendered, the
/// meshes are the file names of `targets`' STL and 3MF files.
pub fn mesh_claims(
    source: String,
    targets: &Targets,
    triangles: usize,
    parts: Option<u64>,
    euler: Option<i64>,
    genus: Option<i64>,
    per_part: Option<Vec<PartClaim>>,
) -> Claims {
    let meshes = [&targets.stl, &targets.threemf]
        .into_iter()
        .flatten()
        .map(|p| {
            p.file_name().map_or_else(
                || p.display().to_string(),
                |f| f.to_string_lossy().to_string(),
            )
        })
        .collect();
    Claims {
        format: CLAIMS_FORMAT.into(),
        version: CLAIMS_VERSION,
        source,
        meshes,
        triangles: triangles as u64,
        parts,
        euler,
        genus,
        per_part,
    }
}

/// The claims of a volume's level-n solid written to `targets`: the surface pieces are the
/// components and the voids; Σχ of the surface is 2χ of the solid; its genus is the number of
/// tunnels (THEORY §10).
pub fn volume_solid_claims(source: String, targets: &Targets, vs: &VolumeSolid) -> Claims {
    let x = &vs.exact;
    let euler = num_traits::ToPrimitive::to_i64(&(num_bigint::BigInt::from(2) * &x.euler));
    let genus = x.tunnels.as_ref().and_then(num_traits::ToPrimitive::to_i64);
    mesh_claims(
        source,
        targets,
        vs.solid.triangle_count(),
        x.components.zip(x.voids).map(|(b0, b2)| b0 + b2),
        euler,
        genus,
        None,
    )
}

/// The measures of a volume's level-n solid as `lacuna measure --json` prints them: the exact
/// topology of the level, the checked mesh, its sizes in mm and the printability against
/// `resolution` and the build volume `bed`, with the caller's verdict `verified`.
pub fn volume_measure_json(
    name: &str,
    vs: &VolumeSolid,
    sizes: &VolumeSizes,
    resolution: f64,
    bed: [f64; 3],
    verified: bool,
) -> Value {
    let embedded = vs.crossing.is_none();
    serde_json::json!({
        "input": name,
        "level": vs.solid.level,
        "verified": verified,
        "solid": vs.exact,
        "mesh": {
            "parts": vs.solid.parts.len(),
            "triangles": vs.solid.triangle_count(),
            "surface_euler": vs.euler,
            "surface_pieces": vs.surfaces,
            "genus": vs.genus,
            "embedded": embedded,
            "crossing": vs.crossing,
        },
        "sizes": sizes,
        "printability": sizes.report(&vs.solid.parts, vs.solid.level, resolution, bed),
        "resolution_mm": resolution,
        "below_resolution": sizes.below(resolution),
    })
}
