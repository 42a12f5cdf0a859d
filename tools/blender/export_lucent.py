# export_lucent.py: exports the open Blender scene as a lucent scene file (JSON) with its meshes as PLY files.
#
# Headless:   blender -b scene.blend --python tools/blender/export_lucent.py -- out/scene.json
# Add-on:     Edit > Preferences > Add-ons > Install... this file; then File > Export > lucent scene (.json).
#
# What is written (docs/blender.md):
# - every visible mesh object, modifiers applied, in Blender's world coordinates (metres x unit scale) as
#   <scene>_<object>.ply (positions and vertex normals), with "up_axis": "z" so lucent turns Blender's +Z up to +Y;
# - the material: the first material slot's Principled BSDF as {"principled": {...}} when it has subsurface
#   scattering, else an opaque object with the Base Color as its albedo. Blender 3.x: the Subsurface, Subsurface
#   Color, Subsurface IOR ... sockets (subsurface above 0). Blender 4 (bpy.app.version >= 4.0, the Principled v2
#   node): "version": 4 with Subsurface Weight, Subsurface Radius, Subsurface Scale, IOR, Subsurface IOR,
#   Subsurface Anisotropy and the node's subsurface_method (weight and scale above 0). Texture links are not
#   followed (the socket's own value is used, with a note on stderr);
# - the scene camera (perspective) as eye, target, up and the vertical field of view of the render's aspect;
# - sun lights as directional lights: radiance = Strength x Color (W/m^2, the irradiance on a surface facing it, as
#   in Cycles); point lights as point lights: intensity = Power x Color / (4 pi) (W/sr, the radiant intensity of an
#   isotropic source of that power; Cycles gives a point light of P watts the same intensity); other light types
#   are skipped with a note;
# - scale_mm = 1000 x the scene's unit scale (Blender units are metres at unit scale 1);
# - the render resolution, and the world's Background colour x strength as the render background.
# Camera and light positions and directions are turned from Blender's Z-up to lucent's Y-up: (x, y, z) ->
# (x, z, -y), the same turn that "up_axis": "z" gives the meshes.
import json
import math
import os
import re
import struct
import sys

import bpy
import mathutils

bl_info = {
    "name": "lucent scene (.json)",
    "author": "lucent",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Export > lucent scene (.json)",
    "description": "Export meshes, camera, lights and Principled subsurface materials as a lucent scene",
    "category": "Import-Export",
}

# Blender 3.x's subsurface_method values, and Blender 4's: 4.0 renamed Random Walk (radius from the colour) to
# Random Walk (Skin) and Random Walk (Fixed Radius) to Random Walk.
SUBSURFACE_METHODS = {
    "RANDOM_WALK": "random_walk",
    "RANDOM_WALK_FIXED_RADIUS": "random_walk_fixed_radius",
    "BURLEY": "burley",
}
SUBSURFACE_METHODS_V2 = {
    "RANDOM_WALK": "random_walk",
    "RANDOM_WALK_SKIN": "random_walk_skin",
    "BURLEY": "burley",
}


def note(message):
    print("export_lucent: " + message, file=sys.stderr)


def y_up(v):
    """Blender's Z-up world to lucent's Y-up world."""
    return [v.x, v.z, -v.y]


def rounded(values, digits=6):
    return [round(float(x), digits) for x in values]


