#pragma once
// Spherical projection of a LiDAR scan to a range image (the RangeNet++ / SalsaNext
// convention) and back-projection of per-pixel labels to every point.
//
// Projection, sensor frame (x forward, y left, z up), r = |p|, yaw = atan2(y, x),
// pitch = asin(z / r), fov = fov_up - fov_down (radians):
//   u = floor(0.5 * (1 - yaw / pi) * width)        column, clamped to [0, width - 1]
//   v = floor((1 - (pitch - fov_down) / fov) * height)   row, clamped to [0, height - 1]
// so column 0 looks backwards (yaw = pi) and columns grow clockwise seen from above; row 0
// is the top beam. Points above or below the field of view land on the first or last row, as
// in RangeNet++. A pixel shows the nearest point that falls into it; tools/train_range_net
// implements the same formula (keep the two in step).
//
// Back-projection: a point shown by its pixel takes the pixel's label; a point hidden behind
// a nearer one in the same pixel takes the label of the nearest shown point in 3-D among the
// pixels within +-search_rows rows and +-search_cols columns of its own (columns wrap
// around), never blindly the pixel's: the returns behind a pole are wall, not pole.
#include <cstdint>
#include <vector>

#include "io/kitti_scan.h"

namespace slide::frontend {

struct RangeProjection {
  int height = 64, width = 1024;
  double fov_up_deg = 3.0, fov_down_deg = -25.0;  // vertical field of view (HDL-64E)
  int search_rows = 2, search_cols = 4;           // hidden points' neighbour window
};

// One scan projected to an image. Points that are non-finite or at range 0 have no pixel.
struct RangeImage {
  int height = 0, width = 0;
  std::vector<int> point_of_pixel;  // height * width, row-major: nearest point index, -1 if empty
  std::vector<int> pixel_of_point;  // per point: pixel index, -1 for a point without a pixel
  std::vector<float> range_of_pixel;  // metres, 0 where empty
};

// Throws std::invalid_argument for a non-positive size or an empty field of view.
RangeImage projectScan(const io::LabelledScan& scan, const RangeProjection& projection);

// Channels a model reads, in its input order.
enum class RangeChannel { Range, X, Y, Z, Remission };

// Input blob (channel-major, channels.size() x height x width) of the shown points:
// (value - mean[c]) / std[c]; empty pixels hold 0 (the mean). Sizes of means and stds must
// equal channels.size() (std::invalid_argument otherwise); remission reads scan.intensity
// (0 when the scan has none).
std::vector<float> rangeImageInput(const io::LabelledScan& scan, const RangeImage& image,
                                   const std::vector<RangeChannel>& channels, const std::vector<float>& means,
                                   const std::vector<float>& stds);

// Per-point labels from per-pixel labels (height * width, row-major), as above. Points without
// a pixel get `none`.
std::vector<uint16_t> backProjectLabels(const io::LabelledScan& scan, const RangeImage& image,
                                        const std::vector<uint16_t>& pixel_labels, const RangeProjection& projection,
                                        uint16_t none = 0);

}  // namespace slide::frontend
