// Outputs appear whole or not at all, and never over the input.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "mesh_io/atomic_file.h"
#include "tools/tool_runner.h"

namespace eqmesh::testing {
namespace {

const std::vector<uint8_t> kBytes = {'e', 'q', 'm', 0, 1, 2, 255};

TEST(AtomicWrite, WritesTheBytesAndLeavesNoTemporary) {
  ScratchDir dir("atomic_write");
  ASSERT_TRUE(WriteFileAtomically(dir.Path("a.bin"), kBytes).ok());
  EXPECT_EQ(ReadFileOrEmpty(dir.Path("a.bin")), kBytes);
  EXPECT_EQ(dir.Files(), std::vector<std::string>{"a.bin"});
}

TEST(AtomicWrite, ReplacesAnExistingFile) {
  ScratchDir dir("atomic_replace");
  WriteText(dir.Path("a.bin"), "an older, longer content");
  ASSERT_TRUE(WriteFileAtomically(dir.Path("a.bin"), kBytes).ok());
  EXPECT_EQ(ReadFileOrEmpty(dir.Path("a.bin")), kBytes);
  EXPECT_EQ(dir.Files(), std::vector<std::string>{"a.bin"});
}

TEST(AtomicWrite, FailureNamesThePathAndLeavesNothingBehind) {
  ScratchDir dir("atomic_fail");
  const Status missing_dir = WriteFileAtomically(dir.Path("no/such/dir/a.bin"), kBytes);
  EXPECT_EQ(missing_dir.code(), StatusCode::kIoError);
  EXPECT_NE(missing_dir.message().find("no/such/dir/a.bin"), std::string::npos) << missing_dir.message();
  // A directory in the way: the rename fails after the temporary was written.
  const std::string blocker = dir.Path("blocker");
  ASSERT_EQ(std::system(("mkdir " + blocker + " && touch " + blocker + "/keep").c_str()), 0);
  EXPECT_FALSE(WriteFileAtomically(blocker, kBytes).ok());
  EXPECT_EQ(dir.Files(), std::vector<std::string>{"blocker"});
}

TEST(AtomicWrite, FailedEncodeLeavesThePreviousOutputUntouched) {
  ScratchDir dir("atomic_encode");
  WriteText(dir.Path("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  WriteText(dir.Path("out.eqm"), "previous output");
  const ToolRun run = RunTool("encode " + dir.Path("bad.obj") + " " + dir.Path("out.eqm"));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_EQ(ReadText(dir.Path("out.eqm")), "previous output");
  EXPECT_EQ(dir.Files(), (std::vector<std::string>{"bad.obj", "out.eqm"}));
}

TEST(AtomicWrite, CommandsRefuseToWriteOverTheirInput) {
  ScratchDir dir("atomic_same");
  const std::string in = dir.Path("in.obj");
  const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  WriteText(in, text);
  ASSERT_EQ(std::system(("ln -s in.obj " + dir.Path("link.obj")).c_str()), 0);
  for (const char* command : {"convert", "encode", "remesh", "perturb", "decode"}) {
    for (const std::string& out : {in, dir.Path("link.obj")}) {
      const std::string extra = std::string(command) == "perturb" ? " --noise 0.01" : "";
      const ToolRun run = RunTool(std::string(command) + " " + in + " " + out + extra);
      EXPECT_EQ(run.exit_code, 1) << command << ": " << run.output;
      EXPECT_NE(run.output.find("is the input file"), std::string::npos) << command << ": " << run.output;
    }
  }
  EXPECT_EQ(ReadText(in), text);
}

}  // namespace
}  // namespace eqmesh::testing
