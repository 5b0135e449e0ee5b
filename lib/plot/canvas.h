#pragma once
// A picture as a list of drawing primitives in pixel coordinates (x right, y down), written
// as PNG (rasterised with OpenCV, anti-aliased) or SVG (written by hand). Whoever draws decides
// where things go; the canvas only records and renders.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace slide::plot {

struct Rgb {
  int r = 0, g = 0, b = 0;
};

struct Style {
  Rgb stroke{0, 0, 0};
  double stroke_width = 1.0;  // pixels; 0 draws no outline
  bool dashed = false;
  bool filled = false;
  Rgb fill{255, 255, 255};
  double fill_opacity = 1.0;  // 0..1
};

enum class TextAnchor { Start, Middle, End };

class Canvas {
 public:
  Canvas(int width, int height, Rgb background = {255, 255, 255});

  int width() const { return width_; }
  int height() const { return height_; }

  void polyline(const std::vector<Eigen::Vector2d>& pts, const Style& style);  // open
  void polygon(const std::vector<Eigen::Vector2d>& pts, const Style& style);   // closed
  // Ellipse with semi-axes rx, ry (pixels), rotated by angle (radians, clockwise on screen).
  void ellipse(const Eigen::Vector2d& centre, double rx, double ry, double angle, const Style& style);
  void circle(const Eigen::Vector2d& centre, double r, const Style& style) { ellipse(centre, r, r, 0, style); }
  // Text whose baseline passes through pos; size is the cap height in pixels, roughly.
  void text(const Eigen::Vector2d& pos, const std::string& s, double size, Rgb colour,
            TextAnchor anchor = TextAnchor::Start);
  // Approximate width in pixels of text at a size (to lay out legends and labels).
  static double textWidth(const std::string& s, double size);

  // Writes PNG or SVG by the path's extension (.png, .svg); throws std::runtime_error naming
  // the path when the extension is unknown or the file cannot be written.
  void write(const std::string& path) const;
  void writePng(const std::string& path) const;
  void writeSvg(const std::string& path) const;
  std::string toSvg() const;
  std::size_t size() const { return items_.size(); }

 private:
  enum class Kind { Polyline, Polygon, Ellipse, Text };
  struct Item {
    Kind kind;
    std::vector<Eigen::Vector2d> pts;  // polyline/polygon points; ellipse centre; text position
    double rx = 0, ry = 0, angle = 0;  // ellipse
    std::string text;
    double size = 0;
    TextAnchor anchor = TextAnchor::Start;
    Style style;
  };
  int width_, height_;
  Rgb background_;
  std::vector<Item> items_;
};

}  // namespace slide::plot
