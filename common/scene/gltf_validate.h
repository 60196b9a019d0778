// Checks of a glTF 2.0 file that tinygltf leaves to its user, for the loader of the contract
// (README.md) "Scenes" (gltf_loader.cpp): the file and its JSON before tinygltf reads them
// (gltf_precheck.cpp), references and the node tree after (gltf_validate.cpp), and every accessor
// a primitive reads, sparse ones included (gltf_accessors.cpp). Not part of the article:
// malformed files made one line.
#pragma once

#include <cfloat>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

namespace pt::gltf {

// The usual advice at the end of a message about a malformed file: a violation of the
// specification, which exporting again with the same tool would repeat (damaged bytes, where a
// fresh copy helps, are said as such where they are found: gltf_precheck.cpp, gltf_images.cpp).
inline constexpr const char* kReexport =
    "this breaks the glTF 2.0 specification (the Khronos glTF-Validator reports it too): fix the file, or report "
    "it to the tool that wrote it";

// Throws pt::Error(kExitBadScene, "<file>: <message>"), the message made one line.
[[noreturn]] void fail(const std::string& file, const std::string& message);

// A JSON number as a finite 32-bit float within [lo, hi]; `where` is its JSON path.
float checked_float(const std::string& file, double value, const std::string& where, double lo = -FLT_MAX,
                    double hi = FLT_MAX);

struct SourceFile {
  std::vector<unsigned char> bytes;  // the whole file (a .glb cut to its stated length)
  bool binary = false;               // .glb
  std::string base_dir;              // the folder buffer URIs are relative to ("" = cwd)
};

// Reads the file and checks what tinygltf would otherwise trust: Git LFS pointers in place
// of the file or its buffers, the GLB container, the JSON syntax and integers,
// extensionsRequired (before any buffer is read), buffer and image URIs (they may not
// leave the scene's folder) and the bufferViews of images.
SourceFile read_and_precheck(const std::string& path);

// Names the unsupported extensions used (once), checks every reference between arrays and
// the node tree (one parent per node, no cycles, scenes list roots only). Returns each
// node's parent (-1 for a root).
std::vector<int> check_model(const tinygltf::Model& model, const std::string& file);

// The POSITION accessor of a triangle primitive, checked and read (sparse accessors
// applied, here and below); `what` names it in messages, e.g.
// "accessors[2] (POSITION of meshes[0].primitives[0])".
std::vector<glm::vec3> read_positions(const tinygltf::Model& model, int accessor, const std::string& file,
                                      const std::string& what);

// The indices accessor of a triangle primitive, each checked against vertex_count.
std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int accessor, std::size_t vertex_count,
                                        const std::string& file, const std::string& what);

// A TEXCOORD_n accessor: VEC2 of FLOAT, or of normalized UNSIGNED_BYTE / UNSIGNED_SHORT
// (read as c / 255, c / 65535); vertex_count entries (POSITION's count), each finite.
std::vector<glm::vec2> read_texcoords(const tinygltf::Model& model, int accessor, std::size_t vertex_count,
                                      const std::string& file, const std::string& what);

// A COLOR_n accessor: VEC3 or VEC4 of the same component types; VEC3 gets alpha 1.
std::vector<glm::vec4> read_colors(const tinygltf::Model& model, int accessor, std::size_t vertex_count,
                                   const std::string& file, const std::string& what);

// An EXT_mesh_gpu_instancing attribute: TRANSLATION and SCALE (components 3) VEC3 of FLOAT,
// ROTATION (components 4) VEC4 of FLOAT or of normalized BYTE / SHORT; `instances` entries, each
// finite; `components` floats an instance.
std::vector<float> read_instance_attribute(const tinygltf::Model& model, int accessor, int components,
                                           std::size_t instances, const std::string& file, const std::string& what);

}  // namespace pt::gltf
