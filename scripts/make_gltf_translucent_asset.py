"""Makes tests/data/gltf/translucent_textured.glb with Blender's own glTF exporter (Debian 12's Blender 3.4):

    blender -b --factory-startup --python scripts/make_gltf_translucent_asset.py -- tests/data/gltf/translucent_textured.glb

A 4 cm ico sphere (metres, as Blender works: a scene reading it wants "scale_mm": 1000) with a 16 x 16 base colour
texture and a glass-style volume: Principled BSDF transmission 1, IOR 1.4, roughness 0.2; a Volume Absorption node
(colour 0.9/0.6/0.3, density 50 m^-1: attenuation distance 2 cm) and the glTF Material Output group's thickness
4 cm, which Blender 3.4 exports as KHR_materials_transmission, KHR_materials_volume and KHR_materials_ior. Its
subsurface settings (weight 0.3) have no glTF extension in Blender 3.4 and are not exported.
"""
import sys

import bpy

out = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)

bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=0.02)
sphere = bpy.context.active_object
sphere.name = "wax_ball"
sphere.data.name = "wax_ball_mesh"
bpy.ops.object.shade_smooth()

# 16 x 16 texels: red rising to the right, green rising upwards, blue in a checker (sRGB values, as painted).
size = 16
image = bpy.data.images.new("wax_albedo", size, size, alpha=False)
pixels = []
for y in range(size):
    for x in range(size):
        pixels += [0.55 + 0.4 * x / (size - 1), 0.35 + 0.5 * y / (size - 1), 0.25 if (x // 4 + y // 4) % 2 else 0.6, 1.0]
image.pixels = pixels
image.file_format = "PNG"
image.pack()

material = bpy.data.materials.new("wax")
material.use_nodes = True
nodes, links = material.node_tree.nodes, material.node_tree.links
bsdf = nodes["Principled BSDF"]
texture = nodes.new("ShaderNodeTexImage")
texture.image = image
links.new(texture.outputs["Color"], bsdf.inputs["Base Color"])
bsdf.inputs["Transmission"].default_value = 1.0
bsdf.inputs["IOR"].default_value = 1.4
bsdf.inputs["Roughness"].default_value = 0.2
bsdf.inputs["Subsurface"].default_value = 0.3

absorption = nodes.new("ShaderNodeVolumeAbsorption")
absorption.inputs["Color"].default_value = (0.9, 0.6, 0.3, 1.0)
absorption.inputs["Density"].default_value = 50.0
links.new(absorption.outputs["Volume"], nodes["Material Output"].inputs["Volume"])

# The exporter's thickness comes from the "glTF Material Output" group (as its importer makes it).
group = bpy.data.node_groups.new("glTF Material Output", "ShaderNodeTree")
group.inputs.new("NodeSocketFloat", "Thickness")
settings = nodes.new("ShaderNodeGroup")
settings.node_tree = group
settings.inputs["Thickness"].default_value = 0.04

sphere.data.materials.append(material)
bpy.ops.export_scene.gltf(filepath=out, export_format="GLB", use_selection=False, export_apply=True)
print("wrote", out)
