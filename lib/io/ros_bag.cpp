// The one file that sees rosbag_storage and the ROS message headers. Messages are taken from
// the bag as raw bytes (RawMessage below) and decoded by a bounds-checked cursor: ROS's own
// deserializers resize vectors to whatever length a corrupt message claims before checking it.
#include "io/ros_bag.h"

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "geometry/deskew.h"
#include "io/io_error.h"
#include "io/point_cloud2.h"

namespace slide::io {
// Any message, as its serialized bytes (or only their first kStampBytes for MessageStamp).
struct RawMessage {
  std::vector<uint8_t> bytes;
};
struct MessageStamp {
  std::vector<uint8_t> bytes;
};
}  // namespace slide::io

namespace ros {
namespace message_traits {
template <class M>
struct AnyType {
  static const char* value() { return "*"; }
  static const char* value(const M&) { return value(); }
};
template <> struct MD5Sum<slide::io::RawMessage> : AnyType<slide::io::RawMessage> {};
template <> struct DataType<slide::io::RawMessage> : AnyType<slide::io::RawMessage> {};
template <> struct Definition<slide::io::RawMessage> : AnyType<slide::io::RawMessage> {};
template <> struct MD5Sum<slide::io::MessageStamp> : AnyType<slide::io::MessageStamp> {};
template <> struct DataType<slide::io::MessageStamp> : AnyType<slide::io::MessageStamp> {};
template <> struct Definition<slide::io::MessageStamp> : AnyType<slide::io::MessageStamp> {};
}  // namespace message_traits
namespace serialization {
template <>
struct Serializer<slide::io::RawMessage> {
  template <class Stream>
  static void read(Stream& s, slide::io::RawMessage& m) {
    m.bytes.assign(s.getData(), s.getData() + s.getLength());
  }
};
template <>
struct Serializer<slide::io::MessageStamp> {
  template <class Stream>
  static void read(Stream& s, slide::io::MessageStamp& m) {
    m.bytes.assign(s.getData(), s.getData() + std::min<uint32_t>(12, s.getLength()));  // seq, stamp
  }
};
}  // namespace serialization
}  // namespace ros

