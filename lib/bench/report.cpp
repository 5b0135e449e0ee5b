#include "bench/report.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace slide::bench {

namespace {
std::string cell(const std::optional<double>& v) {
  if (!v) return "-";
  std::ostringstream s;
  s << std::setprecision(4) << *v;
  return s.str();
}
}  // namespace

BenchResult& BenchReport::add(BenchResult r) {
  results_.push_back(std::move(r));
  return results_.back();
}

BenchResult& BenchReport::add(const std::string& name, double value, const std::string& unit, bool lower_is_better,
                              std::optional<double> target, std::optional<double> paper) {
  BenchResult r;
  r.name = name;
  r.value = value;
  r.unit = unit;
  r.lower_is_better = lower_is_better;
  r.target = target;
  r.paper = paper;
  return add(std::move(r));
}

bool BenchReport::meetsTarget(const BenchResult& r) {
  if (!r.target || !std::isfinite(r.value)) return false;
  return r.lower_is_better ? r.value <= *r.target : r.value >= *r.target;
}

void BenchReport::printTable(std::ostream& out) const {
  out << "suite " << suite_ << "\n";
  out << std::left << std::setw(44) << "name" << std::right << std::setw(12) << "value" << std::setw(7) << "unit"
      << std::setw(10) << "target" << std::setw(10) << "paper" << "  ok  note\n";
  for (const BenchResult& r : results_) {
    std::ostringstream v;
    v << std::setprecision(5) << r.value;
    out << std::left << std::setw(44) << r.name << std::right << std::setw(12) << v.str() << std::setw(7) << r.unit
        << std::setw(10) << cell(r.target) << std::setw(10) << cell(r.paper) << "  "
        << (r.target ? (meetsTarget(r) ? "yes " : "NO  ") : "    ") << r.note << "\n";
  }
}

std::string BenchReport::toJson() const {
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  for (const BenchResult& r : results_) {
    nlohmann::ordered_json j;
    j["name"] = r.name;
    j["value"] = r.value;  // NaN and infinities are written as null
    j["unit"] = r.unit;
    if (r.target) j["target"] = *r.target;
    if (r.paper) j["paper"] = *r.paper;
    j["better"] = r.lower_is_better ? "lower" : "higher";
    if (!r.note.empty()) j["note"] = r.note;
    results.push_back(std::move(j));
  }
  nlohmann::ordered_json doc;
  doc["suite"] = suite_;
  doc["results"] = std::move(results);
  return doc.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

void BenchReport::writeJson(const std::string& path) const {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write benchmark JSON");
  out << toJson();
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace slide::bench
