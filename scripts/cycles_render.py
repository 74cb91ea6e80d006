# Renders a project scene with Blender's Cycles, for `bench cycles`
# (src/apps/bench/bench_cycles.cpp). Run by the bench, not by hand:
#
#   blender -b --factory-startup --python scripts/cycles_render.py -- \
#       SCENE_EXPORT.json OUT_PREFIX SPP:SEED [SPP:SEED ...]
#
# SCENE_EXPORT.json is the scene as the project loaded it (world-space
# triangles grouped by material, the camera's basis, film, depth, threads),
# written by the bench, so this script parses no OBJ, MTL or scene JSON of
# its own. Each SPP:SEED job renders OUT_PREFIX_<spp>_<seed>.exr (linear,
# float) and prints one line "CYCLES_RESULT {json}" with its wall seconds
# and the process's CPU seconds during the render. A first 1-spp render is
# a warm-up (kernel loading, caches) and is not reported.
#
# The conventions it matches (docs/sampling.md, "bench cycles"):
#   depth     the project's -m N (paths of up to N bounces, -m 1 direct
#             light) is Cycles' max_bounces N - 1 (0 = direct light only)
#   film      a box filter one pixel wide, no clamping of samples, no light
#             threshold, no denoising, no adaptive sampling, black world
#   lights    emission on the front (geometric normal) side only, as the
#             project's one-sided area lights; sampled as lights (MIS)
#   colour    linear RGB in, linear EXR out (no view transform)
#   pattern   Blender 3.4's default, progressive multi-jitter, or Sobol-Burley
#             (its enum value "SOBOL"), as the bench's --cycles-pattern says
import json
import math
import resource
import sys
import time

import bpy
from mathutils import Matrix


def cpu_seconds():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def set_if_present(owner, name, value):
    # Cycles' options move between Blender versions; the bench reports the
    # version, and a missing option is left at its default.
    if hasattr(owner, name):
        setattr(owner, name, value)


def make_material(m):
    mat = bpy.data.materials.new(m["name"])
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    if m["type"] == "mirror":
        bsdf = nodes.new("ShaderNodeBsdfGlossy")
        bsdf.distribution = "SHARP"
        bsdf.inputs["Color"].default_value = (*m["reflectance"], 1)
    else:
        bsdf = nodes.new("ShaderNodeBsdfDiffuse")
        bsdf.inputs["Color"].default_value = (*m["albedo"], 1)
        bsdf.inputs["Roughness"].default_value = 0  # Lambert
    shader = bsdf.outputs[0]
    e = m["emission"]
    strength = max(e)
    if strength > 0:
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = (*[c / strength for c in e], 1)
        emission.inputs["Strength"].default_value = strength
        # One-sided: the back face gets the mix's empty second shader (black).
        geometry = nodes.new("ShaderNodeNewGeometry")
        front = nodes.new("ShaderNodeMixShader")
        links.new(geometry.outputs["Backfacing"], front.inputs[0])
        links.new(emission.outputs[0], front.inputs[1])
        add = nodes.new("ShaderNodeAddShader")
        links.new(shader, add.inputs[0])
        links.new(front.outputs[0], add.inputs[1])
        shader = add.outputs[0]
        set_if_present(mat.cycles, "sample_as_light", True)
    links.new(shader, out.inputs["Surface"])
    return mat


def build_scene(desc):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.use_adaptive_sampling = False
    c.sampling_pattern = desc["pattern"]  # "SOBOL" is Sobol-Burley in Blender 3.2 and later
    c.use_denoising = False
    bounces = desc["max_depth"] - 1
    for name in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces",
                 "transparent_max_bounces"):
        set_if_present(c, name, bounces)
    set_if_present(c, "volume_bounces", 0)
    set_if_present(c, "sample_clamp_direct", 0)
    set_if_present(c, "sample_clamp_indirect", 0)
    set_if_present(c, "light_sampling_threshold", 0)
    set_if_present(c, "blur_glossy", 0)
    set_if_present(c, "caustics_reflective", True)
    set_if_present(c, "caustics_refractive", True)
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    r = scene.render
    r.resolution_x, r.resolution_y = desc["width"], desc["height"]
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1
    r.film_transparent = False
    r.threads_mode = "FIXED"
    r.threads = desc["threads"]
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_mode = "RGB"
    r.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0
    scene.view_settings.gamma = 1

    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0, 0, 0, 1)
    background.inputs["Strength"].default_value = 0
    scene.world = world

    materials = [make_material(m) for m in desc["materials"]]
    for i, mesh in enumerate(desc["meshes"]):
        p, t = mesh["positions"], mesh["triangles"]
        verts = [tuple(p[k:k + 3]) for k in range(0, len(p), 3)]
        faces = [tuple(t[k:k + 3]) for k in range(0, len(t), 3)]
        me = bpy.data.meshes.new("mesh%d" % i)
        me.from_pydata(verts, [], faces)
        me.materials.append(materials[mesh["material"]])
        normals = mesh.get("normals")  # per triangle corner, or absent: flat
        if normals:
            me.use_auto_smooth = True
            for poly in me.polygons:
                poly.use_smooth = True
            me.normals_split_custom_set([tuple(normals[k:k + 3]) for k in range(0, len(normals), 3)])
        me.update()
        ob = bpy.data.objects.new("mesh%d" % i, me)
        scene.collection.objects.link(ob)

    cam = desc["camera"]
    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(cam["vfov"])
    data.clip_start = cam["clip_start"]
    data.clip_end = cam["clip_end"]
    ob = bpy.data.objects.new("camera", data)
    # Blender's camera looks down its -z with +y up, as the project's
    # camera space does (scene/camera.h): the columns are right, up, backward.
    rgt, up, back, pos = cam["right"], cam["up"], cam["backward"], cam["position"]
    ob.matrix_world = Matrix([[rgt[k], up[k], back[k], pos[k]] for k in range(3)] + [[0, 0, 0, 1]])
    scene.collection.objects.link(ob)
    scene.camera = ob
    return scene


def render(scene, spp, seed, path):
    scene.cycles.samples = spp
    scene.cycles.seed = seed
    wall, cpu = time.perf_counter(), cpu_seconds()
    bpy.ops.render.render(write_still=False)
    wall, cpu = time.perf_counter() - wall, cpu_seconds() - cpu
    if path:
        bpy.data.images["Render Result"].save_render(path)
    return wall, cpu


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    with open(argv[0]) as f:
        desc = json.load(f)
    prefix, jobs = argv[1], [tuple(int(v) for v in job.split(":")) for job in argv[2:]]
    scene = build_scene(desc)
    render(scene, 1, 0, None)  # warm-up
    for spp, seed in jobs:
        path = "%s_%d_%d.exr" % (prefix, spp, seed)
        wall, cpu = render(scene, spp, seed, path)
        print("CYCLES_RESULT " + json.dumps({
            "spp": spp, "seed": seed, "path": path, "wall_seconds": wall, "cpu_seconds": cpu,
            "blender": bpy.app.version_string,
            "pattern": getattr(scene.cycles, "sampling_pattern", "?"),
            "threads": scene.render.threads}), flush=True)


main()
