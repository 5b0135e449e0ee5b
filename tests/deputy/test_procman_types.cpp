// Our lcmtypes/procman_lcm must have procman's fingerprints: lcm-gen runs on the reference
// definitions (fixtures/procman_lcm, from ashuang/procman) and the fingerprints it implies
// are compared with getHash() of the compiled types.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "procman_lcm/cmd_desired_t.hpp"
#include "procman_lcm/cmd_status_t.hpp"
#include "procman_lcm/cmd_t.hpp"
#include "procman_lcm/deputy_info_t.hpp"
#include "procman_lcm/discovery_t.hpp"
#include "procman_lcm/orders_t.hpp"
#include "procman_lcm/output_t.hpp"

namespace fs = std::filesystem;

namespace {

struct TypeHash {
  uint64_t base = 0;
  std::vector<std::string> members;  // nested procman_lcm types, in order
};

// Runs lcm-gen on the .lcm files of dir and reads each type's base hash and nested types.
std::map<std::string, TypeHash> generate(const fs::path& dir, const fs::path& out) {
  fs::remove_all(out);
  fs::create_directories(out);
  const std::string cmd = std::string(LCM_GEN_PATH) + " --cpp --cpp-hpath " + out.string() + " " + dir.string() + "/*.lcm";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::map<std::string, TypeHash> types;
  for (const auto& f : fs::directory_iterator(out / "procman_lcm")) {
    std::ifstream in(f.path());
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    std::smatch m;
    static const std::regex hash_re(R"(uint64_t hash = 0x([0-9a-f]+)LL([^;]*);)");
    if (!std::regex_search(text, m, hash_re)) continue;
    TypeHash t;
    t.base = std::stoull(m[1].str(), nullptr, 16);
    const std::string rest = m[2].str();
    static const std::regex member_re(R"(procman_lcm::(\w+)::_computeHash)");
    for (auto it = std::sregex_iterator(rest.begin(), rest.end(), member_re); it != std::sregex_iterator(); ++it)
      t.members.push_back((*it)[1].str());
    types[f.path().stem().string()] = t;
  }
  return types;
}

uint64_t fingerprint(const std::map<std::string, TypeHash>& types, const std::string& name) {
  const TypeHash& t = types.at(name);
  uint64_t h = t.base;
  for (const std::string& m : t.members) h += fingerprint(types, m);
  return (h << 1) + ((h >> 63) & 1);
}

// A per-process scratch folder (tests of several build trees may run at once).
fs::path scratch(const std::string& name) {
  return fs::temp_directory_path() / ("slide_procman_" + name + "_" + std::to_string(getpid()));
}

const fs::path kFixtures = fs::path(SLIDE_SOURCE_DIR) / "tests/deputy/fixtures/procman_lcm";

}  // namespace

TEST(ProcmanTypes, FingerprintsMatchProcman) {
  const auto ref = generate(kFixtures, scratch("ref"));
  fs::remove_all(scratch("ref"));
  ASSERT_EQ(ref.size(), 7u);
  EXPECT_EQ(fingerprint(ref, "cmd_t"), uint64_t(procman_lcm::cmd_t::getHash()));
  EXPECT_EQ(fingerprint(ref, "cmd_desired_t"), uint64_t(procman_lcm::cmd_desired_t::getHash()));
  EXPECT_EQ(fingerprint(ref, "cmd_status_t"), uint64_t(procman_lcm::cmd_status_t::getHash()));
  EXPECT_EQ(fingerprint(ref, "deputy_info_t"), uint64_t(procman_lcm::deputy_info_t::getHash()));
  EXPECT_EQ(fingerprint(ref, "orders_t"), uint64_t(procman_lcm::orders_t::getHash()));
  EXPECT_EQ(fingerprint(ref, "output_t"), uint64_t(procman_lcm::output_t::getHash()));
  EXPECT_EQ(fingerprint(ref, "discovery_t"), uint64_t(procman_lcm::discovery_t::getHash()));
}

TEST(ProcmanTypes, FingerprintsEqualProcmansOwn) {
  // getHash() of the C++ types lcm-gen makes from procman's definitions (fixtures/README.md).
  EXPECT_EQ(uint64_t(procman_lcm::cmd_t::getHash()), 0x2277f449a855d330ULL);
  EXPECT_EQ(uint64_t(procman_lcm::cmd_desired_t::getHash()), 0xb2a6c7a09ba54539ULL);
  EXPECT_EQ(uint64_t(procman_lcm::cmd_status_t::getHash()), 0xa8e0208786cf86e3ULL);
  EXPECT_EQ(uint64_t(procman_lcm::deputy_info_t::getHash()), 0x8876aeb040efd01fULL);
  EXPECT_EQ(uint64_t(procman_lcm::orders_t::getHash()), 0xd343f45b171ab855ULL);
  EXPECT_EQ(uint64_t(procman_lcm::output_t::getHash()), 0x8efa5caf5da01eb3ULL);
  EXPECT_EQ(uint64_t(procman_lcm::discovery_t::getHash()), 0xb1c83182bed74b95ULL);
}

TEST(ProcmanTypes, ALayoutChangeChangesTheFingerprint) {
  // Guards the comparison above: one renamed field must show.
  const fs::path dir = scratch("changed");
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(kFixtures, dir, fs::copy_options::overwrite_existing | fs::copy_options::recursive);
  std::ifstream in(dir / "cmd_t.lcm");
  std::stringstream ss;
  ss << in.rdbuf();
  in.close();
  std::string text = ss.str();
  text.replace(text.find("exec_str"), 8, "exec_cmd");
  std::ofstream(dir / "cmd_t.lcm") << text;
  const auto changed = generate(dir, scratch("changed_out"));
  fs::remove_all(dir);
  fs::remove_all(scratch("changed_out"));
  EXPECT_NE(fingerprint(changed, "cmd_t"), uint64_t(procman_lcm::cmd_t::getHash()));
  EXPECT_NE(fingerprint(changed, "orders_t"), uint64_t(procman_lcm::orders_t::getHash()));
}
