//! The MODITERE Python model that the seed authors' AutoFrac2D command-line tool writes
//! (`output.py`), produced from lacuna's closure, for `lacuna export INPUT --format moditere`.
//!
//! The layout follows AutoFrac2DCLI's `StructurePrinter::exportStruct` section by section
//! (`docs/FORMATS.md`, "Export formats"): the vertex state `s`; one state per edge type with its
//! embeddings, reversal, subdivision and fixed operators; one state `Cell_<t>` per face type of the
//! closure; the start faces as the subdivisions of `init`; boundaries, subdivisions, spaces, grids
//! and primitives of every cell; incidence, adjacency and edge-adjacency constraints of every cell
//! and the shared edges of the start faces; the control points of the start faces; and, where
//! AutoFrac2D loads matrices saved from a previous optimisation, lacuna's exact particular solution
//! of the constraint system. Numbers are written exactly, as Python fractions `p/q` under
//! `from __future__ import division`.

use crate::algebra::matrix::Matrix;
use crate::constraint::{solve_system, Generated, Solution};
use crate::input::{CoordKind, Input};
use crate::topology::{Algorithm, EdgeKind, EdgeType, Face, Limits, TypeSet};
use num_rational::BigRational;
use std::collections::{BTreeSet, HashMap};

/// AutoFrac2D's name of an edge state: `B2`, or `C2_2` for lacuna's `C2^3` (remaining delay).
fn edge_name(e: &EdgeType) -> String {
    let k = match e.kind {
        EdgeKind::B => "B",
        EdgeKind::C => "C",
    };
    if e.is_delayed() {
        format!("{k}{}_{}", e.n, e.delay - 1)
    } else {
        format!("{k}{}", e.n)
    }
}

/// AutoFrac2D's text of an edge in a cell name: `C_2_0`.
fn edge_text(e: &EdgeType) -> String {
    let k = match e.kind {
        EdgeKind::B => "B",
        EdgeKind::C => "C",
    };
    format!("{k}_{}_{}", e.n, e.delay - 1)
}

/// AutoFrac2D's algorithm number where one exists (0 = A3, 1 = AF1 or A1 without delays, 2 =
/// A2), else lacuna's notation of the algorithm.
fn algorithm_text(f: &Face) -> String {
    let delays = f.delay > 1
        || f.boundary
            .iter()
            .chain([&f.params.ea, &f.params.el, &f.params.ec])
            .any(EdgeType::is_delayed);
    if f.algorithm == Algorithm::a3() {
        "0".into()
    } else if f.algorithm == Algorithm::af1() || (f.algorithm == Algorithm::a1() && !delays) {
        "1".into()
    } else if f.algorithm == Algorithm::a2() {
        "2".into()
    } else {
        f.algorithm.to_string()
    }
}

/// AutoFrac2D's `Face::toString`: `C_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1`.
fn cell_text(f: &Face) -> String {
    let edges: Vec<String> = f.boundary.iter().map(edge_text).collect();
    format!(
        "{} / {} - {} - {} / {} / {}",
        edges.join(" - "),
        edge_text(&f.params.ea),
        edge_text(&f.params.el),
        edge_text(&f.params.ec),
        f.delay - 1,
        algorithm_text(f)
    )
}

/// `Cell_<t>`, with `_<remaining delay>` for a delayed face as AutoFrac2D names them.
fn cell_name(t: usize, f: &Face) -> String {
    if f.delay > 1 {
        format!("Cell_{t}_{}", f.delay - 1)
    } else {
        format!("Cell_{t}")
    }
}

fn number(q: &BigRational) -> String {
    q.to_string()
}

/// `FMat([[…], […]])` rows of a matrix (or of some of its columns).
fn fmat(m: &Matrix, cols: &[usize]) -> String {
    let rows: Vec<String> = (0..m.rows)
        .map(|r| {
            let v: Vec<String> = cols.iter().map(|&c| number(m.get(r, c))).collect();
            format!("        [{}]", v.join(", "))
        })
        .collect();
    format!("FMat([\n{}])", rows.join(",\n"))
}

/// The inner control points of an edge state of dimension `m`: `Intern_('')` for one (as
/// AutoFrac2D writes quadratic edges), `Intern_('0')`, `Intern_('1')`, … for more.
fn interns(m: usize) -> Vec<String> {
    match m {
        0..=2 => Vec::new(),
        3 => vec![String::new()],
        _ => (0..m - 2).map(|i| i.to_string()).collect(),
    }
}

