//! The command line's arguments (clap derive): the commands, their flags and help texts. Part of
//! the `lacuna` binary, not of the library.

use clap::{Args, Parser, Subcommand};
use lacuna::topology::Limits;

#[derive(Parser)]
#[command(
    name = "lacuna",
    version,
    about = "Exact verifier for fractal topology (BC-IFS)"
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
    /// No progress bars (they are drawn on standard error only when it is a terminal).
    #[arg(long, global = true, visible_alias = "quiet", help_heading = "Global")]
    pub(crate) no_progress: bool,
}

/// The limits of the exact work, on the commands that do such work (not on `check`, `design`,
/// `library`), under their own help heading.
#[derive(Args)]
pub(crate) struct LimitArgs {
    /// Maximum boundary length of a face type.
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_boundary)]
    pub(crate) max_boundary: usize,
    /// Maximum number of face types in a closure.
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_types)]
    pub(crate) max_types: usize,
    /// Maximum level for counts.
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_level)]
    pub(crate) max_level: u64,
    /// Maximum sub-edge count n of an edge type.
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_subedges)]
    pub(crate) max_subedges: u32,
    /// Maximum delay of an edge or a face.
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_delay)]
    pub(crate) max_delay: u32,
    /// Maximum number of certified digits.
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_digits)]
    pub(crate) max_digits: usize,
    /// Maximum number of unknowns of a constraint system.
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_unknowns)]
    pub(crate) max_unknowns: usize,
    /// Maximum estimated memory of a constraint solve, in MiB (checked before the solve).
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_memory_mb)]
    pub(crate) max_memory: u64,
    /// Maximum size n of an n×n matrix for eigen analysis (`operators`).
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_matrix)]
    pub(crate) max_matrix: usize,
    /// Maximum number of operator products formed to prove that an automaton contracts (one of
    /// more than 1000 scalar multiplications counts as that many thousands).
    #[arg(long, help_heading = "Limits", default_value_t = Limits::default().max_products)]
    pub(crate) max_products: usize,
}

impl LimitArgs {
    /// The limits these flags set.
    pub(crate) fn limits(&self) -> Limits {
        Limits {
            max_boundary: self.max_boundary,
            max_types: self.max_types,
            max_level: self.max_level,
            max_subedges: self.max_subedges,
            max_delay: self.max_delay,
            max_digits: self.max_digits,
            max_unknowns: self.max_unknowns,
            max_memory_mb: self.max_memory,
            max_matrix: self.max_matrix,
            max_products: self.max_products,
        }
    }
}

