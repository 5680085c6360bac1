// obscura-compare: error figures between two AO images. See `obscura-compare --help` and docs/accuracy.md.
#include <iostream>

#include "apps/CompareCommandLine.h"
#include "base/Error.h"

int main(int argc, char** argv) {
  try {
    const obscura::CompareOptions options =
        obscura::parseCompareCommandLine(std::vector<std::string>(argv + 1, argv + argc));
    return obscura::runCompare(options);
  } catch (const obscura::InputError& e) {
    std::cerr << "obscura-compare: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "obscura-compare: " << e.what() << "\n";
    return 1;
  }
}
