#pragma once
// The state of a run as named blocks of bytes: what a checkpoint holds.
//
// Every class with state that outlives a step has one member
//   void checkpoint(core::StateArchive& a);
// that passes each such member through a.sync(name, member). Saving copies the
// member into the archive, restoring copies it back: one function for both
// directions, so they cannot drift apart. A restore that finds a block missing
// or of another size (another scene, another build) throws StateMismatch; a
// block nobody asked for is caught by unread() after the restore.
//
// Blocks hold the bytes of trivially copyable values and of Eigen's fixed-size
// matrices, so a restored double is the same bits as the saved one (a resumed
// run continues bitwise). The file (write/read) is this machine's byte order
// with a 64-bit FNV-1a checksum over everything before it.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "solver/core/error.hpp"  // StateMismatch

namespace pdmpm::core {

namespace detail {
template <class T>
concept EigenFixed = requires {
  typename T::Scalar;
  T::SizeAtCompileTime;
}
&&(T::SizeAtCompileTime > 0) && (sizeof(T) == sizeof(typename T::Scalar) * T::SizeAtCompileTime);
}  // namespace detail

// A struct of such values (Eigen members make it not trivially copyable by the
// standard's rule) opts in by specialising this for itself.
template <class T>
inline constexpr bool kBytesAreValue = false;

// Values whose bytes are the value: what sync() accepts.
template <class T>
concept ByteCopyable = std::is_trivially_copyable_v<T> || detail::EigenFixed<T> || kBytesAreValue<T>;

class StateArchive {
 public:
  enum class Mode { save, restore };
  explicit StateArchive(Mode mode) : mode_(mode) {}

  bool saving() const { return mode_ == Mode::save; }

  template <ByteCopyable T>
  void sync(const std::string& name, T& value) {
    if (saving()) {
      put(name, &value, sizeof(T));
    } else {
      const std::string& bytes = take(name, sizeof(T), 1);
      std::memcpy(static_cast<void*>(&value), bytes.data(), sizeof(T));
    }
  }
  // A vector takes the stored length (lists that grow in a run, such as contact partners).
  template <ByteCopyable T>
  void sync(const std::string& name, std::vector<T>& values) {
    if (saving()) {
      put(name, values.data(), values.size() * sizeof(T));
    } else {
      const std::string& bytes = take(name, sizeof(T), 0);
      values.resize(bytes.size() / sizeof(T));
      if (!bytes.empty()) std::memcpy(static_cast<void*>(values.data()), bytes.data(), bytes.size());
    }
  }
  void sync(const std::string& name, std::string& text);
  // A count the scene fixes (particles, bonds, grid nodes): saved, and on restore
  // compared — StateMismatch naming it when the checkpoint's differs. Restored
  // vectors take the stored length, so these checks come first.
  void expect(const std::string& name, std::int64_t value);

  // Restore: the blocks no sync() has read (state this build does not know).
  std::vector<std::string> unread() const;
  bool contains(const std::string& name) const { return blocks_.count(name) > 0; }

  // A saved archive as one to restore from, in memory: for running the same state
  // more than once (benchmark samples that must all start alike).
  StateArchive restorer() const {
    StateArchive r(Mode::restore);
    r.blocks_ = blocks_;
    return r;
  }

  // Writes the archive to `path` (the caller makes it atomic by writing a temporary
  // name and renaming); throws std::runtime_error naming the file on failure.
  void write(const std::filesystem::path& path) const;
  // Reads a file written by write() for restoring; StateMismatch if it is not one
  // (wrong magic, truncated, checksum).
  static StateArchive read(const std::filesystem::path& path);

 private:
  void put(const std::string& name, const void* data, std::size_t bytes);
  // The block `name` for restoring; its size must be `count` elements of `element`
  // bytes, or any whole number of them when count is 0.
  const std::string& take(const std::string& name, std::size_t element, std::size_t count);

  Mode mode_;
  std::map<std::string, std::string> blocks_;
  std::set<std::string> read_;
};

}  // namespace pdmpm::core