/// A command's own arguments followed by the limit flags.
#[derive(Args)]
pub(crate) struct Limited<T: Args> {
    #[command(flatten)]
    pub(crate) args: T,
    #[command(flatten)]
    pub(crate) limits: LimitArgs,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Verify a face, an assembly file or a library entry (default: the built-in F0).
    Verify(Limited<VerifyArgs>),
    /// Run only the independent checker on a certificate: prints its claim, then every step; exit
    /// 0 when every step the claim needs is proved, 1 when one fails, 2 when one is refused for
    /// cost (a budget, not a verdict), 3 when steps are missing.
    Check(CheckArgs),
    /// Re-check a printable mesh (binary or ASCII STL, 3MF) from the file alone, sharing no code
    /// with lacuna's mesh writer: exact coordinates, no degenerate triangle, closed and oriented
    /// (every edge in two triangles of opposite directions), every vertex link one cycle, no two
    /// triangles crossing, and per part V, E, F, χ, genus and the enclosed volume; exit 0 when
    /// every check passes and every expectation holds, 1 when one fails, 2 for bad input.
    CheckMesh(CheckMeshArgs),
    /// The closure: every face type with its sub-faces and contribution.
    Closure(Limited<ClosureArgs>),
    /// Exact counts of faces and lacunas per level.
    Counts(Limited<CountsArgs>),
    /// The exact limit ratio R of lacunas against sub-faces, by eigen analysis.
    Ratio(Limited<RatioArgs>),
    /// Eigen analysis of subdivision operators (THEORY §8): eigenvalues, fixed point, contraction,
    /// tangent and pseudo-curvature class, end and joining points of curves.
    Operators(Limited<OperatorsArgs>),
    /// Inverse design: T = V·D·V⁻¹ from eigenvalues and eigenvectors (one per row), exact.
    Design(DesignArgs),
    /// Instantiate the verified model (default parameters: a template fit rounded to an exact point
    /// of the solution space) and export level N: SVG, JSON polygons, PNG, and printable solids (STL,
    /// 3MF, OBJ) checked against the exact topology.
    // Boxed: its many flags make it the largest variant by far.
    Render(Box<Limited<RenderArgs>>),
    /// Measure the instantiated structure per level: area, perimeter and their factors, box-counting
    /// dimension, holes and components compared with the exact counts (a mismatch fails, exit 1).
    Measure(Limited<MeasureArgs>),
    /// One self-contained HTML page: pictures of levels 0–N, type graph, counts, R, the solver's
    /// verdict, measures with the plots of ln A, ln P and the box-counting fit.
    Report(Limited<ReportArgs>),
    /// Solve the BC-IFS constraint system of an automaton file, a face or an assembly exactly.
    Solve(Limited<SolveArgs>),
    /// Close and count every face of a family, in parallel; print the distribution of type counts.
    Census(Limited<CensusArgs>),
    /// List the named structures of the library.
    Library(LibraryArgs),
    /// Write the generated automaton of a face or an assembly: in lacuna's automaton format
    /// (`aut`, which `lacuna solve` reads back with the same rank and degrees of freedom) or as
    /// the MODITERE Python model that AutoFrac2D writes (`moditere`).
    Export(Limited<ExportArgs>),
    /// Property-based exploration of a rule over a family of boundaries: closes, consistent, no
    /// forced collapse, R exists, the certificate checks; each failure shrunk to a minimal
    /// counterexample (exit 1 when a property fails).
    Explore(Limited<ExploreArgs>),
    /// Topological class (THEORY §13): cardinality (cells per level) and multiplicity (valences of
    /// the level-k complex and of the limit) of two inputs; exit 0 same class, 1 different, with
    /// the first invariant that differs.
    Classify(Limited<ClassifyArgs>),
    /// Metamorphosis (THEORY §13): frames along the segment between two parameter choices of one
    /// structure, each verified (no forced collapse, observed holes and components equal to the
    /// exact counts); an animated SVG and PNG frames; exit 1 with the first failing frame.
    Morph(Limited<MorphArgs>),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell) on standard output.
    Completions(CompletionsArgs),
    /// Print the manual page (roff, for `man -l -`) on standard output; with `--all DIR`, write
    /// a page for lacuna and one for every subcommand (`lacuna-verify.1`, …) into DIR.
    Man(ManArgs),
}

/// The export formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum ExportFormat {
    /// lacuna's automaton format (docs/FORMATS.md).
    Aut,
    /// The MODITERE Python model of AutoFrac2DCLI (docs/FORMATS.md).
    Moditere,
}

/// The arguments of `lacuna export`.
#[derive(Args)]
pub(crate) struct ExportArgs {
    /// Face notation in quotes, an assembly or AutoFrac2D file, a library name (or, for `aut`,
    /// an automaton file).
    pub(crate) input: String,
    /// The format.
    #[arg(long)]
    pub(crate) format: ExportFormat,
    /// Write to this file instead of standard output.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub(crate) output: Option<std::path::PathBuf>,
    /// Bézier degree of `Bn` edges in the generated automaton.
    #[arg(long, default_value_t = 2)]
    pub(crate) degree: usize,
    /// Cantor layout of the generated automaton: gap length / piece length (exact, > 0).
    #[arg(long, default_value = "1")]
    pub(crate) cantor_gap: String,
}

