// tessera-submit: renders a scene file on a coordinator, as tessera-render would here.
#include <cstdio>
#include <string>
#include <vector>

#include "client/submit_job.h"
#include "client/submit_options.h"

int main(int argc, char** argv) {
  using namespace tessera;
  const auto parsed = parse_submit_cli(std::vector<std::string>(argv + 1, argv + argc));
  if (std::holds_alternative<SubmitHelp>(parsed)) {
    std::fputs(submit_cli_usage().c_str(), stdout);
    return 0;
  }
  if (const auto* error = std::get_if<std::string>(&parsed)) {
    std::fprintf(stderr, "tessera-submit: %s (tessera-submit --help lists the options)\n",
                 error->c_str());
    return 2;
  }
  return submit_job(std::get<SubmitOptions>(parsed));
}
