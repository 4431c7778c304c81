"""The Cornell box of ../shared/scenes/cornell-box-spec.md in Cycles, as scenes/cornell-box.lua builds it in torte.
Run: blender -b --factory-startup --python bench/cycles/cornell_box.py -- out=x.exr [size=256] [spp=1024]
     [bounces=64] [threads=2]"""
import math
import os
import sys

WHITE, RED, GREEN = (0.73, 0.73, 0.73), (0.63, 0.065, 0.05), (0.14, 0.45, 0.091)
# (name, colour, emission, v0, v1, v2, v3); each quad is the triangles (v0, v1, v2) and (v0, v2, v3).
QUADS = [
    ("floor", WHITE, None, (552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)),
    ("ceiling", WHITE, None, (556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)),
    ("back", WHITE, None, (549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2)),
    ("green", GREEN, None, (0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)),
    ("red", RED, None, (552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0)),
    ("short", WHITE, None, (130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)),
    ("short", WHITE, None, (290, 0, 114), (290, 165, 114), (240, 165, 272), (240, 0, 272)),
    ("short", WHITE, None, (130, 0, 65), (130, 165, 65), (290, 165, 114), (290, 0, 114)),
    ("short", WHITE, None, (82, 0, 225), (82, 165, 225), (130, 165, 65), (130, 0, 65)),
    ("short", WHITE, None, (240, 0, 272), (240, 165, 272), (82, 165, 225), (82, 0, 225)),
    ("tall", WHITE, None, (423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)),
    ("tall", WHITE, None, (423, 0, 247), (423, 330, 247), (472, 330, 406), (472, 0, 406)),
    ("tall", WHITE, None, (472, 0, 406), (472, 330, 406), (314, 330, 456), (314, 0, 456)),
    ("tall", WHITE, None, (314, 0, 456), (314, 330, 456), (265, 330, 296), (265, 0, 296)),
    ("tall", WHITE, None, (265, 0, 296), (265, 330, 296), (423, 330, 247), (423, 0, 247)),
    ("light", (0, 0, 0), (17, 12, 4), (343, 548.7, 227), (343, 548.7, 332), (213, 548.7, 332), (213, 548.7, 227)),
]
EYE, LOOK_AT, UP = (278, 273, -800), (278, 273, 0), (0, 1, 0)
VFOV = 2 * math.degrees(math.atan(12.5 / 35))

if __name__ == "__main__":  # inside Blender; compare.py imports the tables above without bpy
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import cycles_common as cc
    a = cc.args()
    size = int(a.get("size", 256))
    cc.setup(size, size, int(a.get("spp", 1024)), int(a.get("bounces", 64)), int(a.get("threads", 2)))
    mats = {}
    for i, (name, color, emission, *quad) in enumerate(QUADS):
        key = (color, emission)
        if key not in mats:
            mats[key] = cc.material(f"m{len(mats)}", "lambert", color, emission=emission)
        cc.mesh_object(f"{name}{i}", quad, [(0, 1, 2), (0, 2, 3)], mats[key])
    cc.camera(EYE, LOOK_AT, UP, VFOV)
    cc.render(os.path.abspath(a["out"]))
