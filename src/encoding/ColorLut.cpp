#include "encoding/ColorLut.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include "base/Error.h"
#include "base/Text.h"

namespace obscura {
namespace {

float stored(float v) { return std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f; }

std::string trimmed(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

// The whitespace-separated words of a line.
std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

bool finiteNumber(const std::string& word, float& value) {
  if (word.empty()) return false;
  char* end = nullptr;
  value = std::strtof(word.c_str(), &end);
  return end == word.c_str() + word.size() && std::isfinite(value);
}

}  // namespace

glm::vec3 ColorLut::apply(const glm::vec3& color, bool asStored) const {
  const glm::vec3 unit = glm::clamp((color - domainMin) / (domainMax - domainMin), 0.0f, 1.0f);
  const glm::vec3 x = unit * static_cast<float>(size - 1);
  const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(x)), glm::ivec3(size - 2));
  const glm::vec3 f = x - glm::vec3(i0);
  auto value = [&](int r, int g, int b) {
    const glm::vec3& v = at(r, g, b);
    return asStored ? glm::vec3(stored(v.r), stored(v.g), stored(v.b)) : v;
  };
  glm::vec3 out(0.0f);
  for (int db = 0; db < 2; ++db)
    for (int dg = 0; dg < 2; ++dg)
      for (int dr = 0; dr < 2; ++dr) {
        const float w = (dr ? f.r : 1.0f - f.r) * (dg ? f.g : 1.0f - f.g) * (db ? f.b : 1.0f - f.b);
        out += w * value(i0.r + dr, i0.g + dg, i0.b + db);
      }
  return out;
}

ColorLut ColorLut::identity(int size) {
  return of(size, [](const glm::vec3& c) { return c; });
}

ColorLut ColorLut::of(int size, const std::function<glm::vec3(const glm::vec3&)>& f) {
  ColorLut lut;
  lut.size = size;
  lut.values.reserve(static_cast<size_t>(size) * size * size);
  const float step = 1.0f / static_cast<float>(size - 1);
  for (int b = 0; b < size; ++b)
    for (int g = 0; g < size; ++g)
      for (int r = 0; r < size; ++r)
        lut.values.push_back(f(glm::vec3(static_cast<float>(r), static_cast<float>(g), static_cast<float>(b)) * step));
  return lut;
}

ColorLut parseCubeLut(const std::string& text, const std::string& name) {
  ColorLut lut;
  int domainLine = 0;  // the last line that set the domain
  size_t expected = 0;
  int lineNumber = 0;
  auto fail = [&](const std::string& why) {
    throw InputError(name + " line " + std::to_string(lineNumber) + ": " + why);
  };
  // Checked once the header is read (before the first row, or at the end), at the line that last set the domain.
  auto checkDomain = [&] {
    if (domainLine && glm::any(glm::greaterThanEqual(lut.domainMin, lut.domainMax))) {
      lineNumber = domainLine;
      fail("the domain's minimum must lie below its maximum in every channel");
    }
    domainLine = 0;
  };
  auto three = [&](const std::vector<std::string>& w, size_t first) {
    glm::vec3 v;
    if (w.size() != first + 3) fail("expected three numbers after " + w[0]);
    for (int c = 0; c < 3; ++c)
      if (!finiteNumber(w[first + static_cast<size_t>(c)], v[c])) fail("'" + w[first + static_cast<size_t>(c)] +
                                                                        "' is not a number");
    return v;
  };
  std::istringstream in(text);
  for (std::string raw; std::getline(in, raw);) {
    ++lineNumber;
    const std::string line = trimmed(raw);
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> w = words(line);
    const std::string& key = w[0];
    // A keyword is upper-case letters, digits and underscores, starting with a letter; anything else starts a row.
    const bool keyword = std::isupper(static_cast<unsigned char>(key[0])) &&
                         std::all_of(key.begin(), key.end(), [](char ch) {
                           return std::isupper(static_cast<unsigned char>(ch)) ||
                                  std::isdigit(static_cast<unsigned char>(ch)) || ch == '_';
                         });
    if (!keyword) {
      if (lut.size == 0) fail("a row of the table before LUT_3D_SIZE");
      if (lut.values.empty()) {
        const int row = lineNumber;
        checkDomain();
        lineNumber = row;
      }
      if (lut.values.size() == expected)
        fail("more rows than LUT_3D_SIZE " + std::to_string(lut.size) + " makes (" + std::to_string(expected) + ")");
      glm::vec3 v;
      if (w.size() != 3) fail("expected three numbers, got '" + line + "'");
      for (int c = 0; c < 3; ++c)
        if (!finiteNumber(w[static_cast<size_t>(c)], v[c])) fail("'" + w[static_cast<size_t>(c)] + "' is not a number");
      lut.values.push_back(v);
      continue;
    }
    if (!lut.values.empty()) fail("'" + key + "' after the table's rows");
    if (key == "TITLE") {
      const size_t open = line.find('"'), close = line.rfind('"');
      if (open == std::string::npos || close == open) fail("TITLE needs its text in double quotes");
      lut.title = line.substr(open + 1, close - open - 1);
    } else if (key == "LUT_3D_SIZE") {
      if (lut.size != 0) fail("a second LUT_3D_SIZE");
      float n = 0.0f;
      if (w.size() != 2 || !finiteNumber(w[1], n) || n != std::floor(n) || n < kMinLutSize || n > kMaxLutSize)
        fail("LUT_3D_SIZE must be a whole number from " + std::to_string(kMinLutSize) + " to " +
             std::to_string(kMaxLutSize));
      lut.size = static_cast<int>(n);
      expected = static_cast<size_t>(lut.size) * lut.size * lut.size;
      lut.values.reserve(expected);
    } else if (key == "LUT_1D_SIZE") {
      fail("a 1D LUT (LUT_1D_SIZE): only 3D LUTs are read (grading's slope, offset and power make curves)");
    } else if (key == "DOMAIN_MIN") {
      lut.domainMin = three(w, 1);
      domainLine = lineNumber;
    } else if (key == "DOMAIN_MAX") {
      lut.domainMax = three(w, 1);
      domainLine = lineNumber;
    } else if (key == "LUT_3D_INPUT_RANGE") {
      float lo = 0.0f, hi = 0.0f;
      if (w.size() != 3 || !finiteNumber(w[1], lo) || !finiteNumber(w[2], hi))
        fail("LUT_3D_INPUT_RANGE needs two numbers, min and max");
      lut.domainMin = glm::vec3(lo);
      lut.domainMax = glm::vec3(hi);
      domainLine = lineNumber;
    } else {
      fail("unknown keyword '" + key + "'");
    }
  }
  checkDomain();
  if (lut.size == 0) throw InputError(name + ": no LUT_3D_SIZE (not a 3D .cube LUT)");
  if (lut.values.size() != expected)
    throw InputError(name + " line " + std::to_string(lineNumber) + ": the file ends after " +
                     std::to_string(lut.values.size()) + " rows of the " + std::to_string(expected) +
                     " LUT_3D_SIZE " + std::to_string(lut.size) + " makes");
  return lut;
}

