#include "skinning/output_stores.h"

#include <atomic>
#include <cctype>

namespace crowdprof {
namespace {

std::atomic<OutputStores> g_stores{OutputStores::Auto};

bool equals_lowercase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
  return true;
}

}  // namespace

OutputStores output_stores() {
  return g_stores.load(std::memory_order_relaxed);
}

bool stream_skinned_output(uint64_t frame_output_bytes) {
  switch (output_stores()) {
    case OutputStores::Regular:
      return false;
    case OutputStores::Streaming:
      return true;
    case OutputStores::Auto:
      break;
  }
  return frame_output_bytes > kStreamOutputBytes;
}

const char* to_string(OutputStores stores) {
  switch (stores) {
    case OutputStores::Regular:
      return "regular";
    case OutputStores::Streaming:
      return "streaming";
    case OutputStores::Auto:
      break;
  }
  return "auto";
}

std::string force_output_stores(std::string_view name) {
  for (OutputStores s : {OutputStores::Auto, OutputStores::Regular, OutputStores::Streaming})
    if (equals_lowercase(name, to_string(s))) {
      g_stores.store(s, std::memory_order_relaxed);
      return {};
    }
  return "unknown store policy \"" + std::string(name) + "\": expected auto, regular or streaming";
}

}  // namespace crowdprof
