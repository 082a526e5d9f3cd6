// `make bench-scene`: scene compiler build time and SAH cost for the Stanford bunny, Sponza and
// the conference room (single-threaded; the OBJ is loaded once, outside the timed loop).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "compiler.hpp"
#include "error.hpp"

namespace {

struct Loaded {
  rc::scene::Scene scene;
  double load_ms = 0.0;
};

std::map<std::string, Loaded>& cache() {
  static std::map<std::string, Loaded> c;
  return c;
}

struct Row {
  size_t triangles = 0, dropped = 0, nodes = 0, leaves = 0, empty = 0, refs = 0, max_leaf = 0;
  uint32_t depth = 0;
  double load_ms = 0, kdtree_ms = 0, compile_ms = 0, sah = 0, mean_leaf = 0;
};
std::map<std::string, Row>& rows() {
  static std::map<std::string, Row> r;
  return r;
}

void BM_SceneBuild(benchmark::State& state, const std::string& model) {
  const std::string path = std::string(RC_SOURCE_DIR) + "/../shared/models/" + model;
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("model not found: " + path).c_str());
    return;
  }
  auto it = cache().find(model);
  if (it == cache().end()) {
    const auto t0 = std::chrono::steady_clock::now();
    Loaded l;
    l.scene = rc::scene::load_scene(path, {});
    l.load_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    it = cache().emplace(model, std::move(l)).first;
  }
  const Loaded& loaded = it->second;
  rc::scene::BuildStats st;
  double total_ms = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    rc::scene::Compiled c = rc::scene::compile_scene(loaded.scene, rc::scene::CompileOptions());
    total_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    st = std::move(c.stats);
    benchmark::DoNotOptimize(c.image.data());
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["triangles"] = static_cast<double>(st.triangles);
  state.counters["nodes"] = static_cast<double>(st.nodes);
  state.counters["depth"] = st.depth;
  state.counters["SAH"] = st.sah_cost;
  state.counters["kdtree_ms"] = st.build_ms;
  Row& r = rows()[model];
  r = {st.triangles,  st.dropped,  st.nodes,    st.leaves,      st.empty_leaves,
       st.references, st.max_leaf, st.depth,    loaded.load_ms, st.build_ms,
       total_ms / n,  st.sah_cost, st.mean_leaf};
}

BENCHMARK_CAPTURE(BM_SceneBuild, bunny, std::string("bunny/bunny.obj"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_SceneBuild, sponza, std::string("sponza/sponza.obj"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_SceneBuild, conference, std::string("conference/conference.obj"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::printf("\nscene compiler, fp24, single-threaded (compile = transforms + kd-tree + image)\n");
  std::printf("%-28s %9s %7s %9s %9s %9s %8s %8s %6s %6s %6s %5s\n", "model", "triangles",
              "dropped", "load ms", "kd ms", "total ms", "SAH", "nodes", "leaf", "max", "refs",
              "depth");
  for (const auto& [model, r] : rows())
    std::printf("%-28s %9zu %7zu %9.0f %9.0f %9.0f %8.2f %8zu %6.2f %6zu %6.2f %5u\n",
                model.c_str(), r.triangles, r.dropped, r.load_ms, r.kdtree_ms, r.compile_ms, r.sah,
                r.nodes, r.mean_leaf, r.max_leaf,
                static_cast<double>(r.refs) / static_cast<double>(r.triangles - r.dropped),
                r.depth);
  std::printf("(leaf = mean triangles per non-empty leaf, refs = leaf references per triangle)\n");
  return 0;
}
