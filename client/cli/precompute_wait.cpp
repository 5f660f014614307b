#include "client/cli/precompute_wait.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "client/cli/interrupt.h"
#include "client/cli/progress_bar.h"
#include "client/cli/quiet.h"

namespace soiq::cli {

Result<bool> wait_for_precompute(const client::Client& c) {
  ProgressBar bar;
  int64_t most = 0;  // the longest queue seen: the bar's total
  while (true) {
    SOIQ_ASSIGN_OR_RETURN(const soiq::v1::ServerInfo info, c.server_info());
    if (!info.precompute_enabled()) {
      bar.clear();
      return false;
    }
    const int64_t queued = info.precompute_queued();
    if (queued == 0) {
      bar.clear();
      return true;
    }
    most = std::max(most, queued);
    bar.update("precompute", most - queued, most);
    if (interrupted()) {
      bar.clear();
      return Status(StatusCode::kCancelled, "stopped waiting for precompute (it goes on in soiqd)");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

Status wait_option(const client::Client& c) {
  SOIQ_ASSIGN_OR_RETURN(const bool waited, wait_for_precompute(c));
  if (!waited && !quiet()) std::fprintf(stderr, "soiq: soiqd runs with --precompute off; nothing to wait for\n");
  return ok_status();
}

}  // namespace soiq::cli
