// The checks of where a glTF file's data lies, before tinygltf reads it (gltf_precheck_uris.cpp),
// for read_and_precheck (gltf_precheck.cpp): buffer and image URIs, and the bufferViews of
// images; and the one way the loader opens a file (the scene, its buffers and images), used
// again by the file callbacks tinygltf reads through (gltf_loader.cpp). Internal to the glTF
// checks; not part of the article: malformed files made one line.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

namespace pt::gltf::detail {

// The largest file the loader reads: the scene file (.gltf or .glb) and each external buffer
// or image. Each is read whole into memory, and a .gltf's JSON is parsed into trees several
// times its size (nlohmann's, then tinygltf's), so this bounds the memory before any is spent.
inline constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t(1) << 30;  // 1 GiB

// The root that buffers and images must lie in: the folder of the scene file as given (""
// is the working directory), made canonical (symbolic links and ".." resolved).
std::string scene_root(const std::string& base_dir);

// Whether the canonical `path` lies inside the canonical folder `root`.
bool inside_root(const std::string& path, const std::string& root);

// Reads a regular file of at most kMaxSceneFileBytes whole. Anything else (no such file, a
// folder, a FIFO, a device, a socket, too large, unreadable) calls refuse(reason) with a reason
// such as "is a FIFO, not a regular file", which must throw. Opened without blocking and checked
// on the open descriptor, so a FIFO is never waited on and a file swapped after the check is not
// read.
std::vector<unsigned char> read_regular_file(const std::string& path,
                                             const std::function<void(const std::string&)>& refuse);

// What tinygltf's file callbacks know: the scene's folder as given (buffer URIs are relative
// to it; "" is the working directory) and the root every file must resolve into.
struct SceneFolder {
  std::string base_dir;  // as given
  std::string root;      // scene_root(base_dir)
  std::string file;      // the scene file, for messages
};

// The file callbacks tinygltf reads buffers and images through: a file exists only in the
// scene's folder (by stat: a FIFO is not opened to find out), and is read only when it resolves
// inside folder->root, by read_regular_file; anything else throws pt::Error (exit 3) naming it.
// check_uris has said what is wrong with each URI already; these hold should a file change
// in between.
tinygltf::FsCallbacks scene_folder_callbacks(SceneFolder* folder);

// Buffer and image URIs stay inside scene_root(base_dir) once resolved (symbolic links
// included); the files they name that exist are regular and at most kMaxSceneFileBytes;
// external buffers must exist, be as long as their byteLength and not be Git LFS pointers;
// a data: URI must hold byteLength bytes.
void check_uris(const nlohmann::json& doc, const std::string& base_dir, const std::string& file);

// tinygltf hands &buffer.data[view.byteOffset] to the image loader unchecked: check the
// bufferViews of images against the buffers' stated lengths before it runs.
void check_image_views(const nlohmann::json& doc, const std::string& file);

}  // namespace pt::gltf::detail
