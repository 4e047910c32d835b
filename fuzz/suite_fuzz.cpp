// Suite files (harness/suite.hpp load_suite) on any bytes: refused with a std::runtime_error
// ("file:line:col: reason"; the CLI escapes it), or expanded into cases whose ids are safe
// folder names. Beside the suite lie a scene file (scene.toml, with its mesh tri.obj) and a
// mask image (mask.png) that the suite may name.
#include "ao/scene_cases.hpp"
#include "fuzz/fuzz_util.hpp"
#include "harness/suite_file.hpp"

namespace fuzz = aosuite::fuzz;
namespace hs = aosuite::harness;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  aosuite::ao::register_scene_cases();  // scene cases too, as `aosuite check` reads them
  fuzz::write_file(fuzz::scratch() / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  fuzz::write_file(fuzz::scratch() / "scene.toml",
                   "[[meshes]]\nfile = \"tri.obj\"\n\n[[views]]\nname = \"v\"\n"
                   "eye = [0, 0, 3]\ntarget = [0, 0, 0]\n");
  fuzz::write_file(fuzz::scratch() / "mask.png", "a mask need only exist here");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = fuzz::scratch() / "suite.toml";
  fuzz::write_file(file, fuzz::as_text(data, size));
  try {
    const hs::Suite suite = hs::load_suite(file);
    if (!hs::valid_name(suite.name)) fuzz::fail("a suite name that is not a folder name");
    for (const hs::Case& c : suite.cases) {
      if (!hs::valid_name(c.id)) fuzz::fail("a case id that is not a folder name");
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}
