#pragma once
// Point records described by named fields (the layout of ROS sensor_msgs/PointCloud2 and of
// PCL's PCLPointCloud2), decoded without ROS or PCL headers. Understands the layouts of the
// common LiDAR drivers:
//   x, y, z                 float32 or float64 (required)
//   intensity | reflectivity  any numeric type, kept as its value (0 when neither exists)
//   ring | line             beam index (Velodyne, Ouster: ring; Livox: line)
//   t                       Ouster: uint32 nanoseconds since the cloud's stamp (float: seconds)
//   time                    Velodyne/LIO-SAM: float32 seconds relative to the stamp
//   timestamp               Livox/Hesai: float64 absolute time (ns when > 1e15, else s)
// Organised (height > 1) and unorganised clouds; points with a NaN/infinite coordinate or time, or at
// the origin (no return) are skipped and counted.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace slide::io {

struct CloudField {
  std::string name;
  uint32_t offset = 0;
  uint8_t datatype = 0;  // 1 int8, 2 uint8, 3 int16, 4 uint16, 5 int32, 6 uint32, 7 float32, 8 float64
  uint32_t count = 1;
};

struct CloudLayout {
  uint32_t height = 0, width = 0, point_step = 0, row_step = 0;
  bool is_bigendian = false;
  std::vector<CloudField> fields;
};

struct DecodedCloud {
  std::vector<Eigen::Vector3f> xyz;
  std::vector<float> intensity;  // one per point (0 without an intensity field)
  std::vector<uint16_t> ring;    // one per point, empty without a ring/line field
  std::vector<double> time;      // seconds relative to the cloud's stamp, empty without per-point time
  std::size_t skipped = 0;       // NaN, infinite or zero points, NaN times
};

// Most points a cloud may hold (a 128-beam, 2048-column sweep is 262,144).
constexpr std::size_t kMaxCloudPoints = 4'000'000;

// Decodes `size` bytes of point records. stamp_s (the cloud's header time) turns absolute
// per-point times into relative ones. Throws std::invalid_argument naming the field or size
// that does not fit (missing x/y/z, field past point_step, rows past the data, big-endian).
DecodedCloud decodeCloud(const CloudLayout& layout, const uint8_t* data, std::size_t size, double stamp_s);

}  // namespace slide::io
