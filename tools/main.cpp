#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "tools/command.h"
#include "tools/huge_pages.h"

namespace eqmesh::cli {

std::vector<Command>& Registry() {
  static std::vector<Command> commands;
  return commands;
}

int Fail(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "eqmesh %s: error: %s\n", command.c_str(), message.c_str());
  return 1;
}

}  // namespace eqmesh::cli

namespace {

void PrintUsage(FILE* out) {
  auto commands = eqmesh::cli::Registry();
  std::sort(commands.begin(), commands.end(),
            [](const auto& a, const auto& b) { return a.name < b.name; });
  std::fprintf(out, "eqmesh: normal-mesh geometry codec (EXT_normal_mesh_compression)\n\n");
  std::fprintf(out, "usage: eqmesh <command> [options]   (eqmesh <command> --help for details)\n\n");
  std::fprintf(out, "commands:\n");
  for (const auto& c : commands) std::fprintf(out, "  %-10s %s\n", c.name.c_str(), c.summary.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  eqmesh::cli::ReexecWithHugePagesIfUseful(argv);
  if (argc < 2) {
    PrintUsage(stderr);
    return 2;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    PrintUsage(stdout);
    return 0;
  }
  if (name == "--version") {
    std::printf("eqmesh 0.1.0\n");
    return 0;
  }
  for (const auto& c : eqmesh::cli::Registry()) {
    if (c.name == name) {
      std::string program = "eqmesh " + name;
      std::vector<char> program_buf(program.begin(), program.end());
      program_buf.push_back('\0');
      argv[1] = program_buf.data();
      return c.run(argc - 1, argv + 1);
    }
  }
  std::fprintf(stderr, "eqmesh: error: unknown command '%s' (try eqmesh --help)\n", name.c_str());
  return 2;
}
