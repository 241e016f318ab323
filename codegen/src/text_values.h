// The directive values' lexical forms, shared by every part of the parser.
#pragma once
#include <string>
#include <vector>

namespace sao::codegen {

bool isIdentifier(const std::string& s);
// A finite number in C syntax (strtod), the whole string.
bool parseNumber(const std::string& s, double& out);
// A decimal int with an optional sign; false (never an exception) beyond int's range.
bool parseInt(const std::string& s, int& out);
std::vector<std::string> splitList(const std::string& s, char sep = ',');

}  // namespace sao::codegen
