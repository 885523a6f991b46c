"""Issue #16 comparison: lacuna's exact eigen analysis against python-flint on the same matrices.

Usage: flint_operators.py MATRICES LACUNA_BINARY
       flint_operators.py MATRICES --flint-only   (FLINT's work once, nothing printed: for timing
       the whole Python process, interpreter start and import included, in compare_peers.sh)
MATRICES holds one matrix per line, `[a b; c d]` with exact rationals (exported by
`lacuna operators F0 --json`). FLINT computes, for every matrix, the characteristic polynomial
(fmpq_mat.charpoly), its factorisation over Q (fmpq_poly.factor) and certified complex roots of
every factor (fmpz_poly.complex_roots, arb enclosures). lacuna runs `lacuna operators --matrix M
--matrix M ...` once on the same matrices (charpoly, factorisation, real root isolation, certified
complex disks, eigenvectors, fixed point, contraction and the exact §8 class). Best of 5 runs each.
"""
import subprocess
import sys
import time
from fractions import Fraction

import flint


def parse(line):
    rows = line.strip().strip("[]").split(";")
    return [[Fraction(x) for x in r.split()] for r in rows]


def flint_run(mats):
    out = []
    for m in mats:
        n = len(m)
        a = flint.fmpq_mat(n, n, [flint.fmpq(x.numerator, x.denominator) for r in m for x in r])
        chi = a.charpoly()
        _, factors = chi.factor()
        roots = []
        for f, _mult in factors:
            num = f.numer() if hasattr(f, "numer") else f
            roots.append(flint.fmpz_poly(num).complex_roots())
        out.append((chi, factors, roots))
    return out


def best(fn, reps=5):
    """Best of `reps` runs: (wall seconds, CPU seconds of this process and its children)."""
    wall, cpu = [], []
    for _ in range(reps):
        s, c = time.perf_counter(), cpu_now()
        fn()
        wall.append(time.perf_counter() - s)
        cpu.append(cpu_now() - c)
    return min(wall), min(cpu)


def cpu_now():
    import resource
    own = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def main():
    lines = [l for l in open(sys.argv[1]) if l.strip()]
    mats = [parse(l) for l in lines]
    if sys.argv[2] == "--flint-only":
        flint_run(mats)
        return
    binary = sys.argv[2]
    args = [binary, "operators"]
    for l in lines:
        args += ["--matrix", l.strip()]
    t_flint = best(lambda: flint_run(mats))
    t_lacuna = best(lambda: subprocess.run(args, check=True, stdout=subprocess.DEVNULL))
    sizes = " ".join(f"{len(m)}x{len(m)}" for m in mats)
    print(f"matrices: {len(mats)} ({sizes})")
    print(f"python-flint {flint.__version__}: wall {t_flint[0]:.4f} s, CPU {t_flint[1]:.4f} s (charpoly, factor over Q, certified complex roots)")
    print(f"lacuna operators --matrix ...: wall {t_lacuna[0]:.4f} s, CPU {t_lacuna[1]:.4f} s (whole process: exact analysis and report)")
    print(f"ratio lacuna / flint: wall {t_lacuna[0] / t_flint[0]:.1f}x, CPU {t_lacuna[1] / max(t_flint[1], 1e-9):.1f}x")


if __name__ == "__main__":
    main()
