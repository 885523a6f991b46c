"""The plain peer of issue #34's STL row: Python writing binary STL with `struct.pack` only.

Usage: stl_writer.py LACUNA.stl OUT.stl [RUNS]
Reads the triangles of a binary STL written by `lacuna render ... --stl` (before the clock
starts), then writes the same triangles as binary STL: an 80-byte header, the count, and per
facet its unit normal (computed here from the vertices, as a writer has to), the three vertices
as little-endian f32 and a zero attribute word, 50 bytes a facet. Best of RUNS (default 3).
Prints `triangles seconds check`, where check says whether every facet's vertex bytes equal
lacuna's (the same triangles were written)."""
import math
import struct
import sys
import time

FACET = struct.Struct("<12fH")


def read(path):
    data = open(path, "rb").read()
    (count,) = struct.unpack_from("<I", data, 80)
    vertices = struct.Struct("<9f")
    return data, [vertices.unpack_from(data, 84 + 50 * i + 12) for i in range(count)]


def write(path, triangles):
    with open(path, "wb") as f:
        f.write(b"binary STL written by a plain Python struct writer".ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for ax, ay, az, bx, by, bz, cx, cy, cz in triangles:
            ux, uy, uz = bx - ax, by - ay, bz - az
            vx, vy, vz = cx - ax, cy - ay, cz - az
            nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
            length = math.sqrt(nx * nx + ny * ny + nz * nz) or 1.0
            f.write(FACET.pack(nx / length, ny / length, nz / length,
                               ax, ay, az, bx, by, bz, cx, cy, cz, 0))


def main(src, dst, runs):
    original, triangles = read(src)
    best = math.inf
    for _ in range(runs):
        start = time.perf_counter()
        write(dst, triangles)
        best = min(best, time.perf_counter() - start)
    ours = open(dst, "rb").read()
    same = len(ours) == len(original) and all(
        ours[84 + 50 * i + 12:84 + 50 * i + 48] == original[84 + 50 * i + 12:84 + 50 * i + 48]
        for i in range(len(triangles)))
    print(len(triangles), f"{best:.4f}", "same-vertices" if same else "vertices-differ")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 3)