namespace slide::io {

namespace {
constexpr const char* kTf = "/tf";
constexpr const char* kTfStatic = "/tf_static";

// Reads ROS 1 serialized fields (little-endian) and throws std::invalid_argument past the end.
class Cursor {
 public:
  Cursor(const uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  const uint8_t* take(std::size_t k) {
    if (k > n_ - pos_)
      throw std::invalid_argument("message ends after " + std::to_string(n_) + " bytes; " + std::to_string(k) +
                                  " more needed at byte " + std::to_string(pos_));
    const uint8_t* q = p_ + pos_;
    pos_ += k;
    return q;
  }
  template <class T>
  T get() {
    T v;
    std::memcpy(&v, take(sizeof(T)), sizeof(T));
    return v;
  }
  uint32_t u32() { return get<uint32_t>(); }
  uint8_t u8() { return get<uint8_t>(); }
  double f64() { return get<double>(); }
  std::string str() {
    const uint32_t len = u32();
    const uint8_t* q = take(len);
    return std::string(reinterpret_cast<const char*>(q), len);
  }
  double stamp() {
    const uint32_t sec = u32(), nsec = u32();
    return sec + 1e-9 * nsec;
  }

 private:
  const uint8_t* p_;
  std::size_t n_, pos_ = 0;
};

struct Header {
  double stamp = 0;
  std::string frame_id;
};
Header readHeader(Cursor& c) {
  Header h;
  c.u32();  // seq
  h.stamp = c.stamp();
  h.frame_id = c.str();
  return h;
}

Pose readPose(Cursor& c) {  // geometry_msgs/Pose or Transform: 3 + 4 float64
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) t[i] = c.f64();
  const double x = c.f64(), y = c.f64(), z = c.f64(), w = c.f64();
  const Eigen::Quaterniond q(w, x, y, z);
  if (!t.allFinite() || !std::isfinite(q.norm()) || std::abs(q.norm() - 1.0) > 1e-2)
    throw std::invalid_argument("pose is not finite or its quaternion is not unit length");
  return poseFromPositionQuaternion(t, q);
}

struct ImageMsg {
  Header header;
  uint32_t height = 0, width = 0, step = 0;
  std::string encoding;
  bool bigendian = false;
  const uint8_t* data = nullptr;
  std::size_t size = 0;
};
ImageMsg readImage(Cursor& c) {
  ImageMsg m;
  m.header = readHeader(c);
  m.height = c.u32(), m.width = c.u32();
  m.encoding = c.str();
  m.bigendian = c.u8() != 0;
  m.step = c.u32();
  m.size = c.u32();
  m.data = c.take(m.size);
  return m;
}

// An open bag; rosbag's exceptions become IoErrors naming the file.
std::unique_ptr<rosbag::Bag> openBag(const std::string& path) {
  auto bag = std::make_unique<rosbag::Bag>();
  try {
    bag->open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException&) {
    throw IoError(path, "bag is not indexed (truncated, or its recording was cut): 'rosbag reindex' a copy of it");
  } catch (const std::exception& e) {
    throw IoError(path, std::string("cannot open the bag (truncated, or not a ROS 1 bag?): ") + e.what());
  }
  return bag;
}

struct TopicCheck {
  std::string topic, type, md5;
};
template <class Msg>
TopicCheck expect(const std::string& topic) {
  return {topic, ros::message_traits::DataType<Msg>::value(), ros::message_traits::MD5Sum<Msg>::value()};
}

// Throws unless every topic is in the bag with the expected type.
void checkTopics(const std::string& path, const rosbag::Bag& bag, const std::vector<TopicCheck>& wanted) {
  rosbag::View all(bag);
  std::map<std::string, const rosbag::ConnectionInfo*> by_topic;
  for (const rosbag::ConnectionInfo* c : all.getConnections()) by_topic[c->topic] = c;
  for (const TopicCheck& w : wanted) {
    const auto it = by_topic.find(w.topic);
    if (it == by_topic.end()) {
      std::string have;
      for (const auto& [t, c] : by_topic) have += (have.empty() ? "" : ", ") + t + " [" + c->datatype + "]";
      throw IoError(path, "topic '" + w.topic + "' is not in the bag (it holds: " + (have.empty() ? "nothing" : have) + ")");
    }
    if (it->second->datatype != w.type || (it->second->md5sum != w.md5 && it->second->md5sum != "*"))
      throw IoError(path, "topic '" + w.topic + "' has type " + it->second->datatype + " (md5 " + it->second->md5sum +
                              "), expected " + w.type + " (md5 " + w.md5 + ")");
  }
}

bool hasTopic(const rosbag::Bag& bag, const std::string& topic) {
  rosbag::View v(bag, rosbag::TopicQuery(topic));
  return v.size() > 0;
}

// Calls f(index, cursor) for every message of `topic`; errors name bag, topic and index.
template <class Raw, class F>
void forEachMessage(const std::string& path, const rosbag::Bag& bag, const std::string& topic, F f) {
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  std::size_t k = 0;
  try {
    for (const rosbag::MessageInstance& mi : view) {
      const boost::shared_ptr<Raw> raw = mi.instantiate<Raw>();
      Cursor c(raw->bytes.data(), raw->bytes.size());
      f(k, c, mi);
      ++k;
    }
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(path, "topic '" + topic + "' message " + std::to_string(k) + ": " + e.what());
  }
}

// Poses of child frames in parent frames from /tf and /tf_static.
struct TfTree {
  struct Edge {
    std::string parent;
    std::vector<StampedPose> samples;  // sorted by time; one sample for a static edge
    bool is_static = false;
  };
  std::map<std::string, Edge> by_child;

