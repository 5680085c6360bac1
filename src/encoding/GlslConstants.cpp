#include "encoding/GlslConstants.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace obscura {
namespace {

// The shortest decimal that reads back as the same binary32 value: nine significant digits always do (IEEE 754-2008,
// sec. 5.12.2: Pmin(binary32) = 9), and constants copied from a paper keep their printed form (0.59719, not
// 0.597190022). GLSL needs a '.' or an exponent to read it as a float.
std::string formatFloat(float v) {
  char buffer[32];
  const double magnitude = std::abs(static_cast<double>(v));
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, static_cast<double>(v));
    if (std::strchr(buffer, 'e') && magnitude >= 1e-4 && magnitude < 1e7) {  // 620, not 6.2e+02
      const int decimals = std::max(0, digits - 1 - static_cast<int>(std::floor(std::log10(magnitude))));
      std::snprintf(buffer, sizeof buffer, "%.*f", decimals, static_cast<double>(v));
    }
    if (std::strtof(buffer, nullptr) == v) break;
  }
  std::string s = buffer;
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

bool isIdentifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

}  // namespace

GlslConstant glslMat3(const std::string& name, const glm::mat3& m) {
  GlslConstant c{"mat3", name, {}};
  for (int column = 0; column < 3; ++column)
    for (int row = 0; row < 3; ++row) c.values.push_back(m[column][row]);
  return c;
}

GlslConstant glslFloat(const std::string& name, float value) { return {"float", name, {value}}; }

std::string formatGlslConstants(const std::vector<GlslConstant>& constants) {
  std::string out;
  for (const GlslConstant& c : constants) {
    out += "const " + c.type + " " + c.name + " = ";
    if (c.type == "float") {
      out += formatFloat(c.values.at(0));
    } else {
      // One column per line for a mat3.
      const bool matrix = c.type == "mat3";
      out += c.type + (matrix ? "(\n    " : "(");
      for (size_t i = 0; i < c.values.size(); ++i) {
        if (i > 0) out += (matrix && i % 3 == 0) ? ",\n    " : ", ";
        out += formatFloat(c.values[i]);
      }
      out += ")";
    }
    out += ";\n";
  }
  return out;
}

std::optional<std::vector<float>> parseGlslConstant(std::string_view source, const std::string& name) {
  for (size_t at = source.find(name); at != std::string_view::npos; at = source.find(name, at + 1)) {
    // The whole identifier, declared `const <type> name =`.
    if (at > 0 && isIdentifierChar(source[at - 1])) continue;
    size_t after = at + name.size();
    if (after < source.size() && isIdentifierChar(source[after])) continue;
    const size_t lineStart = source.rfind('\n', at) == std::string_view::npos ? 0 : source.rfind('\n', at) + 1;
    const std::string_view head = source.substr(lineStart, at - lineStart);
    if (head.find("const ") == std::string_view::npos) continue;
    while (after < source.size() && source[after] == ' ') ++after;
    if (after >= source.size() || source[after] != '=') continue;
    const size_t end = source.find(';', after);
    if (end == std::string_view::npos) return std::nullopt;
    const std::string body(source.substr(after + 1, end - after - 1));
    std::vector<float> values;
    for (size_t i = 0; i < body.size();) {
      const char c = body[i];
      if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {  // a type name such as mat3: skip it whole
        while (i < body.size() && isIdentifierChar(body[i])) ++i;
      } else if (std::isdigit(static_cast<unsigned char>(c)) || c == '.' ||
                 (c == '-' && i + 1 < body.size() &&
                  (std::isdigit(static_cast<unsigned char>(body[i + 1])) || body[i + 1] == '.'))) {
        char* stop = nullptr;
        values.push_back(std::strtof(body.c_str() + i, &stop));  // correctly rounded to binary32
        i = static_cast<size_t>(stop - body.c_str());
      } else {
        ++i;
      }
    }
    return values;
  }
  return std::nullopt;
}

}  // namespace obscura
