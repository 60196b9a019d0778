# Renders a glTF scene with Blender's Cycles under settings that match the stages (issue 23,
# "the bench's anchor"): the factory start-up scene cleared and a black world, each imported
# Principled BSDF replaced by Diffuse(base colour) + Emission(emissive factor x strength, one-sided
# unless the glTF material is double-sided), the glTF camera, no adaptive sampling, denoising,
# clamping, light threshold or glossy blur, bounce limits raised (the stages end paths by Russian
# roulette only), a Box 1.0 pixel filter, fixed threads, linear float32 RGB OpenEXR out. Times the
# render call alone and prints `CYCLES_RENDER cpu_s=... wall_s=... samples=... threads=...`.
# Bench-only: nothing in the build or the tests runs it. docs/results/cycles_notes.md explains it.
#
# Usage (Debian 12: apt-get install blender, 3.4.1):
#   blender --factory-startup -b --python bench/cycles/render_cycles.py -- \
#       --scene scenes/cornell.gltf --width 64 --height 64 --spp 256 --seed 0 --threads 2 --out X.exr
import argparse
import os
import sys
import time

import bpy

BOUNCES = 1024  # "no limit": the stages have none; Cycles' Russian roulette still ends paths


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_cycles.py", description=__doc__)
    p.add_argument("--scene", required=True, help="a .gltf or .glb file")
    p.add_argument("--width", type=int, required=True)
    p.add_argument("--height", type=int, required=True)
    p.add_argument("--spp", type=int, required=True)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--out", required=True, help="OpenEXR file (linear float32 R,G,B)")
    return p.parse_args(argv)


def fail(message):
    print("render_cycles.py: " + message, file=sys.stderr)
    sys.exit(2)


