// The packed skinned-vertex format (--vertex-format packed): what a GPU reads
// in 10 bytes a vertex instead of 24. Positions are quantised to 16 bits per
// axis in a box that holds every pose of the character (GL_UNSIGNED_SHORT,
// normalised: code / 65535 across the box); normals are 10:10:10:2 signed
// normalised (GL_INT_2_10_10_10_REV: x in bits 0-9, y in 10-19, z in 20-29,
// two's complement, value = code / 511; the 2-bit w is 0).
//
// These scalar functions are the definition; the SIMD kernels
// (skinning_kernels.cpp) compute the same codes from the floats they skinned,
// on every target, which skinning_test.cpp checks vertex by vertex.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

namespace crowdprof {

// Bytes one packed vertex takes: 3 x 16-bit position codes, one 32-bit normal.
constexpr size_t kPackedPositionBytes = 3 * sizeof(uint16_t);
constexpr size_t kPackedNormalBytes = sizeof(uint32_t);
constexpr size_t kPackedVertexBytes = kPackedPositionBytes + kPackedNormalBytes;
// ...against the float format's two vec3.
constexpr size_t kFloatVertexBytes = 2 * 3 * sizeof(float);

// The largest code of each format.
constexpr float kPositionCodeMax = 65535.0f;
constexpr float kNormalCodeMax = 511.0f;

// The box positions are quantised in: code = round((p - min) * scale), with
// scale = 65535 / (max - min) per axis (0 on an axis of no extent), clamped to
// [0, 65535]; decoded as min + code / 65535 * (max - min).
struct PositionQuantisation {
  glm::vec3 min{0.0f};
  glm::vec3 extent{0.0f};  // max - min
  glm::vec3 scale{0.0f};   // to codes

  // The largest decoding error of a position inside the box, per axis, in
  // model units: half a code's step, plus the float rounding of encoding and
  // decoding (a few ulps of the box's coordinates).
  glm::vec3 max_error() const;
};

// The quantisation of the box [min, max] (min <= max on every axis).
PositionQuantisation position_quantisation(glm::vec3 min, glm::vec3 max);

// One vertex's codes, x, y, z. Round to nearest, ties to even; NaN is not
// defined (a finite pose gives finite positions).
void quantise_position(const PositionQuantisation& q, glm::vec3 p, uint16_t out[3]);
glm::vec3 dequantise_position(const PositionQuantisation& q, const uint16_t code[3]);

// A normal's 10:10:10:2 word (each component clamped to [-1, 1], times 511,
// rounded to nearest, ties to even) and its decoded value, as GL decodes it.
uint32_t pack_normal(glm::vec3 n);
glm::vec3 unpack_normal(uint32_t word);

// The largest angle, in degrees, between a unit normal and its decoded packed
// word: each component is off by at most 0.5 / 511, so the decoded vector is
// within sqrt(3) * 0.5 / 511 of the normal, asin of which is 0.0971 degrees.
constexpr double kPackedNormalMaxErrorDegrees = 0.0972;

}  // namespace crowdprof
