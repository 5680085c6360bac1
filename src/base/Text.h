#pragma once
// Numbers as text, the same everywhere a value is written for a user to read back: parameters (the page's URL, the
// command line), camera coordinates in the viewers' state text, messages; and a command-line number read back.
#include <string>

namespace obscura {

// The shortest decimal text that reads back as exactly `value`, so "0.3" stays "0.3" rather than "0.300000012".
// Plain decimals where they are short ("50", "0.012"), else the shortest exponent form.
std::string formatShortest(float value);

// A finite number in min .. max given to a command-line option. Throws InputError("<option>: ...").
float parseNumber(const std::string& option, const std::string& text, double min, double max);

}  // namespace obscura
