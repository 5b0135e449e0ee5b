#include "io/pcd_file.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include <filesystem>

#include "io/io_error.h"
#include "io/point_cloud2.h"

namespace slide::io {

LabelledScan readPcdFile(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw IoError(path, "cannot open file");
  pcl::PCLPointCloud2 cloud;
  try {  // PCL prints its own complaint to stderr too; the exception is what callers see
    if (pcl::io::loadPCDFile(path, cloud) < 0) throw IoError(path, "not a readable PCD file");
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(path, std::string("not a readable PCD file: ") + e.what());
  }
  CloudLayout l;  // decoded by its fields as a ROS PointCloud2 is (one decoder for both)
  l.height = cloud.height, l.width = cloud.width, l.point_step = cloud.point_step, l.row_step = cloud.row_step;
  l.is_bigendian = cloud.is_bigendian;
  for (const pcl::PCLPointField& f : cloud.fields) l.fields.push_back({f.name, f.offset, f.datatype, f.count});
  try {
    DecodedCloud d = decodeCloud(l, cloud.data.data(), cloud.data.size(), 0.0);
    LabelledScan s;
    s.xyz = std::move(d.xyz);
    s.intensity = std::move(d.intensity);
    return s;
  } catch (const std::exception& e) {
    throw IoError(path, e.what());
  }
}

}  // namespace slide::io
