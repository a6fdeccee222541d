// Plotter: one page per object: its local translation, rotation and scale channels (plot_internal.hpp).
#include "plot_internal.hpp"

namespace inbetween::cli::plot_detail {

void Plotter::plot_object(std::size_t i) {
  const auto& node = scene_.objects()[i];
  const std::string& name = node.name;
  const bool on_path = !scene_.path_legs(i).empty();
  const bool camera = scene_.camera(i) != nullptr;
  const bool root = !node.parent.has_value();
  // Dashed outside a channel's keys (objects' keyed channels) or outside the path legs.
  auto channel_pieces = [&](std::span<const double> frames, std::string before, std::string after) {
    Pieces p{{}, false, {}, std::move(before), std::move(after)};
    if (!frames.empty()) p.breaks = {frames.front(), frames.back()};
    return p;
  };
  Pieces path_pieces{{}, false, {}, "held (path start)", "held (path end)"};
  if (on_path) {
    const auto legs = scene_.path_legs(i);
    path_pieces.breaks = {legs.front().motion.frame_range().lo, legs.back().motion.frame_range().hi};
  }
  std::vector<Pane> panes;
  // Translation.
  {
    Pieces p = on_path ? path_pieces : Pieces{};
    if (!on_path && node.local.translation) {
      p = channel_pieces(node.local.translation->frames(), "extended (" + std::string(enum_name(node.local.translation->extend_before())) + ")",
                         "extended (" + std::string(enum_name(node.local.translation->extend_after())) + ")");
    }
    Pane pane{name + ".translation (world)", "position (scene units)", {}, {}, p, {}};
    for (std::size_t c = 0; c < 3; ++c) {
      const char l = "xyz"[c];
      const std::string col = name + ".translation." + l;
      Curve curve{std::string(1, l), component_colour(l, c), col, col_value(col), {}};
      if (root && !on_path && node.local.translation && node.local.translation->size() <= kMaxObjectKeyDots) {
        const auto& tr = *node.local.translation;
        for (std::size_t k = 0; k < tr.size(); ++k) curve.keys.emplace_back(tr.frames()[k], tr.values()[k][int(c)]);
      }
      pane.curves.push_back(std::move(curve));
    }
    panes.push_back(std::move(pane));
  }
  // Rotation (components and angle).
  {
    Pieces p = on_path ? path_pieces : Pieces{};
    std::vector<std::pair<double, Quatd>> keys;
    if (!on_path && !camera && node.local.rotation) {
      const auto& r = *node.local.rotation;
      p = channel_pieces(r.frames(), "held (first key)", "held (last key)");
      if (root && r.size() <= kMaxObjectKeyDots) {
        for (std::size_t k = 0; k < r.size(); ++k) keys.emplace_back(r.frames()[k], r.keys()[k]);
      }
    }
    const std::string prefix = name + ".rotation";
    Pane comps{name + ".rotation (world)", "quaternion component (unitless)", {}, {}, p, {}};
    for (int c = 0; c < 4; ++c) {
      const char l = "wxyz"[c];
      const std::string col = prefix + "." + l;
      Curve curve{std::string(1, l), component_colour(l, std::size_t(c)), col, col_value(col), {}};
      for (const auto& [f, q] : keys) curve.keys.emplace_back(f, c == 0 ? q.w : c == 1 ? q.x : c == 2 ? q.y : q.z);
      comps.curves.push_back(std::move(curve));
    }
    Pane angle{name + ".rotation (world): angle about the axis", "angle (degrees)", {}, {}, p, {}};
    angle.curves.push_back({"angle 2·atan2(|xyz|, w)", "#8c564b", "angle_deg(" + prefix + ")", angle_value(prefix), {}});
    panes.push_back(std::move(comps));
    panes.push_back(std::move(angle));
  }
  // Scale.
  {
    Pieces p;
    if (node.local.scale) {
      p = channel_pieces(node.local.scale->frames(), "extended (" + std::string(enum_name(node.local.scale->extend_before())) + ")",
                         "extended (" + std::string(enum_name(node.local.scale->extend_after())) + ")");
    }
    Pane pane{name + ".scale (world)", "scale factor (unitless)", {}, {}, p, {}};
    for (std::size_t c = 0; c < 3; ++c) {
      const char l = "xyz"[c];
      const std::string col = name + ".scale." + l;
      Curve curve{std::string(1, l), component_colour(l, c), col, col_value(col), {}};
      if (root && node.local.scale && node.local.scale->size() <= kMaxObjectKeyDots) {
        const auto& sc = *node.local.scale;
        for (std::size_t k = 0; k < sc.size(); ++k) curve.keys.emplace_back(sc.frames()[k], sc.values()[k][int(c)]);
      }
      pane.curves.push_back(std::move(curve));
    }
    panes.push_back(std::move(pane));
  }
  std::string what = camera ? "camera " : "object ";
  write_panes("objects", name, what + name + ": world transform" + (on_path ? " (on a path)" : ""), panes);
}

}  // namespace inbetween::cli::plot_detail
