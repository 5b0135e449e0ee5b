#include "frontend/scan_lines.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "frontend/azimuth.h"

namespace slide::frontend {

namespace {
// Azimuth difference wrapped into (-pi, pi].
float wrapped(float d) {
  if (d > float(M_PI)) return d - 2 * float(M_PI);
  if (d <= -float(M_PI)) return d + 2 * float(M_PI);
  return d;
}
// tan(elevation + tolerance) - tan(elevation), to first order in the tolerance.
float tanTolerance(float tan_elevation, double tolerance_deg) {
  return static_cast<float>(std::tan(tolerance_deg * M_PI / 180.0)) * (1 + tan_elevation * tan_elevation);
}
}  // namespace

ScanLines::ScanLines(const Cloud& cloud, const std::vector<int>& points) : cloud_(cloud) {
  std::vector<Return> polars(points.size());
  start_.assign(kBins + 1, 0);
  for (std::size_t k = 0; k < points.size(); ++k) ++start_[bin((polars[k] = polar(cloud[points[k]], points[k])).azimuth) + 1];
  for (int b = 0; b < kBins; ++b) start_[b + 1] += start_[b];
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  returns_.resize(points.size());
  for (const Return& r : polars) returns_[fill[bin(r.azimuth)]++] = r;
  for (int b = 0; b < kBins; ++b)
    std::sort(returns_.begin() + start_[b], returns_.begin() + start_[b + 1],
              [](const Return& a, const Return& c) { return a.tan_elevation < c.tan_elevation; });
}

int ScanLines::bin(float azimuth) {
  return std::clamp(static_cast<int>((azimuth + float(M_PI)) * (kBins / (2 * float(M_PI)))), 0, kBins - 1);
}

ScanLines::Return ScanLines::polar(const Eigen::Vector3f& p, int index) {
  const float r = std::max(std::sqrt(p.x() * p.x() + p.y() * p.y()), 1e-3f);
  return {azimuthOf(p.y(), p.x()), p.z() / r, r, index};
}

std::pair<const ScanLines::Return*, const ScanLines::Return*> ScanLines::band(int b, float lo, float hi) const {
  const Return* first = returns_.data() + start_[b];
  const Return* last = returns_.data() + start_[b + 1];
  first = std::lower_bound(first, last, lo, [](const Return& r, float v) { return r.tan_elevation < v; });
  last = std::upper_bound(first, last, hi, [](float v, const Return& r) { return v < r.tan_elevation; });
  return {first, last};
}

std::vector<int> ScanLines::next(int from, int direction, int count, double window_deg, double beam_tolerance_deg,
                                 const std::vector<char>& skip) const {
  const Return q = polar(cloud_[from], from);
  const float window = static_cast<float>(window_deg * M_PI / 180.0);
  const float tol = tanTolerance(q.tan_elevation, beam_tolerance_deg);
  const int b0 = bin(q.azimuth), reach = static_cast<int>(std::ceil(window_deg * kBins / 360.0)) + 1;
  std::vector<std::pair<float, int>> found;  // (azimuth beyond `from`, index)
  for (int k = 0; k <= std::min(reach, kBins / 2); ++k) {
    const auto [first, last] = band(((b0 + direction * k) % kBins + kBins) % kBins, q.tan_elevation - tol, q.tan_elevation + tol);
    for (const Return* r = first; r != last; ++r) {
      if (skip[r->index]) continue;
      const float d = wrapped(r->azimuth - q.azimuth) * direction;
      if (d > 0 && d <= window) found.emplace_back(d, r->index);
    }
  }
  const std::size_t n = std::min(found.size(), static_cast<std::size_t>(std::max(count, 0)));
  std::partial_sort(found.begin(), found.begin() + n, found.end());
  std::vector<int> out;
  for (std::size_t k = 0; k < n; ++k) out.push_back(found[k].second);
  return out;
}

std::vector<ScanLines::BeamEdges> ScanLines::beamEdges(const std::vector<int>& points, double beam_tolerance_deg) const {
  std::vector<Return> pts;  // sorted by elevation
  pts.reserve(points.size());
  for (int i : points) pts.push_back(polar(cloud_[i], i));
  std::sort(pts.begin(), pts.end(), [](const Return& a, const Return& b) { return a.tan_elevation < b.tan_elevation; });
  const float tol = static_cast<float>(std::tan(beam_tolerance_deg * M_PI / 180.0));
  std::vector<BeamEdges> out;
  for (std::size_t s = 0; s < pts.size();) {
    // Azimuths are measured from the beam's first return, so the +-pi seam does not matter.
    std::size_t e = s + 1, lo = s, hi = s;
    float dlo = 0, dhi = 0;
    for (; e < pts.size() && pts[e].tan_elevation - pts[e - 1].tan_elevation <= tol; ++e) {
      const float d = wrapped(pts[e].azimuth - pts[s].azimuth);
      if (d < dlo) dlo = d, lo = e;
      if (d > dhi) dhi = d, hi = e;
    }
    out.push_back({pts[lo].index, pts[hi].index});
    s = e;
  }
  return out;
}

bool ScanLines::hiddenAbove(const Eigen::Vector3f& p, float range) const {
  constexpr float kTanAbove = 0.052408f;  // tan(3 deg)
  const Return q = polar(p, -1);
  // tan(elevation + 3 deg) from tan(elevation), without trigonometry per point.
  const float lo = q.tan_elevation + 1e-4f, hi = (q.tan_elevation + kTanAbove) / (1.0f - q.tan_elevation * kTanAbove);
  const int b = bin(q.azimuth);
  for (int d = -3; d <= 3; ++d) {
    const auto [first, last] = band((b + d + kBins) % kBins, lo, hi);
    for (const Return* r = first; r != last; ++r)
      if (r->tan_elevation > lo && r->range < range) return true;
  }
  return false;
}

std::vector<ScanLines::Return> ScanLines::byBin(const std::vector<int>& points) const {
  std::vector<Return> out;
  out.reserve(points.size());
  for (int i : points) out.push_back(polar(cloud_[i], i));
  std::sort(out.begin(), out.end(), [](const Return& a, const Return& b) {
    const int ba = bin(a.azimuth), bb = bin(b.azimuth);
    return ba != bb ? ba < bb : a.tan_elevation < b.tan_elevation;
  });
  return out;
}

std::vector<int> ScanLines::hiddenBelow(const std::vector<int>& points, float below, float margin, int& bins,
                                        float ground_z) const {
  std::vector<Return> lowest = byBin(points);  // then the lowest per bin
  lowest.erase(std::unique(lowest.begin(), lowest.end(),
                           [](const Return& a, const Return& b) { return bin(a.azimuth) == bin(b.azimuth); }),
               lowest.end());
  bins = static_cast<int>(lowest.size());
  std::vector<int> out;
  for (const Return& q : lowest) {
    const int b = bin(q.azimuth);
    int found = -1;
    auto search = [&](float hi) {
      const float lo = hi - below / q.range;
      for (int d = -1; d <= 1 && found < 0; ++d) {
        const auto [first, last] = band((b + d + kBins) % kBins, lo, hi);
        for (const Return* r = first; r != last && found < 0; ++r)
          if (r->range < q.range - margin) found = r->index;
      }
    };
    search(q.tan_elevation - 1e-4f);
    // Under the ground level too: returns of a face below the points that were taken for the
    // ground (not indexed) leave the lines just under the points ending there, not nearer.
    if (found < 0 && std::isfinite(ground_z) && ground_z / q.range < q.tan_elevation - 1e-4f)
      search(ground_z / q.range);
    if (found >= 0) out.push_back(found);
  }
  return out;
}

double ScanLines::continuedFraction(const std::vector<int>& points, const std::vector<char>& in_set,
                                    const std::vector<char>& unknown, float range_tolerance, double window_deg) const {
  const std::vector<Return> sorted = byBin(points);
  const float w = static_cast<float>(std::tan(window_deg * M_PI / 180.0));
  auto goesOn = [&](const Return& r, const Return& from) {
    return !unknown[r.index] && std::abs(r.range - from.range) <= range_tolerance;
  };
  int bins = 0, continued = 0;
  for (std::size_t k = 0; k < sorted.size();) {
    const int b = bin(sorted[k].azimuth);
    const Return& low = sorted[k];
    while (k + 1 < sorted.size() && bin(sorted[k + 1].azimuth) == b) ++k;
    const Return& high = sorted[k++];
    ++bins;
    // The nearest other return past each end within the window (tan(elevation +- window) from
    // tan(elevation), as in hiddenAbove).
    bool on = false;
    {
      const auto [first, last] = band(b, high.tan_elevation + 1e-5f, (high.tan_elevation + w) / (1.0f - high.tan_elevation * w));
      const Return* r = std::find_if(first, last, [&](const Return& x) { return !in_set[x.index]; });
      on = r != last && goesOn(*r, high);
    }
    if (!on) {
      const auto [first, last] = band(b, (low.tan_elevation - w) / (1.0f + low.tan_elevation * w), low.tan_elevation - 1e-5f);
      const auto r = std::find_if(std::make_reverse_iterator(last), std::make_reverse_iterator(first),
                                  [&](const Return& x) { return !in_set[x.index]; });
      on = r != std::make_reverse_iterator(first) && goesOn(*r, low);
    }
    continued += on;
  }
  return bins ? static_cast<double>(continued) / bins : 0.0;
}

std::vector<float> ScanLines::heightsAbove(const Eigen::Vector3f& p, float range) const {
  const Return q = polar(p, -1);
  const int b = bin(q.azimuth);
  std::vector<float> z;
  for (int d = -1; d <= 1; ++d) {
    const auto [first, last] = band((b + d + kBins) % kBins, q.tan_elevation + 1e-4f, std::numeric_limits<float>::max());
    for (const Return* r = first; r != last; ++r)
      if (r->range < range) z.push_back(cloud_[r->index].z());
  }
  return z;
}

std::optional<ScanLines::ViewTop> ScanLines::viewTop(double tolerance_deg, double min_share, double max_height) const {
  // Candidates: the highest returns of each bin (seen from the origin); the top beam's are
  // among them for any origin height up to max_height.
  constexpr int kPerBin = 8;
  struct Candidate {
    float z, range;
    int bin;
  };
  std::vector<Candidate> cand;
  for (int b = 0; b < kBins; ++b)
    for (int k = start_[b + 1] - 1; k >= std::max(start_[b], start_[b + 1] - kPerBin); --k)
      cand.push_back({returns_[k].tan_elevation * returns_[k].range, returns_[k].range, b});
  if (cand.empty()) return std::nullopt;
  std::optional<ViewTop> best;
  int best_hit = 0;
  std::vector<float> bin_top(kBins);
  const int steps = static_cast<int>(std::floor(max_height / 0.02 + 1e-9));
  for (int s = -steps; s <= steps; ++s) {
    const float height = 0.02f * s;
    std::fill(bin_top.begin(), bin_top.end(), -std::numeric_limits<float>::infinity());
    float top = -std::numeric_limits<float>::infinity();
    for (const Candidate& c : cand) {
      const float t = (c.z - height) / c.range;
      bin_top[c.bin] = std::max(bin_top[c.bin], t);
      top = std::max(top, t);
    }
    const float tol = tanTolerance(top, tolerance_deg);
    int hit = 0;
    for (float t : bin_top) hit += t >= top - tol;
    // Of heights that reach as many bins, the one nearest the origin.
    if (hit > best_hit || (hit == best_hit && best && std::abs(height) < std::abs(best->height)))
      best_hit = hit, best = ViewTop{top, height};
  }
  if (best_hit < min_share * kBins) return std::nullopt;
  return best;
}

void ScanLines::markUnderTop(const ViewTop& top, double tolerance_deg, float range_tolerance, std::vector<char>& mark) const {
  const float tan_tolerance = tanTolerance(top.tan_elevation, tolerance_deg);
  std::vector<std::vector<float>> top_ranges(kBins);  // per bin: ranges of its returns at the top
  bool any = false;
  for (int b = 0; b < kBins; ++b)
    for (int k = start_[b]; k < start_[b + 1]; ++k) {
      const Return& r = returns_[k];
      if (r.tan_elevation * r.range >= top.at(r.range) - tan_tolerance * r.range) top_ranges[b].push_back(r.range), any = true;
    }
  if (!any) return;
  for (int b = 0; b < kBins; ++b)
    for (int d = -1; d <= 1; ++d)
      for (float r : top_ranges[(b + d + kBins) % kBins])
        for (int k = start_[b]; k < start_[b + 1]; ++k)
          if (std::abs(returns_[k].range - r) <= range_tolerance) mark[returns_[k].index] = 1;
}

bool ScanLines::besideMarked(const Eigen::Vector3f& p, const std::vector<char>& mark, float range_tolerance) const {
  const Return q = polar(p, -1);
  const int b = bin(q.azimuth);
  for (int d = -1; d <= 1; ++d) {
    const int n = (b + d + kBins) % kBins;
    for (int k = start_[n]; k < start_[n + 1]; ++k)
      if (mark[returns_[k].index] && std::abs(returns_[k].range - q.range) <= range_tolerance) return true;
  }
  return false;
}

}  // namespace slide::frontend
