# cycles_crosscheck.py: renders a lucent scene file with Blender Cycles (an independent path tracer) and compares
# lucent references with Cycles renders (docs/references.md, "Cross-check with Blender Cycles"). Blender is a
# cross-check tool, not a lucent dependency (Debian: apt-get install blender python3-numpy).
#
#   blender -b --python bench/cycles_crosscheck.py -- render SCENE.json OUT.exr [--spp N] [--seed S] [--threads T]
#           [--bounces B] [--terminator-offset F] [--width W --height H] [--sampling-pattern P]
#   blender -b --python bench/cycles_crosscheck.py -- compare LUCENT.exr [LUCENT2.exr ...] CYCLES_SEED1.exr
#           CYCLES_SEED2.exr [--png SIDE_BY_SIDE.png [--zoom Z]] [--json OUT.json]
#
# render: the same scene as `lucent reference`: the scene file's mesh (OBJ read here, no axis conversion: lucent's
# +y up stays +y, the camera is placed by its matrix) or box under the object's translate / rotate_deg / scale, with
# assimp's smooth normals (lucent loads meshes through assimp with aiProcess_GenSmoothNormals: the normalized mean of
# the unit face normals around a position) as custom split normals; the look-at pinhole camera (vertical field of
# view, square pixels); directional lights as Cycles suns of angle 0 with Strength = lucent's irradiance (W/m^2 on a
# surface facing the light; a Cycles sun of Strength E gives a white Lambertian surface facing it radiance E / pi);
# opaque objects as a Diffuse BSDF (roughness 0: Lambert) of the albedo; translucent objects with eta = 1 as an
# index-matched homogeneous medium (no surface shader; Volume Scatter of density sigma_s with Henyey-Greenstein g
# plus Volume Absorption of density sigma_a, both in lucent's mm^-1 times scale_mm, i.e. per scene unit = per
# Blender unit). Cycles CPU path tracing, no denoiser, no adaptive sampling, no clamping, no light threshold, a box
# pixel filter 1 pixel wide (lucent --jitter averages uniformly over the pixel), the background as a world colour
# of strength 0 behind the scene (lucent: camera rays that miss see the background, which lights nothing; the
# scenes used here have a black background), linear 32-bit EXR.
#
# compare: each lucent render (its mean image and its standard-error image <stem>.stderr.exr; several, e.g. with
# sphere jumps on and off, against the same Cycles pair) against the mean of two Cycles renders with different
# seeds; the Cycles noise of that mean is estimated from their difference (var(mean of 2) = (C1 - C2)^2 / 4 per
# pixel, averaged over pixels). On the mean of the RGB channels, prints per lucent render the mean ratio lucent /
# Cycles with its standard error, the image-mean difference with its combined standard error (the "same mean
# within noise" check: |difference| <= 3 standard errors), the RMSE, the combined noise sqrt(<SE_l^2> +
# <(C1 - C2)^2 / 4>) and RMSE / noise (1 when the two agree within their noise); and each renderer's efficiency
# 1 / (image-mean per-pixel variance of the mean x seconds) from the renders' metadata (<stem>.meta.json: lucent's
# seconds, samples, sphere_jumps and steps_per_path; Cycles' wall time of the render call, scene setup and BVH
# build included, Blender's start-up and the OBJ reading not), with the ratios lucent / Cycles and between the
# lucent renders.
import json
import math
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Matrix, Vector


def die(message):
    print("cycles_crosscheck: " + message, file=sys.stderr)
    sys.exit(2)


def args_after_dashes():
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


def option(args, name, default, kind=str):
    if name in args:
        i = args.index(name)
        value = kind(args[i + 1])
        del args[i:i + 2]
        return value
    return default


# ---------------------------------------------------------------------------------------------------------- render

