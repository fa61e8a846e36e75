// A scene source that remembers the files a load read, so that exactly those travel with the
// scene: the coordinator's bundle of a job (coordinator/jobs/job_request.cpp) and the files
// tessera-submit sends (client/scene_bundle.h).
#pragma once

#include <map>
#include <optional>
#include <string>

#include "common/loaders/scene_source.h"

namespace tessera {

class RecordingSource : public SceneSource {
 public:
  // Reads from `first`, else from `fallback` when there is one.
  explicit RecordingSource(const SceneSource& first, const SceneSource* fallback = nullptr)
      : first_(first), fallback_(fallback) {}
  std::optional<std::string> read(const std::string& path) const override;
  bool admits(const std::string& path) const override { return first_.admits(path); }
  // Every file read so far, by its root-relative path.
  const std::map<std::string, std::string>& files() const { return read_; }

 private:
  const SceneSource& first_;
  const SceneSource* fallback_;
  mutable std::map<std::string, std::string> read_;
};

}  // namespace tessera
