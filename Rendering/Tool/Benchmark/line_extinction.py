"""The table of cao::LineVoxelExtinction (Filters/Kernels/Lines/caoLineAO.cxx):
for each tube radius rho (in voxels), the extinction sigma (per voxel length)
that makes the voxels VoxelizeLines sets for a tube (every cube the axis
passes through, and every voxel whose centre lies within rho of the axis)
block rays as the exact tube does, on average over rays of every direction
and offset: the sigma whose mean exp(-sigma l) over the rays' chords l
through the voxelized tube equals the rays' mean transmittance through the
exact tube (0 when the ray meets it, else 1). A tube of random direction
through a random point of the unit cell, cut to a slab 8 voxels long along
its axis (the same cut for both); rays of uniform direction, offset
uniformly over a disk of radius rho + 2.5 around the tube's point. rho 0
is a line drawn as a line: its supercover against a tube of the
supercover's cross-section (1.5 voxels^2: radius 0.691). Seeded; pure
Python, about 5 s a radius at the default 20 000 rays. Run with
/usr/bin/python3:

    /usr/bin/python3 Rendering/Tool/Benchmark/line_extinction.py [RHO ...]
"""
import math
import os
import random
import sys


def unit(rng):
    while True:
        v = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in v))
        if n > 1e-9:
            return [x / n for x in v]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def cube_hit(o, axis, c):
    """The infinite line o + t axis meets the cube [c, c + 1]."""
    t0, t1 = -1e30, 1e30
    for a in range(3):
        if abs(axis[a]) < 1e-12:
            if o[a] < c[a] or o[a] > c[a] + 1:
                return False
        else:
            u, v = (c[a] - o[a]) / axis[a], (c[a] + 1 - o[a]) / axis[a]
            t0, t1 = max(t0, min(u, v)), min(t1, max(u, v))
    return t0 <= t1


def chord(start, d, length, is_set):
    """The length of start + t d, t in [0, length], inside set voxels
    (Amanatides and Woo's walk, as cao::LineRaysOf)."""
    cell = [math.floor(x) for x in start]
    step = [1 if x > 0 else -1 for x in d]
    nxt, delta = [], []
    for a in range(3):
        if abs(d[a]) < 1e-12:
            nxt.append(1e30)
            delta.append(1e30)
        else:
            c = math.floor(start[a])
            nxt.append(((c + 1 - start[a]) if d[a] > 0 else (start[a] - c)) / abs(d[a]))
            delta.append(1 / abs(d[a]))
    t = total = 0.0
    while t < length:
        a = min(range(3), key=lambda q: nxt[q])
        leave = min(nxt[a], length)
        if is_set(tuple(cell)):
            total += leave - t
        t = leave
        nxt[a] += delta[a]
        cell[a] += step[a]
    return total


def extinction(rho, trials, seed=7):
    rng = random.Random(seed)
    real_rho = rho if rho > 0 else math.sqrt(1.5 / math.pi)
    half = 4.0  # the slab's half length along the axis
    chords, passes = [], []
    for _ in range(trials):
        o = [rng.random() for _ in range(3)]
        axis = unit(rng)
        cache = {}

        def is_set(c):
            if c not in cache:
                centre = [c[0] + 0.5 - o[0], c[1] + 0.5 - o[1], c[2] + 0.5 - o[2]]
                along = dot(centre, axis)
                inside = False
                if abs(along) <= half:
                    inside = cube_hit(o, axis, c) or (
                        rho > 0 and dot(centre, centre) - along * along <= rho * rho)
                cache[c] = inside
            return cache[c]

        d = unit(rng)
        e1 = cross(d, [1, 0, 0] if abs(d[0]) < 0.6 else [0, 1, 0])
        n = math.sqrt(dot(e1, e1))
        e1 = [x / n for x in e1]
        e2 = cross(d, e1)
        r, phi = (rho + 2.5) * math.sqrt(rng.random()), 2 * math.pi * rng.random()
        p = [o[k] + r * math.cos(phi) * e1[k] + r * math.sin(phi) * e2[k] for k in range(3)]
        start = [p[k] - 2 * half * d[k] for k in range(3)]
        chords.append(chord(start, d, 4 * half, is_set))
        # The exact tube: the ray's line against the cylinder of radius
        # real_rho, cut by the same slab.
        w0 = [p[k] - o[k] for k in range(3)]
        a1, b1 = dot(d, axis), dot(w0, axis)
        dp = [d[k] - a1 * axis[k] for k in range(3)]
        wp = [w0[k] - b1 * axis[k] for k in range(3)]
        qa, qb, qc = dot(dp, dp), 2 * dot(dp, wp), dot(wp, wp) - real_rho * real_rho
        if qa < 1e-12:
            t0, t1 = (-1e30, 1e30) if qc < 0 else (1, 0)
        else:
            disc = qb * qb - 4 * qa * qc
            if disc < 0:
                t0, t1 = 1, 0
            else:
                sq = math.sqrt(disc)
                t0, t1 = (-qb - sq) / (2 * qa), (-qb + sq) / (2 * qa)
        hit = False
        if t0 <= t1:
            if abs(a1) < 1e-12:
                s0, s1 = (-1e30, 1e30) if abs(b1) <= half else (1, 0)
            else:
                s0, s1 = sorted(((-half - b1) / a1, (half - b1) / a1))
            hit = max(t0, s0, -2 * half) <= min(t1, s1, 2 * half)
        passes.append(0.0 if hit else 1.0)
    target = sum(passes) / len(passes)
    lo, hi = 0.0, 50.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if sum(math.exp(-mid * l) for l in chords) / len(chords) > target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi), target


if __name__ == "__main__":
    trials = int(os.environ.get("TRIALS", "20000"))
    radii = [float(x) for x in sys.argv[1:]] or [0, 0.25, 0.5, 0.75, 1, 1.25, 1.5, 2, 3, 4, 6]
    print("| rho (voxels) | sigma (per voxel) | exact tube's transmittance |")
    print("|---:|---:|---:|")
    for rho in radii:
        sigma, target = extinction(rho, trials)
        print("| %.2f | %.3f | %.3f |" % (rho, sigma, target), flush=True)