ColorLut readCubeLut(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot be read");
  std::ostringstream text;
  text << file.rdbuf();
  return parseCubeLut(text.str(), path);
}

std::string writeCubeLut(const ColorLut& lut) {
  std::string out;
  if (!lut.title.empty()) out += "TITLE \"" + lut.title + "\"\n";
  out += "LUT_3D_SIZE " + std::to_string(lut.size) + "\n";
  auto triple = [](const glm::vec3& v) {
    return formatShortest(v.r) + " " + formatShortest(v.g) + " " + formatShortest(v.b);
  };
  if (lut.domainMin != glm::vec3(0.0f) || lut.domainMax != glm::vec3(1.0f)) {
    out += "DOMAIN_MIN " + triple(lut.domainMin) + "\n";
    out += "DOMAIN_MAX " + triple(lut.domainMax) + "\n";
  }
  for (const glm::vec3& v : lut.values) out += triple(v) + "\n";
  return out;
}

LutStrip lutStrip(const ColorLut& lut, int maxTextureSize) {
  const int n = lut.size;
  LutStrip strip;
  strip.slicesPerRow = std::min(n, maxTextureSize / n);
  if (strip.slicesPerRow < 1) throw InputError("a LUT of size " + std::to_string(n) + " does not fit a texture");
  const int rows = (n + strip.slicesPerRow - 1) / strip.slicesPerRow;
  strip.width = strip.slicesPerRow * n;
  strip.height = rows * n;
  if (strip.height > maxTextureSize)
    throw InputError("a LUT of size " + std::to_string(n) + " does not fit this context's " +
                     std::to_string(maxTextureSize) + "-texel textures");
  strip.rgba.assign(static_cast<size_t>(strip.width) * strip.height * 4, 0);
  for (int b = 0; b < n; ++b)
    for (int g = 0; g < n; ++g)
      for (int r = 0; r < n; ++r) {
        const int x = (b % strip.slicesPerRow) * n + r, y = (b / strip.slicesPerRow) * n + g;
        const glm::vec3& v = lut.at(r, g, b);
        std::uint8_t* texel = &strip.rgba[(static_cast<size_t>(y) * strip.width + x) * 4];
        for (int c = 0; c < 3; ++c)
          texel[c] = static_cast<std::uint8_t>(std::lround(std::clamp(v[c], 0.0f, 1.0f) * 255.0f));
        texel[3] = 255;
      }
  return strip;
}

}  // namespace obscura
