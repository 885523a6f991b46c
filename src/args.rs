//! The command line's arguments (clap derive): the commands, their flags and help texts. Part of
//! the `lacuna` binary, not of the library.

use clap::{Args, Parser, Subcommand};
use lacuna::Limits;

#[derive(Parser)]
#[command(
    name = "lacuna",
    version,
    about = "Exact verifier for fractal topology (BC-IFS)"
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
    #[command(flatten)]
    pub(crate) limits: LimitArgs,
    /// No progress bars (they are drawn on standard error only when it is a terminal).
    #[arg(long, global = true, visible_alias = "quiet")]
    pub(crate) no_progress: bool,
}

#[derive(Args)]
pub(crate) struct LimitArgs {
    /// Maximum boundary length of a face type.
    #[arg(long, global = true, default_value_t = Limits::default().max_boundary)]
    pub(crate) max_boundary: usize,
    /// Maximum number of face types in a closure.
    #[arg(long, global = true, default_value_t = Limits::default().max_types)]
    pub(crate) max_types: usize,
    /// Maximum level for counts.
    #[arg(long, global = true, default_value_t = Limits::default().max_level)]
    pub(crate) max_level: u64,
    /// Maximum sub-edge count n of an edge type.
    #[arg(long, global = true, default_value_t = Limits::default().max_subedges)]
    pub(crate) max_subedges: u32,
    /// Maximum delay of an edge or a face.
    #[arg(long, global = true, default_value_t = Limits::default().max_delay)]
    pub(crate) max_delay: u32,
    /// Maximum number of certified digits.
    #[arg(long, global = true, default_value_t = Limits::default().max_digits)]
    pub(crate) max_digits: usize,
    /// Maximum number of unknowns of a constraint system.
    #[arg(long, global = true, default_value_t = Limits::default().max_unknowns)]
    pub(crate) max_unknowns: usize,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Verify a face, an assembly file or a library entry (default: the built-in F0).
    Verify {
        /// Face notation in quotes, a file, or a library name.
        input: Option<String>,
        /// Levels of the counts table.
        #[arg(long, default_value_t = 5)]
        levels: u64,
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// Write the certificate of every verdict (JSON) to this file.
        #[arg(long, value_name = "OUT.json")]
        certificate: Option<std::path::PathBuf>,
    },
    /// Run only the independent checker on a certificate: prints its claim, then every step; exit
    /// 0 when every step the claim needs is proved, 1 when one fails, 3 when steps are missing.
    Check {
        /// The certificate file (JSON).
        certificate: std::path::PathBuf,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// The closure: every face type with its sub-faces and contribution.
    Closure {
        /// Face notation in quotes, a file, or a library name.
        input: String,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Exact counts of faces and lacunas per level.
    Counts {
        /// Face notation in quotes, a file, or a library name.
        input: String,
        /// The last level.
        #[arg(long)]
        levels: u64,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// The exact limit ratio R of lacunas against sub-faces, by eigen analysis.
    Ratio {
        /// Face notation in quotes, a file, or a library name.
        input: String,
        /// Certified decimal digits.
        #[arg(long, default_value_t = 30)]
        digits: usize,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Eigen analysis of subdivision operators (SPEC §8): eigenvalues, fixed point, contraction,
    /// tangent and pseudo-curvature class, end and joining points of curves.
    Operators {
        /// An automaton file, a face, an assembly or a library name (faces are instantiated with
        /// the default parameters first); optional when --matrix is given.
        input: Option<String>,
        /// A matrix to analyse, `[a b; c d]` (repeatable).
        #[arg(long)]
        matrix: Vec<String>,
        /// Estimate the range of pseudo-curvatures at the fixed point of this operator (α = 2
        /// only; floating point, an estimate): needs --points.
        #[arg(long, value_name = "OP", requires = "points")]
        curvature: Option<String>,
        /// The control points of the operator's state in the plane, `x y; x y; …`.
        #[arg(long, requires = "curvature")]
        points: Option<String>,
        /// Word length of the attractor samples for --curvature (at most 16).
        #[arg(long, default_value_t = 8)]
        level: u32,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Inverse design: T = V·D·V⁻¹ from eigenvalues and eigenvectors (one per row), exact.
    Design {
        /// Eigenvalues, e.g. '1 1/2 1/4'.
        #[arg(long)]
        eigenvalues: String,
        /// Eigenvectors, one per row in the order of the eigenvalues, e.g. '[1 0 0; -1 1 0; 1 -2 1]'.
        #[arg(long)]
        eigenvectors: String,
        /// An automaton file to check the operator against.
        #[arg(long, requires = "op")]
        check: Option<String>,
        /// The operator of that automaton to replace.
        #[arg(long, requires = "check")]
        op: Option<String>,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Instantiate the verified model (default parameters: a template fit rounded to an exact point
    /// of the solution space) and export level N: SVG, JSON polygons, OBJ and STL prisms, PNG.
    Render {
        #[command(flatten)]
        geo: GeoArgs,
        /// Write an SVG picture (cells filled, lacunas open).
        #[arg(long, value_name = "OUT.svg")]
        svg: Option<std::path::PathBuf>,
        /// Write the level-N cells as JSON polygons.
        #[arg(long, value_name = "OUT.json")]
        json_out: Option<std::path::PathBuf>,
        /// Write an OBJ mesh: every cell a closed prism of this thickness (printable).
        #[arg(long, value_name = "OUT.obj")]
        obj: Option<std::path::PathBuf>,
        /// Write an ASCII STL mesh: every cell a closed, triangulated prism (printable).
        #[arg(long, value_name = "OUT.stl")]
        stl: Option<std::path::PathBuf>,
        /// Prism thickness for --obj and --stl.
        #[arg(long, default_value_t = 0.05)]
        thickness: f64,
        /// Write a PNG raster (black cells on white).
        #[arg(long, value_name = "OUT.png")]
        png: Option<std::path::PathBuf>,
        /// PNG size in pixels.
        #[arg(long, default_value_t = 1024)]
        size: usize,
        /// Write the relative-density map of level N as an 8-bit grayscale PNG (one pixel per
        /// block, black = covered).
        #[arg(long, value_name = "OUT.png")]
        density: Option<std::path::PathBuf>,
        /// Blocks per side of the density map.
        #[arg(long, default_value_t = 64)]
        density_grid: usize,
        /// Write the default template (the targets to edit for --template) to this file.
        #[arg(long, value_name = "FILE")]
        write_template: Option<std::path::PathBuf>,
    },
    /// Measure the instantiated structure per level: area, perimeter and their factors, box-counting
    /// dimension, holes and components compared with the exact counts (a mismatch fails, exit 1).
    Measure {
        #[command(flatten)]
        geo: GeoArgs,
        /// Raster size for box counting and the smallest raster for holes and components (a power
        /// of two); a level gets a finer one when its smallest hole needs it.
        #[arg(long, default_value_t = 2048)]
        raster: usize,
        /// The finest raster a level may get (a power of two); a hole still narrower fails (E1011).
        #[arg(long, default_value_t = 8192)]
        max_raster: usize,
        /// Blocks per side of the relative-density map of level N (0: none).
        #[arg(long, default_value_t = 64)]
        density_grid: usize,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// One self-contained HTML page: pictures of levels 0–N, type graph, counts, R, the solver's
    /// verdict, measures with the plots of ln A, ln P and the box-counting fit.
    Report {
        #[command(flatten)]
        geo: GeoArgs,
        /// The HTML file to write.
        #[arg(long, value_name = "OUT.html")]
        out: std::path::PathBuf,
        /// Raster size for the measures (a power of two).
        #[arg(long, default_value_t = 1024)]
        raster: usize,
    },
    /// Solve the BC-IFS constraint system of an automaton file, a face or an assembly exactly.
    Solve {
        /// An automaton file, face notation in quotes, an assembly file, or a library name.
        input: String,
        /// Print the free parameters with their directions.
        #[arg(long)]
        params: bool,
        /// Bézier degree of `Bn` edges in generated automata.
        #[arg(long, default_value_t = 2)]
        degree: usize,
        /// Cantor layout of generated automata: gap length / piece length (exact, > 0).
        #[arg(long, default_value = "1")]
        cantor_gap: String,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Close and count every face of a family, in parallel; print the distribution of type counts.
    Census {
        #[command(flatten)]
        spec: CensusArgs,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// List the named structures of the library.
    Library {
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
}

#[derive(Args)]
pub(crate) struct GeoArgs {
    /// Face notation in quotes, a file, or a library name.
    pub(crate) input: String,
    /// The level.
    #[arg(long, default_value_t = 3)]
    pub(crate) level: u32,
    /// Set a free parameter exactly, `NAME=VALUE` (names from `lacuna solve INPUT --params`).
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub(crate) params: Vec<String>,
    /// Segments per Bézier edge when flattening.
    #[arg(long, default_value_t = 4)]
    pub(crate) segments: usize,
    /// Refuse before the work when level N has more cells than this.
    #[arg(long)]
    pub(crate) max_cells: Option<u64>,
    /// The corners of a single face, exact, counter-clockwise: "X Y, X Y, …" (corner i starts
    /// edge i as written).
    #[arg(long, value_name = "\"X Y, X Y, …\"")]
    pub(crate) corners: Option<String>,
    /// Project this template file exactly onto the solution space instead of the default fit
    /// (docs/FORMATS.md; `render --write-template` writes the default one to edit).
    #[arg(long, value_name = "FILE")]
    pub(crate) template: Option<std::path::PathBuf>,
    /// An inequality goal met through an LP: `nonnegative`, `nonnegative=M`, `min-lacuna=S`
    /// (repeatable; docs/GEOMETRY.md).
    #[arg(long = "goal", value_name = "GOAL")]
    pub(crate) goals: Vec<String>,
}

#[derive(Args)]
pub(crate) struct CensusArgs {
    /// Largest boundary length.
    #[arg(long, default_value_t = 6)]
    pub(crate) max_length: usize,
    /// Edge types of the boundaries (comma-separated).
    #[arg(long, default_value = "B2,C2,B3,C3")]
    pub(crate) edges: String,
    /// Edge types for each of Ea, El, Ec (comma-separated).
    #[arg(long, default_value = "B2,C2")]
    pub(crate) params: String,
    /// Algorithms (comma-separated).
    #[arg(long, default_value = "A1,A2")]
    pub(crate) algorithms: String,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub(crate) threads: Option<usize>,
}