def read_obj(path):
    """Positions and triangles (polygons fanned, as aiProcess_Triangulate does for convex faces)."""
    positions, triangles = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                positions.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                idx = []
                for token in line.split()[1:]:
                    i = int(token.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(positions) + i)
                for k in range(1, len(idx) - 1):
                    triangles.append([idx[0], idx[k], idx[k + 1]])
    return np.array(positions, dtype=np.float64), np.array(triangles, dtype=np.int64)


def box_mesh(size):
    h = 0.5 * np.array(size, dtype=np.float64)
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=np.float64) * h
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = []
    for a, b, c, d in quads:
        tris += [[a, b, c], [a, c, d]]
    positions, triangles = corners, np.array(tris, dtype=np.int64)
    # Outward winding (counter-clockwise seen from outside).
    centre = positions.mean(axis=0)
    for t in triangles:
        p = positions[t]
        if np.dot(np.cross(p[1] - p[0], p[2] - p[0]), p.mean(axis=0) - centre) < 0:
            t[1], t[2] = t[2], t[1]
    return positions, triangles


def smooth_normals(positions, triangles):
    """assimp's GenSmoothNormals after JoinIdenticalVertices: per position, the normalized sum of unit face normals."""
    p = positions[triangles]
    face = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    length = np.linalg.norm(face, axis=1, keepdims=True)
    face = np.where(length > 0, face / np.maximum(length, 1e-300), 0.0)
    # Group vertices by exact position (the OBJ may repeat positions under different indices).
    _, group = np.unique(positions, axis=0, return_inverse=True)
    group = group.reshape(-1)
    sums = np.zeros((group.max() + 1, 3))
    for k in range(3):
        np.add.at(sums, group[triangles[:, k]], face)
    n = sums[group]
    return n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)


def world_from_object(obj):
    t = obj.get("translate", [0, 0, 0])
    r = [math.radians(a) for a in obj.get("rotate_deg", [0, 0, 0])]
    s = obj.get("scale", 1.0)
    return (Matrix.Translation(Vector(t)) @ Matrix.Rotation(r[2], 4, "Z") @ Matrix.Rotation(r[1], 4, "Y") @
            Matrix.Rotation(r[0], 4, "X") @ Matrix.Scale(s, 4))


def vec3(value, default):
    if value is None:
        return list(default)
    return [float(value)] * 3 if isinstance(value, (int, float)) else [float(x) for x in value]


def colour_and_strength(rgb):
    peak = max(rgb)
    return ([c / peak for c in rgb] if peak > 0 else [0.0, 0.0, 0.0]), peak


def diffuse_material(name, albedo):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*albedo, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.0
    links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    return mat


def medium_material(name, sigma_a, sigma_s, g):
    """Index-matched homogeneous medium, coefficients per Blender unit. Cycles: Volume Scatter adds sigma_s =
    colour x density (HG with anisotropy g), Volume Absorption adds sigma_a = (1 - colour) x density."""
    if len(set(g)) != 1:
        die("Cycles has one anisotropy per Volume Scatter node: give a grey g")
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.cycles.homogeneous_volume = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    scatter = nodes.new("ShaderNodeVolumeScatter")
    colour, density = colour_and_strength(sigma_s)
    scatter.inputs["Color"].default_value = (*colour, 1.0)
    scatter.inputs["Density"].default_value = density
    scatter.inputs["Anisotropy"].default_value = g[0]
    absorb = nodes.new("ShaderNodeVolumeAbsorption")
    peak = max(sigma_a)
    absorb.inputs["Color"].default_value = (*[1.0 - a / peak if peak > 0 else 1.0 for a in sigma_a], 1.0)
    absorb.inputs["Density"].default_value = peak
    add = nodes.new("ShaderNodeAddShader")
    links.new(scatter.outputs[0], add.inputs[0])
    links.new(absorb.outputs[0], add.inputs[1])
    links.new(add.outputs[0], out.inputs["Volume"])  # no surface shader: the mesh only bounds the volume
    return mat


