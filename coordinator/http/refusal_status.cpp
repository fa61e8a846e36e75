#include "coordinator/http/refusal_status.h"

namespace tessera {

int http_status(Refusal refusal) {
  switch (refusal) {
    case Refusal::bad_request:
      return 400;
    case Refusal::unauthorized:
      return 401;
    case Refusal::forbidden:
      return 403;
    case Refusal::not_found:
      return 404;
    case Refusal::method_not_allowed:
      return 405;
    case Refusal::too_large:
      return 413;
    case Refusal::unsupported_media_type:
      return 415;
    case Refusal::unprocessable:
      return 422;
    case Refusal::too_many_jobs:
      return 429;
    case Refusal::busy:
      return 503;
    case Refusal::cannot_store:
      return 507;
  }
  return 500;
}

}  // namespace tessera
