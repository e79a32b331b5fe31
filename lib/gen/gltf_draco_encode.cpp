#include "gen/gltf_draco_encode.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

namespace crowdprof {
namespace {

template <typename T>
int add_attribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, draco::DataType data_type, int components,
                  const T* values, size_t count) {
  draco::GeometryAttribute ga;
  const int64_t stride = static_cast<int64_t>(sizeof(T));
  ga.Init(type, nullptr, static_cast<int8_t>(components), data_type, false, stride, 0);
  const int id = mesh.AddAttribute(ga, true, static_cast<uint32_t>(count));
  draco::PointAttribute* attribute = mesh.attribute(id);
  for (size_t i = 0; i < count; ++i)
    attribute->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)), &values[i]);
  return static_cast<int>(attribute->unique_id());
}

constexpr int kWeightBits = 12;

// Draco stores component c of a weight as round((w - min_c) / delta), with
// min_c the component's minimum and delta = (largest component range) / 4095,
// so four weights that summed to 1 come back summing to 1 +- 4 delta / 2: a
// fix-up for every loader. Moving each vertex's weights onto that grid, with
// steps that add up to (1 - sum of min_c) / delta, keeps the sum at 1 after
// decoding. Weights the grid cannot keep whole are left as they are.
std::vector<glm::vec4> snap_weights(std::span<const glm::vec4> weights) {
  std::vector<glm::vec4> out(weights.begin(), weights.end());
  if (weights.empty()) return out;
  glm::vec4 lo = weights[0], hi = weights[0];
  for (const glm::vec4& w : weights) lo = glm::min(lo, w), hi = glm::max(hi, w);
  float range = 0.0f;
  for (int c = 0; c < 4; ++c) range = std::max(range, hi[c] - lo[c]);
  if (!(range > 0.0f)) return out;
  const double delta = double(range) / double((1 << kWeightBits) - 1);
  const double steps = (1.0 - (double(lo[0]) + lo[1] + lo[2] + lo[3])) / delta;
  const double want = std::round(steps);
  if (std::abs(steps - want) > 1e-3) return out;
  for (glm::vec4& w : out) {
    std::array<double, 4> q, rest;
    double sum = 0.0;
    for (size_t c = 0; c < 4; ++c) {
      double x = (w[int(c)] - lo[int(c)]) / delta;
      q[c] = std::floor(x);
      rest[c] = x - q[c];
      sum += q[c];
    }
    const double missing = want - sum;
    if (missing < 0.0 || missing > 3.0) continue;  // weights far from summing to 1
    std::array<size_t, 4> order = {0, 1, 2, 3};
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return rest[a] > rest[b]; });
    for (size_t i = 0; i < static_cast<size_t>(missing); ++i) q[order[i]] += 1.0;
    for (size_t c = 0; c < 4; ++c) w[int(c)] = static_cast<float>(lo[int(c)] + q[c] * delta);
  }
  return out;
}

}  // namespace

DracoPrimitive encode_draco_primitive(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                      std::span<const glm::u16vec4> joints, std::span<const glm::vec4> weights,
                                      std::span<const uint32_t> indices, bool joints_u8) {
  const size_t n = positions.size();
  draco::Mesh mesh;
  mesh.set_num_points(static_cast<uint32_t>(n));
  mesh.SetNumFaces(indices.size() / 3);
  for (size_t f = 0; f < indices.size() / 3; ++f)
    mesh.SetFace(draco::FaceIndex(static_cast<uint32_t>(f)),
                 {draco::PointIndex(indices[3 * f]), draco::PointIndex(indices[3 * f + 1]),
                  draco::PointIndex(indices[3 * f + 2])});

  DracoPrimitive out;
  out.position_id = add_attribute(mesh, draco::GeometryAttribute::POSITION, draco::DT_FLOAT32, 3, positions.data(), n);
  if (!normals.empty())
    out.normal_id = add_attribute(mesh, draco::GeometryAttribute::NORMAL, draco::DT_FLOAT32, 3, normals.data(), n);
  if (!joints.empty()) {
    if (joints_u8) {
      std::vector<glm::u8vec4> narrow(joints.begin(), joints.end());
      out.joints_id = add_attribute(mesh, draco::GeometryAttribute::GENERIC, draco::DT_UINT8, 4, narrow.data(), n);
    } else {
      out.joints_id = add_attribute(mesh, draco::GeometryAttribute::GENERIC, draco::DT_UINT16, 4, joints.data(), n);
    }
  }
  if (!weights.empty()) {
    std::vector<glm::vec4> snapped = snap_weights(weights);
    out.weights_id = add_attribute(mesh, draco::GeometryAttribute::GENERIC, draco::DT_FLOAT32, 4, snapped.data(), n);
  }

  // Quantisation applies to float attributes only: the joint indices, being
  // integers, are compressed without loss.
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::GENERIC, kWeightBits);
  encoder.SetSpeedOptions(5, 5);
  draco::EncoderBuffer buffer;
  draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!status.ok()) throw std::runtime_error(std::string("Draco encoding failed: ") + status.error_msg());
  out.bytes.assign(buffer.data(), buffer.data() + buffer.size());

  // The accessors must describe what a decoder will produce, so decode it.
  draco::DecoderBuffer in;
  in.Init(buffer.data(), buffer.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&in);
  if (!decoded.ok())
    throw std::runtime_error(std::string("Draco cannot decode its own stream: ") + decoded.status().error_msg());
  const draco::Mesh& back = *decoded.value();
  out.points = back.num_points();
  out.faces = back.num_faces();
  const draco::PointAttribute* pos = back.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  for (draco::PointIndex i(0); i < back.num_points(); ++i) {
    glm::vec3 p;
    pos->ConvertValue<float, 3>(pos->mapped_index(i), &p[0]);
    out.min = i.value() == 0 ? p : glm::min(out.min, p);
    out.max = i.value() == 0 ? p : glm::max(out.max, p);
  }
  return out;
}

}  // namespace crowdprof
