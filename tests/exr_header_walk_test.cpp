// image/exr_header_walk.cpp against OpenEXR itself: a file holding an attribute of every type
// OpenEXR 3.1 knows is walked to its end, and so is one whose declared sizes lie where
// OpenEXR's reader ignores them; a size claim after such a lie is still caught.
#include "image/exr_header_walk.hpp"

#include <ImfAttribute.h>
#include <ImfBoxAttribute.h>
#include <ImfChannelListAttribute.h>
#include <ImfChromaticitiesAttribute.h>
#include <ImfCompressionAttribute.h>
#include <ImfDeepImageStateAttribute.h>
#include <ImfDoubleAttribute.h>
#include <ImfEnvmapAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfFloatVectorAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfKeyCodeAttribute.h>
#include <ImfLineOrderAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfPreviewImageAttribute.h>
#include <ImfRationalAttribute.h>
#include <ImfStdIO.h>
#include <ImfStringAttribute.h>
#include <ImfStringVectorAttribute.h>
#include <ImfTileDescriptionAttribute.h>
#include <ImfTimeCodeAttribute.h>
#include <ImfVecAttribute.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Attr {
  std::string name, type;
};

// The attributes the test file carries beside OpenEXR's own, one per type the walk sizes
// by type rather than by declared size, then a few sized by their declared size.
// "zzz" sorts last: OpenEXR writes attributes in name order.
const std::vector<Attr> kFixedSize = {
    {"a_box2i", "box2i"},
    {"a_box2f", "box2f"},
    {"a_chroma", "chromaticities"},
    {"a_compression", "compression"},
    {"a_deep", "deepImageState"},
    {"a_double", "double"},
    {"a_envmap", "envmap"},
    {"a_float", "float"},
    {"a_int", "int"},
    {"a_keycode", "keycode"},
    {"a_lineorder", "lineOrder"},
    {"a_m33f", "m33f"},
    {"a_m33d", "m33d"},
    {"a_m44f", "m44f"},
    {"a_m44d", "m44d"},
    {"a_rational", "rational"},
    {"a_tiledesc", "tiledesc"},
    {"a_timecode", "timecode"},
    {"a_v2i", "v2i"},
    {"a_v2f", "v2f"},
    {"a_v2d", "v2d"},
    {"a_v3i", "v3i"},
    {"a_v3f", "v3f"},
    {"a_v3d", "v3d"},
    {"a_chlist", "chlist"},
    {"channels", "chlist"},
};

std::string write_file() {
  Imf::Header h(3, 2);
  h.channels().insert("Y", Imf::Channel(Imf::FLOAT));
  h.insert("a_box2i", Imf::Box2iAttribute(Imath::Box2i({1, 2}, {3, 4})));
  h.insert("a_box2f", Imf::Box2fAttribute(Imath::Box2f({1, 2}, {3, 4})));
  h.insert("a_chroma", Imf::ChromaticitiesAttribute(Imf::Chromaticities()));
  h.insert("a_compression", Imf::CompressionAttribute(Imf::PIZ_COMPRESSION));
  h.insert("a_deep", Imf::DeepImageStateAttribute(Imf::DIS_TIDY));
  h.insert("a_double", Imf::DoubleAttribute(0.25));
  h.insert("a_envmap", Imf::EnvmapAttribute(Imf::ENVMAP_CUBE));
  h.insert("a_float", Imf::FloatAttribute(0.5f));
  h.insert("a_int", Imf::IntAttribute(7));
  h.insert("a_keycode", Imf::KeyCodeAttribute(Imf::KeyCode(1, 2, 3, 4, 5, 4, 64)));
  h.insert("a_lineorder", Imf::LineOrderAttribute(Imf::DECREASING_Y));
  h.insert("a_m33f", Imf::M33fAttribute(Imath::M33f()));
  h.insert("a_m33d", Imf::M33dAttribute(Imath::M33d()));
  h.insert("a_m44f", Imf::M44fAttribute(Imath::M44f()));
  h.insert("a_m44d", Imf::M44dAttribute(Imath::M44d()));
  h.insert("a_rational", Imf::RationalAttribute(Imf::Rational(1, 3)));
  h.insert("a_tiledesc", Imf::TileDescriptionAttribute(Imf::TileDescription(8, 8)));
  h.insert("a_timecode", Imf::TimeCodeAttribute(Imf::TimeCode(1, 2, 3, 4)));
  h.insert("a_v2i", Imf::V2iAttribute(Imath::V2i(1, 2)));
  h.insert("a_v2f", Imf::V2fAttribute(Imath::V2f(1, 2)));
  h.insert("a_v2d", Imf::V2dAttribute(Imath::V2d(1, 2)));
  h.insert("a_v3i", Imf::V3iAttribute(Imath::V3i(1, 2, 3)));
  h.insert("a_v3f", Imf::V3fAttribute(Imath::V3f(1, 2, 3)));
  h.insert("a_v3d", Imf::V3dAttribute(Imath::V3d(1, 2, 3)));
  Imf::ChannelList more;
  more.insert("R", Imf::Channel(Imf::HALF));
  more.insert("a long channel name", Imf::Channel(Imf::UINT));
  h.insert("a_chlist", Imf::ChannelListAttribute(more));
  h.insert("b_floats", Imf::FloatVectorAttribute({1.0f, 2.0f, 3.0f}));
  h.insert("b_strings", Imf::StringVectorAttribute({"one", "", "three"}));
  Imf::PreviewImage preview(2, 3);
  h.insert("b_preview", Imf::PreviewImageAttribute(preview));
  h.insert("b_opaque", Imf::StringAttribute("a string"));
  h.insert("zzz", Imf::StringAttribute("the last attribute"));
  Imf::StdOSStream os;
  {
    Imf::OutputFile out(os, h);
    std::vector<float> px(6, 0.5f);
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data()), sizeof(float),
                              3 * sizeof(float)));
    out.setFrameBuffer(fb);
    out.writePixels(2);
  }
  return os.str();
}

