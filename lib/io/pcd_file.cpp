#include "io/pcd_file.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <filesystem>

#include "io/io_error.h"

namespace slide {

LabelledScan readPcdFile(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw IoError(path, "cannot open file");
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  // PCL prints its own complaint to stderr too; the exception is what callers see.
  if (reader.read(path, blob) < 0) throw IoError(path, "not a readable PCD file");
  bool x = false, y = false, z = false, intensity = false;
  for (const auto& f : blob.fields) {
    x |= f.name == "x", y |= f.name == "y", z |= f.name == "z";
    intensity |= f.name == "intensity";
  }
  if (!x || !y || !z) throw IoError(path, "PCD file lacks an x, y or z field");
  if (blob.data.size() < static_cast<std::size_t>(blob.width) * blob.height * blob.point_step)
    throw IoError(path, "PCD data shorter than its header says");
  LabelledScan scan;
  if (intensity) {
    pcl::PointCloud<pcl::PointXYZI> cloud;
    pcl::fromPCLPointCloud2(blob, cloud);
    for (const auto& p : cloud.points) {
      scan.xyz.emplace_back(p.x, p.y, p.z);
      scan.intensity.push_back(p.intensity);
    }
  } else {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    pcl::fromPCLPointCloud2(blob, cloud);
    for (const auto& p : cloud.points) {
      scan.xyz.emplace_back(p.x, p.y, p.z);
      scan.intensity.push_back(0.0f);
    }
  }
  return scan;
}

}  // namespace slide
