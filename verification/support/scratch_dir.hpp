#pragma once
// A scratch directory per test under the system's temporary directory, named by a
// tag and the process id (tests run side by side), removed with its contents when
// the object goes out of scope — even when a test made parts of it read-only.
#include <filesystem>
#include <string>

namespace pdmpm::test {

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag);
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // A path inside the directory that does not exist yet (e.g. a run's output directory).
  std::filesystem::path fresh(const std::string& name) const;

 private:
  std::filesystem::path path_;
};

}  // namespace pdmpm::test