  // Frames from `from` up to `to` (child first), or empty when `to` is not an ancestor.
  std::vector<std::string> chain(const std::string& from, const std::string& to) const {
    std::vector<std::string> out;
    std::string f = from;
    std::set<std::string> seen;
    while (f != to) {
      const auto it = by_child.find(f);
      if (it == by_child.end() || !seen.insert(f).second) return {};
      out.push_back(f);
      f = it->second.parent;
    }
    return out;
  }
};

void addTransforms(TfTree& tree, Cursor& c, bool is_static) {
  const uint32_t n = c.u32();
  for (uint32_t i = 0; i < n; ++i) {
    const Header h = readHeader(c);
    const std::string child = c.str();
    const Pose T = readPose(c);
    if (child.empty() || h.frame_id.empty()) throw std::invalid_argument("transform with an empty frame name");
    TfTree::Edge& e = tree.by_child[child];
    if (!e.parent.empty() && e.parent != h.frame_id)
      throw std::invalid_argument("frame '" + child + "' has two parents ('" + e.parent + "', '" + h.frame_id + "')");
    e.parent = h.frame_id;
    e.is_static = is_static;
    if (is_static) e.samples = {{h.stamp, T}};
    else e.samples.push_back({h.stamp, T});
  }
}

TfTree readTf(const std::string& path, const rosbag::Bag& bag) {
  TfTree tree;
  for (const char* topic : {kTfStatic, kTf}) {
    if (!hasTopic(bag, topic)) continue;
    checkTopics(path, bag, {expect<tf2_msgs::TFMessage>(topic)});
    const bool st = std::string(topic) == kTfStatic;
    forEachMessage<RawMessage>(path, bag, topic, [&](std::size_t, Cursor& c, const rosbag::MessageInstance&) { addTransforms(tree, c, st); });
  }
  for (auto& [child, e] : tree.by_child)
    std::stable_sort(e.samples.begin(), e.samples.end(), [](const StampedPose& a, const StampedPose& b) { return a.t < b.t; });
  return tree;
}

// T_top_bottom along chain (child-first frame list) at time t.
PoseMiss chainPose(const TfTree& tree, const std::vector<std::string>& chain, double t, double max_gap, Pose& out) {
  out = Pose::Identity();
  for (const std::string& f : chain) {
    const TfTree::Edge& e = tree.by_child.at(f);
    Pose T;
    if (e.is_static) T = e.samples.front().pose;
    else if (const PoseMiss m = poseAtTime(e.samples, t, max_gap, T); m != PoseMiss::None) return m;
    out = T * out;
  }
  return PoseMiss::None;
}

// The robot's odometry T_odom_body(t) and its body frame's name.
struct BagOdometry {
  PoseLookup at;
  std::string body_frame;
};

BagOdometry readOdometry(const std::string& path, const rosbag::Bag& bag, const BagOptions& o, double max_gap,
                         const std::shared_ptr<const TfTree>& tree) {
  BagOdometry odo;
  if (!o.odom_topic.empty()) {
    checkTopics(path, bag, {expect<nav_msgs::Odometry>(o.odom_topic)});
    auto traj = std::make_shared<std::vector<StampedPose>>();
    std::string child;
    forEachMessage<RawMessage>(path, bag, o.odom_topic, [&](std::size_t, Cursor& c, const rosbag::MessageInstance&) {
      const Header h = readHeader(c);
      const std::string ch = c.str();
      if (child.empty()) child = ch;
      traj->push_back({h.stamp, readPose(c)});  // pose.pose; covariance and twist not needed
    });
    if (traj->empty()) throw IoError(path, "topic '" + o.odom_topic + "' holds no odometry");
    std::stable_sort(traj->begin(), traj->end(), [](const StampedPose& a, const StampedPose& b) { return a.t < b.t; });
    odo.body_frame = o.body_frame.empty() ? child : o.body_frame;
    if (odo.body_frame != child) {
      // The configured body frame sits below the odometry's child (T_child_body along the /tf
      // chain body -> child) or above it (the inverse of the chain child -> body), at time t:
      // a moving joint's pose is interpolated like the odometry, and a miss drops the frame.
      std::vector<std::string> ch = tree->chain(odo.body_frame, child);
      const bool inverse = ch.empty();
      if (inverse) ch = tree->chain(child, odo.body_frame);
      if (ch.empty())
        throw IoError(path, "topic '" + o.odom_topic + "': no /tf chain between the odometry's child frame '" + child +
                                "' and body frame '" + odo.body_frame + "' (set sensor_driver.bag.body_frame)");
      odo.at = [traj, tree, ch, inverse, max_gap](double t, Pose& T) {
        Pose T_odom_child, T_chain;
        if (const PoseMiss m = poseAtTime(*traj, t, max_gap, T_odom_child); m != PoseMiss::None) return m;
        if (const PoseMiss m = chainPose(*tree, ch, t, max_gap, T_chain); m != PoseMiss::None) return m;
        T = T_odom_child * (inverse ? Pose(T_chain.inverse()) : T_chain);
        return PoseMiss::None;
      };
    } else {
      odo.at = [traj, max_gap](double t, Pose& T) { return poseAtTime(*traj, t, max_gap, T); };
    }
    return odo;
  }
  odo.body_frame = o.body_frame.empty() ? "base_link" : o.body_frame;
  const std::vector<std::string> ch = tree->chain(odo.body_frame, o.odom_frame);
  if (ch.empty())
    throw IoError(path, "no odometry: no odom topic configured and no /tf chain from '" + o.odom_frame + "' to '" +
                            odo.body_frame + "' (set sensor_driver.bag.odom_topic, odom_frame, body_frame)");
  odo.at = [tree, ch, max_gap](double t, Pose& T) { return chainPose(*tree, ch, t, max_gap, T); };
  return odo;
}

// T_body_sensor from options, or /tf_static (any chain of static edges).
Pose sensorExtrinsic(const std::string& path, const BagOptions& o, const TfTree& tree, const std::string& body,
                     const std::string& sensor_frame, const std::string& topic) {
  if (o.T_body_sensor) return *o.T_body_sensor;
  if (sensor_frame == body || sensor_frame.empty()) return Pose::Identity();
  const std::vector<std::string> ch = tree.chain(sensor_frame, body);
  bool all_static = !ch.empty();
  for (const std::string& f : ch) all_static = all_static && tree.by_child.at(f).is_static;
  if (!all_static)
    throw IoError(path, "topic '" + topic + "': no /tf_static transform from body frame '" + body + "' to sensor frame '" +
                            sensor_frame + "' (set sensor_driver.bag.T_body_sensor in the config)");
  Pose T;
  if (chainPose(tree, ch, 0, 0, T) != PoseMiss::None)  // static edges always have their pose
    throw std::logic_error("static /tf chain without a pose");
  return T;
}

// Header stamps (and frame ids) of a topic, read without decoding the messages.
std::vector<double> stampsOf(const std::string& path, const rosbag::Bag& bag, const std::string& topic,
                             std::vector<rosbag::MessageInstance>& msgs) {
  std::vector<double> t;
  forEachMessage<MessageStamp>(path, bag, topic, [&](std::size_t, Cursor& c, const rosbag::MessageInstance& mi) {
    c.u32();
    const double s = c.stamp();
    t.push_back(s > 0 ? s : mi.getTime().toSec());  // unstamped messages: record time
    msgs.push_back(mi);
  });
  return t;
}

std::string firstFrameId(const std::string& path, const rosbag::Bag& bag, const std::string& topic) {
  std::string id;
  rosbag::View v(bag, rosbag::TopicQuery(topic));
  try {
    for (const rosbag::MessageInstance& mi : v) {
      const auto raw = mi.instantiate<RawMessage>();
      Cursor c(raw->bytes.data(), raw->bytes.size());
      id = readHeader(c).frame_id;
      break;
    }
  } catch (const std::exception& e) {
    throw IoError(path, "topic '" + topic + "' message 0: " + e.what());
  }
  return id;
}

class BagReader : public FrameReader {
 public:
  BagReader(std::string path, std::unique_ptr<rosbag::Bag> bag) : path_(std::move(path)), bag_(std::move(bag)) {}

