// obscura-render: the headless command-line renderer. See `obscura-render --help`.
#include <iostream>

#include "apps/RenderCommandLine.h"
#include "base/Error.h"

int main(int argc, char** argv) {
  try {
    const obscura::RenderOptions options =
        obscura::parseRenderCommandLine(std::vector<std::string>(argv + 1, argv + argc));
    return obscura::runRender(options);
  } catch (const obscura::InputError& e) {
    std::cerr << "obscura-render: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "obscura-render: " << e.what() << "\n";
    return 1;
  }
}
