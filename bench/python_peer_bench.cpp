// The C++ side of the Python benchmark (bench/python_bench.py, issue 14): the same two workloads
// the script times through the inbetween module, here without Python — 10⁶ u(s) queries of an
// ArcLengthInverse over an AnyCurve read from a curve file, and a bake of a scene file into a
// preallocated table (rows of frame, time and every column, F-curve columns rounded to float as
// `inbetween bake` and the module's bake do).  Same inputs, same s sequence, same frames.
#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/arclength/arc_length_inverse.hpp"
#include "inbetween/io/curve_file.hpp"
#include "inbetween/io/scene.hpp"

namespace {

using namespace inbetween;

std::string read(const std::string& relative) {
  std::ifstream in(std::string(INBETWEEN_SOURCE_DIR) + "/" + relative);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// 10⁶ arc lengths s_k = L·((k·7919) mod N)/N: every s once, in a scattered order (python_bench.py
// builds the same array with NumPy).
constexpr std::size_t kQueries = 1000000;

void BM_Python_UofS_1e6(benchmark::State& state) {
  const AnyCurve curve = *parse_curve_json(read("examples/curves/catmull-rom-centripetal.json"), "curve");
  const auto inv = *ArcLengthInverse<AnyCurve>::build(*ArcLength<AnyCurve>::build(curve));
  std::vector<double> s(kQueries), u(kQueries);
  for (std::size_t k = 0; k < kQueries; ++k) s[k] = inv.length() * double((k * 7919) % kQueries) / double(kQueries);
  for (auto _ : state) {
    for (std::size_t k = 0; k < kQueries; ++k) u[k] = inv.u_at(s[k]);
    benchmark::DoNotOptimize(u.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(kQueries));
}
BENCHMARK(BM_Python_UofS_1e6)->Unit(benchmark::kMillisecond);

// frame22.json (two path objects, a camera on a path, a holding camera) over its range at a step
// of 0.01: 7001 rows.
void BM_Python_Bake_Frame22(benchmark::State& state) {
  const Scene scene = *parse_scene(read("examples/scenes/frame22.json"));
  const auto columns = scene.columns();
  std::vector<double> frames;
  for (std::size_t i = 0; i < 7001; ++i) frames.push_back(16.0 + double(i) * 0.01);
  const std::size_t nc = columns.size() + 2;
  std::vector<double> table(frames.size() * nc), row(columns.size());
  for (auto _ : state) {
    SceneCursor cursor(scene);
    for (std::size_t i = 0; i < frames.size(); ++i) {
      double* r = table.data() + i * nc;
      r[0] = frames[i];
      r[1] = frames[i] / scene.fps();
      scene.sample(frames[i], row, cursor);
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const double v = columns[c].single_precision ? double(float(row[c])) : row[c];
        if (!std::isfinite(v)) state.SkipWithError("not finite");
        r[c + 2] = v;
      }
    }
    benchmark::DoNotOptimize(table.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(frames.size()));
}
BENCHMARK(BM_Python_Bake_Frame22)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
