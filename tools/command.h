// The eqmesh command line: one file per subcommand (cmd_<name>.cpp), each a thin
// layer over library functions. A command registers itself with
// EQMESH_REGISTER_COMMAND; main() dispatches on argv[1].
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mesh_io/atomic_file.h"

namespace eqmesh::cli {

struct Command {
  std::string name;
  std::string summary;                       // one line for `eqmesh --help`
  std::function<int(int argc, char** argv)> run;  // argv[0] is "eqmesh <name>"
};

std::vector<Command>& Registry();

struct Registrar {
  explicit Registrar(Command command) { Registry().push_back(std::move(command)); }
};

// Prints "eqmesh <command>: error: <message>" on stderr and returns exit code 1.
int Fail(const std::string& command, const std::string& message);

// Largest .eqm file the commands read: streams are small, so anything larger is
// refused before it is read whole.
inline constexpr uint64_t kMaxStreamFileBytes = uint64_t{1} << 31;

// Whether a path ends with an extension such as ".srm" (exact case; commands pick
// their output format and their special inputs by name).
inline bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace eqmesh::cli

#define EQMESH_CLI_CONCAT_INNER(a, b) a##b
#define EQMESH_CLI_CONCAT(a, b) EQMESH_CLI_CONCAT_INNER(a, b)
// fn may be any callable expression (qualified names included).
#define EQMESH_REGISTER_COMMAND(name, summary, fn) \
  static ::eqmesh::cli::Registrar EQMESH_CLI_CONCAT(eqmesh_registrar_, __COUNTER__)({name, summary, fn})