def build_scene(scene_path, width, height, terminator_offset):
    with open(scene_path) as f:
        desc = json.load(f)
    base = os.path.dirname(os.path.abspath(scene_path))
    scale_mm = float(desc.get("scale_mm", 1.0))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    render = desc.get("render", {})
    scene.render.resolution_x = width or int(render.get("width", 640))
    scene.render.resolution_y = height or int(render.get("height", 480))
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0

    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (*vec3(render.get("background"), [0, 0, 0]), 1.0)
    bg.inputs["Strength"].default_value = 0.0
    scene.world = world
    if any(vec3(render.get("background"), [0, 0, 0])):
        print("cycles_crosscheck: note: the background is rendered black (use a black background to compare)")

    cam_desc = desc.get("camera", {})
    eye = Vector(cam_desc.get("eye", [0, 0, 5]))
    target = Vector(cam_desc.get("target", [0, 0, 0]))
    up = Vector(cam_desc.get("up", [0, 1, 0])).normalized()
    forward = (target - eye).normalized()
    right = forward.cross(up).normalized()
    true_up = right.cross(forward)
    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = "PERSP"
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(float(cam_desc.get("fov_y_deg", 45)))
    cam_data.shift_x = cam_data.shift_y = 0.0
    cam_data.clip_start, cam_data.clip_end = 1e-4, 1e6
    cam = bpy.data.objects.new("camera", cam_data)
    m = Matrix.Identity(4)
    for row in range(3):  # Blender cameras look along local -z with local +y up
        m[row][0], m[row][1], m[row][2], m[row][3] = right[row], true_up[row], -forward[row], eye[row]
    cam.matrix_world = m
    scene.collection.objects.link(cam)
    scene.camera = cam

    for i, light in enumerate(desc.get("lights", [])):
        if light.get("type", "directional") != "directional":
            die("only directional lights are converted")
        colour, strength = colour_and_strength(vec3(light.get("radiance"), [1, 1, 1]))
        sun = bpy.data.lights.new(f"sun{i}", "SUN")
        sun.energy = strength  # W/m^2, irradiance on a surface facing the light
        sun.color = colour
        sun.angle = 0.0  # a delta light, like lucent's
        sun.cycles.cast_shadow = True
        obj = bpy.data.objects.new(f"sun{i}", sun)
        direction = Vector(light["direction"]).normalized()  # the way the light travels: the sun's local -z
        obj.rotation_mode = "QUATERNION"
        obj.rotation_quaternion = Vector((0, 0, -1)).rotation_difference(direction)
        scene.collection.objects.link(obj)

    for i, o in enumerate(desc.get("objects", [])):
        if "mesh" in o:
            path = o["mesh"] if os.path.isabs(o["mesh"]) else os.path.join(base, o["mesh"])
            positions, triangles = read_obj(path)
        elif o.get("shape") == "box":
            positions, triangles = box_mesh(o["size"])
        else:
            die(f"object {i}: only meshes (OBJ) and boxes are converted")
        xf = np.array(world_from_object(o))
        world = positions @ xf[:3, :3].T + xf[:3, 3]
        normals = smooth_normals(world, triangles) if "mesh" in o else None
        mesh = bpy.data.meshes.new(o.get("name", f"object{i}"))
        mesh.from_pydata(world.tolist(), [], triangles.tolist())
        mesh.update()
        if normals is not None:
            mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
            mesh.use_auto_smooth = True
            mesh.normals_split_custom_set_from_vertices(normals.tolist())
        obj = bpy.data.objects.new(mesh.name, mesh)
        # Cycles' default moves shadow rays off smooth-shaded low-poly surfaces (geometry offset 0.1): lucent
        # starts them at the hit point.
        obj.cycles.shadow_terminator_geometry_offset = terminator_offset
        obj.cycles.shadow_terminator_offset = 0.0
        scene.collection.objects.link(obj)
        if "material" in o:
            mat_desc = o["material"]
            if isinstance(mat_desc, str) or "preset" in mat_desc:
                die(f"object {i}: give sigma_a, sigma_s and g explicitly (presets are not converted)")
            if abs(float(mat_desc.get("eta", 1.3)) - 1.0) > 1e-6:
                die(f"object {i}: only index-matched media (eta 1) are converted: a delta light behind a refracting "
                    "boundary is a caustic that Cycles' next-event estimation cannot reach")
            sigma_a = [x * scale_mm for x in vec3(mat_desc["sigma_a"], None)]
            sigma_s = [x * scale_mm for x in vec3(mat_desc["sigma_s"], None)]
            g = vec3(mat_desc.get("g", 0.0), None)
            obj.data.materials.append(medium_material(f"medium{i}", sigma_a, sigma_s, g))
        else:
            obj.data.materials.append(diffuse_material(f"diffuse{i}", vec3(o.get("albedo"), [0.8, 0.8, 0.8])))
    return scene


