// Overloaded{lambda...}: one callable from several lambdas, for std::visit over a variant (the
// parameter table's fields and values). Header-only.
#pragma once

namespace aosuite {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
// C++20 deduces this for an aggregate; clang before 17 (the fuzz build's) still needs it said.
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace aosuite
