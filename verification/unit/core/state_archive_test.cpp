// The checkpoint archive: what is saved is restored bit for bit, and a file or
// block that does not fit is refused with a message rather than read as state.
#include "solver/core/state_archive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "solver/core/types.hpp"
#include "verification/support/scratch_dir.hpp"
#include "verification/support/same_bits.hpp"

namespace pdmpm::core {
namespace {

using test::same_bits;

struct Sample {
  std::vector<double> values{1.0, -0.0, std::numeric_limits<double>::quiet_NaN(), 1e-310, -1e308};
  std::vector<Vec<3>> vectors{Vec<3>(1, 2, 3), Vec<3>(-4, 5e-300, 6)};
  std::vector<std::uint8_t> flags{0, 1, 255};
  std::vector<std::int64_t> empty;
  Mat<2> matrix = (Mat<2>() << 1, 2, 3, 4).finished();
  std::int64_t count = -7;
  std::string text = "a scene\nwith lines";

  void sync(StateArchive& a) {
    a.sync("values", values);
    a.sync("vectors", vectors);
    a.sync("flags", flags);
    a.sync("empty", empty);
    a.sync("matrix", matrix);
    a.sync("count", count);
    a.sync("text", text);
  }
};

TEST(StateArchive, RestoresWhatWasSavedBitForBitThroughAFile) {
  test::ScratchDir dir("state_archive");
  Sample saved;
  StateArchive out(StateArchive::Mode::save);
  saved.sync(out);
  const auto path = dir.path() / "a.pdmpm";
  out.write(path);

  StateArchive in = StateArchive::read(path);
  Sample restored;
  restored.values.clear();
  restored.vectors.assign(5, Vec<3>::Zero());  // the stored length wins
  restored.matrix.setZero();
  restored.count = 0;
  restored.text.clear();
  restored.sync(in);
  EXPECT_TRUE(same_bits(restored.values, saved.values));
  EXPECT_EQ(restored.vectors, saved.vectors);
  EXPECT_EQ(restored.flags, saved.flags);
  EXPECT_TRUE(restored.empty.empty());
  EXPECT_EQ(restored.matrix, saved.matrix);
  EXPECT_EQ(restored.count, -7);
  EXPECT_EQ(restored.text, saved.text);
  EXPECT_TRUE(in.unread().empty());
}

TEST(StateArchive, AnInMemoryRestorerRestoresTheSameStateAsOftenAsAsked) {
  Sample saved;
  StateArchive out(StateArchive::Mode::save);
  saved.sync(out);
  const StateArchive in = out.restorer();
  EXPECT_FALSE(in.saving());
  for (int round = 0; round < 2; ++round) {  // each restore starts from the same blocks
    StateArchive again = in;
    Sample restored;
    restored.values.assign(1, 9.0);
    restored.count = round;
    restored.sync(again);
    EXPECT_TRUE(same_bits(restored.values, saved.values));
    EXPECT_EQ(restored.vectors, saved.vectors);
    EXPECT_EQ(restored.count, -7);
    EXPECT_EQ(restored.text, saved.text);
    EXPECT_TRUE(again.unread().empty());
  }
}

TEST(StateArchive, AMissingOrMisfitBlockIsAMismatch) {
  StateArchive out(StateArchive::Mode::save);
  double x = 1.0;
  std::vector<double> v{1.0, 2.0, 3.0};
  out.sync("x", x);
  out.sync("v", v);
  test::ScratchDir dir("state_archive_misfit");
  out.write(dir.path() / "a");
  {
    StateArchive in = StateArchive::read(dir.path() / "a");
    double y = 0.0;
    EXPECT_THROW(in.sync("y", y), StateMismatch);
    std::int32_t narrow = 0;
    EXPECT_THROW(in.sync("x", narrow), StateMismatch);  // 8 bytes stored, 4 asked
    std::vector<Vec<2>> pairs;
    EXPECT_THROW(in.sync("v", pairs), StateMismatch);  // 24 bytes are not whole 2-vectors
  }
  {
    StateArchive in = StateArchive::read(dir.path() / "a");
    in.sync("x", x);
    ASSERT_EQ(in.unread().size(), 1u);
    EXPECT_EQ(in.unread().front(), "v");
  }
  EXPECT_THROW(out.sync("x", x), std::logic_error);  // the same name twice is a programming error
}

TEST(StateArchive, ADamagedTruncatedOrForeignFileIsRefused) {
  test::ScratchDir dir("state_archive_damaged");
  StateArchive out(StateArchive::Mode::save);
  std::vector<double> v(100, 0.5);
  out.sync("v", v);
  const auto good = dir.path() / "good";
  out.write(good);
  std::string bytes;
  {
    std::ifstream in(good, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  auto write = [&](const std::string& name, const std::string& content) {
    std::ofstream o(dir.path() / name, std::ios::binary);
    o << content;
    return dir.path() / name;
  };
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  EXPECT_THROW(StateArchive::read(write("flipped", flipped)), StateMismatch);
  EXPECT_THROW(StateArchive::read(write("cut", bytes.substr(0, bytes.size() - 9))), StateMismatch);
  EXPECT_THROW(StateArchive::read(write("toml", "[scene]\nid = \"x\"\n")), StateMismatch);
  EXPECT_THROW(StateArchive::read(dir.path() / "absent"), StateMismatch);
  EXPECT_NO_THROW(StateArchive::read(good));
}

}  // namespace
}  // namespace pdmpm::core
