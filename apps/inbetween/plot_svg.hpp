#pragma once
// The drawing layer of `inbetween plot`: an XML-escaping SVG writer whose numbers are the shortest
// text that reads back to the same double (std::to_chars), and a Panel that maps a data rectangle
// onto a pixel rectangle and draws its axes, tick labels, units and legend.  A reader (a person or
// tests/apps/plot_check.py) recovers the data of every drawn point from the tick labels alone.
//
// Machine-readable marks, so that a test can check a plot against `bake` (docs/plots.md):
// - every panel is <g class="panel">; each tick is <g class="tick-x|tick-y|tick-x2"> holding a
//   <line> at the tick's pixel position and a <text> with its label (frames, values, seconds);
// - every drawn data line is <polyline class="data"> with data-x and data-y (what each axis shows:
//   "frame", a bake column, angle_deg(PREFIX) or derivative(COLUMN)) and data-frames (the frame of
//   each point, in order); every key or position dot is <circle class="data"> with data-frame.

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "inbetween/math/vec.hpp"

namespace inbetween::cli {

/// The shortest text that reads back to the same double ("-0" as "0"), as std::to_chars writes it.
std::string svg_number(double v);

/// `text` with &, <, >, " and ' replaced by their XML entities.
std::string xml_escape(std::string_view text);

/// One attribute: name and (unescaped) value.
using SvgAttr = std::pair<std::string_view, std::string>;

/// An SVG document written element by element, indented; attribute values and text are escaped.
class SvgDocument {
 public:
  /// A document `width_px` × `height_px` with a white background and `title` as its <title>.
  SvgDocument(double width_px, double height_px, std::string_view title);
  /// Opens <tag attrs…>; close() ends it.
  void open(std::string_view tag, const std::vector<SvgAttr>& attrs = {});
  /// Closes the innermost open element.
  void close();
  /// An empty element <tag attrs…/>.
  void leaf(std::string_view tag, const std::vector<SvgAttr>& attrs);
  /// <tag attrs…>text</tag>.
  void text(std::string_view tag, const std::vector<SvgAttr>& attrs, std::string_view content);
  /// The finished document (closes what is still open).
  [[nodiscard]] std::string str();
  /// Width and height in pixels.
  [[nodiscard]] double width() const noexcept { return width_; }
  [[nodiscard]] double height() const noexcept { return height_; }  ///< see width()

 private:
  void attrs_out(const std::vector<SvgAttr>& attrs);
  std::string out_;
  std::vector<std::string> open_;
  double width_, height_;
};

/// Tick values for an axis over [lo, hi]: multiples of a step 1, 2 or 5 × 10^k giving about
/// `target` ticks, all inside [lo, hi] (lo < hi).
std::vector<double> nice_ticks(double lo, double hi, int target);

/// [lo, hi] widened to contain every finite value of `values`, then padded by `pad` of its width
/// (a zero width becomes ±max(1, |value|)·0.5).  Returns {0, 1} when nothing is finite.
std::pair<double, double> padded_range(const std::vector<double>& values, double pad);

/// One legend entry: a line style and a name.
struct LegendEntry {
  std::string label;   ///< what the line shows
  std::string colour;  ///< stroke colour
  std::string dash;    ///< stroke-dasharray ("" solid)
  bool dot = false;    ///< a dot instead of a line
};

/// A rectangular plot area with a linear data → pixel map (y up unless flipped).
class Panel {
 public:
  /// The pixel rectangle [left, left + width] × [top, top + height] showing [x0, x1] × [y0, y1];
  /// flip_x (flip_y) makes x grow leftwards (y downwards), as in a view from the other side.
  Panel(double left, double top, double width, double height, double x0, double x1, double y0, double y1,
        bool flip_x = false, bool flip_y = false);
  /// Makes both axes the same scale (pixels per unit) by widening the smaller-scale range about
  /// its centre (path views: a circle stays round).
  void equal_aspect();
  /// Pixel x of data x.
  [[nodiscard]] double px(double x) const noexcept;
  /// Pixel y of data y.
  [[nodiscard]] double py(double y) const noexcept;
  /// Data x range.
  [[nodiscard]] std::pair<double, double> x_range() const noexcept { return {x0_, x1_}; }
  [[nodiscard]] std::pair<double, double> y_range() const noexcept { return {y0_, y1_}; }  ///< data y range

  /// Opens <g class="panel"> with a clip path, the frame, grid, ticks and labels: `x_label` below,
  /// `y_label` to the left (units in the label, "value (scene units)"), `title` above.  With
  /// fps > 0 a second x axis on top shows seconds = x / fps.  Call end() after the data.
  void begin(SvgDocument& doc, const std::string& title, const std::string& x_label, const std::string& y_label,
             double fps = 0) const;
  /// Draws the legend to the right of the panel and closes the panel's group.
  void end(SvgDocument& doc, const std::vector<LegendEntry>& legend) const;
  /// Starts a clipped group for data (so extrapolated lines stay inside the frame); end_data() closes it.
  void begin_data(SvgDocument& doc) const;
  /// Closes the group of begin_data().
  void end_data(SvgDocument& doc) const;

  /// Points (x, y) as the "points" attribute value.
  [[nodiscard]] std::string points(const std::vector<double>& xs, const std::vector<double>& ys) const;

 private:
  double left_, top_, width_, height_;
  double x0_, x1_, y0_, y1_;
  bool flip_x_, flip_y_;
  std::string clip_id_;
};

/// One of the three orthographic views of the path and trajectory pages: scene axis h across and
/// v up (0 x, 1 y, 2 z), flipped where the view looks from the other side.
struct ThreeView {
  const char* title;    ///< the panel's title
  int h, v;             ///< scene axes across and up
  bool flip_x, flip_y;  ///< x grows leftwards, y downwards
  const char* x_label;  ///< label of the axis across
  const char* y_label;  ///< label of the axis up
};
/// The top, front and side views, in that order (third-angle projection).
inline constexpr ThreeView kThreeViews[3] = {
    {"top view (looking down −y; z grows downwards)", 0, 2, false, true, "x (scene units)", "z (scene units)"},
    {"front view (looking along −z)", 0, 1, false, false, "x (scene units)", "y (scene units)"},
    {"side view (from +x, looking along −x; z grows leftwards)", 2, 1, true, false, "z (scene units)", "y (scene units)"},
};
/// Pixel size of one view and the gap between views.
inline constexpr double kThreeViewSize = 330, kThreeViewGap = 130;

/// The panel of view `vi` (kThreeViews) in the third-angle layout whose top-left view starts at
/// (left, top): the top view above the front view, the side view to its right.  Its ranges hold
/// every point of `points` along the view's axes, padded by 8 %, with equal scales.
Panel three_view_panel(int vi, const std::vector<Vec3d>& points, double left, double top);

/// The colour of component i of a multi-line plot (x, y, z red, green, blue; w grey; r, g, b, a
/// red, green, blue, grey; further ones a fixed palette).
std::string component_colour(char letter, std::size_t i);

/// A file-name-safe version of a track or object name for a plot's file (letters, digits, . - _
/// kept, others '_'), at most 96 bytes: a longer one keeps its start and gets the FNV-1a hash of
/// the whole name, so that a legal 256-character name stays within the file system's 255 bytes
/// (the page's title keeps the full name).
std::string plot_file_name(const std::string& name);

}  // namespace inbetween::cli
