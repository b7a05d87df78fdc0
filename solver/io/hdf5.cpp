#include "solver/io/hdf5.hpp"

#include <fmt/format.h>

#include <vector>

#include "solver/core/error.hpp"

namespace pdmpm::io::h5 {
namespace {

struct StackEntry {
  std::string function, description, minor;
};

herr_t collect_entry(unsigned /*n*/, const H5E_error2_t* error, void* data) {
  auto& entries = *static_cast<std::vector<StackEntry>*>(data);
  StackEntry entry;
  entry.function = error->func_name ? error->func_name : "";
  entry.description = error->desc ? error->desc : "";
  char minor[256] = {0};
  if (H5Eget_msg(error->min_num, nullptr, minor, sizeof minor) > 0) entry.minor = minor;
  entries.push_back(std::move(entry));
  return 0;
}

herr_t close_any(hid_t id) {
  switch (H5Iget_type(id)) {
    case H5I_FILE:
      return H5Fclose(id);
    case H5I_GROUP:
      return H5Gclose(id);
    case H5I_DATASET:
      return H5Dclose(id);
    case H5I_DATASPACE:
      return H5Sclose(id);
    case H5I_ATTR:
      return H5Aclose(id);
    case H5I_DATATYPE:
      return H5Tclose(id);
    case H5I_GENPROP_LST:
      return H5Pclose(id);
    default:
      return H5Idec_ref(id) < 0 ? -1 : 0;
  }
}

Handle scalar_space() { return Handle(check(H5Screate(H5S_SCALAR), "create scalar dataspace")); }

template <class T>
void write_scalar_attribute(hid_t object, const std::string& name, hid_t file_type, hid_t memory_type, const T& value) {
  // Deleting first lets a value be updated even if its type changed.
  const htri_t exists = H5Aexists(object, name.c_str());
  check(static_cast<herr_t>(exists), "query attribute '" + name + "'");
  if (exists > 0) check(H5Adelete(object, name.c_str()), "replace attribute '" + name + "'");
  Handle space = scalar_space();
  Handle attribute(check(H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         "create attribute '" + name + "'"));
  check(H5Awrite(attribute.get(), memory_type, &value), "write attribute '" + name + "'");
  attribute.close("close attribute '" + name + "'");
}

void write_any_dataset(hid_t parent, const std::string& name, const void* data, std::size_t size,
                       std::span<const hsize_t> dims, hid_t file_type, hid_t memory_type) {
  hsize_t expected = 1;
  for (hsize_t d : dims) expected *= d;
  if (expected != size)
    throw RunError(fmt::format("HDF5: dataset '{}' has {} values for a shape of {}", name, size, expected));
  Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                     "create dataspace for '" + name + "'"));
  Handle dataset(check(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                       "create dataset '" + name + "'"));
  // HDF5 refuses a null buffer even for zero elements; nothing to write then.
  if (size > 0)
    check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write dataset '" + name + "'");
  dataset.close("close dataset '" + name + "'");
}

}  // namespace

void silence_automatic_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

std::string take_error_stack() {
  std::vector<StackEntry> entries;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_entry, &entries);
  H5Eclear2(H5E_DEFAULT);
  if (entries.empty()) return {};
  // The outermost entry names the API call; the innermost says why it failed.
  const StackEntry& outer = entries.front();
  const StackEntry& inner = entries.back();
  std::string text = fmt::format("{}: {}", outer.function, outer.description);
  if (entries.size() > 1) text += fmt::format(" <- {}: {}", inner.function, inner.description);
  if (!inner.minor.empty()) text += fmt::format(" ({})", inner.minor);
  return text;
}

hid_t check(hid_t id, std::string_view what) {
  if (id < 0) {
    const std::string stack = take_error_stack();
    throw RunError(fmt::format("HDF5: cannot {}{}{}", what, stack.empty() ? "" : ": ", stack));
  }
  return id;
}

void check(herr_t status, std::string_view what) { check(static_cast<hid_t>(status), what); }

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = other.id_;
    other.id_ = H5I_INVALID_HID;
  }
  return *this;
}

void Handle::close(std::string_view what) {
  if (id_ < 0) return;
  const hid_t id = id_;
  id_ = H5I_INVALID_HID;
  check(close_any(id), what);
}

void Handle::reset() noexcept {
  if (id_ < 0) return;
  close_any(id_);
  id_ = H5I_INVALID_HID;
  H5Eclear2(H5E_DEFAULT);
}

Handle create_file(const std::string& path) {
  return Handle(check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create file '" + path + "'"));
}

Handle open_file_for_writing(const std::string& path) {
  return Handle(check(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open file '" + path + "'"));
}

Handle open_group(hid_t parent, const std::string& name) {
  return Handle(check(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), "open group '" + name + "'"));
}

std::vector<std::string> link_names(hid_t group) {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names), "list group");
  return names;
}

void delete_link(hid_t parent, const std::string& name) {
  check(H5Ldelete(parent, name.c_str(), H5P_DEFAULT), "delete '" + name + "'");
}

bool link_exists(hid_t parent, const std::string& name) {
  return check(static_cast<hid_t>(H5Lexists(parent, name.c_str(), H5P_DEFAULT)), "look up '" + name + "'") > 0;
}

void flush(hid_t file) { check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush file"); }

Handle create_group(hid_t parent, const std::string& name) {
  return Handle(
      check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create group '" + name + "'"));
}

void write_dataset(hid_t parent, const std::string& name, std::span<const double> data, std::span<const hsize_t> dims) {
  write_any_dataset(parent, name, data.data(), data.size(), dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}

void write_dataset(hid_t parent, const std::string& name, std::span<const std::int32_t> data,
                   std::span<const hsize_t> dims) {
  write_any_dataset(parent, name, data.data(), data.size(), dims, H5T_STD_I32LE, H5T_NATIVE_INT32);
}

void write_attribute(hid_t object, const std::string& name, double value) {
  write_scalar_attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, value);
}

void write_attribute(hid_t object, const std::string& name, std::int64_t value) {
  write_scalar_attribute(object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, value);
}

void write_attribute(hid_t object, const std::string& name, int value) {
  write_scalar_attribute(object, name, H5T_STD_I32LE, H5T_NATIVE_INT, value);
}

}  // namespace pdmpm::io::h5
