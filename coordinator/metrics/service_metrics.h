// Every metric the coordinator exports at GET /metrics, created once in one place so that the
// list in docs/SERVICE.md ("Metrics") has one source. The HTTP layer counts requests, the
// scheduler counts units; values that live elsewhere (jobs by state, connected workers) are
// read by collectors when /metrics is asked for.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "common/protocol/frame.h"
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
  // The worker port: frames by direction and type ("invalid" for those that do not decode),
  // and their bytes.
  Family<Counter>& worker_frames;
  Counter& worker_received_bytes;
  Counter& worker_sent_bytes;
  // Read at scrape time (collectors set them).
  Family<Gauge>& jobs;  // by state
  Gauge& workers;
  Gauge& worker_threads;
  Gauge& store_bytes;  // the data directory as counted against --max-disk

  // Counts one frame of a worker connection (FrameTraffic).
  void count_worker_frame(bool sent, std::optional<MessageType> type, std::size_t bytes);
};

// The label for a request path: the route it matched, with ids replaced ("/api/jobs/{id}"),
// so that the label takes few values; "static" for the page's files, "other" for the rest.
std::string route_label(const std::string& path);

}  // namespace tessera
