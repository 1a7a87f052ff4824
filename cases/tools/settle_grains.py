"""Deterministic settling of disks (2D) or spheres (3D) into a box under gravity: a stand-in
for the DEM pre-processing step with which Fuchs et al. 2021 obtained their powder grains'
positions ("can, e.g., be obtained in a pre-processing step based on the discrete element
method (DEM) and a cohesive powder model"). We do not have their DEM positions, so this places
grains with a seeded generator and lets them settle by position-based dynamics (Mueller et al.
2007): every iteration moves all grains down by a small step and then projects away overlaps
with the floor, the side walls and each other (pairs pushed apart along the line of centres,
in proportion to the other grain's mass), until no grain moves any more. The result is a
packing in which every grain rests on the floor, the walls or other grains, without overlap
(the grains start at rest on their supports, as in the paper), reproducible bit for bit from
the seed. No cohesion: the paper's cohesive model would leave a looser packing.

Used by make_powder_grains.py (2D) and make_powder_melting_3d.py (3D)."""
import math
import random


def settle(diameters, lo, hi, seed, clearance=0.0, step=None, tol=1e-7, max_iter=200000):
    """Settles grains with the given diameters into the box [lo, hi] (lists of length 2 or 3,
    gravity along -axis 1 in 2D and -axis 2 in 3D). Grains start at random positions in a
    column above the box, one above the next. `clearance` is kept between grains and from
    the walls. Returns a list of (centre, radius)."""
    dim = len(lo)
    up = dim - 1  # gravity along -y (2D) or -z (3D)
    rng = random.Random(seed)
    radii = [0.5 * d for d in diameters]
    pos = []
    height = lo[up]
    for r in radii:
        c = [rng.uniform(lo[a] + r + clearance, hi[a] - r - clearance) for a in range(dim)]
        height += 2 * r + clearance
        c[up] = height
        pos.append(c)
    step = step if step is not None else 0.01 * min(radii)
    mass = [r ** dim for r in radii]

    def project():
        """One sweep of the constraints; returns the largest violation it found."""
        worst = 0.0
        for i, p in enumerate(pos):
            r = radii[i] + clearance
            for a in range(dim):
                low = lo[a] + r
                high = hi[a] - r if a != up else math.inf
                worst = max(worst, low - p[a], p[a] - high)
                p[a] = min(max(p[a], low), high)
        for i in range(len(pos)):
            for j in range(i + 1, len(pos)):
                d = [pos[j][a] - pos[i][a] for a in range(dim)]
                dist = math.sqrt(sum(v * v for v in d))
                need = radii[i] + radii[j] + clearance
                if dist < need:
                    if dist == 0.0:  # coincident centres: separate along the first axis
                        d, dist = [1.0] + [0.0] * (dim - 1), 1.0
                    worst = max(worst, need - dist)
                    push = (need - dist) / dist
                    wi = mass[j] / (mass[i] + mass[j])
                    for a in range(dim):
                        pos[i][a] -= wi * push * d[a]
                        pos[j][a] += (1 - wi) * push * d[a]
        return worst

    for it in range(max_iter):
        old = [list(p) for p in pos]
        for p in pos:
            p[up] -= step
        for _ in range(4):  # a few projection sweeps per iteration
            project()
        moved = max(math.sqrt(sum((p[a] - q[a]) ** 2 for a in range(dim))) for p, q in zip(pos, old))
        if it > 100 and moved < tol:  # settled: nothing moves any more
            break
    # Without the gravity step, sweep until no overlap is left (walls and pairs together).
    for _ in range(10000):
        if project() < 1e-12:
            break
    return [(p, r) for p, r in zip(pos, radii)], it
