#include "solver/io/fields_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>
#include <system_error>
#include <utility>

#include "solver/core/error.hpp"
#include "solver/io/hdf5.hpp"

namespace pdmpm::io {
namespace {

constexpr int kFormatVersion = 1;

const char* xdmf_attribute_type(FieldKind kind) {
  switch (kind) {
    case FieldKind::scalar:
      return "Scalar";
    case FieldKind::vector:
      return "Vector";
    case FieldKind::tensor6:
      return "Tensor6";
  }
  return "Scalar";
}

std::string frame_name(std::int64_t step) { return fmt::format("{:08d}", step); }
std::string vertex_list_name(std::int64_t n) { return fmt::format("polyvertex_{}", n); }

// Field names become HDF5 link names and XDMF attribute names: keep them to
// characters that need no escaping in either.
bool is_valid_field_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

struct FieldRecord {
  std::string name;
  FieldKind kind;
};

struct FrameRecord {
  std::int64_t step;
  double time;
  std::int64_t particles;
  std::vector<FieldRecord> fields;
};

}  // namespace

int components(FieldKind kind) {
  switch (kind) {
    case FieldKind::scalar:
      return 1;
    case FieldKind::vector:
      return 3;
    case FieldKind::tensor6:
      return 6;
  }
  return 1;
}

std::vector<double> pad_to_3d(std::span<const double> values, int dimension) {
  if (dimension < 1 || dimension > 3)
    throw RunError(fmt::format("pad_to_3d: dimension {} is not 1, 2 or 3", dimension));
  const auto d = static_cast<std::size_t>(dimension);
  if (values.size() % d != 0)
    throw RunError(fmt::format("pad_to_3d: {} values are not a whole number of {}-vectors", values.size(), d));
  const std::size_t n = values.size() / d;
  std::vector<double> out(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < d; ++k) out[3 * i + k] = values[d * i + k];
  return out;
}

struct FieldsWriter::Impl {
  std::filesystem::path h5_path, xdmf_path;
  std::string h5_name;
  int dimension;
  h5::Handle file, frames_group, topology_group;
  std::vector<FrameRecord> records;
  std::set<std::int64_t> vertex_lists;  // particle counts whose 0..n-1 list is stored
  bool closed = false;

