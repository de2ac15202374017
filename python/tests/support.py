"""Fixtures of the Python module's tests: meshes made by code and the closed forms they are
checked against (the same formulas as tests/support/closed_forms.hpp, in numpy).

Ball of radius R (T. Yamada's PDE with ã = a·h0², κ = 2/(a·h0), z = κR): s = A·x inside with
A = 1/(ã(2 + z + 1/(1+z))), so ∇s = A·I, f_h = 3·h0²·A, h_f = h0(1/f_h − a) and the principal
thickness h_p = h0(1/(h0²·A) − a), everywhere inside and on the surface.
"""

import numpy as np


def icosphere(radius, subdivisions):
    """Geodesic sphere: the icosahedron with every triangle split in four `subdivisions`
    times, vertices pushed onto the sphere. 20·4^k faces, 10·4^k + 2 vertices, outward
    oriented. Returns V float64 (n, 3), F int64 (m, 3)."""
    t = (1.0 + 5.0 ** 0.5) / 2.0
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    vertices = [np.array(v, dtype=float) / np.linalg.norm(v) for v in vertices]
    for _ in range(subdivisions):
        midpoint = {}

        def middle(i, j):
            key = (min(i, j), max(i, j))
            if key not in midpoint:
                m = vertices[i] + vertices[j]
                vertices.append(m / np.linalg.norm(m))
                midpoint[key] = len(vertices) - 1
            return midpoint[key]

        finer = []
        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = finer
    return radius * np.array(vertices), np.array(faces, dtype=np.int64)


def box(size):
    """Axis-aligned box [0, sx]×[0, sy]×[0, sz]: 8 vertices, 12 outward-oriented triangles."""
    sx, sy, sz = size
    V = np.array([(x, y, z) for z in (0, sz) for y in (0, sy) for x in (0, sx)], dtype=float)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    F = [(a, b, c) for a, b, c, d in quads] + [(a, c, d) for a, b, c, d in quads]
    return V, np.array(F, dtype=np.int64)


class Ball:
    """The closed form of the ball of radius R for the PDE's h0 and a."""

    def __init__(self, radius, h0, a=0.2):
        a_tilde = a * h0 * h0
        z = 2.0 / (a * h0) * radius
        self.A = 1.0 / (a_tilde * (2.0 + z + 1.0 / (1.0 + z)))
        self.f_h = 3.0 * h0 * h0 * self.A
        self.h_f = h0 * (1.0 / self.f_h - a)
        self.h_p = h0 * (1.0 / (h0 * h0 * self.A) - a)


def max_relative_deviation(values, reference):
    return float(np.max(np.abs(np.asarray(values) / reference - 1.0)))
