#include "coordinator/metrics/service_metrics.h"

namespace tessera {

ServiceMetrics::ServiceMetrics(MetricsRegistry& r)
    : registry(r),
      http_requests(
          r.counter("tessera_http_requests_total", "HTTP requests answered.", {"route", "status"})),
      http_received_bytes(
          r.counter("tessera_http_received_bytes_total", "Bytes of HTTP request bodies.").with()),
      http_sent_bytes(
          r.counter("tessera_http_sent_bytes_total", "Bytes of HTTP response bodies.").with()),
      units_dispatched(r.counter("tessera_units_dispatched_total",
                                 "Work units sent to workers, speculative copies included.")
                           .with()),
      units_finished(
          r.counter("tessera_units_finished_total", "Work units merged into their job.").with()),
      units_requeued(r.counter("tessera_units_requeued_total",
                               "Work units taken back from a lost or failing worker.")
                         .with()),
      unit_latency(r.histogram("tessera_unit_latency_seconds",
                               "From a unit's dispatch to its result's arrival.",
                               latency_buckets_seconds())
                       .with()),
      unit_render(r.histogram("tessera_unit_render_seconds",
                              "A unit's render time as its worker measured it.",
                              latency_buckets_seconds())
                      .with()),
      pixels(r.counter("tessera_pixels_total", "Pixel passes merged into jobs.").with()),
      rays(r.counter("tessera_rays_total", "Rays of every kind traced for merged units.").with()),
      worker_frames(r.counter("tessera_worker_port_frames_total",
                              "Frames on the worker port, by direction and message type.",
                              {"direction", "type"})),
      worker_received_bytes(r.counter("tessera_worker_port_received_bytes_total",
                                      "Bytes of frames read on the worker port, before TLS.")
                                .with()),
      worker_sent_bytes(r.counter("tessera_worker_port_sent_bytes_total",
                                  "Bytes of frames sent on the worker port, before TLS.")
                            .with()),
      jobs(r.gauge("tessera_jobs", "Jobs held, by state.", {"state"})),
      workers(r.gauge("tessera_workers", "Connected workers.").with()),
      worker_threads(
          r.gauge("tessera_worker_threads", "Render threads of the connected workers.").with()),
      store_bytes(r.gauge("tessera_store_bytes",
                          "The data directory's size as --max-disk counts it: the database's "
                          "used pages, bundles and images.")
                      .with()) {}

void ServiceMetrics::count_worker_frame(bool sent, std::optional<MessageType> type,
                                        std::size_t bytes) {
  worker_frames.with({sent ? "sent" : "received", type ? to_string(*type) : "invalid"}).add();
  (sent ? worker_sent_bytes : worker_received_bytes).add(static_cast<double>(bytes));
}

std::string route_label(const std::string& path) {
  if (path == "/metrics" || path == "/api/workers" || path == "/api/predict" || path == "/api/jobs")
    return path;
  const std::string jobs = "/api/jobs/";
  if (path.starts_with(jobs)) {
    const std::string rest = path.substr(jobs.size());
    const auto slash = rest.find('/');
    const std::string id = rest.substr(0, slash);
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) return "other";
    if (slash == std::string::npos) return "/api/jobs/{id}";
    const std::string sub = rest.substr(slash + 1);
    if (sub == "image" || sub == "tiles" || sub == "rerender") return "/api/jobs/{id}/" + sub;
    return "other";
  }
  if (path.starts_with("/api/")) return "other";
  return "static";
}

}  // namespace tessera
