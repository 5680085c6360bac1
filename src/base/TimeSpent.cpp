#include "base/TimeSpent.h"

#include <set>

namespace obscura {
namespace {

std::map<std::string, TimeSpent::Total>& totals() {
  static std::map<std::string, TimeSpent::Total> map;
  return map;
}

std::set<std::string>& open() {
  static std::set<std::string> names;
  return names;
}

}  // namespace

void TimeSpent::add(const std::string& name, double ms) {
  Total& total = totals()[name];
  total.ms += ms;
  ++total.count;
}

std::map<std::string, TimeSpent::Total> TimeSpent::take() {
  std::map<std::string, Total> out;
  out.swap(totals());
  return out;
}

double TimeSpent::nowMs() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

TimedScope::TimedScope(const char* name)
    : name_(name), outermost_(open().insert(name).second), start_(std::chrono::steady_clock::now()) {}

TimedScope::~TimedScope() {
  if (!outermost_) return;
  open().erase(name_);
  TimeSpent::add(name_, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count());
}

}  // namespace obscura
