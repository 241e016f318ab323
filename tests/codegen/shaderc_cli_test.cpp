// sao-shaderc as a program: exact diagnostics for malformed sources, no outputs on error,
// golden generated glue for the small test effect, deterministic output and a correct depfile.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "test_process.h"

namespace fs = std::filesystem;
using sao::test::readFile;
using sao::test::runCommand;

namespace {

const std::string kShaderc = SAO_SHADERC;
const std::string kTestsDir = SAO_CODEGEN_TESTS_DIR;

fs::path freshDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("sao_cli_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(p);
  return p;
}

std::map<std::string, std::string> readTree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) files[e.path().filename().string()] = readFile(e.path().string());
  return files;
}

struct MalformedCase {
  std::string file;
  std::string expected;
};

// Keeps test names short and stable (gtest would otherwise print the object's bytes).
void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.file; }

std::vector<MalformedCase> loadMalformedCases() {
  std::vector<MalformedCase> cases;
  std::ifstream in(kTestsDir + "/malformed/expected.txt");
  std::string line;
  while (std::getline(in, line)) {
    const auto tab = line.find('\t');
    if (tab == std::string::npos) continue;
    cases.push_back({line.substr(0, tab), line.substr(tab + 1)});
  }
  return cases;
}

class Malformed : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(Malformed, ReportsExactDiagnosticAndWritesNothing) {
  const MalformedCase& c = GetParam();
  const fs::path out = freshDir("malformed_" + c.file);
  const auto r = runCommand("'" + kShaderc + "' '" + c.file + "' -o '" + out.string() + "' --depfile '" +
                                out.string() + "/x.d'",
                            kTestsDir + "/malformed");
  EXPECT_NE(r.exitCode, 0) << c.file;
  const std::string firstLine = r.err.substr(0, r.err.find('\n'));
  EXPECT_EQ(firstLine, c.expected) << "full stderr:\n" << r.err;
  EXPECT_FALSE(fs::exists(out)) << "outputs left behind for " << c.file;
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Corpus, Malformed, ::testing::ValuesIn(loadMalformedCases()),
                         [](const auto& info) { return info.param.file.substr(0, info.param.file.find('.')); });

TEST(MalformedCorpus, HasAtLeastFifteenCases) { EXPECT_GE(loadMalformedCases().size(), 15u); }

TEST(Shaderc, MiniEffectMatchesGoldenFiles) {
  const fs::path out = freshDir("golden");
  const auto r = runCommand("'" + kShaderc + "' mini/mini.glsl -o '" + out.string() + "'", kTestsDir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const auto& golden : fs::directory_iterator(kTestsDir + "/golden")) {
    const std::string name = golden.path().filename().string();
    const std::string actual = readFile((out / name).string());
    if (std::getenv("SAO_UPDATE_GOLDEN")) {
      std::ofstream(golden.path(), std::ios::binary) << actual;
      continue;
    }
    EXPECT_EQ(actual, readFile(golden.path().string()))
        << name << " differs from the golden copy; if the change is intended rerun with SAO_UPDATE_GOLDEN=1";
  }
  fs::remove_all(out);
}