  std::string path_;
  std::unique_ptr<rosbag::Bag> bag_;
  std::string cloud_topic_, color_topic_, depth_topic_;
  std::vector<rosbag::MessageInstance> clouds_;
  std::vector<std::pair<rosbag::MessageInstance, rosbag::MessageInstance>> images_;  // colour, depth
  std::vector<std::size_t> cloud_index_;                                              // message index per frame id
  std::vector<std::pair<std::size_t, std::size_t>> image_index_;
  Eigen::Isometry3f T_body_sensor_ = Eigen::Isometry3f::Identity();
  PoseLookup odometry_;  // set: deskew with it
  CameraCalib camera_;
  mutable std::atomic<std::size_t> skipped_points_{0}, deskew_dropped_{0};

  LabelledScan scan(std::size_t id) const override {
    if (clouds_.empty()) throw std::logic_error("this bag source has no LiDAR topic");
    const std::string where = "topic '" + cloud_topic_ + "' message " + std::to_string(cloud_index_.at(id));
    try {
      const auto raw = clouds_.at(id).instantiate<RawMessage>();
      Cursor c(raw->bytes.data(), raw->bytes.size());
      const Header h = readHeader(c);
      CloudLayout l;
      l.height = c.u32(), l.width = c.u32();
      const uint32_t nf = c.u32();
      if (nf > 64) throw std::invalid_argument(std::to_string(nf) + " point fields");
      for (uint32_t i = 0; i < nf; ++i) {
        CloudField f;
        f.name = c.str();
        f.offset = c.u32();
        f.datatype = c.u8();
        f.count = c.u32();
        l.fields.push_back(f);
      }
      l.is_bigendian = c.u8() != 0;
      l.point_step = c.u32(), l.row_step = c.u32();
      const uint32_t size = c.u32();
      const uint8_t* data = c.take(size);
      DecodedCloud d = decodeCloud(l, data, size, h.stamp);
      skipped_points_ += d.skipped;
      for (Eigen::Vector3f& p : d.xyz) p = T_body_sensor_ * p;
      LabelledScan s;
      if (odometry_ && !d.time.empty()) {
        const std::vector<uint8_t> ok = deskewSweep(d.xyz, d.time, h.stamp, odometry_);
        for (std::size_t i = 0; i < ok.size(); ++i) {
          if (!ok[i]) {
            ++deskew_dropped_;
            continue;
          }
          s.xyz.push_back(d.xyz[i]);
          s.intensity.push_back(d.intensity[i]);
        }
      } else {
        s.xyz = std::move(d.xyz);
        s.intensity = std::move(d.intensity);
      }
      return s;
    } catch (const std::exception& e) {
      throw IoError(path_, where + ": " + e.what());
    }
  }

