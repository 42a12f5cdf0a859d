// long_call.cpp: see long_call.h.
#include "long_call.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "bindings.h"
#include "python_warnings.h"

namespace lucent::python {
namespace {

constexpr std::chrono::milliseconds kPollInterval{50};

// The work's thread and its outcome.
class Worker {
 public:
  Worker(const std::function<void(LongCallControl&)>& work, LongCallControl& control)
      : thread_([this, &work, &control] { run(work, control); }) {}
  ~Worker() {
    if (thread_.joinable()) thread_.join();
  }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Waits up to kPollInterval; true once the work has returned. Call without the GIL.
  bool wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    return finished_cv_.wait_for(lock, kPollInterval, [this] { return finished_; });
  }
  void join() { thread_.join(); }
  std::exception_ptr failure() const { return failure_; }

 private:
  void run(const std::function<void(LongCallControl&)>& work, LongCallControl& control) {
    try {
      work(control);
    } catch (...) {
      failure_ = std::current_exception();
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    finished_ = true;
    finished_cv_.notify_all();
  }

  std::mutex mutex_;
  std::condition_variable finished_cv_;
  bool finished_ = false;
  std::exception_ptr failure_;
  std::thread thread_;  // last: it starts once the members it uses exist
};

// One wake-up of the waiting thread, with the GIL: signals, then progress, then warnings. Throws what they raise.
void poll(LongCallControl& control, const py::handle& progress, double& reported) {
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  const double fraction = control.fraction.load();
  if (!progress.is_none() && fraction >= 0.0 && fraction != reported) {
    reported = fraction;
    progress(fraction);
  }
  emit_warnings();
}

// The outcome of abandonable work, shared with its thread (which may outlive the call).
struct AbandonableState {
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false;
  std::exception_ptr failure;
};

}  // namespace

namespace {

// Runs `work` on a detached thread that owns it; its outcome lands in the returned state.
std::shared_ptr<AbandonableState> start_abandonable(std::function<void()> work) {
  auto state = std::make_shared<AbandonableState>();
  std::thread([state, work = std::move(work)] {
    std::exception_ptr failure;
    try {
      work();
    } catch (...) {
      failure = std::current_exception();
    }
    const std::lock_guard<std::mutex> lock(state->mutex);
    state->failure = failure;
    state->finished = true;
    state->finished_cv.notify_all();
  }).detach();
  return state;
}

}  // namespace

void run_abandonable(std::function<void()> work) {
  const std::shared_ptr<AbandonableState> state = start_abandonable(std::move(work));
  for (bool finished = false; !finished;) {
    {
      const py::gil_scoped_release unlocked;
      std::unique_lock<std::mutex> lock(state->mutex);
      finished = state->finished_cv.wait_for(lock, kPollInterval, [&] { return state->finished; });
    }
    emit_warnings();
    if (!finished && PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  if (state->failure) std::rethrow_exception(state->failure);
}

void run_long_call(const std::function<void(LongCallControl&)>& work, const py::handle& progress) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw py::type_error("progress: expected a callable taking the fraction done, or None");
  LongCallControl control;
  std::exception_ptr raised;  // from Python (a signal handler, the progress callback, a warnings filter)
  double reported = -1.0;
  {
    Worker worker(work, control);
    for (bool finished = false; !finished;) {
      {
        const py::gil_scoped_release unlocked;
        finished = worker.wait();
      }
      if (raised || finished) continue;
      try {
        poll(control, progress, reported);
      } catch (...) {
        raised = std::current_exception();
        control.stop = true;  // the work returns at its next poll of the flag
      }
    }
    const py::gil_scoped_release unlocked;
    worker.join();
    if (!raised && worker.failure()) raised = worker.failure();
  }
  if (raised) {
    try {
      emit_warnings();
    } catch (...) {  // the call's own exception says more than a warning turned into an error
    }
    std::rethrow_exception(raised);
  }
  emit_warnings();
  if (!progress.is_none() && reported != 1.0) progress(1.0);
}

}  // namespace lucent::python

namespace lucent::python {

void LongCallControl::set_step(std::string_view name) {
  const std::lock_guard<std::mutex> lock(step_mutex_);
  step_ = name;
}

std::string LongCallControl::step() const {
  const std::lock_guard<std::mutex> lock(step_mutex_);
  return step_;
}

void run_staged_call(std::function<void(LongCallControl&)> work, const py::handle& progress) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw py::type_error("progress: expected a callable taking (step, fraction), or None");
  auto control = std::make_shared<LongCallControl>();
  const std::shared_ptr<AbandonableState> state =
      start_abandonable([control, work = std::move(work)] { work(*control); });

  std::pair<std::string, double> reported{"", -1.0};
  const auto wait = [&](std::chrono::milliseconds interval) {
    const py::gil_scoped_release unlocked;
    std::unique_lock<std::mutex> lock(state->mutex);
    return state->finished_cv.wait_for(lock, interval, [&] { return state->finished; });
  };
  for (bool finished = false; !finished;) {
    finished = wait(kPollInterval);
    try {
      if (!finished && PyErr_CheckSignals() != 0) throw py::error_already_set();
      std::pair<std::string, double> now{control->step(), control->fraction.load()};
      if (!progress.is_none() && now.second >= 0.0 && now != reported) {
        reported = now;
        progress(now.first, now.second);
      }
      emit_warnings();
    } catch (...) {
      control->stop = true;  // the work stops at its next poll; what it has not finished by then is abandoned
      wait(std::chrono::milliseconds(static_cast<int>(1000 * kAbandonAfterInterruptSeconds)));
      throw;
    }
  }
  emit_warnings();
  if (state->failure) std::rethrow_exception(state->failure);
}

}  // namespace lucent::python
