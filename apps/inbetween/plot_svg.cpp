// SvgDocument, Panel, ticks: see plot_svg.hpp.
#include "plot_svg.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

namespace inbetween::cli {
namespace {

// Layout constants of a panel, in pixels.
constexpr double kTickLength = 5;
constexpr double kFontSize = 12;
constexpr const char* kFont = "sans-serif";
constexpr const char* kAxisColour = "#333333";
constexpr const char* kGridColour = "#e4e4e4";

// A panel's clip-path id: unique within the process, so unique within every document (atomic:
// in-process runs may draw in several threads at once, run.hpp).
int next_clip_id() {
  static std::atomic<int> id{0};
  return ++id;
}

// A tick label: the tick value, with the rounding noise of k·step removed (12 significant digits
// are far more than any tick needs and keep 0.30000000000000004 as "0.3").
std::string tick_label(double v, double step) {
  if (v == 0 || std::abs(v) < step * 1e-9) return "0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  return std::string(buf, r.ptr);
}

}  // namespace

std::string svg_number(double v) {
  if (v == 0) return "0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // Control characters other than tab and line breaks are not allowed in XML 1.0.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') {
          out += '?';
        } else {
          out += c;
        }
    }
  }
  return out;
}

SvgDocument::SvgDocument(double width_px, double height_px, std::string_view title)
    : width_(width_px), height_(height_px) {
  out_ = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out_ += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + svg_number(width_px) +
          "\" height=\"" + svg_number(height_px) + "\" viewBox=\"0 0 " + svg_number(width_px) + " " +
          svg_number(height_px) + "\" font-family=\"" + kFont + "\" font-size=\"" + svg_number(kFontSize) + "\">\n";
  open_.push_back("svg");
  text("title", {}, title);
  leaf("rect", {{"width", "100%"}, {"height", "100%"}, {"fill", "white"}});
}

void SvgDocument::attrs_out(const std::vector<SvgAttr>& attrs) {
  for (const auto& [name, value] : attrs) {
    out_ += ' ';
    out_ += name;
    out_ += "=\"";
    out_ += xml_escape(value);
    out_ += '"';
  }
}

void SvgDocument::open(std::string_view tag, const std::vector<SvgAttr>& attrs) {
  out_ += std::string(2 * open_.size(), ' ') + "<" + std::string(tag);
  attrs_out(attrs);
  out_ += ">\n";
  open_.emplace_back(tag);
}

void SvgDocument::close() {
  if (open_.empty()) return;
  const std::string tag = open_.back();
  open_.pop_back();
  out_ += std::string(2 * open_.size(), ' ') + "</" + tag + ">\n";
}

void SvgDocument::leaf(std::string_view tag, const std::vector<SvgAttr>& attrs) {
  out_ += std::string(2 * open_.size(), ' ') + "<" + std::string(tag);
  attrs_out(attrs);
  out_ += "/>\n";
}

void SvgDocument::text(std::string_view tag, const std::vector<SvgAttr>& attrs, std::string_view content) {
  out_ += std::string(2 * open_.size(), ' ') + "<" + std::string(tag);
  attrs_out(attrs);
  // Appended piece by piece: `">" + std::string&&` inserts at the front of the temporary, where
  // GCC 12 reports a false -Wrestrict (a known libstdc++/GCC 12 false positive in the inlined
  // basic_string::insert); appending also copies less.
  out_ += '>';
  out_ += xml_escape(content);
  out_ += "</";
  out_ += tag;
  out_ += ">\n";
}

std::string SvgDocument::str() {
  while (!open_.empty()) close();
  return out_;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  // Half extents throughout: hi − lo overflows for ranges near ±1.8e308 (issue 9: a Lagrange curve
  // from 1.6e308 to −2e307), hi/2 − lo/2 never does; halving is exact, so normal ranges give the
  // same ticks to the last bit.
  if (!(hi > lo) || !std::isfinite(hi) || !std::isfinite(lo)) return ticks;
  const double raw = (hi / 2 - lo / 2) / std::max(target, 1) * 2;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  }
  const double first = std::ceil(lo / step - 1e-9);
  const double last = std::floor(hi / step + 1e-9);
  for (double k = first; k <= last && ticks.size() < 100; k += 1) {
    // The label of k·step is printed with 12 digits; the tick sits at the value of that label, so
    // the label is the exact coordinate of the tick.
    const std::string label = tick_label(k * step, step);
    ticks.push_back(std::strtod(label.c_str(), nullptr));
  }
  return ticks;
}

std::pair<double, double> padded_range(const std::vector<double>& values, double pad) {
  double lo = INFINITY, hi = -INFINITY;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!(lo <= hi)) return {0, 1};
  if (hi / 2 - lo / 2 <= 0.5e-12 * std::max(1.0, std::abs(lo))) {
    const double half = 0.5 * std::max(1.0, std::abs(lo));
    return {lo - half, hi + half};
  }
  // Half extents (exact, the same bits for normal ranges) so that a range near ±1.8e308 does not
  // overflow; the padded ends saturate at the largest finite value.
  const double d = (hi / 2 - lo / 2) * (2 * pad);
  constexpr double big = std::numeric_limits<double>::max();
  return {std::max(lo - d, -big), std::min(hi + d, big)};
}

