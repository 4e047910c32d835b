// Float images written as EXR files with OpenImageIO, not with aosuite's own writer: the
// fixtures of the tests that read EXRs through aosuite.
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace aosuite::test {

// A float image of `channels` named channels ({"Y"}, {"R", "G", "B"}), interleaved.
inline void write_exr(const std::filesystem::path& path, int w, int h,
                      const std::vector<std::string>& channels, const std::vector<float>& pixels) {
  OIIO::ImageSpec spec(w, h, int(channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = channels;
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out && out->open(path.string(), spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
}

}  // namespace aosuite::test
