// The HTTP status that answers each kind of refusal (jobs/api_error.h).
#pragma once

#include "coordinator/jobs/api_error.h"

namespace tessera {

int http_status(Refusal refusal);

}  // namespace tessera