TEST(Shaderc, EmitsEveryPassVariantAsGlsl430AndSpirv) {
  const fs::path out = freshDir("mini_files");
  const auto r = runCommand("'" + kShaderc + "' mini/mini.glsl -o '" + out.string() + "'", kTestsDir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // first: EXTRA0/1; smoothing: no variant; second: FANCY0/1 (the FANCY=1 EXTRA=1 exclusion removes
  // no projection).
  for (const std::string stem : {"first.EXTRA0", "first.EXTRA1", "smoothing", "second.FANCY0", "second.FANCY1"}) {
    const std::string glsl = readFile((out / (stem + ".glsl")).string());
    EXPECT_EQ(glsl.rfind("#version 430\n", 0), 0u) << stem;
    const std::string spv = readFile((out / (stem + ".spv")).string());
    ASSERT_GE(spv.size(), 20u) << stem;
    EXPECT_EQ(static_cast<unsigned char>(spv[0]), 0x03) << "SPIR-V magic, little endian";
    EXPECT_EQ(static_cast<unsigned char>(spv[3]), 0x07);
  }
  fs::remove_all(out);
}

// Two runs of the real effect: this one, into a fresh folder, and the build's own (the same tool on
// the same source, into the build tree with a depfile), which the build made already; one run here
// instead of two keeps the slowest sanitizer test at half its cost.
TEST(Shaderc, OutputIsDeterministicAndHoldsNoAbsolutePaths) {
  const fs::path a = freshDir("det_a"), b = SAO_EFFECT_GENERATED_DIR;
  ASSERT_EQ(runCommand("'" + kShaderc + "' '" + SAO_EFFECT_ENTRY + "' -o '" + a.string() + "'").exitCode, 0);
  const auto ta = readTree(a), tb = readTree(b);
  ASSERT_GT(ta.size(), 10u);
  // The build's folder also holds its depfile (absolute paths by nature), which its outputs list
  // names, and in an incremental build the files of earlier variants: every file of this run must
  // be there with the same bytes, and this run's outputs list (no depfile) a part of the build's.
  const std::string outputsList = "sao-shaderc-outputs.txt";
  auto lines = [](const std::string& text) {
    std::set<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.insert(line);
    return out;
  };
  const std::set<std::string> buildOutputs = lines(tb.at(outputsList));
  for (const std::string& line : lines(ta.at(outputsList)))
    EXPECT_EQ(buildOutputs.count(line), 1u) << line << " is not among the build's outputs";
  const std::string sourceRoot = fs::path(SAO_EFFECT_ENTRY).parent_path().parent_path().string();
  for (const auto& [name, content] : ta) {
    ASSERT_EQ(tb.count(name), 1u) << name << " is not in the build's folder";
    if (name != outputsList) EXPECT_EQ(content, tb.at(name)) << name << " differs between two runs";
    EXPECT_EQ(content.find(sourceRoot), std::string::npos) << name << " contains the absolute source path";
    EXPECT_EQ(content.find(a.string()), std::string::npos) << name << " contains the output path";
  }
  fs::remove_all(a);
}

TEST(Shaderc, DepfileListsEveryIncludedFile) {
  const fs::path out = freshDir("depfile");
  const auto r = runCommand("'" + kShaderc + "' mini/mini.glsl -o '" + out.string() + "' --depfile '" +
                                (out / "mini.d").string() + "'",
                            kTestsDir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string dep = readFile((out / "mini.d").string());
  EXPECT_EQ(dep.rfind((out / "mini_effect.h").string() + ":", 0), 0u) << dep;
  EXPECT_NE(dep.find("mini/mini.glsl"), std::string::npos) << dep;
  EXPECT_NE(dep.find("mini/include/mini_lib.glsl"), std::string::npos) << dep;
  fs::remove_all(out);
}

// The writers' rule (docs/ROBUSTNESS.md, "Files of the user's"): a file of an output's name that
// sao-shaderc did not write is refused without --overwrite and left as it was, nothing else is
// written; its own earlier outputs (listed in sao-shaderc-outputs.txt) are replaced.
TEST(Shaderc, ReplacesNoFileItDidNotWriteWithoutOverwrite) {
  const fs::path out = freshDir("users_file");
  fs::create_directories(out);
  std::ofstream(out / "mini_effect.h") << "the user's notes\n";
  const std::string command = "'" + kShaderc + "' mini/mini.glsl -o '" + out.string() + "'";
  const auto refused = runCommand(command, kTestsDir);
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_EQ(refused.err, "sao-shaderc: error: '" + (out / "mini_effect.h").string() +
                             "' exists and sao-shaderc did not write it (sao-shaderc-outputs.txt there does not list "
                             "it): move it, choose another -o folder, or give --overwrite to replace it\n");
  EXPECT_EQ(readTree(out), (std::map<std::string, std::string>{{"mini_effect.h", "the user's notes\n"}}));
  ASSERT_EQ(runCommand(command + " --overwrite", kTestsDir).exitCode, 0);
  EXPECT_NE(readFile((out / "mini_effect.h").string()), "the user's notes\n");
  const std::string listed = readFile((out / "sao-shaderc-outputs.txt").string());
  EXPECT_NE(listed.find("mini_effect.h\n"), std::string::npos) << listed;
  EXPECT_NE(listed.find("smoothing.spv\n"), std::string::npos) << listed;
  const auto again = runCommand(command, kTestsDir);  // its own outputs: replaced without a flag
  EXPECT_EQ(again.exitCode, 0) << again.err;
  fs::remove_all(out);
}

TEST(Shaderc, NeverWritesOntoItsInput) {
  // An effect file named like one of its outputs (smoothing.glsl), compiled into its own folder.
  const fs::path dir = freshDir("input");
  fs::create_directories(dir / "include");
  fs::copy_file(kTestsDir + "/mini/mini.glsl", dir / "smoothing.glsl");
  fs::copy(kTestsDir + "/mini/include", dir / "include", fs::copy_options::recursive);
  const std::string before = readFile((dir / "smoothing.glsl").string());
  const auto r = runCommand("'" + kShaderc + "' smoothing.glsl -o . --overwrite", dir.string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "sao-shaderc: error: './smoothing.glsl' is the input 'smoothing.glsl': an input is never written "
                   "onto, --overwrite or not\n");
  EXPECT_EQ(readFile((dir / "smoothing.glsl").string()), before);
  EXPECT_FALSE(fs::exists(dir / "mini_effect.h"));
  fs::remove_all(dir);
}

TEST(Shaderc, BadCommandLinesFailWithUsage) {
  EXPECT_EQ(runCommand("'" + kShaderc + "'").exitCode, 2);
  EXPECT_EQ(runCommand("'" + kShaderc + "' mini/mini.glsl", kTestsDir).exitCode, 2);
  const auto r = runCommand("'" + kShaderc + "' no_such_file.glsl -o /tmp/sao_never", kTestsDir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "no_such_file.glsl: error: cannot open effect file 'no_such_file.glsl'\n");
  EXPECT_FALSE(fs::exists("/tmp/sao_never"));
  const auto d = runCommand("'" + kShaderc + "' mini -o /tmp/sao_never", kTestsDir);
  EXPECT_EQ(d.err, "mini: error: 'mini' is a directory, not a source file\n");
}

}  // namespace
