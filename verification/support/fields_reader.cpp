#include "verification/support/fields_reader.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pdmpm::test {
namespace {

struct Closer {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Closer() {
    if (id >= 0) close(id);
  }
};

hid_t checked(hid_t id, const std::string& what) {
  if (id < 0) throw std::runtime_error("fields.h5: cannot " + what);
  return id;
}

template <class T>
T attribute(hid_t group, const char* name, hid_t type) {
  Closer a{checked(H5Aopen(group, name, H5P_DEFAULT), std::string("open attribute ") + name), H5Aclose};
  T v{};
  if (H5Aread(a.id, type, &v) < 0) throw std::runtime_error(std::string("fields.h5: cannot read attribute ") + name);
  return v;
}

}  // namespace

FieldsReader::FieldsReader(const std::string& path) : path_(path) {
  Closer f{checked(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + path), H5Fclose};
  Closer g{checked(H5Gopen2(f.id, "frames", H5P_DEFAULT), "open frames/"), H5Gclose};
  hsize_t n = 0;
  H5Gget_num_objs(g.id, &n);
  for (hsize_t k = 0; k < n; ++k) {
    char name[64];
    H5Gget_objname_by_idx(g.id, k, name, sizeof name);
    Closer fr{checked(H5Gopen2(g.id, name, H5P_DEFAULT), std::string("open frame ") + name), H5Gclose};
    frames_.push_back({name, attribute<std::int64_t>(fr.id, "step", H5T_NATIVE_INT64), attribute<double>(fr.id, "time", H5T_NATIVE_DOUBLE)});
  }
  std::sort(frames_.begin(), frames_.end(), [](const FrameInfo& a, const FrameInfo& b) { return a.step < b.step; });
  if (frames_.empty()) throw std::runtime_error("fields.h5: no frames in " + path);
}

const FrameInfo& FieldsReader::nearest(double t) const {
  return *std::min_element(frames_.begin(), frames_.end(),
                           [t](const FrameInfo& a, const FrameInfo& b) { return std::abs(a.time - t) < std::abs(b.time - t); });
}

std::vector<double> FieldsReader::read(const FrameInfo& frame, const std::string& field) const {
  Closer f{checked(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + path_), H5Fclose};
  const std::string where = "frames/" + frame.name + "/" + field;
  Closer d{checked(H5Dopen2(f.id, where.c_str(), H5P_DEFAULT), "open " + where), H5Dclose};
  Closer s{checked(H5Dget_space(d.id), "get the space of " + where), H5Sclose};
  const hssize_t n = H5Sget_simple_extent_npoints(s.id);
  std::vector<double> out(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
  if (H5Dread(d.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw std::runtime_error("fields.h5: cannot read " + where);
  return out;
}

}  // namespace pdmpm::test
