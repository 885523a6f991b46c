"""Solve one exported lacuna system with python-flint (dense fmpq_mat rref) and print
`rank_A rank_Ab seconds`. The system file is lacuna's sparse text layout:
first line `rows cols`, then per equation `rhs | col:coef col:coef ...`."""
import sys
import time
from fractions import Fraction

import flint


def q(s):
    f = Fraction(s)
    return flint.fmpq(f.numerator, f.denominator)


def main(path):
    with open(path) as f:
        m, n = map(int, f.readline().split())
        rows = []
        for line in f:
            rhs, _, terms = line.partition("|")
            rows.append((q(rhs.strip()), [(int(c), q(v)) for c, v in (t.split(":") for t in terms.split())]))
    start = time.perf_counter()
    a = flint.fmpq_mat(m, n + 1)
    for i, (rhs, terms) in enumerate(rows):
        for c, v in terms:
            a[i, c] += v
        a[i, n] = rhs
    _, rank_ab = a.rref()
    # rank of A alone: the augmented rref has rank(A) pivots outside the last column.
    r, _ = a.rref()
    rank_a = sum(1 for i in range(min(m, rank_ab)) if any(r[i, j] != 0 for j in range(n)))
    print(rank_a, rank_ab, f"{time.perf_counter() - start:.4f}")


if __name__ == "__main__":
    main(sys.argv[1])
