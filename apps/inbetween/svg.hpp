#pragma once
// A small SVG writer for plots: a fixed-size canvas mapping a data rectangle onto the page (y up),
// polylines, circles and text.  Only what `inbetween curve plot` needs; output is plain, indented
// SVG 1.1 that a person can read.

#include <sstream>
#include <string>
#include <vector>

namespace inbetween::cli {

/// A 2-D point in data coordinates.
struct SvgPoint {
  double x = 0, y = 0;
};

/// Builds an SVG document; call the drawing functions, then str().
class SvgCanvas {
 public:
  /// A canvas `width_px` × `height_px` showing the data box [x0, x1] × [y0, y1] (padded by 5%,
  /// aspect ratio kept).
  SvgCanvas(double width_px, double height_px, double x0, double x1, double y0, double y1);
  /// A polyline through the points.
  void polyline(const std::vector<SvgPoint>& pts, const std::string& stroke, double width_px,
                const std::string& dash = "");
  /// A filled circle of radius `r_px` at p.
  void circle(SvgPoint p, double r_px, const std::string& fill);
  /// Text at the top-left corner, line `row` (0-based).
  void caption(int row, const std::string& text);
  /// The finished document.
  std::string str() const;

 private:
  double map_x(double x) const;
  double map_y(double y) const;
  double w_, h_, x0_, y0_, scale_, off_x_, off_y_;
  std::ostringstream body_;
};

}  // namespace inbetween::cli
