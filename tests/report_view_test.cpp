// What the report shows, as a reviewer sees it in headless Chromium at 1280x720: float (EXR)
// images as pictures, through PNG previews beside them in the report folder, made again when
// the EXR changes; a metric-gated row in its gate's own units; and every failure on one page,
// golden | new | diff side by side, whose boxes feed the approve bar's bless command; what a
// tolerance ignores drawn over the diff. And the review loop on a laptop (1280x800) and a
// desktop (1920x1080): the table beside an open case stays readable, the panel's width is
// dragged and remembered, and an image's views zoom to its largest difference, pan together
// and flicker.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "compare/opencv.hpp"
#include "exr_fixture.hpp"
#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;

// A float value as the preview shows it: sRGB-encoded, in 8 bits.
unsigned char srgb8(double linear) {
  return static_cast<unsigned char>(std::lround(255 * (1.055 * std::pow(linear, 1 / 2.4) - 0.055)));
}

class ReportView : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* d : {"actual", "expected"}) fs::create_directories(dir_ / d);
    // chart.png: half its rows turn green. ao.exr: one grey channel, 12x9, 0.2 -> 0.6.
    cv::Mat red(6, 8, CV_8UC4, cv::Scalar(255, 0, 0, 255));
    write_png_rgba8(dir_ / "expected" / "chart.png", red);
    red.rowRange(0, 3).setTo(cv::Scalar(0, 255, 0, 255));
    write_png_rgba8(dir_ / "actual" / "chart.png", red);
    grey("expected", 0.2f);
    grey("actual", 0.6f);
  }
  void grey(const char* folder, float value) {
    test::write_exr(dir_ / folder / "ao.exr", 12, 9, {"Y"}, std::vector<float>(12 * 9, value));
  }
  test::Outcome check() {
    return test::run_shell("cd " + dir_.path().string() + " && " + AOSUITE_BIN +
                               " check --actual actual --expected expected --report rep"
                               " --gate flip.max_mean=0.05",
                           dir_.path());
  }
  // The page's data: its cases in the report's order.
  nlohmann::json data() const {
    const std::string html = test::read_text(dir_ / "rep" / "index.html");
    const std::string tag = "<script type=\"application/json\" id=data>";
    const std::size_t d0 = html.find(tag) + tag.size();
    return nlohmann::json::parse(html.substr(d0, html.find("</script>", d0) - d0));
  }
  static const nlohmann::json& by_id(const nlohmann::json& cases, const std::string& id) {
    for (const nlohmann::json& c : cases)
      if (c.at("id") == id) return c;
    throw std::runtime_error("no case " + id);
  }
  // The page as Chromium draws it at 1280x720 after `hash`, images loaded.
  std::string dom(const std::string& hash) {
    const test::Outcome r = test::run_shell(
        "chromium --headless --no-sandbox --disable-gpu --window-size=1280,720 "
        "--virtual-time-budget=5000 --dump-dom 'file://" +
            (dir_ / "rep" / "index.html").string() + hash + "'",
        dir_.path());
    EXPECT_EQ(r.rc, 0) << r.err;
    return r.out;
  }
  // Folder mode: `count` more failing cases of long ids, 400x300 pictures of a gradient of which
  // one pixel, (300, 200), turned red: gone__frame_with_a_long_name/sub/dir/image_number_042.png
  // (id gone__frame_with_a_long_name__sub__dir__image_number_042.png) and on.
  void long_named_cases(int count) {
    cv::Mat golden(300, 400, CV_8UC4);
    for (int y = 0; y < golden.rows; ++y)
      for (int x = 0; x < golden.cols; ++x)
        golden.at<cv::Vec4b>(y, x) = cv::Vec4b(static_cast<unsigned char>(x * 255 / 400),
                                               static_cast<unsigned char>(y * 255 / 300), 128, 255);
    cv::Mat fresh = golden.clone();
    fresh.at<cv::Vec4b>(200, 300) = cv::Vec4b(255, 0, 0, 255);
    for (int n = 42; n < 42 + count; ++n) {
      const std::string name =
          fmt::format("gone__frame_with_a_long_name/sub/dir/image_number_{:03}.png", n);
      for (const auto& [side, image] :
           {std::pair{"expected", golden}, std::pair{"actual", fresh}}) {
        fs::create_directories((dir_ / side / name).parent_path());
        write_png_rgba8(dir_ / side / name, image);
      }
    }
    const test::Outcome r =
        test::run_shell("cd " + dir_.path().string() + " && " + AOSUITE_BIN +
                            " check --actual actual --expected expected --report rep",
                        dir_.path());
    ASSERT_EQ(r.rc, 1) << r.out << r.err;
  }
  // Runs `script`, the body of an async function, in a page that shows the report at `hash` in
  // a frame of width x height (the report's window), once it has loaded: f is the frame, w its
  // window, d its document; key(k) presses a key in it, wait(ms) waits (virtual time). Returns
  // what the script returns, {"error": ...} if it threw. The page is in the report's folder
  // (the frame's document is then its own; --allow-file-access-from-files) and Chromium's
  // profile is fresh for each run (localStorage empty).
  nlohmann::json probe(const std::string& hash, int width, int height, const std::string& script) {
    std::ofstream(dir_ / "rep" / "probe.html")
        << "<!doctype html><body style=margin:0><iframe id=f style=\"border:0;width:" << width
        << "px;height:" << height << "px\" src=\"index.html" << hash
        << "\"></iframe><pre id=out></pre>"
        << R"(<script>
const f = document.getElementById("f"), wait = (ms) => new Promise((done) => setTimeout(done, ms));
const key = (k) => f.contentDocument.dispatchEvent(new KeyboardEvent("keydown", { key: k, bubbles: true }));
f.addEventListener("load", async () => {
  const w = f.contentWindow, d = f.contentDocument;
  let out;
  try { out = await (async () => {)"
        << script << R"(})(); } catch (e) { out = { error: String(e) }; }
  document.getElementById("out").textContent = JSON.stringify(out);
}, { once: true });
</script>)";
    fs::remove_all(dir_ / "profile");
    const test::Outcome r = test::run_shell(
        fmt::format("chromium --headless --no-sandbox --disable-gpu --allow-file-access-from-files "
                    "--user-data-dir={} --window-size={},{} --virtual-time-budget=10000 "
                    "--dump-dom 'file://{}'",
                    (dir_ / "profile").string(), width, height + 100,
                    (dir_ / "rep" / "probe.html").string()),
        dir_.path());
    EXPECT_EQ(r.rc, 0) << r.err;
    const std::string tag = "<pre id=\"out\">";
    const std::size_t at = r.out.find(tag);
    if (at == std::string::npos) return {{"error", "no output: " + r.out}};
    std::string out = r.out.substr(at + tag.size(), r.out.find("</pre>", at) - at - tag.size());
    for (const auto& [entity, ch] :
         {std::pair{"&lt;", "<"}, std::pair{"&gt;", ">"}, std::pair{"&amp;", "&"}})
      for (std::size_t p; (p = out.find(entity)) != std::string::npos;)
        out.replace(p, std::string(entity).size(), ch);
    return nlohmann::json::parse(out);
  }
  test::TempDir dir_;
};

