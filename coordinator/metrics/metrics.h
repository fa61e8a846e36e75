// The coordinator's metrics in Prometheus' text exposition format (version 0.0.4), served at
// GET /metrics. Names follow Prometheus' rules: a `tessera_` prefix, base units (`_seconds`,
// `_bytes`), `_total` for counters; labels take few values (route, status, state), never a job
// id. Debian packages no Prometheus client for C++, and the format is small.
//
// Families are created once, at start; their series are updated from any thread (a counter or
// a histogram is a few atomics or one short lock), and read when /metrics is asked for.
// Values known only at scrape time (jobs by state, connected workers) come from collectors.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera {

// Label values in declaration order of the family's label names.
using LabelValues = std::vector<std::string>;

class Counter {
 public:
  void add(double amount = 1);
  double value() const { return value_.load(std::memory_order_relaxed); }

 private:
  std::atomic<double> value_{0};
};

class Gauge {
 public:
  void set(double v) { value_.store(v, std::memory_order_relaxed); }
  double value() const { return value_.load(std::memory_order_relaxed); }

 private:
  std::atomic<double> value_{0};
};

class Histogram {
 public:
  explicit Histogram(std::vector<double> upper_bounds);
  void observe(double v);
  struct Snapshot {
    std::vector<double> upper_bounds;
    std::vector<unsigned long long> cumulative;  // per bound, then +Inf
    double sum = 0;
  };
  Snapshot snapshot() const;

 private:
  const std::vector<double> bounds_;
  mutable std::mutex mutex_;
  std::vector<unsigned long long> counts_;  // per bucket (not cumulative), then +Inf
  double sum_ = 0;
};

// Buckets for latencies from a millisecond to a minute, about 2.5x apart.
std::vector<double> latency_buckets_seconds();

template <class Series>
class Family {
 public:
  Family(std::string name, std::string help, std::vector<std::string> label_names,
         std::function<std::unique_ptr<Series>()> make)
      : name_(std::move(name)),
        help_(std::move(help)),
        label_names_(std::move(label_names)),
        make_(std::move(make)) {}
  // The series of these label values, made on first use. References stay valid.
  Series& with(const LabelValues& labels = {}) {
    if (labels.size() != label_names_.size())
      throw std::invalid_argument(name_ + ": " + std::to_string(label_names_.size()) +
                                  " label values expected");
    std::lock_guard lock(mutex_);
    auto& slot = series_[labels];
    if (!slot) slot = make_();
    return *slot;
  }
  const std::string& name() const { return name_; }
  const std::string& help() const { return help_; }
  const std::vector<std::string>& label_names() const { return label_names_; }
  template <class F>
  void for_each(F f) const {
    std::lock_guard lock(mutex_);
    for (const auto& [labels, series] : series_) f(labels, *series);
  }

 private:
  std::string name_, help_;
  std::vector<std::string> label_names_;
  std::function<std::unique_ptr<Series>()> make_;
  mutable std::mutex mutex_;
  std::map<LabelValues, std::unique_ptr<Series>> series_;
};

class MetricsRegistry {
 public:
  Family<Counter>& counter(const std::string& name, const std::string& help,
                           std::vector<std::string> label_names = {});
  Family<Gauge>& gauge(const std::string& name, const std::string& help,
                       std::vector<std::string> label_names = {});
  Family<Histogram>& histogram(const std::string& name, const std::string& help,
                               std::vector<double> upper_bounds,
                               std::vector<std::string> label_names = {});
  // Runs before every exposition, on the thread that asks for it: sets gauges whose values
  // live elsewhere (the coordinator calls expose() on its io thread).
  void add_collector(std::function<void()> collect);

  // The text exposition of every family, in the order they were created.
  std::string expose() const;

 private:
  void check_new_name(const std::string& name) const;
  std::vector<std::function<void()>> collectors_;
  std::vector<std::unique_ptr<Family<Counter>>> counters_;
  std::vector<std::unique_ptr<Family<Gauge>>> gauges_;
  std::vector<std::unique_ptr<Family<Histogram>>> histograms_;
  std::vector<std::pair<char, std::size_t>> order_;  // 'c', 'g', 'h' and the index
};

// The exposition format's escaping of a label value (backslash, double quote, newline).
std::string escape_label_value(const std::string& value);

}  // namespace tessera
