#include "verification/support/scratch_dir.hpp"

#include <unistd.h>

namespace pdmpm::test {

namespace fs = std::filesystem;

ScratchDir::ScratchDir(const std::string& tag)
    : path_(fs::temp_directory_path() / ("pdmpm_" + tag + "_" + std::to_string(::getpid()))) {
  fs::remove_all(path_);
  fs::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  // Give back write permission anywhere a test took it away, so removal succeeds.
  for (auto it = fs::recursive_directory_iterator(path_, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
    fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ec);
  fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
  fs::remove_all(path_, ec);
}

fs::path ScratchDir::fresh(const std::string& name) const {
  const fs::path p = path_ / name;
  fs::remove_all(p);
  return p;
}

}  // namespace pdmpm::test
