#include "simulator/forest_world.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "io/io_error.h"
#include "simulator/route_lattice.h"

namespace slide::simulator {

namespace {
struct Stem {
  Eigen::Vector2d xy;
  double dbh;     // metres
  double height;  // metres, 0 when unknown
};

// Reads a forest_inventory CSV (header line, then x,y,diameter[,height]); diameters in cm
// for longleaf/finpines and in m for spruces.
std::vector<Stem> readInventory(const std::string& path, double diameter_scale) {
  std::ifstream in(path);
  if (!in) throw io::IoError(path, "cannot open file");
  std::string line;
  std::getline(in, line);
  std::vector<Stem> stems;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    Stem st{};
    if (!(s >> st.xy.x() >> st.xy.y() >> st.dbh))
      throw io::IoError(path, "line " + std::to_string(n) + ": expected x,y,diameter");
    if (!(s >> st.height)) st.height = 0;
    st.dbh *= diameter_scale;
    stems.push_back(st);
  }
  if (stems.empty()) throw io::IoError(path, "no trees");
  return stems;
}

std::vector<Stem> realLayout(const ForestParams& p, std::mt19937_64& rng) {
  const std::string dir = p.inventory_dir.empty() ? std::string(SLIDE_DATA_DIR) + "/forest_inventory" : p.inventory_dir;
  double scale = 0.01;
  if (p.layout == "spruces") scale = 1.0;
  else if (p.layout != "longleaf" && p.layout != "finpines")
    throw std::invalid_argument("unknown forest layout '" + p.layout + "' (procedural, longleaf, finpines, spruces)");
  std::vector<Stem> plot = readInventory(dir + "/" + p.layout + ".csv", scale);
  Eigen::AlignedBox2d box;
  for (const Stem& s : plot) box.extend(s.xy);
  const Eigen::Vector2d size = box.sizes().cwiseMax(Eigen::Vector2d(1, 1));
  // Tile the plot over the world, mirroring alternate tiles so seams stay plausible.
  std::vector<Stem> out;
  const int tx = static_cast<int>(std::ceil(p.side / size.x())), ty = static_cast<int>(std::ceil(p.side / size.y()));
  std::normal_distribution<double> jitter(0, 0.05);
  for (int i = 0; i < tx; ++i)
    for (int j = 0; j < ty; ++j)
      for (Stem s : plot) {
        Eigen::Vector2d l = s.xy - box.min();
        if (i % 2) l.x() = size.x() - l.x();
        if (j % 2) l.y() = size.y() - l.y();
        s.xy = Eigen::Vector2d(i * size.x(), j * size.y()) + l - Eigen::Vector2d::Constant(p.side / 2);
        s.xy += Eigen::Vector2d(jitter(rng), jitter(rng));
        if (std::abs(s.xy.x()) <= p.side / 2 && std::abs(s.xy.y()) <= p.side / 2) out.push_back(s);
      }
  return out;
}

std::vector<Stem> proceduralLayout(const ForestParams& p, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-p.side / 2, p.side / 2);
  std::normal_distribution<double> n01(0, 1);
  const int clustered = static_cast<int>(p.num_trees * p.cluster_fraction);
  const int num_clusters = std::max(1, clustered / 12);
  std::vector<Eigen::Vector2d> centres;
  for (int i = 0; i < num_clusters; ++i) centres.emplace_back(u(rng), u(rng));
  std::vector<Stem> out;
  std::uniform_int_distribution<int> pick(0, num_clusters - 1);
  int guard = 0;
  while (static_cast<int>(out.size()) < p.num_trees && guard++ < 100 * p.num_trees) {
    Eigen::Vector2d xy;
    if (static_cast<int>(out.size()) < clustered)
      xy = centres[pick(rng)] + p.cluster_sigma * Eigen::Vector2d(n01(rng), n01(rng));
    else
      xy = {u(rng), u(rng)};
    if (std::abs(xy.x()) > p.side / 2 || std::abs(xy.y()) > p.side / 2) continue;
    const double dbh = std::max(0.08, p.dbh_mean + p.dbh_sd * n01(rng));
    bool clash = false;  // stems may not overlap
    for (const Stem& s : out)
      if ((s.xy - xy).squaredNorm() < std::pow(0.5 * (s.dbh + dbh) + 0.3, 2)) {
        clash = true;
        break;
      }
    if (!clash) out.push_back({xy, dbh, 0});
  }
  return out;
}
}  // namespace

World makeForestWorld(const ForestParams& p, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  World w;
  w.name = "forest";
  w.terrain = unevenTerrain(p.terrain_amplitude, seed ^ 0x9e3779b97f4a7c15ULL, label::kTerrain);
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(0.5 * p.side + 130);
  w.terrain.bake(Eigen::AlignedBox2d(-margin, margin), 1.0);
  const std::vector<Stem> stems = p.layout == "procedural" ? proceduralLayout(p, rng) : realLayout(p, rng);
  for (const Stem& s : stems) {
    const double radius = std::max(0.04, 0.5 * s.dbh);
    const double height = s.height > 2 ? s.height : 10 + 12 * u(rng) + 10 * radius;
    const double lean = p.max_lean_deg * M_PI / 180 * u(rng) * u(rng);
    const double lean_dir = 2 * M_PI * u(rng);
    const Eigen::Vector3d axis(std::sin(lean) * std::cos(lean_dir), std::sin(lean) * std::sin(lean_dir), std::cos(lean));
    const Eigen::Vector3d root(s.xy.x(), s.xy.y(), w.terrain.height(s.xy.x(), s.xy.y()) - 0.3);
    const double crown_base = height * (0.45 + 0.2 * u(rng));
    io::GroundTruthObject g;
    g.object.class_id = 71;
    g.semantic = label::kTrunk;
    g.object.model = Cylinder{root, axis, radius, p.crowns ? crown_base + 1.0 : height};
    w.objects.push_back(g);
    if (p.crowns) {
      const double crown_h = height - crown_base;
      const double crown_r = std::min(4.0, 1.2 + 0.15 * crown_h + 2 * radius) * (0.8 + 0.4 * u(rng));
      const Eigen::Vector3d c = root + (crown_base + 0.5 * crown_h) / axis.z() * axis;
      w.structures.push_back({Ellipsoid{c, crown_r, crown_h}, label::kVegetation});
    }
  }
  std::uniform_real_distribution<double> ux(-p.side / 2, p.side / 2);
  for (int i = 0; i < p.bushes; ++i) {
    const double x = ux(rng), y = ux(rng);
    const double r = 0.4 + 0.8 * u(rng), h = 0.6 + 0.9 * u(rng);
    w.structures.push_back({Ellipsoid{{x, y, w.terrain.height(x, y) + 0.3 * h}, r, h}, label::kVegetation});
  }
  w.bounds = Eigen::AlignedBox2d(Eigen::Vector2d::Constant(-p.side / 2), Eigen::Vector2d::Constant(p.side / 2));
  w.routes = routeLattice(w.bounds, p.route_spacing, 0.2 * p.route_spacing, rng);
  w.renumber();
  return w;
}

}  // namespace slide::simulator
