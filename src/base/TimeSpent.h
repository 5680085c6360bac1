#pragma once
// Where a process's time goes, by name: the start-up figures the page's stats and obscura-bench print (compiling
// programs, making and prefiltering the sky, uploading the scene). A TimedScope adds the wall time it lives to its
// name's total; take() reads the totals and starts them afresh. Scopes of one name may nest (the inner time is
// counted once, by the outermost). Single-threaded, like the rest of the core.
#include <chrono>
#include <map>
#include <string>

namespace obscura {

class TimeSpent {
 public:
  static void add(const std::string& name, double ms);
  // The totals since the last take(), in ms by name, and how often each was timed.
  struct Total {
    double ms = 0.0;
    int count = 0;
  };
  static std::map<std::string, Total> take();
  // Milliseconds of a steady clock, for callers that time spans across calls.
  static double nowMs();
};

class TimedScope {
 public:
  explicit TimedScope(const char* name);
  ~TimedScope();
  TimedScope(const TimedScope&) = delete;
  TimedScope& operator=(const TimedScope&) = delete;

 private:
  const char* name_;
  bool outermost_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace obscura
