#include "client/cli/quiet.h"

namespace soiq::cli {

namespace {
bool g_quiet = false;
}  // namespace

void set_quiet(bool quiet) { g_quiet = quiet; }
bool quiet() { return g_quiet; }

}  // namespace soiq::cli
