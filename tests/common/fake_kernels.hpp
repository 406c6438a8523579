#pragma once
// The kernels of the tests' fake back-ends: each quantity a function of the result (kernels.hpp).

#include <functional>
#include <memory>
#include <utility>

#include "modalbench/kernels.hpp"
#include "modalbench/result.hpp"

namespace modalbench::testing {

/// Each kernel runs its function; one left empty computes nothing (the fake leaves that quantity out).
/// The fakes give no mode shapes: asked for them (the comparison asks), they leave them empty.
class FakeKernels final : public Kernels {
 public:
  using Fill = std::function<void(Result&)>;
  FakeKernels(Fill modes, Fill statics = {}, Fill frf = {})
      : modes_(std::move(modes)), statics_(std::move(statics)), frf_(std::move(frf)) {}
  void modes(Result& r) override { run(modes_, r); }
  void shapes(Result&) override {}
  void statics(Result& r) override { run(statics_, r); }
  void frf(Result& r) override { run(frf_, r); }

 private:
  static void run(const Fill& f, Result& r) {
    if (f) f(r);
  }
  Fill modes_, statics_, frf_;
};

/// A fake back-end whose model is its frequencies: `fill` is its modes kernel.
inline std::unique_ptr<Kernels> modes_kernel(FakeKernels::Fill fill) {
  return std::make_unique<FakeKernels>(std::move(fill));
}

}  // namespace modalbench::testing