  RgbdImages rgbd(std::size_t id) const override {
    if (images_.empty()) throw std::logic_error("this bag source has no RGBD topics");
    RgbdImages f;
    f.color = decodeColor(images_.at(id).first, image_index_.at(id).first);
    f.depth = decodeDepth(images_.at(id).second, image_index_.at(id).second);
    if (f.color.size() != f.depth.size())
      throw IoError(path_, "topic '" + depth_topic_ + "' message " + std::to_string(image_index_[id].second) + ": depth " +
                               std::to_string(f.depth.cols) + "x" + std::to_string(f.depth.rows) + " differs from colour " +
                               std::to_string(f.color.cols) + "x" + std::to_string(f.color.rows) + " (register depth to colour)");
    if (f.color.cols != camera_.width || f.color.rows != camera_.height)
      throw IoError(path_, "topic '" + color_topic_ + "' message " + std::to_string(image_index_[id].first) +
                               ": image size differs from the CameraInfo's " + std::to_string(camera_.width) + "x" +
                               std::to_string(camera_.height));
    return f;
  }

  // Throws IoError naming the topic and message index when the first image of the colour or
  // depth topic has an encoding this reader cannot decode (a corrupt first message is left to
  // rgbd(), which drops its frame).
  void checkFirstEncodings() const {
    for (const bool depth : {false, true}) {
      const rosbag::MessageInstance& mi = depth ? images_.front().second : images_.front().first;
      const std::size_t index = depth ? image_index_.front().second : image_index_.front().first;
      std::string encoding;
      try {
        const boost::shared_ptr<RawMessage> raw = mi.instantiate<RawMessage>();
        Cursor c(raw->bytes.data(), raw->bytes.size());
        encoding = readImage(c).encoding;
      } catch (const std::exception&) {
        continue;
      }
      try {
        checkEncoding(encoding, depth);
      } catch (const std::exception& e) {
        throw IoError(path_, "topic '" + (depth ? depth_topic_ : color_topic_) + "' message " + std::to_string(index) + ": " + e.what());
      }
    }
  }

