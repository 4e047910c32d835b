// main() for the benchmarks that render in-process: they run with huge-page malloc as the
// `aosuite` GL commands do (renderer/huge_page_malloc.hpp), so frame totals match the CLI's,
// and name the GL device they measured (AOSUITE_GL and AOSUITE_GL_DEVICE pick it).
#pragma once

#include <benchmark/benchmark.h>

#include "common/huge_page_malloc.hpp"
#include "renderer/renderer.hpp"

namespace aosuite::bench {

// The one GL context of a benchmark process.
inline renderer::Renderer& bench_renderer() {
  static renderer::Renderer r;
  return r;
}

}  // namespace aosuite::bench

#define AOSUITE_RENDERING_BENCHMARK_MAIN()                                        \
  int main(int argc, char** argv) {                                               \
    aosuite::reexec_with_huge_page_malloc(argv);                                  \
    benchmark::Initialize(&argc, argv);                                           \
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;             \
    auto& r = aosuite::bench::bench_renderer();                                   \
    benchmark::AddCustomContext("gl", r.gl_source() + ": " + r.gl_description()); \
    benchmark::RunSpecifiedBenchmarks();                                          \
    benchmark::Shutdown();                                                        \
    return 0;                                                                     \
  }
