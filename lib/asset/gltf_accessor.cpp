#include "asset/gltf_accessor.h"

#include <cmath>
#include <cstring>

#include <tiny_gltf.h>

#include "base/errors.h"

namespace crowdprof {

namespace {

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

const char* type_name(int components) {
  switch (components) {
    case 1:
      return "SCALAR";
    case 3:
      return "VEC3";
    case 4:
      return "VEC4";
    case 16:
      return "MAT4";
    default:
      return "?";
  }
}

template <typename T>
T load(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

}  // namespace

AccessorReader::Layout AccessorReader::layout(int index, int components, const std::string& what) const {
  auto fail = [&](const std::string& why) { throw InputError(file, what + ": " + why); };
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
    fail("accessor " + std::to_string(index) + " does not exist (" + std::to_string(model.accessors.size()) +
         " accessors)");
  const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
  std::string name = "accessor " + std::to_string(index);
  if (component_count(a.type) != components) fail(name + " is not " + type_name(components));
  if (a.sparse.isSparse) fail(name + " is sparse, which crowdprof does not read");
  int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  if (size <= 0) fail(name + " has unknown component type " + std::to_string(a.componentType));
  if (a.count == 0) fail(name + " is empty");
  if (a.count > kMaxAccessorElements)
    fail(name + " claims " + std::to_string(a.count) + " elements; refused as absurd");
  uint64_t element = uint64_t(size) * uint64_t(components);
  if (a.bufferView < 0) fail(name + " has no buffer view");
  if (static_cast<size_t>(a.bufferView) >= model.bufferViews.size())
    fail(name + " names buffer view " + std::to_string(a.bufferView) + ", which does not exist");
  const tinygltf::BufferView& v = model.bufferViews[static_cast<size_t>(a.bufferView)];
  std::string view_name = "buffer view " + std::to_string(a.bufferView);
  if (v.buffer < 0 || static_cast<size_t>(v.buffer) >= model.buffers.size())
    fail(view_name + " names buffer " + std::to_string(v.buffer) + ", which does not exist");
  const tinygltf::Buffer& b = model.buffers[static_cast<size_t>(v.buffer)];
  // Offsets come from the file and may be near 2^64: compare without adding them.
  if (v.byteOffset > b.data.size() || v.byteLength > b.data.size() - v.byteOffset)
    fail(view_name + " reaches past the end of buffer " + std::to_string(v.buffer) + " (bytes " +
         std::to_string(v.byteOffset) + " + " + std::to_string(v.byteLength) + " of " + std::to_string(b.data.size()) +
         ")");
  uint64_t stride = v.byteStride ? uint64_t(v.byteStride) : element;
  if (stride < element) fail(view_name + " has a stride smaller than " + name + "'s elements");
  // count <= 2^24 and stride <= 2^8 here, so the span cannot overflow.
  uint64_t span = stride * (a.count - 1) + element;
  if (a.byteOffset > v.byteLength || span > v.byteLength - a.byteOffset)
    fail(name + " reads past the end of " + view_name + " (bytes " + std::to_string(a.byteOffset) + " + " +
         std::to_string(span) + " of " + std::to_string(v.byteLength) + ")");
  return {b.data.data() + v.byteOffset + a.byteOffset,
          a.count,
          static_cast<size_t>(stride),
          a.componentType,
          components,
          a.normalized};
}

size_t AccessorReader::count(int index, int components, const std::string& what) const {
  return layout(index, components, what).count;
}

std::vector<float> AccessorReader::floats(int index, int components, const std::string& what) const {
  Layout l = layout(index, components, what);
  std::vector<float> out(l.count * static_cast<size_t>(components));
  for (size_t e = 0; e < l.count; ++e) {
    const unsigned char* p = l.data + e * l.stride;
    for (int c = 0; c < components; ++c) {
      float value = 0.0f;
      switch (l.component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
          value = load<float>(p + 4 * c);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
          float raw = load<uint8_t>(p + c);
          value = l.normalized ? raw / 255.0f : raw;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          float raw = load<uint16_t>(p + 2 * c);
          value = l.normalized ? raw / 65535.0f : raw;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
          float raw = load<int8_t>(p + c);
          value = l.normalized ? std::max(raw / 127.0f, -1.0f) : raw;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
          float raw = load<int16_t>(p + 2 * c);
          value = l.normalized ? std::max(raw / 32767.0f, -1.0f) : raw;
          break;
        }
        default:
          throw InputError(file, what + ": accessor " + std::to_string(index) + " has component type " +
                                     std::to_string(l.component_type) + ", not one that holds these values");
      }
      if (!std::isfinite(value))
        throw InputError(file, what + ": accessor " + std::to_string(index) + " element " + std::to_string(e) +
                                   " holds " + (std::isnan(value) ? "NaN" : "Inf"));
      out[e * static_cast<size_t>(components) + static_cast<size_t>(c)] = value;
    }
  }
  return out;
}

std::vector<uint32_t> AccessorReader::uints(int index, int components, const std::string& what) const {
  Layout l = layout(index, components, what);
  std::vector<uint32_t> out(l.count * static_cast<size_t>(components));
  for (size_t e = 0; e < l.count; ++e) {
    const unsigned char* p = l.data + e * l.stride;
    for (int c = 0; c < components; ++c) {
      uint32_t value = 0;
      switch (l.component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          value = load<uint8_t>(p + c);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
          value = load<uint16_t>(p + 2 * c);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
          value = load<uint32_t>(p + 4 * c);
          break;
        default:
          throw InputError(file, what + ": accessor " + std::to_string(index) +
                                     " must hold unsigned integers, has component type " +
                                     std::to_string(l.component_type));
      }
      out[e * static_cast<size_t>(components) + static_cast<size_t>(c)] = value;
    }
  }
  return out;
}

}  // namespace crowdprof
