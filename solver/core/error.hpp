#pragma once
// Errors a user can act on. InputError carries where the problem is (file and
// key path) so the command line can print one clear line and exit with status 2.
#include <stdexcept>
#include <string>

namespace pdmpm {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string key, std::string message)
      : std::runtime_error(format(file, key, message)), file_(std::move(file)), key_(std::move(key)) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }

 private:
  static std::string format(const std::string& file, const std::string& key, const std::string& message) {
    std::string s = file.empty() ? std::string("input") : file;
    if (!key.empty()) s += ": key '" + key + "'";
    return s + ": " + message;
  }
  std::string file_, key_;
};

// A run that cannot continue (instability, non-finite state); not the user's input.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pdmpm
