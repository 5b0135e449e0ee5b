// slide-bench-team: traffic and robustness of the peer-sync protocol on simulated 3-robot
// forest and urban runs (the protocol engine of slide-peer-sync over an in-process network).
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <set>

#include "app/app.h"
#include "app/channels.h"
#include "bench/report.h"
#include "team/sim_network.h"
#include "backend_map.h"
#include "team_scenario.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::bench;

namespace {

constexpr Micros kSecond = 1000000;

struct Traffic {
  double bundle = 0, map = 0, heartbeat = 0, ack = 0;
  std::size_t heartbeats = 0, acks = 0;  // messages
};

struct RunResult {
  double bytes = 0;
  std::size_t bundle_chunks = 0, payload = 0;
  Traffic traffic;
  std::vector<std::vector<KeyPoseBundle>> delivered;  // per robot, in delivery order
  double converge_s = 0;
  bool converged = false;
  std::uint64_t drops_total = 0;
};

struct LinkPlan {
  double loss = 0, duplicate = 0, jitter_s = 0;
  bool cuts = false;      // every link down half the time
  bool restarts = false;  // every daemon killed and restarted once
};

std::vector<SyncConfig> configsFor(const TeamScenario& sc) {
  std::vector<std::int32_t> ids;
  for (const auto& r : sc.robots) ids.push_back(r.robot);
  std::vector<SyncConfig> out;
  for (auto id : ids) {
    SyncConfig c;  // the defaults of config/peer_sync.yaml
    c.robot = id;
    c.team = ids;
    c.pair_keys = derivePairKeys("bench-team-key", id, ids);
    out.push_back(c);
  }
  return out;
}

RunResult run(const TeamScenario& sc, const LinkPlan& plan, const std::string& state_root, std::uint64_t seed) {
  SimLinkModel link;
  link.loss = plan.loss;
  link.duplicate = plan.duplicate;
  link.jitter_s = plan.jitter_s;
  bool healed = false;
  if (plan.cuts)
    link.link_up = [&healed](std::int32_t a, std::int32_t b, Micros t) {
      if (healed) return true;
      const Micros period = 20 * kSecond, phase = ((a + b) * 7 % 20) * kSecond;
      return (t + phase) % period < period / 2;
    };
  SimNetwork net(configsFor(sc), state_root, link, seed);
  RunResult res;
  net.on_send = [&](std::size_t, const TeamMessage& m) {
    if (auto* c = std::get_if<Chunk>(&m)) {
      const double b = static_cast<double>(lcmWireBytes(app::channels::kTeamChunk, encodedSize(*c)));
      (c->kind == ChunkKind::Bundle ? res.traffic.bundle : res.traffic.map) += b;
      if (c->kind == ChunkKind::Bundle) ++res.bundle_chunks;
      if (c->kind == ChunkKind::Bundle) res.payload += c->data.size();
    } else if (auto* h = std::get_if<Heartbeat>(&m)) {
      res.traffic.heartbeat += static_cast<double>(lcmWireBytes(app::channels::kTeamHeartbeat, encodedSize(*h)));
      ++res.traffic.heartbeats;
    } else {
      res.traffic.ack += static_cast<double>(lcmWireBytes(app::channels::kTeamAck, encodedSize(std::get<Ack>(m))));
      ++res.traffic.acks;
    }
  };
  const std::size_t n = sc.robots.size(), keyposes = sc.robots[0].bundles.size();
  for (std::size_t k = 0; k < keyposes; ++k) {
    for (std::size_t r = 0; r < n; ++r) {
      if (auto drop = net.node(r).addOwnBundle(sc.robots[r].bundles[k], net.now()))
        throw std::runtime_error(std::string("own bundle refused: ") + dropName(*drop));
      net.node(r).setOwnMap(sc.robots[r].maps[k], net.now());
    }
    net.run(kSecond);  // one key pose per second (1.4 m/s)
    if (plan.restarts && k % (keyposes / (n + 1)) == keyposes / (n + 1) - 1) {
      const std::size_t victim = (k / (keyposes / (n + 1))) % n;
      net.restart(victim);
    }
  }
  healed = true;
  const std::size_t expect = (n - 1) * keyposes;
  const Micros t0 = net.now();
  for (int s = 0; s < 600; ++s) {
    bool done = true;
    for (std::size_t r = 0; r < n; ++r) done = done && net.deliveredBundles(r).size() >= expect;
    if (done) {
      res.converged = true;
      break;
    }
    net.run(kSecond / 10);
  }
  res.converge_s = 1e-6 * static_cast<double>(net.now() - t0);
  res.bytes = net.bytesSent();
  for (std::size_t r = 0; r < n; ++r) {
    res.delivered.push_back(net.deliveredBundles(r));
    for (auto c : net.node(r).drops()) res.drops_total += c;
  }
  return res;
}

// Object positions in each origin's odometry frame, composed from the delivered bundles by
// chaining relative odometry: keyed (robot, origin, seq, object index).
std::map<std::tuple<int, int, int, int>, Eigen::Vector3d> composedMap(const RunResult& r) {
  std::map<std::tuple<int, int, int, int>, Eigen::Vector3d> out;
  for (std::size_t robot = 0; robot < r.delivered.size(); ++robot) {
    std::map<int, Pose> pose;
    for (const KeyPoseBundle& b : r.delivered[robot]) {
      auto it = pose.find(b.robot);
      const Pose T = it == pose.end() ? b.odom_pose : it->second * b.relative_odom;
      pose[b.robot] = T;
      for (std::size_t i = 0; i < b.objects.size(); ++i)
        out[{static_cast<int>(robot), b.robot, b.seq, static_cast<int>(i)}] = T * b.objects[i].position();
    }
  }
  return out;
}

// What robot 0's back-end is fed, in one order for every run: per key pose its own bundle,
// then each peer's bundle of that sequence number as delivered (thinned, quantised).
std::vector<Arrival> feedOfFirstRobot(const TeamScenario& sc, const RunResult& r) {
  std::map<std::pair<int, int>, const KeyPoseBundle*> got;
  for (const KeyPoseBundle& b : r.delivered[0]) got[{b.robot, b.seq}] = &b;
  std::vector<Arrival> out;
  for (std::size_t k = 0; k < sc.robots[0].bundles.size(); ++k) {
    Arrival a;
    a.bundles.push_back(sc.robots[0].bundles[k]);
    for (std::size_t p = 1; p < sc.robots.size(); ++p) {
      auto it = got.find({sc.robots[p].robot, static_cast<int>(k)});
      if (it != got.end()) a.bundles.push_back(*it->second);
    }
    out.push_back(std::move(a));
  }
  return out;
}

void addTraffic(slide::bench::BenchReport& rep, const std::string& p, const TeamScenario& sc, const RunResult& r) {
  double metres = 0;
  std::size_t keyposes = 0;
  for (const auto& rs : sc.robots) {
    metres += rs.metres;
    keyposes += rs.bundles.size();
  }
  rep.add(p + ".bytes_per_landmark", r.bytes / static_cast<double>(sc.landmarks_seen), "bytes", true, 200.0, 1800.0)
      .note = "total team bytes / landmarks seen by the team (paper 1.8-4.0 KB)";
  rep.add(p + ".bytes_per_metre", r.bytes / metres, "bytes", true, 500.0, 1650.0).note =
      "total team bytes / metres travelled by all robots (paper 1.65-5.13 KB)";
  rep.add(p + ".bytes_per_keypose", r.bytes / static_cast<double>(keyposes), "bytes");
  rep.add(p + ".bundle_chunks_per_bundle", static_cast<double>(r.bundle_chunks) / keyposes, "");
  rep.add(p + ".bundle_payload_mean", static_cast<double>(r.payload) / r.bundle_chunks, "bytes");
  // What went on the bus per landmark: observations left after thinning, and their cost.
  std::map<std::pair<int, int>, std::size_t> shared;  // (origin, seq) -> objects as delivered
  for (const auto& robot : r.delivered)
    for (const KeyPoseBundle& b : robot) shared[{b.robot, b.seq}] = b.objects.size();
  std::size_t observations = 0, observed = 0;
  for (const auto& [key, n] : shared) observations += n;
  for (const auto& rs : sc.robots)
    for (const KeyPoseBundle& b : rs.bundles) observed += b.objects.size();
  const double landmarks = static_cast<double>(sc.landmarks_seen);
  rep.add(p + ".observations_per_landmark", static_cast<double>(observed) / landmarks, "").note =
      "observations made by the team per landmark";
  rep.add(p + ".shared_observations_per_landmark", static_cast<double>(observations) / landmarks, "").note =
      "observations put on the team bus per landmark (after thinning)";
  rep.add(p + ".payload_bytes_per_shared_observation",
          static_cast<double>(r.payload) / static_cast<double>(std::max<std::size_t>(1, observations)), "bytes")
      .note = "bundle payload bytes (key-pose headers included) per shared observation";
  rep.add(p + ".share.bundles", r.traffic.bundle / r.bytes, "", true);
  rep.add(p + ".share.maps", r.traffic.map / r.bytes, "", true);
  rep.add(p + ".share.heartbeats", r.traffic.heartbeat / r.bytes, "", true);
  rep.add(p + ".share.acks", r.traffic.ack / r.bytes, "", true);
  rep.add(p + ".heartbeat_bytes_mean",
          r.traffic.heartbeat / static_cast<double>(std::max<std::size_t>(1, r.traffic.heartbeats)), "bytes", true)
      .note = "wire bytes of one heartbeat (" + std::to_string(sc.robots.size()) + " robots)";
  rep.add(p + ".ack_bytes_mean", r.traffic.ack / static_cast<double>(std::max<std::size_t>(1, r.traffic.acks)), "bytes",
          true);
  rep.add(p + ".landmarks", static_cast<double>(sc.landmarks_seen), "", false);
  rep.add(p + ".metres", metres, "m", false);
  rep.add(p + ".objects_per_keypose", sc.mean_objects_per_keypose, "", false);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Team benchmark: bytes per landmark and per metre of the peer-sync protocol on simulated forest and "
               "urban team runs (3 robots unless --robots), and delivery under 30% loss with links down half the time"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  std::string json;
  int keyposes = 200;
  std::uint64_t seed = 1;
  int robots = 3;
  app.add_option("--json", json, "Write the results as JSON to this file");
  app.add_option("--robots", robots, "Robots in the team")->capture_default_str()->check(CLI::Range(2, 16));
  app.add_option("--keyposes", keyposes, "Key poses per robot (1.4 m apart)")->capture_default_str()->check(CLI::Range(10, 100000));
  app.add_option("--seed", seed, "Random seed")->capture_default_str();
  return app::runApp(app, common, argc, argv, [&]() {
    slide::bench::BenchReport rep("team");
    for (const std::string kind : {"forest", "urban"}) {
      const TeamScenario sc = makeScenario(kind, robots, keyposes, seed);
      spdlog::info("{}: {} landmarks seen, {:.1f} objects per key pose", kind, sc.landmarks_seen, sc.mean_objects_per_keypose);
      const RunResult r = run(sc, LinkPlan{}, "", seed);
      if (!r.converged) spdlog::warn("{}: lossless run did not deliver everything", kind);
      addTraffic(rep, kind, sc, r);
    }
    // Lossy: 30% loss, duplicates, reordering, every link down half the time, every daemon
    // restarted once; compared with the lossless run of the same streams.
    const TeamScenario sc = makeScenario("forest", robots, keyposes, seed + 1);
    const RunResult clean = run(sc, LinkPlan{}, "", seed);
    const std::string root = (std::filesystem::temp_directory_path() / ("slide_bench_team_" + std::to_string(::getpid()))).string();
    std::filesystem::remove_all(root);
    LinkPlan lossy;
    lossy.loss = 0.3;
    lossy.duplicate = 0.05;
    lossy.jitter_s = 0.2;
    lossy.cuts = true;
    lossy.restarts = true;
    const RunResult bad = run(sc, lossy, root, seed + 7);
    std::filesystem::remove_all(root);
    std::size_t expected = 0, unique = 0, duplicates = 0;
    for (std::size_t r = 0; r < bad.delivered.size(); ++r) {
      expected += (sc.robots.size() - 1) * sc.robots[0].bundles.size();
      std::set<std::pair<int, int>> seen;
      for (const auto& b : bad.delivered[r]) (seen.insert({b.robot, b.seq}).second ? unique : duplicates) += 1;
    }
    const auto want = composedMap(clean), got = composedMap(bad);
    double diff = 0;
    for (const auto& [key, p] : want) {
      auto it = got.find(key);
      diff = std::max(diff, it == got.end() ? std::numeric_limits<double>::infinity() : (it->second - p).norm());
    }
    if (got.size() != want.size()) diff = std::numeric_limits<double>::infinity();
    rep.add("lossy.delivered_fraction", static_cast<double>(unique) / static_cast<double>(expected), "", false, 1.0);
    rep.add("lossy.duplicates", static_cast<double>(duplicates), "", true, 0.0);
    rep.add("lossy.map_diff_m", diff, "m", true, 1e-6).note =
        "max distance between object positions composed from delivered bundles (odometry chain per origin), "
        "lossy vs lossless run";
    // The back-end's map at robot 0 from what each run delivered, fed in the same order.
    const backend::BackendConfig backend =
        backend::loadBackendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml");
    std::map<std::int32_t, Pose> transforms;
    for (std::size_t r = 1; r < sc.robots.size(); ++r)
      transforms[sc.robots[r].robot] = sc.robots[0].start.inverse() * sc.robots[r].start;
    const auto map_clean = backendMap(backend, sc.robots[0].robot, transforms, feedOfFirstRobot(sc, clean));
    const auto map_lossy = backendMap(backend, sc.robots[0].robot, transforms, feedOfFirstRobot(sc, bad));
    const auto map_again = backendMap(backend, sc.robots[0].robot, transforms, feedOfFirstRobot(sc, clean));
    const MapComparison cmp = compareMaps(map_clean, map_lossy, 1.0);
    rep.add("lossy.backend_map_diff_m", cmp.max_paired_m, "m", true, 1e-4).note =
        "robot 0's back-end map (own bundles + delivered peers', full solve), lossy vs lossless: largest distance "
        "between paired landmarks (nearest of the same class within 1 m)";
    rep.add("lossy.backend_self_diff_m", compareMaps(map_clean, map_again, 1.0).max_paired_m, "m", true).note =
        "the same, lossless vs the lossless feed solved again: the back-end's own run-to-run spread";
    rep.add("lossy.backend_unpaired", static_cast<double>(cmp.unpaired), "", true, 0.0).note =
        "landmarks of either map without a partner within 1 m";
    rep.add("lossy.backend_landmarks", static_cast<double>(map_lossy.size()), "", false).note =
        "landmarks in that map (lossless: " + std::to_string(map_clean.size()) + ")";
    double metres = 0;
    for (const auto& rs : sc.robots) metres += rs.metres;
    rep.add("lossy.bytes_per_metre", bad.bytes / metres, "bytes", true).note = "30% loss, links down half the time";
    rep.add("lossy.clean_bytes_per_metre", clean.bytes / metres, "bytes", true);
    std::size_t keyposes_total = 0;
    for (const auto& rs : sc.robots) keyposes_total += rs.bundles.size();
    rep.add("lossy.bundle_sends_per_bundle", static_cast<double>(bad.bundle_chunks) / keyposes_total, "", true)
        .note = "bundle chunks put on the medium per bundle (a chunk packs the bundles of up to bundle_hold_s)";
    rep.add("lossy.share.bundles", bad.traffic.bundle / bad.bytes, "", true);
    rep.add("lossy.share.heartbeats", bad.traffic.heartbeat / bad.bytes, "", true);
    rep.add("lossy.share.acks", bad.traffic.ack / bad.bytes, "", true);
    rep.add("lossy.share.maps", bad.traffic.map / bad.bytes, "", true);
    rep.add("lossy.converge_s", bad.converge_s, "s", true).note = "after links heal at the end of the run";
    rep.add("lossy.drops_counted", static_cast<double>(bad.drops_total), "", true).note =
        "duplicates and replays caught by the receivers (normal under duplication and resends)";
    rep.printTable(std::cout);
    if (!json.empty()) rep.writeJson(json);
    return 0;
  });
}
