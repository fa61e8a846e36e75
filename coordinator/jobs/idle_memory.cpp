#include "coordinator/jobs/idle_memory.h"

#include <malloc.h>

namespace tessera {

bool IdleMemory::tick(bool jobs_unfinished, Clock::time_point now) {
  if (jobs_unfinished) {
    pool_.renew(now);
    busy_ = now;
    trimmed_ = false;
    return false;
  }
  pool_.release_idle(now);
  if (trimmed_ || now - busy_ < after_) return false;
  malloc_trim(0);  // glibc gives freed heap back only when trimmed
  trimmed_ = true;
  return true;
}

}  // namespace tessera
