#include "plot/canvas.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace slide::plot {

namespace {
constexpr int kShift = 4;  // OpenCV fixed-point sub-pixel bits
constexpr double kScale = 1 << kShift;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontCapHeight = 22.0;  // cap height of kFont at scale 1, pixels

cv::Scalar bgr(Rgb c) { return cv::Scalar(c.b, c.g, c.r); }

std::vector<cv::Point> fixedPoint(const std::vector<Eigen::Vector2d>& pts) {
  std::vector<cv::Point> out;
  out.reserve(pts.size());
  for (const auto& p : pts) out.emplace_back(cvRound(p.x() * kScale), cvRound(p.y() * kScale));
  return out;
}

std::vector<Eigen::Vector2d> ellipsePoints(const Eigen::Vector2d& c, double rx, double ry, double angle) {
  const int n = std::clamp(static_cast<int>(std::max(rx, ry)), 24, 180);
  std::vector<Eigen::Vector2d> out;
  const double ca = std::cos(angle), sa = std::sin(angle);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    const double x = rx * std::cos(t), y = ry * std::sin(t);
    out.emplace_back(c.x() + ca * x - sa * y, c.y() + sa * x + ca * y);
  }
  return out;
}

// Splits a polyline into dash segments of `on` pixels separated by `off` pixels.
std::vector<std::vector<Eigen::Vector2d>> dashes(const std::vector<Eigen::Vector2d>& pts, double on, double off) {
  std::vector<std::vector<Eigen::Vector2d>> out;
  bool drawing = true;
  double left = on;
  std::vector<Eigen::Vector2d> cur;
  if (!pts.empty()) cur.push_back(pts[0]);
  for (std::size_t i = 1; i < pts.size(); ++i) {
    Eigen::Vector2d a = pts[i - 1];
    const Eigen::Vector2d b = pts[i];
    double seg = (b - a).norm();
    while (seg > left) {
      const Eigen::Vector2d m = a + (b - a) * (left / seg);
      if (drawing) {
        cur.push_back(m);
        out.push_back(cur);
        cur.clear();
      } else {
        cur = {m};
      }
      seg -= left;
      a = m;
      drawing = !drawing;
      left = drawing ? on : off;
    }
    left -= seg;
    if (drawing) cur.push_back(b);
  }
  if (drawing && cur.size() > 1) out.push_back(cur);
  return out;
}

void fillBlended(cv::Mat& img, const std::vector<Eigen::Vector2d>& pts, Rgb colour, double opacity) {
  if (pts.size() < 3 || opacity <= 0) return;
  const auto fp = fixedPoint(pts);
  cv::Rect box = cv::boundingRect(fp);
  box = cv::Rect(box.x >> kShift, box.y >> kShift, (box.width >> kShift) + 3, (box.height >> kShift) + 3) &
        cv::Rect(0, 0, img.cols, img.rows);
  if (box.empty()) return;
  if (opacity >= 1.0) {
    cv::fillPoly(img, std::vector<std::vector<cv::Point>>{fp}, bgr(colour), cv::LINE_AA, kShift);
    return;
  }
  cv::Mat roi = img(box);
  cv::Mat layer = roi.clone();
  std::vector<cv::Point> local;
  for (const auto& p : fp) local.emplace_back(p.x - (box.x << kShift), p.y - (box.y << kShift));
  cv::fillPoly(layer, std::vector<std::vector<cv::Point>>{local}, bgr(colour), cv::LINE_AA, kShift);
  cv::addWeighted(layer, opacity, roi, 1.0 - opacity, 0.0, roi);
}

void stroke(cv::Mat& img, const std::vector<Eigen::Vector2d>& pts, bool closed, const Style& s) {
  if (s.stroke_width <= 0 || pts.size() < 2) return;
  const int th = std::max(1, static_cast<int>(std::lround(s.stroke_width)));
  std::vector<Eigen::Vector2d> path = pts;
  if (closed) path.push_back(pts.front());
  std::vector<std::vector<Eigen::Vector2d>> parts;
  if (s.dashed)
    parts = dashes(path, 6 + 2 * s.stroke_width, 4 + s.stroke_width);
  else
    parts = {path};
  std::vector<std::vector<cv::Point>> fp;
  for (const auto& p : parts) fp.push_back(fixedPoint(p));
  cv::polylines(img, fp, false, bgr(s.stroke), th, cv::LINE_AA, kShift);
}

std::string svgColour(Rgb c) {
  std::ostringstream s;
  s << "rgb(" << c.r << ',' << c.g << ',' << c.b << ')';
  return s.str();
}

std::string svgEscape(const std::string& t) {
  std::string out;
  for (char c : t) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string svgStyle(const Style& s) {
  std::ostringstream o;
  o << " fill=\"" << (s.filled ? svgColour(s.fill) : "none") << "\"";
  if (s.filled && s.fill_opacity < 1.0) o << " fill-opacity=\"" << s.fill_opacity << "\"";
  if (s.stroke_width > 0) {
    o << " stroke=\"" << svgColour(s.stroke) << "\" stroke-width=\"" << s.stroke_width << "\"";
    if (s.dashed) o << " stroke-dasharray=\"" << 6 + 2 * s.stroke_width << ',' << 4 + s.stroke_width << "\"";
    o << " stroke-linejoin=\"round\"";
  } else {
    o << " stroke=\"none\"";
  }
  return o.str();
}

std::string svgPoints(const std::vector<Eigen::Vector2d>& pts) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(2);
  for (std::size_t i = 0; i < pts.size(); ++i) o << (i ? " " : "") << pts[i].x() << ',' << pts[i].y();
  return o.str();
}
}  // namespace

