#include "verification/support/command_line.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>

namespace pdmpm::test {

CommandResult run_command(const std::string& command) {
  CommandResult r;
  // Grouped so a redirection inside `command` (e.g. 2>/dev/null) still wins over ours.
  FILE* pipe = popen(("{ " + command + "; } 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (std::size_t n = fread(buf.data(), 1, buf.size(), pipe)) r.output.append(buf.data(), n);
  const int rc = pclose(pipe);
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  return r;
}

CommandResult run_pdmpm(const std::string& args) {
  return run_command(std::string(PDMPM_BINARY_DIR) + "/pdmpm " + args);
}

}  // namespace pdmpm::test
