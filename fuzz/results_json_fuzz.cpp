// results.json as `report merge` reads a shard's (harness/results.hpp run_from_json): refused
// with an exception (read_results names the file), or read into results that stay inside
// their folders and that write back to JSON that reads back the same.
#include <nlohmann/json.hpp>

#include "fuzz/fuzz_util.hpp"
#include "harness/results.hpp"

namespace fuzz = aosuite::fuzz;
namespace hs = aosuite::harness;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hs::RunResults run;
  try {
    run = hs::run_from_json(nlohmann::json::parse(fuzz::as_text(data, size)));
  } catch (const std::exception&) {
    return 0;
  }
  for (const hs::CaseResult& c : run.cases) {
    if (!hs::valid_name(c.id)) fuzz::fail("a case id that is not a folder name");
  }
  const nlohmann::json written = hs::to_json(run);
  if (hs::to_json(hs::run_from_json(written)) != written) {
    fuzz::fail("results read back differently from how they were written");
  }
  (void)written.dump();  // throws on anything that is not UTF-8
  return 0;
}
