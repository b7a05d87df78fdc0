#pragma once
// Provenance of this build (outputs and reports show which build produced a
// number). Defined in a source file CMake generates at configure time, so a new
// commit recompiles that one file, not the library.
namespace pdmpm::build_info {

const char* git_sha();   // short commit hash at configure time, or "unknown"
const char* compiler();  // e.g. "GNU 12.2.0"
const char* flags();     // optimisation flags of the release build

}  // namespace pdmpm::build_info
