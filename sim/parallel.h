#pragma once
// Parallel loops for the machine without oneTBB in the headers kernels include (every pass
// includes sim/dispatch.h): the loop body crosses into sim/parallel.cpp through a FunctionRef,
// one indirect call per chunk, while the kernel stays inlined in the chunk body.

#include <cstddef>
#include <memory>
#include <type_traits>
#include <utility>

namespace sim {

// A non-owning reference to a callable: one indirect call, no allocation (C++26's
// std::function_ref, reduced to what the machine needs). The callable must outlive the reference.
template <typename Signature>
class FunctionRef;

template <typename R, typename... Args>
class FunctionRef<R(Args...)> {
 public:
  template <typename F>
    requires(!std::is_same_v<std::remove_cvref_t<F>, FunctionRef> && std::is_invocable_r_v<R, F&, Args...>)
  FunctionRef(F&& callable)  // NOLINT(google-explicit-constructor): converts like std::function_ref
      : callable_(const_cast<void*>(static_cast<const void*>(std::addressof(callable)))),
        call_([](void* target, Args... args) -> R {
          return (*static_cast<std::remove_reference_t<F>*>(target))(std::forward<Args>(args)...);
        }) {}

  R operator()(Args... args) const { return call_(callable_, std::forward<Args>(args)...); }

 private:
  void* callable_;
  R (*call_)(void*, Args...);
};

// Runs body(i) for every i in [0, count) on oneTBB's worker threads, in any order.
void ParallelFor(std::size_t count, FunctionRef<void(std::size_t)> body);

}  // namespace sim
