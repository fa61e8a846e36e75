// The metrics registry's exposition text, checked line by line against the Prometheus text
// format (0.0.4), with values worked out by hand.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "coordinator/metrics/metrics.h"

namespace tessera {
namespace {

TEST(Metrics, CountersAndGaugesWithTheirLabels) {
  MetricsRegistry r;
  auto& requests =
      r.counter("tessera_http_requests_total", "HTTP requests answered.", {"route", "status"});
  auto& workers = r.gauge("tessera_workers", "Connected workers.");
  requests.with({"/api/jobs", "201"}).add();
  requests.with({"/api/jobs", "201"}).add(2);
  requests.with({"/api/jobs", "400"}).add();
  workers.with().set(3);
  EXPECT_EQ(r.expose(),
            "# HELP tessera_http_requests_total HTTP requests answered.\n"
            "# TYPE tessera_http_requests_total counter\n"
            "tessera_http_requests_total{route=\"/api/jobs\",status=\"201\"} 3\n"
            "tessera_http_requests_total{route=\"/api/jobs\",status=\"400\"} 1\n"
            "# HELP tessera_workers Connected workers.\n"
            "# TYPE tessera_workers gauge\n"
            "tessera_workers 3\n");
}

TEST(Metrics, HistogramBucketsAreCumulativeAndInclusive) {
  MetricsRegistry r;
  auto& h = r.histogram("tessera_unit_seconds", "Unit latency.", {0.1, 1});
  for (double v : {0.05, 0.1, 0.5, 3.0}) h.with().observe(v);
  EXPECT_EQ(r.expose(),
            "# HELP tessera_unit_seconds Unit latency.\n"
            "# TYPE tessera_unit_seconds histogram\n"
            "tessera_unit_seconds_bucket{le=\"0.1\"} 2\n"
            "tessera_unit_seconds_bucket{le=\"1\"} 3\n"
            "tessera_unit_seconds_bucket{le=\"+Inf\"} 4\n"
            "tessera_unit_seconds_sum 3.65\n"
            "tessera_unit_seconds_count 4\n");
}

TEST(Metrics, LabelledHistogramsPutLeLast) {
  MetricsRegistry r;
  auto& h = r.histogram("tessera_x_seconds", "X.", {1}, {"kind"});
  h.with({"a"}).observe(2);
  const std::string text = r.expose();
  EXPECT_NE(text.find("tessera_x_seconds_bucket{kind=\"a\",le=\"1\"} 0\n"), std::string::npos);
  EXPECT_NE(text.find("tessera_x_seconds_bucket{kind=\"a\",le=\"+Inf\"} 1\n"), std::string::npos);
  EXPECT_NE(text.find("tessera_x_seconds_count{kind=\"a\"} 1\n"), std::string::npos);
}

TEST(Metrics, LabelValuesAndHelpAreEscaped) {
  MetricsRegistry r;
  r.gauge("tessera_g", "A \\ help\nline.", {"name"}).with({"a\"b\\c\nd"}).set(-0.5);
  EXPECT_EQ(r.expose(),
            "# HELP tessera_g A \\\\ help\\nline.\n"
            "# TYPE tessera_g gauge\n"
            "tessera_g{name=\"a\\\"b\\\\c\\nd\"} -0.5\n");
}

TEST(Metrics, CollectorsRunBeforeEachExposition) {
  MetricsRegistry r;
  auto& g = r.gauge("tessera_jobs", "Jobs.", {"state"});
  int calls = 0;
  r.add_collector([&] { g.with({"running"}).set(++calls); });
  EXPECT_NE(r.expose().find("tessera_jobs{state=\"running\"} 1\n"), std::string::npos);
  EXPECT_NE(r.expose().find("tessera_jobs{state=\"running\"} 2\n"), std::string::npos);
}

TEST(Metrics, NamesAndLabelsAreChecked) {
  MetricsRegistry r;
  EXPECT_THROW(r.counter("tessera_units", "No _total suffix."), std::invalid_argument);
  EXPECT_THROW(r.gauge("1bad", "Starts with a digit."), std::invalid_argument);
  EXPECT_THROW(r.gauge("bad-name", "A dash."), std::invalid_argument);
  r.gauge("tessera_once", "Once.");
  EXPECT_THROW(r.gauge("tessera_once", "Twice."), std::invalid_argument);
  EXPECT_THROW(r.histogram("tessera_h", "Bounds.", {1, 0.5}), std::invalid_argument);
  auto& labelled = r.counter("tessera_l_total", "Two labels.", {"a", "b"});
  EXPECT_THROW(labelled.with({"only one"}), std::invalid_argument);
  EXPECT_THROW(labelled.with({"x", "y"}).add(-1), std::invalid_argument);
}

TEST(Metrics, CountsFromManyThreadsAddUp) {
  MetricsRegistry r;
  auto& c = r.counter("tessera_c_total", "C.");
  auto& h = r.histogram("tessera_h_seconds", "H.", {0.5});
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&] {
      for (int i = 0; i < 10000; ++i) {
        c.with().add();
        h.with().observe(i % 2 ? 1.0 : 0.25);
      }
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(c.with().value(), 40000);
  const auto s = h.with().snapshot();
  EXPECT_EQ(s.cumulative, (std::vector<unsigned long long>{20000, 40000}));
  EXPECT_EQ(s.sum, 20000 * 1.0 + 20000 * 0.25);
}

}  // namespace
}  // namespace tessera
