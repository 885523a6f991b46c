//! `lacuna render`.

use super::*;

/// Runs `lacuna render`.
/// The most cells of a face's level that `render` checks for overlaps before drawing it (the
/// constrained triangulation of their outline takes about a second per million cells).
const CHECKED_CELLS: u64 = 2_000_000;

pub(super) fn run(args: RenderArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let RenderArgs {
        geo,
        svg,
        json_out,
        json,
        obj,
        stl,
        stl_ascii,
        claims,
        threemf,
        threemf_colours,
        threemf_parts,
        thickness,
        print,
        png,
        size,
        background,
        no_legend,
        density,
        density_grid,
        write_template,
        state,
    } = args;
    let wanted: Vec<(&str, &std::path::Path)> = [
        ("--write-template", &write_template),
        ("--svg", &svg),
        ("--json-out", &json_out),
        ("--obj", &obj),
        ("--stl", &stl),
        ("--3mf", &threemf),
        ("--claims", &claims),
        ("--png", &png),
        ("--density", &density),
    ]
    .into_iter()
    .filter_map(|(flag, p)| p.as_deref().map(|p| (flag, p)))
    .collect();
    if wanted.is_empty() {
        return Err(Error::Usage(
            "nothing to write: give --svg, --json-out, --obj, --stl, --3mf, --png, --density or --write-template"
                .into(),
        ));
    }
    if claims.is_some() && stl.is_none() && threemf.is_none() {
        return Err(Error::Usage(
            "--claims describes the mesh written with --stl or --3mf: give one of them".into(),
        ));
    }
    // The format is the flag's: a file named for another format (`--png out.jpg`) is refused
    // rather than written with a misleading name.
    for (flag, p) in &wanted {
        let format = match *flag {
            "--svg" => "svg",
            "--png" | "--density" => "png",
            "--stl" => "stl",
            "--3mf" => "3mf",
            "--obj" => "obj",
            "--json-out" | "--claims" => "json",
            _ => continue,
        };
        let ext = p
            .extension()
            .map(|e| e.to_string_lossy().to_lowercase())
            .unwrap_or_default();
        let known = [
            "svg", "png", "jpg", "jpeg", "gif", "bmp", "tif", "tiff", "webp", "pdf", "stl", "3mf",
            "obj", "ply", "json", "html",
        ];
        if known.contains(&ext.as_str()) && ext != format {
            return Err(Error::Usage(format!(
                "{flag} writes {}, but `{}` is named for .{ext}: name it .{format}",
                format.to_uppercase(),
                p.display()
            )));
        }
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
    let thick = thickness.is_some();
    let thickness = match &thickness {
        Some(t) => positive_number("--thickness", t)?,
        None => lacuna::mesh::DEFAULT_THICKNESS,
    };
    let mesh = lacuna::mesh::Targets {
        stl: stl.clone(),
        stl_ascii,
        threemf: threemf.clone(),
        obj: obj.clone(),
    };
    let solid_size = lacuna::mesh::Size {
        width: print.width,
        thickness,
    };
    if mesh.any() {
        lacuna::mesh::check_size("--thickness", thickness).map_err(mesh_error)?;
        lacuna::mesh::check_size("--width", print.width).map_err(mesh_error)?;
        lacuna::mesh::check_size("--resolution", print.resolution).map_err(mesh_error)?;
    }
    let mut outputs = Outputs::check(&geo.inputs(), &wanted)?;
    if json && outputs.to_stdout {
        return Err(Error::Usage(
            "--json and an output on standard output (`-`) would both write to it: give the output a file".into(),
        ));
    }
    outputs.json = json;
    let by_type = |what: &str| {
        Error::Usage(format!(
            "--3mf-colours and --3mf-parts show the cells of faces and volumes by type; {what} has no cells of types"
        ))
    };
    let style = match (threemf_colours, threemf_parts) {
        (true, _) => lacuna::mesh::threemf::Style::Colours,
        (_, true) => lacuna::mesh::threemf::Style::Parts,
        _ => lacuna::mesh::threemf::Style::Plain,
    };
    let no_states = |what: &str| automaton::no_states(state.as_deref(), what, "draw");
    if let Some((name, v)) = lacuna::input::load_volume_file(&geo.input)? {
        if state.is_some() {
            return Err(no_states("a volume has no states"));
        }
        if json_out.is_some() || density.is_some() || write_template.is_some() {
            return Err(Error::Usage(
                "--json-out, --density and --write-template apply to faces; a volume is written with --svg, --png, --stl, --3mf or --obj".into(),
            ));
        }
        let targets = volume::VolumeTargets {
            svg: svg.as_deref(),
            png: png.as_deref(),
            claims: claims.as_deref(),
            mesh: &mesh,
            size,
            transparent: background == BackgroundArg::Transparent,
            style,
        };
        let code = volume::render(&name, &v, &geo, &print, targets, &mut outputs, limits)?;
        return Ok(finish(&geo, &outputs, code));
    }
    if let Some((name, model)) = automaton::automaton_input(&geo)? {
        if style != lacuna::mesh::threemf::Style::Plain {
            return Err(by_type("an automaton"));
        }
        if claims.is_some() && !thick {
            return Err(Error::Usage(
                "--claims describes a closed solid; an automaton's open surface is none: give --thickness T (mm) for a closed shell".into(),
            ));
        }
        if density.is_some() || write_template.is_some() {
            return Err(Error::Usage(
                "--density and --write-template apply to faces; an automaton is written with --svg, --png, --json-out, --obj, --stl or --3mf".into(),
            ));
        }
        let vector = svg.is_some() || json_out.is_some() || obj.is_some();
        let p = automaton::prepare_at(
            &geo,
            name,
            model,
            state.as_deref(),
            limits,
            if vector { 2_000_000 } else { 20_000_000 },
        )?;
        let meshes = automaton::MeshOut {
            targets: mesh,
            claims,
            size: solid_size,
            thick,
            bed: print.bed,
            orient: print.orient,
            resolution: (print.resolution, print.strict),
            layers: print.layers,
        };
        let code = automaton::render(
            &geo,
            p,
            &mut outputs,
            svg.as_deref(),
            json_out.as_deref(),
            png.as_deref(),
            &meshes,
            (size, background.into(), !no_legend),
        )?;
        return Ok(finish(&geo, &outputs, code));
    }
    if state.is_some() {
        return Err(no_states("faces have no states"));
    }
    let vector = svg.is_some() || json_out.is_some() || mesh.any();
    let (_, inst) = instance(&geo, limits, if vector { 2_000_000 } else { 100_000_000 })?;
    let (level, segs) = (geo.level, geo.segments);
    outputs.say(&choice_text(&geo, &inst));
    let wrote = |o: &Outputs, p: &std::path::Path| o.say(&format!("wrote {}\n", p.display()));
    if let Some(p) = &write_template {
        let text = inst.default_template(&lacuna::geometry::InstantiateOptions::default());
        outputs.write(p, |w| w.write_all(text.as_bytes()))?;
        wrote(&outputs, p);
    }
    // Every level drawn is checked as the solid is (E1041 with the place, nothing written): a
    // picture of overlapping or self-touching cells would show a structure the topology does not
    // have. The solid itself is checked below when a mesh is written.
    let drawn = svg.is_some() || json_out.is_some() || png.is_some() || density.is_some();
    if drawn && !mesh.any() {
        match lacuna::measure::check_cells(&inst, level, CHECKED_CELLS) {
            Ok(()) => lacuna::mesh::embedded(&inst, level, segs, solid_size).map_err(mesh_error)?,
            Err(_) => outputs.say(&format!(
                "note: level {level} has more than {CHECKED_CELLS} cells: drawn without the \
                 check that no two cells overlap\n"
            )),
        }
    }
    let picture = lacuna::export::PictureOptions {
        width: size as u32,
        background: background.into(),
        legend: !no_legend,
        ..Default::default()
    };
    if let Some(p) = &svg {
        let opts = lacuna::export::PictureOptions {
            width: 512,
            ..picture.clone()
        };
        outputs.write(p, |w| {
            lacuna::export::write_svg_picture(&inst, level, &opts, w)
        })?;
        wrote(&outputs, p);
    }
    if let Some(p) = &json_out {
        outputs.write(p, |w| lacuna::export::write_json(&inst, level, segs, w))?;
        wrote(&outputs, p);
    }
    if mesh.any() {
        // The solid is built and checked once, before any mesh file is written (THEORY §11).
        let pr = lacuna::mesh::printability(&inst, level, segs, solid_size, print.resolution)
            .map_err(mesh_error)?;
        outputs.say(&pr.text());
        pr.enforce(print.strict).map_err(mesh_error)?;
        if outputs.json {
            outputs.printability = Some(lacuna::mesh::printability::PrintReport::of_plate(
                &pr, print.bed,
            ));
        }
        let type_name = |k: usize| format!("T{k} {}", inst.types.types[k].face);
        let (mut solid, colours) = match style {
            lacuna::mesh::threemf::Style::Colours => {
                let t = lacuna::mesh::build_typed(&inst, level, segs, solid_size)
                    .map_err(mesh_error)?;
                let materials = (0..inst.types.types.len())
                    .map(|k| (type_name(k), lacuna::export::type_colour(k)))
                    .collect();
                let colours = lacuna::mesh::threemf::Colours {
                    materials,
                    per_triangle: t.types,
                };
                (t.solid, Some(colours))
            }
            _ => (
                lacuna::mesh::build(&inst, level, segs, solid_size).map_err(mesh_error)?,
                None,
            ),
        };
        let mut parts = match style {
            lacuna::mesh::threemf::Style::Parts => {
                lacuna::mesh::face_parts(&inst, level, segs, solid_size).map_err(mesh_error)?
            }
            _ => Vec::new(),
        };
        outputs.say(&solid.summary());
        let o = orient(&mut solid.parts, print.orient, &outputs);
        if let Some(w) = solid.bed_advice(print.bed, print.width) {
            eprintln!("{w}");
        }
        if let Some(p) = &stl {
            outputs.write(p, |w| match stl_ascii {
                true => lacuna::mesh::stl::write_ascii(&solid, w),
                false => lacuna::mesh::stl::write_binary(&solid, w),
            })?;
            wrote(&outputs, p);
        }
        if let Some(p) = &threemf {
            match style {
                lacuna::mesh::threemf::Style::Parts => {
                    let title = format!("{} level {level}", solid.name);
                    write_type_parts(&mut outputs, p, &title, &mut parts, &o, type_name)?;
                }
                _ => write_threemf(&mut outputs, p, |zip| {
                    lacuna::mesh::threemf::write_with(&solid, colours.as_ref(), zip)
                })?,
            }
            wrote(&outputs, p);
        }
        if let Some(p) = &obj {
            outputs.write(p, |w| lacuna::mesh::obj::write(&solid, w))?;
            wrote(&outputs, p);
        }
        if let Some(p) = &claims {
            let e = &solid.expected;
            let holds = |h: &num_bigint::BigUint| num_traits::ToPrimitive::to_i64(h);
            let per_part: Option<Vec<lacuna::meshcheck::PartClaim>> = solid
                .parts
                .iter()
                .map(|part| {
                    let h = i64::try_from(part.holes?).ok()?;
                    Some(lacuna::meshcheck::PartClaim {
                        euler: 2 - 2 * h,
                        genus: h,
                    })
                })
                .collect();
            let genus = holds(&e.holes);
            let c = lacuna::export::mesh_claims(
                format!("{} level {level}", geo.input),
                &mesh,
                solid.triangle_count(),
                Some(e.components),
                genus.and_then(|h| (2 * e.components as i64).checked_sub(2 * h)),
                genus,
                per_part,
            );
            write_claims(&mut outputs, p, &c)?;
        }
    }
    if let Some(p) = &png {
        outputs.write(p, |w| {
            lacuna::export::write_png_picture(&inst, level, &picture, w)
        })?;
        wrote(&outputs, p);
    }
    if let Some(p) = &density {
        let map = lacuna::measure::density_map(&inst, level, density_grid, segs);
        // The blocks with no point of the level-0 faces: outside, not holes.
        let face = lacuna::measure::density_map(&inst, 0, density_grid, segs);
        let pic = lacuna::export::DensityPicture {
            size: size as u32,
            level,
            window: lacuna::geometry::bounds(&inst, segs).size(),
            outside: face.values.iter().map(|&v| v == 0.0).collect(),
        };
        outputs.write(p, |w| lacuna::export::write_density_picture(&map, &pic, w))?;
        wrote(&outputs, p);
    }
    Ok(finish(&geo, &outputs, ExitCode::SUCCESS))
}

/// The end of `render`: under `--json`, one object on standard output — the input, the level,
/// the files written and the printability of the mesh (null without one).
fn finish(geo: &GeoArgs, outputs: &Outputs, code: ExitCode) -> ExitCode {
    if outputs.json {
        print_json(&serde_json::json!({
            "input": geo.input,
            "level": geo.level,
            "written": outputs.written(),
            "printability": outputs.printability,
        }));
    }
    code
}

/// Writes a claims file (`render --claims`).
pub(super) fn write_claims(
    outputs: &mut Outputs,
    path: &std::path::Path,
    claims: &lacuna::meshcheck::Claims,
) -> Result<(), Error> {
    outputs.write(path, |w| w.write_all(claims.to_json().as_bytes()))?;
    outputs.say(&format!("wrote {}\n", path.display()));
    Ok(())
}

/// A positive exact number given on the command line (an integer, a decimal or a fraction, as
/// every number of lacuna), as a float.
fn positive_number(flag: &'static str, text: &str) -> Result<f64, Error> {
    let value = lacuna::input::parse_rational(text.trim())
        .and_then(|r| num_traits::ToPrimitive::to_f64(&r).filter(|x| x.is_finite()));
    match value {
        Some(x) if x > 0.0 => Ok(x),
        _ => Err(Error::OutOfRange {
            flag,
            value: text.to_string(),
            what: "the thickness of the solid in mm",
            range: "a positive number: an integer, a decimal or a fraction (2, 0.8, 1/2)".into(),
        }),
    }
}

/// Chooses the orientation (`--orient`), turns the parts to it and reports the overhang and
/// the area on the bed; a warning when nothing rests on the bed.
pub(super) fn orient(
    parts: &mut [lacuna::mesh::Part],
    how: OrientArg,
    outputs: &Outputs,
) -> lacuna::mesh::orient::Orientation {
    let mut o = lacuna::mesh::orient::choose(parts, how == OrientArg::Auto);
    if let Err(why) = lacuna::mesh::orient::turn_checked(parts, &o) {
        // The rounded turn did not pass the mesh check: the best axis direction instead.
        eprintln!("note: {why}; the best axis direction instead");
        o = lacuna::mesh::orient::choose_axis(parts);
        let _ = lacuna::mesh::orient::turn_checked(parts, &o);
    }
    o.largest_bridge_mm = lacuna::mesh::orient::largest_bridge(parts);
    for line in o.text().lines() {
        match line.starts_with("warning:") {
            true => eprintln!("{line}"),
            false => outputs.say(&format!("{line}\n")),
        }
    }
    o
}

/// Writes a 3MF package built in memory (a ZIP is written with seeks) to `p`.
pub(super) fn write_threemf(
    outputs: &mut Outputs,
    p: &std::path::Path,
    f: impl FnOnce(&mut std::io::Cursor<Vec<u8>>) -> std::io::Result<()>,
) -> Result<(), Error> {
    let zip = lacuna::mesh::threemf::in_memory(p, f)?;
    outputs.write(p, |w| w.write_all(&zip))
}

/// `--3mf-parts`: the type parts turned as the solid was (`o`), each named by `name` and of its
/// type's picture colour, written as the parts of one object; a line says what each holds.
pub(super) fn write_type_parts(
    outputs: &mut Outputs,
    p: &std::path::Path,
    title: &str,
    parts: &mut [lacuna::mesh::TypePart],
    o: &lacuna::mesh::orient::Orientation,
    name: impl Fn(usize) -> String,
) -> Result<(), Error> {
    let mut meshes: Vec<lacuna::mesh::Part> = parts.iter().map(|t| t.part.clone()).collect();
    lacuna::mesh::orient::apply(&mut meshes, o);
    for (t, m) in parts.iter_mut().zip(meshes) {
        t.part = m;
    }
    let named: Vec<(String, [u8; 3], &lacuna::mesh::Part)> = parts
        .iter()
        .map(|t| (name(t.ty), lacuna::export::type_colour(t.ty), &t.part))
        .collect();
    let summary: Vec<String> = parts
        .iter()
        .map(|t| format!("{} ×{}", name(t.ty), t.cells))
        .collect();
    outputs.say(&format!(
        "3MF parts: {}, one per type, every cell a closed shell (checked against the exact count of its type): {}\n",
        lacuna::mesh::counted(parts.len(), "part", "parts"),
        summary.join(", ")
    ));
    write_threemf(outputs, p, |zip| {
        lacuna::mesh::threemf::write_parts(title, &named, zip)
    })
}
