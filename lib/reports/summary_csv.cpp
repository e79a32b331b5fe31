#include "reports/summary_csv.h"

#include <cmath>
#include <limits>

#include "base/number_text.h"
#include "measuring/stats.h"

namespace crowdprof {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string summary_csv_header() {
  return "mode,characters,threads,frames,frame_median_ms,frame_p95_ms,frame_p99_ms,frame_fps,cpu_median_ms,"
         "cpu_p95_ms,cpu_p99_ms,cpu_fps,partial,passes,index_order,colour_invocations_per_vertex,"
         "prepass_invocations_per_vertex,shadows_invocations_per_vertex,palette_bytes_per_copy_on_screen,"
         "record_bytes_per_copy_on_screen";
}

void write_summary_csv(const std::vector<const Result*>& runs, std::ostream& out) {
  out << summary_csv_header() << "\n";
  for (const Result* report : runs) {
    const std::vector<double>& frame = report->samples.frame_ms;
    const std::vector<double>& cpu = report->samples.cpu_ms;
    // A rate per median; empty where the median is 0 (no frames), never inf.
    auto rate = [](double median_ms) { return median_ms > 0 ? fixed(1000.0 / median_ms, 2) : std::string(); };
    Summary f = summarize(frame), c = summarize(cpu);
    out << csv_field(report->run.mode) << "," << report->run.characters << "," << report->run.threads << ","
        << report->frames() << "," << fixed(f.median, 4) << "," << fixed(f.p95, 4) << "," << fixed(f.p99, 4) << ","
        << rate(f.median) << "," << fixed(c.median, 4) << "," << fixed(c.p95, 4) << "," << fixed(c.p99, 4) << ","
        << rate(c.median) << "," << (report->partial ? "true" : "false") << "," << report->run.switches.passes << ","
        << to_string(report->run.switches.index_order);
    // Vertex reuse by pass: empty where the GL did not count it or the pass drew nothing.
    for (GpuPass pass : {GpuPass::Colour, GpuPass::Prepass, GpuPass::Shadows}) {
      const double reuse = report->invocations_per_vertex_drawn
                               ? (*report->invocations_per_vertex_drawn)[static_cast<size_t>(pass)]
                               : std::numeric_limits<double>::quiet_NaN();
      out << "," << (std::isfinite(reuse) ? fixed(reuse, 4) : std::string());
    }
    // GPU skinning's uploads a copy on screen: empty in results from before the split.
    for (const std::optional<double>& bytes :
         {report->palette_bytes_per_copy_on_screen, report->record_bytes_per_copy_on_screen})
      out << "," << (bytes ? fixed(*bytes, 1) : std::string());
    out << "\n";
  }
}

}  // namespace crowdprof
