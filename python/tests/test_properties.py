"""Properties over random faces (a fixed seed, so a failure is reproducible): the Python API agrees
with the command line, and the counts agree with an independent recomputation from the closure's
type graph in Python integers."""

import random
from fractions import Fraction

import pytest

import lacuna

EDGES = ["B2", "C2", "B3", "C3", "B2^2"]


def random_faces(n, seed=20261130):
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        boundary = " ".join(rng.choice(EDGES) for _ in range(rng.randint(1, 5)))
        e = " ".join(rng.choice(["B2", "C2"]) for _ in range(3))
        text = f"{boundary} | {e} | {rng.choice(['A1', 'A2', 'A3'])}"
        if rng.random() < 0.25:
            # Corrupt one character: bad input must fail alike here and on the command line.
            i = rng.randrange(len(text))
            text = text[:i] + rng.choice("X0^|1") + text[i + 1 :]
        out.append(text)
    return out


def counts_from_the_type_graph(closure, levels):
    """N^C_i = s·M^i·1 and N^L_i = Σ_{k<i} Σ_t (s·M^k)_t · c_t, with s the start types, M the
    substitution matrix and c_t each type's contribution (THEORY §5)."""
    index = {t.id: i for i, t in enumerate(closure.types)}
    m = closure.matrix()
    n = [0] * len(m)
    for s in closure.start:
        n[index[s]] += 1
    faces, lacunas, lac = [], [], Fraction(0)
    for _ in range(levels + 1):
        faces.append(sum(n))
        lacunas.append(lac)
        lac += sum(k * t.contribution for k, t in zip(n, closure.types))
        n = [sum(n[i] * m[i][j] for i in range(len(m))) for j in range(len(m))]
    return faces, lacunas


@pytest.mark.parametrize("notation", random_faces(40))
def test_random_faces_agree_with_the_command_line_and_the_type_graph(cli, notation):
    code, data = cli("counts", notation, "--levels", 12, "--json")
    try:
        face = lacuna.Face(notation)
        rows = face.counts(12)
    except lacuna.LacunaError as e:
        # Bad input or a runaway: the same error as the command line.
        assert code == 2 and e.code == data["error"]["code"] and e.message == data["error"]["message"]
        return
    assert code == 0
    assert [(r.faces, r.lacunas, r.ratio) for r in rows] == [
        (int(d["faces"]), Fraction(d["lacunas"]), Fraction(d["ratio"])) for d in data["levels"]
    ]
    faces, lacunas = counts_from_the_type_graph(face.closure(), 12)
    assert [r.faces for r in rows] == faces
    assert [r.lacunas for r in rows] == lacunas
    for r in rows:
        total = r.faces + r.lacunas
        assert r.ratio == (r.lacunas / total if total else 0)


@pytest.mark.parametrize("name", ["F0", "cycle-sqrt17", "two-quads", "triangle-C2", "square-B2", "delayed-B2-C2"])
def test_fixture_counts_agree_with_the_type_graph(name):
    s = lacuna.load(name)
    rows = s.counts(15)
    faces, lacunas = counts_from_the_type_graph(s.closure(), 15)
    assert [r.faces for r in rows] == faces
    assert [r.lacunas for r in rows] == lacunas
