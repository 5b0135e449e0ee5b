// slide-team-keys: makes the team's key files, one per robot, holding a key for each pair of
// robots (team_keys.h). Give each robot its own file only.
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "app/app.h"
#include "team/team_keys.h"

using namespace slide;
using namespace slide::team;

int main(int argc, char** argv) {
  CLI::App app{"Makes one team key file per robot (<out>/robot<id>.keys, mode 0600) with a fresh random key for "
               "each pair of robots, or keys derived from a master secret file (--master-file) kept off the robots."};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  std::vector<std::int32_t> team;
  std::string out, master_file;
  app.add_option("--team", team, "Robot ids of the team, e.g. 0,1,2")->required()->delimiter(',');
  app.add_option("--out", out, "Folder for the key files")->required();
  app.add_option("--master-file", master_file, "Derive the pair keys from this secret file instead of at random");
  return app::runApp(app, common, argc, argv, [&]() {
    for (std::int32_t id : team)
      if (id < 0 || id > 32767) throw std::runtime_error("robot id " + std::to_string(id) + " outside 0..32767");
    std::string master;
    if (!master_file.empty()) {
      std::ifstream in(master_file, std::ios::binary);
      if (!in) throw std::runtime_error("cannot read master secret file " + master_file);
      master.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      if (master.size() < 16) throw std::runtime_error("master secret file " + master_file + " holds under 16 bytes");
    }
    std::map<std::pair<std::int32_t, std::int32_t>, std::string> pair;
    for (std::int32_t a : team)
      for (std::int32_t b : team)
        if (a < b) pair[{a, b}] = master.empty() ? randomPairKey() : derivePairKey(master, a, b);
    std::filesystem::create_directories(out);
    for (std::int32_t id : team) {
      PairKeys keys;
      for (std::int32_t peer : team)
        if (peer != id) keys[peer] = pair.at({std::min(id, peer), std::max(id, peer)});
      const std::string path = out + "/robot" + std::to_string(id) + ".keys";
      writeTeamKeys(path, id, keys);
      spdlog::info("wrote {} ({} pair keys)", path, keys.size());
    }
    return 0;
  });
}
