#pragma once
// Transactional output: files are written into a hidden staging directory
// inside the output directory and only moved into place by commit(). A run
// that fails (exception, early return) destroys the object without commit and
// leaves the output directory as it was before the run.
//
// commit() renames file by file; each rename is atomic (same file system), so
// every output file is either the old one or the complete new one.
#include <filesystem>
#include <string>
#include <vector>

namespace pdmpm::io {

class OutputDirectory {
 public:
  // Creates dir (and parents) if needed, then the staging directory
  // dir/.partial-<pid> (a -<k> suffix is added if that name is in use).
  explicit OutputDirectory(std::filesystem::path dir);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // Staging path for a file that will be called dir/name after commit().
  // name must be a plain file name (no directories, not "." or "..").
  std::filesystem::path path(const std::string& name) const;

  // Moves every staged file into dir, replacing files of the same name, and
  // removes the staging directory. Returns the final paths. Call once.
  std::vector<std::filesystem::path> commit();

  const std::filesystem::path& directory() const { return dir_; }
  const std::filesystem::path& staging() const { return staging_; }
  bool committed() const { return committed_; }

 private:
  std::filesystem::path dir_, staging_;
  bool committed_ = false;
};

}  // namespace pdmpm::io