const char* const kLongId = "gone__frame_with_a_long_name__sub__dir__image_number_042.png";

// A row's thumbnail for an image no browser may show as it is (WebP here; JPEG, TIFF alike):
// a PNG made from its pixels, not an empty cell.
TEST_F(ReportView, EveryImageTypeHasAThumbnail) {
  const fs::path corpus = fs::path(AOSUITE_SOURCE_DIR) / "tests" / "data" / "corpus" / "benign";
  for (const char* side : {"actual", "expected"})
    fs::copy_file(corpus / side / "webp_lossless.webp", dir_ / side / "photo.webp");
  ASSERT_EQ(check().rc, 1);  // chart.png and ao.exr changed
  const std::string thumb = by_id(data(), "photo.webp").at("thumb");
  EXPECT_EQ(thumb, "cases/photo.webp/thumb_image.webp.png");
  const cv::Mat png = read_png_rgba8(dir_ / "rep" / thumb);
  EXPECT_GT(png.cols, 0);
  EXPECT_LE(png.cols, 160);
}

TEST_F(ReportView, ExrImagesAreShownThroughPngPreviews) {
  const test::Outcome r = check();
  ASSERT_EQ(r.rc, 1) << r.out << r.err;
  const nlohmann::json cases = data();
  ASSERT_EQ(cases.size(), 2u);
  const nlohmann::json& exr = by_id(cases, "ao.exr");
  const nlohmann::json& image = exr.at("images").at(0);

  // Golden and new are shown as PNG previews named by the EXR's bytes, in the report's case
  // folder, each linking its EXR: sRGB-encoded grey at the EXR's size.
  // cases/ao.exr/[golden_]image.exr.<16 hex digits>.s0.png (no std::regex: GCC 12 warns inside
  // <regex> under the sanitizers' flags, and warnings are errors)
  const auto is_preview = [](const std::string& s) {
    for (const std::string prefix : {"cases/ao.exr/image.exr.", "cases/ao.exr/golden_image.exr."}) {
      if (!s.starts_with(prefix) || s.size() != prefix.size() + 16 + 7 || !s.ends_with(".s0.png"))
        continue;
      const std::string hex = s.substr(prefix.size(), 16);
      if (hex.find_first_not_of("0123456789abcdef") == std::string::npos) return true;
    }
    return false;
  };
  for (const auto& [role, value] : {std::pair{"golden", 0.2}, std::pair{"new", 0.6}}) {
    SCOPED_TRACE(role);
    const std::string shown = image.at(role);
    EXPECT_TRUE(is_preview(shown)) << shown;
    EXPECT_EQ(
        image.at(std::string(role) + "_file"),
        std::string("cases/ao.exr/") + (role == std::string("new") ? "" : "golden_") + "image.exr");
    const cv::Mat png = read_png_rgba8(dir_ / "rep" / shown);
    ASSERT_EQ(png.cols, 12);
    ASSERT_EQ(png.rows, 9);
    const unsigned char v = srgb8(value);
    EXPECT_EQ(png.at<cv::Vec4b>(4, 6), cv::Vec4b(v, v, v, 255));
  }
  EXPECT_EQ(exr.at("thumb"), image.at("new"));
  EXPECT_EQ(by_id(cases, "chart.png").at("images").at(0).at("new_file"), "");
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir_ / "expected"))
    EXPECT_TRUE(e.path().filename() == "ao.exr" || e.path().filename() == "chart.png")
        << e.path() << ": nothing is written beside the goldens";

  // The case opened: both previews drawn as pictures that load, each EXR linked.
  const std::string panel = dom("#case=ao.exr");
  for (const char* role : {"golden", "new"})
    EXPECT_NE(panel.find("<img src=\"" + image.at(role).get<std::string>() + "\""),
              std::string::npos)
        << role;
  EXPECT_NE(panel.find("<a href=\"cases/ao.exr/image.exr\">image.exr</a>"), std::string::npos);
  EXPECT_EQ(panel.find("<figure class=\"missing\">"), std::string::npos)
      << "a picture did not load";
}

