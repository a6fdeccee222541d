// Plotter: one page per scene track: F-curves with their handles, vector and scalar tracks (plot_internal.hpp).
#include "plot_internal.hpp"

namespace inbetween::cli::plot_detail {

void Plotter::plot_track(std::size_t k) {
  const SceneTrack& track = scene_.tracks()[k];
  if (const auto* t = std::get_if<SceneScalarTrack>(&track)) {
    plot_fcurve(*t);
  } else if (const auto* tv = std::get_if<SceneVectorTrack>(&track)) {
    plot_vector(*tv, k < raw_.tracks.size() ? std::get_if<RawVectorTrack>(&raw_.tracks[k]) : nullptr);
  } else if (const auto* tq = std::get_if<SceneQuatTrack>(&track)) {
    std::vector<double> frames(tq->track.frames().begin(), tq->track.frames().end());
    Pieces pieces{frames, true, {}, "held (first key)", "held (last key)"};
    for (std::size_t i = 0; i + 1 < tq->track.size(); ++i) pieces.labels.emplace_back(enum_name(tq->track.interpolation(i)));
    std::vector<std::pair<double, Quatd>> keys;
    for (std::size_t i = 0; i < tq->track.size(); ++i) keys.emplace_back(frames[i], tq->track.keys()[i]);
    plot_rotation("tracks", tq->name, "quaternion track " + tq->name, tq->name, pieces, keys);
  } else if (const auto* te = std::get_if<SceneEulerTrack>(&track)) {
          const auto* r = k < raw_.tracks.size() ? std::get_if<RawEulerTrack>(&raw_.tracks[k]) : nullptr;
    Pieces pieces{{}, true, {}, "held (first key)", "held (last key)"};
    std::vector<std::pair<double, Quatd>> keys;
    if (r) {
      for (std::size_t i = 0; i < r->keys.size(); ++i) {
        pieces.breaks.push_back(r->keys[i].frame);
        keys.emplace_back(r->keys[i].frame, te->track.sample(r->keys[i].frame));
        if (i + 1 < r->keys.size()) {
          pieces.labels.push_back(r->mode == EulerTrackMode::angles ? std::string(enum_name(r->keys[i].tangent))
                                                                    : std::string(enum_name(r->keys[i].interpolation)));
        }
      }
    }
    plot_rotation("tracks", te->name, "Euler track " + te->name + " (" + (r ? r->convention : std::string()) + ", as a quaternion)",
                  te->name, pieces, keys);
  }
}

void Plotter::plot_fcurve(const SceneScalarTrack& t) {
  const auto keys = t.curve.keys();
  Pane pane{"F-curve " + t.name, "value (scene units)", {}, {}, {}, {}};
  Curve curve{t.name, "#1f77b4", t.name, col_value(t.name), {}};
  for (std::size_t i = 0; i < keys.size(); ++i) {
    curve.keys.emplace_back(double(keys[i].x), double(keys[i].y));
    pane.pieces.breaks.push_back(double(keys[i].x));
    if (i + 1 < keys.size()) {
      std::string label(to_string(keys[i].interpolation));
      const auto interp = keys[i].interpolation;
      if (interp != Interpolation::constant && interp != Interpolation::linear && interp != Interpolation::bezier) {
        label += " " + std::string(to_string(keys[i].easing));
      }
      pane.pieces.labels.push_back(label);
      if (interp == Interpolation::bezier) {
        pane.handles.push_back({double(keys[i].x), double(keys[i].y), double(keys[i].right.x), double(keys[i].right.y)});
        pane.handles.push_back({double(keys[i + 1].x), double(keys[i + 1].y), double(keys[i + 1].left.x),
                                double(keys[i + 1].left.y)});
      }
    }
  }
  if (const FCurveCycles* cycles = t.curve.simple_cycles()) {
    pane.pieces.before = cycles->before == CycleMode::none ? "extrapolated (" + std::string(to_string(t.curve.extrapolation())) + ")"
                                                          : "cycled (" + std::string(to_string(cycles->before)) + ")";
    pane.pieces.after = cycles->after == CycleMode::none ? "extrapolated (" + std::string(to_string(t.curve.extrapolation())) + ")"
                                                        : "cycled (" + std::string(to_string(cycles->after)) + ")";
  } else if (!t.curve.modifiers().empty()) {
    std::string stack;
    for (const FCurveModifier& m : t.curve.modifiers()) stack += (stack.empty() ? "" : ", ") + std::string(type_name(m));
    pane.pieces.before = pane.pieces.after = "modifiers (" + stack + ")";
  } else {
    pane.pieces.before = pane.pieces.after = "extrapolated (" + std::string(to_string(t.curve.extrapolation())) + ")";
  }
  pane.curves.push_back(std::move(curve));
  write_panes("tracks", t.name, "scalar track " + t.name + " (graph editor)", {pane});
}

void Plotter::plot_vector(const SceneVectorTrack& t, const RawVectorTrack* raw) {
  const auto frames = t.track.frames();
  Pane pane{"vector track " + t.name, "value (scene units)", {}, {}, {}, {}};
  pane.pieces.breaks.assign(frames.begin(), frames.end());
  pane.pieces.before = "extended (" + std::string(enum_name(t.track.extend_before())) + ")";
  pane.pieces.after = "extended (" + std::string(enum_name(t.track.extend_after())) + ")";
  for (std::size_t i = 0; i + 1 < frames.size(); ++i) {
    pane.pieces.labels.push_back(t.track.stepped(i) ? std::string("stepped")
                                 : raw && i < raw->keys.size() ? std::string(enum_name(raw->keys[i].tangent))
                                                               : std::string());
  }
  const std::string letters = t.components.empty() ? std::string(" ") : t.components;
  for (std::size_t c = 0; c < letters.size(); ++c) {
    const std::string col = t.components.empty() ? t.name : t.name + "." + letters[c];
    Curve curve{t.components.empty() ? t.name : std::string(1, letters[c]), component_colour(letters[c], c), col,
                col_value(col), {}};
    for (std::size_t i = 0; i < frames.size(); ++i) curve.keys.emplace_back(frames[i], t.track.values()[i][int(c)]);
    pane.curves.push_back(std::move(curve));
  }
  write_panes("tracks", t.name, (t.components == "rgba" ? "colour track " : "vector track ") + t.name, {pane});
}

void Plotter::plot_rotation(const std::string& group, const std::string& name, const std::string& title, const std::string& prefix,
                   const Pieces& pieces, const std::vector<std::pair<double, Quatd>>& keys) {
  Pane comps{title + ": components", "quaternion component (unitless)", {}, {}, pieces, {}};
  const char letters[] = {'w', 'x', 'y', 'z'};
  for (int c = 0; c < 4; ++c) {
    const std::string col = prefix + "." + letters[c];
    Curve curve{std::string(1, letters[c]), component_colour(letters[c], std::size_t(c)), col, col_value(col), {}};
    for (const auto& [f, q] : keys) curve.keys.emplace_back(f, c == 0 ? q.w : c == 1 ? q.x : c == 2 ? q.y : q.z);
    comps.curves.push_back(std::move(curve));
  }
  Pane angle{title + ": angle about the axis", "angle (degrees)", {}, {}, pieces, {}};
  Curve a{"angle 2·atan2(|xyz|, w)", "#8c564b", "angle_deg(" + prefix + ")", angle_value(prefix), {}};
  for (const auto& [f, q] : keys) {
    a.keys.emplace_back(f, 2 * std::atan2(std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z), q.w) * 180 / pi_v<double>);
  }
  angle.curves.push_back(std::move(a));
  write_panes(group, name, title, {comps, angle});
}

}  // namespace inbetween::cli::plot_detail