def configure_cycles(scene, spp, seed, threads, bounces, pattern):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    if pattern:
        c.sampling_pattern = pattern
    c.device = "CPU"
    c.feature_set = "SUPPORTED"
    c.progressive = "PATH"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = seed
    c.use_animated_seed = False
    c.max_bounces = bounces
    c.diffuse_bounces = bounces
    c.glossy_bounces = bounces
    c.transmission_bounces = bounces
    c.volume_bounces = bounces
    c.transparent_max_bounces = bounces
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.blur_glossy = 0.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    scene.render.film_transparent = False
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    s = scene.render.image_settings
    s.file_format = "OPEN_EXR"
    s.color_depth = "32"
    s.color_mode = "RGBA"
    s.exr_codec = "ZIP"


def command_render(args):
    spp = option(args, "--spp", 64, int)
    seed = option(args, "--seed", 1, int)
    threads = option(args, "--threads", 2, int)
    bounces = option(args, "--bounces", 1024, int)
    width = option(args, "--width", 0, int)
    height = option(args, "--height", 0, int)
    terminator_offset = option(args, "--terminator-offset", 0.0, float)
    pattern = option(args, "--sampling-pattern", None)
    if len(args) != 2:
        die("render SCENE.json OUT.exr [--spp N] [--seed S] [--threads T] [--bounces B] [--terminator-offset F] "
            "[--width W --height H] [--sampling-pattern SOBOL|PROGRESSIVE_MULTI_JITTER]")
    scene_path, out = args
    scene = build_scene(scene_path, width, height, terminator_offset)
    configure_cycles(scene, spp, seed, threads, bounces, pattern)
    scene.render.filepath = os.path.abspath(out)
    start = time.time()
    bpy.ops.render.render(write_still=True)
    seconds = time.time() - start
    meta = {"renderer": "cycles", "blender": bpy.app.version_string, "samples": spp, "seed": seed,
            "threads": threads, "bounces": bounces, "terminator_offset": terminator_offset, "seconds": seconds,
            "sampling_pattern": scene.cycles.sampling_pattern,
            "width": scene.render.resolution_x, "height": scene.render.resolution_y}
    with open(os.path.splitext(out)[0] + ".meta.json", "w") as f:
        json.dump(meta, f, indent=1)
    print(f"cycles_crosscheck: {out}: {spp} spp, seed {seed}, {threads} threads, {bounces} bounces, {seconds:.2f} s")


# --------------------------------------------------------------------------------------------------------- compare

def read_exr(path):
    """RGB as float64, rows top to bottom (Blender stores them bottom up)."""
    if not os.path.exists(path):
        die(f"{path}: no such file")
    img = bpy.data.images.load(os.path.abspath(path), check_existing=False)
    img.colorspace_settings.name = "Non-Color"
    w, h = img.size
    px = np.empty(w * h * 4, dtype=np.float32)
    img.pixels.foreach_get(px)
    bpy.data.images.remove(img)
    return px.reshape(h, w, 4)[::-1, :, :3].astype(np.float64)


