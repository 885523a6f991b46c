//! What leaves lacuna: SVG and colour PNG pictures with legends, density maps, OBJ, STL and JSON
//! writers, the text and JSON reports of the pipeline, the self-contained HTML report, and the
//! generated automaton in lacuna's automaton format and in the MODITERE Python format of the seed
//! authors' AutoFrac2D tool.
//!
//! Architecture invariant: formats what the layers below computed; decides nothing itself. Only the
//! command line sits above it.

pub(crate) mod automaton_text;
pub(crate) mod automaton_writer;
pub(crate) mod bitmap;
pub(crate) mod classify;
pub(crate) mod generated;
pub(crate) mod graph;
pub(crate) mod html;
pub(crate) mod moditere;
pub(crate) mod morph;
pub(crate) mod operators;
pub(crate) mod palette;
pub(crate) mod picture;
pub(crate) mod plot;
pub(crate) mod report;
pub(crate) mod report_page;
pub(crate) mod volume_mesh;
pub(crate) mod volume_picture;
pub(crate) mod volume_report;
pub(crate) mod writer;

pub use automaton_text::automaton_text;
pub use automaton_writer::{
    automaton_raster, automaton_report_html, automaton_svg, write_automaton_json,
    write_automaton_obj, write_automaton_png, write_automaton_svg,
};
pub use bitmap::{
    write_density_picture, write_png_picture, write_shapes_png, DensityPicture, Projection,
};
pub use classify::{classify_inputs, ClassifyOptions, ClassifyOutcome};
pub use generated::{generated_text, GeneratedFormat};
pub use html::{report_html, report_html_unverified};
pub use moditere::moditere_text;
pub use morph::{
    morph_automata, morph_faces, morph_png_paths, write_morph_automaton_png, write_morph_png,
    write_morph_svg, FrameCells, MorphFrames,
};
pub use operators::{
    design_report, operators_automaton, operators_report, DesignReport, OperatorsInput,
    OperatorsReport, OperatorsRequest,
};
pub use palette::{
    density_colour, hex, lightness, outline_colour, type_colour, Rgb, MUTED, OUTSIDE,
};
pub use picture::{
    legend_entries, outline, stroke_width, write_svg_picture, Background, Frame, PictureOptions,
};
pub use report::{
    closure_json, closure_report, counts_json, counts_table, ratio_of, ratio_text, verify_report,
    VerifyReport,
};
pub use report_page::{automaton_report_page, faces_report_page, volume_report_page, ReportPage};
pub use volume_mesh::{mesh_claims, volume_measure_json, volume_solid_claims, volume_type_colours};
pub use volume_picture::{
    volume_report_html, volume_svg, volume_viewer, volume_viewer_with_id, write_volume_png,
    write_volume_svg,
};
pub use volume_report::{
    solid_table, surface_summary, volume_closure_json, volume_closure_text, volume_counts_table,
    volume_ratio, volume_verify, VolumeVerify,
};
pub use writer::{
    render_raster, triangulate, write_density_png, write_json, write_obj, write_png, write_stl,
    write_svg,
};