// A FLIP-gated row shows FLIP's own value, limit and margin, not a mismatch percentage.
TEST_F(ReportView, AMetricGatedRowShowsItsGatesOwnUnits) {
  ASSERT_EQ(check().rc, 1);
  const nlohmann::json cases = data();
  const nlohmann::json& exr = by_id(cases, "ao.exr");
  const nlohmann::json& flip = exr.at("images").at(0).at("gates").at(0);
  EXPECT_EQ(exr.at("measured"), "flip mean " + flip.at("value").get<std::string>());
  EXPECT_EQ(exr.at("limit"), "≤ 0.05");
  EXPECT_EQ(exr.at("margin"), flip.at("margin"));
  EXPECT_TRUE(flip.at("margin").get<std::string>().starts_with("-"));
  EXPECT_NE(dom("").find("<td class=\"num\">≤ 0.05</td>"), std::string::npos);
}

// The page of failures: both cases, golden | new | diff and FLIP's map of each as pictures that
// load, the EXRs linked, the failing gate in words; its boxes feed the approve bar. Keys: v
// (that page), n (its second case), x (select it).
TEST_F(ReportView, EveryFailureIsOnOnePageAndCanBeSelected) {
  ASSERT_EQ(check().rc, 1);
  const nlohmann::json cases = data();
  ASSERT_EQ(cases.size(), 2u);
  const std::string page = dom("#keys=vnx");
  EXPECT_NE(page.find("<div id=\"table-view\" hidden=\"\">"), std::string::npos);
  EXPECT_NE(page.find("<div id=\"failures-view\">"), std::string::npos);
  for (const nlohmann::json& c : cases) {
    const std::string id = c.at("id");
    EXPECT_NE(page.find(">" + id + "</a> <span class=\"FAIL\">FAIL</span>"), std::string::npos)
        << id;
    const nlohmann::json& v = c.at("images").at(0);
    std::vector<std::string> roles = {"golden", "new", "heat"};
    if (id == "chart.png") roles.push_back("diff");  // Resemble's diff: 8-bit images only
    for (const std::string& role : roles) {
      const std::string src = v.at(role);
      EXPECT_NE(page.find("<img src=\"" + src + "\""), std::string::npos) << id << " " << role;
    }
    const std::string gate = v.at("gates").at(0).at("value");
    // The failed gate in words (an 8-bit image's Resemble limits fail beside it).
    EXPECT_NE(page.find("flip mean " + gate + " &gt; 0.05</p>"), std::string::npos) << id;
  }
  EXPECT_NE(page.find("<a href=\"cases/ao.exr/image.exr\">image.exr</a>"), std::string::npos);
  EXPECT_EQ(page.find("<figure class=\"missing\">"), std::string::npos) << "a picture did not load";
  std::string second;  // the id as a --filter regex: dots escaped
  for (const char ch : cases.at(1).at("id").get<std::string>())
    second += ch == '.' ? "\\." : std::string(1, ch);
  EXPECT_NE(page.find("--filter '^" + second + "$'</code>"), std::string::npos) << page;
  EXPECT_NE(page.find("data-copy-covered=\"false\""), std::string::npos);
}

