// Plotter: path views (three projections with positions and orientations) and speed plots (plot_internal.hpp).
#include "plot_internal.hpp"

namespace inbetween::cli::plot_detail {

Vec3d Plotter::to_world(std::optional<std::size_t> parent, double frame, const Vec3d& p) {
  if (!parent) return p;
  const std::string& n = scene_.objects()[*parent].name;
  const auto r = single_row(frame);
  const Vec3d t{r[column(n + ".translation.x")], r[column(n + ".translation.y")], r[column(n + ".translation.z")]};
  const Quatd q = Quatd::from_wxyz(r[column(n + ".rotation.w")], r[column(n + ".rotation.x")],
                                   r[column(n + ".rotation.y")], r[column(n + ".rotation.z")]);
  const Vec3d s{r[column(n + ".scale.x")], r[column(n + ".scale.y")], r[column(n + ".scale.z")]};
  return t + rotate(normalized(q), Vec3d{s.x * p.x, s.y * p.y, s.z * p.z});
}

void Plotter::plot_path_views(std::size_t i) {
  const auto& node = scene_.objects()[i];
  const std::string& name = node.name;
  const auto legs = scene_.path_legs(i);
  std::vector<std::vector<Vec3d>> curves, controls;
  for (const auto& leg : legs) {
    const AnyCurve& c = leg.motion.path();
    const auto dom = c.domain();
    const double f0 = leg.motion.frame_range().lo;
    std::vector<Vec3d> pts;
    for (int k = 0; k <= kPathSamples; ++k) {
      pts.push_back(to_world(node.parent, f0, c.point(dom.lo + (dom.hi - dom.lo) * k / kPathSamples)));
    }
    curves.push_back(std::move(pts));
    std::vector<Vec3d> cps;
    for (int k = 0; k < c.control_point_count(); ++k) cps.push_back(to_world(node.parent, f0, c.control_point(k)));
    controls.push_back(std::move(cps));
  }
  // A path lives in its parent's space and is drawn with the parent's transform at the leg's
  // first frame; when the parent moves, the legend says so (the positions then leave the line).
  std::string parent_note;
  if (node.parent) {
    const std::string& pn = scene_.objects()[*node.parent].name;
    const std::size_t first = column(pn + ".translation.x");
    bool moves = false;
    for (std::uint64_t g = 1; g < grid_.count && !moves; ++g) {
      for (std::size_t c = first; c < first + 10; ++c) {  // translation 3, rotation 4, scale 3
        // The rotation's sign may flip between frames (q and −q): compare |component|.
        if (std::abs(grid_row(g)[c]) != std::abs(grid_row(0)[c])) moves = true;
      }
    }
    if (moves) parent_note = "drawn with parent " + pn + " as at the leg's first frame (" + pn + " moves)";
  }
  // Position dots: grid frames one frame apart (or more, at most kMaxDots) over the legs' frames.
  const double m0 = legs.front().motion.frame_range().lo, m1 = legs.back().motion.frame_range().hi;
  std::uint64_t every = std::max<std::uint64_t>(1, std::uint64_t(std::llround(1 / grid_.step)));
  std::vector<std::uint64_t> dots;
  for (;;) {
    dots.clear();
    for (std::uint64_t g = 0; g < grid_.count; g += every) {
      if (grid_.frame(g) >= m0 - 1e-9 && grid_.frame(g) <= m1 + 1e-9) dots.push_back(g);
    }
    if (dots.size() <= kMaxDots) break;
    every *= 2;
  }
  std::vector<std::uint64_t> frames_marked;
  if (!dots.empty()) {
    for (int k = 0; k < kOrientationFrames; ++k) {
      frames_marked.push_back(dots[std::size_t(std::llround(double(k) * double(dots.size() - 1) / (kOrientationFrames - 1)))]);
    }
    frames_marked.erase(std::unique(frames_marked.begin(), frames_marked.end()), frames_marked.end());
  }
  const std::size_t tx = column(name + ".translation.x");
  const std::size_t rw = column(name + ".rotation.w");
  auto position = [&](std::uint64_t g) {
    const auto r = grid_row(g);
    return Vec3d{r[tx], r[tx + 1], r[tx + 2]};
  };
  auto rotation = [&](std::uint64_t g) {
    const auto r = grid_row(g);
    return normalized(Quatd::from_wxyz(r[rw], r[rw + 1], r[rw + 2], r[rw + 3]));
  };
  std::vector<Vec3d> everything;
  for (const auto& c : curves) everything.insert(everything.end(), c.begin(), c.end());
  for (const auto& c : controls) everything.insert(everything.end(), c.begin(), c.end());
  for (auto g : dots) everything.push_back(position(g));
  double extent = 0;
  for (int a = 0; a < 3; ++a) {
    std::vector<double> v;
    for (const auto& p : everything) v.push_back(p[a]);
    const auto [lo, hi] = padded_range(v, 0);
    extent = std::max(extent, hi - lo);
  }
  const double axis_len = 0.06 * extent;

  const double dot_frames = double(every) * grid_.step;
  const std::string every_text = dot_frames == 1 ? std::string("every frame") : "every " + short_text(dot_frames) + " frames";
  const std::string title = "path of " + name + ": top, front and side views, positions " + every_text;
  SvgDocument doc(kLeft + 2 * (kThreeViewSize + kThreeViewGap) + 40, kTop + 2 * (kThreeViewSize + kThreeViewGap), title);
  doc.text("text", {{"class", "title"}, {"x", "16"}, {"y", "28"}, {"font-size", "17"}, {"font-weight", "bold"}}, title);
  doc.text("text", {{"x", "16"}, {"y", "48"}, {"fill", "#555555"}},
           options_.title + " · positions at equal time steps: their spacing shows the speed (ease in and out close together)");
  const std::string axis_name[3] = {"x", "y", "z"};
  for (int vi = 0; vi < 3; ++vi) {
    const ThreeView& view = kThreeViews[vi];
    const Panel panel = three_view_panel(vi, everything, kLeft, kTop);
    panel.begin(doc, view.title, view.x_label, view.y_label);
    panel.begin_data(doc);
    for (std::size_t l = 0; l < curves.size(); ++l) {
      std::vector<double> xs, ys, cx, cy;
      for (const auto& p : curves[l]) {
        xs.push_back(p[view.h]);
        ys.push_back(p[view.v]);
      }
      for (const auto& p : controls[l]) {
        cx.push_back(p[view.h]);
        cy.push_back(p[view.v]);
      }
      doc.leaf("polyline", {{"class", "control-polygon"}, {"fill", "none"}, {"stroke", "#bbbbbb"},
                            {"stroke-dasharray", "4 3"}, {"points", panel.points(cx, cy)}});
      doc.leaf("polyline", {{"class", "path"}, {"data-leg", std::to_string(l)}, {"fill", "none"}, {"stroke", "#555555"},
                            {"stroke-width", "2"}, {"points", panel.points(xs, ys)}});
      for (std::size_t k = 0; k < cx.size(); ++k) {
        doc.leaf("rect", {{"class", "control-point"}, {"x", num(panel.px(cx[k]) - 3.5)}, {"y", num(panel.py(cy[k]) - 3.5)},
                          {"width", "7"}, {"height", "7"}, {"fill", "white"}, {"stroke", "#ff7f0e"}});
      }
    }
    const std::string dx = name + ".translation." + axis_name[view.h], dy = name + ".translation." + axis_name[view.v];
    for (auto g : dots) {
      const Vec3d p = position(g);
      doc.leaf("circle", {{"class", "data position"}, {"data-x", dx}, {"data-y", dy}, {"data-frame", num(grid_.frame(g))},
                          {"cx", num(panel.px(p[view.h]))}, {"cy", num(panel.py(p[view.v]))}, {"r", "2.6"},
                          {"fill", "#1f77b4"}});
    }
    for (auto g : frames_marked) {
      const Vec3d p = position(g);
      const Quatd q = rotation(g);
      for (int a = 0; a < 3; ++a) {
        Vec3d e{};
        e[a] = 1;
        const Vec3d tip = p + axis_len * rotate(q, e);
        // Checkable like the data: the line runs from the position (data-x, data-y columns) along
        // data-length · rotate(q, e_axis) with q the columns data-rotation.w x y z.
        doc.leaf("line", {{"class", "frame-axis"}, {"data-frame", num(grid_.frame(g))}, {"data-axis", axis_name[a]},
                          {"data-x", dx}, {"data-y", dy}, {"data-rotation", name + ".rotation"},
                          {"data-length", num(axis_len)},
                          {"x1", num(panel.px(p[view.h]))}, {"y1", num(panel.py(p[view.v]))},
                          {"x2", num(panel.px(tip[view.h]))}, {"y2", num(panel.py(tip[view.v]))},
                          {"stroke", component_colour(axis_name[a][0], std::size_t(a))}, {"stroke-width", "1.5"}});
      }
    }
    panel.end_data(doc);
    std::vector<LegendEntry> legend;
    if (vi == 0) {
      legend = {{"path (" + std::to_string(curves.size()) + (curves.size() == 1 ? " leg)" : " legs)"), "#555555", "", false},
                {"control polygon", "#bbbbbb", "4 3", false},
                {"control point", "#ff7f0e", "", true},
                {"position " + every_text, "#1f77b4", "", true},
                {"object +x (left)", component_colour('x', 0), "", false},
                {"object +y (up)", component_colour('y', 1), "", false},
                {"object +z (front)", component_colour('z', 2), "", false}};
      if (!parent_note.empty()) legend.push_back({"path " + parent_note, "#555555", "", false});
    }
    panel.end(doc, legend);
  }
  add_file("paths", name + "-views", title, doc);
}

void Plotter::ease_markers(const RawPathLeg& leg, const PathMotion& motion, std::vector<std::pair<double, std::string>>& out) const {
  const RawSpeed& s = leg.speed;
  // Keyed forms: their keys are where the speed form changes piece (the acceleration may jump;
  // constraint tuples are C² only where they give an acceleration, acceleration keys of shape
  // constant jump at every key).
  if (s.kind == SpeedKind::distance_keys) {
    for (std::size_t k = 0; k < s.keys.size(); ++k) out.emplace_back(s.keys[k].frame, "key " + std::to_string(k));
  } else if (s.kind == SpeedKind::constraints) {
    for (std::size_t k = 0; k < s.keys.size(); ++k) out.emplace_back(s.keys[k].frame, "constraint " + std::to_string(k));
  } else if (s.kind == SpeedKind::acceleration_keys) {
    for (std::size_t k = 0; k < s.accelerations.size(); ++k) {
      out.emplace_back(s.accelerations[k].frame, "a key " + std::to_string(k));
    }
  } else if (s.kind == SpeedKind::velocity_keys) {
    for (std::size_t k = 0; k < s.velocities.size(); ++k) out.emplace_back(s.velocities[k].frame, "v key " + std::to_string(k));
  } else if (s.kind == SpeedKind::track) {
    for (const auto& t : raw_.tracks) {
      const auto* scalar = std::get_if<RawScalarTrack>(&t);
      if (!scalar || scalar->name != leg.speed_track) continue;
      for (std::size_t k = 0; k < scalar->curve.keys.size(); ++k) {
        out.emplace_back(scalar->curve.keys[k].frame, leg.speed_track + " key " + std::to_string(k));
      }
    }
  }
  // Ease: the built ease's own phase boundaries (so every way of giving them — t1/accel_frames,
  // t2/decel_frames, v0, accelerations, Eq. 3.21 or the equal areas of Figure 3.16 — is read back
  // from the one solver in timing/constant_acceleration.hpp).
  const auto* ease = motion.unit_ease();
  if (!ease) return;
  const Interval<double> fr = motion.frame_range();
  const double span = fr.hi - fr.lo;
  auto at = [&](double t, const std::string& label) {
    if (std::isfinite(t)) out.emplace_back(fr.lo + t * span, label + " = " + short_text(t, 4));
  };
  if (const auto* ca = std::get_if<ConstantAccelerationEase<double>>(ease)) {
    at(ca->t1(), "t1");
    at(ca->t2(), "t2");
  } else if (const auto* sp = std::get_if<SineAccelDecelEase<double>>(ease)) {
    at(sp->k1(), "k1");
    at(sp->k2(), "k2");
  }
}

void Plotter::plot_speed(std::size_t i) {
  const auto& node = scene_.objects()[i];
  const std::string& name = node.name;
  const auto legs = scene_.path_legs(i);
  const RawObject* raw = i < raw_.objects.size() ? &raw_.objects[i] : nullptr;
  std::vector<std::pair<double, std::string>> markers;
  std::vector<double> breaks;
  for (std::size_t k = 0; k < legs.size(); ++k) {
    const auto fr = legs[k].motion.frame_range();
    const std::string leg = legs.size() > 1 ? "leg " + std::to_string(k + 1) + " " : "";
    markers.emplace_back(fr.lo, leg + "start");
    markers.emplace_back(fr.hi, leg + "end");
    if (raw && k < raw->path.size()) ease_markers(raw->path[k], legs[k].motion, markers);
  }
  // One marker per frame: "leg 1 end / leg 2 start".
  std::stable_sort(markers.begin(), markers.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::pair<double, std::string>> merged;
  for (const auto& m : markers) {
    if (!merged.empty() && merged.back().first == m.first) {
      merged.back().second += " / " + m.second;
    } else {
      merged.push_back(m);
    }
  }
  markers = std::move(merged);
  for (const auto& m : markers) breaks.push_back(m.first);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  // Distance and speed are columns (exact at the breaks); acceleration is the speed form's
  // second derivative (PathMotion::distance_at), per second², from the leg that is current.
  auto leg_index = [legs](double f) {
    std::size_t cur = 0;
    for (std::size_t k = 0; k < legs.size(); ++k) {
      if (legs[k].motion.frame_range().lo <= f) cur = k;
    }
    return cur;
  };
  auto acceleration = [&](double f) {
    const PathMotion& m = legs[leg_index(f)].motion;
    return m.distance_at(f).acceleration * m.fps() * m.fps();
  };
  Pieces pieces{breaks, true, {}, "held (path start)", "held (path end)"};
  pieces.labels.assign(breaks.size() > 0 ? breaks.size() - 1 : 0, "");
  Pane dist{"distance along the path of " + name, "distance (scene units)", {}, {}, pieces, markers};
  dist.curves.push_back({"distance s", "#1f77b4", name + ".distance", col_value(name + ".distance"), {}});
  Pane speed{"speed of " + name, "speed (scene units / s)", {}, {}, pieces, markers};
  speed.curves.push_back({"speed ds/dt", "#2ca02c", name + ".speed", col_value(name + ".speed"), {}});

  // The acceleration panel draws piece by piece (it jumps at phase boundaries), each piece
  // evaluated just inside its ends.
  std::vector<double> b = breaks;
  b.insert(b.begin(), grid_.start);
  b.push_back(grid_.end());
  std::sort(b.begin(), b.end());
  b.erase(std::unique(b.begin(), b.end()), b.end());
  const double eps = 1e-7 * (grid_.end() - grid_.start);
  std::vector<std::vector<double>> af, av;
  std::vector<double> all;
  for (std::size_t j = 0; j + 1 < b.size(); ++j) {
    if (b[j] < grid_.start || b[j + 1] > grid_.end()) continue;
    std::vector<double> fs{b[j] + eps};
    for (const auto& p : piece_frames(b[j], b[j + 1], false)) {
      if (p.frame > b[j] + eps && p.frame < b[j + 1] - eps) fs.push_back(p.frame);
    }
    fs.push_back(b[j + 1] - eps);
    std::vector<double> vs;
    for (double f : fs) vs.push_back(acceleration(f));
    all.insert(all.end(), vs.begin(), vs.end());
    af.push_back(std::move(fs));
    av.push_back(std::move(vs));
  }

  const std::string title = "speed control of " + name + ": distance, speed and acceleration over frames";
  SvgDocument doc = page(3, title);
  draw_pane(doc, kTop + 20, dist);
  draw_pane(doc, kTop + 20 + (kPanelHeight + kPanelGap), speed);
  {
    const double top = kTop + 20 + 2 * (kPanelHeight + kPanelGap);
    const auto [y0, y1] = padded_range(all, 0.08);
    Panel panel(kLeft, top, kPanelWidth, kPanelHeight, grid_.start, grid_.end(), y0, y1);
    panel.begin(doc, "acceleration of " + name, "frame", "acceleration (scene units / s²)", scene_.fps());
    panel.begin_data(doc);
    draw_markers(doc, panel, top, markers);
    for (std::size_t j = 0; j < af.size(); ++j) {
      std::string frames;
      for (double f : af[j]) {
        if (!frames.empty()) frames += ' ';
        frames += num(f);
      }
      doc.leaf("polyline", {{"class", "data"}, {"data-x", "frame"}, {"data-y", "derivative(" + name + ".speed)"},
                            {"data-frames", frames}, {"fill", "none"}, {"stroke", "#d62728"}, {"stroke-width", "1.6"},
                            {"points", panel.points(af[j], av[j])}});
    }
    panel.end_data(doc);
    std::vector<LegendEntry> legend{{"acceleration d²s/dt²", "#d62728", "", false},
                                    {"phase boundary", "#999999", "2 3", false}};
    panel.end(doc, legend);
  }
  add_file("paths", name + "-speed", title, doc);
}

}  // namespace inbetween::cli::plot_detail
