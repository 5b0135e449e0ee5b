#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "plot/canvas.h"
#include "plot/viewport.h"

using namespace slide;
namespace fs = std::filesystem;

TEST(Canvas, PngHasTheShapesWhereTheyWereDrawn) {
  plot::Canvas c(200, 100, {255, 255, 255});
  plot::Style red;
  red.filled = true;
  red.fill = {255, 0, 0};
  red.stroke_width = 0;
  c.polygon({{10, 10}, {60, 10}, {60, 60}, {10, 60}}, red);
  plot::Style half = red;
  half.fill = {0, 0, 255};
  half.fill_opacity = 0.5;
  c.circle({150, 50}, 20, half);
  const std::string path = (fs::temp_directory_path() / ("slide_canvas_" + std::to_string(::getpid()) + ".png")).string();
  c.write(path);
  const cv::Mat img = cv::imread(path);
  fs::remove(path);
  ASSERT_EQ(img.cols, 200);
  ASSERT_EQ(img.rows, 100);
  const cv::Vec3b inside = img.at<cv::Vec3b>(35, 35);  // BGR
  EXPECT_EQ(inside, cv::Vec3b(0, 0, 255));
  EXPECT_EQ(img.at<cv::Vec3b>(90, 100), cv::Vec3b(255, 255, 255));
  const cv::Vec3b blended = img.at<cv::Vec3b>(50, 150);  // half blue over white
  EXPECT_NEAR(blended[0], 255, 2);
  EXPECT_NEAR(blended[1], 127, 3);
  EXPECT_NEAR(blended[2], 127, 3);
}

TEST(Canvas, SvgHasElementsAndEscapesText) {
  plot::Canvas c(300, 200);
  plot::Style s;
  s.dashed = true;
  c.polyline({{0, 0}, {10, 10}}, s);
  c.ellipse({50, 50}, 10, 5, 0.5, s);
  c.text({5, 20}, "a<b & c", 12, {0, 0, 0}, plot::TextAnchor::Middle);
  const std::string svg = c.toSvg();
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"300\" height=\"200\""), std::string::npos);
  EXPECT_NE(svg.find("<polyline points=\"0.00,0.00 10.00,10.00\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.find("<ellipse cx=\"50.00\" cy=\"50.00\" rx=\"10.00\" ry=\"5.00\" transform=\"rotate("), std::string::npos);
  EXPECT_NE(svg.find(">a&lt;b &amp; c</text>"), std::string::npos);
  EXPECT_NE(svg.find("text-anchor=\"middle\""), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(Canvas, RejectsBadOutputs) {
  plot::Canvas c(10, 10);
  EXPECT_THROW(c.write("/tmp/picture.jpg"), std::runtime_error);
  EXPECT_THROW(c.write("/nonexistent-dir/x.svg"), std::runtime_error);
  EXPECT_THROW(c.write("/nonexistent-dir/x.png"), std::runtime_error);
  EXPECT_THROW(plot::Canvas(0, 10), std::invalid_argument);
}

TEST(Viewport, EqualAspectMapsCornersAndCentres) {
  // A 20 x 10 m box into a 400 x 400 px area: 20 px per metre, height grown to 20 m.
  const plot::Viewport vp(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(20, 10)), {50, 50, 400, 400},
                          true);
  EXPECT_DOUBLE_EQ(vp.pixelsPerUnitX(), 20);
  EXPECT_DOUBLE_EQ(vp.pixelsPerUnitY(), 20);
  EXPECT_TRUE(vp.toPixel({10, 5}).isApprox(Eigen::Vector2d(250, 250)));
  EXPECT_TRUE(vp.toPixel({0, 15}).isApprox(Eigen::Vector2d(50, 50)));  // top-left: y up becomes pixels down
  const plot::Viewport free(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(20, 10)), {0, 0, 400, 100},
                            false);
  EXPECT_DOUBLE_EQ(free.pixelsPerUnitX(), 20);
  EXPECT_DOUBLE_EQ(free.pixelsPerUnitY(), 10);
}

TEST(Viewport, NiceTicks) {
  EXPECT_DOUBLE_EQ(plot::niceStep(100, 8), 20);
  EXPECT_DOUBLE_EQ(plot::niceStep(7, 8), 1);
  EXPECT_DOUBLE_EQ(plot::niceStep(0.9, 8), 0.2);
  EXPECT_DOUBLE_EQ(plot::niceStep(35, 8), 5);
  const auto t = plot::ticks(-12, 31, 10);
  ASSERT_EQ(t.size(), 5u);  // -10, 0, 10, 20, 30
  EXPECT_DOUBLE_EQ(t.front(), -10);
  EXPECT_DOUBLE_EQ(t.back(), 30);
  EXPECT_EQ(plot::tickLabel(2.5, 0.5), "2.5");
  EXPECT_EQ(plot::tickLabel(-10, 5), "-10");
  EXPECT_EQ(plot::tickLabel(0.05, 0.05), "0.05");
}
