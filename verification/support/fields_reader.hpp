#pragma once
// Reads the frames a run wrote to fields.h5 (solver/io/fields_writer.hpp):
// frames/<step, 8 digits>/{position, displacement, damage, ...} with the
// attributes step and time. For gates that inspect fields at chosen moments.
#include <cstdint>
#include <string>
#include <vector>

namespace pdmpm::test {

struct FrameInfo {
  std::string name;  // group name under frames/
  std::int64_t step = 0;
  double time = 0.0;
};

class FieldsReader {
 public:
  explicit FieldsReader(const std::string& path);
  const std::vector<FrameInfo>& frames() const { return frames_; }
  // The frame whose time is nearest t.
  const FrameInfo& nearest(double t) const;
  // A dataset of one frame, flattened row-major (vectors: 3 components per particle).
  std::vector<double> read(const FrameInfo& frame, const std::string& field) const;

 private:
  std::string path_;
  std::vector<FrameInfo> frames_;
};

}  // namespace pdmpm::test
