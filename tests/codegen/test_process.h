// Runs a command for the tests and captures its exit status and output.
#pragma once
#include <string>

namespace sao::test {

struct ProcessResult {
  int exitCode = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs `command` through /bin/sh in `workingDir`.
ProcessResult runCommand(const std::string& command, const std::string& workingDir = ".");

std::string readFile(const std::string& path);

}  // namespace sao::test
