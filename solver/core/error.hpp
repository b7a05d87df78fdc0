#pragma once
// Errors a user can act on. InputError carries where the problem is (file and
// key path) so the command line can print one clear line and exit with status 2.
#include <exception>
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

namespace core {
// A checkpoint block that is missing, of the wrong size, or a file that is not a
// checkpoint (core/state_archive.hpp).
class StateMismatch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
}  // namespace core

// A distributed run: another process failed and reports why; this one stops with the
// same exit status (mpirun exits with the first non-zero status of its processes).
class OtherProcessFailed : public std::runtime_error {
 public:
  explicit OtherProcessFailed(int exit_status)
      : std::runtime_error("another process of the run failed"), exit_status_(exit_status) {}
  int exit_status() const { return exit_status_; }

 private:
  int exit_status_;
};

// A distributed run: an error of this process that every other process has learnt of
// (they stop with OtherProcessFailed), so none is left waiting. The error is nested.
class SharedFailure : public std::runtime_error {
 public:
  SharedFailure() : std::runtime_error("an error every process of the run knows of") {}
};

// The command line's exit status for an error (solver/app/commands.hpp): 2 bad input
// (a checkpoint that does not fit included), 3 a run that cannot continue, 4 anything
// else (an internal error).
inline int exit_status_of(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const InputError&) {
    return 2;
  } catch (const core::StateMismatch&) {
    return 2;
  } catch (const RunError&) {
    return 3;
  } catch (const OtherProcessFailed& e) {
    return e.exit_status();
  } catch (...) {
    return 4;
  }
}

}  // namespace pdmpm
