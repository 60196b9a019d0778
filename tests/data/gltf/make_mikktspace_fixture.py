# The MikkTSpace fixture (issue #46): a smooth UV sphere and a bent, twisted strip with Blender's
# own MikkTSpace tangents written as TANGENT, against which tests/common/scene/test_gltf_tangents.cpp
# checks the tangents the loader makes where a file has none (common/scene/gltf_tangents.cpp).
# Not part of the article: test data. Run by Debian's Blender (bench-only tool, not a build step):
#   blender -b --factory-startup --python tests/data/gltf/make_mikktspace_fixture.py -- \
#       --out tests/data/gltf/mikktspace_tangents.gltf
import math
import os
import sys

import bpy


def strip():
    """A 6 x 2 quad strip bent into a quarter cylinder and twisted, smooth-shaded, with a UV map
    stretched unevenly along it (so dP/du turns from vertex to vertex)."""
    verts, faces, uvs = [], [], []
    cols, rows = 6, 2
    for j in range(rows + 1):
        for i in range(cols + 1):
            a = 0.5 * math.pi * i / cols
            twist = 0.4 * (j / rows - 0.5) * i / cols
            verts.append((math.cos(a) + twist, math.sin(a), j / rows * 0.8 + 0.2 * math.sin(a)))
    for j in range(rows):
        for i in range(cols):
            k = j * (cols + 1) + i
            faces.append((k, k + 1, k + cols + 2, k + cols + 1))
    mesh = bpy.data.meshes.new("strip")
    mesh.from_pydata(verts, [], faces)
    uv = mesh.uv_layers.new(name="UVMap")
    for poly in mesh.polygons:
        for li in poly.loop_indices:
            k = mesh.loops[li].vertex_index
            i, j = k % (cols + 1), k // (cols + 1)
            uv.data[li].uv = ((i / cols) ** 1.3, j / rows + 0.1 * i / cols)
    for poly in mesh.polygons:
        poly.use_smooth = True
    obj = bpy.data.objects.new("strip", mesh)
    obj.location = (3.0, 0.0, 0.0)
    bpy.context.collection.objects.link(obj)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out = os.path.abspath(argv[argv.index("--out") + 1])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    # 8 segments x 5 rings: 64 triangles, fans at the poles, a UV seam.
    bpy.ops.mesh.primitive_uv_sphere_add(segments=8, ring_count=5, radius=1.0, calc_uvs=True)
    bpy.ops.object.shade_smooth()
    strip()
    # A material with a normal map, so that the file says why it has tangents.
    mat = bpy.data.materials.new("normal_mapped")
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    image = bpy.data.images.new("flat_normals", 2, 2)
    image.pixels = [0.5, 0.5, 1.0, 1.0] * 4
    image.colorspace_settings.name = "Non-Color"
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image
    nmap = nodes.new("ShaderNodeNormalMap")
    mat.node_tree.links.new(tex.outputs["Color"], nmap.inputs["Color"])
    mat.node_tree.links.new(nmap.outputs["Normal"], nodes["Principled BSDF"].inputs["Normal"])
    for obj in bpy.data.objects:
        obj.data.materials.append(mat)
    result = bpy.ops.export_scene.gltf(
        filepath=out, export_format="GLTF_EMBEDDED", export_normals=True, export_texcoords=True,
        export_tangents=True, export_materials="EXPORT", export_image_format="AUTO", export_apply=True,
        export_yup=True, export_cameras=False, export_lights=False, export_animations=False)
    if "FINISHED" not in result:
        print(f"make_mikktspace_fixture.py: export failed: {result}", file=sys.stderr)
        sys.stdout.flush()
        os._exit(1)
    print(f"make_mikktspace_fixture.py: Blender {bpy.app.version_string} wrote {out}")
    sys.stdout.flush()
    os._exit(0)


if __name__ == "__main__":
    try:
        main()
    except Exception:  # noqa: BLE001 (Blender ignores a script's failure in -b mode otherwise)
        import traceback
        traceback.print_exc()
        sys.stderr.flush()
        os._exit(1)
