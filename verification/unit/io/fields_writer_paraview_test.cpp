// The fields a run writes open in ParaView as users open them: a PD, an MPM and a
// hybrid run's fields.xdmf through ParaView's own XDMF reader (pvpython under a
// virtual X server, verification/tools/pvpython_headless.sh), every time step and array found, the arrays finite, and a
// rendered image that is not blank (verification/tools/paraview_check.py).
// Skipped, with the reason, where ParaView is not installed (ci/install_deps.sh
// installs it with PDMPM_WITH_PARAVIEW=1).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "verification/support/command_line.hpp"
#include "verification/support/scratch_dir.hpp"
#include "verification/support/output_files.hpp"

namespace {

namespace fs = std::filesystem;
using pdmpm::test::run_command;

// The scene `file` with its [time] table's first line replaced (a shorter run),
// written into `dir`.
fs::path shortened(const fs::path& file, const std::string& time_line, const fs::path& dir) {
  std::string text = pdmpm::test::read_text(file);
  text = std::regex_replace(text, std::regex(R"((\[time\]\n)[^\n]*)"), "$1" + time_line,
                            std::regex_constants::format_first_only);
  const fs::path out = dir / file.filename();
  std::ofstream(out) << text;
  return out;
}

void check_in_paraview(const fs::path& scene, const std::string& tag) {
  const pdmpm::test::ScratchDir scratch("paraview_" + tag);
  const fs::path out = scratch.path() / "out";
  const fs::path run_scene = shortened(scene, "steps = 120", scratch.path());
  const auto r = pdmpm::test::run_pdmpm("run " + run_scene.string() + " --out " + out.string() + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  // What the writer says it wrote: the frames and the point arrays of fields.xdmf.
  const std::string xdmf = pdmpm::test::read_text(out / "fields.xdmf");
  const std::regex frame(R"(<Grid Name="step_)"), attribute(R"re(Attribute Name="([a-z_]+)")re");
  const auto frames = std::distance(std::sregex_iterator(xdmf.begin(), xdmf.end(), frame), std::sregex_iterator());
  std::set<std::string> names;
  for (auto it = std::sregex_iterator(xdmf.begin(), xdmf.end(), attribute); it != std::sregex_iterator(); ++it)
    names.insert((*it)[1]);
  ASSERT_GE(frames, 2);
  ASSERT_FALSE(names.empty());
  std::string list = names.count("displacement") ? "displacement" : *names.begin();
  for (const auto& n : names)
    if (n != list) list += "," + n;
  const std::string tools = std::string(PDMPM_SOURCE_DIR) + "/verification/tools/";
  const auto pv =
      run_command(tools + "pvpython_headless.sh " + tools + "paraview_check.py " + (out / "fields.xdmf").string() +
                  " " + std::to_string(frames) + " " + list + " " + (scratch.path() / "view.png").string());
  EXPECT_EQ(pv.status, 0) << pv.output;
  EXPECT_NE(pv.output.find("paraview_check: OK"), std::string::npos) << pv.output;
}

class ParaView : public ::testing::Test {
 protected:
  void SetUp() override {
    if (run_command("command -v pvpython && command -v Xvfb").status != 0)
      GTEST_SKIP() << "ParaView's pvpython or Xvfb is not installed (PDMPM_WITH_PARAVIEW=1 ci/install_deps.sh)";
  }
};

// One test for the three (each check starts its own X server).
TEST_F(ParaView, OpensThePdMpmAndHybridFields) {
  const fs::path src = PDMPM_SOURCE_DIR;
  check_in_paraview(src / "scenes/demo_plate_hole.toml", "pd");
  check_in_paraview(src / "verification/scenes/mpm/plate_tension_j2.toml", "mpm");
  check_in_paraview(src / "verification/scenes/hybrid/precracked_plate.toml", "hybrid");
}

}  // namespace
