// holoray/cli: SIGINT and SIGTERM as a request to stop between frames, so a
// long sequence interrupted by the user or a job scheduler leaves only
// complete frames and can be resumed (issue 5, "Nothing lost").
#pragma once

namespace holoray::cli {

/// While it lives, the first SIGINT or SIGTERM is recorded instead of ending
/// the process; a second one ends it at once (the default action is restored
/// by the first). The destructor puts the previous handlers back. One at a
/// time: a signal handler can only reach process-wide state.
class StopOnSignal {
 public:
  StopOnSignal();
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  /// The signal received (SIGINT or SIGTERM), or 0 when none has come.
  int signal() const;
  bool requested() const { return signal() != 0; }
  /// The conventional exit status of a run stopped by it: 128 + signal.
  int exit_status() const { return 128 + signal(); }
};

}  // namespace holoray::cli
