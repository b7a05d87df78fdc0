#include "verification/support/hdf5_gold.hpp"

#include <array>
#include <cstdio>
#include <filesystem>

#include "solver/core/error.hpp"
#include "verification/support/command_line.hpp"
#include "verification/support/provenance.hpp"

namespace pdmpm::test::gold {

using io::h5::check;
using io::h5::Handle;

namespace {

// Variable-length UTF-8 strings: h5py reads them as str, HDF5 tools print them as text.
Handle string_type() {
  Handle t(check(H5Tcopy(H5T_C_S1), "copy string type"));
  check(H5Tset_size(t.get(), H5T_VARIABLE), "set string size");
  check(H5Tset_cset(t.get(), H5T_CSET_UTF8), "set string charset");
  return t;
}

// First line of a shell command's output ("" on failure).
std::string first_line(const std::string& cmd) {
  const CommandResult r = run_command(cmd);
  return r.status == 0 ? r.output.substr(0, r.output.find_first_of("\r\n")) : "";
}

Handle open_object(hid_t file, const std::string& path) {
  return Handle(check(H5Oopen(file, path.c_str(), H5P_DEFAULT), "open '" + path + "'"));
}

}  // namespace

Writer::Writer(std::string path) : path_(std::move(path)), tmp_(path_ + ".tmp") {
  io::h5::silence_automatic_errors();
  std::filesystem::create_directories(std::filesystem::path(path_).parent_path());
  file_ = Handle(check(H5Fcreate(tmp_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create '" + tmp_ + "'"));
}

Writer::~Writer() {
  if (!committed_) {
    file_.reset();
    std::error_code ec;
    std::filesystem::remove(tmp_, ec);
  }
}

void Writer::group(const std::string& path) {
  if (H5Lexists(file_.get(), path.c_str(), H5P_DEFAULT) > 0) return;
  Handle lcpl(check(H5Pcreate(H5P_LINK_CREATE), "link property list"));
  check(H5Pset_create_intermediate_group(lcpl.get(), 1), "intermediate groups");
  Handle g(check(H5Gcreate2(file_.get(), path.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), "create group '" + path + "'"));
}

void Writer::dataset(const std::string& path, const std::vector<double>& values, const std::vector<hsize_t>& dims) {
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  if (n != values.size()) throw RunError("gold: dataset '" + path + "' has a shape that does not match its values");
  Handle lcpl(check(H5Pcreate(H5P_LINK_CREATE), "link property list"));
  check(H5Pset_create_intermediate_group(lcpl.get(), 1), "intermediate groups");
  Handle space(dims.empty() ? check(H5Screate(H5S_SCALAR), "scalar space")
                            : check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "space"));
  Handle d(check(H5Dcreate2(file_.get(), path.c_str(), H5T_IEEE_F64LE, space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
                 "create dataset '" + path + "'"));
  if (!values.empty())
    check(H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "write '" + path + "'");
}

void Writer::attribute(const std::string& object, const std::string& name, const std::string& value) {
  Handle obj = open_object(file_.get(), object);
  Handle type = string_type();
  Handle space(check(H5Screate(H5S_SCALAR), "scalar space"));
  Handle a(check(H5Acreate2(obj.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 "create attribute '" + name + "' on '" + object + "'"));
  const char* text = value.c_str();
  check(H5Awrite(a.get(), type.get(), &text), "write attribute '" + name + "'");
}

void Writer::attribute(const std::string& object, const std::string& name, double value) {
  Handle obj = open_object(file_.get(), object);
  Handle space(check(H5Screate(H5S_SCALAR), "scalar space"));
  Handle a(check(H5Acreate2(obj.get(), name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 "create attribute '" + name + "' on '" + object + "'"));
  check(H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &value), "write attribute '" + name + "'");
}

void Writer::commit() {
  file_.close("close '" + tmp_ + "'");
  std::filesystem::rename(tmp_, path_);
  committed_ = true;
}

Reader::Reader(const std::string& path) {
  io::h5::silence_automatic_errors();
  file_ = Handle(check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open '" + path + "'"));
}

bool Reader::exists(const std::string& path) const {
  // Check each prefix: H5Lexists fails (rather than answering no) on a missing intermediate group.
  std::size_t pos = 0;
  while ((pos = path.find('/', pos + 1)) != std::string::npos)
    if (H5Lexists(file_.get(), path.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
  return H5Lexists(file_.get(), path.c_str(), H5P_DEFAULT) > 0;
}

Array Reader::dataset(const std::string& path) const {
  Handle d(check(H5Dopen2(file_.get(), path.c_str(), H5P_DEFAULT), "open dataset '" + path + "'"));
  Handle space(check(H5Dget_space(d.get()), "dataspace of '" + path + "'"));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  check(static_cast<herr_t>(rank), "rank of '" + path + "'");
  Array a;
  a.dims.resize(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), a.dims.data(), nullptr);
  hsize_t n = 1;
  for (hsize_t x : a.dims) n *= x;
  a.values.resize(n);
  if (n > 0) check(H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.values.data()), "read '" + path + "'");
  return a;
}

double Reader::scalar(const std::string& path) const {
  const auto a = dataset(path);
  if (a.values.size() != 1) throw RunError("gold: '" + path + "' is not a scalar");
  return a.values[0];
}

bool Reader::has_attribute(const std::string& object, const std::string& name) const {
  if (object != "/" && !exists(object)) return false;
  return H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

std::string Reader::string_attribute(const std::string& object, const std::string& name) const {
  Handle a(check(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                 "open attribute '" + name + "' of '" + object + "'"));
  Handle type(check(H5Aget_type(a.get()), "type of attribute '" + name + "'"));
  if (H5Tget_class(type.get()) != H5T_STRING) throw RunError("gold: attribute '" + name + "' is not a string");
  if (H5Tis_variable_str(type.get()) > 0) {
    char* s = nullptr;
    Handle mem = Handle(check(H5Tcopy(H5T_C_S1), "copy string type"));
    H5Tset_size(mem.get(), H5T_VARIABLE);
    H5Tset_cset(mem.get(), H5Tget_cset(type.get()));  // HDF5 does not convert between ASCII and UTF-8
    check(H5Aread(a.get(), mem.get(), &s), "read attribute '" + name + "'");
    std::string out = s ? s : "";
    H5free_memory(s);
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  std::string out(size, '\0');
  check(H5Aread(a.get(), type.get(), out.data()), "read attribute '" + name + "'");
  out.resize(out.find('\0') == std::string::npos ? out.size() : out.find('\0'));
  return out;
}

double Reader::number_attribute(const std::string& object, const std::string& name) const {
  Handle a(check(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                 "open attribute '" + name + "' of '" + object + "'"));
  double v = 0.0;
  check(H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v), "read attribute '" + name + "'");
  return v;
}

std::vector<std::string> Reader::members(const std::string& group) const {
  std::vector<std::string> names;
  Handle g(check(H5Gopen2(file_.get(), group.c_str(), H5P_DEFAULT), "open group '" + group + "'"));
  H5G_info_t info;
  check(H5Gget_info(g.get(), &info), "info of '" + group + "'");
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t len = H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    check(static_cast<herr_t>(len < 0 ? -1 : 0), "member name");
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    names.push_back(name);
  }
  return names;
}

void write_provenance(Writer& w, const std::string& command) {
  const auto p = provenance();
  // The commit checked out when the gold was written (the sha baked in at configure
  // time may be older), and whether the code differed from it; the gold files
  // themselves do not count.
  const std::string git = "git -C '" + std::string(PDMPM_SOURCE_DIR) + "' ";
  std::string sha = first_line(git + "rev-parse --short=12 HEAD 2>/dev/null");
  const bool have_git = !sha.empty();
  if (!have_git) sha = p["git_sha"].get<std::string>();
  const std::string changed = first_line(git + "status --porcelain -- . ':!reference_data' 2>/dev/null");
  w.attribute("/", "git_sha", sha);
  w.attribute("/", "tree", !have_git ? "unknown" : changed.empty() ? "clean (outside reference_data/)" : "dirty");
  w.attribute("/", "date", p["date"].get<std::string>());
  w.attribute("/", "command", command);
  w.attribute("/", "compiler", p["compiler"].get<std::string>());
  w.attribute("/", "flags", p["flags"].get<std::string>());
}

std::string reference_data_dir() { return std::string(PDMPM_SOURCE_DIR) + "/reference_data"; }

}  // namespace pdmpm::test::gold