  void write_xdmf() const;
};

FieldsWriter::FieldsWriter(std::filesystem::path h5_path, std::filesystem::path xdmf_path, std::string h5_name_in_xdmf,
                           int dimension)
    : impl_(std::make_unique<Impl>()) {
  if (dimension < 1 || dimension > 3)
    throw RunError(fmt::format("fields writer: dimension {} is not 1, 2 or 3", dimension));
  if (h5_name_in_xdmf.empty()) throw RunError("fields writer: the HDF5 file name used in the XDMF file is empty");
  Impl& s = *impl_;
  s.h5_path = std::move(h5_path);
  s.xdmf_path = std::move(xdmf_path);
  s.h5_name = std::move(h5_name_in_xdmf);
  s.dimension = dimension;

  h5::silence_automatic_errors();
  s.file = h5::create_file(s.h5_path.string());
  h5::write_attribute(s.file.get(), "format_version", kFormatVersion);
  h5::write_attribute(s.file.get(), "dimension", dimension);
  h5::write_attribute(s.file.get(), "particles", std::int64_t{0});
  s.frames_group = h5::create_group(s.file.get(), "frames");
  s.topology_group = h5::create_group(s.file.get(), "topology");

  // The XDMF text is written at close(); open it now so an unwritable path
  // fails before the run, not after it.
  std::ofstream probe(s.xdmf_path, std::ios::binary | std::ios::trunc);
  if (!probe) throw RunError(fmt::format("fields writer: cannot create '{}'", s.xdmf_path.string()));
}

FieldsWriter::~FieldsWriter() {
  if (!impl_) return;
  try {
    close();
  } catch (...) {
    // A destructor cannot report; callers who care call close() themselves.
  }
}

FieldsWriter::FieldsWriter(FieldsWriter&&) noexcept = default;
FieldsWriter& FieldsWriter::operator=(FieldsWriter&& other) noexcept {
  if (this != &other) {
    if (impl_) {
      try {
        close();
      } catch (...) {}
    }
    impl_ = std::move(other.impl_);
  }
  return *this;
}

FieldsWriter FieldsWriter::resume(const std::filesystem::path& source, std::filesystem::path h5_path,
                                  std::filesystem::path xdmf_path, std::string h5_name_in_xdmf, int dimension,
                                  core::StateArchive& checkpoint) {
  std::error_code error;
  std::filesystem::copy_file(source, h5_path, std::filesystem::copy_options::overwrite_existing, error);
  if (error)
    throw RunError(
        fmt::format("fields: cannot copy '{}' to '{}': {}", source.string(), h5_path.string(), error.message()));
  FieldsWriter w;
  w.impl_ = std::make_unique<Impl>();
  Impl& s = *w.impl_;
  s.h5_path = std::move(h5_path);
  s.xdmf_path = std::move(xdmf_path);
  s.h5_name = std::move(h5_name_in_xdmf);
  s.dimension = dimension;
  w.sync_frames(checkpoint);
  h5::silence_automatic_errors();
  s.file = h5::open_file_for_writing(s.h5_path.string());
  s.frames_group = h5::open_group(s.file.get(), "frames");
  s.topology_group = h5::open_group(s.file.get(), "topology");
  // Frames and vertex lists written after the checkpoint go: the resumed run writes them again.
  std::set<std::string> kept_frames, kept_lists;
  for (const FrameRecord& r : s.records) kept_frames.insert(frame_name(r.step));
  for (std::int64_t n : s.vertex_lists) kept_lists.insert(vertex_list_name(n));
  for (const std::string& name : h5::link_names(s.frames_group.get()))
    if (!kept_frames.count(name)) h5::delete_link(s.frames_group.get(), name);
  for (const std::string& name : h5::link_names(s.topology_group.get()))
    if (!kept_lists.count(name)) h5::delete_link(s.topology_group.get(), name);
  for (const std::string& name : kept_frames)
    if (!h5::link_exists(s.frames_group.get(), name))
      throw RunError(fmt::format("fields '{}' lacks frame {} of the checkpoint", source.string(), name));
  return w;
}

void FieldsWriter::checkpoint(core::StateArchive& a) {
  h5::flush(impl_->file.get());
  sync_frames(a);
}

// The frame list as plain blocks: steps, times, particle counts, and one line of
// "name:kind" pairs per frame.
void FieldsWriter::sync_frames(core::StateArchive& a) {
  Impl& s = *impl_;
  std::vector<std::int64_t> steps, particles, lists(s.vertex_lists.begin(), s.vertex_lists.end());
  std::vector<double> times;
  std::string fields;
  for (const FrameRecord& r : s.records) {
    steps.push_back(r.step);
    times.push_back(r.time);
    particles.push_back(r.particles);
    for (const FieldRecord& f : r.fields) fields += fmt::format("{}:{} ", f.name, static_cast<int>(f.kind));
    fields += '\n';
  }
  a.sync("fields/steps", steps);
  a.sync("fields/times", times);
  a.sync("fields/particles", particles);
  a.sync("fields/names", fields);
  a.sync("fields/vertex_lists", lists);
  if (a.saving()) return;
  if (times.size() != steps.size() || particles.size() != steps.size())
    throw core::StateMismatch("the checkpoint's frame list is inconsistent");
  s.records.clear();
  std::istringstream lines(fields);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    FrameRecord r{steps[k], times[k], particles[k], {}};
    std::string line, item;
    std::getline(lines, line);
    std::istringstream items(line);
    while (items >> item) {
      const auto colon = item.rfind(':');
      if (colon == std::string::npos) throw core::StateMismatch("the checkpoint's frame list is damaged");
      r.fields.push_back({item.substr(0, colon), static_cast<FieldKind>(std::stoi(item.substr(colon + 1)))});
    }
    s.records.push_back(std::move(r));
  }
  s.vertex_lists = std::set<std::int64_t>(lists.begin(), lists.end());
}

std::size_t FieldsWriter::frames() const { return impl_ ? impl_->records.size() : 0; }