/// The arguments of `lacuna explore`.
#[derive(Args)]
pub(crate) struct ExploreArgs {
    /// Edge types of the boundaries (comma-separated).
    #[arg(long, default_value = "B2,C2")]
    pub(crate) edges: String,
    /// Largest boundary length (every length from 1 up).
    #[arg(long, default_value_t = 4)]
    pub(crate) max_length: usize,
    /// Edge types for each of Ea, El, Ec (comma-separated; every combination is explored).
    #[arg(long, default_value = "C2,B2")]
    pub(crate) params: String,
    /// The algorithm: A1, A2, A3, AF1 or a spoke set such as '{gap}'.
    #[arg(long, default_value = "A1")]
    pub(crate) algorithm: String,
    /// Properties to check (comma-separated): closes, consistent, no-collapse, ratio,
    /// certificate, holes (opt-in: instantiates and measures the geometry); `all` for every one
    /// but holes.
    #[arg(long, default_value = "closes,consistent,no-collapse,ratio")]
    pub(crate) properties: String,
    /// Random family: this many boundaries (lengths 1..=max-length, edges uniform) instead of
    /// every boundary.
    #[arg(long, value_name = "N")]
    pub(crate) random: Option<u64>,
    /// Seed of the random family.
    #[arg(long, default_value_t = 0)]
    pub(crate) seed: u64,
    /// Explore only part i of n of the family (1 ≤ i ≤ n): boundary k belongs to part
    /// k mod n + 1. Merged parts give the lines of one run.
    #[arg(long, value_name = "i/n")]
    pub(crate) shard: Option<String>,
    /// Most property evaluations spent shrinking one failure.
    #[arg(long, default_value_t = 400)]
    pub(crate) shrink_budget: usize,
    /// Worker threads (default: all cores); the output does not depend on their number.
    #[arg(long)]
    pub(crate) threads: Option<usize>,
    /// The last level at which the `holes` property compares observed and exact holes (1 to 6).
    #[arg(long, default_value_t = lacuna::family::DEFAULT_HOLES_LEVEL)]
    pub(crate) holes_level: u32,
    /// Maximum estimated work of the `holes` property, in cells: the faces of the family times
    /// 4^--holes-level (the cells of a four-spoke face at that level), checked before any face
    /// is measured.
    #[arg(
        long,
        value_name = "N",
        default_value_t = lacuna::family::DEFAULT_MAX_HOLES_CELLS,
        help_heading = "Limits"
    )]
    pub(crate) max_holes_cells: u64,
    /// JSON lines: one per boundary, then a summary line.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna check-mesh`.