  std::string dropSummary() const override {
    std::string s;
    if (skipped_points_) s += std::to_string(skipped_points_) + " NaN/zero points skipped";
    if (deskew_dropped_) s += (s.empty() ? "" : ", ") + std::to_string(deskew_dropped_) + " points without a pose for deskew";
    return s;
  }

 private:
  // Throws std::invalid_argument for an encoding other than bgr8/8UC3/rgb8 (colour) or
  // 16UC1/mono16 (millimetres), 32FC1 (metres) (depth).
  static void checkEncoding(const std::string& e, bool depth) {
    if (!depth && e != "bgr8" && e != "8UC3" && e != "rgb8")
      throw std::invalid_argument("unsupported colour encoding '" + e + "' (bgr8, rgb8)");
    if (depth && e != "16UC1" && e != "mono16" && e != "32FC1")
      throw std::invalid_argument("unsupported depth encoding '" + e + "' (16UC1 mm, 32FC1 m)");
  }

  // Throws unless the rows (step bytes each, bpp bytes per pixel) fit in the data.
  static void checkRows(const ImageMsg& m, std::size_t bpp) {
    if (m.step < m.width * bpp) throw std::invalid_argument("step " + std::to_string(m.step) + " is shorter than a row");
    if (static_cast<uint64_t>(m.step) * m.height > m.size)
      throw std::invalid_argument("image data holds " + std::to_string(m.size) + " bytes, rows need " +
                                  std::to_string(static_cast<uint64_t>(m.step) * m.height));
  }

  cv::Mat decodeColor(const rosbag::MessageInstance& mi, std::size_t index) const {
    const std::string where = "topic '" + color_topic_ + "' message " + std::to_string(index);
    try {
      const boost::shared_ptr<RawMessage> raw = mi.instantiate<RawMessage>();
      Cursor c(raw->bytes.data(), raw->bytes.size());
      ImageMsg m = readImage(c);
      if (m.width == 0 || m.height == 0 || m.width > 16384 || m.height > 16384)
        throw std::invalid_argument("image size " + std::to_string(m.width) + "x" + std::to_string(m.height));
      checkEncoding(m.encoding, false);
      const bool bgr = m.encoding != "rgb8";
      checkRows(m, 3);
      cv::Mat out(static_cast<int>(m.height), static_cast<int>(m.width), CV_8UC3);
      for (uint32_t r = 0; r < m.height; ++r) {
        const uint8_t* src = m.data + static_cast<std::size_t>(r) * m.step;
        uint8_t* dst = out.ptr<uint8_t>(static_cast<int>(r));
        if (bgr) std::memcpy(dst, src, m.width * 3u);
        else
          for (uint32_t k = 0; k < m.width; ++k) dst[3 * k] = src[3 * k + 2], dst[3 * k + 1] = src[3 * k + 1], dst[3 * k + 2] = src[3 * k];
      }
      return out;
    } catch (const std::exception& e) {
      throw IoError(path_, where + ": " + e.what());
    }
  }

