#include "bench/lib/temporary_registry.hpp"

#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>

namespace rb {

namespace {

enum : int { kFree = 0, kClaimed = 1, kActive = 2 };

// A fixed table: the handler reads it without allocating or locking.
struct Slot {
  std::atomic<int> state{kFree};
  int dirfd = -1;
  pid_t owner = 0;  // a forked child (a plug-in's) never removes its parent's files
  char name[NAME_MAX + 1] = {};
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the table's states");

Slot slots[kMaxRegisteredTemporaries];

// Every signal whose default action ends the process and that can be
// caught: those a user or a system sends (INT, TERM, HUP, QUIT, USR1, USR2,
// ALRM, VTALRM, PROF, XCPU, XFSZ, PIPE, POLL, PWR, STKFLT) and those of a
// fault (ABRT, BUS, FPE, ILL, SEGV, SYS, TRAP), after which the table is
// still only read; the real-time signals are added at install. The handler
// unlinks and re-raises, so each still ends the process, a core dump
// included where its default makes one. (KILL and STOP cannot be caught.)
constexpr int kSignals[] = {SIGINT,  SIGTERM, SIGHUP,  SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM,   SIGVTALRM,
                            SIGPROF, SIGXCPU, SIGXFSZ, SIGPIPE, SIGPOLL, SIGPWR,  SIGSTKFLT, SIGABRT,
                            SIGBUS,  SIGFPE,  SIGILL,  SIGSEGV, SIGSYS,  SIGTRAP};

// kSignals and SIGRTMIN..SIGRTMAX (not constants: the C library keeps the
// first few real-time signals for itself).
sigset_t handled_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (const int signal_number : kSignals) sigaddset(&set, signal_number);
  for (int signal_number = SIGRTMIN; signal_number <= SIGRTMAX; ++signal_number) sigaddset(&set, signal_number);
  return set;
}

void remove_temporaries(int signal_number) {
  const int saved = errno;
  const pid_t self = ::getpid();
  for (Slot& slot : slots)
    if (slot.state.load(std::memory_order_acquire) == kActive && slot.owner == self)
      ::unlinkat(slot.dirfd, slot.name, 0);
  errno = saved;
  // SA_RESETHAND made the action the default again; the signal is blocked
  // until the handler returns, then ends the process as it would have
  ::raise(signal_number);
}

void install_handlers() {
  const sigset_t handled = handled_signals();
  for (int signal_number = 1; signal_number < NSIG; ++signal_number) {
    if (sigismember(&handled, signal_number) != 1) continue;
    struct sigaction old {};
    if (::sigaction(signal_number, nullptr, &old) != 0) continue;
    if ((old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL) continue;  // ignored, or someone else's
    struct sigaction action {};
    action.sa_handler = remove_temporaries;
    action.sa_mask = handled;  // one handler at a time
    action.sa_flags = SA_RESETHAND;
    ::sigaction(signal_number, &action, nullptr);
  }
}

}  // namespace

int register_temporary(int dirfd, const char* name) {
  static std::once_flag installed;
  std::call_once(installed, install_handlers);
  if (std::strlen(name) > NAME_MAX) return -1;
  for (int i = 0; i < kMaxRegisteredTemporaries; ++i) {
    int expected = kFree;
    if (!slots[i].state.compare_exchange_strong(expected, kClaimed, std::memory_order_acquire)) continue;
    slots[i].dirfd = dirfd;
    slots[i].owner = ::getpid();
    std::strcpy(slots[i].name, name);
    slots[i].state.store(kActive, std::memory_order_release);
    return i;
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0 && slot < kMaxRegisteredTemporaries) slots[slot].state.store(kFree, std::memory_order_release);
}

}  // namespace rb
