#include "gl/ShaderLibrary.h"

#include <set>
#include <sstream>

#include "base/Error.h"
#include "base/TimeSpent.h"
#include "gl/EmbeddedShaders.h"

namespace obscura {
namespace ShaderLibrary {

std::string withoutComments(const std::string& source) {
  std::string out;
  out.reserve(source.size());
  for (size_t i = 0; i < source.size(); ++i) {
    if (source.compare(i, 2, "//") == 0) {
      i = source.find('\n', i);
      if (i == std::string::npos) break;
      out += '\n';
    } else if (source.compare(i, 2, "/*") == 0) {
      i = source.find("*/", i + 2);
      if (i == std::string::npos) break;
      ++i;
      out += ' ';
    } else {
      out += source[i];
    }
  }
  return out;
}

namespace {

void expand(const std::string& path, const std::string& text, std::set<std::string>& included, std::string& out,
            int depth) {
  if (depth > 8) throw GlError("shader include nesting too deep at '" + path + "'");
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const size_t start = line.find_first_not_of(" \t");
    if (start != std::string::npos && line.compare(start, 8, "#include") == 0) {
      const size_t open = line.find('"', start);
      const size_t close = open == std::string::npos ? open : line.find('"', open + 1);
      if (close == std::string::npos) throw GlError("malformed #include in shader '" + path + "': " + line);
      const std::string target = line.substr(open + 1, close - open - 1);
      if (included.insert(target).second) {
        out += "// ---- begin " + target + " ----\n";
        expand(target, std::string(file(target)), included, out, depth + 1);
        out += "// ---- end " + target + " ----\n";
      }
      continue;
    }
    out += line;
    out += '\n';
  }
}

}  // namespace

std::string_view file(const std::string& path) {
  for (const EmbeddedShader& shader : embeddedShaders())
    if (shader.path == path) return shader.text;
  throw GlError("no embedded shader file '" + path + "'");
}

std::string compose(const std::string& path, const std::vector<std::pair<std::string, std::string>>& defines,
                    const std::vector<std::string>& extensions) {
  return composeText(std::string(file(path)), defines, extensions);
}

std::string composeText(const std::string& text, const std::vector<std::pair<std::string, std::string>>& defines,
                        const std::vector<std::string>& extensions) {
  std::string out = "#version 100\n";
  for (const std::string& extension : extensions) out += "#extension " + extension + " : require\n";
  for (const auto& [name, value] : defines) out += "#define " + name + " " + value + "\n";
  std::set<std::string> included;
  expand("(top level)", text, included, out, 0);
  return out;
}

}  // namespace ShaderLibrary

// Every extension Obscura enables is a fragment-stage one (texture LOD, draw buffers).
std::string ProgramSpec::vertexSource() const { return ShaderLibrary::compose(vertexFile, defines, {}); }
std::string ProgramSpec::fragmentSource() const {
  return fragmentText.empty() ? ShaderLibrary::compose(fragmentFile, defines, extensions)
                              : ShaderLibrary::composeText(fragmentText, defines, extensions);
}
gl::Program ProgramSpec::build(bool strict) const {
  const TimedScope timed("programs");
  return gl::Program(name, vertexSource(), fragmentSource(), strict);
}
gl::Program ProgramSpec::begin(bool strict) const {
  const TimedScope timed("programs");
  return gl::Program::begin(name, vertexSource(), fragmentSource(), strict);
}

}  // namespace obscura
