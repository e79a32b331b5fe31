// --trace: Chrome trace-event JSON with a span per stage per frame on the main
// thread and per task on the workers, thread ids stable and named.
#include <gtest/gtest.h>

#include <fstream>
#include <future>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "gen/humanoid.h"
#include "frame/crowd_bench.h"
#include "measuring/trace.h"
#include "test_support.h"

using namespace crowdprof;
using nlohmann::json;

namespace {

json written(const Tracer& tracer) {
  std::ostringstream out;
  tracer.write(out);
  return json::parse(out.str());  // throws, failing the test, if it is not JSON
}

}  // namespace

TEST(Trace, ThreadsGetStableIdsMainFirst) {
  Tracer tracer;
  auto now = Tracer::Clock::now();
  tracer.span("main work", "stage", now, now + std::chrono::microseconds(5), 1);
  // Both threads alive at once: a finished thread's id may be given to the next.
  std::promise<void> a_recorded, b_done;
  std::thread a([&] {
    tracer.span("task", "task", now, now + std::chrono::microseconds(3), 1, {{"copies", 2}});
    tracer.span("task", "task", now, now + std::chrono::microseconds(4), 1);
    a_recorded.set_value();
    b_done.get_future().wait();
  });
  a_recorded.get_future().wait();
  std::thread b([&] { tracer.span("task", "task", now, now, 2); });
  b.join();
  b_done.set_value();
  a.join();
  std::vector<TraceSpan> spans = tracer.spans();
  ASSERT_EQ(spans.size(), 4u);
  EXPECT_EQ(spans[0].tid, 1u);
  EXPECT_EQ(spans[1].tid, 2u);
  EXPECT_EQ(spans[2].tid, 2u);  // the same thread keeps its id
  EXPECT_EQ(spans[3].tid, 3u);

  tracer.name_process(1, "mode master");
  json doc = written(tracer);
  ASSERT_TRUE(doc["traceEvents"].is_array());
  std::map<std::pair<int, int>, std::string> thread_names;
  std::string process;
  for (const json& e : doc["traceEvents"]) {
    if (e["ph"] == "M" && e["name"] == "thread_name") thread_names[{e["pid"], e["tid"]}] = e["args"]["name"];
    if (e["ph"] == "M" && e["name"] == "process_name" && e["pid"] == 1) process = e["args"]["name"];
    if (e["ph"] == "X" && e["name"] == "task" && e.contains("args")) {
      EXPECT_EQ(e["args"]["copies"], 2);
    }
  }
  EXPECT_EQ(process, "mode master");
  EXPECT_EQ(thread_names[std::make_pair(1, 1)], "main");
  EXPECT_EQ(thread_names[std::make_pair(1, 2)], "worker 2");
  EXPECT_EQ(thread_names[std::make_pair(2, 3)], "worker 3");
}

TEST(Trace, AThreadedBenchShowsStagesOnMainAndTasksOnWorkers) {
  static const Character character = generate_humanoid({30, 800, 7});
  BenchConfig config;
  config.mode = find_mode("threaded")->switches;
  config.mode_name = "threaded";
  config.threads = 3;
  // Frames of a few milliseconds: long enough for a sleeping worker to wake
  // and take tasks, even on a machine busy with other jobs.
  config.crowd.copies = 600;
  Tracer tracer;
  config.tracer = &tracer;
  CrowdBench bench(character, config);
  // A worker joins within a frame or two; give it up to 5 seconds.
  std::set<uint32_t> task_threads;
  size_t frames = 0;
  auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (frames < 3 || (task_threads.size() < 2 && std::chrono::steady_clock::now() < give_up)) {
    bench.step();
    ++frames;
    task_threads.clear();
    for (const TraceSpan& s : tracer.spans())
      if (s.category == "task") task_threads.insert(s.tid);
  }
  EXPECT_GE(task_threads.size(), 2u) << "tasks ran on one thread only in " << frames << " frames";
  ASSERT_LT(frames, 2000u);

  json doc = written(tracer);
  std::map<std::string, size_t> main_stages;
  std::set<int> tids, named;
  size_t frame_spans = 0, tasks = 0;
  for (const json& e : doc["traceEvents"]) {
    ASSERT_TRUE(e["pid"].is_number_integer() && e["tid"].is_number_integer()) << e;
    if (e["ph"] == "M") {
      if (e["name"] == "thread_name") named.insert(e["tid"].get<int>());
      continue;
    }
    ASSERT_EQ(e["ph"], "X") << e;
    ASSERT_TRUE(e["ts"].is_number() && e["dur"].is_number()) << e;
    EXPECT_GE(e["ts"].get<double>(), 0.0);
    EXPECT_GE(e["dur"].get<double>(), 0.0);
    tids.insert(e["tid"].get<int>());
    if (e["cat"] == "stage") {
      EXPECT_EQ(e["tid"], 1) << "stages run on the main thread";
      ++main_stages[e["name"].get<std::string>()];
    }
    if (e["cat"] == "frame") ++frame_spans;
    if (e["cat"] == "task") {
      ++tasks;
      EXPECT_EQ(e["name"], "pose+skin") << "threaded skins with the pose update";
      EXPECT_GE(e["args"]["copies"].get<int>(), 1);
    }
  }
  EXPECT_EQ(frame_spans, frames);
  for (const char* stage : {"Logic", "Physics", "Animations", "Scenegraph", "Rasterizer", "GPU Latency", "Overhead"})
    EXPECT_EQ(main_stages[stage], frames) << stage;
  EXPECT_GE(tasks, frames);
  EXPECT_GE(tids.size(), 2u);
  EXPECT_EQ(named, tids) << "every thread with spans is named";
}

TEST(TraceCli, BenchWritesATraceThatParses) {
  auto dir = test::scratch_dir("trace_cli");
  std::string scene = (test::source_dir() / "scenes" / "humanoid.glb").string();
  std::string path = (dir / "trace.json").string();
  auto r = test::run_cli("bench '" + scene + "' -n 4 --frames 3 --warmup 1 --mode threaded --threads 2 -q --trace '" +
                         path + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(path);
  json doc = json::parse(in);
  size_t frames = 0;
  for (const json& e : doc["traceEvents"]) frames += e["ph"] == "X" && e["name"] == "frame";
  EXPECT_EQ(frames, 4u) << "warm-up frames are traced too";
}
