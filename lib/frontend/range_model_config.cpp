#include "frontend/range_model_config.h"

#include <filesystem>

#include "config/config.h"

namespace slide::frontend {

namespace {
RangeChannel channelOf(const ConfigNode& n, const std::string& key, const std::string& name) {
  if (name == "range") return RangeChannel::Range;
  if (name == "x") return RangeChannel::X;
  if (name == "y") return RangeChannel::Y;
  if (name == "z") return RangeChannel::Z;
  if (name == "remission" || name == "intensity") return RangeChannel::Remission;
  n.fail(key, "unknown channel '" + name + "' (known: range, x, y, z, remission)");
}
}  // namespace

// Reads projection keys present in `n` into `p` (shared with the front-end config's override).
void readRangeProjection(const ConfigNode& n, RangeProjection& p) {
  n.read("height", p.height);
  n.read("width", p.width);
  n.read("fov_up_deg", p.fov_up_deg);
  n.read("fov_down_deg", p.fov_down_deg);
  n.read("search_rows", p.search_rows);
  n.read("search_cols", p.search_cols);
  if (p.height < 1 || p.height > 4096) n.fail("height", "must be 1..4096");
  if (p.width < 1 || p.width > 65536) n.fail("width", "must be 1..65536");
  if (!(p.fov_up_deg > p.fov_down_deg) || p.fov_up_deg > 90 || p.fov_down_deg < -90)
    n.fail("fov_up_deg", "must exceed fov_down_deg, both within -90..90 degrees");
  if (p.search_rows < 0 || p.search_rows > 16) n.fail("search_rows", "must be 0..16");
  if (p.search_cols < 0 || p.search_cols > 64) n.fail("search_cols", "must be 0..64");
}

RangeModelConfig loadRangeModelConfig(const std::string& path) {
  const ConfigNode root = ConfigNode::load(path);
  RangeModelConfig c;
  c.file = path;
  const std::filesystem::path model = root.get<std::string>("model");
  c.model_path = model.is_absolute() ? model.string() : (std::filesystem::path(path).parent_path() / model).string();
  readRangeProjection(root.child("projection"), c.projection);
  for (const std::string& name : root.getList<std::string>("channels"))
    c.channels.push_back(channelOf(root, "channels", name));
  if (c.channels.empty() || c.channels.size() > 16) root.fail("channels", "expected 1..16 channels");
  c.means = root.getList<float>("means", static_cast<int>(c.channels.size()));
  c.stds = root.getList<float>("stds", static_cast<int>(c.channels.size()));
  for (float s : c.stds)
    if (!(s > 0)) root.fail("stds", "every std must be positive");
  const std::string scores = root.get<std::string>("scores", "logits");
  if (scores != "logits" && scores != "probabilities") root.fail("scores", "expected logits or probabilities, got '" + scores + "'");
  c.logits = scores == "logits";
  const ConfigNode classes = root.child("classes");
  if (classes.size() < 2 || classes.size() > 1000) root.fail("classes", "expected a list of 2..1000 classes");
  for (std::size_t k = 0; k < classes.size(); ++k) {
    const ConfigNode e = classes[k];
    RangeModelClass mc;
    mc.name = e.get<std::string>("name");
    const int label = e.get<int>("label");
    if (label < 0 || label > 65535) e.fail("label", "must be a SemanticKITTI class id 0..65535");
    mc.label = static_cast<uint16_t>(label);
    c.classes.push_back(mc);
  }
  root.rejectUnknownKeys();
  return c;
}

}  // namespace slide::frontend
