#pragma once
// Particle fields over time: one HDF5 file with the heavy data and one XDMF 3
// file that tells a viewer (ParaView, VisIt) how to read it as a point cloud
// that moves and may change size between frames.
//
// HDF5 layout (format_version 1):
//   /                      attributes dimension (int), particles (int64, first frame), format_version (int)
//   /frames/<step %08d>/   attributes time (double), step (int64), particles (int64)
//       position           n x 3 doubles (current positions; unused axes are 0)
//       <field>            n (scalar), n x 3 (vector) or n x 6 (tensor6: xx, yy, zz, xy, yz, xz)
//   tensor6 order: XDMF names no order for Tensor6; ParaView hands the six
//   components to VTK, whose symmetric-tensor convention is this one.
//   /topology/polyvertex_<n>   n x 1 int32 = 0..n-1, one per distinct particle count
// The explicit vertex list exists because the XDMF 3 library counts Polyvertex
// elements from the connectivity it reads; without one a reader sees no cells.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "solver/core/state_archive.hpp"

namespace pdmpm::io {

enum class FieldKind { scalar, vector, tensor6 };

// Values per particle of a field kind: 1, 3 or 6.
int components(FieldKind kind);

struct Field {
  std::string name;
  FieldKind kind;
  std::vector<double> values;  // n * components(kind), particle-major
};

// Pads D-component vectors (D = 1, 2, 3) to the 3 components the file stores.
std::vector<double> pad_to_3d(std::span<const double> values, int dimension);

class FieldsWriter {
 public:
  // h5_name_in_xdmf is how the XDMF file names the HDF5 file (relative to the
  // XDMF file, e.g. "fields.h5"), so the pair can be moved together.
  FieldsWriter(std::filesystem::path h5_path, std::filesystem::path xdmf_path, std::string h5_name_in_xdmf,
               int dimension);
  ~FieldsWriter();
  // Continues the fields of a checkpointed run: copies `source` (that run's HDF5
  // file) to h5_path, drops the frames written after the checkpoint and takes up
  // the frame list the checkpoint holds. RunError if the file cannot be used.
  static FieldsWriter resume(const std::filesystem::path& source, std::filesystem::path h5_path,
                             std::filesystem::path xdmf_path, std::string h5_name_in_xdmf, int dimension,
                             core::StateArchive& checkpoint);
  // Saving: flushes the HDF5 file (what a checkpoint refers to is on disk) and
  // stores the frame list in the archive.
  void checkpoint(core::StateArchive& a);

  FieldsWriter(FieldsWriter&&) noexcept;
  FieldsWriter& operator=(FieldsWriter&&) noexcept;
  FieldsWriter(const FieldsWriter&) = delete;
  FieldsWriter& operator=(const FieldsWriter&) = delete;

  // positions: n * 3 current positions. Steps must increase strictly; the
  // particle count and the set of fields may differ from frame to frame.
  void write_frame(std::int64_t step, double time, const std::vector<double>& positions,
                   const std::vector<Field>& fields);

  // Closes the HDF5 file (flushing it) and writes the XDMF file. Idempotent;
  // the destructor calls it but swallows errors, so call it to see them.
  void close();

  std::size_t frames() const;

 private:
  FieldsWriter() = default;
  void sync_frames(core::StateArchive& a);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pdmpm::io
