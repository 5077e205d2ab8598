# Triangles that draw a Voronoi face (an f_s face of the graph) from its boundary: the
# polylines of its Voronoi edges chained into closed loops (an outer loop and the loops
# around holes), projected onto their best-fitting plane and cut into triangles there (ear
# clipping with the holes bridged in). A face that folds over every plane (the cylinder
# between the two walls of a tube) is drawn as the band between its two loops. Pure Python
# with numpy: no OCCT face filling, which took seconds per face on industrial parts.
"""Drawing Voronoi faces as triangles (VoroHex)."""

import math

import numpy as np

__all__ = ["triangulate_face"]


def _chain_loops(polylines, close):
    """Closed loops (lists of 3-D points, first point not repeated) from the polylines,
    with the indices (per loop) of points where two polylines meet; and the number of
    polylines left over that close no loop. Polylines meet where their ends are within
    `close`; a loop closes on itself within two of its sampling steps (a closed Voronoi
    edge, a circle, does not repeat its first point)."""
    chains = [[tuple(p) for p in pl] for pl in polylines if len(pl) >= 2]
    loops, corners, left = [], [], 0

    def near(a, b, tol=close):
        return math.dist(a, b) <= tol

    def step(chain):
        return max(math.dist(chain[i - 1], chain[i]) for i in range(1, len(chain)))

    while chains:
        loop = list(chains.pop(0))
        joints = [0]
        gap = 2.0 * step(loop)
        while not (len(loop) >= 3 and near(loop[0], loop[-1], max(close, gap))):
            end = loop[-1]
            for k, c in enumerate(chains):
                if near(c[0], end):
                    joints.append(len(loop) - 1)
                    loop += c[1:]
                    break
                if near(c[-1], end):
                    joints.append(len(loop) - 1)
                    loop += list(reversed(c))[1:]
                    break
            else:
                left += 1
                loop = None
                break
            gap = max(gap, 2.0 * step(chains.pop(k)))
        if loop is None:
            continue
        if near(loop[0], loop[-1]):
            loop.pop()  # the last point is the first
        if len(loop) >= 3:
            loops.append(loop)
            corners.append(set(j % len(loop) for j in joints))
    return loops, corners, left


def _thin(loop, keep, spacing):
    """The loop with points closer than `spacing` to the last kept one dropped, except
    where two polylines meet (the face's corners)."""
    out = [loop[0]]
    for i in range(1, len(loop)):
        if i in keep or math.dist(loop[i], out[-1]) >= spacing:
            out.append(loop[i])
    while len(out) > 3 and math.dist(out[-1], out[0]) < spacing and (len(loop) - 1) not in keep:
        out.pop()
    return out


def _area(poly):
    """Signed area: positive when counter-clockwise."""
    return 0.5 * sum(poly[i - 1][0] * poly[i][1] - poly[i][0] * poly[i - 1][1]
                     for i in range(len(poly)))


def _cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _segments_cross(p1, p2, q1, q2):
    d1, d2 = _cross(q1, q2, p1), _cross(q1, q2, p2)
    d3, d4 = _cross(p1, p2, q1), _cross(p1, p2, q2)
    return ((d1 > 0) != (d2 > 0)) and ((d3 > 0) != (d4 > 0)) and d1 * d2 < 0 and d3 * d4 < 0


def _simple(loops2d):
    """True when no two edges of the loops (together) cross."""
    segs = [(a[i - 1], a[i]) for a in loops2d for i in range(len(a))]
    # Sort by x extent and sweep, so that only overlapping spans are compared.
    spans = sorted(((min(p[0], q[0]), max(p[0], q[0]), p, q) for p, q in segs),
                   key=lambda s: s[0])
    for i, (lo, hi, p, q) in enumerate(spans):
        for lo2, hi2, r, s in spans[i + 1:]:
            if lo2 > hi:
                break
            if p in (r, s) or q in (r, s):
                continue
            if _segments_cross(p, q, r, s):
                return False
    return True


def _inside(pt, poly):
    x, y = pt
    inside = False
    for i in range(len(poly)):
        (x1, y1), (x2, y2) = poly[i - 1], poly[i]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


def _bridge(outer, hole, pts, blockers):
    """Joins a hole (indices, clockwise) into the outer polygon (indices, counter-
    clockwise) through the nearest pair of vertices whose segment crosses no edge."""
    segs = [(pts[b[i - 1]], pts[b[i]]) for b in blockers for i in range(len(b))]
    best = None
    for j in sorted(hole, key=lambda h: -pts[h][0])[:8]:  # rightmost hole vertices first
        m = pts[j]
        for i in sorted(range(len(outer)), key=lambda i: math.dist(pts[outer[i]], m)):
            p = pts[outer[i]]
            if all(not _segments_cross(m, p, a, b) or p in (a, b) or m in (a, b)
                   for a, b in segs):
                d = math.dist(p, m)
                if best is None or d < best[0]:
                    best = (d, i, hole.index(j))
                break
    if best is None:
        return None
    _, i, j = best
    return outer[:i + 1] + hole[j:] + hole[:j + 1] + outer[i:]


