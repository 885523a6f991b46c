//! `lacuna render`.

use super::*;

/// Runs `lacuna render`.
pub(super) fn run(args: RenderArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let RenderArgs {
        geo,
        svg,
        json_out,
        obj,
        stl,
        thickness,
        png,
        size,
        background,
        no_legend,
        density,
        density_grid,
        write_template,
    } = args;
    if svg.is_none()
        && json_out.is_none()
        && obj.is_none()
        && stl.is_none()
        && png.is_none()
        && density.is_none()
        && write_template.is_none()
    {
        return Err(Error::Usage(
            "nothing to write: give --svg, --json-out, --obj, --stl, --png, --density or --write-template"
                .into(),
        ));
    }
    check_density_grid(density_grid, 1)?;
    if !(1..=8192).contains(&size) {
        return Err(Error::OutOfRange {
            flag: "--size",
            value: size.to_string(),
            what: "the PNG size in pixels",
            range: "from 1 to 8192".into(),
        });
    }
    if !(thickness.is_finite() && thickness > 0.0) {
        return Err(Error::Usage(format!(
            "--thickness {thickness} must be a positive number"
        )));
    }
    let vector = svg.is_some() || json_out.is_some() || obj.is_some() || stl.is_some();
    let (_, inst) = instance(&geo, limits, if vector { 2_000_000 } else { 100_000_000 })?;
    let io = |path: &std::path::Path, e: std::io::Error| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    };
    let (level, segs) = (geo.level, geo.segments);
    out(&choice_text(&geo, &inst));
    if let Some(p) = &write_template {
        let text = inst.default_template(&lacuna::geometry::InstantiateOptions::default());
        std::fs::write(p, text).map_err(|e| io(p, e))?;
        out(&format!("wrote {}\n", p.display()));
    }
    let picture = lacuna::export::PictureOptions {
        width: size as u32,
        background: match background {
            BackgroundArg::White => lacuna::export::Background::White,
            BackgroundArg::Transparent => lacuna::export::Background::Transparent,
        },
        legend: !no_legend,
        ..Default::default()
    };
    if let Some(p) = &svg {
        let opts = lacuna::export::PictureOptions {
            width: 512,
            ..picture.clone()
        };
        lacuna::export::write_svg_picture(&inst, level, &opts, create(p)?).map_err(|e| io(p, e))?;
        out(&format!("wrote {}\n", p.display()));
    }
    if let Some(p) = &json_out {
        lacuna::export::write_json(&inst, level, segs, create(p)?).map_err(|e| io(p, e))?;
        out(&format!("wrote {}\n", p.display()));
    }
    if let Some(p) = &obj {
        lacuna::export::write_obj(&inst, level, segs, thickness, create(p)?)
            .map_err(|e| io(p, e))?;
        out(&format!("wrote {}\n", p.display()));
    }
    if let Some(p) = &stl {
        lacuna::export::write_stl(&inst, level, segs, thickness, create(p)?)
            .map_err(|e| io(p, e))?;
        out(&format!("wrote {}\n", p.display()));
    }
    if let Some(p) = &png {
        lacuna::export::write_png_picture(&inst, level, &picture, create(p)?)
            .map_err(|e| io(p, e))?;
        out(&format!("wrote {}\n", p.display()));
    }
    if let Some(p) = &density {
        let map = lacuna::measure::density_map(&inst, level, density_grid, segs);
        let pic = lacuna::export::DensityPicture {
            size: size as u32,
            level,
            window: lacuna::geometry::bounds(&inst, segs).size(),
        };
        lacuna::export::write_density_picture(&map, &pic, create(p)?).map_err(|e| io(p, e))?;
        out(&format!("wrote {}\n", p.display()));
    }
    Ok(ExitCode::SUCCESS)
}
