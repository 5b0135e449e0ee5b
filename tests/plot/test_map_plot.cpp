#include <gtest/gtest.h>

#include <cmath>

#include "objects/class_table.h"
#include "plot/map_plot.h"
#include "plot/object_shapes.h"
#include "plot/palette.h"
#include "plot/series_plot.h"

using namespace slide;

namespace {
Object car(double x, double y, double yaw) {
  Object o;
  o.class_id = 10;
  o.model = Cuboid{poseFromXyzYaw(x, y, 0.75, yaw), {4, 2, 1.5}};
  return o;
}
Object trunk(double x, double y) {
  Object o;
  o.class_id = 71;
  o.model = Cylinder{{x, y, 0}, Eigen::Vector3d::UnitZ(), 0.3, 6};
  return o;
}
double area(const std::vector<Eigen::Vector2d>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return 0.5 * a;
}
}  // namespace

TEST(View, TopAndObliqueProjections) {
  const plot::View top = plot::View::top();
  EXPECT_TRUE(top.project({3, 4, 9}).isApprox(Eigen::Vector2d(3, 4), 1e-12));
  EXPECT_TRUE(top.isTop());
  // Looking from -y (azimuth -90) at 30 degrees: x stays right, height z rises by cos 30.
  const plot::View ob = plot::View::oblique(-90, 30);
  EXPECT_TRUE(ob.project({1, 0, 0}).isApprox(Eigen::Vector2d(1, 0), 1e-12));
  EXPECT_NEAR(ob.project({0, 0, 1}).y(), std::cos(M_PI / 6), 1e-12);
  EXPECT_NEAR(ob.project({0, 1, 0}).y(), std::sin(M_PI / 6), 1e-12);
  EXPECT_GT(ob.depth({0, 10, 0}), ob.depth({0, 0, 0}));  // farther from a viewer in -y
}

TEST(ObjectShapes, FacesSeenFromAboveAndAside) {
  // From above, a car is its footprint: one face, 4 x 2 m, rotated with the car.
  const plot::ObjectFacets top = plot::objectFacets(car(5, 5, 0.3), plot::View::top());
  ASSERT_EQ(top.facets.size(), 1u);
  EXPECT_NEAR(std::abs(area(top.facets[0].uv)), 8.0, 1e-9);
  EXPECT_NEAR(std::abs(area(top.silhouette)), 8.0, 1e-9);
  // Obliquely, three faces show (top and two sides), the top in full colour.
  const plot::ObjectFacets ob = plot::objectFacets(car(5, 5, 0.3), plot::View::oblique());
  EXPECT_EQ(ob.facets.size(), 3u);
  // A trunk from above: body and cap are circles of radius 0.3.
  const plot::ObjectFacets t = plot::objectFacets(trunk(0, 0), plot::View::top());
  ASSERT_EQ(t.facets.size(), 2u);
  EXPECT_NEAR(std::abs(area(t.silhouette)), M_PI * 0.09, 0.01);
  // Obliquely its outline is taller than wide.
  const plot::ObjectFacets tb = plot::objectFacets(trunk(0, 0), plot::View::oblique(-90, 30));
  Eigen::AlignedBox2d box;
  for (const auto& p : tb.silhouette) box.extend(p);
  EXPECT_NEAR(box.sizes().x(), 0.6, 1e-3);
  EXPECT_NEAR(box.sizes().y(), 6 * std::cos(M_PI / 6) + 0.6 * std::sin(M_PI / 6), 1e-3);
}

TEST(ObjectShapes, ConvexHull) {
  const auto h = plot::convexHull({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {0.2, 0.8}});
  EXPECT_EQ(h.size(), 4u);
  EXPECT_NEAR(area(h), 1.0, 1e-12);  // counter-clockwise
}

