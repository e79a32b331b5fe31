#include "skinning/simd_target.h"

#include <cctype>

#include <hwy/highway.h>
#include <hwy/targets.h>

namespace crowdprof {
namespace {

// Targets this build compiled the kernels for (HWY_TARGETS is the same in
// skinning_kernels.cpp: same flags) and the CPU supports, as Highway bits;
// lower bits are better targets.
int64_t runnable() {
  return hwy::SupportedTargets() & HWY_TARGETS;
}

// Highway's names of the targets in `targets`, best (the lowest bit) first.
std::vector<std::string> names_of(int64_t targets) {
  std::vector<std::string> names;
  for (int64_t bits = targets; bits != 0; bits &= bits - 1) names.push_back(hwy::TargetName(bits & -bits));
  return names;
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(a[i])) != std::toupper(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

// The targets force_simd_target left Highway, 0 for all the CPU has. Highway's
// SupportedTargets() re-detects the CPU and resets the dispatch tables' choice
// to its best target on every call unless a target set is given to it this way,
// so a set given with DisableTargets would not last.
int64_t g_forced = 0;

void allow(int64_t targets) {
  g_forced = targets;
  hwy::SetSupportedTargetsForTest(targets);
  hwy::GetChosenTarget().Update(hwy::SupportedTargets());
}

}  // namespace

std::string active_simd_target() {
  const int64_t bits = runnable();
  return hwy::TargetName(bits & -bits);
}

std::vector<std::string> available_simd_targets() {
  return names_of(runnable());
}

std::vector<std::string> compiled_simd_targets() {
  return names_of(HWY_TARGETS);
}

std::string force_simd_target(std::string_view name) {
  const int64_t before = g_forced;
  allow(0);  // everything the CPU can run, to choose from
  if (name.empty()) return {};
  // Every target this build knows, runnable here or not, to tell the two apart.
  int64_t wanted = 0;
  for (int64_t bits = HWY_TARGETS; bits != 0; bits &= bits - 1)
    if (equals_ignoring_case(name, hwy::TargetName(bits & -bits))) wanted = bits & -bits;
  if (wanted == 0 || !(wanted & runnable())) {
    const std::string can = joined(available_simd_targets());
    allow(before);
    return "SIMD target \"" + std::string(name) + "\" " +
           (wanted == 0 ? "is not compiled into this build" : "is not supported by this CPU") + " (choose from " + can +
           ")";
  }
  allow(hwy::SupportedTargets() & ~(wanted - 1));  // every better target (a lower bit) off
  return {};
}

}  // namespace crowdprof
