"""Renders one glTF model as the Objaverse rendering scripts do, for the collection benchmark.

    blender -b -P blender_views.py -- MODEL OUT_DIR eevee|cycles [VIEWS] [SIZE] [SAMPLES] [ONLY]
        [PASSES]

The scene is emptied, the model imported and scaled into a unit box centred at the origin, one
large area light put above it, and VIEWS (12) cameras with a 35 mm lens on a 32 mm sensor
placed 1.5 units away on a circle 30 degrees above the horizon, as `encore batch` places them
(view 0 on glTF's +Z, then towards +X). Each view is written as OUT_DIR/000.png ... (RGBA,
transparent film), SIZE (512) square, with SAMPLES (16) samples per pixel. ONLY, a
comma-separated list of view indices ("0,3,6,9"), renders those views of the circle and no
others (the contact sheet shows a few; at seconds per view, rendering the rest is wasted; "all"
renders every view). PASSES "all" also writes, through the compositor, what `encore batch
--albedo --normals --depth --depth-format exr` writes beside each view: the diffuse colour pass
(NNN_albedo.png), the normal pass (NNN_normal.exr) and the Z pass (NNN_depth.exr), the
outputs the G-buffer Objaverse scripts take from Blender.
"""

import math
import os
import sys

import numpy

# Blender 3.4's glTF importer still uses numpy.bool, which numpy 1.24 removed.
numpy.bool = bool

import bpy  # noqa: E402
from mathutils import Vector  # noqa: E402

arguments = sys.argv[sys.argv.index("--") + 1:]
model, out_dir, engine = arguments[:3]
views = int(arguments[3]) if len(arguments) > 3 else 12
size = int(arguments[4]) if len(arguments) > 4 else 512
samples = int(arguments[5]) if len(arguments) > 5 else 16
only = ([int(view) for view in arguments[6].split(",")]
        if len(arguments) > 6 and arguments[6] != "all" else list(range(views)))
passes = len(arguments) > 7 and arguments[7] == "all"

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
render = scene.render
render.resolution_x = render.resolution_y = size
render.resolution_percentage = 100
render.film_transparent = True
render.image_settings.file_format = "PNG"
render.image_settings.color_mode = "RGBA"
if engine == "cycles":
    render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
else:
    render.engine = "BLENDER_EEVEE"
    scene.eevee.taa_render_samples = samples

bpy.ops.import_scene.gltf(filepath=model)

# Into a unit box centred at the origin (the dataset scripts' normalize_scene).
meshes = [obj for obj in scene.objects if obj.type == "MESH"]
low = Vector((math.inf,) * 3)
high = Vector((-math.inf,) * 3)
bpy.context.view_layer.update()
for obj in meshes:
    for corner in obj.bound_box:
        point = obj.matrix_world @ Vector(corner)
        low = Vector(map(min, low, point))
        high = Vector(map(max, high, point))
roots = [obj for obj in scene.objects if obj.parent is None]
scale = 1.0 / max(high - low)
offset = -(low + high) / 2.0
for obj in roots:
    obj.matrix_world = obj.matrix_world.copy()
    obj.location = (obj.location + offset) * scale
    obj.scale = obj.scale * scale
bpy.context.view_layer.update()

world = bpy.data.worlds.new("World")
world.color = (0.05, 0.05, 0.05)
scene.world = world
light_data = bpy.data.lights.new("Area", type="AREA")
light_data.energy = 3000
light = bpy.data.objects.new("Area", light_data)
light.location = (0.0, 0.0, 0.5)
light.scale = (100.0, 100.0, 100.0)
scene.collection.objects.link(light)

camera_data = bpy.data.cameras.new("Camera")
camera_data.lens = 35.0
camera_data.sensor_width = 32.0
camera = bpy.data.objects.new("Camera", camera_data)
scene.collection.objects.link(camera)
scene.camera = camera
target = bpy.data.objects.new("Target", None)
scene.collection.objects.link(target)
track = camera.constraints.new(type="TRACK_TO")
track.target = target
track.track_axis = "TRACK_NEGATIVE_Z"
track.up_axis = "UP_Y"

pass_outputs = []
if passes:
    layer = scene.view_layers[0]
    layer.use_pass_normal = True
    layer.use_pass_z = True
    layer.use_pass_diffuse_color = True
    scene.use_nodes = True
    tree = scene.node_tree
    layers = tree.nodes.get("Render Layers") or tree.nodes.new("CompositorNodeRLayers")
    for socket, suffix, file_format in (("DiffCol", "albedo", "PNG"), ("Normal", "normal",
                                                                         "OPEN_EXR"),
                                        ("Depth", "depth", "OPEN_EXR")):
        output = tree.nodes.new("CompositorNodeOutputFile")
        output.base_path = out_dir
        output.format.file_format = file_format
        if file_format == "OPEN_EXR":
            output.format.color_depth = "32"
        tree.links.new(layers.outputs[socket], output.inputs[0])
        pass_outputs.append((output, suffix))

elevation = math.radians(30.0)
for view in only:
    azimuth = 2.0 * math.pi * view / views
    # glTF (x, y, z) is Blender (x, -z, y).
    x = math.cos(elevation) * math.sin(azimuth)
    y = math.sin(elevation)
    z = math.cos(elevation) * math.cos(azimuth)
    camera.location = (1.5 * x, -1.5 * z, 1.5 * y)
    render.filepath = os.path.join(out_dir, f"{view:03}.png")
    for output, suffix in pass_outputs:
        # The File Output node appends the frame number to the slot's path.
        output.file_slots[0].path = f"{view:03}_{suffix}_"
    bpy.ops.render.render(write_still=True)
