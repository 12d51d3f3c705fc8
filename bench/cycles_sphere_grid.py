# Blender Cycles render of shadowbench's default sphere grid at 800x600, the
# scene of bench_reference, for the comparison in docs/performance.md ("The
# adaptive Monte Carlo reference", Cycles): direct light only (no bounces),
# the same rectangular area light and camera, white diffuse everywhere, no
# denoising, no adaptive sampling. Blender is not a dependency; this is run
# by hand:
#   build/shadowbench scene export sphere_grid grid.glb
#   blender -b -noaudio --python bench/cycles_sphere_grid.py -- grid.glb 64 out.exr [SEED [noshadow]]
# It prints the render's wall time (scene sync, BVH and sampling; not
# Blender's start or the glTF import) and its CPU time (all threads). OUT ending in .exr is written as
# scene-linear float; "noshadow" renders with no object casting shadows
# (the lit image V is divided by). Camera and light are the sphere grid's
# defaults (`shadowbench scene info sphere_grid`).
import math, sys, time
import bpy
import numpy
from mathutils import Vector

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which its
# numpy 1.24 no longer has.
if not hasattr(numpy, "bool") or numpy.bool is not bool:
    numpy.bool = bool

args = sys.argv[sys.argv.index("--") + 1:]
glb, samples, out = args[:3]
samples = int(samples)
seed = int(args[3]) if len(args) > 3 else 0
no_shadow = len(args) > 4 and args[4] == "noshadow"

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)

def blender(v):  # glTF is Y-up, Blender Z-up: (x, y, z) -> (x, -z, y)
    return Vector((v[0], -v[2], v[1]))

white = bpy.data.materials.new("white")
white.use_nodes = True
white.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.8, 0.8, 1)
white.node_tree.nodes["Principled BSDF"].inputs["Specular"].default_value = 0.0
for o in bpy.data.objects:
    if o.type == "MESH":
        o.data.materials.clear()
        o.data.materials.append(white)
        if no_shadow:
            o.visible_shadow = False

scene = bpy.context.scene
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = samples
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 0
scene.render.resolution_x, scene.render.resolution_y = 800, 600
scene.render.resolution_percentage = 100
scene.cycles.seed = seed
scene.render.filepath = out
if out.endswith(".exr"):
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
world = bpy.data.worlds.new("black")
world.color = (0, 0, 0)
scene.world = world

def look(obj, eye, target):
    obj.location = eye
    obj.rotation_euler = (target - eye).to_track_quat("-Z", "Y").to_euler()

cam_data = bpy.data.cameras.new("cam")
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(50.0)
cam_data.clip_start, cam_data.clip_end = 0.1, 175.0
cam = bpy.data.objects.new("cam", cam_data)
scene.collection.objects.link(cam)
look(cam, blender((0, 12.125, 14.5)), blender((0, 0, 1.875)))
scene.camera = cam

light_data = bpy.data.lights.new("area", "AREA")
light_data.shape = "RECTANGLE"
light_data.size, light_data.size_y = 2.0, 2.0
light_data.energy = 2000.0
light = bpy.data.objects.new("area", light_data)
scene.collection.objects.link(light)
look(light, blender((3.5, 10, 2.5)), blender((0, 0, 0)))

t0, c0 = time.perf_counter(), time.process_time()
bpy.ops.render.render(write_still=True)
# cpu_s: the process's CPU time over the render, all threads (on a shared
# machine it counts only the time Blender ran, unlike wall_s).
print("SHADOWBENCH_CYCLES samples=%d wall_s=%.3f threads=%d cpu_s=%.3f" % (
    samples, time.perf_counter() - t0, scene.render.threads, time.process_time() - c0))
