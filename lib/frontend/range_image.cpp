#include "frontend/range_image.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace slide::frontend {

RangeImage projectScan(const io::LabelledScan& scan, const RangeProjection& p) {
  if (p.height <= 0 || p.width <= 0 || p.height > 4096 || p.width > 65536)
    throw std::invalid_argument("range image size must be 1..4096 x 1..65536, got " + std::to_string(p.height) + " x " +
                                std::to_string(p.width));
  const double up = p.fov_up_deg * M_PI / 180.0, down = p.fov_down_deg * M_PI / 180.0, fov = up - down;
  if (!(fov > 0)) throw std::invalid_argument("range image field of view: fov_up_deg must exceed fov_down_deg");
  RangeImage img;
  img.height = p.height;
  img.width = p.width;
  const std::size_t pixels = static_cast<std::size_t>(p.height) * p.width;
  img.point_of_pixel.assign(pixels, -1);
  img.range_of_pixel.assign(pixels, 0.0f);
  img.pixel_of_point.assign(scan.size(), -1);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Vector3d q = scan.xyz[i].cast<double>();
    const double r = q.norm();
    if (!std::isfinite(r) || r <= 0) continue;
    const double yaw = std::atan2(q.y(), q.x()), pitch = std::asin(std::clamp(q.z() / r, -1.0, 1.0));
    const int u = std::clamp(static_cast<int>(std::floor(0.5 * (1.0 - yaw / M_PI) * p.width)), 0, p.width - 1);
    const int v = std::clamp(static_cast<int>(std::floor((1.0 - (pitch - down) / fov) * p.height)), 0, p.height - 1);
    const int px = v * p.width + u;
    img.pixel_of_point[i] = px;
    int& shown = img.point_of_pixel[px];
    if (shown < 0 || r < img.range_of_pixel[px]) shown = static_cast<int>(i), img.range_of_pixel[px] = static_cast<float>(r);
  }
  return img;
}

std::vector<float> rangeImageInput(const io::LabelledScan& scan, const RangeImage& img,
                                   const std::vector<RangeChannel>& channels, const std::vector<float>& means,
                                   const std::vector<float>& stds) {
  if (means.size() != channels.size() || stds.size() != channels.size())
    throw std::invalid_argument("range image input: " + std::to_string(channels.size()) + " channels need as many means and stds");
  const std::size_t pixels = img.point_of_pixel.size();
  std::vector<float> blob(channels.size() * pixels, 0.0f);
  const bool has_intensity = scan.intensity.size() == scan.size();
  for (std::size_t px = 0; px < pixels; ++px) {
    const int i = img.point_of_pixel[px];
    if (i < 0) continue;
    const Eigen::Vector3f& q = scan.xyz[i];
    for (std::size_t c = 0; c < channels.size(); ++c) {
      float v = 0;
      switch (channels[c]) {
        case RangeChannel::Range: v = img.range_of_pixel[px]; break;
        case RangeChannel::X: v = q.x(); break;
        case RangeChannel::Y: v = q.y(); break;
        case RangeChannel::Z: v = q.z(); break;
        case RangeChannel::Remission: v = has_intensity ? scan.intensity[i] : 0.0f; break;
      }
      blob[c * pixels + px] = (v - means[c]) / stds[c];
    }
  }
  return blob;
}

std::vector<uint16_t> backProjectLabels(const io::LabelledScan& scan, const RangeImage& img,
                                        const std::vector<uint16_t>& pixel_labels, const RangeProjection& p, uint16_t none) {
  if (pixel_labels.size() != img.point_of_pixel.size() || img.pixel_of_point.size() != scan.size())
    throw std::invalid_argument("back-projection: labels or image do not match the scan");
  std::vector<uint16_t> out(scan.size(), none);
  const int rows = std::max(0, p.search_rows), cols = std::min(std::max(0, p.search_cols), img.width / 2);
  // The shown points' coordinates by pixel, one padded row per image row (the columns wrap
  // around into the padding), so the window search reads contiguous floats without branches.
  // Empty pixels sit far away.
  constexpr float kEmpty = 1e18f;
  const int stride = img.width + 2 * cols;
  const std::size_t padded = static_cast<std::size_t>(img.height) * stride;
  std::vector<float> sx(padded, kEmpty), sy(padded, kEmpty), sz(padded, kEmpty);
  for (int v = 0; v < img.height; ++v)
    for (int u = -cols; u < img.width + cols; ++u) {
      const int j = img.point_of_pixel[v * img.width + (u + img.width) % img.width];
      if (j < 0) continue;
      const std::size_t q = static_cast<std::size_t>(v) * stride + u + cols;
      sx[q] = scan.xyz[j].x(), sy[q] = scan.xyz[j].y(), sz[q] = scan.xyz[j].z();
    }
  // sin of k column widths / row heights of angle (k = 0..), capped at a right angle.
  std::vector<float> sin_col(cols + 1), sin_row(rows + 1);
  const double col_rad = 2.0 * M_PI / img.width, row_rad = (p.fov_up_deg - p.fov_down_deg) * M_PI / 180.0 / img.height;
  for (int k = 0; k <= cols; ++k) sin_col[k] = static_cast<float>(std::sin(std::min(k * col_rad, M_PI / 2)));
  for (int k = 0; k <= rows; ++k) sin_row[k] = static_cast<float>(std::sin(std::min(k * row_rad, M_PI / 2)));
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const int px = img.pixel_of_point[i];
    if (px < 0) continue;
    if (img.point_of_pixel[px] == static_cast<int>(i)) {
      out[i] = pixel_labels[px];
      continue;
    }
    // Hidden: nearest shown point in 3-D within the window. The own pixel's point first; then a
    // column |du| apart is at least (|du| - 1) column widths of yaw away, so no nearer than
    // r_xy sin((|du| - 1) w), and a row |dv| apart no nearer than r sin((|dv| - 1) h): the
    // window shrinks to the columns and rows that could still hold a nearer point (exact).
    const float x = scan.xyz[i].x(), y = scan.xyz[i].y(), z = scan.xyz[i].z();
    const int v0 = px / img.width, u0 = px % img.width;
    const std::size_t own = static_cast<std::size_t>(v0) * stride + u0 + cols;
    float best = (sx[own] - x) * (sx[own] - x) + (sy[own] - y) * (sy[own] - y) + (sz[own] - z) * (sz[own] - z);
    int best_v = v0, best_u = u0;
    const float r_xy2 = x * x + y * y, r2 = r_xy2 + z * z;
    int cc = 1, rr = 1;
    while (cc < cols && r_xy2 * sin_col[cc] * sin_col[cc] < best) ++cc;
    while (rr < rows && r2 * sin_row[rr] * sin_row[rr] < best) ++rr;
    cc = std::min(cc, cols), rr = std::min(rr, rows);
    for (int v = std::max(0, v0 - rr); v <= std::min(img.height - 1, v0 + rr); ++v) {
      const std::size_t row = static_cast<std::size_t>(v) * stride + u0 + cols;  // padded column of u0
      for (int du = -cc; du <= cc; ++du) {
        const float dx = sx[row + du] - x, dy = sy[row + du] - y, dz = sz[row + du] - z;
        const float d = dx * dx + dy * dy + dz * dz;
        if (d < best) best = d, best_v = v, best_u = u0 + du;
      }
    }
    out[i] = pixel_labels[best_v * img.width + (best_u + img.width) % img.width];
  }
  return out;
}

}  // namespace slide::frontend