#[derive(Args)]
pub(crate) struct CheckMeshArgs {
    /// The mesh: binary or ASCII STL, or 3MF (told apart by content; `-` reads standard input).
    #[arg(value_name = "FILE.stl|FILE.3mf")]
    pub(crate) file: std::path::PathBuf,
    /// The expected Euler characteristic (the sum over the parts of V − E + F).
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    pub(crate) expect_euler: Option<i64>,
    /// The expected number of parts (connected surfaces).
    #[arg(long, value_name = "P")]
    pub(crate) expect_parts: Option<u64>,
    /// Compare with the claims file `render --claims` wrote (triangles, parts, χ and genus).
    #[arg(long, value_name = "CLAIMS.json")]
    pub(crate) claims: Option<std::path::PathBuf>,
    /// Refuse a mesh of more triangles than this before the work (exit 2: a limit, not a
    /// verdict; at most 2^30).
    #[arg(long, value_name = "N", help_heading = "Limits", default_value_t = lacuna::meshcheck::DEFAULT_MAX_TRIANGLES)]
    pub(crate) max_triangles: u64,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna man`.
#[derive(Args)]
pub(crate) struct ManArgs {
    /// Write every page (lacuna.1 and lacuna-SUBCOMMAND.1) into this folder, created if needed,
    /// instead of printing lacuna's page.
    #[arg(long, value_name = "DIR")]
    pub(crate) all: Option<std::path::PathBuf>,
}

/// The arguments of `lacuna completions`.
#[derive(Args)]
pub(crate) struct CompletionsArgs {
    /// The shell.
    pub(crate) shell: clap_complete::Shell,
}

/// The arguments of `lacuna verify`.
#[derive(Args)]
pub(crate) struct VerifyArgs {
    /// Face notation in quotes, a file (`-`: standard input), or a library name.
    pub(crate) input: Option<String>,
    /// Levels of the counts table.
    #[arg(long, default_value_t = 5)]
    pub(crate) levels: u64,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
    /// Write the certificate of every verdict (JSON) to this file.
    #[arg(long, value_name = "OUT.json")]
    pub(crate) certificate: Option<std::path::PathBuf>,
}

/// The arguments of `lacuna check`.
#[derive(Args)]
pub(crate) struct CheckArgs {
    /// The certificate file (JSON; `-`: standard input).
    pub(crate) certificate: std::path::PathBuf,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
    /// Maximum big-integer word operations of the whole check, estimated before each phase or
    /// counted as it goes (a step above it is refused for cost, exit 2, not rejected).
    #[arg(long, value_name = "N", default_value_t = lacuna::checker::Budget::default().work, help_heading = "Limits")]
    pub(crate) max_work: u128,
    /// Maximum levels of counts a limit ratio (`P·d`) or a volume closure may need.
    #[arg(long, value_name = "N", default_value_t = lacuna::checker::Budget::default().levels, help_heading = "Limits")]
    pub(crate) max_levels: u64,
    /// Maximum sides of the level-1 surfaces of all volume types of a closure together.
    #[arg(long, value_name = "N", default_value_t = lacuna::checker::Budget::default().sides, help_heading = "Limits")]
    pub(crate) max_sides: u128,
}

/// The arguments of `lacuna closure`.
#[derive(Args)]
pub(crate) struct ClosureArgs {
    /// Face notation in quotes, a file (`-`: standard input), or a library name.
    pub(crate) input: String,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna counts`.
#[derive(Args)]
pub(crate) struct CountsArgs {
    /// Face notation in quotes, a file (`-`: standard input), or a library name.
    pub(crate) input: String,
    /// The last level.
    #[arg(long)]
    pub(crate) levels: u64,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

/// What `classify` reads of an automaton's multiplicity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum MultiplicityArg {
    /// Also count the pieces meeting at the images of fixed corners (shown, not compared).
    Contacts,
    /// Pieces that are one exact map (seed 002), compared.
    Coincidences,
}

/// The arguments of `lacuna classify`.
#[derive(Args)]
pub(crate) struct ClassifyArgs {
    /// The first input: face notation in quotes, a file, or a library name (faces, assemblies,
    /// volumes, automata).
    pub(crate) a: String,
    /// The second input.
    pub(crate) b: String,
    /// Compare levels 0 to this at least (more when the recurrence orders of faces need more to
    /// decide every level).
    #[arg(long, default_value_t = 4)]
    pub(crate) levels: u64,
    /// For a volume: build its level-k complex for k = 0 to this (at most --levels) and compare
    /// the valences of its corners.
    #[arg(long, default_value_t = 2)]
    pub(crate) volume_levels: u64,
    /// Refuse before the work when a volume's level-k complex has more cells than this.
    #[arg(long, default_value_t = 200_000)]
    pub(crate) max_cells: u64,
    /// For an automaton: `coincidences` compares seed 002's multiplicity (eq. (18): how many
    /// pieces of a level are one exact map, the points a curve defines more than once);
    /// `contacts` also counts the pieces meeting at each image of a fixed corner, shown in a
    /// note and not compared (those points depend on how the automaton is written).
    #[arg(long, value_enum, default_value_t = MultiplicityArg::Coincidences)]
    pub(crate) multiplicity: MultiplicityArg,
    /// Print JSON: `{"same_class", "differs", …}`.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna morph`.
#[derive(Args)]
pub(crate) struct MorphArgs {
    /// The first parameter choice: a template file, `NAME=VALUE,…` (exact `--param` values),
    /// or `default` (the default fit) — of the structure given by --on; or an automaton file.
    pub(crate) a: String,
    /// The second parameter choice (same form as A; an automaton of A's shape when A is one).
    pub(crate) b: String,
    /// The structure the two choices parametrize: face notation in quotes, a file, or a library
    /// name (not needed for two automata).
    #[arg(long, value_name = "INPUT")]
    pub(crate) on: Option<String>,
    /// Number of frames, both ends included (at least 2).
    #[arg(long, default_value_t = 9)]
    pub(crate) frames: u32,
    /// The level drawn and checked in every frame.
    #[arg(long, default_value_t = 2)]
    pub(crate) level: u32,
    /// The animated SVG to write.
    #[arg(long, value_name = "FILE")]
    pub(crate) svg: Option<std::path::PathBuf>,
    /// Write frame k as PNG to this pattern, `{}` replaced by k (`frame-{}.png`).
    #[arg(long, value_name = "PATTERN")]
    pub(crate) png: Option<String>,
    /// Side of the PNG frames and of the raster that counts holes, in pixels.
    #[arg(long, default_value_t = 512)]
    pub(crate) size: u32,
    /// Seconds per frame in the animation.
    #[arg(long, default_value_t = 0.5)]
    pub(crate) seconds: f64,
    /// Refuse before the work when one frame has more cells than this.
    #[arg(long, default_value_t = 200_000)]
    pub(crate) max_cells: u64,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna ratio`.
#[derive(Args)]
pub(crate) struct RatioArgs {
    /// Face notation in quotes, a file (`-`: standard input), or a library name.
    pub(crate) input: String,
    /// Certified decimal digits.
    #[arg(long, default_value_t = 30)]
    pub(crate) digits: usize,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna operators`.
#[derive(Args)]
pub(crate) struct OperatorsArgs {
    /// An automaton file, a face, an assembly or a library name (faces are instantiated with
    /// the default parameters first); optional when --matrix is given.
    pub(crate) input: Option<String>,
    /// A matrix to analyse, `[a b; c d]` (repeatable).
    #[arg(long)]
    pub(crate) matrix: Vec<String>,
    /// Estimate the range of pseudo-curvatures at the fixed point of this operator (α = 2
    /// only; floating point, an estimate): needs --points.
    #[arg(long, value_name = "OP", requires = "points")]
    pub(crate) curvature: Option<String>,
    /// Control points of a curve's state, `x y; x y; …` (2D) or `x y z; …` (3D): adds the
    /// differential characteristic functions and pseudo-curvature ranges of every curve whose
    /// state has that many points.
    #[arg(long)]
    pub(crate) points: Option<String>,
    /// Word length of the attractor samples for --curvature and the curvature ranges.
    #[arg(long, default_value_t = 8)]
    pub(crate) level: u32,
    /// Analyse only this operator of the automaton or face.
    #[arg(long, value_name = "NAME")]
    pub(crate) op: Option<String>,
    /// A dyadic parameter t of the curve (I-adic for I operators, e.g. 3/8) where the left and
    /// right pseudo-curvature ranges are also given (repeatable; needs --points).
    #[arg(long, value_name = "T", requires = "points")]
    pub(crate) at: Vec<String>,
    /// Print every exact form in full (matrix, characteristic polynomial, eigenvectors).
    #[arg(long)]
    pub(crate) exact: bool,
    /// With --points in the plane: write the curve with the osculating circles of κinf and
    /// κsup at the reported points to this SVG file (one file per curve: the state's name is
    /// inserted before the extension when there are several).
    #[arg(long, value_name = "OUT.svg", requires = "points")]
    pub(crate) svg: Option<std::path::PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna design`.
#[derive(Args)]
pub(crate) struct DesignArgs {
    /// Eigenvalues, e.g. '1 1/2 1/4'.
    #[arg(long)]
    pub(crate) eigenvalues: String,
    /// Eigenvectors, one per row in the order of the eigenvalues, e.g. '[1 0 0; -1 1 0; 1 -2 1]'.
    #[arg(long)]
    pub(crate) eigenvectors: String,
    /// An automaton file to check the operator against.
    #[arg(long, requires = "op")]
    pub(crate) check: Option<String>,
    /// The operator of that automaton to replace.
    #[arg(long, requires = "check")]
    pub(crate) op: Option<String>,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna render`.
#[derive(Args)]
pub(crate) struct RenderArgs {
    #[command(flatten)]
    pub(crate) geo: GeoArgs,
    /// Write an SVG picture (cells filled, lacunas open); `-` writes it on standard output, as
    /// every output flag.
    #[arg(long, value_name = "OUT.svg")]
    pub(crate) svg: Option<std::path::PathBuf>,
    /// Write the level-N cells as JSON polygons.
    #[arg(long, value_name = "OUT.json")]
    pub(crate) json_out: Option<std::path::PathBuf>,
    /// Print one JSON object on standard output when done: the input, the level, the files
    /// written and the printability of the mesh (`printability`, as `measure --json` has it;
    /// null without --stl, --3mf or --obj). The status lines go to standard error.
    #[arg(long)]
    pub(crate) json: bool,
    /// Write the solid as a Wavefront OBJ mesh (triangles, one object per component, mm).
    #[arg(long, value_name = "OUT.obj")]
    pub(crate) obj: Option<std::path::PathBuf>,
    /// Write the solid as STL (binary; --stl-ascii for ASCII), mm: one closed manifold per
    /// component, checked against the exact topology before writing.
    #[arg(long, value_name = "OUT.stl")]
    pub(crate) stl: Option<std::path::PathBuf>,
    /// Write --stl as ASCII instead of binary.
    #[arg(long, requires = "stl")]
    pub(crate) stl_ascii: bool,
    /// With --stl or --3mf: write what the mesh is claimed to be (triangles, parts, χ and genus
    /// from the exact topology; for an automaton's shell, from lacuna's check of it) as JSON, for
    /// `lacuna check-mesh MESH --claims CLAIMS.json`.
    #[arg(long, value_name = "OUT.json")]
    pub(crate) claims: Option<std::path::PathBuf>,
    /// Write the solid as 3MF (core specification, unit millimetre, one object per component).
    #[arg(long = "3mf", value_name = "OUT.3mf")]
    pub(crate) threemf: Option<std::path::PathBuf>,
    /// Colour the 3MF by type (a base material per face or volume type, the picture's colours):
    /// for faces every triangle lies in one cell (the top and bottom triangulated cell by
    /// cell), for volumes on one sub-volume. The same checked solid is written to --stl and
    /// --obj.
    #[arg(long = "3mf-colours", requires = "threemf")]
    pub(crate) threemf_colours: bool,
    /// Write the 3MF as one part per face or volume type, each of its type's colour, together
    /// one object (for a multi-material slicer: one extruder per part). Every cell is a closed
    /// shell of its own, checked against the exact count of its type's cells; --stl and --obj
    /// get the one checked solid.
    #[arg(
        long = "3mf-parts",
        requires = "threemf",
        conflicts_with_all = ["threemf_colours", "claims"]
    )]
    pub(crate) threemf_parts: bool,
    /// Thickness of the solid in mm for --stl, --3mf and --obj (exact: 2, 1/2, 0.8; default 2).
    /// For an automaton's surface: thicken it into a closed shell (without it, --stl and --3mf
    /// write the open surface).
    #[arg(long, value_name = "MM")]
    pub(crate) thickness: Option<String>,
    #[command(flatten)]
    pub(crate) print: PrintArgs,
    /// Write a colour PNG: anti-aliased cells filled by type (the SVG's palette), with a legend.
    #[arg(long, value_name = "OUT.png")]
    pub(crate) png: Option<std::path::PathBuf>,
    /// Width in pixels of the PNG picture, and side of the density map.
    #[arg(long, default_value_t = 1024)]
    pub(crate) size: usize,
    /// Background of the SVG and PNG pictures.
    #[arg(long, value_enum, default_value_t = BackgroundArg::White)]
    pub(crate) background: BackgroundArg,
    /// Leave the legend (type → colour and notation) out of the SVG and PNG pictures.
    #[arg(long)]
    pub(crate) no_legend: bool,
    /// Write the relative-density map of level N as a colour PNG, --size pixels a side (viridis:
    /// dark violet empty to yellow full; outside the face grey), with a colour bar, the grid and the mask stated.
    #[arg(long, value_name = "OUT.png")]
    pub(crate) density: Option<std::path::PathBuf>,
    /// Blocks per side of the density map.
    #[arg(long, default_value_t = 64)]
    pub(crate) density_grid: usize,
    /// Write the default template (the targets to edit for --template) to this file.
    #[arg(long, value_name = "FILE")]
    pub(crate) write_template: Option<std::path::PathBuf>,
    /// An automaton: draw the attractor of this state instead of the start state's, from its
    /// frame (the start's points carried by the first operator reaching it, breadth first), in
    /// every output. The start must reach it.
    #[arg(long, value_name = "NAME")]
    pub(crate) state: Option<String>,
}

/// Sizes for printing (THEORY §11), shared by `render` and `measure`.
#[derive(Args)]
pub(crate) struct PrintArgs {
    /// Width in mm of the level-0 faces (x extent): the structure is scaled to it.
    #[arg(long, default_value_t = lacuna::mesh::DEFAULT_WIDTH, value_name = "MM")]
    pub(crate) width: f64,
    /// The printer's smallest feature in mm: smaller holes, ligaments and walls get a warning.
    #[arg(long, default_value_t = lacuna::mesh::DEFAULT_RESOLUTION, value_name = "MM")]
    pub(crate) resolution: f64,
    /// A hole, ligament or wall below --resolution is a failure (E1042, exit 1), not a warning.
    #[arg(long)]
    pub(crate) strict: bool,
    /// The printer's build volume in mm, `XxYxZ`: a solid that does not fit it, or fills it to
    /// within 1 mm, gets a warning (with the --width that would fit).
    #[arg(long, default_value = "200x200x200", value_name = "XxYxZ", value_parser = parse_bed)]
    pub(crate) bed: [f64; 3],
    /// The orientation of the mesh written: `keep` (as built, z up) or `auto` (the axis
    /// direction down with the least overhang that rests a face on the bed). Both report the
    /// overhang beyond 45° and the area on the bed.
    #[arg(long, value_enum, default_value = "keep")]
    pub(crate) orient: OrientArg,
    /// Horizontal layers of a solid (a volume or a shell) whose smallest hole and thinnest
    /// ligament are measured, at the middles of equal bands of its height.
    #[arg(long, default_value_t = lacuna::mesh::slice::DEFAULT_LAYERS, value_name = "N",
          value_parser = parse_layers)]
    pub(crate) layers: usize,
}

