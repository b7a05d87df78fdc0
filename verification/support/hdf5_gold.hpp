#pragma once
// Small HDF5 "gold" files for reference data and regression (reference_data/):
// datasets of doubles under slash paths ("/seed001_table42/constant"), each
// with string/number attributes (source, unit, note), and provenance attributes
// on the root (git sha, tree, date, command, compiler, flags). Written via a
// temporary name and a rename, so a reader never sees half a file; read only by
// the gates (CI never writes them — see reference_data/README.md).
#include <map>
#include <string>
#include <vector>

#include <hdf5.h>

#include "solver/io/hdf5.hpp"

namespace pdmpm::test::gold {

class Writer {
 public:
  // Creates `path`.tmp; commit() renames it to `path`.
  explicit Writer(std::string path);
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // A dataset of shape dims (row-major); intermediate groups are created.
  void dataset(const std::string& path, const std::vector<double>& values, const std::vector<hsize_t>& dims);
  void scalar(const std::string& path, double value) { dataset(path, {value}, {}); }
  // Attributes on an existing object ("/" for the root, a group or a dataset).
  void attribute(const std::string& object, const std::string& name, const std::string& value);
  void attribute(const std::string& object, const std::string& name, double value);
  void group(const std::string& path);
  void commit();

 private:
  std::string path_, tmp_;
  io::h5::Handle file_;
  bool committed_ = false;
};

struct Array {
  std::vector<double> values;
  std::vector<hsize_t> dims;  // empty for a scalar
};

class Reader {
 public:
  explicit Reader(const std::string& path);  // throws RunError if the file cannot be opened
  bool exists(const std::string& path) const;
  Array dataset(const std::string& path) const;
  double scalar(const std::string& path) const;
  bool has_attribute(const std::string& object, const std::string& name) const;
  std::string string_attribute(const std::string& object, const std::string& name) const;
  double number_attribute(const std::string& object, const std::string& name) const;
  // Names of the members of a group, in HDF5's (alphabetical) order.
  std::vector<std::string> members(const std::string& group) const;

 private:
  io::h5::Handle file_;
};

// Root provenance attributes every gold file carries.
void write_provenance(Writer& w, const std::string& command);

// Directory of the committed reference data (<source>/reference_data).
std::string reference_data_dir();

}  // namespace pdmpm::test::gold
