#include "coordinator/metrics/metrics.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace tessera {
namespace {

// Shortest text that reads back as the same double; the format's own spellings for the rest.
std::string number(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

std::string label_set(const std::vector<std::string>& names, const LabelValues& values,
                      const std::string& extra_name = {}, const std::string& extra_value = {}) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < values.size(); ++i)
    out += (out.empty() ? "" : ",") + names[i] + "=\"" + escape_label_value(values[i]) + "\"";
  if (!extra_name.empty())
    out += (out.empty() ? "" : ",") + extra_name + "=\"" + escape_label_value(extra_value) + "\"";
  return out.empty() ? "" : "{" + out + "}";
}

// HELP text escapes only backslash and newline.
std::string escape_help(const std::string& help) {
  std::string out;
  for (char c : help) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out;
}

template <class Series>
void header(std::string& out, const Family<Series>& family, const char* type) {
  out += "# HELP " + family.name() + " " + escape_help(family.help()) + "\n";
  out += "# TYPE " + family.name() + " " + type + "\n";
}

bool valid_name(const std::string& name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':';
  });
}

}  // namespace

std::string escape_label_value(const std::string& value) {
  std::string out;
  for (char c : value) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '"')
      out += "\\\"";
    else if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out;
}

void Counter::add(double amount) {
  if (!(amount >= 0)) throw std::invalid_argument("a counter only goes up");
  value_.fetch_add(amount, std::memory_order_relaxed);
}

Histogram::Histogram(std::vector<double> upper_bounds)
    : bounds_(std::move(upper_bounds)), counts_(bounds_.size() + 1, 0) {
  if (!std::is_sorted(bounds_.begin(), bounds_.end()) ||
      std::adjacent_find(bounds_.begin(), bounds_.end()) != bounds_.end())
    throw std::invalid_argument("histogram bounds must increase");
}

void Histogram::observe(double v) {
  // Buckets hold v <= bound; a NaN counts only in +Inf, as Prometheus' own clients do.
  const auto bucket = static_cast<std::size_t>(std::lower_bound(bounds_.begin(), bounds_.end(), v) -
                                               bounds_.begin());
  std::lock_guard lock(mutex_);
  ++counts_[std::isnan(v) ? bounds_.size() : bucket];
  sum_ += v;
}

Histogram::Snapshot Histogram::snapshot() const {
  Snapshot s;
  s.upper_bounds = bounds_;
  std::lock_guard lock(mutex_);
  unsigned long long running = 0;
  for (unsigned long long c : counts_) s.cumulative.push_back(running += c);
  s.sum = sum_;
  return s;
}

std::vector<double> latency_buckets_seconds() {
  return {0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10, 25, 60};
}

void MetricsRegistry::check_new_name(const std::string& name) const {
  if (!valid_name(name)) throw std::invalid_argument("bad metric name \"" + name + "\"");
  const auto taken = [&](const auto& families) {
    return std::any_of(families.begin(), families.end(),
                       [&](const auto& f) { return f->name() == name; });
  };
  if (taken(counters_) || taken(gauges_) || taken(histograms_))
    throw std::invalid_argument("metric \"" + name + "\" registered twice");
}

Family<Counter>& MetricsRegistry::counter(const std::string& name, const std::string& help,
                                          std::vector<std::string> label_names) {
  check_new_name(name);
  if (!name.ends_with("_total"))
    throw std::invalid_argument("counter \"" + name + "\" must end in _total");
  counters_.push_back(std::make_unique<Family<Counter>>(
      name, help, std::move(label_names), [] { return std::make_unique<Counter>(); }));
  order_.emplace_back('c', counters_.size() - 1);
  return *counters_.back();
}

Family<Gauge>& MetricsRegistry::gauge(const std::string& name, const std::string& help,
                                      std::vector<std::string> label_names) {
  check_new_name(name);
  gauges_.push_back(std::make_unique<Family<Gauge>>(name, help, std::move(label_names),
                                                    [] { return std::make_unique<Gauge>(); }));
  order_.emplace_back('g', gauges_.size() - 1);
  return *gauges_.back();
}

Family<Histogram>& MetricsRegistry::histogram(const std::string& name, const std::string& help,
                                              std::vector<double> upper_bounds,
                                              std::vector<std::string> label_names) {
  check_new_name(name);
  Histogram validated(upper_bounds);  // throws for bounds that do not increase
  histograms_.push_back(std::make_unique<Family<Histogram>>(
      name, help, std::move(label_names),
      [upper_bounds] { return std::make_unique<Histogram>(upper_bounds); }));
  order_.emplace_back('h', histograms_.size() - 1);
  return *histograms_.back();
}

void MetricsRegistry::add_collector(std::function<void()> collect) {
  collectors_.push_back(std::move(collect));
}

std::string MetricsRegistry::expose() const {
  for (const auto& collect : collectors_) collect();
  std::string out;
  for (const auto& [kind, index] : order_) {
    if (kind == 'c') {
      const Family<Counter>& f = *counters_[index];
      header(out, f, "counter");
      f.for_each([&](const LabelValues& labels, const Counter& c) {
        out += f.name() + label_set(f.label_names(), labels) + " " + number(c.value()) + "\n";
      });
    } else if (kind == 'g') {
      const Family<Gauge>& f = *gauges_[index];
      header(out, f, "gauge");
      f.for_each([&](const LabelValues& labels, const Gauge& g) {
        out += f.name() + label_set(f.label_names(), labels) + " " + number(g.value()) + "\n";
      });
    } else {
      const Family<Histogram>& f = *histograms_[index];
      header(out, f, "histogram");
      f.for_each([&](const LabelValues& labels, const Histogram& h) {
        const Histogram::Snapshot s = h.snapshot();
        for (std::size_t b = 0; b <= s.upper_bounds.size(); ++b) {
          const std::string le = b < s.upper_bounds.size() ? number(s.upper_bounds[b]) : "+Inf";
          out += f.name() + "_bucket" + label_set(f.label_names(), labels, "le", le) + " " +
                 std::to_string(s.cumulative[b]) + "\n";
        }
        const std::string set = label_set(f.label_names(), labels);
        out += f.name() + "_sum" + set + " " + number(s.sum) + "\n";
        out += f.name() + "_count" + set + " " + std::to_string(s.cumulative.back()) + "\n";
      });
    }
  }
  return out;
}

}  // namespace tessera