// A preview belongs to the bytes it was made from: when the EXR changes (the same path, the
// report folder's cache in use), the page shows a new preview of the new bytes and the old one
// is gone.
TEST_F(ReportView, APreviewIsMadeAgainWhenItsExrChanges) {
  ASSERT_EQ(check().rc, 1);
  const std::string before = by_id(data(), "ao.exr").at("images").at(0).at("new");
  grey("actual", 0.7f);
  ASSERT_EQ(check().rc, 1);
  const std::string after = by_id(data(), "ao.exr").at("images").at(0).at("new");
  EXPECT_NE(after, before);
  EXPECT_FALSE(fs::exists(dir_ / "rep" / before));
  const unsigned char v = srgb8(0.7);
  EXPECT_EQ(read_png_rgba8(dir_ / "rep" / after).at<cv::Vec4b>(0, 0), cv::Vec4b(v, v, v, 255));
  // Unchanged, it is reused as it is.
  const auto written = fs::last_write_time(dir_ / "rep" / after);
  ASSERT_EQ(check().rc, 1);
  EXPECT_EQ(by_id(data(), "ao.exr").at("images").at(0).at("new"), after);
  EXPECT_EQ(fs::last_write_time(dir_ / "rep" / after), written);
}

// A float image brighter than 1 keeps its highlights: its preview is darkened by whole stops
// (named .s<k>.png), and the page's exposure control, an SVG filter whose table maps each
// 8-bit code c to sRGB(min(1, linear(c) * 2^(stops + exposure))), brings the light back. The
// case opens at minus its images' most stops, so nothing of its brightest 0.1 % clips.
TEST_F(ReportView, BrightFloatImagesArePreviewedDarkenedUnderAnExposureControl) {
  test::write_exr(dir_ / "expected" / "ao.exr", 12, 9, {"Y"}, std::vector<float>(12 * 9, 3.0f));
  grey("actual", 0.5f);
  ASSERT_EQ(check().rc, 1);
  const nlohmann::json image = by_id(data(), "ao.exr").at("images").at(0);
  EXPECT_EQ(image.at("golden_stops"), 2);  // 3 <= 2^2
  EXPECT_EQ(image.at("new_stops"), 0);     // 0.5 <= 1: as it is
  const std::string golden = image.at("golden"), fresh = image.at("new");
  EXPECT_TRUE(golden.ends_with(".s2.png")) << golden;
  EXPECT_TRUE(fresh.ends_with(".s0.png")) << fresh;
  const unsigned char g = srgb8(0.75), n = srgb8(0.5);
  EXPECT_EQ(read_png_rgba8(dir_ / "rep" / golden).at<cv::Vec4b>(0, 0), cv::Vec4b(g, g, g, 255));
  EXPECT_EQ(read_png_rgba8(dir_ / "rep" / fresh).at<cv::Vec4b>(0, 0), cv::Vec4b(n, n, n, 255));

  const std::string panel = dom("#case=ao.exr");
  EXPECT_NE(panel.find("<label class=\"exposure\">"), std::string::npos);
  EXPECT_NE(
      panel.find("<img src=\"" + golden + "\" alt=\"golden\" style=\"filter:url(#exposure2)\">"),
      std::string::npos)
      << panel;
  const std::size_t f = panel.find("<filter id=\"exposure2\"");
  ASSERT_NE(f, std::string::npos) << panel;
  const std::string tag = "tableValues=\"";
  const std::size_t t0 = panel.find(tag, f) + tag.size();
  std::istringstream table(panel.substr(t0, panel.find('"', t0) - t0));
  std::vector<double> entries{std::istream_iterator<double>(table), {}};
  ASSERT_EQ(entries.size(), 256u);
  // The case opens at the exposure its images ask for, -2 (the golden's preview stops), not
  // at 0 where its 3s would clip to white: the table is then the identity, 3 shown as 0.75.
  EXPECT_NE(panel.find("<output>-2</output> stops"), std::string::npos) << panel;
  EXPECT_NE(panel.find("chosen from the images"), std::string::npos) << panel;
  EXPECT_NEAR(entries[g], g / 255.0, 1e-4);
  EXPECT_LT(entries[g], 1.0);
  EXPECT_NEAR(entries[srgb8(0.125)], srgb8(0.125) / 255.0, 1e-4);
  EXPECT_EQ(panel.find("<figure class=\"missing\">"), std::string::npos)
      << "a picture did not load";
}

