// main() for the benchmarks that render in-process: they run with huge-page malloc as the
// `aosuite` GL commands do (renderer/huge_page_malloc.hpp), so frame totals match the CLI's.
#pragma once

#include <benchmark/benchmark.h>

#include "renderer/huge_page_malloc.hpp"

#define AOSUITE_RENDERING_BENCHMARK_MAIN()                            \
  int main(int argc, char** argv) {                                   \
    aosuite::reexec_with_huge_page_malloc(argv);                      \
    benchmark::Initialize(&argc, argv);                               \
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1; \
    benchmark::RunSpecifiedBenchmarks();                              \
    benchmark::Shutdown();                                            \
    return 0;                                                         \
  }
