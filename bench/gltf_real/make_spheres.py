# A scripted Blender scene exported by Blender's own glTF exporter for the bench's comparison
# against Cycles (issue 46): plastics and metals over a roughness range, flat-shaded icospheres
# (so no smooth normals are needed), a sun, a camera. Not part of the article: bench machinery.
#   blender -b --factory-startup --python bench/gltf_real/make_spheres.py -- --out X.gltf
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import export_blend  # noqa: E402  (its main() writes the file with the bench's exporter options)


def material(name, colour, metallic, roughness):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = colour + (1.0,)
    p.inputs["Metallic"].default_value = metallic
    p.inputs["Roughness"].default_value = roughness
    return m


def build():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    bpy.ops.mesh.primitive_plane_add(size=12, location=(0, 0, 0))
    bpy.context.object.data.materials.append(material("floor", (0.5, 0.5, 0.5), 0.0, 0.6))
    plastics = [(0.8, 0.1, 0.1), (0.1, 0.6, 0.15), (0.1, 0.2, 0.8)]
    metals = [(1.0, 0.77, 0.34), (0.95, 0.64, 0.54), (0.91, 0.92, 0.92)]  # gold, copper, silver
    for row, (colours, metallic) in enumerate(((plastics, 0.0), (metals, 1.0))):
        for i, (colour, roughness) in enumerate(zip(colours, (0.1, 0.4, 0.8))):
            bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=0.8,
                                                  location=(2.0 * (i - 1), 2.0 * row - 1.0, 0.8))
            bpy.ops.object.shade_flat()
            bpy.context.object.data.materials.append(
                material(f"{'metal' if metallic else 'plastic'}_r{roughness}", colour, metallic, roughness))
    bpy.ops.object.light_add(type="SUN", rotation=(math.radians(40), 0, math.radians(30)))
    bpy.context.object.data.energy = 3.0
    bpy.ops.object.camera_add(location=(0, -8.5, 5.0), rotation=(math.radians(62), 0, 0))
    bpy.context.object.data.lens = 35
    bpy.context.scene.camera = bpy.context.object
    bpy.context.scene.render.resolution_x, bpy.context.scene.render.resolution_y = 160, 90


if __name__ == "__main__":
    try:
        build()
    except Exception:  # noqa: BLE001 (Blender ignores a script's failure in -b mode otherwise)
        import traceback
        traceback.print_exc()
        sys.stderr.flush()
        os._exit(1)
    export_blend.main()
