# Exports a .blend scene (or a gzip-compressed one) to glTF with Blender's own exporter, for the
# bench's real-file comparison against Cycles (issue 46, bench/cycles/compare_gltf.py).
# Not part of the article: bench machinery. Run by Blender:
#   blender -b --factory-startup FILE.blend --python bench/gltf_real/export_blend.py -- --out X.gltf
import argparse
import os
import sys

import bpy


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="export_blend.py")
    p.add_argument("--out", required=True, help="the .gltf (separate .bin and textures) or .glb to write")
    p.add_argument("--tangents", action="store_true",
                   help="also write Blender's MikkTSpace tangents (TANGENT; bench/cycles/gltf_residuals.py)")
    args = p.parse_args(argv)
    out = os.path.abspath(args.out)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    # Every option that decides what the file holds is named, at the 3.4 exporter's defaults but
    # for cameras and lights (off by default), so a later Blender does not change the file.
    result = bpy.ops.export_scene.gltf(
        filepath=out, export_format="GLB" if out.endswith(".glb") else "GLTF_SEPARATE",
        export_cameras=True, export_lights=True, convert_lighting_mode="SPEC",
        export_apply=True, export_yup=True, export_normals=True, export_texcoords=True,
        export_tangents=args.tangents, export_colors=True, export_materials="EXPORT",
        export_image_format="AUTO", use_mesh_edges=False, use_mesh_vertices=False,
        export_animations=False, use_selection=False, use_visible=False, use_renderable=False)
    if "FINISHED" not in result:
        print(f"export_blend.py: export failed: {result}", file=sys.stderr)
        sys.stdout.flush()
        os._exit(1)
    print(f"export_blend.py: Blender {bpy.app.version_string} wrote {out}")
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
