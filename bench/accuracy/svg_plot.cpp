#include "bench/accuracy/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace tessera {

namespace {

constexpr double kWidth = 760, kHeight = 480;
constexpr double kLeft = 80, kRight = 220, kTop = 40, kBottom = 60;  // margins; legend right
constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                    "#ff7f0e", "#17becf", "#8c564b", "#e377c2"};

struct Axis {
  bool log = false;
  double lo = 0, hi = 1;
  double map(double v) const { return log ? std::log10(v) : v; }
  bool usable(double v) const { return std::isfinite(v) && (!log || v > 0); }
  // Position in [0, 1] along the axis.
  double unit(double v) const { return (map(v) - lo) / (hi - lo); }
};

Axis fit_axis(const Plot& plot, bool log, double PlotPoint::*coordinate) {
  Axis axis{log, std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const PlotSeries& s : plot.series)
    for (const PlotPoint& p : s.points)
      if (axis.usable(p.*coordinate)) {
        axis.lo = std::min(axis.lo, axis.map(p.*coordinate));
        axis.hi = std::max(axis.hi, axis.map(p.*coordinate));
      }
  if (!(axis.lo <= axis.hi)) axis.lo = 0, axis.hi = 1;  // nothing to show
  const double pad = axis.hi > axis.lo ? 0.05 * (axis.hi - axis.lo) : 0.5;
  axis.lo -= pad;
  axis.hi += pad;
  return axis;
}

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

// Tick values: powers of ten on a log axis, five even steps on a linear one.
std::vector<double> ticks(const Axis& axis) {
  std::vector<double> out;
  if (axis.log) {
    // Powers of ten; 2 and 5 times them too where the axis spans few decades.
    const bool fine = axis.hi - axis.lo < 3;
    for (double e = std::floor(axis.lo); e <= axis.hi; ++e)
      for (double m : {1.0, 2.0, 5.0})
        if ((m == 1.0 || fine) && std::log10(m) + e >= axis.lo && std::log10(m) + e <= axis.hi)
          out.push_back(m * std::pow(10.0, e));
  } else {
    for (int i = 0; i <= 5; ++i) out.push_back(axis.lo + (axis.hi - axis.lo) * i / 5);
  }
  return out;
}

}  // namespace

void write_svg_plot(const Plot& plot, const std::string& path) {
  const Axis ax = fit_axis(plot, plot.log_x, &PlotPoint::x);
  const Axis ay = fit_axis(plot, plot.log_y, &PlotPoint::y);
  const double w = kWidth - kLeft - kRight, h = kHeight - kTop - kBottom;
  const auto px = [&](double x) { return kLeft + ax.unit(x) * w; };
  const auto py = [&](double y) { return kTop + (1 - ay.unit(y)) * h; };

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << kLeft << "\" y=\"24\" font-size=\"15\">" << escape(plot.title)
      << "</text>\n"
      << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << w << "\" height=\"" << h
      << "\" fill=\"none\" stroke=\"#444\"/>\n";
  for (double t : ticks(ax)) {
    const double x = px(t);
    svg << "<line x1=\"" << x << "\" y1=\"" << kTop << "\" x2=\"" << x << "\" y2=\"" << kTop + h
        << "\" stroke=\"#ddd\"/><text x=\"" << x << "\" y=\"" << kTop + h + 16
        << "\" text-anchor=\"middle\">" << number(t) << "</text>\n";
  }
  for (double t : ticks(ay)) {
    const double y = py(t);
    svg << "<line x1=\"" << kLeft << "\" y1=\"" << y << "\" x2=\"" << kLeft + w << "\" y2=\"" << y
        << "\" stroke=\"#ddd\"/><text x=\"" << kLeft - 6 << "\" y=\"" << y + 4
        << "\" text-anchor=\"end\">" << number(t) << "</text>\n";
  }
  svg << "<text x=\"" << kLeft + w / 2 << "\" y=\"" << kHeight - 16 << "\" text-anchor=\"middle\">"
      << escape(plot.x_label) << (plot.log_x ? " (log)" : "") << "</text>\n"
      << "<text transform=\"translate(18," << kTop + h / 2 << ") rotate(-90)\" "
      << "text-anchor=\"middle\">" << escape(plot.y_label) << (plot.log_y ? " (log)" : "")
      << "</text>\n";

  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& s = plot.series[i];
    const char* colour = kColours[i % std::size(kColours)];
    std::ostringstream line;
    for (const PlotPoint& p : s.points)
      if (ax.usable(p.x) && ay.usable(p.y)) line << px(p.x) << ',' << py(p.y) << ' ';
    svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\""
        << (s.dashed ? " stroke-dasharray=\"6 4\"" : "") << " points=\"" << line.str() << "\"/>\n";
    for (const PlotPoint& p : s.points) {
      if (!ax.usable(p.x) || !ay.usable(p.y)) continue;
      svg << "<circle cx=\"" << px(p.x) << "\" cy=\"" << py(p.y) << "\" r=\"3\" fill=\"" << colour
          << "\"/>\n";
      if (!p.label.empty())
        svg << "<text x=\"" << px(p.x) + 5 << "\" y=\"" << py(p.y) - 5 << "\" font-size=\"10\">"
            << escape(p.label) << "</text>\n";
    }
    const double ly = kTop + 10 + 18 * static_cast<double>(i);
    svg << "<line x1=\"" << kWidth - kRight + 16 << "\" y1=\"" << ly << "\" x2=\""
        << kWidth - kRight + 40 << "\" y2=\"" << ly << "\" stroke=\"" << colour
        << "\" stroke-width=\"2\"" << (s.dashed ? " stroke-dasharray=\"6 4\"" : "")
        << "/><text x=\"" << kWidth - kRight + 46 << "\" y=\"" << ly + 4 << "\">" << escape(s.name)
        << "</text>\n";
  }
  svg << "</svg>\n";

  std::ofstream out(path);
  out << svg.str();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace tessera