TEST(MapPlot, DrawsObjectsTrajectoriesAndLegend) {
  const ClassTable classes = ClassTable::loadDefault();
  plot::PlotMap est{"robot0 map", {car(0, 0, 0), car(10, 0, 0.5), trunk(5, 5)}, 0, false};
  plot::PlotMap gt{"truth", {car(0.5, 0, 0), trunk(5, 5.5)}, 0, true};
  plot::PlotTrajectory traj{"robot0", {{-5, -5, 0}, {0, -5, 0}, {15, -5, 0}}, 0, false, {}};
  plot::PlotTrajectory gt_traj{"gt", {{-5, -5.5, 0}, {15, -5.5, 0}}, 0, true, {}};
  for (plot::View v : {plot::View::top(), plot::View::oblique()}) {
    plot::MapPlotOptions opts;
    opts.view = v;
    opts.title = "test run";
    const plot::Canvas c = plot::plotMap({est, gt}, {traj, gt_traj}, classes, opts);
    const std::string svg = c.toSvg();
    EXPECT_NE(svg.find(">car (2)</text>"), std::string::npos);
    EXPECT_NE(svg.find(">trunk (1)</text>"), std::string::npos);
    EXPECT_NE(svg.find(">robot0 (20 m)</text>"), std::string::npos);
    EXPECT_NE(svg.find(">test run</text>"), std::string::npos);
    EXPECT_NE(svg.find("ground truth"), std::string::npos);
    EXPECT_NE(svg.find("rgb(220,40,40)"), std::string::npos);  // the car class colour from classes.yaml
    EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);  // truth is dashed
    EXPECT_NE(svg.find(v.isTop() ? ">x [m]</text>" : " m</text>"), std::string::npos);  // axes or scale bar
  }
}

TEST(SeriesPlot, LinesLegendAndErrors) {
  plot::Series s{"robot0", {0, 1, 2}, {0.1, 0.3, 0.2}};
  plot::SeriesPlotOptions o;
  o.title = "ATE";
  o.y_label = "ATE [m]";
  const std::string svg = plot::plotSeries({s}, o).toSvg();
  EXPECT_NE(svg.find(">robot0 (mean 0.2)</text>"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">ATE [m]</text>"), std::string::npos);
  s.y.pop_back();
  EXPECT_THROW(plot::plotSeries({s}, o), std::invalid_argument);
}

TEST(MapPlot, TrajectoryColouredByValueHasAColourBar) {
  plot::PlotTrajectory t{"robot0", {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, 0, false, {0.0, 0.5, 1.0}};
  plot::MapPlotOptions opts;
  opts.values_label = "ATE [m]";
  const std::string svg = plot::plotMap({}, {t}, ClassTable(), opts).toSvg();
  EXPECT_NE(svg.find(">ATE [m]</text>"), std::string::npos);
  // Segment colours: the ramp at each segment's mean value (0.25 and 0.75 of the range).
  for (double v : {0.25, 0.75}) {
    const plot::Rgb c = plot::rampColour(v);
    const std::string stroke =
        "stroke=\"rgb(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")\"";
    EXPECT_NE(svg.find(stroke), std::string::npos) << stroke;
  }
  EXPECT_EQ(plot::rampColour(0).r, 68);
  EXPECT_EQ(plot::rampColour(1).g, 231);
  EXPECT_EQ(plot::rampColour(std::nan("")).r, 68);
}

TEST(MapPlot, ScoringOverlayIsDrawnAndExplained) {
  const ClassTable classes = ClassTable::loadDefault();
  plot::PlotMap est{"est", {car(0, 0, 0), car(30, 0, 0)}, 0, false};
  plot::PlotMap gt{"gt", {car(0.5, 0, 0), car(15, 0, 0)}, 0, true};
  plot::MapPlotOptions opts;
  opts.overlay.matches.push_back({{0, 0, 0.75}, {0.5, 0, 0.75}});
  opts.overlay.false_positives.push_back({30, 0, 0.75});
  opts.overlay.missed.push_back({15, 0, 0.75});
  const std::string svg = plot::plotMap({est, gt}, {}, classes, opts).toSvg();
  EXPECT_NE(svg.find(">match (1)</text>"), std::string::npos);
  EXPECT_NE(svg.find(">x false positive (1)</text>"), std::string::npos);
  EXPECT_NE(svg.find(">o missed (1)</text>"), std::string::npos);
  EXPECT_NE(svg.find("stroke=\"rgb(230,0,0)\""), std::string::npos);
}
