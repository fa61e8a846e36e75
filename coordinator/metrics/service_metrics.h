// Every metric the coordinator exports at GET /metrics, created once in one place so that the
// list in docs/SERVICE.md ("Metrics") has one source. The HTTP layer counts requests, the
// scheduler counts units; values that live elsewhere (jobs by state, connected workers) are
// read by collectors when /metrics is asked for.
#pragma once

#include <string>

#include "coordinator/metrics/metrics.h"

namespace tessera {

struct ServiceMetrics {
  explicit ServiceMetrics(MetricsRegistry& registry);

  MetricsRegistry& registry;
  // HTTP, by route pattern (route_label) and status.
  Family<Counter>& http_requests;
  Counter& http_received_bytes;  // request bodies
  Counter& http_sent_bytes;      // response bodies
  // Work units.
  Counter& units_dispatched;  // sent to a worker, speculative copies included
  Counter& units_finished;    // merged into a job
  Counter& units_requeued;    // taken back from a lost or failing worker
  Histogram& unit_latency;    // from dispatch to the result's arrival, seconds
  Histogram& unit_render;     // the worker's own render time of a unit, seconds
  Counter& pixels;            // pixel passes merged
  Counter& rays;              // rays of every kind traced for merged units
  // Read at scrape time (collectors set them).
  Family<Gauge>& jobs;  // by state
  Gauge& workers;
  Gauge& worker_threads;
};

// The label for a request path: the route it matched, with ids replaced ("/api/jobs/{id}"),
// so that the label takes few values; "static" for the page's files, "other" for the rest.
std::string route_label(const std::string& path);

}  // namespace tessera
