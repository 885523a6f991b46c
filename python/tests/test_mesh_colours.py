"""`render --3mf-colours` read back by lib3mf (the 3MF Consortium's reader, strict mode), which
shares nothing with lacuna's writer: one base material per face type, every triangle naming one,
and each type's share of the top surface equal to its share of the cells' area computed from the
polygons `render --json-out` writes (issue #30)."""

import json
import struct
from collections import defaultdict

import lib3mf


def _read_strict(path):
    """The 3MF at ``path`` read by lib3mf in strict mode, with no warning; returns the model and
    its base-material groups, moved to the first (which must exist)."""
    model = lib3mf.get_wrapper().CreateModel()
    reader = model.QueryReader("3mf")
    reader.SetStrictModeActive(True)
    reader.ReadFromFile(str(path))
    assert reader.GetWarningCount() == 0
    groups = model.GetBaseMaterialGroups()
    assert groups.MoveNext()
    return model, groups


def _signed_volume(triangles):
    """The volume enclosed by triangles given as three points each (the divergence theorem)."""
    return sum(
        (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
         + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
        for a, b, c in triangles
    )


def _shoelace(poly):
    return 0.5 * sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(poly, poly[1:] + poly[:1]))


def test_the_coloured_3mf_gives_each_cell_its_types_material(cli, tmp_path):
    mf, js = tmp_path / "d.3mf", tmp_path / "d.json"
    code, _ = cli(
        "render", "delayed-B2-C2", "--level", "3", "--3mf", mf, "--3mf-colours", "--json-out", js
    )
    assert code == 0
    model, groups = _read_strict(mf)
    group = groups.GetCurrentBaseMaterialGroup()
    names = {pid: group.GetName(pid) for pid in group.GetAllPropertyIDs()}
    # delayed-B2-C2 closes with 5 face types (T0 … T4): one material each, named by its type.
    assert sorted(n.split()[0] for n in names.values()) == [f"T{k}" for k in range(5)]
    assert not groups.MoveNext()
    # Each type's area on the top (z = thickness) against its cells' area in the JSON.
    top = defaultdict(float)
    objects = model.GetMeshObjects()
    while objects.MoveNext():
        obj = objects.GetCurrentMeshObject()
        verts = [v.Coordinates for v in obj.GetVertices()]
        zmax = max(v[2] for v in verts)
        for tri, prop in zip(obj.GetTriangleIndices(), obj.GetAllTriangleProperties()):
            assert prop.ResourceID == group.GetResourceID()
            ty = int(names[prop.PropertyIDs[0]].split()[0][1:])
            a, b, c = (verts[i] for i in tri.Indices)
            if a[2] == b[2] == c[2] == zmax:
                top[ty] += _shoelace([a[:2], b[:2], c[:2]])
    cells = defaultdict(float)
    for cell in json.loads(js.read_text())["cells"]:
        cells[int(cell["type"])] += _shoelace(cell["polygon"])
    assert set(top) == set(cells)
    total_top, total_cells = sum(top.values()), sum(cells.values())
    for ty in cells:
        assert abs(top[ty] / total_top - cells[ty] / total_cells) < 0.01, (ty, top, cells)


def test_the_3mf_parts_are_one_object_of_closed_parts_per_type(cli, tmp_path):
    """`render --3mf-parts` read back by lib3mf in strict mode: one mesh object per volume type
    with cells at the level, each of its own base material and manifold, and one components
    object made of them. cube-B2 at level 2 (THEORY §10): 8 corner pieces W3, each → 16 W3 +
    3 W4, so 128 shells of W3 and 24 of W4; the parts' volumes add up to the solid's."""
    mf, stl = tmp_path / "c.3mf", tmp_path / "c.stl"
    code, _ = cli("render", "cube-B2", "--level", "2", "--3mf", mf, "--3mf-parts", "--stl", stl)
    assert code == 0
    model, groups = _read_strict(mf)
    group = groups.GetCurrentBaseMaterialGroup()
    colours = {group.GetName(p) for p in group.GetAllPropertyIDs()}
    assert colours == {"V1", "V2"}

    shells, total = {}, 0.0
    objects = model.GetMeshObjects()
    while objects.MoveNext():
        obj = objects.GetCurrentMeshObject()
        assert obj.IsManifoldAndOriented(), obj.GetName()
        verts = [v.Coordinates for v in obj.GetVertices()]
        tris = [t.Indices for t in obj.GetTriangleIndices()]
        # Shells: connected pieces of the triangles' vertices.
        parent = list(range(len(verts)))

        def find(x):
            while parent[x] != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x

        for a, b, c in tris:
            parent[find(b)] = find(a)
            parent[find(c)] = find(a)
        shells[obj.GetName()] = len({find(i) for t in tris for i in t})
        total += _signed_volume([[verts[i] for i in t] for t in tris])
    assert sorted(shells.values()) == [24, 128], shells
    components = model.GetComponentsObjects()
    assert components.MoveNext()
    assert components.GetCurrentComponentsObject().GetComponentCount() == 2
    # The solid written beside it encloses the same volume (its cells are the parts' shells).
    data = stl.read_bytes()
    n = int.from_bytes(data[80:84], "little")
    solid = []
    for k in range(n):
        v = struct.unpack_from("<9f", data, 84 + 50 * k + 12)
        solid.append((v[0:3], v[3:6], v[6:9]))
    whole = _signed_volume(solid)
    assert abs(total - whole) < 1e-3 * abs(whole), (total, whole)