def clear_startup_scene():
    """The factory start-up has a cube, a camera, a 1000 W point light and a grey world."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for collection in (bpy.data.meshes, bpy.data.lights, bpy.data.cameras, bpy.data.materials):
        for block in list(collection):
            collection.remove(block)
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    background.inputs["Strength"].default_value = 0.0
    world.color = (0.0, 0.0, 0.0)
    bpy.context.scene.world = world


def unlinked_value(node, name, material):
    socket = node.inputs[name]
    if socket.is_linked:
        fail(f"material '{material.name}': '{name}' is driven by a texture or node; only the glTF "
             "factors are supported here")
    return socket.default_value


def replace_material(material):
    """Principled BSDF -> Diffuse(base colour) + Emission(emissive), one-sided unless double-sided.

    The glTF importer (Blender 3.4) puts baseColorFactor into 'Base Color', emissiveFactor into
    'Emission' and KHR_materials_emissive_strength into 'Emission Strength', and sets
    use_backface_culling = not doubleSided.
    """
    tree = material.node_tree
    principled = [n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"]
    if len(principled) != 1:
        fail(f"material '{material.name}': expected one Principled BSDF, found {len(principled)}")
    p = principled[0]
    base = list(unlinked_value(p, "Base Color", material))[:3]
    emission = list(unlinked_value(p, "Emission", material))[:3]
    strength = float(unlinked_value(p, "Emission Strength", material))
    metallic = float(unlinked_value(p, "Metallic", material))
    transmission = float(unlinked_value(p, "Transmission", material))
    if metallic > 0.0 or transmission > 0.0:
        print(f"render_cycles.py: warning: material '{material.name}' has metallic {metallic}, "
              f"transmission {transmission}; rendered as diffuse only", file=sys.stderr)
    double_sided = not material.use_backface_culling

    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    out.target = "ALL"
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = base + [1.0]
    diffuse.inputs["Roughness"].default_value = 0.0  # Lambert, not Oren-Nayar
    emit = tree.nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = emission + [1.0]
    # Strength 1 on a surface gives radiance = colour, the stages' unit.
    emit.inputs["Strength"].default_value = strength
    if not double_sided and any(c > 0.0 for c in emission) and strength > 0.0:
        # Cycles' emission is two-sided; the stages emit from the front face only (glTF winding).
        # Strength x (1 - Backfacing): back faces emit nothing.
        geometry = tree.nodes.new("ShaderNodeNewGeometry")
        front = tree.nodes.new("ShaderNodeMath")
        front.operation = "SUBTRACT"
        front.inputs[0].default_value = 1.0
        tree.links.new(geometry.outputs["Backfacing"], front.inputs[1])
        scale = tree.nodes.new("ShaderNodeMath")
        scale.operation = "MULTIPLY"
        scale.inputs[1].default_value = strength
        tree.links.new(front.outputs["Value"], scale.inputs[0])
        tree.links.new(scale.outputs["Value"], emit.inputs["Strength"])
    add = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(diffuse.outputs["BSDF"], add.inputs[0])
    tree.links.new(emit.outputs["Emission"], add.inputs[1])
    tree.links.new(add.outputs["Shader"], out.inputs["Surface"])
    material.use_backface_culling = False  # viewport-only flag; leave Cycles' geometry alone
    sides = "two-sided" if double_sided else "one-sided"
    print(f"render_cycles.py: material '{material.name}': diffuse {tuple(round(c, 6) for c in base)}, "
          f"emission {tuple(round(c * strength, 6) for c in emission)} ({sides})")


def numpy_aliases():
    """Debian 12's Blender 3.4.1 runs on the system numpy (1.24), which removed the aliases np.bool,
    np.int, ... that the 3.4 glTF importer still uses (np.bool in set_poly_smoothing). Put them
    back as the builtins they always were."""
    import numpy
    for name, builtin in (("bool", bool), ("int", int), ("float", float), ("object", object)):
        if name not in numpy.__dict__:
            setattr(numpy, name, builtin)


def import_scene(path):
    numpy_aliases()
    result = bpy.ops.import_scene.gltf(filepath=os.path.abspath(path))
    if "FINISHED" not in result:
        fail(f"import of {path} failed: {result}")
    for material in bpy.data.materials:
        if material.use_nodes and material.users > 0:
            replace_material(material)
    lights = [o for o in bpy.data.objects if o.type == "LIGHT"]
    if lights:
        # The importer converts KHR_lights_punctual intensities with its own photometric units.
        fail(f"{path} has {len(lights)} punctual light(s); their units are not matched here yet")
    cameras = [o for o in bpy.data.objects if o.type == "CAMERA"]
    if not cameras:
        fail(f"{path} has no camera; the stages would frame the bounding sphere, this script does not")
    # The stages use the first camera met in the node order; the cornell scene has one.
    bpy.context.scene.camera = sorted(cameras, key=lambda o: o.name)[0]


def configure(args):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args.spp
    c.seed = args.seed
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0       # factory 10
    c.light_sampling_threshold = 0.0    # factory 0.01
    c.blur_glossy = 0.0                 # factory 1 ("filter glossy"), biased
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.max_bounces = BOUNCES             # factory 12
    c.diffuse_bounces = BOUNCES         # factory 4
    c.glossy_bounces = BOUNCES          # factory 4
    c.transmission_bounces = BOUNCES    # factory 12
    c.transparent_max_bounces = BOUNCES  # factory 8
    c.volume_bounces = BOUNCES
    c.min_light_bounces = 0
    c.pixel_filter_type = "BOX"         # factory Blackman-Harris
    c.filter_width = 1.0                # factory 1.5: Box 1.0 = uniform jitter in the pixel
    c.sample_offset = 0
    c.scrambling_distance = 1.0
    c.auto_scrambling_distance = False
    # sampling_pattern is left at the factory PROGRESSIVE_MULTI_JITTER (reported, not changed).
    r = scene.render
    r.resolution_x = args.width
    r.resolution_y = args.height
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.use_border = False
    r.film_transparent = False
    r.use_motion_blur = False
    r.use_compositing = False
    r.use_sequencer = False
    r.dither_intensity = 0.0
    r.threads_mode = "FIXED"
    r.threads = args.threads
    v = scene.view_settings
    v.view_transform = "Standard"       # factory Filmic
    v.look = "None"
    v.exposure = 0.0
    v.gamma = 1.0
    s = r.image_settings
    s.file_format = "OPEN_EXR"
    s.color_mode = "RGB"
    s.color_depth = "32"
    s.exr_codec = "ZIP"
    print(f"render_cycles.py: Cycles {bpy.app.version_string}, sampling pattern {c.sampling_pattern}, "
          f"{args.width}x{args.height}, {args.spp} spp, seed {args.seed}, {args.threads} threads")


def main():
    args = parse_args()
    if args.spp < 1 or args.width < 1 or args.height < 1 or args.threads < 1:
        fail("--spp, --width, --height and --threads must be positive")
    clear_startup_scene()
    import_scene(args.scene)
    configure(args)
    render_and_report(args)


def render_and_report(args):
    """Renders the configured scene, saves it to args.out and prints the CYCLES_RENDER line
    the comparisons read (cpu_s: process_time, user + sys of every thread of this process,
    during the render call only)."""
    cpu0, wall0 = time.process_time(), time.perf_counter()
    bpy.ops.render.render()
    cpu1, wall1 = time.process_time(), time.perf_counter()
    out = os.path.abspath(args.out)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    bpy.data.images["Render Result"].save_render(out)
    print(f"CYCLES_RENDER cpu_s={cpu1 - cpu0:.4f} wall_s={wall1 - wall0:.4f} samples={args.spp} "
          f"threads={args.threads} seed={args.seed} size={args.width}x{args.height} out={out}",
          flush=True)


def run_in_blender(main):
    """Runs main() so that any failure ends Blender with a non-zero status: Blender ignores a
    script's exit status in -b mode unless the process itself exits."""
    try:
        main()
    except SystemExit as e:
        sys.stdout.flush()
        os._exit(e.code if isinstance(e.code, int) else 1)
    except Exception:  # noqa: BLE001 (any failure must end Blender with non-zero status)
        import traceback
        traceback.print_exc()
        sys.stderr.flush()
        os._exit(1)


if __name__ == "__main__":
    run_in_blender(main)
