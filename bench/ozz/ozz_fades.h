// ozz_driver's crossfade comparison (issue 53, item 6): every copy fading
// between two of its character's actions, `--crossfade sampled`'s way, by
// ozz-animation (two SamplingJobs, one context per copy per action, then
// BlendingJob and LocalToModelJob) and by crowdprof's jobs (two SamplingJobs,
// BlendingJob, LocalToModelJob), interleaved in one process. Skinning is
// left out of the times: the fade is what is compared; the vertices of every
// copy at the last frame, skinned by each side, prove the work the same.
#pragma once

#include <cstddef>

#include "asset/character.h"
#include "ozz_convert.h"

namespace ozz_bench {

struct FadeRun {
  size_t copies = 160;
  size_t frames = 240;
  size_t warmup = 10;
  // Issue 56's layered work: a third action sampled per copy and laid over
  // the subtree of the joint that holds closest to half the skeleton (both
  // fading actions masked by 1 - that mask, ozz's partial blending).
  bool layered = false;
};

// With run.layered, a masked layer over each fade (issue 56, item 5).
// Prints one JSON line: both sides' median frames, the per-block ratios, the
// work (poses sampled, joints blended a frame) and how far ozz's vertices
// are from crowdprof's.
// Both sides on the keys ozz holds: call round_like_ozz_storage(c) before
// make_ozz_character; this takes ozz's rotation keys into c's actions.
void run_sampled_fades(crowdprof::Character& c, const OzzCharacter& ozz_character, const FadeRun& run);

}  // namespace ozz_bench
