"""Shared set-up of the Cycles side of `make bench-cycles` (run inside `blender -b --python`): an empty scene,
Cycles on the CPU with the settings both renderers share, Lambert/GGX/emission materials built from nodes, meshes
from vertex lists, and a timed render to linear EXR. Scene coordinates are torte's (+y up): Cycles does not care
which axis is up, so the geometry is not rotated and the camera is aimed with a look-at frame."""
import math
import sys
import time

import bpy
from mathutils import Matrix, Vector


def args():
    """Arguments after `--` on Blender's command line, as key=value pairs."""
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    return dict(a.split("=", 1) for a in argv)


def setup(width, height, spp, max_bounces, threads, seed=0):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = seed
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = max_bounces
    c.transparent_max_bounces = c.volume_bounces = max_bounces
    c.sample_clamp_direct = 0.0    # no clamping, as in torte
    c.sample_clamp_indirect = 0.0  # (Blender's default clamps indirect light at 10)
    c.blur_glossy = 0.0            # "filter glossy" would blur rough reflections
    c.caustics_reflective = c.caustics_refractive = True
    c.pixel_filter_type = "BOX"    # torte.filter.box{radius = 0.5}: one pixel
    c.filter_width = 1.0
    if hasattr(c, "use_guiding"):
        c.use_guiding = False
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    # Linear output: Standard view (no Filmic), no look, no exposure; EXR holds scene-linear values anyway.
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.color_mode = "RGB"
    world = bpy.data.worlds.new("world")
    scene.world = world
    world_background(scene, (0.0, 0.0, 0.0))
    return scene


def world_background(scene, rgb):
    w = scene.world
    w.use_nodes = True
    bg = w.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (*rgb, 1.0)
    bg.inputs["Strength"].default_value = 1.0


def material(name, kind, color=(0.5, 0.5, 0.5), roughness=0.0, gloss=0.0, emission=None):
    """kind: "lambert" (Diffuse BSDF, roughness 0 = Lambert), "ggx" (Glossy BSDF, colour x single-scattering GGX,
    alpha = roughness^2 as in torte), "blend" ((1 - gloss) Lambert + gloss GGX). emission: one-sided radiance
    (front face only, as torte's emitters): the back face is black."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")

    def diffuse(rgb):
        n = nt.nodes.new("ShaderNodeBsdfDiffuse")
        n.inputs["Color"].default_value = (*rgb, 1.0)
        n.inputs["Roughness"].default_value = 0.0
        return n.outputs[0]

    def glossy(rgb):
        n = nt.nodes.new("ShaderNodeBsdfGlossy")
        n.distribution = "GGX"
        n.inputs["Color"].default_value = (*rgb, 1.0)
        n.inputs["Roughness"].default_value = roughness
        return n.outputs[0]

    def mix(fac_socket_or_value, a, b):
        n = nt.nodes.new("ShaderNodeMixShader")
        if isinstance(fac_socket_or_value, float):
            n.inputs["Fac"].default_value = fac_socket_or_value
        else:
            nt.links.new(fac_socket_or_value, n.inputs["Fac"])
        nt.links.new(a, n.inputs[1])
        nt.links.new(b, n.inputs[2])
        return n.outputs[0]

    if kind == "lambert":
        surface = diffuse(color)
    elif kind == "ggx":
        surface = glossy(color)
    elif kind == "blend":
        surface = mix(float(gloss), diffuse(color), glossy((1.0, 1.0, 1.0)))
    else:
        raise ValueError(kind)
    if emission is not None:
        e = nt.nodes.new("ShaderNodeEmission")
        peak = max(emission)
        e.inputs["Color"].default_value = (*(v / peak for v in emission), 1.0)
        e.inputs["Strength"].default_value = peak
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(surface, add.inputs[0])
        nt.links.new(e.outputs[0], add.inputs[1])
        geo = nt.nodes.new("ShaderNodeNewGeometry")
        surface = mix(geo.outputs["Backfacing"], add.outputs[0], surface)
    nt.links.new(surface, out.inputs["Surface"])
    return m


def mesh_object(name, vertices, triangles, mat, normals=None):
    """A mesh object from vertex and triangle lists (or numpy arrays); normals: per-vertex shading normals,
    interpolated over each triangle (torte uses a file's normals the same way)."""
    me = bpy.data.meshes.new(name)
    nv, nt = len(vertices), len(triangles)
    me.vertices.add(nv)
    me.vertices.foreach_set("co", [float(x) for v in vertices for x in v] if not hasattr(vertices, "ravel")
                            else vertices.astype("f4").ravel())
    me.loops.add(3 * nt)
    me.loops.foreach_set("vertex_index", [int(i) for t in triangles for i in t] if not hasattr(triangles, "ravel")
                         else triangles.astype("i4").ravel())
    me.polygons.add(nt)
    me.polygons.foreach_set("loop_start", list(range(0, 3 * nt, 3)))
    me.polygons.foreach_set("loop_total", [3] * nt)
    me.update(calc_edges=True)
    me.validate(clean_customdata=False)
    if normals is not None:
        me.polygons.foreach_set("use_smooth", [True] * nt)
        me.use_auto_smooth = True
        me.normals_split_custom_set_from_vertices([tuple(map(float, n)) for n in normals])
    me.materials.append(mat)
    ob = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(ob)
    return ob


def camera(eye, look_at, up, vfov_degrees):
    """A pinhole camera; Blender cameras look along local -z with local +y up."""
    cam = bpy.data.cameras.new("camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"
    cam.angle = math.radians(vfov_degrees)
    cam.clip_start = 1e-3
    cam.clip_end = 1e6
    ob = bpy.data.objects.new("camera", cam)
    bpy.context.scene.collection.objects.link(ob)
    eye, look_at, up = Vector(eye), Vector(look_at), Vector(up)
    back = (eye - look_at).normalized()          # local +z
    right = up.cross(back).normalized()          # local +x
    true_up = back.cross(right)                   # local +y
    m = Matrix.Identity(4)
    for r in range(3):
        m[r][0], m[r][1], m[r][2], m[r][3] = right[r], true_up[r], back[r], eye[r]
    ob.matrix_world = m
    bpy.context.scene.camera = ob
    return ob


def render(path):
    """Renders the scene to a linear EXR and prints `cycles_render_seconds=<t>`: the render call itself, scene
    sync and BVH build included, Blender's own start-up excluded."""
    scene = bpy.context.scene
    scene.render.filepath = path
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    t = time.perf_counter() - t0
    print(f"cycles_render_seconds={t:.3f}", flush=True)
