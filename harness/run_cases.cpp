#include "harness/run_cases.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <stdexcept>

#include "harness/escape.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

RunResults start_run(const Suite& suite, const RunOptions& o, const std::vector<const Case*>& cases,
                     bool may_render, Makers& first) {
  RunResults run;
  run.suite = suite.name, run.suite_file = absolute_path(suite.file);
  run.goldens = absolute_path(suite.goldens);
  run.expected_folder = suite.expected.empty() ? "" : absolute_path(suite.expected);
  run.bless_prefix = bless_prefix(suite);
  run.approve_prefix = run.bless_prefix + " --from-report --report " +
                       shell_quote(o.report_dir.lexically_normal().string());
  // The first case of a registered kind makes its maker here: what it says of the machine
  // (the GL implementation) is in every input hash, and names the platform's goldens.
  const auto made = std::find_if(cases.begin(), cases.end(), [](const Case* c) { return c->kind; });
  if (may_render && made != cases.end()) {
    Environment env;
    first.by_kind[(*made)->kind] = (*made)->kind->maker(&env);
    run.environment = env.description, run.platform = env.platform;
  }
  if (const char* p = std::getenv("AOSUITE_PLATFORM"); p && *p) run.platform = p;
  if (!o.platform.empty()) run.platform = o.platform;
  if (!run.platform.empty() && !valid_name(run.platform)) {
    throw std::invalid_argument("platform '" + printable(run.platform) +
                                "' must be letters, digits, - _ . (it names a folder)");
  }
  if (o.selection.shard_count > 1) {
    run.shard = fmt::format("{}/{}", o.selection.shard_index, o.selection.shard_count);
  }
  fs::create_directories(o.report_dir / "cases");
  // The last run's page goes before this run writes anything: should its page then fail to be
  // written (a full disk), the folder shows no page rather than one older than its results.
  std::error_code ec;
  fs::remove(o.report_dir / "index.html", ec);
  return run;
}

}  // namespace aosuite::harness
