# Renders a glTF file with Blender's Cycles under an environment map (issue 49, "Measures"): the file
# as Blender's glTF importer brings it in (render_cycles_imported.py), the world an Environment
# Texture fed by Generated coordinates through a Mapping node (type Point, Z rotation --env-rotate),
# Background strength --env-strength: what the stages' --env, --env-strength, --env-rotate mean.
# Not part of the article: bench machinery, run by bench/env/*.py under Blender:
#   blender --factory-startup -b --python bench/cycles/render_cycles_env.py -- --scene F.gltf \
#       --env W.exr --env-rotate 60 --width 160 --height 120 --spp 256 --seed 1 --out X.exr
# The render settings are render_cycles.py's (no denoising, clamping, adaptive sampling or light
# threshold; bounces 1024; Box 1.0 filter; Standard view; fixed seed and threads).
import argparse
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from render_cycles import clear_startup_scene, configure, fail, render_and_report, run_in_blender  # noqa: E402
from render_cycles_imported import import_as_blender_does, lambert_control  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_cycles_env.py")
    p.add_argument("--scene", required=True, help="a .gltf or .glb file with one camera")
    p.add_argument("--env", required=True, help="equirectangular .exr or .hdr")
    p.add_argument("--env-strength", type=float, default=1.0)
    p.add_argument("--env-rotate", type=float, default=0.0, help="degrees about the up axis (Mapping Z)")
    p.add_argument("--width", type=int, required=True)
    p.add_argument("--height", type=int, required=True)
    p.add_argument("--spp", type=int, required=True)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--out", required=True, help="OpenEXR file (linear float32 R,G,B)")
    p.add_argument("--lambert", action="store_true", help="every Principled BSDF made Lambert (the control)")
    p.add_argument("--specular-zero", action="store_true",
                   help="a diagnosis: each Principled BSDF's Specular input set to 0 (its diffuse alone)")
    return p.parse_args(argv)


def set_environment(path, strength, rotate_degrees):
    """World: Generated -> Mapping (Point, Z rotation) -> Environment Texture (Linear) -> Background."""
    world = bpy.context.scene.world
    world.use_nodes = True
    tree = world.node_tree
    background = tree.nodes["Background"]
    coords = tree.nodes.new("ShaderNodeTexCoord")
    mapping = tree.nodes.new("ShaderNodeMapping")
    mapping.vector_type = "POINT"
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(rotate_degrees))
    texture = tree.nodes.new("ShaderNodeTexEnvironment")
    texture.image = bpy.data.images.load(os.path.abspath(path))
    texture.image.colorspace_settings.name = "Linear"
    texture.interpolation = "Linear"
    texture.projection = "EQUIRECTANGULAR"
    tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
    tree.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    tree.links.new(texture.outputs["Color"], background.inputs["Color"])
    background.inputs["Strength"].default_value = strength


def main():
    args = parse_args()
    if not os.path.exists(args.env):
        fail(f"--env {args.env}: no such file")
    clear_startup_scene()
    import_as_blender_does(args.scene)
    if args.lambert:
        lambert_control()
    if args.specular_zero:
        for m in bpy.data.materials:
            for n in (m.node_tree.nodes if m.use_nodes else []):
                if n.type == "BSDF_PRINCIPLED":
                    for link in list(n.inputs["Specular"].links):
                        m.node_tree.links.remove(link)
                    n.inputs["Specular"].default_value = 0.0
    set_environment(args.env, args.env_strength, args.env_rotate)
    configure(args)
    render_and_report(args)


if __name__ == "__main__":
    run_in_blender(main)
