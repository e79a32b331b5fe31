#include "animation/binding.h"

#include <algorithm>

namespace crowdprof {
namespace {

constexpr std::string_view kPrefix = "pose.bones[\"";
constexpr std::string_view kNameEnd = "\"].";

struct Property {
  std::string_view rna_name;
  ChannelPath path;
};
constexpr Property kProperties[] = {
    {"location", ChannelPath::Translation},
    {"rotation_quaternion", ChannelPath::Rotation},
    {"scale", ChannelPath::Scale},
};

// Compares an escaped name (as it appears between the quotes of a path) with a
// plain one, unescaping on the fly so that nothing is allocated.
bool escaped_equals(std::string_view escaped, const std::string& name) {
  size_t k = 0;
  for (size_t i = 0; i < escaped.size(); ++i, ++k) {
    char c = escaped[i];
    if (c == '\\') c = escaped[++i];  // the parser checked a character follows
    if (k == name.size() || name[k] != c) return false;
  }
  return k == name.size();
}

}  // namespace

std::string channel_path(const Skeleton& skeleton, const Channel& channel) {
  if (channel.joint < 0 || static_cast<size_t>(channel.joint) >= skeleton.names.size()) return {};
  std::string path(kPrefix);
  for (char c : skeleton.names[static_cast<size_t>(channel.joint)]) {
    if (c == '"' || c == '\\') path += '\\';
    path += c;
  }
  path += kNameEnd;
  for (const Property& property : kProperties)
    if (property.path == channel.path) path += property.rna_name;
  return path;
}

int32_t resolve_channel_path(const Skeleton& skeleton, std::string_view path, ChannelPath* out_property) {
  if (!path.starts_with(kPrefix)) return -1;
  // The name runs to the first quote that no backslash escapes.
  size_t i = kPrefix.size();
  while (i < path.size() && path[i] != '"') {
    if (path[i] == '\\') {
      if (i + 1 == path.size() || (path[i + 1] != '"' && path[i + 1] != '\\')) return -1;
      ++i;
    }
    ++i;
  }
  const std::string_view escaped_name = path.substr(kPrefix.size(), i - kPrefix.size());
  const std::string_view rest = path.substr(std::min(i, path.size()));
  if (!rest.starts_with(kNameEnd)) return -1;

  const std::string_view rna_name = rest.substr(kNameEnd.size());
  const Property* property = nullptr;
  for (const Property& candidate : kProperties)
    if (candidate.rna_name == rna_name) property = &candidate;
  if (property == nullptr) return -1;

  for (size_t j = 0; j < skeleton.names.size(); ++j) {
    if (escaped_equals(escaped_name, skeleton.names[j])) {
      if (out_property != nullptr) *out_property = property->path;
      return static_cast<int32_t>(j);
    }
  }
  return -1;
}

ActionBindings bind_action(const Skeleton& skeleton, const Action& action) {
  ActionBindings bindings;
  bindings.paths.reserve(action.channels.size());
  bindings.targets.reserve(action.channels.size());
  for (const Channel& channel : action.channels) {
    bindings.paths.push_back(channel_path(skeleton, channel));
    bindings.targets.push_back(resolve_channel_path(skeleton, bindings.paths.back(), nullptr));
  }
  return bindings;
}

bool ResolvePathsJob::Validate() const {
  return skeleton != nullptr && bindings != nullptr && targets_out.size() == bindings->paths.size();
}

bool ResolvePathsJob::Run() const {
  if (!Validate()) return false;
  for (size_t i = 0; i < targets_out.size(); ++i) {
    targets_out[i] = resolve_channel_path(*skeleton, bindings->paths[i], nullptr);
  }
  if (lookups != nullptr) *lookups += targets_out.size();
  return true;
}

}  // namespace crowdprof