/// Writes the MODITERE model of `input`, whose closure is `ts` and whose generated automaton
/// (`automaton_of(ts, opts)`) is `g`. The model carries the exact particular solution of the
/// constraint system, so the solve's unknowns and estimated memory are checked against `limits`
/// before it runs.
pub fn moditere_text(
    input: &Input,
    ts: &TypeSet,
    g: &Generated,
    limits: &Limits,
) -> crate::error::Result<String> {
    g.automaton.check_solve_limits(limits)?;
    let a = &g.automaton;
    let (lin, solution) = solve_system(a)?;
    // Operators and states by name, looked up once per sub-face and edge: a linear search per
    // lookup made the export quadratic in the number of sub-faces (a wide face has 10⁵).
    let op_index: HashMap<&str, usize> = a
        .operators
        .iter()
        .enumerate()
        .map(|(i, o)| (o.name.as_str(), i))
        .collect();
    let state_index: HashMap<&str, usize> = a
        .states
        .iter()
        .enumerate()
        .map(|(i, s)| (s.name.as_str(), i))
        .collect();
    let op_value = |name: &str| -> Option<Matrix> {
        let o = *op_index.get(name)?;
        let op = &a.operators[o];
        if let Some(v) = &op.value {
            return Some(v.clone());
        }
        let Solution::Consistent(space) = &solution else {
            return None;
        };
        let base = lin.offsets[o]?;
        let (r, c) = (a.states[op.to].dim, a.states[op.from].dim);
        Some(Matrix {
            rows: r,
            cols: c,
            data: space.particular.range(base..base + r * c),
        })
    };
    let dim = |e: &EdgeType| a.states[state_index[e.to_string().as_str()]].dim;
    let mut o = String::new();
    let mut line = |s: &str| {
        o.push_str(s);
        o.push('\n');
    };
    line(&format!(
        "# MODITERE model of `{}`, written by lacuna (the layout of AutoFrac2DCLI's output.py)",
        input.name.replace('\n', " ")
    ));
    for h in [
        "from __future__ import division",
        "import sys",
        "import os",
        "",
        "directory = os.path.realpath(__file__)",
        "directory = directory[:directory.find('InterfaceBCIFS')] + 'python'",
        "if directory not in sys.path:",
        "    sys.path.append(directory)",
        "from etat import *",
        "",
        "",
        "def modele():",
        "    init = EtatInit()",
        "    s = Etat('s', 1)",
        "    s.subs = {Sub('0'): s}",
        "    s.buildIntern()",
    ] {
        line(h);
    }
    // Every edge type, with the lower delays of delayed ones.
    let mut edges: BTreeSet<EdgeType> = BTreeSet::new();
    for t in &ts.types {
        let p = t.face.params;
        for e in t.face.boundary.iter().chain([&p.ea, &p.el, &p.ec]) {
            for d in 1..=e.delay {
                edges.insert(e.delayed(d));
            }
        }
    }
    line("    ##############################");
    line("    # all edges states");
    for e in &edges {
        let n = edge_name(e);
        let m = dim(e);
        line(&format!("    {n} = Etat('{n}', {})", m - 2));
        line(&format!("    {n}.bords = {{Bord('0'): s, Bord('1'): s}}"));
        line(&format!("    {n}.permuts = {{Permut('0'): {n}}}"));
    }
    line("    ##############################");
    line("    # all edges impl");
    for e in &edges {
        let n = edge_name(e);
        let m = dim(e);
        let inner = interns(m);
        let pieces = e.piece_count() as usize;
        let piece = edge_name(&e.piece());
        let subs: Vec<String> = (0..pieces)
            .map(|k| format!("Sub('{k}'): {piece}"))
            .collect();
        line(&format!("    {n}.subs = {{{}}}", subs.join(", ")));
        line(&format!("    {n}.buildIntern()"));
        let mut space = vec!["Bord_('0')".to_string()];
        space.extend(inner.iter().map(|i| format!("Intern_('{i}')")));
        space.push("Bord_('1')".into());
        line(&format!("    {n}.space = [{}]", space.join(", ")));
        line(&format!("    {n}(Permut('0') + Bord('0'), Bord('1'))"));
        line(&format!("    {n}(Permut('0') + Bord('1'), Bord('0'))"));
        for (i, x) in inner.iter().enumerate() {
            let y = &inner[inner.len() - 1 - i];
            line(&format!(
                "    {n}(Permut('0') + Intern('{x}'), Intern('{y}'))"
            ));
        }
        for k in 0..pieces {
            line(&format!(
                "    {n}(Permut('0') + Sub('{k}'), Sub('{}') + Permut('0'))",
                pieces - 1 - k
            ));
        }
        line(&format!(
            "    {n}(Bord('0') + Sub('0'), Sub('0') + Bord('0'))"
        ));
        line(&format!(
            "    {n}(Bord('1') + Sub('0'), Sub('{}') + Bord('1'))",
            pieces - 1
        ));
        line(&format!(
            "    {n}.grid.elems = [Figure(1, [{}])]",
            space.join(", ")
        ));
        line(&format!(
            "    {n}.prim.elems = [Figure(1, [Bord_('0'), Bord_('1')])]"
        ));
        for k in 0..pieces {
            let Some(t) = op_value(&format!("{e}.T{k}")) else {
                continue;
            };
            if e.kind == EdgeKind::C && m == 2 && pieces > 1 && (k == 0 || k + 1 == pieces) {
                // As AutoFrac2D: the end point shared with the parent is fixed by the incidence
                // constraints; only the other one is given.
                let (sel, c) = if k == 0 { ("1", 1) } else { ("0", 0) };
                line(&format!(
                    "    {n}.initMat[Sub_('{k}') + Bord('{sel}')] = {}.setTyp('Const')",
                    fmat(&t, &[c])
                ));
            } else if e.is_delayed() {
                // The inner points map onto the successor's inner points.
                for (i, x) in inner.iter().enumerate() {
                    line(&format!(
                        "    {n}.initMat[Sub_('0') + Intern('{x}')] = {}.setTyp('Const')",
                        fmat(&t, &[i + 1])
                    ));
                }
            } else {
                let all: Vec<usize> = (0..m).collect();
                line(&format!(
                    "    {n}.initMat[Sub_('{k}')] = {}.setTyp('Const')",
                    fmat(&t, &all)
                ));
            }
        }
    }
    let names: Vec<String> = ts
        .types
        .iter()
        .enumerate()
        .map(|(t, ty)| cell_name(t, &ty.face))
        .collect();
    line("    ##############################");
    line("    # all cells states");
    for (t, ty) in ts.types.iter().enumerate() {
        let text = cell_text(&ty.face);
        line(&format!("    # {text}    (lacuna: {})", ty.face));
        line(&format!("    {} = Etat('{text}', 0)", names[t]));
    }
    line("    ##############################");
    line("    # subd of init");
    let init: Vec<String> = ts
        .start
        .iter()
        .enumerate()
        .map(|(i, &t)| format!("Sub('{i}'): {}", names[t]))
        .collect();
    line(&format!("    init.subs = {{{}}}", init.join(", ")));
    line("    ##############################");
    line("    # edges of all states");
    for (t, ty) in ts.types.iter().enumerate() {
        let b: Vec<String> = ty
            .face
            .boundary
            .iter()
            .enumerate()
            .map(|(i, e)| format!("Bord('{i}'): {}", edge_name(e)))
            .collect();
        line(&format!("    {}.bords = {{{}}}", names[t], b.join(", ")));
    }
    line("    ##############################");
    line("    # subdivisions of all states");
    for (t, ty) in ts.types.iter().enumerate() {
        let s: Vec<String> = ty
            .children
            .iter()
            .enumerate()
            .map(|(k, &c)| format!("Sub('{k}'): {}", names[c]))
            .collect();
        line(&format!("    {}.subs = {{{}}}", names[t], s.join(", ")));
    }
    line("    ##############################");
    line("    # build intern of all states");
    for n in &names {
        line(&format!("    {n}.buildIntern()"));
    }
    line("    ##############################");
    line("    # spaces of all states");
    for (t, ty) in ts.types.iter().enumerate() {
        let s: Vec<String> = (0..ty.face.boundary.len())
            .map(|i| format!("Bord_('{i}')"))
            .collect();
        line(&format!("    {}.space = [{}]", names[t], s.join(", ")));
    }
    line("    ##############################");
    line("    # grid of all states");
    for n in &names {
        line(&format!("    {n}.addGrid(Bord)"));
    }
    line("    ##############################");
    line("    # prim of all states");
    for (t, ty) in ts.types.iter().enumerate() {
        line(&format!("    {}.prim.elems = [Figure(2, [", names[t]));
        for (i, e) in ty.face.boundary.iter().enumerate() {
            if e.kind == EdgeKind::B && !e.is_delayed() {
                for j in 0..e.n {
                    if e.n > 2 {
                        line(&format!("        Bord_('{i}') + Sub('{j}') + Bord('0'),"));
                    } else {
                        for k in 0..e.n {
                            line(&format!(
                                "        Bord_('{i}') + Sub('{j}') + Sub('{k}') + Bord('0'),"
                            ));
                        }
                    }
                }
            } else {
                line(&format!("        Bord_('{i}') + Bord('0'),"));
            }
        }
        line("    ])]");
    }
    line("    ##############################");
    line("    # constraints of all states");
    for (t, ty) in ts.types.iter().enumerate() {
        let n = &names[t];
        line("    # incidence constraints");
        for (k, sub) in ty.subdivision.subfaces.iter().enumerate() {
            for (l, origin) in sub.origins.iter().enumerate() {
                if let crate::topology::Origin::Piece { edge, piece } = *origin {
                    line(&format!(
                        "    {n}(Bord('{edge}') + Sub('{piece}'), Sub('{k}') + Bord('{l}'))"
                    ));
                }
            }
        }
        line("    # adjacency constraints");
        for adj in &ty.subdivision.adjacencies {
            let ((sa, la), (sb, lb)) = (adj.first, adj.second);
            line(&format!(
                "    {n}(Sub('{sa}') + Bord('{la}') + Permut('0'), Sub('{sb}') + Bord('{lb}'))"
            ));
        }
        line("    # edges adjacency constraints");
        let len = ty.face.boundary.len();
        for i in 0..len {
            line(&format!(
                "    {n}(Bord('{i}') + Bord('1'), Bord('{}') + Bord('0'))",
                (i + 1) % len
            ));
        }
    }
    line("    # constraints on init cells");
    let faces = input.faces();
    let rotation: Vec<usize> = faces.iter().map(|f| f.canonical().1).collect();
    let canonical_edge = |f: usize, e: usize| {
        let len = faces[f].boundary.len();
        (e + len - rotation[f] % len) % len
    };
    for sh in &input.assembly.shared {
        let (fa, ea) = sh.a;
        let (fb, eb) = sh.b;
        line(&format!(
            "    init(Sub('{fa}') + Bord('{}') + Permut('0'), Sub('{fb}') + Bord('{}'))",
            canonical_edge(fa, ea),
            canonical_edge(fb, eb)
        ));
    }
    line("    ");
    line("    ##############################");
    line("    # control points");
    let q = opts_degree(g);
    for (i, f) in faces.iter().enumerate() {
        let pts = control_points(input, i, f, q, rotation[i]);
        let count: usize = f.boundary.iter().map(|e| dim(e) - 1).sum();
        let row = |v: Vec<String>| format!("        [{}]", v.join(", "));
        let (xs, ys): (Vec<String>, Vec<String>) = match &pts {
            Some(p) => p.iter().map(|[x, y]| (number(x), number(y))).unzip(),
            None => (vec!["0".into(); count], vec!["0".into(); count]),
        };
        line(&format!("    init.initMat[Sub_('{i}')] = FMat(["));
        line(&(row(xs) + ","));
        line(&(row(ys) + ","));
        line(&(row(vec!["0".into(); count]) + ","));
        line(&(row(vec!["1".into(); count]) + "]).setTyp('Var')"));
        line(&format!("    for i in range(init.initMat[Sub_('{i}')].n):"));
        line(&format!(
            "        init.initMat[Sub_('{i}')][2, i].setTyp('Const')"
        ));
        line("");
    }
    line("    ##############################");
    line("    # load matrices (lacuna's exact particular solution of the constraint system)");
    let mut to_save = Vec::new();
    for (t, ty) in ts.types.iter().enumerate() {
        let mut all = true;
        for k in 0..ty.children.len() {
            match op_value(&format!("T{t}.T{k}")) {
                Some(m) => {
                    let cols: Vec<usize> = (0..m.cols).collect();
                    line(&format!(
                        "    {}.initMat[Sub_('{k}')] = {}.setTyp('Var')",
                        names[t],
                        fmat(&m, &cols)
                    ));
                }
                None => all = false,
            }
        }
        if !all {
            to_save.push(names[t].clone());
        }
    }
    line("    ");
    line("    ##############################");
    line("    # auto subdivision points and save matrices");
    line(&format!("    allCellsToSave = [{}]", to_save.join(", ")));
    line("    auto = Auto(init)");
    line("    auto.initDic()");
    line("    for etat in auto.figMax:");
    let saved: String = to_save.iter().map(|c| format!(", {c}.name")).collect();
    line(&format!("        auto.autoSubBar(etat, 0, [''{saved}])"));
    for f in [
        "    # to save matrices of cells",
        "    for cell in allCellsToSave:",
        "        folderpath = cell.name.replace('/', '--')",
        "        folderpath = os.path.dirname(os.path.abspath(__file__)) + '/library/' + folderpath.replace(' ', '') + '/'",
        "        os.makedirs(folderpath, exist_ok=True)",
        "        for i in range(len(cell.subs)-1):",
        "            filepath = folderpath + str(i)",
        "            with open(filepath, 'w') as f:",
        "                f.write(str(cell.fm_[Sub(str(i))].tab))",
        "",
        "    return init",
        "",
        "",
        "if __name__ == '__main__':",
        "    print('modele()')",
        "    model_init = modele()",
        "    print('check()')",
        "    model_init.check()",
        "    print('solve()')",
        "    model_init.solve()",
        "    print('End')",
    ] {
        line(f);
    }
    Ok(o)
}

