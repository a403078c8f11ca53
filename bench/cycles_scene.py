"""Builds and renders a Tessera scene in Blender Cycles; run by bench/cycles_check.py as

    blender --background --factory-startup --python bench/cycles_scene.py -- MANIFEST.json

inside Blender's own Python (bpy, numpy). MANIFEST.json, written by cycles_check.py:
camera {origin, target, up, vfov}, width, height, shapes [{name, file (.npz with P
(n, 3, 3), T (n, 3, 2) and optionally N (n, 3, 3), world space, float32), kd, ke,
texture (linear RGB EXR, Kd applied, or null)}], medium (null or {sigma_a, sigma_s, g,
box: null or {min, max}}), render {spp, seeds, max_bounces, threads}, out_dir. Writes
out_dir/cycles_<k>.exr (linear float RGB, one per seed) and out_dir/cycles_times.json.

Conventions (each mirrors Tessera, see bench/README.md "Blender Cycles check"):
- Surfaces: Diffuse BSDF (roughness 0: Lambertian) with colour Kd or the texture,
  Cycles' BSDFs reflect on both sides like Tessera's.
- Emission: an Emission closure of colour Ke, strength 1 − Backfacing, added to the
  diffuse: radiance Ke (W/(sr·m²); Cycles' mesh emission of strength 1 is radiance 1)
  on the front side of cross(p1 − p0, p2 − p0) only, Tessera's one-sided lights.
- Medium: Volume Scatter (colour sigma_s / d_s, density d_s = max sigma_s, anisotropy
  g: Henyey–Greenstein) + Volume Absorption (colour 1 − sigma_a / d_a, density d_a =
  max sigma_a), since Cycles' scatter closure has sigma_s = colour · density and its
  absorption closure sigma_a = (1 − colour) · density (intern/cycles/kernel/svm/closure.h);
  homogeneous. With a box: on a closed cube mesh with outward faces and no surface
  shader (the cube is already shrunk by cycles_check.py); without: the world volume.
"""
import json
import math
import sys
import time
from pathlib import Path

import bpy
import mathutils
import numpy as np


def build_mesh(name, P, T, N):
    n = P.shape[0]
    me = bpy.data.meshes.new(name)
    me.vertices.add(3 * n)
    me.vertices.foreach_set("co", P.reshape(-1).astype(np.float32))
    me.loops.add(3 * n)
    me.loops.foreach_set("vertex_index", np.arange(3 * n, dtype=np.int32))
    me.polygons.add(n)
    me.polygons.foreach_set("loop_start", np.arange(0, 3 * n, 3, dtype=np.int32))
    me.polygons.foreach_set("loop_total", np.full(n, 3, dtype=np.int32))
    uv = me.uv_layers.new(name="UVMap")
    uv.data.foreach_set("uv", T.reshape(-1).astype(np.float32))  # Blender: v = 0 at the bottom, as OBJ
    me.update(calc_edges=True)
    if N is not None:
        me.polygons.foreach_set("use_smooth", np.ones(n, dtype=bool))
        me.use_auto_smooth = True
        me.auto_smooth_angle = math.pi
        me.normals_split_custom_set(N.reshape(-1, 3).tolist())
    return me


def surface_material(name, kd, ke, texture):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    shader = None
    if any(c > 0 for c in kd) or texture:
        diff = nodes.new("ShaderNodeBsdfDiffuse")
        diff.inputs["Color"].default_value = (*kd, 1.0)
        diff.inputs["Roughness"].default_value = 0.0
        if texture:
            tex = nodes.new("ShaderNodeTexImage")
            img = bpy.data.images.load(texture)
            img.colorspace_settings.name = "Non-Color"  # already linear, Kd applied
            tex.image = img
            tex.interpolation = "Linear"  # bilinear, like Tessera's level 0
            tex.extension = "REPEAT"
            links.new(tex.outputs["Color"], diff.inputs["Color"])
        shader = diff.outputs["BSDF"]
    if any(c > 0 for c in ke):
        em = nodes.new("ShaderNodeEmission")
        em.inputs["Color"].default_value = (*ke, 1.0)
        geo = nodes.new("ShaderNodeNewGeometry")
        front = nodes.new("ShaderNodeMath")
        front.operation = "SUBTRACT"
        front.inputs[0].default_value = 1.0
        links.new(geo.outputs["Backfacing"], front.inputs[1])
        links.new(front.outputs["Value"], em.inputs["Strength"])
        if shader is None:
            shader = em.outputs["Emission"]
        else:
            add = nodes.new("ShaderNodeAddShader")
            links.new(shader, add.inputs[0])
            links.new(em.outputs["Emission"], add.inputs[1])
            shader = add.outputs["Shader"]
    if shader is not None:
        links.new(shader, out.inputs["Surface"])
    else:  # black: a holdout-free zero BSDF
        diff = nodes.new("ShaderNodeBsdfDiffuse")
        diff.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        links.new(diff.outputs["BSDF"], out.inputs["Surface"])
    return mat


