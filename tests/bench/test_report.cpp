#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

#include "bench/report.h"
#include "bench/stats.h"

using namespace slide;

TEST(BenchStats, Quantiles) {
  EXPECT_DOUBLE_EQ(bench::median({3, 1, 2}), 2);
  EXPECT_DOUBLE_EQ(bench::median({4, 1, 2, 3}), 2.5);
  EXPECT_DOUBLE_EQ(bench::quantile({0, 10}, 0.99), 9.9);
  EXPECT_TRUE(std::isnan(bench::median({})));
  EXPECT_DOUBLE_EQ(bench::mean({1, 2, 3, 6}), 3);
}

TEST(BenchStats, SlopeOfALine) {
  EXPECT_NEAR(bench::slope({1, 2, 3, 4}, {-0.01, -0.02, -0.03, -0.04}), -0.01, 1e-12);
  EXPECT_NEAR(bench::slope({0, 1, 2, 3}, {5, 5.5, 4.5, 5}), -0.1, 1e-12);
  EXPECT_TRUE(std::isnan(bench::slope({1, 2}, {1, 2})));
  EXPECT_TRUE(std::isnan(bench::slope({2, 2, 2}, {1, 2, 3})));
}

TEST(BenchReport, JsonFollowsConvention) {
  bench::BenchReport r("backend");
  r.add("forest.update_ms.median", 3.2, "ms", true, 5.0, 36.46);
  r.add("forest.landmarks", 860, "", false).note = "confirmed \"landmarks\"";
  r.add("forest.bad", NAN, "m");
  const auto j = nlohmann::json::parse(r.toJson());
  EXPECT_EQ(j.at("suite"), "backend");
  const auto& first = j.at("results").at(0);
  EXPECT_EQ(first.at("name"), "forest.update_ms.median");
  EXPECT_DOUBLE_EQ(first.at("value").get<double>(), 3.2);
  EXPECT_EQ(first.at("unit"), "ms");
  EXPECT_DOUBLE_EQ(first.at("target").get<double>(), 5);
  EXPECT_DOUBLE_EQ(first.at("paper").get<double>(), 36.46);
  EXPECT_EQ(first.at("better"), "lower");
  EXPECT_FALSE(first.contains("note"));
  EXPECT_EQ(j.at("results").at(1).at("better"), "higher");
  EXPECT_EQ(j.at("results").at(1).at("note"), "confirmed \"landmarks\"");
  EXPECT_FALSE(j.at("results").at(1).contains("target"));
  EXPECT_TRUE(j.at("results").at(2).at("value").is_null());
  EXPECT_TRUE(bench::BenchReport::meetsTarget(r.results()[0]));
  EXPECT_FALSE(bench::BenchReport::meetsTarget(r.results()[1]));
  std::ostringstream table;
  r.printTable(table);
  EXPECT_NE(table.str().find("forest.update_ms.median"), std::string::npos);
}
