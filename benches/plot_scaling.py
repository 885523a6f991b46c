"""Plots the solver benchmark (target/bench-solver.txt, written by benches/compare_flint.sh or
`cargo bench --bench solver > target/bench-solver.txt`) as a log-log SVG: solve time against the
number of unknowns, with the line of slope 1 through the largest point (linear growth)."""
import math
import sys

rows = []
for line in open(sys.argv[1] if len(sys.argv) > 1 else "target/bench-solver.txt"):
    parts = line.split()
    if len(parts) > 6 and parts[0].isdigit() and parts[5] in ("true", "false"):
        rows.append((int(parts[2]), float(parts[4])))
rows.sort()
w, h, m = 640, 420, 60
xs = [math.log10(u) for u, _ in rows]
ys = [math.log10(max(t, 1e-6)) for _, t in rows]
x0, x1 = math.floor(min(xs)), math.ceil(max(xs))
y0, y1 = math.floor(min(ys)), math.ceil(max(ys))
px = lambda x: m + (x - x0) / (x1 - x0) * (w - 2 * m)
py = lambda y: h - m - (y - y0) / (y1 - y0) * (h - 2 * m)
out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
       f'<rect width="{w}" height="{h}" fill="white"/>',
       f'<text x="{w / 2}" y="20" text-anchor="middle">lacuna solver: time against unknowns (log-log)</text>']
for d in range(x0, x1 + 1):
    out.append(f'<line x1="{px(d):.1f}" y1="{h - m}" x2="{px(d):.1f}" y2="{m}" stroke="#ddd"/>')
    out.append(f'<text x="{px(d):.1f}" y="{h - m + 16}" text-anchor="middle">1e{d}</text>')
for d in range(y0, y1 + 1):
    out.append(f'<line x1="{m}" y1="{py(d):.1f}" x2="{w - m}" y2="{py(d):.1f}" stroke="#ddd"/>')
    out.append(f'<text x="{m - 6}" y="{py(d) + 4:.1f}" text-anchor="end">1e{d} s</text>')
# Slope-1 reference through the largest system.
xa, ya = xs[-1], ys[-1]
out.append(f'<line x1="{px(x0):.1f}" y1="{py(ya - (xa - x0)):.1f}" x2="{px(xa):.1f}" y2="{py(ya):.1f}" '
           f'stroke="#c33" stroke-dasharray="5,4"/>')
out.append(f'<text x="{px(x0) + 4:.1f}" y="{py(ya - (xa - x0)) - 6:.1f}" fill="#c33">linear growth</text>')
for x, y in zip(xs, ys):
    out.append(f'<circle cx="{px(x):.1f}" cy="{py(y):.1f}" r="4" fill="#236"/>')
out.append(f'<text x="{w / 2}" y="{h - 16}" text-anchor="middle">unknowns</text>')
out.append("</svg>")
open("docs/images/solver-scaling.svg", "w").write("\n".join(out) + "\n")
print(f"docs/images/solver-scaling.svg: {len(rows)} points")
