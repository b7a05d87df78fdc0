// OutputDirectory: nothing is left behind without commit, commit replaces old
// files and leaves unrelated ones alone, unusable paths are refused clearly.
#include "solver/io/output_directory.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <set>
#include <sstream>

#include "solver/core/error.hpp"
#include "verification/support/scratch_dir.hpp"
#include "verification/support/output_files.hpp"

namespace pdmpm::io {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << p;
}

std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const RunError& e) {
    return e.what();
  }
  return "";
}

TEST(OutputDirectory, StagesInsideTheDirectoryUnderAHiddenPidName) {
  test::ScratchDir scratch("outdir_staging");
  const fs::path out = scratch.path() / "run" / "nested";
  OutputDirectory dir(out);
  EXPECT_TRUE(fs::is_directory(out));
  EXPECT_EQ(dir.staging().parent_path(), out);
  EXPECT_EQ(dir.staging().filename().string(), ".partial-" + std::to_string(::getpid()));
  EXPECT_TRUE(fs::is_directory(dir.staging()));
  EXPECT_EQ(dir.path("fields.h5"), dir.staging() / "fields.h5");

  // A second transaction on the same directory in the same process gets its own staging area.
  OutputDirectory other(out);
  EXPECT_NE(other.staging(), dir.staging());
  EXPECT_TRUE(fs::is_directory(other.staging()));
}

TEST(OutputDirectory, AbortLeavesNothingBehind) {
  test::ScratchDir scratch("outdir_abort");
  const fs::path out = scratch.path() / "out";
  fs::create_directories(out);
  write_text(out / "fields.h5", "previous run");
  {
    OutputDirectory dir(out);
    write_text(dir.path("fields.h5"), "half written");
    write_text(dir.path("summary.json"), "{");
    fs::create_directories(dir.path("scratch"));
    write_text(dir.path("scratch") / "deep.bin", "x");
  }  // no commit: as if the run had thrown
  EXPECT_EQ(entries(out), (std::set<std::string>{"fields.h5"}));
  EXPECT_EQ(test::read_text(out / "fields.h5"), "previous run");
}

TEST(OutputDirectory, AbortByExceptionLeavesNothingBehind) {
  test::ScratchDir scratch("outdir_throw");
  const fs::path out = scratch.path() / "out";
  EXPECT_THROW(
      {
        OutputDirectory dir(out);
        write_text(dir.path("history.csv"), "t\n0\n");
        throw RunError("simulated failure");
      },
      RunError);
  EXPECT_TRUE(entries(out).empty());
}

TEST(OutputDirectory, CommitMovesFilesReplacingOldOnesAndKeepsOthers) {
  test::ScratchDir scratch("outdir_commit");
  const fs::path out = scratch.path() / "out";
  fs::create_directories(out);
  write_text(out / "fields.h5", "old fields");
  write_text(out / "notes.txt", "user's notes");
  OutputDirectory dir(out);
  write_text(dir.path("fields.h5"), "new fields");
  write_text(dir.path("summary.json"), "{}");
  const auto moved = dir.commit();
  EXPECT_TRUE(dir.committed());
  EXPECT_EQ(moved, (std::vector<fs::path>{out / "fields.h5", out / "summary.json"}));
  EXPECT_EQ(entries(out), (std::set<std::string>{"fields.h5", "notes.txt", "summary.json"}));
  EXPECT_EQ(test::read_text(out / "fields.h5"), "new fields");
  EXPECT_EQ(test::read_text(out / "summary.json"), "{}");
  EXPECT_EQ(test::read_text(out / "notes.txt"), "user's notes");
  EXPECT_NE(error_of([&] { dir.commit(); }).find("committed twice"), std::string::npos);
  EXPECT_NE(error_of([&] { (void)dir.path("late.txt"); }).find("after commit"), std::string::npos);
}

TEST(OutputDirectory, RejectsNamesThatLeaveTheStagingDirectory) {
  test::ScratchDir scratch("outdir_names");
  OutputDirectory dir(scratch.path() / "out");
  for (const std::string bad : {"", ".", "..", "../escape.txt", "sub/file.txt", "/etc/passwd"})
    EXPECT_NE(error_of([&] { (void)dir.path(bad); }).find("not a plain file name"), std::string::npos) << bad;
}

TEST(OutputDirectory, AFileWhereTheDirectoryShouldBeIsAnError) {
  test::ScratchDir scratch("outdir_file");
  const fs::path out = scratch.path() / "out";
  write_text(out, "I am a file");
  const std::string message = error_of([&] { OutputDirectory dir(out); });
  EXPECT_NE(message.find("exists and is not a directory"), std::string::npos) << message;
  EXPECT_NE(message.find(out.string()), std::string::npos) << message;
  EXPECT_EQ(test::read_text(out), "I am a file");
  // A file on the way to the directory stops creation too.
  EXPECT_NE(error_of([&] { OutputDirectory dir(out / "below"); }).find("cannot create output directory"),
            std::string::npos);
}

TEST(OutputDirectory, ADirectoryWhereNothingCanBeCreatedIsAnError) {
  // procfs refuses new entries even to root, so this runs whoever we are.
  const std::string message = error_of([] { OutputDirectory dir("/proc/self"); });
  EXPECT_NE(message.find("not writable"), std::string::npos) << message;
}

TEST(OutputDirectory, AReadOnlyDirectoryIsAnError) {
  if (::geteuid() == 0) GTEST_SKIP() << "permission bits do not bind root (see the /proc test)";
  test::ScratchDir scratch("outdir_readonly");
  const fs::path out = scratch.path() / "locked";
  fs::create_directories(out);
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_exec);
  const std::string message = error_of([&] { OutputDirectory dir(out); });
  EXPECT_NE(message.find("is not writable"), std::string::npos) << message;
}

}  // namespace
}  // namespace pdmpm::io
