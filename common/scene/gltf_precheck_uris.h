// The checks of where a glTF file's data lies, before tinygltf reads it (gltf_precheck_uris.cpp),
// for read_and_precheck (gltf_precheck.cpp): buffer and image URIs, and the bufferViews of
// images. Internal to the glTF checks; not part of the article: malformed files made one line.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace pt::gltf::detail {

// Buffer and image URIs stay inside the scene's folder; external buffers must exist and
// hold data, not a Git LFS pointer.
void check_uris(const nlohmann::json& doc, const std::string& base_dir, const std::string& file);

// tinygltf hands &buffer.data[view.byteOffset] to the image loader unchecked: check the
// bufferViews of images against the buffers' stated lengths before it runs.
void check_image_views(const nlohmann::json& doc, const std::string& file);

}  // namespace pt::gltf::detail
