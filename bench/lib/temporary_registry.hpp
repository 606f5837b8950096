#pragma once
// The output temporaries this process has open, for its signal handler:
// every signal that ends a process by default and can be caught (INT, TERM,
// HUP, QUIT, USR1, USR2, ALRM, VTALRM, PROF, XCPU, XFSZ, PIPE, POLL, PWR,
// STKFLT, the real-time signals, and a fault's ABRT, BUS, FPE, ILL, SEGV,
// SYS, TRAP) removes them (unlinkat on the folder's descriptor,
// async-signal-safe), then the signal takes its default action, so the
// process still ends by that signal. A signal that was ignored when the
// first temporary was registered (nohup's SIGHUP) or handled by someone else
// (a sanitizer's SIGSEGV) is left so. SIGKILL cannot be caught: its
// temporary stays, named `.NAME.tmp.*` beside the target (docs/formats.md).
namespace rb {

// At most this many temporaries at once are removed on a signal (a sweep's
// jobs each write one cache entry at a time); more are still written, only
// not removed on a signal.
inline constexpr int kMaxRegisteredTemporaries = 64;

// Registers name (one path component, as openat takes it) in the folder
// open as dirfd; installs the handlers on first use. The slot, or -1 when
// the table is full or the name too long.
int register_temporary(int dirfd, const char* name);

// The slot no longer names a temporary (it was renamed or removed).
void unregister_temporary(int slot);

}  // namespace rb
