// Micro-benchmarks of one copy's frame stages on the thesis's character
// (scenes/humanoid.glb), and the machine's memory write bandwidth and vector
// multiply-add rate to set them against. Run: ./setup.sh bench [Google
// Benchmark options], e.g.
//   ./setup.sh bench --benchmark_filter=Skinning --benchmark_repetitions=5
// Per-item times are in the counters: ns_per_joint, ns_per_vertex (seconds with
// an SI prefix: "3.1n" is 3.1 ns), GB/s for the bandwidth probes and
// multiply_adds_per_second for the arithmetic one.
#include <benchmark/benchmark.h>
#include <unistd.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <atomic>
#include <chrono>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "animation/run_job.h"
#include "animation/binding.h"
#include "animation/blending.h"
#include "animation/joint_mask.h"
#include "animation/local_pose.h"
#include "animation/pose.h"
#include "animation/sampling.h"
#include "asset/gltf_loader.h"
#include "asset/vertex_order.h"
#include "skinning/output_buffer.h"
#include "skinning/output_stores.h"
#include "skinning/packed_vertex.h"
#include "skinning/simd_target.h"
#include "skinning/skinning.h"
#include "skinning/skinning_plan.h"

namespace crowdprof {
namespace {

// Its vertices in the order a bench skins them (asset/vertex_order.h).
const Character& humanoid() {
  static const Character character = [] {
    Character c = load_character(CROWDPROF_SOURCE_DIR "/scenes/humanoid.glb");
    order_vertices_for_skinning(c);
    return c;
  }();
  return character;
}

// One copy's state, posed once at time 0.4 s of the first action.
struct Copy {
  const Character& c = humanoid();
  ActionBindings bindings = bind_action(c.skeleton, c.actions[0]);
  SamplingCursor cursor;
  LocalPose pose;
  std::vector<glm::mat4> model = std::vector<glm::mat4>(c.skeleton.joint_count());
  std::vector<SkinMatrix> palette = std::vector<SkinMatrix>(c.skeleton.joint_count());
  Copy() {
    reset_cursor(c.actions[0], &cursor);
    reset_to_rest(c.skeleton, &pose);
    run_job(SamplingJob{&c.actions[0], 0.4f, bindings.targets, &cursor, &pose}, "SamplingJob");
    run_job(LocalToModelJob{&c.skeleton, &pose, model}, "LocalToModelJob");
    run_job(SkinningMatricesJob{&c.skeleton, model, palette}, "SkinningMatricesJob");
  }
};

// Samples the first action one frame (1/60 s) after `*time`, looping.
void sample_next_frame(Copy& copy, float* time) {
  const Action& action = copy.c.actions[0];
  *time += 1.0f / 60.0f;
  if (*time > action.end) *time = action.start;
  run_job(SamplingJob{&action, *time, copy.bindings.targets, &copy.cursor, &copy.pose}, "SamplingJob");
}

void per_joint(benchmark::State& state, size_t joints) {
  state.counters["ns_per_joint"] = benchmark::Counter(
      static_cast<double>(joints), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void per_vertex(benchmark::State& state, size_t vertices) {
  state.counters["ns_per_vertex"] = benchmark::Counter(
      static_cast<double>(vertices), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// GB/s of all threads together: each thread's counter is already the total
// rate (iterations of every thread over the wall time), so the threads' counters
// are averaged, not summed as Google Benchmark would.
benchmark::Counter total_rate(size_t bytes_per_iteration) {
  return benchmark::Counter(static_cast<double>(bytes_per_iteration) / 1e9,
                            benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kAvgThreads);
}

// Memory as skinning's output gets it (output_buffer.h: huge pages).
struct OutputMemory {
  size_t bytes;
  char* p;
  explicit OutputMemory(size_t n) : bytes(n), p(static_cast<char*>(allocate_output(n))) {}
  ~OutputMemory() { free_output(p, bytes); }
  OutputMemory(const OutputMemory&) = delete;
  OutputMemory& operator=(const OutputMemory&) = delete;
  char* get() const { return p; }
};

// Write bandwidth: each thread fills its own 256 MiB, far past the caches, as
// skinning's output to 10,000 copies would. memset is glibc's best store loop.
void BM_MemoryWrite(benchmark::State& state) {
  const size_t bytes = size_t{256} << 20;
  const OutputMemory buffer(bytes);
  std::memset(buffer.get(), 1, bytes);  // fault the pages in before timing
  int value = 0;
  for (auto _ : state) {
    std::memset(buffer.get(), ++value, bytes);
    benchmark::ClobberMemory();
  }
  state.counters["GB/s"] = total_rate(bytes);
}
BENCHMARK(BM_MemoryWrite)->Threads(1)->Threads(2)->UseRealTime()->Unit(benchmark::kMillisecond);

#if defined(__SSE2__)
// The same with streaming (non-temporal) stores, as skinning writes output far
// larger than the caches (skinning/output_stores.h): lines go to memory without
// being read for ownership first. SSE2's 16-byte store, which every x86-64 has;
// the write-combining buffers merge four into a line as AVX-512's would.
void BM_MemoryWriteStreaming(benchmark::State& state) {
  const size_t bytes = size_t{256} << 20;
  const OutputMemory buffer(bytes);
  std::memset(buffer.get(), 1, bytes);
  int value = 0;
  for (auto _ : state) {
    const __m128i v = _mm_set1_epi8(static_cast<char>(++value));
    for (size_t at = 0; at < bytes; at += 16) _mm_stream_si128(reinterpret_cast<__m128i*>(buffer.get() + at), v);
    _mm_sfence();
    benchmark::ClobberMemory();
  }
  state.counters["GB/s"] = total_rate(bytes);
}
BENCHMARK(BM_MemoryWriteStreaming)->Threads(1)->Threads(2)->UseRealTime()->Unit(benchmark::kMillisecond);
#endif

#if defined(__x86_64__)
// The cores' arithmetic beside the memory probes: how many vector multiply-adds
// one thread retires a nanosecond, twelve independent chains (enough to fill
// every multiply-add port), and one dependent chain (its latency, 4 cycles on
// recent Intel cores, gives the clock the vector units run at). The skinning
// kernel's port bound is its multiply-adds a batch over the first figure
// (docs/performance.md). Compiled for each width here, run where the CPU has it.
// Vectors stay inside the functions compiled for their width (no vector in an
// interface of baseline x86-64 code, whose ABI differs).
#define CROWDPROF_MULTIPLY_ADD_RATE(V, FMA, SET)                                      \
  volatile float one = 0.99999994f, tiny = 1e-7f; /* 1 - 2^-24: values stay finite */ \
  const V x = SET(one), y = SET(tiny);                                                \
  V a[12];                                                                            \
  for (int i = 0; i < 12; ++i) a[i] = SET(static_cast<float>(i));                     \
  V chain = SET(1.0f);                                                                \
  constexpr int64_t kSteps = 1 << 16;                                                 \
  const bool dependent = state.range(0) == 1;                                         \
  for (auto _ : state) {                                                              \
    if (dependent) {                                                                  \
      for (int64_t k = 0; k < kSteps; ++k) chain = FMA(chain, x, y);                  \
      benchmark::DoNotOptimize(chain);                                                \
    } else {                                                                          \
      for (int64_t k = 0; k < kSteps; ++k)                                            \
        for (V & v : a) v = FMA(v, x, y);                                             \
      for (V & v : a) benchmark::DoNotOptimize(v);                                    \
    }                                                                                 \
  }                                                                                   \
  state.counters["multiply_adds_per_second"] = benchmark::Counter(                    \
      static_cast<double>(dependent ? kSteps : 12 * kSteps), benchmark::Counter::kIsIterationInvariantRate)

[[gnu::target("avx2,fma")]] void BM_MultiplyAddRateAVX2(benchmark::State& state) {
  CROWDPROF_MULTIPLY_ADD_RATE(__m256, _mm256_fmadd_ps, _mm256_set1_ps);
}
[[gnu::target("avx512f")]] void BM_MultiplyAddRateAVX3(benchmark::State& state) {
  CROWDPROF_MULTIPLY_ADD_RATE(__m512, _mm512_fmadd_ps, _mm512_set1_ps);
}
#undef CROWDPROF_MULTIPLY_ADD_RATE
#endif

// The time for one thread to signal another and see its answer, through one
// shared cache line: what a frame pays at each hand-over between threads (a
// worker taking a task, waiting for a pose, the join). It depends on where the
// host puts the two vCPUs, several times longer when they share no cache
// (docs/performance.md, crowd scale).
void BM_CoreRoundTrip(benchmark::State& state) {
  alignas(64) static std::atomic<int64_t> flag{0};
  if (state.thread_index() == 0) flag.store(0);  // before the threads' common start
  int64_t i = 0;
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    if (state.thread_index() == 0) {
      flag.store(2 * i + 1, std::memory_order_release);
      while (flag.load(std::memory_order_acquire) != 2 * i + 2) {
      }
    } else {
      while (flag.load(std::memory_order_acquire) != 2 * i + 1) {
      }
      flag.store(2 * i + 2, std::memory_order_release);
    }
    ++i;
  }
  const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
  // Thread 0's figure only (counters of threads are summed).
  state.counters["ns_round_trip"] = state.thread_index() == 0 && i > 0 ? ns / static_cast<double>(i) : 0.0;
}
BENCHMARK(BM_CoreRoundTrip)->Threads(2)->UseRealTime();

// Sampling every channel of the dance, the clock moving a frame at a time.
void BM_Sampling(benchmark::State& state) {
  Copy copy;
  float time = 0.0f;
  for (auto _ : state) {
    sample_next_frame(copy, &time);
    benchmark::DoNotOptimize(copy.pose.rotations.data());
  }
  per_joint(state, copy.c.skeleton.joint_count());
}
BENCHMARK(BM_Sampling);

// A crossfade's blend (BlendingJob) of two sampled poses on one SIMD target:
// the dance and the walk, 30% in; with the argument 1, the wave laid over
// the spine's subtree (issue 56's masked layer, the fade masked by 1 - it).
void BM_Blending(benchmark::State& state, std::string target) {
  if (std::string why = force_simd_target(target); !why.empty()) {
    state.SkipWithError(why.c_str());
    return;
  }
  Copy from, to;
  to.bindings = bind_action(to.c.skeleton, to.c.actions[1]);
  reset_cursor(to.c.actions[1], &to.cursor);
  run_job(SamplingJob{&to.c.actions[1], 0.2f, to.bindings.targets, &to.cursor, &to.pose}, "SamplingJob");
  LocalPose rest, out;
  reset_to_rest(from.c.skeleton, &rest);
  reset_to_rest(from.c.skeleton, &out);
  Copy over;
  over.bindings = bind_action(over.c.skeleton, over.c.actions[2]);
  reset_cursor(over.c.actions[2], &over.cursor);
  run_job(SamplingJob{&over.c.actions[2], 0.5f, over.bindings.targets, &over.cursor, &over.pose}, "SamplingJob");
  std::vector<float> upper, lower;
  if (std::string why = joint_mask(from.c.skeleton, "spine_01", 0, &upper); !why.empty()) throw std::runtime_error(why);
  for (float w : upper) lower.push_back(1.0f - w);
  const bool masked = state.range(0) != 0;
  const BlendLayer layers[] = {{&from.pose, 0.7f, masked ? std::span<const float>(lower) : std::span<const float>()},
                               {&to.pose, 0.3f, masked ? std::span<const float>(lower) : std::span<const float>()},
                               {&over.pose, 1.0f, upper}};
  const std::span<const BlendLayer> used(layers, masked ? 3 : 2);
  for (auto _ : state) {
    run_job(BlendingJob{used, &rest, 0.1f, &out}, "BlendingJob");
    benchmark::DoNotOptimize(out.rotations.data());
  }
  force_simd_target("");
  per_joint(state, from.c.skeleton.joint_count());
}

void BM_LocalToModel(benchmark::State& state) {
  Copy copy;
  for (auto _ : state) {
    run_job(LocalToModelJob{&copy.c.skeleton, &copy.pose, copy.model}, "LocalToModelJob");
    benchmark::DoNotOptimize(copy.model.data());
  }
  per_joint(state, copy.c.skeleton.joint_count());
}
BENCHMARK(BM_LocalToModel);

void BM_SkinningMatrices(benchmark::State& state) {
  Copy copy;
  for (auto _ : state) {
    run_job(SkinningMatricesJob{&copy.c.skeleton, copy.model, copy.palette}, "SkinningMatricesJob");
    benchmark::DoNotOptimize(copy.palette.data());
  }
  per_joint(state, copy.c.skeleton.joint_count());
}
BENCHMARK(BM_SkinningMatrices);

// The humanoid's vertices with exactly `influences` influences (0: all of them),
// in their order, as a mesh of their own.
SkinnedMesh vertices_with(const SkinnedMesh& mesh, int influences) {
  SkinnedMesh out;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const glm::vec4 w = mesh.weights[v];
    const int n = (w.x != 0) + (w.y != 0) + (w.z != 0) + (w.w != 0);
    if (influences != 0 && n != influences) continue;
    out.positions.push_back(mesh.positions[v]);
    out.normals.push_back(mesh.normals[v]);
    out.joints.push_back(mesh.joints[v]);
    out.weights.push_back(w);
  }
  return out;
}

// Skinning positions and normals of one copy on one SIMD target; arg 0 is the
// influence count (0: the whole mesh).
void BM_Skinning(benchmark::State& state, std::string target) {
  if (std::string why = force_simd_target(target); !why.empty()) {
    state.SkipWithError(why.c_str());
    return;
  }
  Copy copy;
  const SkinnedMesh mesh = vertices_with(copy.c.mesh, static_cast<int>(state.range(0)));
  SkinningPlan plan;
  build_skinning_plan(mesh, copy.c.skeleton.joint_count(), &plan);
  std::vector<glm::vec3> positions(mesh.vertex_count()), normals(mesh.vertex_count());
  for (auto _ : state) {
    run_job(SkinningJob{copy.palette, &plan, 0, mesh.vertex_count(), positions, normals}, "SkinningJob");
    benchmark::DoNotOptimize(positions.data());
    benchmark::DoNotOptimize(normals.data());
  }
  force_simd_target("");
  per_vertex(state, mesh.vertex_count());
  size_t joints = 0;
  for (const SkinBatch& batch : plan.batches) joints += batch.joint_count;
  state.counters["vertices"] = static_cast<double>(mesh.vertex_count());
  state.counters["joints_per_batch"] = plan.batches.empty() ? 0.0 : double(joints) / double(plan.batches.size());
}

// Output for `copies` copies of the humanoid as the frame lays it out (each
// copy's positions, then its normals, in arrays of their own, every copy
// starting on a cache line), made once per size and faulted in: a frame
// rewrites the same memory every frame. Empty when the machine lacks the
// memory (with room to spare).
struct CrowdOutput {
  size_t copies = 0, stride = 0;  // stride: vec3s from one copy's start to the next's
  std::unique_ptr<OutputMemory> positions, normals;
  std::string missing;  // why not, when it could not be made
};

CrowdOutput& crowd_output(size_t copies, size_t vertices) {
  static std::map<size_t, CrowdOutput> outputs;
  CrowdOutput& out = outputs[copies];
  if (out.copies == copies || !out.missing.empty()) return out;
  // At least one cache line a copy, so each copy's output starts on one (the
  // frame rounds its offsets the same way: frame/copy_store.cpp).
  out.stride = vertices;
  while ((out.stride * sizeof(glm::vec3)) % 64) ++out.stride;
  const size_t bytes = copies * out.stride * sizeof(glm::vec3);
  const double available = static_cast<double>(sysconf(_SC_AVPHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  if (2.0 * static_cast<double>(bytes) > 0.8 * available) {
    out.missing = "needs " + std::to_string(2 * bytes >> 20) + " MiB, the machine has " +
                  std::to_string(static_cast<size_t>(available) >> 20) + " MiB free";
    return out;
  }
  out.positions = std::make_unique<OutputMemory>(bytes);
  out.normals = std::make_unique<OutputMemory>(bytes);
  std::memset(out.positions->get(), 0, bytes);
  std::memset(out.normals->get(), 0, bytes);
  out.copies = copies;
  return out;
}

// Skinning a crowd's worth of copies, the working set a frame has (not one
// copy in L1): arg 0 copies of the humanoid, each with its own output (160
// palettes cycled: posing is not measured here), split between the
// benchmark's threads, on one SIMD target. Streams its output past 64 MiB, as
// the frame does (skinning/output_stores.h). Counters: vertices_per_second and
// bytes_per_second (skinned output written, float format) of all threads
// together; GB/s is the same bandwidth in the memory probes' unit, to set
// against BM_MemoryWriteStreaming's. (With threads, the Time column is per
// thread's iteration: read the counters.)
void BM_SkinningCrowd(benchmark::State& state, std::string target) {
  const size_t copies = static_cast<size_t>(state.range(0));
  static Copy* copy = new Copy;  // one pose, shared by the threads (read-only)
  const size_t n = copy->c.mesh.vertex_count();
  static std::mutex setup;
  CrowdOutput* out = nullptr;
  {
    std::lock_guard<std::mutex> lock(setup);
    out = &crowd_output(copies, n);
  }
  if (!out->missing.empty()) {
    state.SkipWithError(out->missing.c_str());
    return;
  }
  if (std::string why = force_simd_target(target); !why.empty()) {
    state.SkipWithError(why.c_str());
    return;
  }
  SkinningPlan plan;
  build_skinning_plan(copy->c.mesh, copy->c.skeleton.joint_count(), &plan);
  const bool streaming = stream_skinned_output(copies * n * kFloatVertexBytes);
  // This thread's share of the copies.
  const size_t threads = static_cast<size_t>(state.threads()), t = static_cast<size_t>(state.thread_index());
  const size_t first = copies * t / threads, last = copies * (t + 1) / threads;
  auto* positions = reinterpret_cast<glm::vec3*>(out->positions->get());
  auto* normals = reinterpret_cast<glm::vec3*>(out->normals->get());
  for (auto _ : state) {
    for (size_t i = first; i < last; ++i) {
      const size_t at = i * out->stride;
      SkinningJob job{copy->palette, &plan, 0, n, std::span(positions + at, n), std::span(normals + at, n)};
      job.streaming_stores = streaming;
      run_job(job, "SkinningJob");
    }
    benchmark::ClobberMemory();
  }
  // Each thread's share per iteration: Google Benchmark's rate of a thread
  // counts every thread's iterations, so the threads' rates are averaged
  // (total_rate's reasoning) to give the crowd's.
  const size_t mine = last - first;
  const auto all_threads = benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kAvgThreads;
  state.counters["vertices_per_second"] = benchmark::Counter(static_cast<double>(mine * n), all_threads);
  state.counters["bytes_per_second"] =
      benchmark::Counter(static_cast<double>(mine * n * kFloatVertexBytes), all_threads);
  state.counters["GB/s"] = total_rate(mine * n * kFloatVertexBytes);
  state.counters["streaming"] = benchmark::Counter(streaming ? 1 : 0, benchmark::Counter::kAvgThreads);
  state.SetLabel(target);
  if (t == 0) force_simd_target("");
}

// Skinning into the packed format (--vertex-format packed, 10 bytes a vertex)
// against the float one (24 bytes) on the best target: the whole mesh, quantised
// in a box around it. bytes_per_second: skinned output written.
void BM_SkinningFormat(benchmark::State& state) {
  Copy copy;
  const SkinnedMesh& mesh = copy.c.mesh;
  const size_t n = mesh.vertex_count();
  SkinningPlan plan;
  build_skinning_plan(mesh, copy.c.skeleton.joint_count(), &plan);
  std::vector<glm::vec3> positions(n), normals(n);
  run_job(SkinningJob{copy.palette, &plan, 0, n, positions, normals}, "SkinningJob");
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const PositionQuantisation q = position_quantisation(lo - 0.1f, hi + 0.1f);
  std::vector<uint16_t> codes(3 * n);
  std::vector<uint32_t> words(n);
  const bool packed = state.range(0) != 0;
  for (auto _ : state) {
    if (packed) {
      run_job(PackedSkinningJob{copy.palette, &plan, &q, 0, n, codes, words}, "PackedSkinningJob");
      benchmark::DoNotOptimize(codes.data());
      benchmark::DoNotOptimize(words.data());
    } else {
      run_job(SkinningJob{copy.palette, &plan, 0, n, positions, normals}, "SkinningJob");
      benchmark::DoNotOptimize(positions.data());
      benchmark::DoNotOptimize(normals.data());
    }
  }
  per_vertex(state, n);
  const size_t bytes = packed ? kPackedVertexBytes : kFloatVertexBytes;
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * n * bytes));
  state.counters["bytes_per_vertex"] = static_cast<double>(bytes);
}
BENCHMARK(BM_SkinningFormat)->Arg(0)->Arg(1)->ArgName("packed");

// The whole pose and skinning of one copy, as the frame loop runs it.
void BM_PoseAndSkin(benchmark::State& state) {
  Copy copy;
  SkinningPlan plan;
  build_skinning_plan(copy.c.mesh, copy.c.skeleton.joint_count(), &plan);
  const size_t n = copy.c.mesh.vertex_count();
  std::vector<glm::vec3> positions(n), normals(n);
  float time = 0.0f;
  for (auto _ : state) {
    sample_next_frame(copy, &time);
    run_job(LocalToModelJob{&copy.c.skeleton, &copy.pose, copy.model}, "LocalToModelJob");
    run_job(SkinningMatricesJob{&copy.c.skeleton, copy.model, copy.palette}, "SkinningMatricesJob");
    run_job(SkinningJob{copy.palette, &plan, 0, n, positions, normals}, "SkinningJob");
    benchmark::DoNotOptimize(positions.data());
  }
  per_vertex(state, n);
}
BENCHMARK(BM_PoseAndSkin)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace crowdprof

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  for (const std::string& target : crowdprof::available_simd_targets()) {
    benchmark::RegisterBenchmark(("BM_Blending/" + target).c_str(), crowdprof::BM_Blending, target)
        ->Arg(0)
        ->Arg(1)
        ->ArgName("masked");
    benchmark::RegisterBenchmark(("BM_Skinning/" + target).c_str(), crowdprof::BM_Skinning, target)
        ->DenseRange(0, 4)
        ->ArgName("influences");
    benchmark::RegisterBenchmark(("BM_SkinningCrowd/" + target).c_str(), crowdprof::BM_SkinningCrowd, target)
        ->Arg(160)
        ->Arg(100000)
        ->ArgName("copies")
        ->Threads(1)
        ->Threads(2)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
#if defined(__x86_64__)
  // Vector multiply-adds a second: twelve independent chains (0) or one (1).
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    benchmark::RegisterBenchmark("BM_MultiplyAddRate/AVX2", crowdprof::BM_MultiplyAddRateAVX2)
        ->Arg(0)
        ->Arg(1)
        ->ArgName("dependent");
  if (__builtin_cpu_supports("avx512f"))
    benchmark::RegisterBenchmark("BM_MultiplyAddRate/AVX3", crowdprof::BM_MultiplyAddRateAVX3)
        ->Arg(0)
        ->Arg(1)
        ->ArgName("dependent");
#endif
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
