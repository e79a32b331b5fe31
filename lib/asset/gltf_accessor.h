// Bounds-checked reads of glTF accessors. Every index and byte range is checked
// against what the file really holds before a byte is read; a failure throws
// InputError naming the accessor, view or buffer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace crowdprof {

// Larger counts are refused as absurd: the largest useful character is far smaller.
inline constexpr uint64_t kMaxAccessorElements = 1u << 24;

// The accessor's element count after checking that it can be read.
struct AccessorReader {
  const tinygltf::Model& model;
  const std::string& file;  // for messages

  // Elements of accessor `index`; checks type (SCALAR=1, VEC3=3, VEC4=4, MAT4=16 components).
  size_t count(int index, int components, const std::string& what) const;

  // As floats; integer components are converted as the glTF spec says (normalised
  // when the accessor says so). Rejects NaN and Inf.
  std::vector<float> floats(int index, int components, const std::string& what) const;

  // As unsigned integers (indices, joint indices): unsigned byte/short/int only.
  std::vector<uint32_t> uints(int index, int components, const std::string& what) const;

 private:
  struct Layout {
    const unsigned char* data;
    size_t count, stride;
    int component_type, components;
    bool normalized;
  };
  Layout layout(int index, int components, const std::string& what) const;
};

}  // namespace crowdprof
