"""Region means of two linear EXR renders of the same scene (torte and Cycles) and their relative difference.
  python3 compare.py torte.exr cycles.exr [--cornell] [--grid 4] [--tolerance 0.01]
--cornell adds the named regions of the Cornell box (walls, floor, ceiling, blocks, light), found by casting each
pixel's rays into the spec's quads: only pixels whose centre and four inner corners see the same surface count.
Prints one line per region (both means, RGB, and the largest relative channel difference) and a last line
`regions_max_rel_diff=<d> within=<yes|no>`; exits 0 either way (bench/cycles/run.sh reports)."""
import argparse
import math
import os
import sys

import numpy as np
import OpenImageIO as oiio


def read_rgb(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"compare.py: {path}: {buf.geterror()}")
    px = buf.get_pixels(oiio.FLOAT)
    if px is None or px.ndim != 3 or px.shape[2] < 3:
        sys.exit(f"compare.py: {path}: not an RGB image")
    return px[:, :, :3].astype(np.float64)


def cornell_labels(w, h):
    """Per pixel the index of the named region it sees entirely, or -1."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import cornell_box as cb
    names = sorted({q[0] for q in cb.QUADS})
    tris = []
    for name, _c, _e, v0, v1, v2, v3 in cb.QUADS:
        for a, b, c in ((v0, v1, v2), (v0, v2, v3)):
            tris.append((names.index(name), np.array(a, float), np.array(b, float), np.array(c, float)))
    eye, look = np.array(cb.EYE, float), np.array(cb.LOOK_AT, float)
    fwd = (look - eye) / np.linalg.norm(look - eye)
    right = np.cross(fwd, np.array(cb.UP, float))  # +x points to the image's left: right is -x
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    t = math.tan(math.radians(cb.VFOV) / 2)
    label = None
    for ox, oy in ((0.5, 0.5), (0.05, 0.05), (0.95, 0.05), (0.05, 0.95), (0.95, 0.95)):
        xs = (2 * (np.arange(w) + ox) / w - 1) * t * w / h
        ys = (1 - 2 * (np.arange(h) + oy) / h) * t
        d = fwd[None, None, :] + xs[None, :, None] * right + ys[:, None, None] * up
        best = np.full((h, w), np.inf)
        lab = np.full((h, w), -1)
        for idx, a, b, c in tris:  # Moller-Trumbore over all pixels at once
            e1, e2 = b - a, c - a
            p = np.cross(d, e2)
            det = p @ e1
            with np.errstate(divide="ignore", invalid="ignore"):
                inv = 1 / det
                s = eye - a
                u = (p @ s) * inv
                q = np.cross(s, e1)
                v = (d @ q) * inv
                tt = (q @ e2) * inv
            hit = (np.abs(det) > 1e-12) & (u >= 0) & (v >= 0) & (u + v <= 1) & (tt > 0) & (tt < best)
            best[hit] = tt[hit]
            lab[hit] = idx
        label = lab if label is None else np.where(label == lab, label, -1)
    return names, label


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("torte")
    ap.add_argument("cycles")
    ap.add_argument("--cornell", action="store_true")
    ap.add_argument("--grid", type=int, default=4)
    ap.add_argument("--tolerance", type=float, default=0.01)
    o = ap.parse_args()
    a, b = read_rgb(o.torte), read_rgb(o.cycles)
    if a.shape != b.shape:
        sys.exit(f"compare.py: sizes differ: {a.shape[1]}x{a.shape[0]} and {b.shape[1]}x{b.shape[0]}")
    h, w = a.shape[:2]
    regions = []
    g = o.grid
    for j in range(g):
        for i in range(g):
            m = np.zeros((h, w), bool)
            m[j * h // g:(j + 1) * h // g, i * w // g:(i + 1) * w // g] = True
            regions.append((f"tile{j}{i}", m))
    if o.cornell:
        names, label = cornell_labels(w, h)
        regions += [(n, label == k) for k, n in enumerate(names)]
    worst = 0.0
    print(f"{'region':10} {'pixels':>6}  {'torte mean (RGB)':>30}  {'cycles mean (RGB)':>30}  rel.diff")
    for name, m in regions:
        ma, mb = a[m].mean(axis=0), b[m].mean(axis=0)
        # Relative to the larger of the two means per channel; channels under 1e-3 of the region's brightest are
        # noise-dominated (the red wall's blue) and are compared against that brightest channel instead.
        scale = np.maximum(np.maximum(np.abs(ma), np.abs(mb)), 1e-3 * max(ma.max(), mb.max(), 1e-12))
        rel = float(np.max(np.abs(ma - mb) / scale))
        worst = max(worst, rel)
        fa = " ".join(f"{x:9.5f}" for x in ma)
        fb = " ".join(f"{x:9.5f}" for x in mb)
        print(f"{name:10} {int(m.sum()):6d}  {fa:>30}  {fb:>30}  {100 * rel:6.2f} %")
    print(f"regions_max_rel_diff={worst:.4f} within={'yes' if worst <= o.tolerance else 'no'}")


if __name__ == "__main__":
    main()
