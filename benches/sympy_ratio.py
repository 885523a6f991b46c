"""The same limit ratio computed with SymPy, for the comparison of issue #3.

For each exported closure: the characteristic polynomial of the substitution matrix, factored
over Q; the Perron root rho = the largest real root; the left eigenvector y (y M = rho y, which
must be one-dimensional: a simple dominant eigenvalue), exactly over Q(rho); then
R = y.c / (y.c + (rho - 1) y.1), evaluated to 50 digits. Prints the time and both values."""
import json
import sys
import time

import sympy as sp
from sympy.polys.matrices import DomainMatrix


def main(path):
    d = json.load(open(path))
    n = len(d["matrix"])
    start = time.perf_counter()
    m = sp.zeros(n, n)
    for t, row in enumerate(d["matrix"]):
        for s, k in row:
            m[t, s] = k
    c = sp.Matrix([sp.Rational(x) for x in d["contributions"]])
    x = sp.Symbol("x")
    p = m.charpoly(x).as_expr()
    roots = []
    for f, _ in sp.factor_list(p)[1]:
        roots += sp.Poly(f, x).real_roots()
    rho = max(roots, key=lambda r: r.evalf(60))
    # Exact linear algebra over Q(rho) (DomainMatrix); SymPy's Matrix.nullspace on radical
    # expressions mis-detects pivots and gave wrong answers here.
    k = sp.QQ.algebraic_field(rho)
    a = DomainMatrix([[k.from_sympy(v) for v in row] for row in m.T.tolist()], (n, n), k)
    ker = (a - DomainMatrix.eye(n, k) * k.from_sympy(rho)).nullspace()
    if ker.shape[0] != 1:
        print(f"{path}: dominant eigenvalue not simple ({ker.shape[0]}), skipped")
        return
    y = [k.to_sympy(v) for v in ker.to_list()[0]]
    yc = sum(yi * ci for yi, ci in zip(y, c))
    y1 = sum(y)
    r = yc / (yc + (rho - 1) * y1)
    value = sp.N(r, 60)
    seconds = time.perf_counter() - start
    print(f"{d['face']}: sympy {seconds:.3f} s, lacuna {d['lacuna_seconds']:.4f} s, "
          f"ratio {seconds / d['lacuna_seconds']:.0f}x; R sympy {str(value)[:52]} lacuna {d['lacuna_decimal']}")


if __name__ == "__main__":
    for path in sys.argv[1:]:
        main(path)
