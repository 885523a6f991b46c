"""Volumes and volume assemblies from Python (THEORY §10, docs/VOLUMES.md): closure, counts, the
level-n solid, R, the constraints, verification, certificates, pictures and printable meshes, and
errors. The expected numbers are derived by hand in the comments, not copied from lacuna's output.
"""

import struct
from fractions import Fraction

import numpy as np
import pytest

import lacuna

from conftest import REPO

CUBE = "cube B2 | B2 B2 B2 | A1 | B2 B2 | V1"

# cube-B2 (docs/VOLUMES.md "Counts and R"): with B2 edges and A1 every sub-face is a pentagon
# holding one corner of its face, so under V1 a volume with V corners has V children, one per
# corner, whose type depends only on the corner's degree: W3 (13 faces) for degree 3, W4 (17
# faces) for degree 4. The cube has 8 corners of degree 3: V0 → 8 × W3. W3 has 19 corners, 16 of
# degree 3 and 3 of degree 4: W3 → 16 × W3 + 3 × W4; W4 has 25, 20 and 5: W4 → 20 × W3 + 5 × W4.
# The closure numbers them V0 (the cube), V1 = W3, V2 = W4.
CHILDREN = {"V0": {"V1": 8}, "V1": {"V1": 16, "V2": 3}, "V2": {"V1": 20, "V2": 5}}
FACES = {"V0": 6, "V1": 13, "V2": 17}
# One step contributes the central cavity (1) plus half of each face's lacuna (a B2 polygon under
# A1 has one central lacuna, shared with the cell on its other side): 1 + faces/2.
CONTRIBUTION = {t: 1 + Fraction(f, 2) for t, f in FACES.items()}  # 4, 15/2, 19/2


def _cube_counts(levels):
    """Cells, lacunas and R_i of cube-B2 for levels 0..levels from the hand-derived children and
    contributions: N^L_{i+1} = N^L_i + Σ_t (cells of type t at level i) · contribution(t)."""
    by_type = {"V0": 1, "V1": 0, "V2": 0}
    lacunas = Fraction(0)
    rows = []
    for level in range(levels + 1):
        cells = sum(by_type.values())
        rows.append((level, cells, lacunas, lacunas / (lacunas + cells)))
        lacunas += sum(n * CONTRIBUTION[t] for t, n in by_type.items())
        nxt = {"V0": 0, "V1": 0, "V2": 0}
        for t, n in by_type.items():
            for c, k in CHILDREN[t].items():
                nxt[c] += n * k
        by_type = nxt
    return rows


def test_load_gives_a_volume_for_notation_names_and_assemblies():
    cube = lacuna.load("cube-B2")
    assert isinstance(cube, lacuna.Volume)
    assert repr(cube) == "Volume('cube-B2')"
    assert isinstance(lacuna.load(CUBE), lacuna.Volume)
    for name in ("tetrahedron-B2", "truncated-tetrahedron", "two-cubes"):
        v = lacuna.load(name)
        assert isinstance(v, lacuna.Volume) and v.name == name
    # The library name is the notation of its fixture: the same closure and counts.
    assert lacuna.Volume(CUBE).counts(3) == cube.counts(3)
    assert lacuna.Volume.from_file(REPO / "fixtures" / "two-cubes.txt").counts(2) == lacuna.load("two-cubes").counts(2)


def test_the_cube_closes_with_the_types_derived_by_hand():
    c = lacuna.load("cube-B2").closure()
    assert c.closed and c.start == ("V0",)
    assert [t.id for t in c.types] == ["V0", "V1", "V2"]
    for t in c.types:
        kids = {k: t.children.count(k) for k in set(t.children)}
        assert kids == CHILDREN[t.id], t.id
        assert t.faces == FACES[t.id]
        assert t.contribution == CONTRIBUTION[t.id]
        # Every boundary is a sphere: corners − edges + faces = 2.
        assert t.corners - t.edges + t.faces == 2
    # The cube's own boundary: 6 squares, 8 corners, 12 edges.
    assert (c.types[0].faces, c.types[0].corners, c.types[0].edges) == (6, 8, 12)
    assert c.matrix() == [[0, 8, 0], [0, 16, 3], [0, 20, 5]]
    assert repr(c) == "VolumeClosure(closed=True, types=3, start=['V0'])"
    html = c._repr_html_()
    assert "closed: 3 volume types" in html and "<td>16×V1 + 3×V2</td>" in html and "<td>15/2</td>" in html


