# Renders a glTF file with Blender's Cycles as Blender's own glTF importer brings it in (issue 46,
# "Against Blender"): Principled BSDF kept, KHR_lights_punctual lights as the importer makes them
# ("Standard" lighting mode, 683 lm/W, its default light radius), a uniform world of colour --sky.
# Not part of the article: bench machinery, run by bench/cycles/compare_gltf.py under Blender:
#   blender --factory-startup -b --python bench/cycles/render_cycles_imported.py -- \
#       --scene F.gltf --width 160 --height 90 --spp 256 --seed 1 --sky 0.1,0.1,0.1 --out X.exr
# The render settings are render_cycles.py's (no denoising, clamping, adaptive sampling or light
# threshold; bounces 1024; Box 1.0 filter; Standard view; fixed seed and threads).
import argparse
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from render_cycles import clear_startup_scene, configure, fail, numpy_aliases, render_and_report, run_in_blender  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_cycles_imported.py")
    p.add_argument("--scene", required=True, help="a .gltf or .glb file")
    p.add_argument("--width", type=int, required=True)
    p.add_argument("--height", type=int, required=True)
    p.add_argument("--spp", type=int, required=True)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--sky", default="0,0,0", help="uniform world radiance R,G,B (the stages' --sky)")
    p.add_argument("--out", required=True, help="OpenEXR file (linear float32 R,G,B)")
    p.add_argument("--lambert", action="store_true",
                   help="the control: each Principled BSDF's reflection replaced by a Lambert Diffuse BSDF of "
                        "its base colour (texture, vertex colour and normal kept), its emission kept")
    p.add_argument("--specular-zero", action="store_true",
                   help="a diagnosis: each Principled BSDF's Specular input set to 0 "
                        "(its diffuse alone on a dielectric)")
    # Diagnoses of the residuals (bench/cycles/gltf_residuals.py): each changes one thing.
    p.add_argument("--set-input", action="append", default=[], metavar="NAME=VALUE",
                   help="a diagnosis: every Principled BSDF's input NAME unlinked and set to VALUE")
    p.add_argument("--distribution", default=None, help="a diagnosis: every Principled BSDF's distribution "
                   "(GGX or MULTI_GGX)")
    p.add_argument("--interpolation", default=None, help="a diagnosis: every Image Texture node's "
                   "interpolation (Linear, Closest, Cubic)")
    p.add_argument("--spot-blend", type=float, default=None, help="a diagnosis: every spot light's blend")
    p.add_argument("--no-normal-map", action="store_true",
                   help="a diagnosis: every Principled BSDF's Normal input unlinked (before --lambert)")
    p.add_argument("--bare-default-material", action="store_true",
                   help="a diagnosis: each mesh object without a material gets the glTF default one "
                        "(metallic 1, roughness 1) times its first colour attribute, as glTF defines it")
    return p.parse_args(argv)


def import_as_blender_does(path):
    """The importer's defaults, named: lights in 'Standard' (SPEC) units, the file's normals."""
    numpy_aliases()
    result = bpy.ops.import_scene.gltf(filepath=os.path.abspath(path), convert_lighting_mode="SPEC",
                                       import_shading="NORMALS", merge_vertices=False,
                                       import_pack_images=True)
    if "FINISHED" not in result:
        fail(f"import of {path} failed: {result}")
    cameras = [o for o in bpy.data.objects if o.type == "CAMERA"]
    if len(cameras) != 1:
        fail(f"{path} has {len(cameras)} cameras; the bench gives each file exactly one")
    bpy.context.scene.camera = cameras[0]
    for o in bpy.data.objects:
        if o.type == "LIGHT":
            d = o.data
            extra = f", spot size {d.spot_size:.4f} blend {d.spot_blend:.4f}" if d.type == "SPOT" else ""
            extra += f", angle {d.angle:.5f}" if d.type == "SUN" else f", radius {d.shadow_soft_size}"
            print(f"render_cycles_imported.py: light '{o.name}': {d.type} {d.energy:.6g} W{extra}")
    for m in bpy.data.materials:
        if m.use_nodes and m.users > 0:
            kinds = sorted({n.bl_idname for n in m.node_tree.nodes})
            dist = [n.distribution for n in m.node_tree.nodes if n.type == "BSDF_PRINCIPLED"]
            print(f"render_cycles_imported.py: material '{m.name}': {', '.join(kinds)}; "
                  f"Principled distribution {dist}")


def lambert_control():
    """Diffuse(base colour, roughness 0 = Lambert) + the Principled BSDF left with its emission only
    (base colour black, specular, metallic, transmission, sheen, clearcoat, subsurface 0)."""
    for m in bpy.data.materials:
        if not m.use_nodes or m.users == 0:
            continue
        tree = m.node_tree
        for p in [n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"]:
            d = tree.nodes.new("ShaderNodeBsdfDiffuse")
            d.inputs["Roughness"].default_value = 0.0
            for src, dst in (("Base Color", "Color"), ("Normal", "Normal")):
                if p.inputs[src].is_linked:
                    tree.links.new(p.inputs[src].links[0].from_socket, d.inputs[dst])
                elif src == "Base Color":
                    d.inputs[dst].default_value = p.inputs[src].default_value
            for name in ("Base Color", "Specular", "Metallic", "Transmission", "Sheen", "Clearcoat", "Subsurface"):
                for link in list(p.inputs[name].links):
                    tree.links.remove(link)
                p.inputs[name].default_value = (0.0, 0.0, 0.0, 1.0) if name == "Base Color" else 0.0
            add = tree.nodes.new("ShaderNodeAddShader")
            tree.links.new(d.outputs["BSDF"], add.inputs[0])
            for link in list(p.outputs["BSDF"].links):
                to = link.to_socket
                tree.links.remove(link)
                tree.links.new(add.outputs["Shader"], to)
            tree.links.new(p.outputs["BSDF"], add.inputs[1])


def diagnoses(args):
    """The one-change diagnoses of --set-input, --distribution, --interpolation, --spot-blend and
    --bare-default-material, each printed."""
    principled = [n for m in bpy.data.materials if m.use_nodes for n in m.node_tree.nodes
                  if n.type == "BSDF_PRINCIPLED"]
    for item in args.set_input:
        name, value = item.split("=")
        for p in principled:
            for link in list(p.inputs[name].links):
                p.id_data.links.remove(link)
            p.inputs[name].default_value = float(value)
        print(f"render_cycles_imported.py: diagnosis: Principled '{name}' = {value} on {len(principled)} nodes")
    if args.distribution:
        for p in principled:
            p.distribution = args.distribution
        print(f"render_cycles_imported.py: diagnosis: distribution {args.distribution}")
    if args.interpolation:
        images = [n for m in bpy.data.materials if m.use_nodes for n in m.node_tree.nodes if n.type == "TEX_IMAGE"]
        for n in images:
            n.interpolation = args.interpolation
        print(f"render_cycles_imported.py: diagnosis: interpolation {args.interpolation} on {len(images)} images")
    if args.spot_blend is not None:
        for light in bpy.data.lights:
            if light.type == "SPOT":
                light.spot_blend = args.spot_blend
        print(f"render_cycles_imported.py: diagnosis: spot blend {args.spot_blend}")
    if args.bare_default_material:
        bare = [o for o in bpy.data.objects if o.type == "MESH" and not any(o.data.materials)]
        for o in bare:
            m = bpy.data.materials.new("glTF default")
            m.use_nodes = True
            p = m.node_tree.nodes["Principled BSDF"]
            p.inputs["Metallic"].default_value = 1.0
            p.inputs["Roughness"].default_value = 1.0
            p.distribution = "GGX"
            attrs = o.data.color_attributes
            if len(attrs):
                c = m.node_tree.nodes.new("ShaderNodeVertexColor")
                c.layer_name = attrs[0].name
                m.node_tree.links.new(c.outputs["Color"], p.inputs["Base Color"])
            o.data.materials.append(m)
        print(f"render_cycles_imported.py: diagnosis: the glTF default material on {len(bare)} bare objects "
              f"({', '.join(o.name + ': ' + str([a.name for a in o.data.color_attributes]) for o in bare)})")


def set_sky(sky):
    world = bpy.context.scene.world
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = tuple(sky) + (1.0,)
    background.inputs["Strength"].default_value = 1.0 if any(c > 0 for c in sky) else 0.0
    world.color = tuple(sky)


def main():
    args = parse_args()
    try:
        sky = [float(v) for v in args.sky.split(",")]
    except ValueError:
        sky = []
    if len(sky) != 3 or min(sky) < 0:
        fail("--sky must be R,G,B (three non-negative numbers)")
    clear_startup_scene()
    import_as_blender_does(args.scene)
    if args.no_normal_map:
        for m in bpy.data.materials:
            for n in (m.node_tree.nodes if m.use_nodes else []):
                if n.type == "BSDF_PRINCIPLED":
                    for link in list(n.inputs["Normal"].links):
                        m.node_tree.links.remove(link)
        print("render_cycles_imported.py: diagnosis: normal maps unlinked")
    if args.lambert:
        lambert_control()
    for p in [n for m in bpy.data.materials if m.use_nodes for n in m.node_tree.nodes if n.type == "BSDF_PRINCIPLED"]:
        if args.specular_zero:
            for link in list(p.inputs["Specular"].links):
                p.id_data.links.remove(link)
            p.inputs["Specular"].default_value = 0.0
    diagnoses(args)
    set_sky(sky)
    configure(args)
    render_and_report(args)


if __name__ == "__main__":
    run_in_blender(main)