// A failing 8-bit image shows why beside Resemble's diff: its absolute difference scaled to
// the largest (chart.png's rows that turned green: |R| and |G| change by 255, full scale) and
// the signed one in a diverging map, with the FLIP map's colour scale.
TEST_F(ReportView, AFailureShowsItsAbsoluteAndSignedDifference) {
  ASSERT_EQ(check().rc, 1);
  const nlohmann::json image = by_id(data(), "chart.png").at("images").at(0);
  const std::string abs = image.at("abs"), sign = image.at("signed");
  ASSERT_FALSE(abs.empty());
  ASSERT_FALSE(sign.empty());
  const cv::Mat a = read_png_rgba8(dir_ / "rep" / abs), d = read_png_rgba8(dir_ / "rep" / sign);
  // RGBA in memory as written: a changed row is |0-255|, |255-0|, 0 scaled by 255/255.
  EXPECT_EQ(a.at<cv::Vec4b>(0, 0), cv::Vec4b(255, 255, 0, 255));
  EXPECT_EQ(a.at<cv::Vec4b>(5, 0), cv::Vec4b(0, 0, 0, 255));
  EXPECT_EQ(d.at<cv::Vec4b>(5, 0), cv::Vec4b(255, 255, 255, 255));  // unchanged: white
  const std::string panel = dom("#case=chart.png");
  EXPECT_NE(panel.find("|new − golden|, scaled"), std::string::npos) << panel;
  EXPECT_NE(panel.find("blue darker, white unchanged, red brighter"), std::string::npos);
  EXPECT_NE(panel.find("class=\"scale\""), std::string::npos);
  EXPECT_EQ(panel.find("<figure class=\"missing\">"), std::string::npos)
      << "a picture did not load";
  // The views are 8-bit images' (the EXR's change is read through its exposure control).
  EXPECT_EQ(by_id(data(), "ao.exr").at("images").at(0).at("abs"), "");
}