  cv::Mat decodeDepth(const rosbag::MessageInstance& mi, std::size_t index) const {
    const std::string where = "topic '" + depth_topic_ + "' message " + std::to_string(index);
    try {
      const boost::shared_ptr<RawMessage> raw = mi.instantiate<RawMessage>();
      Cursor c(raw->bytes.data(), raw->bytes.size());
      ImageMsg m = readImage(c);
      if (m.width == 0 || m.height == 0 || m.width > 16384 || m.height > 16384)
        throw std::invalid_argument("image size " + std::to_string(m.width) + "x" + std::to_string(m.height));
      if (m.bigendian) throw std::invalid_argument("big-endian depth is not supported");
      checkEncoding(m.encoding, true);
      const bool mm = m.encoding != "32FC1";
      checkRows(m, mm ? 2 : 4);
      cv::Mat out(static_cast<int>(m.height), static_cast<int>(m.width), CV_16UC1);
      for (uint32_t r = 0; r < m.height; ++r) {
        const uint8_t* src = m.data + static_cast<std::size_t>(r) * m.step;
        uint16_t* dst = out.ptr<uint16_t>(static_cast<int>(r));
        if (mm) {
          std::memcpy(dst, src, m.width * 2u);
        } else {
          for (uint32_t k = 0; k < m.width; ++k) {
            float v;
            std::memcpy(&v, src + 4 * k, 4);
            dst[k] = std::isfinite(v) && v > 0 ? static_cast<uint16_t>(std::min(65535.0f, std::round(v * 1000.0f))) : 0;
          }
        }
      }
      return out;
    } catch (const std::exception& e) {
      throw IoError(path_, where + ": " + e.what());
    }
  }
};

// The first CameraInfo's intrinsics. Images are taken as rectified: a non-zero distortion
// vector is not corrected, and says so once in `warnings`.
CameraCalib readCameraInfo(const std::string& path, const rosbag::Bag& bag, const std::string& topic,
                           std::vector<std::string>& warnings) {
  checkTopics(path, bag, {expect<sensor_msgs::CameraInfo>(topic)});
  CameraCalib cam;
  bool found = false;
  forEachMessage<RawMessage>(path, bag, topic, [&](std::size_t, Cursor& c, const rosbag::MessageInstance&) {
    if (found) return;
    readHeader(c);
    cam.height = static_cast<int>(c.u32()), cam.width = static_cast<int>(c.u32());
    const std::string model = c.str();
    const uint32_t nd = c.u32();
    if (nd > 64) throw std::invalid_argument(std::to_string(nd) + " distortion coefficients");
    bool distorted = false;
    for (uint32_t i = 0; i < nd; ++i) distorted |= c.f64() != 0.0;
    if (distorted)
      warnings.push_back("topic '" + topic + "': CameraInfo has non-zero " + (model.empty() ? "" : model + " ") +
                         "distortion, which is not corrected (images are taken as rectified)");
    double K[9];
    for (double& k : K) k = c.f64();
    cam.fx = K[0], cam.cx = K[2], cam.fy = K[4], cam.cy = K[5];
    if (!(cam.fx > 0 && cam.fy > 0 && cam.width > 0 && cam.height > 0 && std::isfinite(cam.cx) && std::isfinite(cam.cy)))
      throw std::invalid_argument("CameraInfo without a valid K matrix or image size");
    found = true;
  });
  if (!found) throw IoError(path, "topic '" + topic + "' holds no CameraInfo");
  cam.depth_scale = 0.001;  // depth is delivered in millimetres (32FC1 metres converted)
  return cam;
}

// Optical frame (z forward, x right, y down) to the camera's x-forward, z-up frame.
Pose opticalToForward() {
  Pose T = Pose::Identity();
  T.linear() << 0, -1, 0, 0, 0, -1, 1, 0, 0;  // the inverse of R_body_optical
  return T;
}
}  // namespace

std::vector<BagTopicInfo> listBagTopics(const std::string& path) {
  const std::unique_ptr<rosbag::Bag> bag = openBag(path);
  std::map<std::string, BagTopicInfo> topics;
  try {
    rosbag::View all(*bag);
    for (const rosbag::ConnectionInfo* c : all.getConnections()) {
      BagTopicInfo& t = topics[c->topic];
      t.topic = c->topic;
      t.type = c->datatype;
    }
    for (auto& [name, t] : topics) {
      rosbag::View v(*bag, rosbag::TopicQuery(name));
      t.messages = v.size();
      if (t.messages > 0) t.first_s = v.getBeginTime().toSec(), t.last_s = v.getEndTime().toSec();
    }
  } catch (const std::exception& e) {
    throw IoError(path, std::string("cannot read the bag's index: ") + e.what());
  }
  std::vector<BagTopicInfo> out;
  for (auto& [name, t] : topics) out.push_back(t);
  return out;
}

RobotDataset openBagDataset(const std::string& path, const DatasetOptions& options) {
  const BagOptions& o = options.bag;
  const bool lidar = !o.cloud_topic.empty(), rgbd = !o.color_topic.empty() || !o.depth_topic.empty();
  if (lidar == rgbd)
    throw IoError(path, "choose one sensor: a cloud topic (LiDAR) or colour + depth + camera-info topics (RGBD)");
  if (rgbd && (o.color_topic.empty() || o.depth_topic.empty() || o.camera_info_topic.empty()))
    throw IoError(path, "an RGBD bag needs colour, depth and camera-info topics");
  auto reader = std::make_shared<BagReader>(path, openBag(path));
  const rosbag::Bag& bag = *reader->bag_;
  RobotDataset d;
  d.path = path;
  try {
    const auto tree = std::make_shared<const TfTree>(readTf(path, bag));
    const BagOdometry odo = readOdometry(path, bag, o, options.max_odometry_gap_s, tree);
    std::vector<double> times;
    PoseLookup frame_pose = odo.at;
    if (lidar) {
      d.sensor = RobotDataset::Sensor::Lidar;
      checkTopics(path, bag, {expect<sensor_msgs::PointCloud2>(o.cloud_topic)});
      reader->cloud_topic_ = o.cloud_topic;
      times = stampsOf(path, bag, o.cloud_topic, reader->clouds_);
      for (std::size_t k = 0; k < times.size(); ++k) reader->cloud_index_.push_back(k);
      if (times.empty()) throw IoError(path, "topic '" + o.cloud_topic + "' holds no messages");
      reader->T_body_sensor_ =
          sensorExtrinsic(path, o, *tree, odo.body_frame, firstFrameId(path, bag, o.cloud_topic), o.cloud_topic).cast<float>();
      if (o.deskew) reader->odometry_ = odo.at;
    } else {
      d.sensor = RobotDataset::Sensor::Rgbd;
      checkTopics(path, bag, {expect<sensor_msgs::Image>(o.color_topic), expect<sensor_msgs::Image>(o.depth_topic)});
      reader->color_topic_ = o.color_topic, reader->depth_topic_ = o.depth_topic;
      d.camera = readCameraInfo(path, bag, o.camera_info_topic, d.warnings);
      std::vector<rosbag::MessageInstance> color, depth;
      const std::vector<double> tc = stampsOf(path, bag, o.color_topic, color), td = stampsOf(path, bag, o.depth_topic, depth);
      std::vector<std::size_t> order(td.size());
      for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return td[a] < td[b]; });
      for (std::size_t k = 0; k < tc.size(); ++k) {  // nearest depth image within max_color_depth_dt
        const auto it = std::lower_bound(order.begin(), order.end(), tc[k], [&](std::size_t j, double t) { return td[j] < t; });
        std::size_t best = td.size();
        for (auto j = it == order.begin() ? it : std::prev(it); j != order.end() && j <= it; ++j)
          if (std::abs(td[*j] - tc[k]) <= o.max_color_depth_dt && (best == td.size() || std::abs(td[*j] - tc[k]) < std::abs(td[best] - tc[k])))
            best = *j;
        if (best == td.size()) continue;
        reader->images_.push_back({color[k], depth[best]});
        reader->image_index_.push_back({k, best});
        times.push_back(tc[k]);
      }
      if (times.empty())
        throw IoError(path, "no colour image on '" + o.color_topic + "' has a depth image on '" + o.depth_topic + "' within " +
                                std::to_string(o.max_color_depth_dt) + " s");
      reader->checkFirstEncodings();
      const Pose T_body_optical =
          sensorExtrinsic(path, o, *tree, odo.body_frame, firstFrameId(path, bag, o.color_topic), o.color_topic);
      d.camera.T_body_camera = T_body_optical;
      reader->camera_ = d.camera;
      // The segmenter takes a frame's pose as that of the camera's x-forward frame.
      const Pose T_body_forward = T_body_optical * opticalToForward();
      frame_pose = [at = odo.at, T_body_forward](double t, Pose& T) {
        const PoseMiss m = at(t, T);
        T = T * T_body_forward;
        return m;
      };
    }
    keepFramesWithOdometry(d, times, frame_pose);
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(path, std::string("cannot read the bag: ") + e.what());
  }
  d.reader = reader;
  return d;
}

}  // namespace slide::io
