// `eqmesh encode` and `eqmesh remesh` on a corpus of broken meshes generated
// here: each is refused with one clear line naming the problem and the file
// (and a non-zero exit, and no output file), or handled by a documented repair.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "coding/decoder.h"
#include "test_support.h"
#include "tools/tool_runner.h"

namespace eqmesh::testing {
namespace {

// A 642-vertex icosphere as OBJ text, edited by each case.
struct ObjText {
  std::vector<std::string> vertices;  // "x y z"
  std::vector<std::string> faces;     // "a b c", 1-based
  std::string Str() const {
    std::ostringstream s;
    for (const std::string& v : vertices) s << "v " << v << "\n";
    for (const std::string& f : faces) s << "f " << f << "\n";
    return s.str();
  }
};

ObjText Sphere(double scale = 1.0) {
  const Mesh m = MakeIcosphere(3);
  ObjText t;
  for (const Vec3& p : m.positions) {
    std::ostringstream v;
    v.precision(17);
    v << p.x() * scale << " " << p.y() * scale << " " << p.z() * scale;
    t.vertices.push_back(v.str());
  }
  for (const Face& f : m.faces) {
    t.faces.push_back(std::to_string(f[0] + 1) + " " + std::to_string(f[1] + 1) + " " + std::to_string(f[2] + 1));
  }
  return t;
}

std::string FirstTwo(const std::string& face) { return face.substr(0, face.rfind(' ')); }

struct Refusal {
  std::string name;
  std::string text;
  std::string expected;  // substring of the error line
  bool repairable = false;
  // `remesh` writes a mesh whose components are all too small as it is (kept
  // exactly); only a stream needs a remeshed component.
  bool remesh_refuses = true;
};

std::vector<Refusal> RefusedCorpus() {
  std::vector<Refusal> cases;
  {
    ObjText t = Sphere();
    t.vertices.push_back("2 2 2");
    t.faces.push_back(FirstTwo(t.faces[0]) + " " + std::to_string(t.vertices.size()));
    cases.push_back({"non_manifold_edge", t.Str(), "non-manifold edge", true});
  }
  {
    ObjText t = Sphere();  // a tetrahedron hanging off vertex 1
    for (const char* v : {"1.5 0 0", "1.5 0.5 0", "1.5 0 0.5"}) t.vertices.push_back(v);
    const std::string a = std::to_string(t.vertices.size() - 2), b = std::to_string(t.vertices.size() - 1),
                      c = std::to_string(t.vertices.size());
    const std::string apex = t.faces[0].substr(0, t.faces[0].find(' '));
    for (const std::string& f : {apex + " " + a + " " + b, apex + " " + b + " " + c, apex + " " + c + " " + a,
                                 a + " " + c + " " + b}) {
      t.faces.push_back(f);
    }
    cases.push_back({"pinched_vertex", t.Str(), "pinched", true});
  }
  {
    ObjText t = Sphere();
    t.faces.push_back(t.faces[5]);
    cases.push_back({"duplicate_face", t.Str(), "duplicate face", true});
  }
  {
    ObjText t = Sphere();
    std::istringstream in(t.faces[7]);
    std::string a, b, c;
    in >> a >> b >> c;
    t.faces[7] = a + " " + c + " " + b;
    cases.push_back({"flipped_face", t.Str(), "inconsistently oriented", true});
  }
  {
    ObjText t = Sphere();
    t.vertices[3] = "nan 0 0";
    // The file line, and the vertex index as stored (0-based).
    cases.push_back({"nan_coordinate", t.Str(), "line 4: vertex 3 (0-based) has a non-finite", false});
  }
  {
    ObjText t = Sphere();
    t.vertices[3] = "0 -inf 0";
    cases.push_back({"inf_coordinate", t.Str(), "line 4: vertex 3 (0-based) has a non-finite", false});
  }
  {
    ObjText t = Sphere();
    t.faces.push_back("1 2 9999");
    cases.push_back({"index_out_of_range", t.Str(), "out of range", false});
  }
  {
    ObjText t = Sphere();
    t.faces.push_back("1 -9999 2");
    cases.push_back({"relative_index_out_of_range", t.Str(), "out of range", false});
  }
  cases.push_back({"empty", "", "empty", false});
  {
    ObjText t = Sphere();
    t.faces.clear();
    cases.push_back({"vertices_only", t.Str(), "no faces", false});
  }
  {
    ObjText t = Sphere();
    for (std::string& f : t.faces) f = FirstTwo(f) + " " + f.substr(0, f.find(' '));
    cases.push_back({"only_degenerate_faces", t.Str(), "no faces with three distinct vertices", false});
  }
  cases.push_back({"coordinates_beyond_float", Sphere(1e300).Str(), "float", false});
  {
    ObjText t;  // an octahedron: every component is below the remeshing size
    t.vertices = {"1 0 0", "-1 0 0", "0 1 0", "0 -1 0", "0 0 1", "0 0 -1"};
    t.faces = {"1 3 5", "3 2 5", "2 4 5", "4 1 5", "3 1 6", "2 3 6", "4 2 6", "1 4 6"};
    cases.push_back({"too_small_to_remesh", t.Str(), "too small", false, false});
  }
  return cases;
}

// A refused input leaves the directory as it was: no output, no temporary.
void ExpectRefused(const ScratchDir& dir, const Refusal& c, const std::string& command, const std::string& out) {
  const std::string in = dir.Path(c.name + ".obj");
  const ToolRun run = RunTool(command + " " + in + " " + dir.Path(out) + " --levels 2");
  EXPECT_EQ(run.exit_code, 1) << c.name << ": " << run.output;
  EXPECT_NE(run.output.find(c.expected), std::string::npos) << c.name << ": " << run.output;
  // The line names the input, or the output when writing it is what failed
  // (remesh of float64 input beyond float32 range).
  EXPECT_TRUE(run.output.find(c.name + ".obj") != std::string::npos || run.output.find(out) != std::string::npos)
      << c.name << ": " << run.output;
  EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << c.name << ": " << run.output;
  EXPECT_EQ(dir.Files(), std::vector<std::string>{c.name + ".obj"}) << c.name;
}

TEST(BrokenMeshes, EachIsRefusedWithAClearErrorAndNoOutput) {
  for (const Refusal& c : RefusedCorpus()) {
    ScratchDir dir("broken_" + c.name);
    WriteText(dir.Path(c.name + ".obj"), c.text);
    ExpectRefused(dir, c, "encode", "out.eqm");
    ExpectRefused(dir, c, "encode", "out.glb");
    if (c.remesh_refuses) ExpectRefused(dir, c, "remesh", "out.ply");
  }
}

TEST(BrokenMeshes, TopologyProblemsAreFixedByRepair) {
  for (const Refusal& c : RefusedCorpus()) {
    if (!c.repairable) continue;
    ScratchDir dir("repair_" + c.name);
    WriteText(dir.Path("in.obj"), c.text);
    const ToolRun run = RunTool("encode " + dir.Path("in.obj") + " " + dir.Path("out.eqm") + " --levels 2 --repair");
    EXPECT_EQ(run.exit_code, 0) << c.name << ": " << run.output;
    const std::vector<uint8_t> stream = ReadFileOrEmpty(dir.Path("out.eqm"));
    EXPECT_TRUE(Decode(stream.data(), stream.size()).ok()) << c.name;
  }
}

// Documented (README, "What the converter accepts"): faces with a repeated
// vertex are dropped, components under 20 vertices (zero-area ones included)
// are carried as they are (positions on the stream's quantization grid), and
// any finite float32 extent is coded.
StatusOr<Mesh> EncodeAndDecode(const ScratchDir& dir, const std::string& text) {
  WriteText(dir.Path("in.obj"), text);
  const ToolRun run = RunTool("encode " + dir.Path("in.obj") + " " + dir.Path("out.eqm") + " --levels 2");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  const std::vector<uint8_t> stream = ReadFileOrEmpty(dir.Path("out.eqm"));
  return Decode(stream.data(), stream.size());
}

TEST(BrokenMeshes, DegenerateFacesAreDropped) {
  ScratchDir dir("degenerate_faces");
  ObjText t = Sphere();
  t.faces.push_back("1 1 2");
  t.faces.push_back("3 4 4");
  auto mesh = EncodeAndDecode(dir, t.Str());
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
}

TEST(BrokenMeshes, ZeroAreaComponentIsKeptExactly) {
  ScratchDir dir("zero_area_component");
  ObjText t = Sphere();
  for (const char* v : {"3 3 3", "4 4 4", "5 5 5"}) t.vertices.push_back(v);
  const size_t n = t.vertices.size();
  t.faces.push_back(std::to_string(n - 2) + " " + std::to_string(n - 1) + " " + std::to_string(n));
  auto mesh = EncodeAndDecode(dir, t.Str());
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  size_t found = 0;
  for (const Vec3& p : mesh->positions) found += (p - Vec3(4, 4, 4)).norm() < 1e-4;
  EXPECT_EQ(found, 1u);
}

TEST(BrokenMeshes, HugeAndTinyCoordinatesKeepTheirScale) {
  for (const double scale : {1e37, 1e-30}) {
    ScratchDir dir("scale");
    auto mesh = EncodeAndDecode(dir, Sphere(scale).Str());
    ASSERT_TRUE(mesh.ok()) << scale << ": " << mesh.status().ToString();
    for (const Vec3& p : mesh->positions) {
      ASSERT_TRUE(p.allFinite()) << scale;
      EXPECT_NEAR(p.norm() / scale, 1.0, 0.05) << scale;
    }
  }
}

}  // namespace
}  // namespace eqmesh::testing
