"""Imports a glTF written by `lucent export` into Blender (Debian 12's Blender 3.4, headless) and prints what its
importer made of it: objects and meshes by name, each Principled BSDF's transmission, roughness, IOR and base
colour, the volume absorption, the camera and the lights (docs/materials.md, "Whole-scene export"). Not run in CI.

    blender -b --factory-startup --python scripts/check_gltf_in_blender.py -- scene.gltf
"""
import math
import sys

import bpy

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
# import_shading SMOOTH: Debian 12's Blender 3.4 importer guesses flat faces with np.bool, which Debian's numpy 1.24
# removed (the default, NORMALS, fails on every mesh with normals); lucent's meshes are smooth-shaded anyway.
bpy.ops.import_scene.gltf(filepath=path, import_shading="SMOOTH")


def rgb(v):
    return "(" + ", ".join(f"{x:.3f}" for x in v[:3]) + ")"


for obj in sorted(bpy.context.scene.objects, key=lambda o: o.name):
    where = rgb(obj.matrix_world.translation)
    if obj.type == "MESH":
        material = obj.active_material
        print(f"object {obj.name!r} mesh {obj.data.name!r} material {material.name if material else None!r}"
              f" world scale {obj.matrix_world.to_scale()[0]:.4g}")
        if material and material.use_nodes:
            for node in material.node_tree.nodes:
                if node.type == "BSDF_PRINCIPLED":
                    i = node.inputs
                    print(f"  principled: transmission {i['Transmission'].default_value:.3f} roughness "
                          f"{i['Roughness'].default_value:.3f} ior {i['IOR'].default_value:.3f} base colour "
                          f"{rgb(i['Base Color'].default_value)} metallic {i['Metallic'].default_value:.3f}")
                if node.type == "VOLUME_ABSORPTION":
                    print(f"  volume absorption: colour {rgb(node.inputs['Color'].default_value)} density "
                          f"{node.inputs['Density'].default_value:.4g} /m")
    elif obj.type == "CAMERA":
        print(f"camera {obj.name!r} at {where} type {obj.data.type} vertical fov "
              f"{math.degrees(obj.data.angle_y):.2f} deg sensor fit {obj.data.sensor_fit}")
    elif obj.type == "LIGHT":
        print(f"light {obj.name!r} type {obj.data.type} energy {obj.data.energy:.4g} colour {rgb(obj.data.color)} "
              f"at {where} pointing {rgb(obj.matrix_world.to_3x3() @ __import__('mathutils').Vector((0, 0, -1)))}")
    else:
        print(f"{obj.type.lower()} {obj.name!r} at {where}")
