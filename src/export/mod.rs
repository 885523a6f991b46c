//! What leaves lacuna: SVG, PNG, OBJ, STL and JSON writers, the text and JSON reports of the
//! pipeline, and the self-contained HTML report.
//!
//! Architecture invariant: formats what the layers below computed; decides nothing itself. Only the
//! command line sits above it.

pub(crate) mod automaton_writer;
pub(crate) mod html;
pub(crate) mod report;
pub(crate) mod writer;

pub use automaton_writer::{
    automaton_raster, automaton_report_html, automaton_svg, write_automaton_json,
    write_automaton_obj, write_automaton_svg,
};
pub use html::report_html;
pub use report::{
    closure_json, closure_report, counts_json, counts_table, ratio_of, ratio_text, verify_report,
    VerifyReport,
};
pub use writer::{
    render_raster, triangulate, write_density_png, write_json, write_obj, write_png, write_stl,
    write_svg,
};
