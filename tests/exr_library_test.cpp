// libaosuite_exr.so's C entry points as any caller sees them: a written image reads back
// exactly, and an allocator that refuses the size still leaves a reason in err (exr_fuzz found
// a refusal that said nothing: fuzz/corpus/exr/window_refused_by_allocator.exr).
#include "image/exr_library.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "common/file_io.hpp"
#include "tests/png_fixture.hpp"

namespace {

// What the library asked room for, and the room given (none when `refuse` is set).
struct Room {
  bool refuse = false;
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;
};

float* room_for(void* user, int width, int height, int channels) {
  auto& room = *static_cast<Room*>(user);
  room.width = width, room.height = height, room.channels = channels;
  if (room.refuse) return nullptr;
  room.pixels.assign(std::size_t(width) * std::size_t(height) * std::size_t(channels), -1.0f);
  return room.pixels.data();
}

std::vector<unsigned char> written_exr(int width, int height, const std::vector<float>& pixels) {
  const aosuite::test::TempDir dir;  // its own: ctest runs these tests side by side
  const auto path = dir / "written.exr";
  char err[512] = {};
  EXPECT_EQ(aosuite_write_exr(path.c_str(), width, height, 1, pixels.data(), err, sizeof err), 0)
      << err;
  return aosuite::read_file(path);
}

std::vector<float> ramp(int count) {
  std::vector<float> v(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) v[std::size_t(i)] = 0.25f * float(i) - 1.5f;
  return v;
}

TEST(ExrLibrary, AWrittenImageReadsBackExactly) {
  const std::vector<float> pixels = ramp(7 * 5);
  const auto bytes = written_exr(7, 5, pixels);
  Room room;
  char err[512] = {};
  ASSERT_EQ(aosuite_read_exr(bytes.data(), bytes.size(), &room_for, &room, err, sizeof err), 0)
      << err;
  EXPECT_EQ(room.width, 7);
  EXPECT_EQ(room.height, 5);
  EXPECT_EQ(room.channels, 1);
  EXPECT_EQ(room.pixels, pixels);
}

TEST(ExrLibrary, ARefusedSizeIsNamedInTheError) {
  const auto bytes = written_exr(9, 4, ramp(9 * 4));
  Room room;
  room.refuse = true;
  char err[512] = {};
  EXPECT_EQ(aosuite_read_exr(bytes.data(), bytes.size(), &room_for, &room, err, sizeof err), 1);
  EXPECT_EQ(room.width, 9);  // the allocator was asked for the real size, then refused it
  const std::string reason = err;
  EXPECT_NE(reason.find("9x4"), std::string::npos) << reason;
  EXPECT_NE(reason.find("refused"), std::string::npos) << reason;
}

TEST(ExrLibrary, TruncatedBytesAreRefusedWithAReason) {
  const auto bytes = written_exr(6, 6, ramp(36));
  for (const std::size_t keep : {std::size_t{0}, std::size_t{3}, bytes.size() / 2}) {
    Room room;
    char err[512] = {};
    EXPECT_EQ(aosuite_read_exr(bytes.data(), keep, &room_for, &room, err, sizeof err), 1);
    EXPECT_NE(std::string(err), "") << "keeping " << keep << " bytes";
  }
}

}  // namespace
