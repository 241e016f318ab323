#include "test_process.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace sao::test {

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

ProcessResult runCommand(const std::string& command, const std::string& workingDir) {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path tmp = fs::temp_directory_path() / ("sao_test_proc_" + std::to_string(::getpid()) + "_" +
                                                    std::to_string(counter++));
  fs::create_directories(tmp);
  const std::string full = "cd '" + workingDir + "' && " + command + " >'" + (tmp / "out").string() + "' 2>'" +
                           (tmp / "err").string() + "'";
  const int status = std::system(full.c_str());
  ProcessResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readFile((tmp / "out").string());
  r.err = readFile((tmp / "err").string());
  fs::remove_all(tmp);
  return r;
}

}  // namespace sao::test
