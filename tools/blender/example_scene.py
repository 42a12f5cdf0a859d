# example_scene.py: builds a small Blender scene (a 12 mm sphere with a Principled subsurface material on a grey
# floor, a sun, a point light, a camera), exports it with export_lucent.py, and optionally renders it with Cycles
# (linear EXR) to compare with lucent's reference of the exported scene (docs/blender.md).
#
#   blender -b --factory-startup --python tools/blender/example_scene.py -- out/example.json [cycles.exr [spp]]
#
# The material and light are set by the constants below. Environment: LUCENT_EXAMPLE_SPHERE_ONLY=1 builds the
# sphere alone (no floor, no point light), the comparison setup of docs/materials.md; LUCENT_EXAMPLE_SEGMENTS sets
# the sphere's segments (default 32; rings are half as many).
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import export_lucent  # noqa: E402

SPHERE_RADIUS_M = 0.006
SUBSURFACE = {"Base Color": (0.8, 0.8, 0.8, 1.0), "Subsurface": 1.0,
              "Subsurface Radius": (0.003, 0.0015, 0.0008), "Subsurface Color": (0.85, 0.6, 0.4, 1.0),
              "Subsurface IOR": 1.4, "Subsurface Anisotropy": 0.0, "Specular": 0.0}
SUN_STRENGTH = 3.0  # W/m^2


def clear():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)


def subsurface_material():
    material = bpy.data.materials.new("skin")
    material.use_nodes = True
    node = next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    node.subsurface_method = "RANDOM_WALK"
    for name, value in SUBSURFACE.items():
        node.inputs[name].default_value = value
    return material


def build(sphere_only):
    clear()
    scene = bpy.context.scene
    scene.unit_settings.scale_length = 1.0
    segments = int(os.environ.get("LUCENT_EXAMPLE_SEGMENTS", "32"))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=SPHERE_RADIUS_M, segments=segments, ring_count=segments // 2,
                                         location=(0, 0, 0))
    sphere = bpy.context.active_object
    sphere.name = "sphere"
    bpy.ops.object.shade_smooth()
    sphere.data.materials.append(subsurface_material())
    if not sphere_only:
        bpy.ops.mesh.primitive_plane_add(size=0.2, location=(0, 0, -SPHERE_RADIUS_M))
        floor = bpy.context.active_object
        floor.name = "floor"
        grey = bpy.data.materials.new("floor")
        grey.use_nodes = True
        next(n for n in grey.node_tree.nodes if n.type == "BSDF_PRINCIPLED").inputs["Base Color"].default_value = (
            0.5, 0.5, 0.5, 1.0)
        floor.data.materials.append(grey)
        bpy.ops.object.light_add(type="POINT", location=(0.03, -0.03, 0.03))
        bpy.context.active_object.data.energy = 2.0  # W
        bpy.context.active_object.data.shadow_soft_size = 0.0  # a point, as lucent's (Blender's default is 0.25 m)
    bpy.ops.object.light_add(type="SUN", rotation=(math.radians(30), 0, math.radians(-20)))
    bpy.context.active_object.data.energy = SUN_STRENGTH
    bpy.context.active_object.data.angle = 0.0
    bpy.ops.object.camera_add(location=(0, -0.05, 0.0), rotation=(math.radians(90), 0, 0))
    scene.camera = bpy.context.active_object
    scene.camera.data.lens = 50.0
    scene.camera.data.clip_start = 0.001  # m: the camera is 5 cm from the sphere
    scene.render.resolution_x = scene.render.resolution_y = 128
    scene.render.resolution_percentage = 100
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    scene.world = world


def render_cycles(path, spp):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = spp
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 1024
    scene.cycles.transparent_max_bounces = 1024
    scene.render.filter_size = 0.01  # pixel centres, as lucent's reference without --jitter
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    arguments = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if not 1 <= len(arguments) <= 3:
        print("usage: blender -b --factory-startup --python example_scene.py -- out.json [cycles.exr [spp]]",
              file=sys.stderr)
        sys.exit(2)
    build(os.environ.get("LUCENT_EXAMPLE_SPHERE_ONLY") == "1")
    export_lucent.export_scene(arguments[0])
    print(f"example_scene: wrote {arguments[0]}")
    if len(arguments) >= 2:
        render_cycles(os.path.abspath(arguments[1]), int(arguments[2]) if len(arguments) == 3 else 64)
