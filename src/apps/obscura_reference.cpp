// obscura-reference: the ray-traced AO reference (Embree). See `obscura-reference --help` and docs/accuracy.md.
#include <iostream>

#include "apps/ReferenceCommandLine.h"
#include "base/Error.h"

int main(int argc, char** argv) {
  try {
    const obscura::ReferenceOptions options =
        obscura::parseReferenceCommandLine(std::vector<std::string>(argv + 1, argv + argc));
    return obscura::runReference(options);
  } catch (const obscura::InputError& e) {
    std::cerr << "obscura-reference: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "obscura-reference: " << e.what() << "\n";
    return 1;
  }
}
