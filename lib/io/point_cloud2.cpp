#include "io/point_cloud2.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace slide::io {

namespace {
std::size_t typeSize(uint8_t t) {
  switch (t) {
    case 1: case 2: return 1;
    case 3: case 4: return 2;
    case 5: case 6: case 7: return 4;
    case 8: return 8;
    default: return 0;
  }
}

template <class T>
double load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}

double value(uint8_t type, const uint8_t* p) {
  switch (type) {
    case 1: return load<int8_t>(p);
    case 2: return load<uint8_t>(p);
    case 3: return load<int16_t>(p);
    case 4: return load<uint16_t>(p);
    case 5: return load<int32_t>(p);
    case 6: return load<uint32_t>(p);
    case 7: return load<float>(p);
    default: return load<double>(p);
  }
}

// The first field named any of `names`, checked against point_step; null when none.
const CloudField* findField(const CloudLayout& l, std::initializer_list<const char*> names) {
  for (const char* n : names)
    for (const CloudField& f : l.fields)
      if (f.name == n) {
        const std::size_t s = typeSize(f.datatype);
        if (s == 0) throw std::invalid_argument("field '" + f.name + "' has unknown datatype " + std::to_string(f.datatype));
        if (f.count < 1 || static_cast<std::size_t>(f.offset) + s > l.point_step)
          throw std::invalid_argument("field '" + f.name + "' at offset " + std::to_string(f.offset) +
                                      " does not fit in point_step " + std::to_string(l.point_step));
        return &f;
      }
  return nullptr;
}

enum class TimeKind { None, RelativeNs, RelativeS, Absolute };
}  // namespace

DecodedCloud decodeCloud(const CloudLayout& l, const uint8_t* data, std::size_t size, double stamp_s) {
  if (l.is_bigendian) throw std::invalid_argument("big-endian point data is not supported");
  const std::size_t n = static_cast<std::size_t>(l.height) * l.width;
  if (n > kMaxCloudPoints) throw std::invalid_argument(std::to_string(n) + " points exceed the limit of " + std::to_string(kMaxCloudPoints));
  if (n > 0 && l.point_step == 0) throw std::invalid_argument("point_step is 0");
  if (static_cast<uint64_t>(l.width) * l.point_step > l.row_step)
    throw std::invalid_argument("row_step " + std::to_string(l.row_step) + " is shorter than width x point_step");
  if (static_cast<uint64_t>(l.row_step) * l.height > size)
    throw std::invalid_argument("data holds " + std::to_string(size) + " bytes, rows need " +
                                std::to_string(static_cast<uint64_t>(l.row_step) * l.height));
  const CloudField *fx = findField(l, {"x"}), *fy = findField(l, {"y"}), *fz = findField(l, {"z"});
  if (!fx || !fy || !fz) throw std::invalid_argument("no x, y, z fields");
  for (const CloudField* f : {fx, fy, fz})
    if (f->datatype != 7 && f->datatype != 8) throw std::invalid_argument("field '" + f->name + "' is not float32/float64");
  const CloudField* fi = findField(l, {"intensity", "reflectivity"});
  const CloudField* fr = findField(l, {"ring", "line"});
  const CloudField* ft = findField(l, {"t", "time", "timestamp", "time_stamp"});
  TimeKind kind = TimeKind::None;
  if (ft) {
    const bool integer = ft->datatype != 7 && ft->datatype != 8;
    if (ft->name == "t") kind = integer ? TimeKind::RelativeNs : TimeKind::RelativeS;
    else if (ft->datatype == 8) kind = TimeKind::Absolute;  // decided per value: absolute stamps are > 1e9 s
    else kind = integer ? TimeKind::RelativeNs : TimeKind::RelativeS;
  }
  DecodedCloud c;
  c.xyz.reserve(n);
  c.intensity.reserve(n);
  if (fr) c.ring.reserve(n);
  if (ft) c.time.reserve(n);
  for (uint32_t r = 0; r < l.height; ++r) {
    const uint8_t* row = data + static_cast<std::size_t>(r) * l.row_step;
    for (uint32_t k = 0; k < l.width; ++k) {
      const uint8_t* p = row + static_cast<std::size_t>(k) * l.point_step;
      const double x = value(fx->datatype, p + fx->offset), y = value(fy->datatype, p + fy->offset),
                   z = value(fz->datatype, p + fz->offset);
      double rel = 0;
      if (ft) {
        const double v = value(ft->datatype, p + ft->offset);
        rel = kind == TimeKind::RelativeNs ? v * 1e-9 : v;
        if (kind == TimeKind::Absolute) rel = v > 1e15 ? v * 1e-9 - stamp_s : (v > 1e9 ? v - stamp_s : v);
      }
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || (x == 0 && y == 0 && z == 0) ||
          !std::isfinite(rel)) {
        ++c.skipped;
        continue;
      }
      c.xyz.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
      c.intensity.push_back(fi ? static_cast<float>(value(fi->datatype, p + fi->offset)) : 0.f);
      if (fr) c.ring.push_back(static_cast<uint16_t>(value(fr->datatype, p + fr->offset)));
      if (ft) c.time.push_back(rel);
    }
  }
  return c;
}

}  // namespace slide::io
