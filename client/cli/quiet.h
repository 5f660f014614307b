#pragma once
// The global --quiet (-q) option: no progress bars, notes or summaries on stderr. Errors still
// show, and so do the lines that say an answer is partial (skipped candidates), since an exit
// code alone does not say why. `soiq upload` prints only the new id. Set once, by
// take_remote_options, before the command runs.

namespace soiq::cli {

void set_quiet(bool quiet);
bool quiet();

}  // namespace soiq::cli