def write_png(path, rgb):
    h, w, _ = rgb.shape
    img = bpy.data.images.new("png", w, h, alpha=False, float_buffer=False)
    rgba = np.concatenate([np.clip(rgb, 0, 1), np.ones((h, w, 1))], axis=2)[::-1].astype(np.float32)
    img.pixels.foreach_set(rgba.reshape(-1))
    img.filepath_raw = os.path.abspath(path)
    img.file_format = "PNG"
    img.save()
    bpy.data.images.remove(img)


def read_meta(exr_path):
    with open(os.path.splitext(exr_path)[0] + ".meta.json") as f:
        return json.load(f)


def compare_one(lucent_path, c, vc, sum_c, grey):
    """One lucent render against the mean of the Cycles renders: the statistics of the docstring above."""
    L = read_exr(lucent_path)
    SE = read_exr(os.path.splitext(lucent_path)[0] + ".stderr.exr")
    if not (L.shape == SE.shape and L.shape[:2] == c.shape):
        die(f"{lucent_path}: image size {L.shape} (standard error {SE.shape}) differs from Cycles' {c.shape}")
    l, se = grey(L), grey(SE)
    vl = se ** 2
    n = l.size
    sum_l = l.sum()
    ratio = sum_l / sum_c
    se_ratio = ratio * math.sqrt(vl.sum() / sum_l ** 2 + vc.sum() / sum_c ** 2)
    # Same mean within noise: the image means' difference against its standard error, both images' pixel
    # variances of the mean added (pixels taken as independent).
    diff = (sum_l - sum_c) / n
    diff_se = math.sqrt(vl.sum() + vc.sum()) / n
    rmse = math.sqrt(((l - c) ** 2).mean())
    noise = math.sqrt(vl.mean() + vc.mean())
    r = {"lucent": lucent_path, "mean_lucent": float(sum_l / n), "ratio": float(ratio), "ratio_se": se_ratio,
         "mean_difference": float(diff), "mean_difference_se": diff_se,
         "mean_difference_over_se": float(diff / diff_se),
         "same_mean_within_3se": bool(abs(diff) <= 3.0 * diff_se),
         "rmse": rmse, "noise_lucent": math.sqrt(vl.mean()), "noise_combined": noise, "rmse_over_noise": rmse / noise,
         "variance_of_mean_lucent": float(vl.mean())}
    try:
        meta = read_meta(lucent_path)
        r.update({"lucent_seconds": meta["seconds"], "lucent_spp": meta["samples_per_pixel"],
                  "sphere_jumps": meta.get("sphere_jumps"), "steps_per_path": meta.get("steps_per_path"),
                  "camera_paths_per_second": meta.get("camera_paths_per_second"),
                  "efficiency_lucent": float(1.0 / (vl.mean() * meta["seconds"]))})
    except (OSError, KeyError) as e:
        print(f"cycles_crosscheck: {lucent_path}: no efficiency ({e})")
    return r, L, vl


