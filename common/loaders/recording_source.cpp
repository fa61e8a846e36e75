#include "common/loaders/recording_source.h"

namespace tessera {

std::optional<std::string> RecordingSource::read(const std::string& path) const {
  std::optional<std::string> bytes = first_.read(path);
  if (!bytes && fallback_) bytes = fallback_->read(path);
  if (bytes) read_[path] = *bytes;
  return bytes;
}

}  // namespace tessera
