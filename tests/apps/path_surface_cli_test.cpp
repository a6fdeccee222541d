// `inbetween path surface`: runs the built CLI on OBJ files.  Expected numbers: the library's own
// paths (the tool must only format them), the chord on a flat mesh, and the torus's closed forms
// (tests/io/obj_test.cpp) for the Blender export in tests/data/obj/.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "inbetween/io/curve_file.hpp"
#include "inbetween/io/obj.hpp"
#include "inbetween/paths/mesh_path.hpp"
#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using inbetween::Vec3d;
using inbetween::test::CliRun;
using inbetween::test::run_cli;
using inbetween::test::slurp;
using inbetween::test::test_dir;
using inbetween::test::write_test_file;

const std::string kTorus = std::string(INBETWEEN_SOURCE_DIR) + "/tests/data/obj/blender_torus.obj";

// A 2 × 2 grid of unit squares in y = 0 as quads (vertex (i, k) is line i·3 + k + 1).
std::string flat_obj() {
  std::string s = "# 3 x 3 vertices\n";
  for (int i = 0; i <= 2; ++i)
    for (int k = 0; k <= 2; ++k) s += "v " + std::to_string(i) + " 0 " + std::to_string(k) + "\n";
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k) {
      const int a = i * 3 + k + 1;
      s += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 4) + " " +
           std::to_string(a + 3) + "\n";
    }
  return s;
}

std::vector<Vec3d> parse_rows(const std::string& text) {
  std::vector<Vec3d> out;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,z");
  while (std::getline(in, line)) {
    Vec3d p;
    char c1 = 0, c2 = 0;
    std::istringstream ls(line);
    ls >> p.x >> c1 >> p.y >> c2 >> p.z;
    EXPECT_TRUE(ls && c1 == ',' && c2 == ',') << line;
    out.push_back(p);
  }
  return out;
}

double length(const std::vector<Vec3d>& pts) { return inbetween::polyline_length(pts); }

TEST(PathSurfaceCli, FlatMeshPlaneAndGreedyAreTheChord) {
  const auto obj = write_test_file("flat.obj", flat_obj());
  for (const char* method : {"plane", "greedy"}) {
    SCOPED_TRACE(method);
    // Vertex 0 = (0, 0, 0), vertex 7 = (2, 0, 1): the chord √5.
    const CliRun r = run_cli("path surface " + obj.string() + " --from 0 --to 7 --method " + method);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = parse_rows(r.out);
    ASSERT_GE(rows.size(), 2u);
    EXPECT_EQ(rows.front(), (Vec3d{0, 0, 0}));
    EXPECT_EQ(rows.back(), (Vec3d{2, 0, 1}));
    EXPECT_NEAR(length(rows), std::sqrt(5.0), 1e-12);
  }
  // Edges: the quads are split along their (first, third) corner diagonal, (i, k)-(i+1, k+1);
  // (0,0) → (2,1) is one diagonal and one unit edge, √2 + 1.
  const CliRun r = run_cli("path surface " + obj.string() + " --from 0 --to 7 --method edges");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(length(parse_rows(r.out)), std::sqrt(2.0) + 1, 1e-12);
}

TEST(PathSurfaceCli, BlenderTorusRowsAreTheLibrarysPath) {
  auto mesh = inbetween::parse_obj(slurp(kTorus), "torus.obj");
  ASSERT_TRUE(mesh);
  for (const char* method : {"plane", "greedy", "edges"}) {
    SCOPED_TRACE(method);
    const CliRun r = run_cli("path surface " + kTorus + " --from 0 --to 24 --method " + method);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string m = method;
    auto want = m == "plane" ? inbetween::plane_mesh_path(*mesh, 0, 24)
                : m == "greedy" ? inbetween::greedy_mesh_path(*mesh, 0, 24)
                                : inbetween::edge_mesh_path(*mesh, 0, 24);
    ASSERT_TRUE(want);
    EXPECT_EQ(parse_rows(r.out), *want);  // shortest round-trip text: exact
  }
  // Downhill from the top of the tube (vertex 2) to the lowest ring, y = −0.35; written to a file.
  const auto out = test_dir() / "down.csv";
  const CliRun r = run_cli("path surface " + kTorus + " --downhill 2 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  const auto rows = parse_rows(slurp(out));
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows.front(), mesh->vertex(2));
  EXPECT_NEAR(rows.back().y, -0.35, 1e-12);
  // --up -y: "downhill" is then up, to the top ring, y = 0.35.
  const CliRun up = run_cli("path surface " + kTorus + " --downhill 6 --up 0 -1 0");
  ASSERT_EQ(up.exit_code, 0) << up.err;
  EXPECT_NEAR(parse_rows(up.out).back().y, 0.35, 1e-12);
}