def command_compare(args):
    png = option(args, "--png", None)
    zoom = option(args, "--zoom", 1, int)
    json_out = option(args, "--json", None)
    if len(args) < 3:
        die("compare LUCENT.exr [LUCENT2.exr ...] CYCLES1.exr CYCLES2.exr [--png OUT.png] [--json OUT.json]")
    lucent_paths, (c1_path, c2_path) = args[:-2], args[-2:]
    C1, C2 = read_exr(c1_path), read_exr(c2_path)
    if C1.shape != C2.shape:
        die(f"Cycles image sizes differ: {C1.shape} {C2.shape}")
    C = 0.5 * (C1 + C2)
    # The statistics on the mean of the three channels: lucent's bands share their paths (hero band), so in a
    # grey scene the channels are one number three times, not three independent estimates.
    grey = lambda x: x.mean(axis=2)
    c, c1, c2 = grey(C), grey(C1), grey(C2)
    vc = 0.25 * (c1 - c2) ** 2
    sum_c = c.sum()
    result = {"cycles": [c1_path, c2_path], "pixels": c.size, "mean_cycles": float(sum_c / c.size),
              "noise_cycles": math.sqrt(vc.mean()), "variance_of_mean_cycles": float(vc.mean()),
              "cycles_seed_ratio": float(c1.sum() / c2.sum())}
    # Efficiency 1 / (variance x time): the image-mean per-pixel variance of the mean of a render and its seconds.
    # lucent: its standard-error image squared and its metadata's seconds. Cycles: the mean of the two seeds, of
    # variance <(C1 - C2)^2> / 4, over the two renders' seconds added (the same as one render's variance
    # <(C1 - C2)^2> / 2 times its mean seconds).
    try:
        metas_c = [read_meta(p) for p in (c1_path, c2_path)]
        t_c = metas_c[0]["seconds"] + metas_c[1]["seconds"]
        result.update({"cycles_seconds": t_c, "cycles_spp": metas_c[0]["samples"] + metas_c[1]["samples"],
                       "cycles_threads": metas_c[0]["threads"], "cycles_bounces": metas_c[0]["bounces"],
                       "efficiency_cycles": float(1.0 / (vc.mean() * t_c))})
    except (OSError, KeyError) as e:
        print(f"cycles_crosscheck: no Cycles efficiency ({e})")
    rows = []
    result["lucent"] = []
    for path in lucent_paths:
        r, L, vl = compare_one(path, c, vc, sum_c, grey)
        if "efficiency_lucent" in r and "efficiency_cycles" in result:
            r["efficiency_ratio_lucent_over_cycles"] = r["efficiency_lucent"] / result["efficiency_cycles"]
        result["lucent"].append(r)
        rows.append((L, vl))
    for a in range(len(result["lucent"])):
        for b in range(a + 1, len(result["lucent"])):
            ra, rb = result["lucent"][a], result["lucent"][b]
            if "efficiency_lucent" in ra and "efficiency_lucent" in rb:
                result.setdefault("efficiency_ratios_between_lucent_renders", []).append(
                    {"numerator": ra["lucent"], "denominator": rb["lucent"],
                     "ratio": ra["efficiency_lucent"] / rb["efficiency_lucent"]})
    print(json.dumps(result, indent=1))
    if json_out:
        with open(json_out, "w") as f:
            json.dump(result, f, indent=1)
    if png:
        # Per lucent render, one row: lucent | Cycles | (lucent - Cycles) / combined noise per pixel, smoothed over
        # 3x3 pixels (red: lucent brighter, blue: darker; full scale +-3 sigma)
        scale = np.percentile(np.concatenate([C] + [L for L, _ in rows]), 99.5) or 1.0
        tone = lambda x: (np.clip(x / scale, 0, 1)) ** (1 / 2.2)
        def blur(x):
            p = np.pad(x, 1, mode="edge")
            return sum(p[dy:dy + x.shape[0], dx:dx + x.shape[1]] for dy in range(3) for dx in range(3)) / 9.0
        lines = []
        for L, vl in rows:
            d = blur(grey(L) - c)
            s = np.sqrt(blur(vl + vc) / 9.0)
            z = np.where(s > 0, d / np.maximum(s, 1e-30), 0.0) / 3.0
            diff = np.stack([np.clip(z, 0, 1), np.zeros_like(z), np.clip(-z, 0, 1)], axis=2)
            gap = np.ones((L.shape[0], 2, 3))
            if lines:
                lines.append(np.ones((2, 3 * L.shape[1] + 4, 3)))
            lines.append(np.concatenate([tone(L), gap, tone(C), gap, diff], axis=1))
        side = np.concatenate(lines, axis=0)
        write_png(png, np.repeat(np.repeat(side, zoom, axis=0), zoom, axis=1))
        print(f"cycles_crosscheck: wrote {png}")


def main():
    args = args_after_dashes()
    if not args:
        die("usage: blender -b --python bench/cycles_crosscheck.py -- render|compare ...")
    command, rest = args[0], args[1:]
    if command == "render":
        command_render(rest)
    elif command == "compare":
        command_compare(rest)
    else:
        die(f"unknown command {command}")


main()
