"""Solve one exported lacuna system with SymPy's sparse DomainMatrix over QQ and print
`rank_A rank_Ab seconds ground_types`, the SymPy twin of flint_rref.py (issue #34).

The system file is lacuna's sparse text layout (`lacuna::constraint::write_text`): first line
`rows cols`, then one equation per line, `rhs | col:coef col:coef ...`. The augmented matrix
[A | b] is built as a dict-of-dicts DomainMatrix (SymPy's SDM, sparse rows) and reduced with
`rref()`. The clock starts before the matrix is built from the parsed terms, as in
flint_rref.py, so both peers pay for building their own matrix and neither for reading the file.
rank(A) is the number of pivots left of the right-hand-side column."""
import sys
import time
from fractions import Fraction

from sympy import QQ
from sympy.external.gmpy import GROUND_TYPES
from sympy.polys.matrices import DomainMatrix


def main(path):
    with open(path) as f:
        m, n = map(int, f.readline().split())
        rows = []
        for line in f:
            rhs, _, terms = line.partition("|")
            pairs = [(int(c), Fraction(v)) for c, v in (t.split(":") for t in terms.split())]
            rows.append((Fraction(rhs.strip()), pairs))
    start = time.perf_counter()
    entries = {}
    for i, (rhs, pairs) in enumerate(rows):
        row = {}
        for c, v in pairs:
            row[c] = row.get(c, QQ.zero) + QQ(v.numerator, v.denominator)
        if rhs:
            row[n] = QQ(rhs.numerator, rhs.denominator)
        row = {c: v for c, v in row.items() if v}
        if row:
            entries[i] = row
    a = DomainMatrix(entries, (m, n + 1), QQ)
    _, pivots = a.rref()
    rank_ab = len(pivots)
    rank_a = sum(1 for p in pivots if p < n)
    print(rank_a, rank_ab, f"{time.perf_counter() - start:.4f}", GROUND_TYPES)


if __name__ == "__main__":
    main(sys.argv[1])