/// `--layers N`: from 1 to [`lacuna::mesh::slice::MAX_LAYERS`].
fn parse_layers(s: &str) -> Result<usize, String> {
    let max = lacuna::mesh::slice::MAX_LAYERS;
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!(
            "`{s}` is not a number of layers: give an integer from 1 to {max}"
        )),
    }
}

/// How the mesh written is oriented (`--orient`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum OrientArg {
    // As built: z up. (Plain comments: documented variants would turn every help text that
    // shows this flag into the long layout.)
    Keep,
    // The best of the six axis directions down (GEOMETRY §5).
    Auto,
}

/// `--bed XxYxZ`: three positive sizes in mm, separated by `x` (or `×`).
fn parse_bed(s: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(['x', '×', 'X']).map(str::trim).collect();
    let sizes: Vec<f64> = parts
        .iter()
        .filter_map(|p| p.parse::<f64>().ok())
        .filter(|v| v.is_finite() && *v > 0.0)
        .collect();
    match sizes.as_slice() {
        [x, y, z] if parts.len() == 3 => Ok([*x, *y, *z]),
        _ => Err(format!(
            "`{s}` is not a build volume: give three positive sizes in mm, such as 200x200x200"
        )),
    }
}

/// The background of a picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum BackgroundArg {
    /// Opaque white.
    White,
    /// Transparent.
    Transparent,
}