Panel three_view_panel(int vi, const std::vector<Vec3d>& points, double left, double top) {
  const ThreeView& view = kThreeViews[vi];
  std::vector<double> hs, vs;
  for (const auto& p : points) {
    hs.push_back(p[view.h]);
    vs.push_back(p[view.v]);
  }
  const auto [h0, h1] = padded_range(hs, 0.08);
  const auto [v0, v1] = padded_range(vs, 0.08);
  const double x = vi == 2 ? left + kThreeViewSize + kThreeViewGap : left;
  const double y = vi == 0 ? top : top + kThreeViewSize + kThreeViewGap;
  Panel panel(x, y, kThreeViewSize, kThreeViewSize, h0, h1, v0, v1, view.flip_x, view.flip_y);
  panel.equal_aspect();
  return panel;
}

Panel::Panel(double left, double top, double width, double height, double x0, double x1, double y0, double y1,
             bool flip_x, bool flip_y)
    : left_(left), top_(top), width_(width), height_(height), x0_(x0), x1_(x1), y0_(y0), y1_(y1),
      flip_x_(flip_x), flip_y_(flip_y), clip_id_("clip" + std::to_string(next_clip_id())) {}

void Panel::equal_aspect() {
  // Pixels per half unit, from half extents (see px()): the same bits as pixels per unit / 2.
  const double sx = width_ / (x1_ / 2 - x0_ / 2), sy = height_ / (y1_ / 2 - y0_ / 2);
  constexpr double big = std::numeric_limits<double>::max();
  if (sx > sy) {
    const double half = width_ / sy, mid = x0_ / 2 + x1_ / 2;
    x0_ = std::max(mid - half, -big);
    x1_ = std::min(mid + half, big);
  } else {
    const double half = height_ / sx, mid = y0_ / 2 + y1_ / 2;
    y0_ = std::max(mid - half, -big);
    y1_ = std::min(mid + half, big);
  }
}

// Half extents: x − x0 and x1 − x0 overflow near ±1.8e308, the halves never do; halving is exact,
// so the fraction has the same bits for every normal range.
double Panel::px(double x) const noexcept {
  const double f = (x / 2 - x0_ / 2) / (x1_ / 2 - x0_ / 2);
  return left_ + (flip_x_ ? 1 - f : f) * width_;
}

double Panel::py(double y) const noexcept {
  const double f = (y / 2 - y0_ / 2) / (y1_ / 2 - y0_ / 2);
  return top_ + (flip_y_ ? f : 1 - f) * height_;
}

void Panel::begin(SvgDocument& doc, const std::string& title, const std::string& x_label, const std::string& y_label,
                  double fps) const {
  doc.open("g", {{"class", "panel"}});
  doc.open("defs");
  doc.open("clipPath", {{"id", clip_id_}});
  doc.leaf("rect", {{"x", svg_number(left_)}, {"y", svg_number(top_)}, {"width", svg_number(width_)},
                    {"height", svg_number(height_)}});
  doc.close();
  doc.close();
  doc.text("text", {{"class", "panel-title"}, {"x", svg_number(left_)}, {"y", svg_number(top_ - (fps > 0 ? 26 : 8))},
                    {"font-size", "14"}, {"font-weight", "bold"}},
           title);
  const double bottom = top_ + height_, right = left_ + width_;
  // Grid and ticks: x below, y left.
  for (double v : nice_ticks(std::min(x0_, x1_), std::max(x0_, x1_), 8)) {
    const double p = px(v);
    doc.open("g", {{"class", "tick-x"}});
    doc.leaf("line", {{"x1", svg_number(p)}, {"y1", svg_number(bottom)}, {"x2", svg_number(p)},
                      {"y2", svg_number(bottom + kTickLength)}, {"stroke", kAxisColour}});
    doc.text("text", {{"x", svg_number(p)}, {"y", svg_number(bottom + kTickLength + kFontSize + 1)},
                      {"text-anchor", "middle"}},
             tick_label(v, 0));
    doc.close();
    doc.leaf("line", {{"class", "grid"}, {"x1", svg_number(p)}, {"y1", svg_number(top_)}, {"x2", svg_number(p)},
                      {"y2", svg_number(bottom)}, {"stroke", kGridColour}});
  }
  for (double v : nice_ticks(std::min(y0_, y1_), std::max(y0_, y1_), 6)) {
    const double p = py(v);
    doc.open("g", {{"class", "tick-y"}});
    doc.leaf("line", {{"x1", svg_number(left_ - kTickLength)}, {"y1", svg_number(p)}, {"x2", svg_number(left_)},
                      {"y2", svg_number(p)}, {"stroke", kAxisColour}});
    doc.text("text", {{"x", svg_number(left_ - kTickLength - 3)}, {"y", svg_number(p + kFontSize * 0.35)},
                      {"text-anchor", "end"}},
             tick_label(v, 0));
    doc.close();
    doc.leaf("line", {{"class", "grid"}, {"x1", svg_number(left_)}, {"y1", svg_number(p)}, {"x2", svg_number(right)},
                      {"y2", svg_number(p)}, {"stroke", kGridColour}});
  }
  if (fps > 0) {
    // Seconds on top: ticks at nice seconds, placed at frame = seconds · fps.
    for (double s : nice_ticks(std::min(x0_, x1_) / fps, std::max(x0_, x1_) / fps, 8)) {
      const double p = px(s * fps);
      doc.open("g", {{"class", "tick-x2"}});
      doc.leaf("line", {{"x1", svg_number(p)}, {"y1", svg_number(top_ - kTickLength)}, {"x2", svg_number(p)},
                        {"y2", svg_number(top_)}, {"stroke", kAxisColour}});
      doc.text("text", {{"x", svg_number(p)}, {"y", svg_number(top_ - kTickLength - 3)}, {"text-anchor", "middle"},
                        {"fill", "#666666"}},
               tick_label(s, 0));
      doc.close();
    }
    doc.text("text", {{"x", svg_number(right + 6)}, {"y", svg_number(top_ - kTickLength - 3)}, {"fill", "#666666"}},
             "seconds");
  }
  doc.leaf("rect", {{"class", "frame"}, {"x", svg_number(left_)}, {"y", svg_number(top_)}, {"width", svg_number(width_)},
                    {"height", svg_number(height_)}, {"fill", "none"}, {"stroke", kAxisColour}});
  doc.text("text", {{"class", "axis-label"}, {"x", svg_number(left_ + width_ / 2)},
                    {"y", svg_number(bottom + kTickLength + 2 * kFontSize + 6)}, {"text-anchor", "middle"}},
           x_label);
  const double ly = top_ + height_ / 2, lx = left_ - 58;
  doc.text("text", {{"class", "axis-label"}, {"x", svg_number(lx)}, {"y", svg_number(ly)}, {"text-anchor", "middle"},
                    {"transform", "rotate(-90 " + svg_number(lx) + " " + svg_number(ly) + ")"}},
           y_label);
}

