#include "solver/io/output_directory.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <system_error>

#include "solver/core/error.hpp"

namespace pdmpm::io {

namespace fs = std::filesystem;

OutputDirectory::OutputDirectory(fs::path dir) : dir_(std::move(dir)) {
  const std::string shown = dir_.string();
  std::error_code ec;
  const fs::file_status status = fs::status(dir_, ec);
  if (fs::exists(status) && !fs::is_directory(status))
    throw RunError(fmt::format("output directory '{}' exists and is not a directory", shown));
  if (!fs::exists(status)) {
    fs::create_directories(dir_, ec);
    if (ec) throw RunError(fmt::format("cannot create output directory '{}': {}", shown, ec.message()));
  }
  // access() answers for the real user; the staging mkdir below is the real
  // test (it also catches read-only file systems, where root gets no pass).
  if (::access(dir_.c_str(), W_OK | X_OK) != 0)
    throw RunError(fmt::format("output directory '{}' is not writable", shown));

  const std::string base = fmt::format(".partial-{}", static_cast<long>(::getpid()));
  for (int attempt = 0;; ++attempt) {
    fs::path candidate = dir_ / (attempt == 0 ? base : fmt::format("{}-{}", base, attempt));
    if (fs::create_directory(candidate, ec)) {
      staging_ = std::move(candidate);
      break;
    }
    if (ec) throw RunError(fmt::format("output directory '{}' is not writable: {}", shown, ec.message()));
    if (attempt >= 1000) throw RunError(fmt::format("output directory '{}': too many staging directories", shown));
  }
}

OutputDirectory::~OutputDirectory() {
  if (committed_ || staging_.empty()) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);  // best effort: nothing to report to from here
}

fs::path OutputDirectory::path(const std::string& name) const {
  if (committed_) throw RunError(fmt::format("output directory '{}': path('{}') after commit", dir_.string(), name));
  const fs::path p(name);
  if (name.empty() || name == "." || name == ".." || p.has_parent_path() || p.is_absolute())
    throw RunError(fmt::format("output directory '{}': '{}' is not a plain file name", dir_.string(), name));
  return staging_ / p;
}

std::vector<fs::path> OutputDirectory::commit() {
  if (committed_) throw RunError(fmt::format("output directory '{}': committed twice", dir_.string()));
  std::vector<fs::path> staged;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(staging_, ec)) staged.push_back(entry.path());
  if (ec) throw RunError(fmt::format("output directory '{}': cannot list staged files: {}", dir_.string(), ec.message()));
  std::sort(staged.begin(), staged.end());

  std::vector<fs::path> final_paths;
  for (const fs::path& from : staged) {
    fs::path to = dir_ / from.filename();
    fs::rename(from, to, ec);
    if (ec)
      throw RunError(fmt::format("output directory '{}': cannot move '{}' into place: {}", dir_.string(),
                                 from.filename().string(), ec.message()));
    final_paths.push_back(std::move(to));
  }
  fs::remove(staging_, ec);
  if (ec) throw RunError(fmt::format("output directory '{}': cannot remove staging directory: {}", dir_.string(), ec.message()));
  committed_ = true;
  return final_paths;
}

}  // namespace pdmpm::io