impl From<BackgroundArg> for lacuna::export::Background {
    fn from(b: BackgroundArg) -> Self {
        match b {
            BackgroundArg::White => lacuna::export::Background::White,
            BackgroundArg::Transparent => lacuna::export::Background::Transparent,
        }
    }
}

/// The arguments of `lacuna measure`.
#[derive(Args)]
pub(crate) struct MeasureArgs {
    #[command(flatten)]
    pub(crate) geo: GeoArgs,
    /// Raster size for box counting and the smallest raster for holes and components (a power
    /// of two); a level gets a finer one when its smallest hole needs it.
    #[arg(long, default_value_t = lacuna::measure::MeasureOptions::default().raster)]
    pub(crate) raster: usize,
    /// The finest raster a level may get (a power of two); a hole still narrower fails (E1011).
    #[arg(long, default_value_t = lacuna::measure::MeasureOptions::default().max_raster)]
    pub(crate) max_raster: usize,
    /// Blocks per side of the relative-density map of level N (0: none).
    #[arg(long, default_value_t = 64)]
    pub(crate) density_grid: usize,
    #[command(flatten)]
    pub(crate) print: PrintArgs,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
    /// Certified digits of the similarity dimension of an automaton.
    #[arg(long, default_value_t = 30)]
    pub(crate) digits: usize,
    /// Write the certificate of the faces and of the chosen point (JSON; a `level-one` step
    /// proves the exact level-1 line) to this file. Faces only: for volumes and automata
    /// `lacuna verify --certificate` certifies the exact figures.
    #[arg(long, value_name = "OUT.json")]
    pub(crate) certificate: Option<std::path::PathBuf>,
    /// An automaton: measure the attractor of this state instead of the start state's, from
    /// its frame (as `render --state` draws it). The start must reach it.
    #[arg(long, value_name = "NAME")]
    pub(crate) state: Option<String>,
}