/// The Bézier degree of the generated automaton (a `Bn` state has q + 1 points).
fn opts_degree(g: &crate::constraint::Generated) -> usize {
    g.automaton
        .states
        .iter()
        .find(|s| s.name.starts_with('B'))
        .map_or(2, |s| s.dim - 1)
}

/// The control points of start face `i` in the canonical rotation, from the user's coordinates:
/// all control points when given at degree `q`, or the corners with the inner Bézier points
/// evenly spaced on the segment (AutoFrac2D's `-a`). `None` without usable coordinates.
fn control_points(
    input: &Input,
    i: usize,
    f: &Face,
    q: usize,
    rotation: usize,
) -> Option<Vec<crate::input::ExactPoint>> {
    let fc = input.assembly.coords.faces.iter().find(|c| c.face == i)?;
    let dims: Vec<usize> = f
        .boundary
        .iter()
        .map(|e| match e.kind {
            EdgeKind::B => q + 1,
            EdgeKind::C => 2,
        })
        .collect();
    let mut pts: Vec<crate::input::ExactPoint> = match fc.kind {
        CoordKind::Controls { degree } if degree == q => fc.points.clone(),
        CoordKind::Corners if fc.points.len() == f.boundary.len() => {
            let len = f.boundary.len();
            let mut out = Vec::new();
            for (k, &m) in dims.iter().enumerate() {
                let p = &fc.points[k];
                let r = &fc.points[(k + 1) % len];
                out.push(p.clone());
                for j in 1..m - 1 {
                    let t = BigRational::new((j as i64).into(), ((m - 1) as i64).into());
                    let one = BigRational::from_integer(1.into());
                    out.push([
                        &p[0] * (&one - &t) + &r[0] * &t,
                        &p[1] * (&one - &t) + &r[1] * &t,
                    ]);
                }
            }
            out
        }
        _ => return None,
    };
    let want: usize = dims.iter().map(|m| m - 1).sum();
    if pts.len() != want {
        return None;
    }
    let shift: usize = dims[..rotation % dims.len()].iter().map(|m| m - 1).sum();
    pts.rotate_left(shift);
    Some(pts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_autofrac() {
        let f = Face::parse("C2 B2^3 | C2 B2 B2 | AF1").unwrap();
        assert_eq!(
            cell_text(&f),
            "C_2_0 - B_2_2 / C_2_0 - B_2_0 - B_2_0 / 0 / 1"
        );
        assert_eq!(edge_name(&f.boundary[1]), "B2_2");
        let f = Face::parse("C2 B2 | C2 B2 B2 | A1 | 3").unwrap();
        assert_eq!(cell_name(4, &f), "Cell_4_2");
        // A1 with delays is not an AutoFrac2D algorithm: the name keeps lacuna's notation.
        assert_eq!(
            cell_text(&f),
            "C_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 2 / A1"
        );
    }
}