// What a tolerance sets apart is drawn over the diff: the pixels its ignore box and mask leave
// out, as a layer (outlined, translucent inside) that the page stacks on the diff picture.
TEST_F(ReportView, IgnoredPixelsAreDrawnOverTheDiff) {
  fs::create_directories(dir_ / "s");
  fs::copy_file(dir_ / "expected" / "chart.png", dir_ / "s" / "x.png");
  cv::Mat mask(6, 8, CV_8UC4, cv::Scalar(0, 0, 0, 255));
  mask.at<cv::Vec4b>(5, 7) = cv::Vec4b(255, 255, 255, 255);
  write_png_rgba8(dir_ / "s" / "m.png", mask);
  std::ofstream(dir_ / "s" / "t.toml") << "[[case]]\nname = \"x\"\nfiles = [\"x.png\"]\n"
                                          "[case.tolerance]\nignore = [[0, 0, 2, 1]]\n"
                                          "mask = \"m.png\"\n";
  const auto aosuite = [&](const std::string& args) {
    return test::run_shell("cd " + dir_.path().string() + " && " + AOSUITE_BIN + " " + args,
                           dir_.path());
  };
  ASSERT_EQ(aosuite("bless s/t.toml").rc, 0);
  fs::copy_file(dir_ / "actual" / "chart.png", dir_ / "s" / "x.png",
                fs::copy_options::overwrite_existing);
  const test::Outcome r = aosuite("check s/t.toml --report rep");
  ASSERT_EQ(r.rc, 1) << r.out << r.err;  // rows 0-2 changed, beyond the box: still a failure
  const nlohmann::json image = data().at(0).at("images").at(0);
  ASSERT_EQ(image.at("ignored"), "cases/x/ignored_x.png");
  const cv::Mat layer = read_png_rgba8(dir_ / "rep" / "cases" / "x" / "ignored_x.png");
  ASSERT_EQ(layer.cols, 8);
  ASSERT_EQ(layer.rows, 6);
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{2, 1}, std::pair{7, 5}})
    EXPECT_EQ(layer.at<cv::Vec4b>(y, x)[3], 255) << x << "," << y;  // ignored, on its outline
  for (const auto& [x, y] : {std::pair{3, 0}, std::pair{4, 3}, std::pair{6, 5}})
    EXPECT_EQ(layer.at<cv::Vec4b>(y, x)[3], 0) << x << "," << y;  // compared
  const std::string panel = dom("#case=x");
  EXPECT_NE(panel.find("<div class=\"over\"><img src=\"" + image.at("diff").get<std::string>() +
                       "\" alt=\"diff\"><img class=\"ignored\" src=\"cases/x/ignored_x.png\""),
            std::string::npos)
      << panel;
  EXPECT_EQ(panel.find("<figure class=\"missing\">"), std::string::npos)
      << "a picture did not load";
}

// With a case open beside it, at 1280x800 (the panel half the window, the table's measured,
// limit and time giving way) and at 1920x1080 (every column), each drawn row of the table keeps
// a fixed height, its case's name a readable width broken only after a separator, never inside
// a word, and its thumbnail whole, left of the panel.
TEST_F(ReportView, AnOpenCaseLeavesTheTableReadable) {
  long_named_cases(30);
  for (const auto& [width, height] : {std::pair{1280, 800}, std::pair{1920, 1080}}) {
    SCOPED_TRACE(width);
    const nlohmann::json seen = probe(std::string("#case=") + kLongId, width, height, R"(
      const panel = d.getElementById("detail").getBoundingClientRect();
      return { panel: panel.left, width: panel.width, rows: Array.from(d.querySelectorAll("#cases tbody tr"), (tr) => {
        // The text before each line break of the name: where a character starts a line below.
        const name = tr.querySelector("td.id a"), range = d.createRange(), tops = [], breaks = [];
        for (const node of name.childNodes) {
          for (let i = 0; node.nodeType === Node.TEXT_NODE && i < node.length; ++i) {
            range.setStart(node, i);
            range.setEnd(node, i + 1);
            tops.push(range.getBoundingClientRect().top);
          }
        }
        for (let i = 1; i < tops.length; ++i) if (tops[i] > tops[i - 1]) breaks.push(name.textContent.slice(0, i));
        return { id: name.textContent, height: tr.getBoundingClientRect().height, name: tr.querySelector("td.id").getBoundingClientRect().width,
          thumb: tr.querySelector("td.thumb").getBoundingClientRect().right, breaks };
      }) };)");
    ASSERT_FALSE(seen.contains("error")) << seen;
    EXPECT_NEAR(seen.at("width").get<double>(), width / 2, 10);  // half, less the scroll bar's
    ASSERT_EQ(seen.at("rows").size(), 32u);                      // and chart.png, ao.exr
    bool long_seen = false;
    for (const nlohmann::json& row : seen.at("rows")) {
      const std::string id = row.at("id");
      SCOPED_TRACE(id);
      EXPECT_LE(row.at("height").get<double>(), 130);
      EXPECT_GE(row.at("name").get<double>(), 200);
      EXPECT_LE(row.at("thumb").get<double>(), seen.at("panel").get<double>());
      for (const std::string before : row.at("breaks")) {
        const std::string separators = "/_-.";
        EXPECT_NE(separators.find(before.back()), std::string::npos) << "a break after " << before;
        EXPECT_EQ(separators.find(id[before.size()]), std::string::npos)
            << "a break after " << before;
      }
      long_seen |= id == kLongId && !row.at("breaks").empty();
    }
    EXPECT_TRUE(long_seen) << "the long name is on more than one line";
  }
}