def test_counts_are_exact_and_follow_the_children():
    counts = lacuna.load("cube-B2").counts(4)
    # Level 2 from the children of the 8 W3: 8 × (16 + 3) = 152 cells; level 3: the 8 × 16 = 128
    # W3 and 8 × 3 = 24 W4 give 128 × 19 + 24 × 25 = 3032. Lacunas: 4, then 4 + 8 · 15/2 = 64,
    # then 64 + 128 · 15/2 + 24 · 19/2 = 1252.
    assert [c.cells for c in counts[:4]] == [1, 8, 152, 3032]
    assert [c.lacunas for c in counts[:4]] == [0, 4, 64, 1252]
    assert [(c.level, c.cells, c.lacunas, c.ratio) for c in counts] == _cube_counts(4)
    assert all(type(c.cells) is int and isinstance(c.lacunas, Fraction) for c in counts)
    assert counts[2].ratio == Fraction(64, 64 + 152)
    html = counts._repr_html_()
    assert "<td>3032</td>" in html and "<td>1252</td>" in html and "cells N^C" in html
    # Big levels stay exact: cells grow as 20^i (ρ = 20) and are Python ints of any size.
    big = lacuna.load("cube-B2").counts(60)[60].cells
    assert type(big) is int and big > 20**59


def test_the_level_n_solid_by_hand():
    solid = lacuna.load("cube-B2").solid(1)
    # Level 0 is the cube itself, one ball: 1 volume, 6 faces, 12 edges, 8 corners, χ = 1.
    s0 = solid[0]
    assert (s0.volumes, s0.faces, s0.edges, s0.corners, s0.euler) == (1, 6, 12, 8, 1)
    assert (s0.components, s0.voids, s0.tunnels) == (1, 0, 0)
    # Level 1: the 8 corner blocks joined along the cube's 12 edges around the open central
    # cavity: a thickened cube frame, which retracts onto the cube's 1-skeleton (8 vertices, 12
    # edges): one component, no void, χ = 8 − 12 = −4, tunnels b1 = 1 + 0 − χ = 5. Its corners
    # (THEORY §13): 8 cube corners, 12 joints, 24 lacuna corners, 12 + 24 inner corners = 80; its
    # edges are half the valence sum 3·20 + 4·48 + 5·12 = 312: 156. So faces = χ − corners +
    # edges + volumes = −4 − 80 + 156 + 8 = 80.
    s1 = solid[1]
    assert (s1.volumes, s1.faces, s1.edges, s1.corners, s1.euler) == (8, 80, 156, 80, -4)
    assert (s1.components, s1.voids, s1.tunnels) == (1, 0, 5)
    assert s1.corners - s1.edges + s1.faces - s1.volumes == s1.euler
    html = solid._repr_html_()
    assert "<th>χ</th>" in html and "<td>-4</td>" in html and "<th>tunnels</th>" in html


def test_two_cubes_glued_by_hand():
    two = lacuna.load("two-cubes")
    # Two cube-B2 sharing a square: every count is twice the cube's.
    assert [c.cells for c in two.counts(2)] == [2 * r[1] for r in _cube_counts(2)]
    assert [c.lacunas for c in two.counts(2)] == [2 * r[2] for r in _cube_counts(2)]
    # Level 0: 2 volumes, 6 + 6 − 1 = 11 faces, 12 + 12 − 4 = 20 edges, 8 + 8 − 4 = 12 corners:
    # χ = 12 − 20 + 11 − 2 = 1, one ball.
    s0 = two.solid(0)[0]
    assert (s0.volumes, s0.faces, s0.edges, s0.corners, s0.euler, s0.tunnels) == (2, 11, 20, 12, 1, 0)


def test_the_limit_ratio_of_the_cube():
    # The dominant class {W3, W4} has M = [[16, 3], [20, 5]]: λ² − 21λ + 20 = 0, ρ = 20, left
    # eigenvector u = (5, 1) (5·16 + 20 = 100 = 20·5, 5·3 + 5 = 20). Cells grow as 20^i·(5 + 1);
    # lacunas add u·c = 5 · 15/2 + 19/2 = 47 per unit, summed over the levels below: 47/19.
    # R = (47/19) / (47/19 + 6) = 47/161.
    r = lacuna.load("cube-B2").ratio()
    assert r.exists and r.value == Fraction(47, 161)
    assert r.perron_root == "20" and r.degree == 1


