#pragma once
// `soiq man`: the soiq(1) manual page in roff (man(7) macros), made from the command table
// (command_table.h) so that it says what `soiq help` says. The build writes it to man/soiq.1 and
// `cmake --install` puts it in share/man/man1. roff_escape keeps text literal in roff: backslashes,
// a leading dot or quote, and hyphens as minus signs (\-) so that options can be searched and copied.

#include <string>
#include <string_view>

#include "client/soiq_client.h"

namespace soiq::cli {

std::string roff_escape(std::string_view text);

std::string soiq_man_page();

// Prints soiq_man_page(); takes no arguments.
int run_man_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
