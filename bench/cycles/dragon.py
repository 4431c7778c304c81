"""scenes/dragon-bench.lua in Cycles: two Stanford dragons (the PLY's vertices and normals) on a matte floor under a
uniform sky and one one-sided area light; the same numbers as the torte scene, which documents the materials.
Run: blender -b --factory-startup --python bench/cycles/dragon.py -- out=x.exr ply=<dragon_100k_binary_le.ply>
     [size=256] [spp=1024] [bounces=64] [threads=2]"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_common as cc  # noqa: E402


def read_ply(path):
    """Binary little-endian PLY with float x y z nx ny nz per vertex and uchar-counted int triangles (the file's
    layout; anything else is refused)."""
    with open(path, "rb") as f:
        header = []
        while True:
            line = f.readline().decode("ascii").strip()
            header.append(line)
            if line == "end_header":
                break
        nv = int(next(h for h in header if h.startswith("element vertex")).split()[2])
        nf = int(next(h for h in header if h.startswith("element face")).split()[2])
        props = [h.split()[2] for h in header if h.startswith("property float")]
        if "format binary_little_endian 1.0" not in header or props != ["x", "y", "z", "nx", "ny", "nz"]:
            sys.exit(f"dragon.py: {path}: unexpected PLY layout")
        v = np.frombuffer(f.read(nv * 24), dtype="<f4").reshape(nv, 6)
        faces = np.frombuffer(f.read(nf * 13), dtype=np.dtype([("n", "u1"), ("i", "<i4", 3)]))
        if not np.all(faces["n"] == 3):
            sys.exit(f"dragon.py: {path}: not all faces are triangles")
    return v[:, :3].astype(np.float64), v[:, 3:].astype(np.float64), faces["i"].astype(np.int64)


if __name__ == "__main__":
    a = cc.args()
    size = int(a.get("size", 256))
    scene = cc.setup(size, size, int(a.get("spp", 1024)), int(a.get("bounces", 64)), int(a.get("threads", 2)))
    cc.world_background(scene, (0.30, 0.35, 0.45))
    pos, nrm, tri = read_ply(a["ply"])
    lo, hi = pos.min(axis=0), pos.max(axis=0)
    s = 1 / max(hi[0] - lo[0], hi[2] - lo[2])
    base = (pos - np.array([(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2])) * s
    plastic = cc.material("plastic", "blend", (0.7, 0.25, 0.08), roughness=0.3, gloss=0.1)
    gloss = cc.material("metal", "ggx", (1.0, 1.0, 1.0), roughness=0.3)
    cc.mesh_object("dragon_plastic", base + [0.6, 0, 0], tri, plastic, normals=nrm)
    cc.mesh_object("dragon_metal", base + [-0.6, 0, 0], tri, gloss, normals=nrm)
    floor = cc.material("floor", "lambert", (0.5, 0.5, 0.5))
    cc.mesh_object("floor", [(-4, 0, -4), (-4, 0, 4), (4, 0, 4), (4, 0, -4)], [(0, 1, 2), (0, 2, 3)], floor)
    light = cc.material("light", "lambert", (0.0, 0.0, 0.0), emission=(12, 11, 10))
    cc.mesh_object("light", [(-0.5, 3, -1), (0.5, 3, -1), (0.5, 3, 0), (-0.5, 3, 0)], [(0, 1, 2), (0, 2, 3)], light)
    cc.camera((0, 0.9, -2.5), (0, 0.3, 0), (0, 1, 0), 32)
    cc.render(os.path.abspath(a["out"]))
