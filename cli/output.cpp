#include "cli/output.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>

#include "base/output_file.h"
#include "result/result_codec.h"

std::function<void(size_t, size_t)> terminal_progress(bool quiet, const std::string& what) {
  if (quiet || !isatty(STDERR_FILENO)) return {};
  auto start = std::chrono::steady_clock::now();
  auto last = std::make_shared<std::chrono::steady_clock::time_point>(start);
  auto shown = std::make_shared<bool>(false);
  return [start, last, shown, what](size_t done, size_t total) {
    auto now = std::chrono::steady_clock::now();
    if (done >= total) {  // the end: erase the line, if one was shown
      if (*shown) std::fprintf(stderr, "\r\033[K");
      *shown = false;
      std::fflush(stderr);
      return;
    }
    if (now - start < std::chrono::seconds(1)) return;  // a short run shows nothing
    if (*shown && now - *last < std::chrono::milliseconds(100)) return;
    *last = now;
    *shown = true;
    double elapsed = std::chrono::duration<double>(now - start).count();
    double left = done > 0 ? elapsed / static_cast<double>(done) * static_cast<double>(total - done) : 0.0;
    std::fprintf(stderr, "\rcrowdprof: %s %zu/%zu frames, %.0f s left\033[K", what.c_str(), done, total, left);
    std::fflush(stderr);
  };
}

bool prints_on_stdout(bool quiet, std::initializer_list<std::string> outputs) {
  if (quiet) return false;
  for (const std::string& path : outputs)
    if (crowdprof::is_standard_output(path)) return false;
  return true;
}

void write_text(const std::string& path, const std::string& what, const std::function<void(std::ostream&)>& body) {
  std::ostringstream text;
  body(text);
  crowdprof::write_file(path, what, text.view());
}

void write_result_file(const std::string& path, const std::string& what, const crowdprof::Result& result) {
  write_text(path, what, [&](std::ostream& out) {
    out << crowdprof::with_paths_relative_to(crowdprof::result_to_json(result), path).dump(2) << "\n";
  });
}
