// SvgCanvas: see svg.hpp.
#include "svg.hpp"

#include <algorithm>
#include <cstdio>

namespace inbetween::cli {
namespace {
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}
std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}
}  // namespace

SvgCanvas::SvgCanvas(double width_px, double height_px, double x0, double x1, double y0, double y1)
    : w_(width_px), h_(height_px), x0_(x0), y0_(y0) {
  // Half extents and half differences: x1 − x0 overflows for coordinates near ±1.8e308 (issue 9,
  // a Lagrange curve from 1.6e308 to −2e307 plotted NaN), x1/2 − x0/2 never does.
  const double dx = std::max(x1 / 2 - x0 / 2, 0.5e-12), dy = std::max(y1 / 2 - y0 / 2, 0.5e-12);
  const double margin = 0.05;
  scale_ = std::min(w_ * (1 - 2 * margin) / dx, h_ * (1 - 2 * margin) / dy);  // pixels per half unit
  off_x_ = (w_ - dx * scale_) / 2;
  off_y_ = (h_ - dy * scale_) / 2;
}

double SvgCanvas::map_x(double x) const { return off_x_ + (x / 2 - x0_ / 2) * scale_; }
double SvgCanvas::map_y(double y) const { return h_ - (off_y_ + (y / 2 - y0_ / 2) * scale_); }

void SvgCanvas::polyline(const std::vector<SvgPoint>& pts, const std::string& stroke, double width_px,
                         const std::string& dash) {
  body_ << "  <polyline fill=\"none\" stroke=\"" << stroke << "\" stroke-width=\"" << num(width_px) << "\"";
  if (!dash.empty()) body_ << " stroke-dasharray=\"" << dash << "\"";
  body_ << " points=\"";
  for (std::size_t i = 0; i < pts.size(); ++i) body_ << (i ? " " : "") << num(map_x(pts[i].x)) << "," << num(map_y(pts[i].y));
  body_ << "\"/>\n";
}

void SvgCanvas::circle(SvgPoint p, double r_px, const std::string& fill) {
  body_ << "  <circle cx=\"" << num(map_x(p.x)) << "\" cy=\"" << num(map_y(p.y)) << "\" r=\"" << num(r_px)
        << "\" fill=\"" << fill << "\"/>\n";
}

void SvgCanvas::caption(int row, const std::string& text) {
  body_ << "  <text x=\"8\" y=\"" << num(18 + 16 * row) << "\" font-family=\"sans-serif\" font-size=\"13\">"
        << escape(text) << "</text>\n";
}

std::string SvgCanvas::str() const {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << num(w_) << "\" height=\"" << num(h_)
      << "\" viewBox=\"0 0 " << num(w_) << " " << num(h_) << "\">\n"
      << "  <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << body_.str() << "</svg>\n";
  return out.str();
}

}  // namespace inbetween::cli