def test_solve_gives_what_the_command_line_gives(cli):
    v = lacuna.load("tetrahedron-B2")
    s = v.solve(degree=1)
    assert s.consistent and s.ok and s.degeneracy_checked
    # A state per volume type (the tetrahedron, W3 and W4), beside the face states.
    assert {"V0", "V1", "V2"} <= set(s.dof_by_state)
    assert s.dof == s.unknowns - s.rank
    code, data = cli("solve", "tetrahedron-B2", "--degree", "1", "--json")
    assert code == 0
    assert (s.unknowns, s.equations, s.rank, s.dof) == (data["unknowns"], data["equations"], data["rank"], data["dof"])


def test_verify_and_a_certificate_the_checker_accepts(tmp_path, cli):
    v = lacuna.load("cube-B2")
    report = v.verify(levels=3)
    assert report.verified and report.failures == []
    assert [int(c.cells) for c in report.counts] == [r[1] for r in _cube_counts(3)]
    assert report.solver.consistent
    cert = v.certificate(tmp_path / "cube.json", levels=2)
    # volume-closure, limit-ratio, solid-homology, solid-recurrence, the constraints' solution
    # space and the degeneracy of the surfaces' faces on it.
    assert repr(cert) == "Certificate(input='cube-B2', steps=6)"
    assert '"step":"solid-recurrence"' in cert.text
    assert '"step":"volume-solution-space"' in cert.text
    assert cert.check().all_proved
    assert lacuna.check(tmp_path / "cube.json").all_proved
    code, data = cli("check", tmp_path / "cube.json", "--json")
    assert code == 0
    # A forged count is refused by the checker.
    forged = cert.text.replace('"152"', '"153"', 1)
    assert forged != cert.text
    assert not lacuna.Certificate(forged).check().all_proved


def test_render_writes_a_checked_mesh(tmp_path, cli):
    v = lacuna.load("cube-B2")
    out = {k: tmp_path / f"cube.{k}" for k in ("stl", "3mf", "obj", "svg", "png")}
    r = v.render(
        1,
        stl=out["stl"],
        threemf=out["3mf"],
        obj=out["obj"],
        svg=out["svg"],
        png=out["png"],
        size=200,
        claims=tmp_path / "claims.json",
    )
    assert r.embedded and r.crossing is None
    assert set(r.written) == set(out.values()) | {tmp_path / "claims.json"}
    assert all(p.exists() and p.stat().st_size > 0 for p in r.written)
    # One part (one component); the triangle mesh's V − E + F (E = 3F/2) is 2χ of the solid, the
    # boundary of a compact 3-manifold: 2 · (−4) = −8, genus 5.
    assert len(r) == 1 and r.solid.euler == -4
    verts, tris = r.vertices[0], r.triangles[0]
    assert verts.shape[1] == 3 and tris.shape[1] == 3 and tris.max() < len(verts)
    assert len(verts) - 3 * len(tris) // 2 + len(tris) == 2 * r.solid.euler
    # Width 100 mm: the x extent of the solid as built.
    assert np.isclose(verts[:, 0].max() - verts[:, 0].min(), 100.0, atol=1e-3)
    # A binary STL says its triangle count at byte 80.
    assert struct.unpack("<I", out["stl"].read_bytes()[80:84])[0] == len(tris)
    png = out["png"].read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">I", png[16:20])[0] == 200
    assert r.printability is not None and r.printability.fits_bed
    assert "closed oriented manifold" in r.notes
    text = repr(r)
    assert "\n" not in text and len(text) < 400 and text.startswith("VolumeRendering(level=1, parts=1")
    # The independent mesh checker accepts the STL against the claims written with it.
    code, _ = cli("check-mesh", out["stl"], "--claims", tmp_path / "claims.json")
    assert code == 0
    # Without files: the mesh only.
    assert v.render(1).written == []


def test_render_by_type_and_measure(tmp_path):
    v = lacuna.load("cube-B2")
    colours = v.render(1, threemf=tmp_path / "c.3mf", threemf_colours=True)
    parts = v.render(1, threemf=tmp_path / "p.3mf", threemf_parts=True)
    assert colours.written == [tmp_path / "c.3mf"] and parts.written == [tmp_path / "p.3mf"]
    m = v.measure(1)
    # The level-1 solid derived above: χ = −4, one part, surface χ −8, genus 5.
    assert m.verified and m.mesh.embedded
    assert (m.mesh.parts, m.mesh.surface_euler, m.mesh.genus) == (1, -8, 5)
    assert m.solid.euler == "-4"


