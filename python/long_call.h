// long_call.h: calls that can run for seconds (references, renders of many frames) stay responsive to Python: the
// work runs on a thread of its own while the calling thread waits with the GIL released, waking every 50 ms to
// check for signals (Ctrl-C raises KeyboardInterrupt there and only there: Python runs signal handlers on the main
// thread), to call the progress callback and to emit the warnings queued so far.
#pragma once
#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>

#include <pybind11/pybind11.h>

namespace lucent::python {

// Shared between the waiting Python thread and the work.
struct LongCallControl {
  std::atomic<bool> stop{false};      // set when the call is interrupted: the work returns early, its result unused
  std::atomic<double> fraction{-1.0};  // the work's progress in [0, 1] (negative: none reported yet)
  // run_staged_call only: the step `fraction` belongs to (set_step before the step's fractions).
  void set_step(std::string_view name);
  std::string step() const;

 private:
  mutable std::mutex step_mutex_;
  std::string step_;
};

// Runs `work` and waits for it. A signal handler that raises (KeyboardInterrupt), or a progress callback that
// raises, sets control.stop, waits for the work to return (it must poll control.stop) and raises that exception;
// nothing the work produced is used. Otherwise rethrows what `work` threw. `progress`: None or a callable
// taking the fraction done, called on the calling thread with the GIL when it changed, and with 1.0 at the end.
void run_long_call(const std::function<void(LongCallControl&)>& work, const pybind11::handle& progress);

// For work that cannot poll a stop flag (a BSSRDF model's total, the tabulated model's photon tables, which are
// cached on disk with a checksum): waits as run_long_call does, but on an interrupt raises at once and leaves the
// work to finish on its own thread, its result unused. `work` therefore owns everything it uses (captures by value,
// shared_ptr for its result).
void run_abandonable(std::function<void()> work);

// For work in steps that polls control.stop only between its parts (a lucent.Renderer's build: the texture atlas,
// the method's precomputation, shader compiles): runs as run_long_call does, with `progress` None or a callable
// taking (step, fraction). On an interrupt it sets control.stop, waits at most kAbandonAfterInterrupt for the work
// to return and then raises, leaving the work to finish on its own thread, its result unused: `work` owns what it
// uses (captures by value, shared_ptr for its result; the control is shared with it).
constexpr double kAbandonAfterInterruptSeconds = 0.5;
void run_staged_call(std::function<void(LongCallControl&)> work, const pybind11::handle& progress);

}  // namespace lucent::python