// The panel's left edge drags (to 900 px), moves by 40 px with ← when focused; the width is
// remembered when the page is opened again, and the table keeps 600 px however far the edge is
// dragged.
TEST_F(ReportView, ThePanelsWidthIsDraggedAndRemembered) {
  long_named_cases(3);
  const nlohmann::json seen = probe(std::string("#case=") + kLongId, 1280, 800, R"(
    const width = () => f.contentDocument.getElementById("detail").getBoundingClientRect().width;
    const dragTo = (x) => {
      const w = f.contentWindow, grip = w.document.getElementById("grip"), at = grip.getBoundingClientRect();
      const send = (type, x, to) => to.dispatchEvent(new w.PointerEvent(type, { clientX: x, clientY: 300, bubbles: true }));
      send("pointerdown", at.left + at.width / 2, grip);
      send("pointermove", x, w);
      send("pointerup", x, w);
    };
    dragTo(900);
    const dragged = width();
    d.getElementById("grip").dispatchEvent(new KeyboardEvent("keydown", { key: "ArrowLeft", bubbles: true }));
    const keyed = width();
    w.location.reload();
    await new Promise((done) => f.addEventListener("load", done, { once: true }));
    const reopened = width();
    dragTo(0);
    const table = f.contentDocument.querySelector("main").getBoundingClientRect();
    return { room: f.contentDocument.getElementById("detail").getBoundingClientRect().right, dragged, keyed, reopened, widest: width(), table: table.width, right: table.right,
      panel: f.contentDocument.getElementById("detail").getBoundingClientRect().left };)");
  ASSERT_FALSE(seen.contains("error")) << seen;
  const int room = seen.at("room");  // the window less its scroll bar
  EXPECT_EQ(seen.at("dragged"), room - 900);
  EXPECT_EQ(seen.at("keyed"), room - 900 + 40);
  EXPECT_EQ(seen.at("reopened"), room - 900 + 40);
  EXPECT_EQ(seen.at("widest"), room - 600);
  EXPECT_EQ(seen.at("table"), 600);
  EXPECT_LE(seen.at("right").get<double>(), seen.at("panel").get<double>());
}

// m zooms to 8x and centres every view of the image (golden, new, diff, |new - golden|, new -
// golden, swap, slider) on its largest difference, (300, 200), marked; a view panned by
// dragging takes the others along (Chromium draws no frame in this test, so the page's scroll
// events are sent by hand); b flickers golden and new every 500 ms until b again.
TEST_F(ReportView, TheLargestDifferenceIsShownInEveryViewWhichPanTogether) {
  long_named_cases(1);
  const nlohmann::json seen = probe(std::string("#case=") + kLongId, 1280, 800, R"(
    const views = Array.from(d.querySelectorAll("#detail .images .view"));
    const scrolls = () => views.map((v) => [v.scrollLeft, v.scrollTop]);
    key("m");
    await wait(100);
    const jumped = views.map((v) => {
      const img = v.querySelector("img"), box = v.getBoundingClientRect(), at = img.getBoundingClientRect();
      const scale = at.width / img.naturalWidth, x = at.left + 300.5 * scale, y = at.top + 200.5 * scale;
      return { scale, marked: !!v.querySelector(".mark"),
        centred: Math.abs(x - (box.left + v.clientLeft + v.clientWidth / 2)) <= scale && Math.abs(y - (box.top + v.clientTop + v.clientHeight / 2)) <= scale };
    });
    const atJump = scrolls();
    const send = (type, x, to) => to.dispatchEvent(new w.PointerEvent(type, { clientX: x, clientY: 100, bubbles: true }));
    send("pointerdown", 700, views[1].querySelector("img"));
    send("pointermove", 760, w);
    send("pointerup", 760, w);
    views[1].dispatchEvent(new Event("scroll"));
    const panned = scrolls();
    const swap = d.querySelector(".swap img.new"), shown = () => getComputedStyle(swap).display === "block";
    const flicker = [];
    key("b");
    for (let i = 0; i < 4; ++i, await wait(500)) flicker.push(shown());
    key("b");
    await wait(1000);
    flicker.push(shown());
    return { jumped, atJump, panned, flicker,
      keys: d.querySelector(".keys").textContent, buttons: d.querySelector("#detail .zoom").textContent };)");
  ASSERT_FALSE(seen.contains("error")) << seen;
  ASSERT_EQ(seen.at("jumped").size(), 7u) << seen;
  for (const nlohmann::json& view : seen.at("jumped")) {
    EXPECT_EQ(view.at("scale"), 8) << seen;
    EXPECT_TRUE(view.at("centred")) << seen;
    EXPECT_TRUE(view.at("marked")) << seen;
  }
  const nlohmann::json at_jump = seen.at("atJump"), panned = seen.at("panned");
  EXPECT_GT(at_jump.at(0).at(0).get<double>(), 2000);  // 300 px at 8x, less half a view
  for (std::size_t k = 1; k < 7; ++k) {
    EXPECT_EQ(at_jump.at(k), at_jump.at(0));
    EXPECT_EQ(panned.at(k), panned.at(0));
  }
  EXPECT_EQ(panned.at(0).at(0).get<double>(), at_jump.at(0).at(0).get<double>() - 60);
  EXPECT_EQ(seen.at("flicker"), nlohmann::json({false, true, false, true, false}));
  EXPECT_NE(seen.at("keys").get<std::string>().find("m largest difference, b flicker"),
            std::string::npos);
  EXPECT_NE(seen.at("buttons").get<std::string>().find("largest difference (m)"),
            std::string::npos);
  EXPECT_NE(seen.at("buttons").get<std::string>().find("flicker (b)"), std::string::npos);
}