def test_a_volume_shows_a_picture():
    png = lacuna.load("tetrahedron-B2")._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">I", png[16:20])[0] == 480


@pytest.mark.parametrize(
    "notation, code",
    [
        # 4 fields: no rule.
        ("cube B2 | B2 B2 B2 | A1 | B2 B2", "E1201"),
        # E has two parameters.
        ("cube B2 | B2 B2 | A1 | B2 B2 | V1", "E1203"),
        # G is one edge type.
        ("cube B2 | B2 B2 B2 | A1 | B2 | V1", "E1204"),
        # No rule V9.
        ("cube B2 | B2 B2 B2 | A1 | B2 B2 | V9", "E1205"),
        # Delay 0 (1–64).
        ("cube B2 | B2 B2 B2 | A1 | B2 B2 | V1 | 0", "E1206"),
    ],
)
def test_bad_volume_notation_is_a_coded_error(notation, code, cli):
    with pytest.raises(lacuna.InputError) as e:
        lacuna.Volume(notation)
    assert e.value.code == code and e.value.span is not None
    assert code in e.value.rendered
    with pytest.raises(lacuna.InputError) as e2:
        lacuna.load(notation)
    assert e2.value.code == code
    # The command line refuses it as bad input.
    exit_code, _ = cli("closure", notation)
    assert exit_code == 2


def test_errors_of_volume_methods():
    v = lacuna.load("cube-B2")
    with pytest.raises(lacuna.UsageError) as e:
        lacuna.Volume("F0")
    assert e.value.code == "E0504"
    with pytest.raises(lacuna.UsageError) as e:
        v.counts(-1)
    assert e.value.code == "E0503"
    with pytest.raises(lacuna.LimitError) as e:
        v.counts(10**6)
    assert e.value.code == "E0501"
    # The level-1 solid has 80 faces (derived above), above max_cells = 79: refused before any
    # geometry is built.
    with pytest.raises(lacuna.LimitError) as e:
        v.render(1, max_cells=79)
    assert e.value.code == "E0501"
    with pytest.raises(lacuna.UsageError):
        v.render(1, claims="c.json")
    with pytest.raises(lacuna.UsageError):
        v.render(1, threemf="x.3mf", threemf_colours=True, threemf_parts=True)
    with pytest.raises(lacuna.UsageError):
        v.render(1, orient="sideways")
    with pytest.raises(lacuna.FileError) as e:
        lacuna.Volume.from_file(REPO / "no-such-volume.txt")
    assert e.value.code == "E0601"
    with pytest.raises(lacuna.UsageError):
        lacuna.Volume("C2 B2 B2 | C2 B2 B2 | A1")


def test_a_solid_that_folds_is_not_written(tmp_path):
    # The cube whose top is turned by 160° (fixtures/twisted-cube-160.txt) folds at level 2 under
    # all three inner-face rules (two triangles cross; docs/VOLUMES.md, the command line's test
    # `a_solid_that_folds_is_not_written`): a mesh would not be the verified structure, so nothing
    # is written (E1041). The tetrahedron C3 A1 V1 at level 3 folded too until boundary faces were
    # fanned around a point of their own kernel (issue #31).
    v = lacuna.Volume.from_file(REPO / "fixtures" / "twisted-cube-160.txt")
    with pytest.raises(lacuna.GeometryError) as e:
        v.render(2, stl=tmp_path / "t3.stl")
    assert e.value.code == "E1041"
    assert not (tmp_path / "t3.stl").exists()


def test_a_volume_view_is_the_report_s_webgl_inline():
    import re

    v = lacuna.load("cube-B2")
    a, b = v.view(1), v.view(1)
    html = a._repr_html_()
    assert html.count("<canvas") == 1 and "<script>" in html and "getContext('webgl'" in html
    # Two views on one notebook page: each canvas has its own id, and its script finds it.
    ids = [re.search(r'<canvas id="([^"]+)"', r._repr_html_()).group(1) for r in (a, b)]
    assert ids[0] != ids[1]
    assert all(f"getElementById('{i}')" in r._repr_html_() for i, r in zip(ids, (a, b)))
    # Every triangle of the mesh is in the view: three points of three coordinates each.
    pos = re.search(r"new Float32Array\(\[([^\]]*)\]\)", html).group(1)
    assert len([x for x in pos.split(",") if x]) == 9 * sum(len(t) for t in a.triangles)
    # Without asking, a rendering has no view (a notebook shows its repr).
    assert v.render(1)._repr_html_() is None
