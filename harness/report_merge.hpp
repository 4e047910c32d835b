// `aosuite report merge`'s library side: shard reports joined into one report folder, every
// shard checked before anything is written.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harness/results.hpp"

namespace aosuite::harness {

// Reads each shard's results.json (read_results: ids and files stay inside their folders) and
// checks them before anything is written: one suite, no case twice, no shard twice nor of
// another run's count, `out` none of the shards, no link or special file among the case
// folders' report files, and every shard of the run there unless `partial` (then the result's
// `shard` says "partial, missing i/n, ..."). Then, holding `out`'s lock (waiting for it if
// `wait`), copies the case folders (each file under a temporary name, then renamed) and writes
// the merged results.json, whose approve command points at `out`. Throws std::runtime_error
// naming the folder at fault, with nothing written.
struct MergedReport {
  RunResults run;
  std::string missing;  // the shards a partial run lacks, "i/n, ..."; empty when it is whole
};
MergedReport merge_reports(const std::filesystem::path& out, const std::vector<std::string>& shards,
                           bool partial, bool wait);

}  // namespace aosuite::harness
