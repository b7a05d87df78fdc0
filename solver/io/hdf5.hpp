#pragma once
// Thin layer over the HDF5 C API: identifiers that close themselves, and
// failures that become pdmpm::RunError carrying HDF5's own explanation instead
// of a stack dump on stderr.
#include <hdf5.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pdmpm::io::h5 {

// Turns off HDF5's automatic printing of its error stack (for this thread's
// default stack); errors are reported through exceptions instead.
void silence_automatic_errors();

// Text of the current HDF5 error stack (outermost call, innermost cause), then
// clears it. Empty when the stack is empty.
std::string take_error_stack();

// Throws RunError("HDF5: <what>: <stack>") when an HDF5 call returned < 0.
hid_t check(hid_t id, std::string_view what);
void check(herr_t status, std::string_view what);

// Owns one identifier and closes it with the H5*close that matches its type.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id_(other.id_) { other.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  hid_t get() const { return id_; }
  explicit operator bool() const { return id_ >= 0; }
  // Closes now and reports a failure (the destructor has to stay silent).
  void close(std::string_view what);
  void reset() noexcept;

 private:
  hid_t id_ = H5I_INVALID_HID;
};

Handle create_file(const std::string& path);
Handle open_file_for_writing(const std::string& path);  // an existing file, read-write
Handle create_group(hid_t parent, const std::string& name);
Handle open_group(hid_t parent, const std::string& name);
// Names of the links in a group, in name order.
std::vector<std::string> link_names(hid_t group);
void delete_link(hid_t parent, const std::string& name);
bool link_exists(hid_t parent, const std::string& name);
// Writes what the library holds of the file to disk (it stays open).
void flush(hid_t file);

// Contiguous dataset of shape dims (row-major), stored as little-endian IEEE
// doubles / int32 whatever the machine.
void write_dataset(hid_t parent, const std::string& name, std::span<const double> data, std::span<const hsize_t> dims);
void write_dataset(hid_t parent, const std::string& name, std::span<const std::int32_t> data,
                   std::span<const hsize_t> dims);

// Scalar attributes; an existing attribute of the same name is overwritten.
void write_attribute(hid_t object, const std::string& name, double value);
void write_attribute(hid_t object, const std::string& name, std::int64_t value);
void write_attribute(hid_t object, const std::string& name, int value);

}  // namespace pdmpm::io::h5
