// The skinned fixture with its primitive compressed by Draco (KHR_draco_mesh_compression),
// encoded here with draco::Encoder so the Draco tests need no sample files.
#pragma once

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include "gltf_fixture.h"

namespace crowdprof::test {

struct DracoFixture : SkinnedFixture {
  int draco_view = -1;

  DracoFixture() {
    draco::Mesh mesh;
    const size_t n = 6;
    mesh.set_num_points(static_cast<uint32_t>(n));
    auto add = [&](draco::GeometryAttribute::Type type, int accessor, int components, draco::DataType data_type,
                   size_t component_size) {
      draco::GeometryAttribute attribute;
      attribute.Init(type, nullptr, static_cast<uint8_t>(components), data_type, false,
                     static_cast<int64_t>(component_size) * components, 0);
      int id = mesh.AddAttribute(attribute, true, static_cast<uint32_t>(n));
      for (size_t v = 0; v < n; ++v)
        mesh.attribute(id)->SetAttributeValue(
            draco::AttributeValueIndex(static_cast<uint32_t>(v)),
            bytes_of(accessor) + v * component_size * static_cast<size_t>(components));
      return static_cast<int>(mesh.attribute(id)->unique_id());
    };
    int position = add(draco::GeometryAttribute::POSITION, positions, 3, draco::DT_FLOAT32, 4);
    int normal = add(draco::GeometryAttribute::NORMAL, normals, 3, draco::DT_FLOAT32, 4);
    int joint = add(draco::GeometryAttribute::GENERIC, joints, 4, draco::DT_UINT16, 2);
    int weight = add(draco::GeometryAttribute::GENERIC, weights, 4, draco::DT_FLOAT32, 4);
    const auto* index = reinterpret_cast<const uint16_t*>(bytes_of(indices));
    for (size_t t = 0; t < 4; ++t)
      mesh.AddFace(
          {draco::PointIndex(index[3 * t]), draco::PointIndex(index[3 * t + 1]), draco::PointIndex(index[3 * t + 2])});
    draco::Encoder encoder;
    encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);  // keeps the vertex order
    draco::EncoderBuffer encoded;
    if (!encoder.EncodeMeshToBuffer(mesh, &encoded).ok())
      throw std::runtime_error("Draco could not encode the fixture");
    draco_view = add_view(encoded.data(), encoded.size());
    // The primitive's accessors now describe what Draco decodes, and hold no view.
    for (int a : {positions, normals, joints, weights, indices}) accessor(a).erase("bufferView");
    json["meshes"][0]["primitives"][0]["extensions"] = {
        {"KHR_draco_mesh_compression",
         {{"bufferView", draco_view},
          {"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"JOINTS_0", joint}, {"WEIGHTS_0", weight}}}}}};
    json["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    json["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  }

  unsigned char* draco_bytes() {
    return bin.data() + json["bufferViews"][static_cast<size_t>(draco_view)]["byteOffset"].get<size_t>();
  }
  size_t draco_size() const { return json["bufferViews"][static_cast<size_t>(draco_view)]["byteLength"].get<size_t>(); }
};

}  // namespace crowdprof::test