/// The arguments of `lacuna report`.
#[derive(Args)]
pub(crate) struct ReportArgs {
    #[command(flatten)]
    pub(crate) geo: GeoArgs,
    /// The HTML file to write.
    #[arg(long, value_name = "OUT.html")]
    pub(crate) out: std::path::PathBuf,
    /// Raster size for box counting and the smallest raster for holes and components (a power
    /// of two), as in `lacuna measure`.
    #[arg(long, default_value_t = lacuna::measure::MeasureOptions::default().raster)]
    pub(crate) raster: usize,
}

/// The arguments of `lacuna solve`.
#[derive(Args)]
pub(crate) struct SolveArgs {
    /// An automaton file, face notation in quotes, an assembly file, or a library name.
    pub(crate) input: String,
    /// Print the free parameters with their directions.
    #[arg(long)]
    pub(crate) params: bool,
    /// Bézier degree of `Bn` edges in generated automata.
    #[arg(long, default_value_t = 2)]
    pub(crate) degree: usize,
    /// Cantor layout of generated automata: gap length / piece length (exact, > 0).
    #[arg(long, default_value = "1")]
    pub(crate) cantor_gap: String,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna census`.
#[derive(Args)]
pub(crate) struct CensusArgs {
    #[command(flatten)]
    pub(crate) spec: CensusSpecArgs,
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The arguments of `lacuna library`.
#[derive(Args)]
pub(crate) struct LibraryArgs {
    /// Print JSON.
    #[arg(long)]
    pub(crate) json: bool,
}

#[derive(Args)]
pub(crate) struct GeoArgs {
    /// Face notation in quotes, a file (`-`: standard input), or a library name.
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
pub(crate) struct CensusSpecArgs {
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
