// slide-bench-kdtree: the project's static k-d tree (lib/geometry/kdtree.h) against nanoflann
// (Debian libnanoflann-dev) on the sizes the system queries: object maps of real stem layouts
// (584 longleaf pines, tiled up to ~9,300 objects) and a real terrestrial laser scan (114,024
// points). Same points, same queries; results are checked to agree before any time counts.
// Times are CPU medians over repeated runs in this process. This decides which tree lib/ uses.
#include <nanoflann.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "app/app.h"
#include "bench/report.h"
#include "bench/stats.h"
#include "geometry/kdtree.h"

namespace {

using Point = Eigen::Vector3d;

double cpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * ts.tv_sec + 1e-6 * ts.tv_nsec;
}

std::vector<Point> readStems(const std::string& path) {  // x,y,... CSV with a header line
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<Point> out;
  std::string line;
  std::getline(in, line);
  for (int n = 2; std::getline(in, line); ++n) {
    double x, y;
    char comma;
    std::istringstream s(line);
    if (!(s >> x >> comma >> y)) throw std::runtime_error(path + ":" + std::to_string(n) + ": expected x,y");
    out.emplace_back(x, y, 0.0);
  }
  return out;
}

std::vector<Point> readXyz(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<Point> out;
  double x, y, z;
  while (in >> x >> y >> z) out.emplace_back(x, y, z);
  if (out.empty()) throw std::runtime_error(path + ": no points");
  return out;
}

struct Cloud {  // nanoflann's dataset adaptor over the same vector
  const std::vector<Point>& pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return pts[i][d]; }
  template <class B>
  bool kdtree_get_bbox(B&) const { return false; }
};
using Nano = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3, std::size_t>;

struct Case {
  std::string name;
  std::vector<Point> points;
  double radius;  // the radius the system queries at this scale
};

struct Times {
  double build = 0, radius = 0, knn = 0;
};

Times timeOurs(const Case& c, const std::vector<Point>& queries, int repeats, std::size_t& checksum) {
  std::vector<double> b, r, k;
  for (int i = 0; i < repeats; ++i) {
    double t = cpuMs();
    const slide::KdTree<3> tree(c.points);
    b.push_back(cpuMs() - t);
    t = cpuMs();
    std::size_t n = 0;
    for (const Point& q : queries) n += tree.radius(q, c.radius).size();
    r.push_back(cpuMs() - t);
    t = cpuMs();
    for (const Point& q : queries) n += tree.nearest(q, 8).front().first;
    k.push_back(cpuMs() - t);
    checksum = n;
  }
  return {slide::median(b), slide::median(r), slide::median(k)};
}