struct Bad {
  std::string obj, args, expect;
};

TEST(PathSurfaceCli, BadInputExitsTwoNamingTheLineOrArgument) {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n";
  const std::vector<Bad> cases = {
      {square + "f 1 2 3\nf 1 3 5\n", "--from 0 --to 2", "m.obj: line 6: face names vertex 5"},  // missing vertex
      {square + "f 1 2 3\nf 1 3 -9\n", "--from 0 --to 2", "m.obj: line 6:"},                     // relative, out of range
      {"v 0 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\n", "--from 0 --to 2", "m.obj: line 2: 'v' coordinate \"nan\" is not finite"},
      {"", "--from 0 --to 1", "m.obj: the mesh has no vertices"},
      {square, "--from 0 --to 1", "m.obj: the mesh has no faces"},
      {square + "f 1 2 3 4\n", "--from 0 --to 4", "--to 4: vertex 4 is not one of the mesh's 4 vertices"},
      {square + "f 1 2 3 4\n", "--from -1 --to 2", "--from -1: vertex -1 is not one of"},
      {square + "f 1 2 3 4\n", "--downhill 9", "--downhill 9: vertex 9 is not one of"},
      {square + "f 1 2 3 4\n", "--from 0", "give --from I and --to J, or --downhill I"},
      {square + "f 1 2 3 4\n", "--downhill 0 --method plane", "--downhill takes no --from, --to or --method"},
      {square + "f 1 2 3 4\n", "--downhill 0 --up 0 0 0", "--up: up must be a non-zero finite vector"},
      {square + "f 1 2 3\nv 5 5 5\nv 6 5 5\nv 5 5 6\nf 5 6 7\n", "--from 0 --to 4 --method edges", "not connected"},
  };
  for (const Bad& c : cases) {
    SCOPED_TRACE(c.args + " on:\n" + c.obj);
    const auto obj = write_test_file("m.obj", c.obj);
    const auto out = test_dir() / "out.csv";
    const CliRun r = run_cli("path surface " + obj.string() + " " + c.args + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));  // nothing written on an error
  }
  // The texts' plane walk that closes a loop on the torus: exit 2 with the reason, no rows.
  const CliRun loop = run_cli("path surface " + kTorus + " --from 2 --to 44 --method plane");
  EXPECT_EQ(loop.exit_code, 2);
  EXPECT_EQ(loop.out, "");
  EXPECT_NE(loop.err.find("vertex 2: the plane walk returns to vertex 2"), std::string::npos) << loop.err;
}

}  // namespace