// A retried case that failed, then passed, shows its failing attempt's pictures beside the
// passing ones; under --report-images failures a passing case says its images were left out and
// names its golden.
TEST_F(ReportView, AFlakyCaseShowsItsFailingAttemptAndAPassNamesItsGolden) {
  fs::create_directories(dir_ / "s");
  cv::Mat red(6, 8, CV_8UC4, cv::Scalar(255, 0, 0, 255));
  write_png_rgba8(dir_ / "s" / "red.png", red);
  red.rowRange(0, 3).setTo(cv::Scalar(0, 255, 0, 255));
  write_png_rgba8(dir_ / "s" / "green.png", red);
  // Green on its first run, red after: FLAKY once the red golden is blessed.
  std::ofstream(dir_ / "s" / "t.toml") << R"([[case]]
name = "wobbly"
command = ["sh", "-c", "if [ -e {suite_dir}/odd ]; then rm {suite_dir}/odd; cp {suite_dir}/red.png {out}/w.png; else touch {suite_dir}/odd; cp {suite_dir}/green.png {out}/w.png; fi"]
outputs = ["w.png"]
)";
  std::ofstream(dir_ / "s" / "odd") << "";
  const std::string bin = std::string(AOSUITE_BIN) + " ";
  const std::string in = "cd " + dir_.path().string() + " && ";
  ASSERT_EQ(test::run_shell(in + bin + "bless s/t.toml", dir_.path()).rc, 0);
  test::Outcome r = test::run_shell(
      in + bin + "check s/t.toml --retries 1 --report rep --report-images failures", dir_.path());
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  std::string panel = dom("#case=wobbly");
  EXPECT_NE(panel.find("Attempt 1: <span class=\"FAIL\">FAIL</span>"), std::string::npos) << panel;
  for (const char* file : {"attempt1_w.png", "attempt1_golden_w.png", "attempt1_diff_w.png"})
    EXPECT_NE(panel.find(std::string("<img src=\"cases/wobbly/") + file + "\""), std::string::npos)
        << file;
  EXPECT_EQ(panel.find("<figure class=\"missing\">"), std::string::npos)
      << "a picture did not load";

  // It passes at once now: its images are left out and the page names its golden.
  std::ofstream(dir_ / "s" / "odd") << "";  // red this time
  r = test::run_shell(in + bin + "check s/t.toml --report rep --report-images failures",
                      dir_.path());
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  panel = dom("#case=wobbly");
  EXPECT_NE(panel.find("Its images were not kept"), std::string::npos) << panel;
  EXPECT_NE(panel.find("s/goldens/t/wobbly/w.png</code>"), std::string::npos) << panel;
  EXPECT_EQ(panel.find("Attempt 1"), std::string::npos);
}

}  // namespace
}  // namespace aosuite