void FieldsWriter::write_frame(std::int64_t step, double time, const std::vector<double>& positions,
                               const std::vector<Field>& fields) {
  if (!impl_ || impl_->closed) throw RunError("fields writer: write_frame after close");
  Impl& s = *impl_;
  const std::string where = fmt::format("fields writer, step {}", step);

  // Validate everything before touching the file, so a bad frame leaves the
  // file as it was.
  if (step < 0) throw RunError(fmt::format("{}: step is negative", where));
  if (!s.records.empty() && step <= s.records.back().step)
    throw RunError(fmt::format("{}: steps must increase (previous frame was step {})", where, s.records.back().step));
  if (!std::isfinite(time)) throw RunError(fmt::format("{}: time is not finite", where));
  if (!s.records.empty() && time < s.records.back().time)
    throw RunError(fmt::format("{}: time {} is before the previous frame's {}", where, time, s.records.back().time));
  if (positions.size() % 3 != 0)
    throw RunError(fmt::format("{}: {} position values are not a whole number of 3-vectors", where, positions.size()));
  const std::size_t n = positions.size() / 3;
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw RunError(fmt::format("{}: {} particles exceed the int32 vertex index", where, n));
  std::set<std::string> seen;
  for (const Field& field : fields) {
    if (!is_valid_field_name(field.name))
      throw RunError(
          fmt::format("{}: field name '{}' must be non-empty letters, digits, '_' or '-'", where, field.name));
    if (field.name == "position") throw RunError(fmt::format("{}: field name 'position' is reserved", where));
    if (!seen.insert(field.name).second) throw RunError(fmt::format("{}: field '{}' given twice", where, field.name));
    const std::size_t expected = n * static_cast<std::size_t>(components(field.kind));
    if (field.values.size() != expected)
      throw RunError(fmt::format("{}: field '{}' has {} values, expected {} ({} particles x {} components)", where,
                                 field.name, field.values.size(), expected, n, components(field.kind)));
  }

  const auto count = static_cast<std::int64_t>(n);
  const hsize_t rows = n;
  if (s.vertex_lists.insert(count).second) {
    std::vector<std::int32_t> ids(n);
    std::iota(ids.begin(), ids.end(), 0);
    const hsize_t dims[2] = {rows, 1};
    h5::write_dataset(s.topology_group.get(), vertex_list_name(count), std::span<const std::int32_t>(ids), dims);
  }

  h5::Handle group = h5::create_group(s.frames_group.get(), frame_name(step));
  h5::write_attribute(group.get(), "time", time);
  h5::write_attribute(group.get(), "step", step);
  h5::write_attribute(group.get(), "particles", count);
  const hsize_t position_dims[2] = {rows, 3};
  h5::write_dataset(group.get(), "position", std::span<const double>(positions), position_dims);
  FrameRecord record{step, time, count, {}};
  for (const Field& field : fields) {
    const hsize_t vector_dims[2] = {rows, static_cast<hsize_t>(components(field.kind))};
    const std::span<const hsize_t> dims(vector_dims, field.kind == FieldKind::scalar ? 1 : 2);
    h5::write_dataset(group.get(), field.name, std::span<const double>(field.values), dims);
    record.fields.push_back({field.name, field.kind});
  }
  group.close("close frame group " + frame_name(step));
  if (s.records.empty()) h5::write_attribute(s.file.get(), "particles", count);
  s.records.push_back(std::move(record));
}

void FieldsWriter::close() {
  if (!impl_ || impl_->closed) return;
  Impl& s = *impl_;
  s.closed = true;
  s.frames_group.close("close group /frames");
  s.topology_group.close("close group /topology");
  s.file.close("close '" + s.h5_path.string() + "'");
  s.write_xdmf();
}

void FieldsWriter::Impl::write_xdmf() const {
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  const std::string h5 = xml_escape(h5_name);
  fmt::format_to(it, "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n");
  fmt::format_to(it, "<Xdmf Version=\"3.0\">\n  <Domain>\n");
  fmt::format_to(it, "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (const FrameRecord& frame : records) {
    const std::string group = "/frames/" + frame_name(frame.step);
    const std::int64_t n = frame.particles;
    fmt::format_to(it, "      <Grid Name=\"step_{}\" GridType=\"Uniform\">\n", frame_name(frame.step));
    // 17 significant digits: the time read back is the double that was written.
    fmt::format_to(it, "        <Time Value=\"{:.17g}\"/>\n", frame.time);
    fmt::format_to(it, "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" NodesPerElement=\"1\">\n",
                   n);
    fmt::format_to(it,
                   "          <DataItem Dimensions=\"{} 1\" NumberType=\"Int\" Precision=\"4\" "
                   "Format=\"HDF\">{}:/topology/{}</DataItem>\n",
                   n, h5, vertex_list_name(n));
    fmt::format_to(it, "        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n");
    fmt::format_to(it,
                   "          <DataItem Dimensions=\"{} 3\" NumberType=\"Float\" Precision=\"8\" "
                   "Format=\"HDF\">{}:{}/position</DataItem>\n",
                   n, h5, group);
    fmt::format_to(it, "        </Geometry>\n");
    for (const FieldRecord& field : frame.fields) {
      const int c = components(field.kind);
      const std::string dims = c == 1 ? fmt::format("{}", n) : fmt::format("{} {}", n, c);
      fmt::format_to(it, "        <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n", field.name,
                     xdmf_attribute_type(field.kind));
      fmt::format_to(it,
                     "          <DataItem Dimensions=\"{}\" NumberType=\"Float\" Precision=\"8\" "
                     "Format=\"HDF\">{}:{}/{}</DataItem>\n",
                     dims, h5, group, field.name);
      fmt::format_to(it, "        </Attribute>\n");
    }
    fmt::format_to(it, "      </Grid>\n");
  }
  fmt::format_to(it, "    </Grid>\n  </Domain>\n</Xdmf>\n");

  std::ofstream stream(xdmf_path, std::ios::binary | std::ios::trunc);
  stream.write(out.data(), static_cast<std::streamsize>(out.size()));
  stream.close();
  if (!stream) throw RunError(fmt::format("fields writer: cannot write '{}'", xdmf_path.string()));
}

}  // namespace pdmpm::io
