// An accessor's elements read safely (gltf_elements.h): bufferViews checked against their
// buffers, spans against their bufferViews under overflow checks, and glTF 2.0's "Sparse
// Accessors" applied. For the glTF loader of the contract (README.md) "Scenes".
#include "common/scene/gltf_elements.h"

#include <algorithm>
#include <cstring>

namespace pt::gltf::detail {

namespace {

// A sparse accessor without a bufferView starts as zeros that the file only states the
// count of: a few bytes of JSON must not ask for gigabytes.
constexpr std::uint64_t kMaxZeroFill = std::uint64_t(1) << 28;  // 256 MiB

// The bufferView `index` checked against its buffer; `user` names what reads it.
const tinygltf::BufferView& checked_view(const tinygltf::Model& model, int index, const std::string& file,
                                         const std::string& user) {
  check_index(file, index, model.bufferViews.size(), user + ".bufferView", "bufferViews");
  const tinygltf::BufferView& v = model.bufferViews[index];
  std::string view = "bufferViews[" + std::to_string(index) + "]";
  check_index(file, v.buffer, model.buffers.size(), view + ".buffer", "buffers");
  std::uint64_t view_end = 0, has = model.buffers[v.buffer].data.size();
  bool overflow = __builtin_add_overflow(std::uint64_t(v.byteOffset), std::uint64_t(v.byteLength), &view_end);
  if (overflow || view_end > has) {
    fail(file, view + " (used by " + user + ") runs past buffers[" + std::to_string(v.buffer) + "] (" +
                   need_text(overflow, view_end, has) + "): " + kReexport);
  }
  return v;
}

// Fails unless `count` elements of `size` bytes, `stride` apart from byteOffset `offset`,
// fit in the bufferView `view` that `user` reads.
void check_span(const tinygltf::BufferView& v, int view, std::uint64_t offset, std::uint64_t stride,
                std::uint64_t count, std::uint64_t size, const std::string& file, const std::string& user) {
  std::uint64_t needed = 0;  // offset + stride * (count - 1) + size
  bool overflow = __builtin_mul_overflow(stride, count - 1, &needed) ||
                  __builtin_add_overflow(needed, offset, &needed) ||
                  __builtin_add_overflow(needed, size, &needed);
  if (overflow || needed > v.byteLength) {
    fail(file, user + " runs past bufferViews[" + std::to_string(view) + "] (" +
                   need_text(overflow, needed, v.byteLength) + "): " + kReexport);
  }
}

const unsigned char* view_data(const tinygltf::Model& model, const tinygltf::BufferView& v) {
  return model.buffers[v.buffer].data.data() + v.byteOffset;
}

// The elements in the accessor's bufferView, read in place.
Elements dense_elements(const tinygltf::Model& model, const tinygltf::Accessor& a, std::size_t element_size,
                        const std::string& file, const std::string& what) {
  if (a.bufferView < 0) fail(file, what + " has no bufferView (no data): " + std::string(kReexport));
  const tinygltf::BufferView& v = checked_view(model, a.bufferView, file, what);
  std::size_t stride = v.byteStride != 0 ? v.byteStride : element_size;
  if (stride < element_size) {
    fail(file, "bufferViews[" + std::to_string(a.bufferView) + "].byteStride " + str(stride) +
                   " is smaller than an element of " + what + " (" + str(element_size) +
                   " bytes): " + kReexport);
  }
  check_span(v, a.bufferView, a.byteOffset, stride, a.count, element_size, file, what);
  return {view_data(model, v) + a.byteOffset, stride, a.count, {}};
}

// What a sparse accessor starts from: its bufferView's elements, or zeros without one.
std::vector<unsigned char> sparse_base(const tinygltf::Model& model, const tinygltf::Accessor& a,
                                       std::size_t element_size, const std::string& file,
                                       const std::string& what) {
  std::uint64_t bytes = 0;
  bool overflow = __builtin_mul_overflow(std::uint64_t(a.count), std::uint64_t(element_size), &bytes);
  if (a.bufferView < 0) {
    if (overflow || bytes > kMaxZeroFill) {
      fail(file, what + " is sparse without a bufferView and has count " + str(a.count) +
                     ", more zeros than this renderer fills in (256 MiB): re-export it with its data in a "
                     "bufferView");
    }
    return std::vector<unsigned char>(bytes, 0);
  }
  Elements dense = dense_elements(model, a, element_size, file, what);  // bounds count by the buffer
  std::vector<unsigned char> packed(bytes);
  for (std::size_t i = 0; i < a.count; ++i) std::memcpy(&packed[i * element_size], dense.at(i), element_size);
  return packed;
}

// One of the two arrays of a sparse accessor (`user` is "... sparse.indices" or "... sparse.values"):
// `count` elements of `size` bytes, tightly packed from byteOffset in their bufferView.
const unsigned char* sparse_array(const tinygltf::Model& model, int view, int offset, std::size_t size,
                                  std::size_t count, const std::string& file, const std::string& user) {
  const tinygltf::BufferView& v = checked_view(model, view, file, user);
  if (offset < 0) fail(file, user + ".byteOffset is negative: " + std::string(kReexport));
  check_span(v, view, std::uint64_t(offset), size, count, size, file, user);
  return view_data(model, v) + offset;
}

// glTF 2.0 "Sparse Accessors": sparse.count indices, strictly increasing and below the
// accessor's count, each naming the element that the value at the same position replaces.
void apply_sparse(const tinygltf::Model& model, const tinygltf::Accessor& a, std::size_t element_size,
                  std::vector<unsigned char>& packed, const std::string& file, const std::string& what) {
  const auto& sparse = a.sparse;
  if (sparse.count <= 0 || std::size_t(sparse.count) > a.count) {
    fail(file, what + " has sparse.count " + std::to_string(sparse.count) + "; it must be 1 to its count (" +
                   str(a.count) + "): " + kReexport);
  }
  std::size_t count = std::size_t(sparse.count), index_size = unsigned_size(sparse.indices.componentType);
  if (index_size == 0) {
    fail(file, what + " sparse.indices.componentType " + std::to_string(sparse.indices.componentType) +
                   " is not UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT: " + kReexport);
  }
  const unsigned char* indices = sparse_array(model, sparse.indices.bufferView, sparse.indices.byteOffset,
                                              index_size, count, file, what + " sparse.indices");
  const unsigned char* values = sparse_array(model, sparse.values.bufferView, sparse.values.byteOffset,
                                             element_size, count, file, what + " sparse.values");
  for (std::size_t k = 0; k < count; ++k) {
    std::uint32_t index = read_unsigned(indices + k * index_size, index_size);
    std::string entry = what + " sparse index " + str(k) + " is " + str(index);
    if (index >= a.count) fail(file, entry + ", past its count (" + str(a.count) + "): " + kReexport);
    std::uint32_t previous = k > 0 ? read_unsigned(indices + (k - 1) * index_size, index_size) : 0;
    if (k > 0 && index <= previous) {
      fail(file, entry + ", not above the one before it (" + str(previous) +
                     "); sparse indices must strictly increase: " + kReexport);
    }
    std::memcpy(&packed[std::size_t(index) * element_size], values + k * element_size, element_size);
  }
}

}  // namespace

const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index, const std::string& file,
                                      const std::string& what) {
  check_index(file, index, model.accessors.size(), what, "accessors");
  return model.accessors[index];
}

Elements read_elements(const tinygltf::Model& model, int index, std::size_t element_size,
                       const std::string& file, const std::string& what) {
  const tinygltf::Accessor& a = accessor_at(model, index, file, what);
  if (a.count == 0) fail(file, what + " has count 0; a primitive needs vertices: " + std::string(kReexport));
  if (!a.sparse.isSparse) return dense_elements(model, a, element_size, file, what);
  Elements elements{nullptr, element_size, a.count, sparse_base(model, a, element_size, file, what)};
  apply_sparse(model, a, element_size, elements.packed, file, what);
  return elements;
}


}  // namespace pt::gltf::detail
