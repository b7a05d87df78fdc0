#pragma once
// Running a shell command or the pdmpm executable from a test: exit status and
// everything it printed (stdout and stderr, interleaved as they were written).
#include <string>

namespace pdmpm::test {

struct CommandResult {
  int status = -1;     // exit status; −1 if the command could not start or was killed
  std::string output;  // stdout + stderr
};

CommandResult run_command(const std::string& command);

// `pdmpm <args>` from this build tree.
CommandResult run_pdmpm(const std::string& args);

}  // namespace pdmpm::test