// Where the attribute's declared size sits in the file.
std::size_t size_field(const std::string& file, const Attr& a) {
  const std::string key = a.name + '\0' + a.type + '\0';
  const std::size_t at = file.find(key, 8);
  if (at == std::string::npos) throw std::logic_error("no attribute " + a.name);
  return at + key.size();
}

std::uint32_t get_u32(const std::string& file, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(file[at + std::size_t(i)]);
  return v;
}

void put_u32(std::string& file, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) file[at + std::size_t(i)] = char(v >> (8 * i) & 0xff);
}

std::vector<std::string> walk(const std::string& file) {
  return aosuite::exr::check_attribute_sizes(reinterpret_cast<const unsigned char*>(file.data()),
                                             file.size());
}

// The attributes' names as OpenEXR read them (in name order: OpenEXR writes them so).
std::vector<std::string> openexr_names(const std::string& file) {
  Imf::StdISStream is;
  is.str(file);
  Imf::InputFile f(is);
  std::vector<std::string> names;
  for (auto it = f.header().begin(); it != f.header().end(); ++it) names.emplace_back(it.name());
  return names;
}

// OpenEXR reads the whole file: header and pixels.
bool openexr_reads(const std::string& file) {
  try {
    Imf::StdISStream is;
    is.str(file);
    Imf::InputFile f(is);
    std::vector<float> px(6);
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data()), sizeof(float),
                              3 * sizeof(float)));
    f.setFrameBuffer(fb);
    f.readPixels(0, 1);
    return px[5] == 0.5f;
  } catch (const std::exception&) {
    return false;
  }
}

TEST(ExrHeaderWalk, EveryAttributeTypeIsWalkedToTheEnd) {
  const std::string file = write_file();
  ASSERT_TRUE(openexr_reads(file));
  EXPECT_EQ(walk(file), openexr_names(file));
  // The walk reaches the last attribute: a claim there is caught.
  std::string claims = file;
  put_u32(claims, size_field(file, {"zzz", "string"}), 0x73690013u);
  try {
    walk(claims);
    ADD_FAILURE() << "a 1.9 GB claim in the last attribute passed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("attribute 'zzz' claims 1936261139 bytes"),
              std::string::npos)
        << e.what();
  }
}

// OpenEXR's readers of these types take what their type holds, whatever the declared size
// says (exr_fuzz: a channel list declaring fewer bytes than it held hid a 1.9 GB claim after
// it). Each lie is checked to be one OpenEXR reads past, so the premise is tested too.
TEST(ExrHeaderWalk, DeclaredSizesTheReaderIgnoresDoNotLoseTheWalk) {
  const std::string file = write_file();
  std::mt19937 rng(20261124);
  std::vector<Attr> lied = kFixedSize;
  lied.push_back({"b_floats", "floatvector"});  // whole floats only: 12 + 3 still reads 3
  for (const Attr& a : lied) {
    const std::size_t at = size_field(file, a);
    const std::uint32_t truth = get_u32(file, at);
    for (int i = 0; i < 6; ++i) {
      std::string lie = file;
      const std::uint32_t size =
          a.type == "floatvector" ? truth + 1 + std::uint32_t(i % 3) : std::uint32_t(rng() % 64);
      put_u32(lie, at, size);
      ASSERT_TRUE(openexr_reads(lie)) << a.name << " declared " << size;
      EXPECT_EQ(walk(lie), openexr_names(lie)) << a.name << " declared " << size;
      put_u32(lie, size_field(file, {"zzz", "string"}), 0x7fff0000u);
      EXPECT_THROW(walk(lie), std::runtime_error) << a.name << " declared " << size;
    }
  }
}

TEST(ExrHeaderWalk, CutOffAndOverlongNamesAreRefused) {
  const std::string file = write_file();
  const std::size_t size_at = size_field(file, {"zzz", "string"});
  for (std::size_t n = size_at; n < size_at + 4; ++n)  // inside the size field
    EXPECT_THROW(walk(file.substr(0, n)), std::runtime_error) << n;
  // Cut inside the value: the declared 18 bytes are more than are left.
  EXPECT_THROW(walk(file.substr(0, size_at + 4 + 17)), std::runtime_error);
  // OpenEXR's names hold 255 bytes at most.
  const std::string overlong = file.substr(0, 8) + std::string(256, 'n') + '\0' + "int" + '\0';
  EXPECT_THROW(walk(overlong + std::string(8, '\0')), std::runtime_error);
  const std::string longest = file.substr(0, 8) + std::string(255, 'n') + '\0' + "int" + '\0';
  EXPECT_NO_THROW(walk(longest + std::string("\4\0\0\0", 4) + std::string(4, '\0') + '\0'));
}

}  // namespace
