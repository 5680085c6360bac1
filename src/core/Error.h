#pragma once
// The two kinds of failure Obscura reports. Both carry one readable line meant for the user.
#include <stdexcept>
#include <string>

namespace obscura {

// Bad input from the user: a missing or malformed file, an unknown option, an out-of-range value. The command-line
// tools exit with status 2 on it; the viewer and the page show the message and keep the previous scene.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The GL context could not do what was asked: a shader that does not compile, an incomplete framebuffer, a missing
// capability (fragment highp), a GL error after a pass.
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace obscura
