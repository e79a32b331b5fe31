#include "base/backend_choice.h"

namespace crowdprof {

std::optional<BackendChoice> parse_backend(std::string_view name) {
  if (name == "auto") return BackendChoice::Auto;
  if (name == "egl") return BackendChoice::Egl;
  if (name == "osmesa") return BackendChoice::OsMesa;
  if (name == "none") return BackendChoice::None;
  return std::nullopt;
}

}  // namespace crowdprof
