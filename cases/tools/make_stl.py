#!/usr/bin/env python3
"""Writes the small binary STL files the cases in cases/ read (cases/geometry/).

  cases/tools/make_stl.py [OUT_DIR]       (default: cases/geometry next to this script)

funnel_block.stl  a solid cylinder of radius 50 and height 60 whose top is a cone falling to
                  a depression 30 deep at the axis (Reder et al. 2021 sec. 3.4's cone, as a
                  wall block), in millimetres, 48 segments around
icosphere.stl     an icosahedron subdivided twice (320 triangles) on the unit sphere
Both are closed and oriented outwards (checked here by their signed volume).
"""
import math
import os
import struct
import sys


def write_stl(path, vertices, triangles):
    volume = sum(dot(v_a, cross(v_b, v_c)) for v_a, v_b, v_c in
                 ((vertices[a], vertices[b], vertices[c]) for a, b, c in triangles)) / 6
    if volume < 0:
        triangles = [(a, c, b) for a, b, c in triangles]
    with open(path, "wb") as f:
        f.write(b"sphd cases/tools/make_stl.py".ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for a, b, c in triangles:
            f.write(struct.pack("<3f", 0, 0, 0))
            for v in (vertices[a], vertices[b], vertices[c]):
                f.write(struct.pack("<3f", *v))
            f.write(struct.pack("<H", 0))
    print(f"{path}: {len(triangles)} triangles, volume {abs(volume):.6g}")


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def revolve(profile, segments):
    """Surface of revolution about z of a closed profile [(r, z), ...] whose first and last
    points lie on the axis (r = 0)."""
    vertices, index = [], {}
    for k, (r, z) in enumerate(profile):
        if r == 0:
            index[(k, 0)] = len(vertices)
            vertices.append((0.0, 0.0, z))
        else:
            for j in range(segments):
                t = 2 * math.pi * j / segments
                index[(k, j)] = len(vertices)
                vertices.append((r * math.cos(t), r * math.sin(t), z))

    def vid(k, j):
        return index[(k, 0)] if profile[k][0] == 0 else index[(k, j % segments)]

    triangles = []
    for k in range(len(profile) - 1):
        for j in range(segments):
            a, b = vid(k, j), vid(k + 1, j)
            c, d = vid(k + 1, j + 1), vid(k, j + 1)
            if a != d:
                triangles.append((a, b, d) if b == c else (a, b, c))
            if b != c and a != d:
                triangles.append((a, c, d))
            elif b != c:
                triangles.append((a, b, c))
    return vertices, triangles


def icosphere(levels):
    t = (1 + 5 ** 0.5) / 2
    raw = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
           (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    vertices = [tuple(c / math.sqrt(dot(v, v)) for c in v) for v in raw]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9),
                 (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2),
                 (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
                 (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        mid = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                m = [(vertices[a][i] + vertices[b][i]) / 2 for i in range(3)]
                n = math.sqrt(dot(m, m))
                vertices.append(tuple(c / n for c in m))
                mid[key] = len(vertices) - 1
            return mid[key]

        nxt = []
        for a, b, c in triangles:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            nxt += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        triangles = nxt
    return vertices, triangles


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "geometry")
    os.makedirs(out, exist_ok=True)
    write_stl(os.path.join(out, "funnel_block.stl"),
              *revolve([(0, 0), (50, 0), (50, 60), (0, 30)], 48))
    write_stl(os.path.join(out, "icosphere.stl"), *icosphere(2))


if __name__ == "__main__":
    main()
