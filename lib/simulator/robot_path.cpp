#include "simulator/robot_path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>

namespace slide::simulator {

double Trajectory::length() const {
  double s = 0;
  for (std::size_t i = 1; i < poses.size(); ++i) s += (poses[i].translation() - poses[i - 1].translation()).norm();
  return s;
}

namespace {
using Graph = std::vector<std::vector<int>>;

double walkLength(const RouteGraph& g, const std::vector<int>& walk) {
  double s = 0;
  for (std::size_t i = 1; i < walk.size(); ++i) s += (g.nodes[walk[i]] - g.nodes[walk[i - 1]]).norm();
  return s;
}

// Random walk that avoids turning back and prefers edges it has used least.
std::vector<int> randomWalk(const RouteGraph& g, const Graph& nb, int start, int prev, double length,
                            std::mt19937_64& rng) {
  std::vector<int> walk{start};
  std::map<std::pair<int, int>, int> used;
  double s = 0;
  int cur = start;
  while (s < length) {
    std::vector<int> options;
    int fewest = std::numeric_limits<int>::max();
    for (int n : nb[cur]) {
      if (n == prev && nb[cur].size() > 1) continue;
      const int u = used[{std::min(cur, n), std::max(cur, n)}];
      if (u < fewest) fewest = u, options.clear();
      if (u == fewest) options.push_back(n);
    }
    if (options.empty()) break;
    const int next = options[std::uniform_int_distribution<std::size_t>(0, options.size() - 1)(rng)];
    ++used[{std::min(cur, next), std::max(cur, next)}];
    s += (g.nodes[next] - g.nodes[cur]).norm();
    prev = cur;
    cur = next;
    walk.push_back(cur);
  }
  return walk;
}

std::vector<int> shortestPath(const RouteGraph& g, const Graph& nb, int from, int to) {
  std::vector<double> dist(g.nodes.size(), std::numeric_limits<double>::infinity());
  std::vector<int> parent(g.nodes.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  dist[from] = 0;
  q.push({0, from});
  while (!q.empty()) {
    const auto [d, u] = q.top();
    q.pop();
    if (d > dist[u]) continue;
    if (u == to) break;
    for (int v : nb[u]) {
      const double nd = d + (g.nodes[u] - g.nodes[v]).norm();
      if (nd < dist[v]) dist[v] = nd, parent[v] = u, q.push({nd, v});
    }
  }
  std::vector<int> path;
  if (parent[to] < 0 && to != from) return {from};
  for (int v = to; v != -1; v = parent[v]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

void append(std::vector<int>& walk, const std::vector<int>& more) {
  for (int v : more)
    if (walk.empty() || walk.back() != v) walk.push_back(v);
}

// Resamples a polyline every `step` metres.
std::vector<Eigen::Vector2d> densify(const std::vector<Eigen::Vector2d>& line, double step) {
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Eigen::Vector2d d = line[i + 1] - line[i];
    const int n = std::max(1, static_cast<int>(std::ceil(d.norm() / step)));
    for (int k = 0; k < n; ++k) out.push_back(line[i] + d * (static_cast<double>(k) / n));
  }
  if (!line.empty()) out.push_back(line.back());
  return out;
}

std::vector<Eigen::Vector2d> movingAverage(const std::vector<Eigen::Vector2d>& p, int half) {
  std::vector<Eigen::Vector2d> out(p.size());
  const int n = static_cast<int>(p.size());
  for (int i = 0; i < n; ++i) {
    Eigen::Vector2d s = Eigen::Vector2d::Zero();
    int c = 0;
    for (int k = std::max(0, i - half); k <= std::min(n - 1, i + half); ++k) s += p[k], ++c;
    out[i] = s / c;
  }
  return out;
}
}  // namespace

std::vector<std::vector<Eigen::Vector2d>> planRoutes(const RouteGraph& g, int robots, double length, double overlap,
                                                     std::mt19937_64& rng) {
  std::vector<std::vector<Eigen::Vector2d>> routes;
  if (g.nodes.empty() || robots <= 0) return routes;
  const Graph nb = g.neighbours();
  overlap = std::clamp(overlap, 0.0, 1.0);
  // Start nodes far apart (farthest-point sampling from a random node).
  std::vector<int> starts{std::uniform_int_distribution<int>(0, static_cast<int>(g.nodes.size()) - 1)(rng)};
  while (static_cast<int>(starts.size()) < robots) {
    int best = 0;
    double best_d = -1;
    for (std::size_t v = 0; v < g.nodes.size(); ++v) {
      double d = std::numeric_limits<double>::infinity();
      for (int s : starts) d = std::min(d, (g.nodes[v] - g.nodes[s]).norm());
      if (d > best_d) best_d = d, best = static_cast<int>(v);
    }
    starts.push_back(best);
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& n : g.nodes) mean += n;
  mean /= static_cast<double>(g.nodes.size());
  int centre = 0;
  for (std::size_t v = 0; v < g.nodes.size(); ++v)
    if ((g.nodes[v] - mean).norm() < (g.nodes[centre] - mean).norm()) centre = static_cast<int>(v);
  const std::vector<int> common = overlap > 0 ? randomWalk(g, nb, centre, -1, overlap * length, rng) : std::vector<int>{};

  for (int r = 0; r < robots; ++r) {
    std::vector<int> walk = randomWalk(g, nb, starts[r], -1, 0.5 * (1 - overlap) * length, rng);
    if (!common.empty()) {
      append(walk, shortestPath(g, nb, walk.back(), common.front()));
      append(walk, common);
    }
    const double rest = length - walkLength(g, walk);
    if (rest > 0) {
      const int prev = walk.size() > 1 ? walk[walk.size() - 2] : -1;
      append(walk, randomWalk(g, nb, walk.back(), prev, rest + 1.0, rng));
    }
    std::vector<Eigen::Vector2d> line;
    for (int v : walk) line.push_back(g.nodes[v]);
    routes.push_back(line);
  }
  return routes;
}

Trajectory followRoute(const std::vector<Eigen::Vector2d>& polyline, const Terrain& terrain, const MotionParams& m,
                       double max_length, int max_frames, double t0) {
  Trajectory traj;
  if (polyline.size() < 2) return traj;
  const double ds = 0.1;
  const std::vector<Eigen::Vector2d> smooth =
      movingAverage(movingAverage(densify(polyline, ds), static_cast<int>(m.corner_radius / ds)),
                    static_cast<int>(m.corner_radius / ds));
  std::vector<double> s(smooth.size(), 0.0);
  for (std::size_t i = 1; i < smooth.size(); ++i) s[i] = s[i - 1] + (smooth[i] - smooth[i - 1]).norm();
  const double step = m.speed / m.rate;
  const double max_turn = m.max_yaw_rate > 0 ? m.max_yaw_rate / m.rate : std::numeric_limits<double>::infinity();
  const double total = std::min(max_length, s.back());
  auto full = [&] { return max_frames > 0 && static_cast<int>(traj.size()) >= max_frames; };
  auto emit = [&](const Eigen::Vector2d& p, double sk, double yaw) {
    const double ground = terrain.height(p.x(), p.y());
    double z, roll = 0, pitch = 0;
    if (m.aerial) {
      z = ground + m.height + m.altitude_amplitude * std::sin(2 * M_PI * sk / m.altitude_wavelength);
    } else {
      z = ground + m.height;
      const Eigen::Vector2d grad = terrain.gradient(p.x(), p.y());
      pitch = -std::atan(grad.dot(Eigen::Vector2d(std::cos(yaw), std::sin(yaw))));
      roll = std::atan(grad.dot(Eigen::Vector2d(-std::sin(yaw), std::cos(yaw))));
    }
    traj.times.push_back(t0 + static_cast<double>(traj.size()) / m.rate);
    traj.poses.push_back(poseFromXyzRpy({p.x(), p.y(), z}, roll, pitch, yaw));
  };
  std::size_t j = 0;
  Eigen::Vector2d last_p;
  double last_yaw = 0, last_s = 0;
  for (int k = 0;; ++k) {
    const double sk = k * step;
    if (sk > total + 1e-9 || full()) break;
    while (j + 2 < s.size() && s[j + 1] < sk) ++j;
    const double a = s[j + 1] > s[j] ? std::clamp((sk - s[j]) / (s[j + 1] - s[j]), 0.0, 1.0) : 0.0;
    const Eigen::Vector2d p = smooth[j] + a * (smooth[j + 1] - smooth[j]);
    const std::size_t i0 = j > 5 ? j - 5 : 0, i1 = std::min(smooth.size() - 1, j + 6);
    const Eigen::Vector2d dir = smooth[i1] - smooth[i0];
    const double yaw = std::atan2(dir.y(), dir.x());
    if (k > 0) {  // turn in place where the path turns too fast
      double d = std::remainder(yaw - last_yaw, 2 * M_PI);
      while (std::abs(d) > max_turn && !full()) {
        last_yaw += std::copysign(max_turn, d);
        emit(last_p, last_s, last_yaw);
        d = std::remainder(yaw - last_yaw, 2 * M_PI);
      }
      if (full()) break;
    }
    emit(p, sk, yaw);
    last_p = p, last_yaw = yaw, last_s = sk;
  }
  return traj;
}

}  // namespace slide::simulator