def volume_shader(tree, medium):
    """Volume Scatter + Volume Absorption nodes for sigma_s, sigma_a, g; returns the output socket."""
    nodes, links = tree.nodes, tree.links
    ss = [float(x) for x in medium.get("sigma_s", [0, 0, 0])]
    sa = [float(x) for x in medium.get("sigma_a", [0, 0, 0])]
    ds, da = max(ss), max(sa)
    sc = nodes.new("ShaderNodeVolumeScatter")
    sc.inputs["Color"].default_value = (*[s / ds if ds > 0 else 0.0 for s in ss], 1.0)
    sc.inputs["Density"].default_value = ds
    sc.inputs["Anisotropy"].default_value = float(medium.get("g", 0.0))
    ab = nodes.new("ShaderNodeVolumeAbsorption")
    ab.inputs["Color"].default_value = (*[1.0 - a / da if da > 0 else 1.0 for a in sa], 1.0)
    ab.inputs["Density"].default_value = da
    add = nodes.new("ShaderNodeAddShader")
    links.new(sc.outputs["Volume"], add.inputs[0])
    links.new(ab.outputs["Volume"], add.inputs[1])
    return add.outputs["Shader"]


def box_mesh(lo, hi):
    """Closed cube, faces counter-clockwise seen from outside (outward normals: Cycles
    enters the volume through front faces)."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (3, 7, 6, 2), (0, 4, 7, 3), (1, 2, 6, 5)]
    me = bpy.data.meshes.new("medium_box")
    me.from_pydata(v, [], faces)
    me.update(calc_edges=True)
    return me


def setup_camera(scene, cam, width, height):
    o, t, up = (np.asarray(cam[k], dtype=np.float64) for k in ("origin", "target", "up"))
    f = (t - o) / np.linalg.norm(t - o)
    r = np.cross(f, up)
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    data = bpy.data.cameras.new("camera")
    data.type = "PERSP"
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(float(cam["vfov"]))
    data.clip_start = 1e-5
    data.clip_end = 1e7
    obj = bpy.data.objects.new("camera", data)
    M = np.eye(4)
    M[:3, 0], M[:3, 1], M[:3, 2], M[:3, 3] = r, u, -f, o  # Blender cameras look down local -Z
    obj.matrix_world = mathutils.Matrix(M.tolist())  # rows
    scene.collection.objects.link(obj)
    scene.camera = obj


def settings(scene, m):
    r = m["render"]
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device = "CPU"
    cy.samples = int(r["spp"])
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.light_sampling_threshold = 0.0  # no probabilistic dropping of weak light samples
    cy.blur_glossy = 0.0
    b = int(r["max_bounces"])
    cy.max_bounces = b
    cy.diffuse_bounces = b
    cy.glossy_bounces = b
    cy.transmission_bounces = b
    cy.volume_bounces = b  # default 0 would be single scattering
    cy.transparent_max_bounces = b  # medium-box crossings count as transparent bounces
    cy.min_light_bounces = 0
    cy.min_transparent_bounces = 0
    cy.caustics_reflective = True
    cy.caustics_refractive = True
    cy.pixel_filter_type = "BOX"  # Tessera: uniform jitter in the pixel, a one-pixel box
    cy.filter_width = 1.0
    cy.use_animated_seed = False
    scene.render.resolution_x = int(m["width"])
    scene.render.resolution_y = int(m["height"])
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
    scene.render.film_transparent = False
    scene.render.use_persistent_data = True
    scene.render.threads_mode = "FIXED"
    scene.render.threads = int(r["threads"])
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    im = scene.render.image_settings
    im.file_format = "OPEN_EXR"
    im.color_mode = "RGB"
    im.color_depth = "32"
    im.exr_codec = "ZIP"


def main():
    manifest = Path(sys.argv[sys.argv.index("--") + 1])
    m = json.loads(manifest.read_text())
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    settings(scene, m)
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    wn = world.node_tree.nodes
    wn.clear()
    wout = wn.new("ShaderNodeOutputWorld")
    bg = wn.new("ShaderNodeBackground")
    bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bg.inputs["Strength"].default_value = 0.0
    world.node_tree.links.new(bg.outputs["Background"], wout.inputs["Surface"])
    scene.world = world
    setup_camera(scene, m["camera"], m["width"], m["height"])
    for s in m["shapes"]:
        d = np.load(s["file"])
        me = build_mesh(s["name"], d["P"], d["T"], d["N"] if "N" in d else None)
        me.materials.append(surface_material(s["name"], s["kd"], s["ke"], s["texture"]))
        scene.collection.objects.link(bpy.data.objects.new(s["name"], me))
    med = m.get("medium")
    if med is not None:
        if med.get("box") is None:
            world.node_tree.links.new(volume_shader(world.node_tree, med), wout.inputs["Volume"])
            world.cycles.homogeneous_volume = True
        else:
            mat = bpy.data.materials.new("medium")
            mat.use_nodes = True
            mat.node_tree.nodes.clear()
            out = mat.node_tree.nodes.new("ShaderNodeOutputMaterial")
            mat.node_tree.links.new(volume_shader(mat.node_tree, med), out.inputs["Volume"])
            mat.cycles.homogeneous_volume = True
            me = box_mesh(med["box"]["min"], med["box"]["max"])
            me.materials.append(mat)
            scene.collection.objects.link(bpy.data.objects.new("medium_box", me))
    out_dir = Path(m["out_dir"])
    times = []
    for k, seed in enumerate(m["render"]["seeds"]):
        scene.cycles.seed = int(seed)
        scene.render.filepath = str(out_dir / f"cycles_{k}.exr")
        t0 = time.time()
        bpy.ops.render.render(write_still=True)
        times.append(time.time() - t0)
        print(f"cycles_scene: batch {k} seed {seed}: {times[-1]:.1f} s", flush=True)
    (out_dir / "cycles_times.json").write_text(json.dumps({"seconds": times, "version": bpy.app.version_string}))


main()
