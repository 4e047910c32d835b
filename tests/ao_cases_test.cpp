// The AO bench's rendered suite cases (ao/scene_cases.hpp): how a [[case]] with a scene
// expands, what its input hash covers, and its section of the report.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "ao/scene_cases.hpp"
#include "harness/html_report.hpp"
#include "harness/suite_file.hpp"
#include "png_fixture.hpp"
#include "renderer/params.hpp"
#include "renderer/scene/scene.hpp"
#include "suite_file_fixture.hpp"

namespace aosuite::harness {
namespace {

namespace fs = std::filesystem;

const ao::SceneCase& scene_of(const Case& k) { return static_cast<const ao::SceneCase&>(*k.made); }

Case sized(int width, int height) {
  Case k;
  k.width = width, k.height = height;
  return k;
}

// Suite files with scene cases: the AO bench's kind registered first.
class SceneSuite : public test::SuiteFile {
 protected:
  SceneSuite() { ao::register_scene_cases(); }
};

// With no `techniques`, a case renders every registered screen-space technique (the registry
// is the one list: a new technique joins such suites without an edit in the harness).
TEST_F(SceneSuite, NoTechniquesMeansEveryScreenSpaceTechniqueOfTheRegistry) {
  const Suite s = load_suite(write("[[case]]\nscene = \"plane\"\nviews = [\"above\"]\n"));
  std::vector<std::string> rendered;
  for (const Case& k : s.cases)
    rendered.emplace_back(renderer::technique_name(scene_of(k).technique));
  std::vector<std::string> expected;
  for (const renderer::TechniqueInfo& t : renderer::techniques())
    if (t.space == renderer::Space::kScreen) expected.emplace_back(t.name);
  EXPECT_EQ(rendered, expected);
  EXPECT_NE(std::find(rendered.begin(), rendered.end(), "gtao"), rendered.end());
}

TEST_F(SceneSuite, ExpandsScenesViewsAndTechniquesWithDefaultsAndOverrides) {
  const Suite s = load_suite(write(R"(
[defaults]
width = 64
height = 36
techniques = ["alchemy", "sao"]
params = { samples = 4 }
[defaults.tolerance]
mode = "nothing"
max_mismatch_percent = 1.5

[[case]]
scene = "corner"

[[case]]
scene = "village"
views = ["street"]
techniques = ["mssao"]
name = "wide"
width = 80
params = { radius = 3, level_weights = [1, 0, 0, 0, 0], blur = "none" }
tolerance = { max_channel_delta = 9 }
)"));
  EXPECT_EQ(s.name, "s");
  EXPECT_EQ(s.goldens, (dir_ / "suites" / "goldens" / "s").lexically_normal());  // beside it
  ASSERT_EQ(s.cases.size(), 5u);  // corner: 2 views x 2 techniques; village: 1
  EXPECT_EQ(s.cases[0].id, "corner-" + scene_of(s.cases[0]).view + "-alchemy-64x36");
  EXPECT_EQ(scene_of(s.cases[0]).params.samples, 4);
  EXPECT_EQ(scene_of(s.cases[0]).params.radius,
            renderer::default_params(renderer::Technique::kAlchemy).radius);
  EXPECT_EQ(scene_of(s.cases[1]).technique, renderer::Technique::kSao);
  const Case& v = s.cases[4];
  const ao::SceneCase& vs = scene_of(v);
  EXPECT_EQ(v.id, "village-street-mssao-80x36-wide");
  EXPECT_EQ(vs.params.samples, 4);
  EXPECT_EQ(vs.params.radius, 3);
  EXPECT_EQ(vs.params.mssao.level_weights[1], 0);
  EXPECT_EQ(vs.params.blur, renderer::Blur::kNone);
  EXPECT_EQ(v.tolerance.mode, resemble::Mode::kNothing);  // defaults kept where not overridden
  EXPECT_EQ(v.tolerance.max_mismatch_percent, 1.5);
  EXPECT_EQ(v.tolerance.max_channel_delta, 9);
  EXPECT_EQ(v.images, std::vector<std::string>{"with_ao"});
  // Each case knows its [[case]]: the corner's four share the first table's tolerance.
  for (std::size_t i = 0; i < s.cases.size(); ++i) EXPECT_EQ(s.cases[i].table, i < 4 ? 0 : 1);
}

TEST_F(SceneSuite, MalformedSuitesNameFileLineAndReason) {
  const std::string file = (dir_ / "suites" / "s.toml").string();
  struct Bad {
    std::string text, line, reason;
  };
  const std::vector<Bad> bad = {
      {"[[case]]\nscene = \"plane\"\nwidth = = 3\n", ":3:", ""},
      {"[[case]]\nscene = \"plane\"\ncolour = 3\n", ":3:", "unknown key 'colour'"},
      {"[[case]]\nscene = \"atlantis\"\n", ":2:", "unknown scene 'atlantis'"},
      {"[[case]]\nscene = \"plane\"\nviews = [\"nope\"]\n", ":3:", "no view 'nope'"},
      {"[[case]]\nscene = \"plane\"\ntechniques = [\"hbao\"]\n", ":3:", "unknown technique"},
      {"[[case]]\nscene = \"plane\"\nparams = { radius = \"big\" }\n", ":3:", "radius=big"},
      {"[[case]]\nscene = \"plane\"\nparams = { spin = 1 }\n", ":3:", "unknown parameter 'spin'"},
      {"[[case]]\nscene = \"plane\"\nwidth = 0\n", ":3:", "width must be 1..16384"},
      {"[[case]]\nscene = \"plane\"\n[[case]]\nscene = \"plane\"\n", ":3:", "duplicate case"},
      {"name = \"x\"\n", ":1:", "at least one [[case]]"},
      {"[[case]]\nscene = \"plane\"\ntolerance = { mode = \"fuzzy\" }\n", ":3:", "fuzzy"},
      {"[[case]]\nscene = \"plane\"\ntolerance = { max_mismatch_percent = 120 }\n",
       ":3:", "0..100"},
      {"[[case]]\nscene = \"plane\"\ntolerance = { mask = \"none.png\" }\n", ":3:", "no mask"},
      {"[[case]]\nviews = [\"above\"]\n", ":1:", "needs scene"},
      {"[[case]]\nscene = \"plane\"\nimages = [\"depth\"]\n", ":3:", "unknown image 'depth'"},
  };
  for (const Bad& b : bad) {
    const std::string msg = error_of(b.text);
    EXPECT_EQ(msg.rfind(file + b.line, 0), 0u) << b.text << " -> " << msg;
    EXPECT_NE(msg.find(b.reason), std::string::npos) << b.text << " -> " << msg;
  }
}

// A parameter left out of the input hash would silently reuse stale renders: every
// parameter of the table, set to its sample value, must change the hash, for every technique.
TEST(CaseHash, EveryParameterChangesTheInputHash) {
  ao::SceneCase c;
  c.scene = std::make_shared<const renderer::Scene>(renderer::builtin_scene("plane"));
  c.view = "above";
  const Case k = sized(8, 8);
  for (const renderer::TechniqueInfo& t : renderer::techniques()) {
    c.technique = t.id, c.params = t.defaults();
    const std::string base = c.input_hash(k, "gl");
    for (const renderer::ParamSpec& spec : renderer::param_specs()) {
      ao::SceneCase changed = c;
      renderer::set_param(changed.params, spec.key, spec.sample);
      EXPECT_NE(renderer::param_text(spec, changed.params), renderer::param_text(spec, c.params))
          << spec.key << ": its sample equals " << t.name << "'s default";
      EXPECT_NE(changed.input_hash(k, "gl"), base) << t.name << " " << spec.key;
    }
  }
}

// Every field of the scene a render reads changes the input hash: a changed field of view (or
// any other) must never reuse a stale render (a mutation that left fovy_degrees out of the hash
// passed every test before this one). Placement transforms are applied when a scene is loaded,
// so they reach the hash as the positions and normals they move.
TEST(CaseHash, EverySceneMeshAndViewFieldChangesTheInputHash) {
  ao::SceneCase c;
  c.scene = std::make_shared<const renderer::Scene>(renderer::builtin_scene("corner"));
  c.view = c.scene->views[0].name;
  c.technique = renderer::Technique::kSao, c.params = renderer::default_params(c.technique);
  const Case k = sized(8, 8);
  const std::string base = c.input_hash(k, "gl");
  using Edit = std::function<void(renderer::Scene&)>;
  const std::vector<std::pair<const char*, Edit>> edits{
      {"position", [](renderer::Scene& s) { s.meshes[0].positions[0].y += 1e-3f; }},
      {"normal", [](renderer::Scene& s) { s.meshes[0].normals[0].x += 1e-3f; }},
      {"triangle",
       [](renderer::Scene& s) {
         std::swap(s.meshes[0].triangles[0].x, s.meshes[0].triangles[0].y);
       }},
      {"colour", [](renderer::Scene& s) { s.meshes[0].colour.g += 1e-3f; }},
      {"ground", [](renderer::Scene& s) { s.meshes[0].ground = !s.meshes[0].ground; }},
      {"mesh added", [](renderer::Scene& s) { s.meshes.push_back(s.meshes[0]); }},
      {"eye", [](renderer::Scene& s) { s.views[0].eye.z += 1e-3f; }},
      {"target", [](renderer::Scene& s) { s.views[0].target.x += 1e-3f; }},
      {"up", [](renderer::Scene& s) { s.views[0].up.x += 1e-3f; }},
      {"fovy_degrees", [](renderer::Scene& s) { s.views[0].fovy_degrees += 1e-3f; }},
      {"near", [](renderer::Scene& s) { s.views[0].near *= 1.001f; }},
  };
  for (const auto& [field, edit] : edits) {
    renderer::Scene s = *c.scene;
    edit(s);
    ao::SceneCase changed = c;
    changed.scene = std::make_shared<const renderer::Scene>(std::move(s));
    EXPECT_NE(changed.input_hash(k, "gl"), base) << field;
  }
  ao::SceneCase other_view = c, other_technique = c;
  other_view.view = c.scene->views[1].name;
  other_technique.technique = renderer::Technique::kGtao;
  EXPECT_NE(other_view.input_hash(k, "gl"), base);
  EXPECT_NE(other_technique.input_hash(k, "gl"), base);
  EXPECT_NE(c.input_hash(sized(9, 8), "gl"), base);
  EXPECT_NE(c.input_hash(sized(8, 9), "gl"), base);
  EXPECT_NE(c.input_hash(k, "another GL"), base);
}

TEST(HtmlReport, ASuiteWithSceneCasesLinksTheLatestSweepBesideIt) {
  ao::register_scene_cases();
  const test::TempDir dir;
  RunResults r;
  r.suite = "s";
  CaseResult c;
  c.id = "c", c.kind = "render", c.status = Status::kPass;
  c.labels = {{"technique", "sao"}};
  c.figures = {{"ao_effect_less", 12.5}, {"ao_effect_nothing", 40}};
  r.cases = {c};
  write_html_report(r, dir.path() / "s");
  auto page = [&] {
    std::ifstream in(dir.path() / "s" / "index.html");
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_NE(page().find("No sweep next to this report"), std::string::npos);
  fs::create_directories(dir.path() / "sweep");
  std::ofstream(dir.path() / "sweep" / "sweep.md") << "| t |";
  std::ofstream(dir.path() / "sweep" / "sweep_320x180.svg") << "<svg/>";
  write_html_report(r, dir.path() / "s");
  EXPECT_NE(page().find("href=\"../sweep/sweep.md\""), std::string::npos);
  EXPECT_NE(page().find("href=\"../sweep/sweep_320x180.svg\""), std::string::npos);
  EXPECT_NE(page().find("<td class=num>12.50</td>"), std::string::npos);  // the AO effect
  // An image-only run has no AO section.
  r.cases[0].kind = "files";
  write_html_report(r, dir.path() / "s");
  EXPECT_EQ(page().find("sweep"), std::string::npos);
}

// The project's own suites name their goldens, so they are found from any directory.
TEST_F(SceneSuite, TheDefaultSuitesGoldensAreFoundFromAnyDirectory) {
  const Suite d = load_suite(fs::path(AOSUITE_SOURCE_DIR) / "suites" / "default.toml");
  EXPECT_EQ(d.goldens, (fs::path(AOSUITE_SOURCE_DIR) / "goldens" / "default").lexically_normal());
  EXPECT_TRUE(fs::is_directory(d.goldens / d.cases.front().id)) << d.goldens;
}

}  // namespace
}  // namespace aosuite::harness