void Panel::begin_data(SvgDocument& doc) const { doc.open("g", {{"clip-path", "url(#" + clip_id_ + ")"}}); }

void Panel::end_data(SvgDocument& doc) const { doc.close(); }

void Panel::end(SvgDocument& doc, const std::vector<LegendEntry>& legend) const {
  if (!legend.empty()) {
    doc.open("g", {{"class", "legend"}});
    double y = top_ + 10;
    const double x = left_ + width_ + 14;
    for (const auto& e : legend) {
      if (e.dot) {
        doc.leaf("circle", {{"cx", svg_number(x + 11)}, {"cy", svg_number(y - 4)}, {"r", "3.5"}, {"fill", e.colour}});
      } else {
        std::vector<SvgAttr> a{{"x1", svg_number(x)}, {"y1", svg_number(y - 4)}, {"x2", svg_number(x + 22)},
                               {"y2", svg_number(y - 4)}, {"stroke", e.colour}, {"stroke-width", "2"}};
        if (!e.dash.empty()) a.emplace_back("stroke-dasharray", e.dash);
        doc.leaf("line", a);
      }
      doc.text("text", {{"x", svg_number(x + 28)}, {"y", svg_number(y)}}, e.label);
      y += 17;
    }
    doc.close();
  }
  doc.close();
}

std::string Panel::points(const std::vector<double>& xs, const std::vector<double>& ys) const {
  std::string s;
  for (std::size_t i = 0; i < xs.size() && i < ys.size(); ++i) {
    if (i) s += ' ';
    s += svg_number(px(xs[i]));
    s += ',';
    s += svg_number(py(ys[i]));
  }
  return s;
}

std::string component_colour(char letter, std::size_t i) {
  switch (letter) {
    case 'x': case 'r': return "#d62728";
    case 'y': case 'g': return "#2ca02c";
    case 'z': case 'b': return "#1f77b4";
    case 'w': case 'a': return "#7f7f7f";
    default: break;
  }
  static const char* palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b"};
  return palette[i % 6];
}

std::string plot_file_name(const std::string& name) {
  constexpr std::size_t kMaxFileNameBytes = 96;
  std::string out;
  for (unsigned char c : name) out += (std::isalnum(c) || c == '.' || c == '-' || c == '_') ? char(c) : '_';
  if (out.empty() || out[0] == '.') out = "_" + out;
  if (out.size() > kMaxFileNameBytes) {
    std::uint64_t h = 14695981039346656037ull;
    for (unsigned char c : name) h = (h ^ c) * 1099511628211ull;
    char hex[20];
    std::snprintf(hex, sizeof hex, "-%016llx", static_cast<unsigned long long>(h));
    out = out.substr(0, kMaxFileNameBytes - 17) + hex;
  }
  return out;
}

}  // namespace inbetween::cli
