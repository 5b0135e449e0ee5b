#include <gtest/gtest.h>

#include <cmath>

#include "report/json.h"
#include "report/suite_runs.h"

using namespace slide;

TEST(Json, ParsesAndDumpsRoundTrip) {
  const report::Json j =
      report::parseJson(R"({"a": [1, 2.5, -3e2, true, false, null], "s": "x\"y\\z\u00e9\n", "o": {}})");
  const auto& a = j.at("a");
  ASSERT_EQ(a.size(), 6u);
  EXPECT_DOUBLE_EQ(a[1].get<double>(), 2.5);
  EXPECT_DOUBLE_EQ(a[2].get<double>(), -300);
  EXPECT_TRUE(a[3].get<bool>());
  EXPECT_TRUE(a[5].is_null());
  EXPECT_EQ(j.at("s").get<std::string>(), "x\"y\\z\xc3\xa9\n");
  EXPECT_TRUE(j.at("o").is_object());
  const report::Json back = report::parseJson(j.dump());
  EXPECT_EQ(back.dump(0), j.dump(0));
  EXPECT_EQ(report::Json(std::nan("")).dump(), "null");
  EXPECT_EQ(report::Json(3).dump(), "3");
}

TEST(Json, ErrorsGiveLineAndColumn) {
  try {
    report::parseJson("{\n  \"a\": [1, 2,]\n}", "f.json");
    FAIL();
  } catch (const report::JsonError& e) {
    EXPECT_NE(std::string(e.what()).find("f.json: line 2, column 14"), std::string::npos) << e.what();
  }
  EXPECT_THROW(report::parseJson("{\"a\": 1} x"), report::JsonError);
  EXPECT_THROW(report::parseJson("\"unterminated"), report::JsonError);
  EXPECT_THROW(report::parseJson("01x"), report::JsonError);
  EXPECT_THROW(report::parseJson(""), report::JsonError);
  EXPECT_THROW(report::parseJson("[1,]"), report::JsonError);
  EXPECT_THROW(report::Json(1.0).get<std::string>(), report::Json::type_error);
}

TEST(SuiteResults, ParsesTheBenchmarkConvention) {
  const report::Json doc = report::parseJson(R"({"suite": "backend", "results": [
    {"name": "forest.update_ms.median", "value": 3.2, "unit": "ms", "target": 5.0, "paper": 36.46, "better": "lower"},
    {"name": "forest.f1", "value": null, "unit": "", "better": "higher"}]})");
  const auto r = report::parseSuiteResults(doc, "b.json");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].name, "forest.update_ms.median");
  EXPECT_DOUBLE_EQ(*r[0].target, 5.0);
  EXPECT_DOUBLE_EQ(*r[0].paper, 36.46);
  EXPECT_TRUE(r[0].lower_is_better);
  EXPECT_TRUE(std::isnan(r[1].value));
  EXPECT_FALSE(r[1].lower_is_better);
  EXPECT_FALSE(r[1].target.has_value());
  EXPECT_THROW(report::parseSuiteResults(report::parseJson(R"({"results": [{"value": 1}]})"), "x.json"),
               report::JsonError);
  EXPECT_THROW(report::parseSuiteResults(
                   report::parseJson(R"({"results": [{"name": "a", "value": 1, "better": "up"}]})"), "x.json"),
               report::JsonError);
  EXPECT_THROW(report::parseSuiteResults(report::parseJson(R"({"suite": "a"})"), "x.json"), report::JsonError);
}

TEST(SuiteResults, MarkdownMarksPassAndFail) {
  report::SuiteRun run;
  run.suite = "place";
  bench::BenchResult ok;
  ok.name = "kitti05.slidematch.trans_err_m";
  ok.value = 0.2;
  ok.unit = "m";
  ok.target = 0.5;
  ok.paper = 0.245;
  bench::BenchResult bad = ok;
  bad.name = "kitti05.slidematch.yaw_err_deg";
  bad.value = 7;
  bad.unit = "deg";
  bad.target = 5;
  run.results = {ok, bad};
  report::SuiteRun missing;
  missing.suite = "team";
  missing.status = report::SuiteRun::Status::Missing;
  missing.problem = "no executable";
  const std::string md =
      report::markdownReport({run, missing}, {12.5, "2026-01-01T00:00:00Z", "host", "./slide bench"});
  EXPECT_NE(md.find("| kitti05.slidematch.trans_err_m | 0.2 | m | <= 0.5 | 0.245 | pass |"), std::string::npos) << md;
  EXPECT_NE(md.find("| kitti05.slidematch.yaw_err_deg | 7 | deg | <= 5 | 0.245 | **FAIL** |"), std::string::npos) << md;
  EXPECT_NE(md.find("| team | missing | - |"), std::string::npos) << md;
  EXPECT_NE(md.find("## Figures that miss their target"), std::string::npos) << md;
  EXPECT_NE(md.find("| place | kitti05.slidematch.yaw_err_deg | 7 | deg | <= 5 | 0.245 |"), std::string::npos) << md;
  EXPECT_NE(md.find("total wall time: 12.5 s"), std::string::npos) << md;
  const report::Json j = report::combinedJson({run, missing}, {12.5, "", "", ""});
  EXPECT_EQ(j.at("totals").at("targets").get<double>(), 2);
  EXPECT_EQ(j.at("totals").at("targets_met").get<double>(), 1);
  EXPECT_EQ(j.at("totals").at("missing").get<double>(), 1);
}