Times timeNano(const Case& c, const std::vector<Point>& queries, int repeats, std::size_t& checksum) {
  std::vector<double> b, r, k;
  const Cloud cloud{c.points};
  for (int i = 0; i < repeats; ++i) {
    double t = cpuMs();
    const Nano tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));  // builds the index
    b.push_back(cpuMs() - t);
    t = cpuMs();
    std::size_t n = 0;
    std::vector<std::pair<std::size_t, double>> hits;
    nanoflann::SearchParams params;
    params.sorted = false;
    for (const Point& q : queries) n += tree.radiusSearch(q.data(), c.radius * c.radius, hits, params);
    r.push_back(cpuMs() - t);
    t = cpuMs();
    std::size_t idx[8];
    double d2[8];
    for (const Point& q : queries) {
      tree.knnSearch(q.data(), 8, idx, d2);
      n += idx[0];
    }
    k.push_back(cpuMs() - t);
    checksum = n;
  }
  return {slide::median(b), slide::median(r), slide::median(k)};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"k-d tree benchmark (suite 'kdtree'): the project's tree against nanoflann", "slide-bench-kdtree"};
  slide::CommonOptions common;
  slide::addCommonOptions(app, common);
  std::string json, data = SLIDE_DATA_DIR;
  int repeats = 7;
  app.add_option("--json", json, "Write the results as JSON to FILE");
  app.add_option("--data", data, "Real data folder")->capture_default_str();
  app.add_option("--repeats", repeats, "Runs per timing (medians)")->capture_default_str()->check(CLI::Range(1, 1000));
  return slide::runApp(app, common, argc, argv, [&]() {
    slide::BenchReport report("kdtree");
    const std::vector<Point> stems = readStems(data + "/forest_inventory/longleaf.csv");
    std::vector<Point> tiled;  // 4x4 tiles of the 200 m plot: a long mission's object map
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (const Point& p : stems) tiled.push_back(p + Point(200.0 * i, 200.0 * j, 0));
    const std::vector<Case> cases = {{"map584", stems, 10.0},
                                     {"map9344", tiled, 10.0},
                                     {"scan114k", readXyz(data + "/tls/pine_plot.xyz"), 0.3}};
    std::printf("%-10s %8s | %9s %9s %9s | %9s %9s %9s  (ms, median of %d)\n", "case", "points", "ours bld", "radius",
                "knn8", "nano bld", "radius", "knn8", repeats);
    for (const Case& c : cases) {
      // Queries: points of the set moved by up to half the radius, a tenth of the set (at least 2,000).
      std::mt19937 rng(1);
      std::uniform_real_distribution<double> jitter(-0.5 * c.radius, 0.5 * c.radius);
      std::vector<Point> queries;
      for (std::size_t i = 0; queries.size() < std::max<std::size_t>(2000, c.points.size() / 10); i = (i + 7) % c.points.size())
        queries.push_back(c.points[i] + Point(jitter(rng), jitter(rng), 0.1 * jitter(rng)));
      // Agreement first: the same neighbour sets for a sample of queries.
      const slide::KdTree<3> ours(c.points);
      const Cloud cloud{c.points};
      const Nano nano(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
      for (std::size_t i = 0; i < queries.size(); i += 97) {
        std::vector<std::size_t> a = ours.radius(queries[i], c.radius);
        std::vector<std::pair<std::size_t, double>> hits;
        nano.radiusSearch(queries[i].data(), c.radius * c.radius, hits, nanoflann::SearchParams());
        std::vector<std::size_t> b;
        for (const auto& h : hits) b.push_back(h.first);
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        if (a != b) throw std::runtime_error(c.name + ": the trees disagree on query " + std::to_string(i));
      }
      std::size_t sum_ours = 0, sum_nano = 0;
      const Times o = timeOurs(c, queries, repeats, sum_ours);
      const Times n = timeNano(c, queries, repeats, sum_nano);
      if (sum_ours != sum_nano) throw std::runtime_error(c.name + ": the trees' answers differ");
      std::printf("%-10s %8zu | %9.3f %9.3f %9.3f | %9.3f %9.3f %9.3f\n", c.name.c_str(), c.points.size(), o.build,
                  o.radius, o.knn, n.build, n.radius, n.knn);
      const std::string note = std::to_string(queries.size()) + " queries, radius " + std::to_string(c.radius).substr(0, 4) +
                               " m; CPU ms, median of " + std::to_string(repeats) + "; real data";
      auto add = [&](const std::string& what, double ours_ms, double nano_ms) {
        report.add(c.name + ".ours." + what + "_ms", ours_ms, "ms", true).note = note;
        report.add(c.name + ".nanoflann." + what + "_ms", nano_ms, "ms", true).note = note;
        report.add(c.name + "." + what + ".nanoflann_over_ours", nano_ms / ours_ms, "x", true).note =
            "> 1: the project's tree is faster";
      };
      add("build", o.build, n.build);
      add("radius", o.radius, n.radius);
      add("knn8", o.knn, n.knn);
    }
    report.printTable(std::cout);
    if (!json.empty()) report.writeJson(json);
    return 0;
  });
}
