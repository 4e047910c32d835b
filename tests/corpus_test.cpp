// One comparison, one tolerance: every pair of the corpus (tests/data/corpus, made by its
// make_corpus.py) gets the same verdict and the same reasons through the four entry points,
// `aosuite compare`, folder mode, a suite and the C++ API, under the defaults alone. The
// regressions (a 1 px shift, 2 % brighter, 1 % noise, a patch, a blur, a channel swap, 16 -> 8
// bits) must fail and the benign changes (re-encoded PNG, lossless WebP, TIFF, a driver's +-1
// on a few pixels) must pass.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <aosuite/aosuite.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "process.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(AOSUITE_SOURCE_DIR) / "tests" / "data" / "corpus";

struct Said {
  bool pass = false;
  std::string message;  // the failed limits, "; "-joined; "" when it passed
};

class Corpus : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "aosuite-corpus-XXXXXX").string();
    dir_ = mkdtemp(tmpl.data());
    const std::string& name = GetParam();
    group_ = fs::exists(kCorpus / "regressions" / "expected" / name) ? "regressions" : "benign";
    expected_ = kCorpus / group_ / "expected" / name;
    actual_ = kCorpus / group_ / "actual" / name;
  }
  void TearDown() override { fs::remove_all(dir_); }

  aosuite::test::Outcome run(const std::string& args) {
    return aosuite::test::run_shell("cd '" + dir_.string() + "' && " + AOSUITE_BIN + " " + args,
                                    dir_);
  }

  Said compare() {
    const auto r = run("compare '" + expected_.string() + "' '" + actual_.string() + "' --json");
    EXPECT_NE(r.rc, 2) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    Said s{r.rc == 0, ""};
    for (const auto& f : j.at("failed_gates"))
      s.message += (s.message.empty() ? "" : "; ") + f.get<std::string>();
    EXPECT_EQ(j.at("verdict") == "same", s.pass) << r.out;
    return s;
  }

  // The one image of a run's results.json.
  Said from_results(const aosuite::test::Outcome& r, const fs::path& results) {
    EXPECT_NE(r.rc, 2) << r.out << r.err;
    std::ifstream in(results);
    const auto image = nlohmann::json::parse(in).at("cases").at(0).at("images").at(0);
    return {r.rc == 0, image.value("message", "")};
  }

  Said folder() {
    const std::string file = actual_.filename().string();
    fs::create_directories(dir_ / "act");
    fs::create_directories(dir_ / "exp");
    fs::copy_file(actual_, dir_ / "act" / file);
    fs::copy_file(expected_, dir_ / "exp" / file);
    return from_results(run("check --actual act --expected exp --report folder"),
                        dir_ / "folder" / "results.json");
  }

  Said suite() {
    const auto write = [&](const fs::path& image) {
      std::ofstream(dir_ / "corpus.toml", std::ios::trunc)
          << "[[case]]\nname = \"pair\"\nfiles = [\"" << image.string() << "\"]\n";
    };
    write(expected_);
    const auto blessed = run("bless corpus.toml");
    EXPECT_EQ(blessed.rc, 0) << blessed.out << blessed.err;
    write(actual_);
    return from_results(run("check corpus.toml --report suite"), dir_ / "suite" / "results.json");
  }

  // The renderer's view: its frame in memory against the golden file.
  Said api() {
    setenv("AOSUITE_FAILURES", (dir_ / "failures").c_str(), 1);
    const aosuite::Verdict v =
        aosuite::matches_golden(aosuite::read_image(actual_.string()), expected_.string());
    EXPECT_NE(v.status, aosuite::Verdict::Status::kError) << v;
    return {bool(v), v.message.substr(0, v.message.find('\n'))};
  }

  fs::path dir_, expected_, actual_;
  std::string group_;
};

TEST_P(Corpus, EveryEntryPointGivesTheDefaultsVerdictInTheSameWords) {
  const Said c = compare(), f = folder(), s = suite(), a = api();
  EXPECT_EQ(c.pass, group_ == "benign") << c.message;
  EXPECT_EQ(f.pass, c.pass) << f.message;
  EXPECT_EQ(s.pass, c.pass) << s.message;
  EXPECT_EQ(a.pass, c.pass) << a.message;
  EXPECT_EQ(f.message, c.message);
  EXPECT_EQ(s.message, c.message);
  EXPECT_EQ(a.message, c.message);
  EXPECT_EQ(c.message.empty(), c.pass) << "a failure names its limits; a pass names none";
}

std::vector<std::string> pairs() {
  std::vector<std::string> out;
  for (const char* group : {"regressions", "benign"}) {
    for (const auto& e : fs::directory_iterator(kCorpus / group / "expected"))
      out.push_back(e.path().filename().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

INSTANTIATE_TEST_SUITE_P(Defaults, Corpus, ::testing::ValuesIn(pairs()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           std::string id = p.param;
                           for (char& ch : id)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return id;
                         });

// The corpus is what the test reads: seven regressions and four benign changes.
TEST(CorpusFiles, HoldEveryKindTheDefaultsAreMeasuredOn) {
  const std::vector<std::string> all = pairs();
  EXPECT_EQ(all.size(), 11u);
}

}  // namespace
