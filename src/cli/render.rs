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
    if !(1..=16_384).contains(&size) {
        return Err(Error::OutOfRange {
            flag: "--size",
            value: size.to_string(),
            what: "the PNG size in pixels",
            range: "from 1 to 16384".into(),
        });
    }
    if !(thickness.is_finite() && thickness > 0.0) {
        return Err(Error::Usage(format!(
            "--thickness {thickness} must be a positive number"
        )));
    }
    if let Some((name, model)) = automaton::automaton_input(&geo)? {
        if stl.is_some() || density.is_some() || write_template.is_some() {
            return Err(Error::Usage(
                "--stl, --density and --write-template apply to faces; an automaton is written with --svg, --png, --json-out or --obj".into(),
            ));
        }
        let vector = svg.is_some() || json_out.is_some() || obj.is_some();
        let p = automaton::prepare(
            &geo,
            name,
            model,
            limits,
            if vector { 2_000_000 } else { 20_000_000 },
        )?;
        return automaton::render(
            &geo,
            p,
            svg.as_deref(),
            json_out.as_deref(),
            obj.as_deref(),
            png.as_deref(),
            size,
        );
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
    if let Some(p) = &svg {
        lacuna::export::write_svg(&inst, level, segs, create(p)?).map_err(|e| io(p, e))?;
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
        let raster = lacuna::export::render_raster(&inst, level, size, segs);
        lacuna::export::write_png(&raster, create(p)?).map_err(|e| io(p, e))?;
        out(&format!("wrote {}\n", p.display()));
    }
    if let Some(p) = &density {
        let map = lacuna::measure::density_map(&inst, level, density_grid, segs);
        lacuna::export::write_density_png(&map, create(p)?).map_err(|e| io(p, e))?;
        out(&format!("wrote {}\n", p.display()));
    }
    Ok(ExitCode::SUCCESS)
}