def write_ply(path, positions, normals, triangles):
    """A binary little-endian PLY with float positions, float normals and int triangle indices."""
    header = (
        "ply\nformat binary_little_endian 1.0\ncomment written by lucent's Blender exporter\n"
        f"element vertex {len(positions)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\n"
        f"element face {len(triangles)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        for p, n in zip(positions, normals):
            f.write(struct.pack("<6f", p[0], p[1], p[2], n[0], n[1], n[2]))
        for t in triangles:
            f.write(struct.pack("<B3i", 3, t[0], t[1], t[2]))


def export_mesh(obj, depsgraph, path):
    """The evaluated mesh in world coordinates; False when it has no triangles."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        world = obj.matrix_world
        mesh.transform(world)
        if world.to_3x3().determinant() < 0.0:
            mesh.flip_normals()  # a mirroring transform turns the winding inside out
        mesh.calc_loop_triangles()
        if len(mesh.loop_triangles) == 0:
            return False
        positions = [v.co.copy() for v in mesh.vertices]
        normals = [v.normal.copy() for v in mesh.vertices]
        triangles = [tuple(t.vertices) for t in mesh.loop_triangles]
        write_ply(path, positions, normals, triangles)
        return True
    finally:
        evaluated.to_mesh_clear()


def socket_value(node, name, what):
    socket = node.inputs.get(name)
    if socket is None:
        return None
    if socket.is_linked:
        note(f"{what}: '{name}' is linked to a node; its own value is exported")
    return socket.default_value


def principled_node(material):
    if material is None or not material.use_nodes:
        return None
    for node in material.node_tree.nodes:
        if node.type == "BSDF_PRINCIPLED":
            return node
    return None


def material_entry(obj):
    """{"material": {"principled": ...}} or {"albedo": [...]} for the object's first material."""
    material = obj.material_slots[0].material if obj.material_slots else None
    node = principled_node(material)
    if node is None:
        note(f"{obj.name}: no Principled BSDF; exported as opaque grey")
        return {"albedo": [0.8, 0.8, 0.8]}
    what = f"{obj.name} / {material.name}"
    if bpy.app.version >= (4, 0, 0):
        return principled_v2_entry(node, material, what)
    base = rounded(socket_value(node, "Base Color", what)[:3])
    subsurface = float(socket_value(node, "Subsurface", what))
    if subsurface <= 0.0:
        return {"albedo": base}
    block = {
        "base_color": base,
        "subsurface": round(subsurface, 6),
        "subsurface_radius": rounded(socket_value(node, "Subsurface Radius", what)),
        "subsurface_color": rounded(socket_value(node, "Subsurface Color", what)[:3]),
        "subsurface_ior": round(float(socket_value(node, "Subsurface IOR", what)), 6),
        "subsurface_anisotropy": round(float(socket_value(node, "Subsurface Anisotropy", what)), 6),
        "subsurface_method": SUBSURFACE_METHODS[node.subsurface_method],
    }
    return {"material": {"principled": block, "name": material.name}}


def principled_v2_entry(node, material, what):
    """Blender 4's Principled BSDF (v2): the same as material_entry's Blender 3.x block, with v2's sockets."""
    base = rounded(min(max(float(x), 0.0), 1.0) for x in socket_value(node, "Base Color", what)[:3])  # as Cycles
    weight = float(socket_value(node, "Subsurface Weight", what))
    scale = float(socket_value(node, "Subsurface Scale", what))
    if weight <= 0.0 or scale <= 0.0:
        return {"albedo": base}
    if weight < 1.0:
        note(f"{what}: Subsurface Weight {weight:g} mixes a diffuse surface in; lucent renders weight 1 only")
    block = {
        "version": 4,
        "base_color": base,
        "subsurface_weight": round(weight, 6),
        "subsurface_radius": rounded(socket_value(node, "Subsurface Radius", what)),
        "subsurface_scale": round(scale, 9),
        "ior": round(float(socket_value(node, "IOR", what)), 6),
        "subsurface_anisotropy": round(float(socket_value(node, "Subsurface Anisotropy", what)), 6),
        "subsurface_method": SUBSURFACE_METHODS_V2[node.subsurface_method],
    }
    subsurface_ior = socket_value(node, "Subsurface IOR", what)  # used by random_walk_skin
    if subsurface_ior is not None:
        block["subsurface_ior"] = round(float(subsurface_ior), 6)
    return {"material": {"principled": block, "name": material.name}}


def vertical_fov_deg(camera, scene):
    """The vertical field of view of the render: Blender fits the sensor to the wider side under AUTO."""
    data = camera.data
    render = scene.render
    aspect = (render.resolution_x * render.pixel_aspect_x) / (render.resolution_y * render.pixel_aspect_y)
    fit = data.sensor_fit
    if fit == "AUTO":
        fit = "HORIZONTAL" if aspect >= 1.0 else "VERTICAL"
        sensor = data.sensor_width
    else:
        sensor = data.sensor_width if fit == "HORIZONTAL" else data.sensor_height
    half = math.atan(sensor / (2.0 * data.lens))
    if fit == "HORIZONTAL":
        half = math.atan(math.tan(half) / aspect)
    return math.degrees(2.0 * half)


def camera_entry(scene):
    camera = scene.camera
    if camera is None:
        raise RuntimeError("the scene has no camera")
    if camera.data.type != "PERSP":
        raise RuntimeError(f"camera '{camera.name}': only perspective cameras are exported")
    world = camera.matrix_world
    eye = world.translation
    forward = (world.to_3x3() @ mathutils.Vector((0.0, 0.0, -1.0))).normalized()
    up = (world.to_3x3() @ mathutils.Vector((0.0, 1.0, 0.0))).normalized()
    return {"eye": rounded(y_up(eye)), "target": rounded(y_up(eye + forward)), "up": rounded(y_up(up)),
            "fov_y_deg": round(vertical_fov_deg(camera, scene), 4)}


def light_entry(obj):
    light = obj.data
    colour = mathutils.Vector(light.color)
    if light.type == "SUN":
        direction = (obj.matrix_world.to_3x3() @ mathutils.Vector((0.0, 0.0, -1.0))).normalized()
        return {"type": "directional", "direction": rounded(y_up(direction)),
                "radiance": rounded(colour * light.energy)}
    if light.type == "POINT":
        return {"type": "point", "position": rounded(y_up(obj.matrix_world.translation)),
                "intensity": rounded(colour * (light.energy / (4.0 * math.pi)))}
    note(f"{obj.name}: {light.type.lower()} lights are not exported")
    return None


def background(scene):
    world = scene.world
    if world is None or not world.use_nodes:
        return [0.0, 0.0, 0.0]
    for node in world.node_tree.nodes:
        if node.type == "BACKGROUND":
            colour = mathutils.Vector(node.inputs["Color"].default_value[:3])
            return rounded(colour * node.inputs["Strength"].default_value)
    return [0.0, 0.0, 0.0]


def export_scene(path, context=None):
    context = context or bpy.context
    scene = context.scene
    depsgraph = context.evaluated_depsgraph_get()
    directory = os.path.dirname(os.path.abspath(path))
    stem = os.path.splitext(os.path.basename(path))[0]
    os.makedirs(directory, exist_ok=True)
    objects, lights = [], []
    for obj in scene.objects:
        if not obj.visible_get():
            continue
        if obj.type == "MESH":
            mesh_file = f"{stem}_{bpy.path.clean_name(obj.name)}.ply"
            if not export_mesh(obj, depsgraph, os.path.join(directory, mesh_file)):
                note(f"{obj.name}: no faces; skipped")
                continue
            entry = {"name": obj.name, "mesh": mesh_file, "up_axis": "z"}
            entry.update(material_entry(obj))
            objects.append(entry)
        elif obj.type == "LIGHT":
            entry = light_entry(obj)
            if entry:
                lights.append(entry)
    render = scene.render
    document = {
        "comment": f"exported from Blender {bpy.app.version_string} by tools/blender/export_lucent.py",
        "scale_mm": round(1000.0 * scene.unit_settings.scale_length, 6),
        "camera": camera_entry(scene),
        "lights": lights,
        "objects": objects,
        "render": {"width": int(render.resolution_x * render.resolution_percentage / 100),
                   "height": int(render.resolution_y * render.resolution_percentage / 100),
                   "background": background(scene)},
    }
    text = json.dumps(document, indent=2)
    text = re.sub(r"\[\s+([-0-9.e, \n]+?)\s+\]", lambda m: "[" + re.sub(r"\s+", " ", m.group(1)) + "]", text)
    with open(path, "w") as f:
        f.write(text + "\n")
    return document


class ExportLucent(bpy.types.Operator):
    """Export the scene as a lucent scene file"""
    bl_idname = "export_scene.lucent"
    bl_label = "Export lucent scene"
    filename_ext = ".json"
    filepath: bpy.props.StringProperty(subtype="FILE_PATH")

    def invoke(self, context, event):
        if not self.filepath:
            self.filepath = bpy.path.ensure_ext(bpy.data.filepath or "untitled", ".json")
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        try:
            export_scene(self.filepath, context)
        except RuntimeError as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        return {"FINISHED"}


def menu_entry(self, context):
    self.layout.operator(ExportLucent.bl_idname, text="lucent scene (.json)")


def register():
    bpy.utils.register_class(ExportLucent)
    bpy.types.TOPBAR_MT_file_export.append(menu_entry)


def unregister():
    bpy.types.TOPBAR_MT_file_export.remove(menu_entry)
    bpy.utils.unregister_class(ExportLucent)


if __name__ == "__main__":
    arguments = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(arguments) != 1:
        print("usage: blender -b file.blend --python export_lucent.py -- out.json", file=sys.stderr)
        sys.exit(2)
    try:
        document = export_scene(arguments[0])
    except RuntimeError as error:
        print(f"export_lucent: {error}", file=sys.stderr)
        sys.exit(1)
    print(f"export_lucent: {arguments[0]}: {len(document['objects'])} objects, {len(document['lights'])} lights")
