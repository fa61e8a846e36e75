// What tessera-submit does: bundle the scene, submit it (POST /api/jobs as a form), follow the
// job's progress, download the image. Returns the exit status: 0 done, 1 any failure (with a
// message on stderr naming what failed).
#pragma once

#include "client/submit_options.h"

namespace tessera {

int submit_job(const SubmitOptions& options);

}  // namespace tessera
