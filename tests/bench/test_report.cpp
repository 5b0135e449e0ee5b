#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "bench/report.h"
#include "bench/stats.h"

using namespace slide;

TEST(BenchStats, Quantiles) {
  EXPECT_DOUBLE_EQ(median({3, 1, 2}), 2);
  EXPECT_DOUBLE_EQ(median({4, 1, 2, 3}), 2.5);
  EXPECT_DOUBLE_EQ(quantile({0, 10}, 0.99), 9.9);
  EXPECT_TRUE(std::isnan(median({})));
  EXPECT_DOUBLE_EQ(mean({1, 2, 3, 6}), 3);
}

TEST(BenchReport, JsonFollowsConvention) {
  BenchReport r("backend");
  r.add("forest.update_ms.median", 3.2, "ms", true, 5.0, 36.46);
  r.add("forest.landmarks", 860, "", false).note = "confirmed \"landmarks\"";
  r.add("forest.bad", NAN, "m");
  const std::string j = r.toJson();
  EXPECT_NE(j.find("\"suite\": \"backend\""), std::string::npos);
  EXPECT_NE(j.find("{\"name\": \"forest.update_ms.median\", \"value\": 3.2, \"unit\": \"ms\", \"target\": 5, "
                   "\"paper\": 36.46, \"better\": \"lower\"}"),
            std::string::npos)
      << j;
  EXPECT_NE(j.find("\"better\": \"higher\""), std::string::npos);
  EXPECT_NE(j.find("\\\"landmarks\\\""), std::string::npos);
  EXPECT_NE(j.find("\"value\": null"), std::string::npos);
  EXPECT_TRUE(BenchReport::meetsTarget(r.results()[0]));
  EXPECT_FALSE(BenchReport::meetsTarget(r.results()[1]));
  std::ostringstream table;
  r.printTable(table);
  EXPECT_NE(table.str().find("forest.update_ms.median"), std::string::npos);
}
