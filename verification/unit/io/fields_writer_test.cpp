// FieldsWriter: frames read back through the plain HDF5 C API must be the
// same bits that were written, and the XDMF file must be well-formed XML whose
// every DataItem points at a dataset of the declared shape and type.
#include "solver/io/fields_writer.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "solver/core/error.hpp"
#include "verification/support/scratch_dir.hpp"
#include "verification/support/output_files.hpp"
#include "verification/support/same_bits.hpp"

namespace pdmpm::io {
namespace {

using test::same_bits;

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------
// Reading back with the HDF5 C API (deliberately not through solver/io/hdf5).
struct H5File {
  hid_t id;
  explicit H5File(const fs::path& p) : id(H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~H5File() {
    if (id >= 0) H5Fclose(id);
  }
};

bool has_link(hid_t file, const std::string& path) {
  // Check each level: H5Lexists fails (rather than returning false) when a parent is missing.
  std::string prefix;
  std::stringstream parts(path);
  std::string part;
  while (std::getline(parts, part, '/')) {
    if (part.empty()) continue;
    prefix += "/" + part;
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

std::vector<hsize_t> dataset_dims(hid_t file, const std::string& path) {
  hid_t dset = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(dset, 0) << path;
  hid_t space = H5Dget_space(dset);
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(dset);
  return dims;
}

// Class (float/integer) and size in bytes of a dataset's stored type.
std::pair<H5T_class_t, std::size_t> dataset_type(hid_t file, const std::string& path) {
  hid_t dset = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  hid_t type = H5Dget_type(dset);
  auto result = std::make_pair(H5Tget_class(type), H5Tget_size(type));
  H5Tclose(type);
  H5Dclose(dset);
  return result;
}

template <class T>
std::vector<T> read_dataset(hid_t file, const std::string& path, hid_t memory_type) {
  std::size_t count = 1;
  for (hsize_t d : dataset_dims(file, path)) count *= static_cast<std::size_t>(d);
  std::vector<T> values(count);
  hid_t dset = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (count > 0) {
    EXPECT_GE(H5Dread(dset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0) << path;
  }
  H5Dclose(dset);
  return values;
}

template <class T>
T read_attribute(hid_t file, const std::string& object, const std::string& name, hid_t memory_type) {
  T value{};
  hid_t attr = H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(attr, 0) << object << "@" << name;
  EXPECT_GE(H5Aread(attr, memory_type, &value), 0);
  H5Aclose(attr);
  return value;
}

// ---------------------------------------------------------------------------
// Minimal XML reader: elements, attributes, text, the <?xml?> prolog and
// comments; throws on anything malformed (unclosed or mismatched tags, junk
// after the root). Enough to check structure without an XML library.
struct XmlNode {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::vector<XmlNode> children;
  std::string text;

  std::vector<const XmlNode*> all(const std::string& child) const {
    std::vector<const XmlNode*> out;
    for (const XmlNode& c : children)
      if (c.name == child) out.push_back(&c);
    return out;
  }
  const XmlNode& one(const std::string& child) const {
    auto found = all(child);
    if (found.size() != 1) throw std::runtime_error(name + " has " + std::to_string(found.size()) + " <" + child + ">");
    return *found.front();
  }
  std::string attr(const std::string& key) const {
    auto it = attributes.find(key);
    if (it == attributes.end()) throw std::runtime_error(name + " lacks attribute " + key);
    return it->second;
  }
};

class XmlParser {
 public:
  explicit XmlParser(std::string text) : s_(std::move(text)) {}

  XmlNode document() {
    skip_misc();
    XmlNode root = element();
    skip_misc();
    if (i_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML: " + what + " at offset " + std::to_string(i_));
  }
  bool starts(const char* token) const { return s_.compare(i_, std::strlen(token), token) == 0; }
  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  void skip_until(const char* token) {
    const std::size_t end = s_.find(token, i_);
    if (end == std::string::npos) fail(std::string("missing ") + token);
    i_ = end + std::strlen(token);
  }
  void skip_misc() {
    for (;;) {
      skip_space();
      if (starts("<?"))
        skip_until("?>");
      else if (starts("<!--"))
        skip_until("-->");
      else
        return;
    }
  }
  std::string name() {
    const std::size_t begin = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || std::strchr("_:-.", s_[i_]))) ++i_;
    if (i_ == begin) fail("expected a name");
    return s_.substr(begin, i_ - begin);
  }
  std::string decode(const std::string& raw) const {
    static const std::pair<const char*, char> entities[] = {
        {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
    std::string out;
    for (std::size_t k = 0; k < raw.size();) {
      if (raw[k] == '<') fail("'<' in text");
      if (raw[k] != '&') {
        out += raw[k++];
        continue;
      }
      bool known = false;
      for (auto [entity, c] : entities)
        if (raw.compare(k, std::strlen(entity), entity) == 0) {
          out += c;
          k += std::strlen(entity);
          known = true;
          break;
        }
      if (!known) fail("unknown entity");
    }
    return out;
  }
  XmlNode element() {
    if (!starts("<")) fail("expected '<'");
    ++i_;
    XmlNode node;
    node.name = name();
    for (;;) {
      skip_space();
      if (starts("/>")) {
        i_ += 2;
        return node;
      }
      if (starts(">")) {
        ++i_;
        break;
      }
      const std::string key = name();
      skip_space();
      if (!starts("=")) fail("expected '='");
      ++i_;
      skip_space();
      const char quote = i_ < s_.size() ? s_[i_] : '\0';
      if (quote != '"' && quote != '\'') fail("expected a quoted value");
      const std::size_t end = s_.find(quote, i_ + 1);
      if (end == std::string::npos) fail("unterminated attribute");
      if (!node.attributes.emplace(key, decode(s_.substr(i_ + 1, end - i_ - 1))).second)
        fail("repeated attribute " + key);
      i_ = end + 1;
    }
    for (;;) {
      const std::size_t lt = s_.find('<', i_);
      if (lt == std::string::npos) fail("unclosed <" + node.name + ">");
      node.text += decode(s_.substr(i_, lt - i_));
      i_ = lt;
      if (starts("<!--")) {
        skip_until("-->");
      } else if (starts("</")) {
        i_ += 2;
        if (name() != node.name) fail("mismatched </...> for <" + node.name + ">");
        skip_space();
        if (!starts(">")) fail("expected '>'");
        ++i_;
        return node;
      } else {
        node.children.push_back(element());
      }
    }
  }

  std::string s_;
  std::size_t i_ = 0;
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// Resolves an XDMF HDF DataItem against the file: reference "<h5>:<path>",
// dataset present, same shape, stored type matching NumberType/Precision.
void expect_data_item_resolves(const XmlNode& item, hid_t file, const std::string& h5_name,
                               const std::string& expected_path, const std::string& expected_dims) {
  EXPECT_EQ(item.attr("Format"), "HDF");
  EXPECT_EQ(item.attr("Dimensions"), expected_dims);
  const std::string ref = trim(item.text);
  const auto colon = ref.find(':');
  ASSERT_NE(colon, std::string::npos) << ref;
  EXPECT_EQ(ref.substr(0, colon), h5_name);
  const std::string path = ref.substr(colon + 1);
  EXPECT_EQ(path, expected_path);
  ASSERT_TRUE(has_link(file, path)) << path;
  std::string dims;
  for (hsize_t d : dataset_dims(file, path)) dims += (dims.empty() ? "" : " ") + std::to_string(d);
  EXPECT_EQ(dims, expected_dims) << path;
  const auto [cls, size] = dataset_type(file, path);
  EXPECT_EQ(cls, item.attr("NumberType") == "Float" ? H5T_FLOAT : H5T_INTEGER) << path;
  EXPECT_EQ(std::to_string(size), item.attr("Precision")) << path;
}

// ---------------------------------------------------------------------------
// Test data: distinct values per frame, field and component, plus values whose
// bits are easy to lose in a text or conversion step.
std::vector<double> pattern(std::size_t count, double seed) {
  std::vector<double> v(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double x = static_cast<double>(k);
    v[k] = seed + 1.0 / (3.0 + x) - 1e-7 * x * x;
  }
  const double special[] = {-0.0,
                            std::numeric_limits<double>::denorm_min(),
                            std::numeric_limits<double>::max(),
                            -std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::quiet_NaN(),
                            0.1};
  for (std::size_t k = 0; k < std::size(special) && k < count; ++k) v[(7 * k + 1) % count] = special[k];
  return v;
}

struct FrameSpec {
  std::int64_t step;
  double time;
  std::vector<double> positions;
  std::vector<Field> fields;
};

FrameSpec make_frame(int dimension, std::int64_t step, double time, std::size_t n, bool with_tensor) {
  FrameSpec f{step, time, {}, {}};
  const double seed = static_cast<double>(step);
  f.positions = pad_to_3d(pattern(n * static_cast<std::size_t>(dimension), seed), dimension);
  f.fields.push_back({"damage", FieldKind::scalar, pattern(n, seed + 0.5)});
  f.fields.push_back({"displacement", FieldKind::vector,
                      pad_to_3d(pattern(n * static_cast<std::size_t>(dimension), seed + 0.25), dimension)});
  if (with_tensor) f.fields.push_back({"stress", FieldKind::tensor6, pattern(6 * n, seed + 0.75)});
  return f;
}

// Writes the frames, then checks the HDF5 contents bit for bit and the XDMF
// structure against them.
void write_and_check(int dimension, const std::vector<FrameSpec>& frames, const std::string& tag) {
  test::ScratchDir dir("fields_" + tag);
  const fs::path h5 = dir.path() / "fields.h5", xdmf = dir.path() / "fields.xdmf";
  {
    FieldsWriter writer(h5, xdmf, "fields.h5", dimension);
    for (const FrameSpec& f : frames) writer.write_frame(f.step, f.time, f.positions, f.fields);
    EXPECT_EQ(writer.frames(), frames.size());
    writer.close();
    writer.close();  // idempotent
  }

  H5File file(h5);
  ASSERT_GE(file.id, 0);
  EXPECT_EQ(read_attribute<int>(file.id, "/", "dimension", H5T_NATIVE_INT), dimension);
  EXPECT_EQ(read_attribute<int>(file.id, "/", "format_version", H5T_NATIVE_INT), 1);
  EXPECT_EQ(read_attribute<std::int64_t>(file.id, "/", "particles", H5T_NATIVE_INT64),
            static_cast<std::int64_t>(frames.front().positions.size() / 3));
  for (const FrameSpec& f : frames) {
    char group[32];
    std::snprintf(group, sizeof group, "/frames/%08lld", static_cast<long long>(f.step));
    const auto n = static_cast<std::int64_t>(f.positions.size() / 3);
    SCOPED_TRACE(group);
    const double time = read_attribute<double>(file.id, group, "time", H5T_NATIVE_DOUBLE);
    EXPECT_EQ(std::memcmp(&time, &f.time, sizeof time), 0);
    EXPECT_EQ(read_attribute<std::int64_t>(file.id, group, "step", H5T_NATIVE_INT64), f.step);
    EXPECT_EQ(read_attribute<std::int64_t>(file.id, group, "particles", H5T_NATIVE_INT64), n);
    EXPECT_TRUE(
        same_bits(read_dataset<double>(file.id, std::string(group) + "/position", H5T_NATIVE_DOUBLE), f.positions));
    EXPECT_EQ(dataset_dims(file.id, std::string(group) + "/position"), (std::vector<hsize_t>{hsize_t(n), 3}));
    for (const Field& field : f.fields) {
      const std::string path = std::string(group) + "/" + field.name;
      EXPECT_TRUE(same_bits(read_dataset<double>(file.id, path, H5T_NATIVE_DOUBLE), field.values)) << path;
      const std::vector<hsize_t> dims = field.kind == FieldKind::scalar
          ? std::vector<hsize_t>{hsize_t(n)}
          : std::vector<hsize_t>{hsize_t(n), hsize_t(components(field.kind))};
      EXPECT_EQ(dataset_dims(file.id, path), dims) << path;
    }
    const auto ids = read_dataset<std::int32_t>(file.id, "/topology/polyvertex_" + std::to_string(n), H5T_NATIVE_INT32);
    ASSERT_EQ(ids.size(), static_cast<std::size_t>(n));
    for (std::size_t k = 0; k < ids.size(); ++k) EXPECT_EQ(ids[k], static_cast<std::int32_t>(k));
  }

  // XDMF: well-formed, one temporal collection, one uniform grid per frame.
  XmlNode root;
  ASSERT_NO_THROW(root = XmlParser(test::read_text(xdmf)).document());
  EXPECT_EQ(root.name, "Xdmf");
  EXPECT_EQ(root.attr("Version"), "3.0");
  const XmlNode& collection = root.one("Domain").one("Grid");
  EXPECT_EQ(collection.attr("GridType"), "Collection");
  EXPECT_EQ(collection.attr("CollectionType"), "Temporal");
  const auto grids = collection.all("Grid");
  ASSERT_EQ(grids.size(), frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const FrameSpec& f = frames[k];
    const XmlNode& grid = *grids[k];
    char group[32];
    std::snprintf(group, sizeof group, "/frames/%08lld", static_cast<long long>(f.step));
    SCOPED_TRACE(group);
    const std::string n = std::to_string(f.positions.size() / 3);
    EXPECT_EQ(grid.attr("GridType"), "Uniform");
    const double time = std::strtod(grid.one("Time").attr("Value").c_str(), nullptr);
    EXPECT_EQ(std::memcmp(&time, &f.time, sizeof time), 0) << grid.one("Time").attr("Value");

    const XmlNode& topology = grid.one("Topology");
    EXPECT_EQ(topology.attr("TopologyType"), "Polyvertex");
    EXPECT_EQ(topology.attr("NumberOfElements"), n);
    EXPECT_EQ(topology.attr("NodesPerElement"), "1");
    expect_data_item_resolves(topology.one("DataItem"), file.id, "fields.h5", "/topology/polyvertex_" + n, n + " 1");

    const XmlNode& geometry = grid.one("Geometry");
    EXPECT_EQ(geometry.attr("GeometryType"), "XYZ");
    expect_data_item_resolves(geometry.one("DataItem"), file.id, "fields.h5", std::string(group) + "/position",
                              n + " 3");

    const auto attributes = grid.all("Attribute");
    ASSERT_EQ(attributes.size(), f.fields.size());
    for (std::size_t a = 0; a < attributes.size(); ++a) {
      const Field& field = f.fields[a];
      const XmlNode& attribute = *attributes[a];
      EXPECT_EQ(attribute.attr("Name"), field.name);
      EXPECT_EQ(attribute.attr("Center"), "Node");
      const char* type = field.kind == FieldKind::scalar ? "Scalar"
          : field.kind == FieldKind::vector              ? "Vector"
                                                         : "Tensor6";
      EXPECT_EQ(attribute.attr("AttributeType"), type);
      const std::string dims = field.kind == FieldKind::scalar ? n : n + " " + std::to_string(components(field.kind));
      expect_data_item_resolves(attribute.one("DataItem"), file.id, "fields.h5", std::string(group) + "/" + field.name,
                                dims);
    }
  }
}

// ---------------------------------------------------------------------------

TEST(FieldsWriter, ThreeDimensionalFramesWithChangingParticleCountRoundTripBitwise) {
  write_and_check(3,
                  {make_frame(3, 0, 0.0, 9, true), make_frame(3, 10, 1.0 / 3.0 * 1e-6, 12, true),
                   make_frame(3, 25, 7.123456789012345e-6, 5, true), make_frame(3, 40, 1e-5, 12, true)},
                  "3d");
}

TEST(FieldsWriter, TwoDimensionalFramesPadZAndMayChangeFieldSets) {
  std::vector<FrameSpec> frames = {make_frame(2, 0, 0.0, 7, false), make_frame(2, 1, 2.5e-7, 11, true),
                                   make_frame(2, 99999999, 3e-7, 4, false)};
  write_and_check(2, frames, "2d");
  for (const FrameSpec& f : frames)
    for (std::size_t i = 0; i < f.positions.size() / 3; ++i) EXPECT_EQ(f.positions[3 * i + 2], 0.0);
}

TEST(FieldsWriter, OneDimensionalAndEmptyFrames) {
  write_and_check(1, {make_frame(1, 3, 0.0, 6, false), make_frame(1, 4, 1.0, 0, true), make_frame(1, 5, 2.0, 6, true)},
                  "1d");
}

TEST(FieldsWriter, PadTo3dFillsUnusedAxesWithZero) {
  const std::vector<double> xy = {1, 2, 3, 4};
  EXPECT_EQ(pad_to_3d(xy, 2), (std::vector<double>{1, 2, 0, 3, 4, 0}));
  EXPECT_EQ(pad_to_3d(xy, 1), (std::vector<double>{1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0}));
  EXPECT_THROW(pad_to_3d(std::vector<double>{1, 2, 3}, 2), RunError);
}

TEST(FieldsWriter, DestructorClosesAndWritesXdmf) {
  test::ScratchDir dir("fields_dtor");
  {
    FieldsWriter writer(dir.path() / "f.h5", dir.path() / "f.xdmf", "f.h5", 3);
    const FrameSpec f = make_frame(3, 0, 0.0, 4, true);
    writer.write_frame(f.step, f.time, f.positions, f.fields);
  }
  H5File file(dir.path() / "f.h5");
  EXPECT_GE(file.id, 0);
  const XmlNode root = XmlParser(test::read_text(dir.path() / "f.xdmf")).document();
  EXPECT_EQ(root.one("Domain").one("Grid").all("Grid").size(), 1u);
}

// A bad frame is rejected with a message that names the problem, before the
// file is touched (so the writer stays usable).
TEST(FieldsWriter, RejectsInconsistentInput) {
  test::ScratchDir dir("fields_invalid");
  FieldsWriter writer(dir.path() / "f.h5", dir.path() / "f.xdmf", "f.h5", 2);
  const FrameSpec good = make_frame(2, 5, 1.0, 4, true);
  auto expect_error = [&](std::int64_t step, double time, const std::vector<double>& positions,
                          const std::vector<Field>& fields, const std::string& fragment) {
    try {
      writer.write_frame(step, time, positions, fields);
      ADD_FAILURE() << "no error for: " << fragment;
    } catch (const RunError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error(5, 1.0, std::vector<double>(10), good.fields, "not a whole number of 3-vectors");
  std::vector<Field> short_field = good.fields;
  short_field[1].values.pop_back();
  expect_error(5, 1.0, good.positions, short_field, "field 'displacement' has 11 values, expected 12");
  std::vector<Field> twice = good.fields;
  twice.push_back(twice.front());
  expect_error(5, 1.0, good.positions, twice, "given twice");
  expect_error(5, 1.0, good.positions, {{"bad name", FieldKind::scalar, std::vector<double>(4)}},
               "field name 'bad name'");
  expect_error(5, 1.0, good.positions, {{"position", FieldKind::vector, std::vector<double>(12)}}, "reserved");
  expect_error(5, std::nan(""), good.positions, good.fields, "not finite");
  expect_error(-1, 1.0, good.positions, good.fields, "negative");
  writer.write_frame(good.step, good.time, good.positions, good.fields);
  expect_error(5, 2.0, good.positions, good.fields, "steps must increase");
  expect_error(6, 0.5, good.positions, good.fields, "before the previous frame");
  EXPECT_EQ(writer.frames(), 1u);
  writer.close();
  expect_error(7, 3.0, good.positions, good.fields, "after close");
  EXPECT_THROW(FieldsWriter(dir.path() / "g.h5", dir.path() / "g.xdmf", "g.h5", 4), RunError);
}

// HDF5 failures surface as RunError with HDF5's reason, and nothing is printed
// by HDF5's own error handler.
TEST(FieldsWriter, HdfErrorsBecomeExceptionsWithoutPrinting) {
  test::ScratchDir dir("fields_h5error");
  const fs::path missing = dir.path() / "no_such_dir" / "f.h5";
  testing::internal::CaptureStderr();
  std::string message;
  try {
    FieldsWriter writer(missing, dir.path() / "f.xdmf", "f.h5", 3);
  } catch (const RunError& e) {
    message = e.what();
  }
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_NE(message.find("HDF5: cannot create file"), std::string::npos) << message;
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
  EXPECT_EQ(printed, "");

  // An unwritable XDMF path is found at construction, not after the run.
  EXPECT_THROW(FieldsWriter(dir.path() / "ok.h5", dir.path() / "no_such_dir" / "f.xdmf", "ok.h5", 3), RunError);
}

}  // namespace
}  // namespace pdmpm::io
