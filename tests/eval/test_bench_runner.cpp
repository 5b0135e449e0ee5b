#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "report/json.h"

using namespace slide;
namespace fs = std::filesystem;

namespace {
// A fresh folder DIR with DIR/bin/slide-bench-<name> linked to the fake suite for each name.
fs::path fakeSuites(const std::string& stem, std::initializer_list<const char*> names) {
  const fs::path dir = fs::temp_directory_path() / (stem + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "bin");
  const fs::path fake = fs::path(SLIDE_BINARY_DIR) / "tests" / "eval" / "fake_bench_suite";
  EXPECT_TRUE(fs::exists(fake)) << fake;
  for (const char* name : names) fs::create_symlink(fake, dir / "bin" / (std::string("slide-bench-") + name));
  return dir;
}
}  // namespace

// Runs ./slide bench on fake suites (one good, one failing, one writing broken JSON, one
// writing none, one absent) and checks the merged JSON and the Markdown report.
TEST(BenchRunner, ReportsEverySuiteAndContinuesAfterFailures) {
  const fs::path dir = fakeSuites("slide_bench_runner_", {"good", "failing", "badjson", "nojson"});

  const std::string cmd = "SLIDE_NO_BUILD=1 SLIDE_BUILD='" + std::string(SLIDE_BINARY_DIR) + "' SLIDE_BENCH_BIN='" +
                          (dir / "bin").string() + "' '" + SLIDE_SOURCE_DIR + "/slide' bench good failing absent badjson nojson --out '" +
                          (dir / "out").string() + "' --json '" + (dir / "all.json").string() + "' > '" +
                          (dir / "stdout.txt").string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 0) << "a failing or missing suite must fail the run";

  const report::Json doc = report::readJsonFile((dir / "all.json").string());
  const auto& suites = doc.at("suites");
  ASSERT_EQ(suites.size(), 5u);
  auto suite = [&](std::size_t i, const char* field) -> const report::Json& { return *suites[i].find(field); };
  EXPECT_EQ(suite(0, "suite").get<std::string>(), "good");
  EXPECT_EQ(suite(0, "status").get<std::string>(), "ok");
  ASSERT_EQ(suite(0, "results").size(), 2u);
  const report::Json& ate = suite(0, "results")[0];
  EXPECT_DOUBLE_EQ(ate.at("value").get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(ate.at("paper").get<double>(), 0.54);
  EXPECT_TRUE(ate.at("pass").get<bool>());
  EXPECT_FALSE(suite(0, "results")[1].at("pass").get<bool>());
  EXPECT_EQ(suite(1, "status").get<std::string>(), "failed");
  EXPECT_EQ(suite(1, "exit_code").get<double>(), 3);
  EXPECT_EQ(suite(1, "results").size(), 2u);  // figures of a failed suite are kept
  EXPECT_EQ(suite(2, "status").get<std::string>(), "missing");
  EXPECT_EQ(suite(3, "status").get<std::string>(), "no-results");
  EXPECT_NE(suite(3, "problem").get<std::string>().find("bad JSON"), std::string::npos);
  EXPECT_EQ(suite(4, "status").get<std::string>(), "no-results");
  EXPECT_GE(doc.at("total_wall_s").get<double>(), 0.0);
  EXPECT_EQ(doc.at("totals").at("targets_met").get<double>(), 2);

  std::ifstream md_in(dir / "all.md");
  ASSERT_TRUE(md_in) << "no Markdown report beside the JSON";
  std::stringstream md;
  md << md_in.rdbuf();
  EXPECT_NE(md.str().find("| failing | failed | 3 |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("| absent | missing |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("| good.ate_m | 0.5 | m | <= 1 | 0.54 | pass |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("| good.f1 | 0.7 |  | >= 0.8 | - | **FAIL** | 3 runs |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("total wall time"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "out" / "good.log"));
  fs::remove_all(dir);
}

// A named-only suite (place_scale) runs its program with its arguments, and a plain run (no suite
// named) leaves it out.
TEST(BenchRunner, NamedOnlySuiteRunsItsProgramWithArgumentsAndOnlyWhenNamed) {
  const fs::path dir = fakeSuites("slide_bench_named_", {"place"});
  auto run = [&](const std::string& suites, const std::string& tag) {
    const std::string cmd = "SLIDE_NO_BUILD=1 SLIDE_BUILD='" + std::string(SLIDE_BINARY_DIR) + "' SLIDE_BENCH_BIN='" +
                            (dir / "bin").string() + "' '" + SLIDE_SOURCE_DIR + "/slide' bench " + suites + " --out '" +
                            (dir / tag).string() + "' --json '" + (dir / (tag + ".json")).string() + "' > '" +
                            (dir / (tag + ".txt")).string() + "' 2>&1";
    return std::system(cmd.c_str());
  };
  const int named = run("place_scale", "named");
  ASSERT_TRUE(WIFEXITED(named));
  EXPECT_EQ(WEXITSTATUS(named), 0);
  const report::Json doc = report::readJsonFile((dir / "named.json").string());
  ASSERT_EQ(doc.at("suites").size(), 1u);
  EXPECT_EQ(doc.at("suites")[0].at("suite").get<std::string>(), "place_scale");
  EXPECT_EQ(doc.at("suites")[0].at("status").get<std::string>(), "ok");
  std::ifstream out_in(dir / "named.txt");
  std::stringstream out;
  out << out_in.rdbuf();
  EXPECT_NE(out.str().find("slide-bench-place --only scale --json"), std::string::npos) << out.str();

  run("", "plain");  // every other known suite is missing here: the run fails, place runs
  const report::Json all = report::readJsonFile((dir / "plain.json").string());
  bool place = false;
  for (const report::Json& s : all.at("suites")) {
    EXPECT_NE(s.at("suite").get<std::string>(), "place_scale");
    place |= s.at("suite").get<std::string>() == "place";
  }
  EXPECT_TRUE(place);
  fs::remove_all(dir);
}

// A named suite of several parts (team_scale: the team bench at 3, 5 and 10 robots) runs each
// part with its arguments and keeps every part's figures, named after the part's label.
TEST(BenchRunner, NamedSuiteOfSeveralPartsKeepsEachPartsFiguresUnderItsLabel) {
  const fs::path dir = fakeSuites("slide_bench_parts_", {"team"});
  const std::string cmd = "SLIDE_NO_BUILD=1 SLIDE_BUILD='" + std::string(SLIDE_BINARY_DIR) + "' SLIDE_BENCH_BIN='" +
                          (dir / "bin").string() + "' '" + SLIDE_SOURCE_DIR + "/slide' bench team_scale --out '" +
                          (dir / "out").string() + "' --json '" + (dir / "all.json").string() + "' > '" +
                          (dir / "out.txt").string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const report::Json doc = report::readJsonFile((dir / "all.json").string());
  ASSERT_EQ(doc.at("suites").size(), 1u);
  const report::Json& suite = doc.at("suites")[0];
  EXPECT_EQ(suite.at("suite").get<std::string>(), "team_scale");
  EXPECT_EQ(suite.at("status").get<std::string>(), "ok");
  std::vector<std::string> names;
  for (const report::Json& r : suite.at("results")) names.push_back(r.at("name").get<std::string>());
  EXPECT_EQ(names, (std::vector<std::string>{"robots3.team.ate_m", "robots3.team.f1", "robots5.team.ate_m",
                                             "robots5.team.f1", "robots10.team.ate_m", "robots10.team.f1"}));
  std::ifstream out_in(dir / "out.txt");
  std::stringstream out;
  out << out_in.rdbuf();
  for (const char* robots : {"3", "5", "10"})
    EXPECT_NE(out.str().find(std::string("slide-bench-team --robots ") + robots + " --json"),
              std::string::npos)
        << out.str();
  fs::remove_all(dir);
}