namespace {

// Issue 21: `path surface /dev/zero` read the device until 4 GB were allocated.  Now refused at
// once: exit 2, one line naming the file.
TEST(PathSurfaceCli, ADeviceIsRefusedAtOnce) {
  const auto start = std::chrono::steady_clock::now();
  const CliRun r = run_cli("path surface /dev/zero --from 0 --to 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("inbetween: /dev/zero: is not a regular file", 0), 0u) << r.err;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

}  // namespace

namespace {

// Issue 21, messages: an OBJ literal of 5 000 characters was quoted whole, a magnitude printed in
// 309 digits.  Now a short escaped excerpt and the shortest round-trip number.
TEST(PathSurfaceCli, ObjErrorsQuoteShortly) {
  const fs::path literal = write_test_file("literal.obj", "v 1 2 " + std::string(5000, 'x') + "\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CliRun r = run_cli("path surface '" + literal.string() + "' --from 0 --to 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("line 1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("xxx\"… (5000 bytes)"), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), literal.string().size() + 150) << r.err;
  const fs::path big = write_test_file("big.obj", "v 1 2 3\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n");
  r = run_cli("path surface '" + big.string() + "' --from 0 --to 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("magnitude 1e+308, beyond the mesh limit 2.2471164185778946e+307"), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), big.string().size() + 120) << r.err;
}


// Surface files (`path surface SURFACE.json`): numbers read back from the CSV, checked against the
// closed forms of the example surfaces (examples/surfaces/).
const std::string kExamples = std::string(INBETWEEN_SOURCE_DIR) + "/examples/surfaces/";

// Rows of `columns` comma-separated numbers after a header line `header`.
std::vector<std::vector<double>> numeric_rows(const std::string& text, const std::string& header, std::size_t columns) {
  std::vector<std::vector<double>> out;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, header);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream ls(line);
    std::string field;
    while (std::getline(ls, field, ',')) row.push_back(std::stod(field));
    EXPECT_EQ(row.size(), columns) << line;
    out.push_back(row);
  }
  return out;
}

TEST(PathSurfaceCli, UvLineOnTheSphereIsACircleOfLatitude) {
  // examples/surfaces/sphere.json: R = 2 at the origin.  The u-line at latitude v = 0.5 keeps the
  // distance R·cos 0.5 from the axis and the height R·sin 0.5; its ends are S(0, 0.5), S(1.5, 0.5).
  const CliRun r = run_cli("path surface " + kExamples + "sphere.json --from 0 0.5 --to 1.5 0.5 --count 7");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = numeric_rows(r.out, "u,v,x,y,z", 5);
  ASSERT_EQ(rows.size(), 7u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_NEAR(rows[i][0], 1.5 * double(i) / 6, 1e-15);
    EXPECT_EQ(rows[i][1], 0.5);
    EXPECT_NEAR(std::hypot(rows[i][2], rows[i][4]), 2 * std::cos(0.5), 1e-14);
    EXPECT_NEAR(rows[i][3], 2 * std::sin(0.5), 1e-15);
    EXPECT_NEAR(std::atan2(rows[i][4], rows[i][2]), rows[i][0], 1e-14);
  }
}

TEST(PathSurfaceCli, CurveFilePassesThroughThePoints) {
  // --curve: a catmull-rom curve file whose control points are the CSV's points (the curve
  // interpolates them), for a surface file and a mesh alike.
  for (const std::string& args : {kExamples + "sphere.json --from 0 0.5 --to 1.5 0.5 --count 5",
                                  kTorus + " --from 0 --to 24 --method plane"}) {
    SCOPED_TRACE(args);
    const auto curve = test_dir() / "c.json";
    const CliRun r = run_cli("path surface " + args + " --curve " + curve.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::istringstream in(r.out);
    std::string header;
    std::getline(in, header);
    const std::size_t columns = header == "u,v,x,y,z" ? 5 : 3;
    const auto rows = numeric_rows(r.out, header, columns);
    auto file = inbetween::parse_curve_json(slurp(curve), "c.json");
    ASSERT_TRUE(file) << file.error().describe();
    const auto json = nlohmann::json::parse(slurp(curve));
    EXPECT_EQ(json["type"], "catmull-rom");
    ASSERT_EQ(json["points"].size(), rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(json["points"][i][c].get<double>(), rows[i][columns - 3 + c]);
  }
  const CliRun single = run_cli("path surface " + kExamples + "sphere.json --from 0 0.5 --to 0 0.5 --curve x.json");
  EXPECT_EQ(single.exit_code, 2);
  EXPECT_NE(single.err.find("--curve: the path is a single point"), std::string::npos) << single.err;
}

TEST(PathSurfaceCli, DownhillOnTheBowlAndTheSphere) {
  // examples/surfaces/bowl.json samples y = x² + z² (the bicubic grid reproduces it): downhill from
  // S(1.5, 1) runs along the radius to the origin, ending within one step (default 0.5 / 20).
  const CliRun bowl = run_cli("path surface " + kExamples + "bowl.json --downhill 1.5 1");
  ASSERT_EQ(bowl.exit_code, 0) << bowl.err;
  const auto rows = parse_rows(bowl.out);
  ASSERT_GT(rows.size(), 10u);
  EXPECT_EQ(rows.front(), (Vec3d{1.5, 3.25, 1}));
  for (const Vec3d& p : rows) {
    EXPECT_NEAR(p.x - 1.5 * p.z, 0.0, 1e-12);
    EXPECT_NEAR(p.y, p.x * p.x + p.z * p.z, 1e-12);
  }
  EXPECT_LE(std::hypot(rows.back().x, rows.back().z), 0.5 / 20);
  // The sphere, from a point X Y Z pulled onto it: down the meridian (z/x constant) to the bottom.
  const CliRun sphere = run_cli("path surface " + kExamples + "sphere.json --method downhill --from 3 1 1.5 --step 0.01");
  ASSERT_EQ(sphere.exit_code, 0) << sphere.err;
  const auto s = parse_rows(sphere.out);
  ASSERT_GT(s.size(), 10u);
  for (const Vec3d& p : s) {
    EXPECT_NEAR(norm(p), 2.0, 1e-12);
    EXPECT_NEAR(p.z - 0.5 * p.x, 0.0, 1e-12);
  }
  EXPECT_LT(distance(s.back(), Vec3d{0, -2, 0}), 0.01);
}

TEST(PathSurfaceCli, SurfaceFileErrorsNameTheOptionOrThePlace) {
  const std::string sphere = kExamples + "sphere.json";
  const auto patch = write_test_file("patch.json", R"({"inbetween_surface": 1, "bezier_patch": {"points": [
      [[0,0,0],[1,0,0],[2,0,0],[3,0,0]], [[0,0,1],[1,0,1],[2,0,1],[3,0,1]],
      [[0,0,2],[1,0,2],[2,0,2],[3,0,2]], [[0,0,3],[1,0,3],[2,0,3],[3,0,3]]]}})");
  struct Bad {
    std::string file, args, expect;
  };
  const std::vector<Bad> cases{
      {sphere, "--from 0 0 --to 1", "--to 1: on a surface file --to takes two numbers U V"},
      {sphere, "--from 0 0", "give --from U V and --to U V, or --downhill U V"},
      {sphere, "--from 0 0 --to 1 1 --count 1", "--count 1: must be 2"},
      {sphere, "--from 0 0 --to 1 1 --method plane", "--method plane: a surface file takes --method uv"},
      {sphere, "--from 0 0 --to 1 1 --step 0.1", "--step and --max-steps are for --downhill"},
      {sphere, "--downhill 0 1 --step -1", "--step: step must be finite and > 0"},
      {sphere, "--downhill 0 1 --up 0 0 0", "--up: up must be a non-zero finite vector"},
      {sphere, "--downhill 0 0 0", "--downhill 0 0 0: the surface gradient is zero"},
      {patch.string(), "--downhill 0.5 0.5", "patch.json: a bezier_patch has no implicit form"},
      {write_test_file("t.json", R"({"inbetween_surface": 1, "torus": {"major_radius": 1, "minor_radius": 2}})").string(),
       "--from 0 0 --to 1 1", "t.json:/torus/major_radius: the torus's major_radius must be > minor_radius"},
      {write_test_file("p.json", R"({"inbetween_surface": 1, "plane": {"u_axis": [1e150, 0, 0]}})").string(),
       "--from 0 0 --to 1e300 0", "--from 0 0 --to 1e+300 0: the (u, v) line leaves the range of finite numbers"},
      {write_test_file("h.json", R"({"inbetween_surface": 1, "height_field": {"heights": [[0, 1], [2, "x"]]}})").string(),
       "--from 0 0 --to 1 1", "h.json:/height_field/heights/1/1: expected a number, got string"},
      {write_test_file("two.json", R"({"inbetween_surface": 1, "sphere": {"radius": 1}, "plane": {}})").string(),
       "--from 0 0 --to 1 1", "two.json: expected exactly one surface"},
      {std::string(INBETWEEN_SOURCE_DIR) + "/examples/environments/capsule_slot.json", "--from 0 0 --to 1 1",
       "capsule_slot.json: an environment file, not a surface file"},
      {std::string(INBETWEEN_SOURCE_DIR) + "/examples/curves/bezier-path.json", "--from 0 0 --to 1 1",
       "bezier-path.json: a curve file, not a surface file"},
      {kTorus, "--from 0 1 --to 3", "--from 0 1: on a mesh --from takes one vertex index"},
      {kTorus, "--from 0.5 --to 3", "--from 0.5: a vertex index is a whole number"},
      {kTorus, "--from 0 --to 3 --count 4", "--count, --step and --max-steps are for a surface file"},
  };
  for (const Bad& c : cases) {
    SCOPED_TRACE(c.args);
    const auto out = test_dir() / "out.csv";
    const CliRun r = run_cli("path surface " + c.file + " " + c.args + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
