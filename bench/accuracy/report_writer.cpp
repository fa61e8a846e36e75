#include "bench/accuracy/report_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "bench/accuracy/svg_plot.h"

namespace tessera {

namespace {

std::string fixed(double v, int digits) {
  if (std::isinf(v)) return "∞";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

std::string seconds(double s) {
  if (s < 1e-3) return fixed(s * 1e6, 1) + " µs";
  return s < 0.1 ? fixed(s * 1e3, 2) + " ms" : fixed(s, 3) + " s";
}

std::string join(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : ", ") + p;
  return out.empty() ? "none" : out;
}

// The knobs in the order the sweep measured them.
std::vector<std::string> knobs_of(const AccuracyReport& report) {
  std::vector<std::string> knobs;
  for (const Measured& m : report.measured)
    if (knobs.empty() || knobs.back() != m.variant.knob) knobs.push_back(m.variant.knob);
  return knobs;
}

Plot time_vs_error_plot(const AccuracyReport& report) {
  Plot plot{"Time against error, " + report.scene_name,
            "render time, s",
            "RMSE against reference",
            true,
            true,
            {}};
  for (const std::string& knob : knobs_of(report)) {
    PlotSeries series{knob, {}, false};
    for (const Measured& m : report.measured)
      if (m.variant.knob == knob) series.points.push_back({m.seconds, m.error.rmse, ""});
    plot.series.push_back(series);
  }
  PlotSeries front{"Pareto front", {}, true};
  std::map<double, const Measured*> by_time;
  for (const Measured& m : report.measured)
    if (m.pareto) by_time[m.seconds] = &m;
  for (const auto& [t, m] : by_time) front.points.push_back({t, m->error.rmse, m->variant.label});
  plot.series.push_back(front);
  return plot;
}

Plot levels_plot(const AccuracyReport& report) {
  Plot plot{"Progressive levels, " + report.scene_name,
            "time since the first level, s",
            "RMSE of the preview",
            true,
            true,
            {}};
  PlotSeries series{"after each level", {}, false};
  for (const LevelRow& row : report.levels)
    series.points.push_back(
        {row.cumulative_seconds, row.error.rmse, "L" + std::to_string(row.level)});
  plot.series.push_back(series);
  return plot;
}

std::string markdown(const AccuracyReport& r) {
  std::ostringstream md;
  md << "# Accuracy report: " << r.scene_name << "\n\n"
     << r.width << "×" << r.height << ", " << r.threads << " thread(s), times are medians of "
     << r.repeats << " renders. Effects the scene calls for: " << join(r.effects) << ".\n\n"
     << "Reference: " << r.reference.label << ", recursion depth " << r.reference.max_depth << " ("
     << seconds(r.reference_seconds) << "). Errors compare the images as displayed "
     << "(clamped to [0, 1]): RMSE, PSNR, and the share of pixels with a channel off by more "
     << "than one 8-bit step. ★ marks the Pareto front: no other setting is both faster and "
     << "closer.\n\n![time against error](time_vs_error.svg)\n\n";
  for (const std::string& knob : knobs_of(r)) {
    md << "## " << knob << "\n\n| setting | time | × cheapest | RMSE | PSNR dB | pixels off |\n"
       << "| --- | --- | --- | --- | --- | --- |\n";
    for (const Measured& m : r.measured)
      if (m.variant.knob == knob)
        md << "| " << m.variant.label << (m.pareto ? " ★" : "") << " | " << seconds(m.seconds)
           << " | " << fixed(m.time_ratio, 2) << " | " << fixed(m.error.rmse, 5) << " | "
           << fixed(m.error.psnr, 1) << " | " << fixed(100 * m.error.share_off_by_step, 1)
           << " % |\n";
    md << "\n";
  }
  if (!r.not_swept.empty()) {
    md << "Not swept:\n\n";
    for (const std::string& line : r.not_swept) md << "- " << line << "\n";
    md << "\n";
  }
  md << "## Progressive levels\n\nPass 0 at 1 sample a pixel traced level by level on one "
        "thread; after each level every pixel shows its block's anchor.\n\n"
     << "| level | block | blocks | traced | time | time per block | time per pixel | "
        "cumulative | RMSE of preview |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  const double pixels = static_cast<double>(r.width) * r.height;
  for (const LevelRow& row : r.levels)
    md << "| " << row.level << " | " << row.block << "×" << row.block << " | " << row.blocks
       << " | " << row.traced << " | " << seconds(row.seconds) << " | "
       << fixed(row.traced > 0 ? row.seconds / static_cast<double>(row.traced) * 1e6 : 0, 2)
       << " µs | " << fixed(row.seconds / pixels * 1e6, 3) << " µs | "
       << seconds(row.cumulative_seconds) << " | " << fixed(row.error.rmse, 5) << " |\n";
  md << "\n![progressive levels](progressive_levels.svg)\n";
  return md.str();
}

}  // namespace

std::vector<std::string> write_accuracy_report(const AccuracyReport& report,
                                               const std::string& dir) {
  std::filesystem::create_directories(dir);
  const std::string md_path = dir + "/report.md", plot_path = dir + "/time_vs_error.svg",
                    levels_path = dir + "/progressive_levels.svg";
  write_svg_plot(time_vs_error_plot(report), plot_path);
  write_svg_plot(levels_plot(report), levels_path);
  std::ofstream md(md_path);
  md << markdown(report);
  if (!md) throw std::runtime_error("cannot write " + md_path);
  return {md_path, plot_path, levels_path};
}

}  // namespace tessera