Canvas::Canvas(int width, int height, Rgb background) : width_(width), height_(height), background_(background) {
  if (width <= 0 || height <= 0 || width > 20000 || height > 20000)
    throw std::invalid_argument("canvas size must be 1..20000 pixels, got " + std::to_string(width) + "x" +
                                std::to_string(height));
}

void Canvas::polyline(const std::vector<Eigen::Vector2d>& pts, const Style& style) {
  items_.push_back({Kind::Polyline, pts, 0, 0, 0, "", 0, TextAnchor::Start, style});
}

void Canvas::polygon(const std::vector<Eigen::Vector2d>& pts, const Style& style) {
  items_.push_back({Kind::Polygon, pts, 0, 0, 0, "", 0, TextAnchor::Start, style});
}

void Canvas::ellipse(const Eigen::Vector2d& centre, double rx, double ry, double angle, const Style& style) {
  items_.push_back({Kind::Ellipse, {centre}, std::abs(rx), std::abs(ry), angle, "", 0, TextAnchor::Start, style});
}

void Canvas::text(const Eigen::Vector2d& pos, const std::string& s, double size, Rgb colour, TextAnchor anchor) {
  Style st;
  st.stroke = colour;
  items_.push_back({Kind::Text, {pos}, 0, 0, 0, s, size, anchor, st});
}

double Canvas::textWidth(const std::string& s, double size) {
  int baseline = 0;
  const double scale = size / kFontCapHeight;
  return cv::getTextSize(s, kFont, scale, size < 16 ? 1 : 2, &baseline).width;
}

void Canvas::writePng(const std::string& path) const {
  cv::Mat img(height_, width_, CV_8UC3, bgr(background_));
  for (const Item& it : items_) {
    switch (it.kind) {
      case Kind::Polyline: stroke(img, it.pts, false, it.style); break;
      case Kind::Polygon:
        if (it.style.filled) fillBlended(img, it.pts, it.style.fill, it.style.fill_opacity);
        stroke(img, it.pts, true, it.style);
        break;
      case Kind::Ellipse: {
        const auto pts = ellipsePoints(it.pts[0], it.rx, it.ry, it.angle);
        if (it.style.filled) fillBlended(img, pts, it.style.fill, it.style.fill_opacity);
        stroke(img, pts, true, it.style);
        break;
      }
      case Kind::Text: {
        const double scale = it.size / kFontCapHeight;
        const int th = it.size < 16 ? 1 : 2;
        double x = it.pts[0].x();
        if (it.anchor != TextAnchor::Start) {
          const double w = textWidth(it.text, it.size);
          x -= it.anchor == TextAnchor::Middle ? w / 2 : w;
        }
        cv::putText(img, it.text, cv::Point(cvRound(x), cvRound(it.pts[0].y())), kFont, scale, bgr(it.style.stroke), th,
                    cv::LINE_AA);
        break;
      }
    }
  }
  bool ok = false;
  try {
    ok = cv::imwrite(path, img);
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path + ": cannot write PNG (" + e.what() + ")");
  }
  if (!ok) throw std::runtime_error(path + ": cannot write PNG");
}

std::string Canvas::toSvg() const {
  std::ostringstream o;
  o << std::fixed << std::setprecision(2);
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_ << "\" height=\"" << height_ << "\" viewBox=\"0 0 "
    << width_ << ' ' << height_ << "\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"" << svgColour(background_) << "\"/>\n";
  for (const Item& it : items_) {
    switch (it.kind) {
      case Kind::Polyline:
        o << "<polyline points=\"" << svgPoints(it.pts) << "\"" << svgStyle(Style{it.style.stroke, it.style.stroke_width,
                                                                               it.style.dashed}) << " stroke-linecap=\"round\"/>\n";
        break;
      case Kind::Polygon: o << "<polygon points=\"" << svgPoints(it.pts) << "\"" << svgStyle(it.style) << "/>\n"; break;
      case Kind::Ellipse:
        o << "<ellipse cx=\"" << it.pts[0].x() << "\" cy=\"" << it.pts[0].y() << "\" rx=\"" << it.rx << "\" ry=\""
          << it.ry << "\"";
        if (it.angle != 0)
          o << " transform=\"rotate(" << it.angle * 180 / M_PI << ' ' << it.pts[0].x() << ' ' << it.pts[0].y() << ")\"";
        o << svgStyle(it.style) << "/>\n";
        break;
      case Kind::Text: {
        const char* anchor = it.anchor == TextAnchor::Start ? "start" : it.anchor == TextAnchor::Middle ? "middle" : "end";
        o << "<text x=\"" << it.pts[0].x() << "\" y=\"" << it.pts[0].y() << "\" font-family=\"Helvetica, Arial, sans-serif\""
          << " font-size=\"" << it.size / 0.72 << "\" text-anchor=\"" << anchor << "\" fill=\""
          << svgColour(it.style.stroke) << "\">" << svgEscape(it.text) << "</text>\n";
        break;
      }
    }
  }
  o << "</svg>\n";
  return o.str();
}

void Canvas::writeSvg(const std::string& path) const {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write SVG");
  out << toSvg();
  if (!out) throw std::runtime_error(path + ": write failed");
}

void Canvas::write(const std::string& path) const {
  auto endsWith = [&](const std::string& e) {
    return path.size() >= e.size() && std::equal(e.rbegin(), e.rend(), path.rbegin(),
                                                 [](char a, char b) { return std::tolower(a) == std::tolower(b); });
  };
  if (endsWith(".png")) return writePng(path);
  if (endsWith(".svg")) return writeSvg(path);
  throw std::runtime_error(path + ": output must end in .png or .svg");
}

}  // namespace slide::plot