def _ear_clip(poly, pts):
    """Triangles (index triples) of a simple counter-clockwise polygon of point indices."""
    idx = list(poly)
    size = max(max(abs(pts[i][0]), abs(pts[i][1])) for i in idx) or 1.0
    flat = 1e-12 * size * size
    tris = []
    while len(idx) > 3:
        n = len(idx)
        for k in range(n):
            a, b, c = idx[k - 1], idx[k], idx[(k + 1) % n]
            pa, pb, pc = pts[a], pts[b], pts[c]
            turn = _cross(pa, pb, pc)
            if abs(turn) <= flat and pa != pc:  # b on a straight run: no area, drop it
                del idx[k]
                break
            if turn <= 0:
                continue  # reflex
            corners = (pa, pb, pc)
            if any(pts[v] not in corners and _cross(pa, pb, pts[v]) > flat and
                   _cross(pb, pc, pts[v]) > flat and _cross(pc, pa, pts[v]) > flat
                   for v in idx):
                continue
            tris.append((a, b, c))
            del idx[k]
            break
        else:
            return None  # no ear: numerically not simple
    if len(idx) == 3 and abs(_cross(*(pts[i] for i in idx))) > flat:
        tris.append(tuple(idx))
    return tris


def _band(loop_a, loop_b, samples=48):
    """Points and triangles of the band between two closed loops (a ruled strip)."""
    def resample(loop):
        closed = loop + [loop[0]]
        lengths = [0.0]
        for i in range(1, len(closed)):
            lengths.append(lengths[-1] + math.dist(closed[i - 1], closed[i]))
        total, out, k = lengths[-1], [], 0
        for s in range(samples):
            t = total * s / samples
            while k < len(lengths) - 2 and lengths[k + 1] < t:
                k += 1
            seg = lengths[k + 1] - lengths[k] or 1.0
            f = (t - lengths[k]) / seg
            out.append(tuple(closed[k][d] + f * (closed[k + 1][d] - closed[k][d])
                             for d in range(3)))
        return out

    a, b = resample(loop_a), resample(loop_b)
    start = min(range(samples), key=lambda i: math.dist(a[0], b[i]))
    forward = [b[(start + i) % samples] for i in range(samples)]
    backward = [b[(start - i) % samples] for i in range(samples)]
    b = min((forward, backward), key=lambda c: sum(math.dist(p, q) for p, q in zip(a, c)))
    points = a + b
    tris = []
    for i in range(samples):
        j = (i + 1) % samples
        tris += [(i, j, samples + i), (j, samples + j, samples + i)]
    return points, tris


def triangulate_face(polylines, scale, inner_point=None):
    """(points, triangles, None) drawing the Voronoi face bounded by `polylines` (its
    edges' point lists), or (None, None, reason) when it cannot be drawn. `scale`: the
    model's size (bounding-box diagonal), for tolerances; inner_point: a point of the face
    (the graph gives one), the apex of a fan for a one-loop face that folds over every
    plane (an approximation of its surface)."""
    loops, corners, left = _chain_loops(polylines, 1e-6 * scale)
    if not loops:
        return None, None, "its {} boundary edge(s) do not close into a loop".format(
            len(polylines))
    spacing = 5e-3 * scale
    loops = [_thin(lp, keep, spacing) for lp, keep in zip(loops, corners)]
    loops = [lp for lp in loops if len(lp) >= 3]
    if not loops:
        return None, None, "its boundary is smaller than the drawing accuracy"
    allpts = np.array([p for lp in loops for p in lp], dtype=float)
    centre = allpts.mean(axis=0)
    _, _, vt = np.linalg.svd(allpts - centre, full_matrices=False)
    u, v = vt[0], vt[1]
    loops2d = [[(float(np.dot(np.subtract(p, centre), u)), float(np.dot(np.subtract(p, centre), v)))
                for p in lp] for lp in loops]
    extent = max(max(abs(_area(lp)) for lp in loops2d), 1e-300)
    flat_enough = all(abs(_area(lp)) > 1e-6 * extent for lp in loops2d)
    if flat_enough and _simple(loops2d):
        tris = _triangulate_2d(loops2d)
        if tris is not None:
            return [p for lp in loops for p in lp], tris, None
    if len(loops) == 2:
        points, tris = _band(loops[0], loops[1])
        return points, tris, None
    if len(loops) == 1 and inner_point is not None:
        loop = loops[0]
        n = len(loop)
        return loop + [tuple(inner_point)], [(i, (i + 1) % n, n) for i in range(n)], None
    return None, None, ("it folds over every plane and has {} boundary loops (only a face "
                        "with one plane view or two loops is drawn)".format(len(loops)))


def _triangulate_2d(loops2d):
    """Triangles over the concatenated points of the loops (outer loops with their holes),
    or None."""
    pts, index_loops, at = [], [], 0
    for lp in loops2d:
        pts += lp
        index_loops.append(list(range(at, at + len(lp))))
        at += len(lp)
    # A loop inside an odd number of others is a hole of the smallest loop around it.
    depth, parent = [], []
    for k, lp in enumerate(loops2d):
        around = [j for j, other in enumerate(loops2d) if j != k and _inside(lp[0], other)]
        depth.append(len(around))
        parent.append(min(around, key=lambda j: abs(_area(loops2d[j]))) if around else None)
    tris = []
    for k, lp in enumerate(loops2d):
        if depth[k] % 2:
            continue
        outer = index_loops[k] if _area(lp) > 0 else index_loops[k][::-1]
        holes = [index_loops[j] if _area(loops2d[j]) < 0 else index_loops[j][::-1]
                 for j in range(len(loops2d)) if parent[j] == k and depth[j] % 2]
        holes.sort(key=lambda h: -max(pts[i][0] for i in h))
        for h in holes:
            joined = _bridge(outer, h, pts, [outer] + holes)
            if joined is None:
                return None
            outer = joined
        part = _ear_clip(outer, pts)
        if part is None:
            return None
        tris += part
    return tris
