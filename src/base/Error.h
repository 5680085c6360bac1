#pragma once
// The kinds of failure Obscura reports. Each carries one readable line.
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
// capability (fragment highp), a GL error after a pass, a uniform a program does not have (strict programs).
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The effect table does not add up: a pass reads a target no earlier pass writes, two effects write one target
// under different encodings, a name is used twice. A mistake in Obscura (or in an effect added to it), reported when
// the Renderer is built, before any frame.
class PipelineError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace obscura
