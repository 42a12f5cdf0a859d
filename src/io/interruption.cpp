// interruption.cpp: see interruption.h. The handler touches only lock-free atomics and fixed arrays and calls only
// async-signal-safe functions (unlink, sigaction, raise).
#include "io/interruption.h"

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>

#include <unistd.h>

namespace lucent {
namespace {

constexpr int kSlots = 64;
constexpr std::size_t kPathBytes = 4096;  // PATH_MAX
constexpr std::array<int, 3> kSignals = {SIGINT, SIGTERM, SIGHUP};

enum SlotState : int { kFree = 0, kFilling = 1, kRegistered = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathBytes] = {};
};

std::array<Slot, kSlots> g_slots;
std::atomic<int> g_deferring{0};  // DeferredInterruptions alive
std::atomic<int> g_pending{0};    // the signal recorded while deferring, not yet taken
std::atomic<int> g_signals{0};    // signals seen while deferring (the second ends the process)
static_assert(std::atomic<int>::is_always_lock_free);

void remove_registered_files() {
  for (Slot& slot : g_slots)
    if (slot.state.load() == kRegistered) ::unlink(slot.path);
}

[[noreturn]] void end_process(int signal) {
  remove_registered_files();
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  ::sigaction(signal, &action, nullptr);
  ::raise(signal);  // delivered when the handler returns (or at once outside it): the default action ends the process
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, signal);
  ::sigprocmask(SIG_UNBLOCK, &set, nullptr);
  ::_exit(128 + signal);  // not reached
}

extern "C" void on_termination_signal(int signal) {
  if (g_deferring.load() > 0 && g_signals.fetch_add(1) == 0) {
    g_pending.store(signal);
    return;
  }
  end_process(signal);
}

}  // namespace

void install_interruption_handlers() {
  struct sigaction action {};
  action.sa_handler = on_termination_signal;
  sigemptyset(&action.sa_mask);
  for (int signal : kSignals) sigaddset(&action.sa_mask, signal);  // one handler at a time
  action.sa_flags = SA_RESTART;
  for (int signal : kSignals) {
    struct sigaction old {};
    // A signal the parent ignores (nohup, a shell's background job) stays ignored.
    if (::sigaction(signal, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    ::sigaction(signal, &action, nullptr);
  }
}

RemoveOnSignal::RemoveOnSignal(const std::string& path) {
  if (path.empty() || path.size() >= kPathBytes) return;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_slots[static_cast<std::size_t>(i)].state.compare_exchange_strong(expected, kFilling)) continue;
    Slot& slot = g_slots[static_cast<std::size_t>(i)];
    std::memcpy(slot.path, path.c_str(), path.size() + 1);
    slot.state.store(kRegistered);
    slot_ = i;
    return;
  }
}

RemoveOnSignal::~RemoveOnSignal() {
  if (slot_ >= 0) g_slots[static_cast<std::size_t>(slot_)].state.store(kFree);
}

DeferredInterruption::DeferredInterruption() { g_deferring.fetch_add(1); }

DeferredInterruption::~DeferredInterruption() {
  if (g_deferring.fetch_sub(1) != 1) return;
  g_signals.store(0);
  if (const int signal = g_pending.exchange(0)) end_process(signal);
}

int DeferredInterruption::received() const { return g_pending.load(); }

int DeferredInterruption::take() { return g_pending.exchange(0); }

}  // namespace lucent
