// OBJ, OFF and PLY features, on small inputs built by the tests themselves.
#include <gtest/gtest.h>

#include "io_test_util.h"
#include "mesh_io/mesh_io.h"

namespace eqmesh {
namespace {

using testing::ToBytes;

StatusOr<Mesh> ReadText(const std::string& text, const std::string& format, ReadReport* report = nullptr) {
  return ReadMeshFromBytes(ToBytes(text), format, "test." + format, report);
}

void ExpectFaces(const Mesh& m, const std::vector<Face>& faces) {
  ASSERT_EQ(m.faces.size(), faces.size());
  for (size_t i = 0; i < faces.size(); ++i) EXPECT_EQ(m.faces[i], faces[i]) << "face " << i;
}

TEST(ReadObj, QuadsNegativeIndicesAndCornerForms) {
  const std::string obj =
      "# a comment\r\n"
      "mtllib x.mtl\r\n"
      "v 0 0 0\r\n"
      "v 1 0 0\r\n"
      "v 1 1 0\r\n"
      "v 0 1 0\r\n"
      "vt 0 0\r\nvn 0 0 1\r\n"
      "g quad\r\n"
      "f 1/1/1 2/1/1 3/1/1 4/1/1\r\n"  // quad, v/vt/vn
      "v 2 0 0 1.0\r\n"                 // with w
      "f -4//1 -1//1 -3//1\r\n"         // relative, v//vn
      "f 5/1 3/1 2/1\r\n";              // v/vt
  ReadReport report;
  auto m = ReadText(obj, "obj", &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(report.format, "obj");
  EXPECT_EQ(m->num_vertices(), 5u);
  EXPECT_EQ(report.polygons_triangulated, 1u);
  ExpectFaces(*m, {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}, {4, 2, 1}});
  EXPECT_EQ(m->positions[4], Vec3(2, 0, 0));
}

TEST(ReadObj, DropsUnreferencedVerticesKeepingOrder) {
  ReadReport report;
  auto m = ReadText("v 9 9 9\nv 0 0 0\nv 8 8 8\nv 1 0 0\nv 0 1 0\nv 7 7 7\nf 2 4 5\n", "obj", &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(report.dropped_unreferenced_vertices, 3u);
  ASSERT_EQ(m->num_vertices(), 3u);
  EXPECT_EQ(m->positions[0], Vec3(0, 0, 0));
  EXPECT_EQ(m->positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(m->positions[2], Vec3(0, 1, 0));
  ExpectFaces(*m, {{0, 1, 2}});
}

TEST(ReadObj, DuplicatePositionsAreNotMerged) {
  auto m = ReadText("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0\nf 1 2 3\nf 4 3 2\n", "obj");
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->num_vertices(), 4u);
}

TEST(ReadObj, ForwardReferenceIsAllowed) {
  auto m = ReadText("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "obj");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->num_faces(), 1u);
}

TEST(ReadOff, CommentsPolygonsAndColours) {
  const std::string off =
      "# leading comment\n"
      "COFF\n"
      "5 3 0\n"
      "0 0 0 255 0 0 255\n"
      "1 0 0 255 0 0 255  # comment after a vertex\n"
      "\n"
      "1 1 0 255 0 0 255\n"
      "0 1 0 255 0 0 255\n"
      "9 9 9 255 0 0 255\n"
      "4 0 1 2 3 0.5 0.5 0.5\n"
      "3 0 2 1\n"
      "2 0 1\n";
  ReadReport report;
  auto m = ReadText(off, "off", &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(report.format, "off");
  EXPECT_EQ(report.polygons_triangulated, 1u);
  EXPECT_EQ(report.dropped_unreferenced_vertices, 1u);
  ASSERT_EQ(report.notes.size(), 1u);  // the 2-gon
  ExpectFaces(*m, {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}});
}

TEST(ReadOff, CountsOnTheKeywordLine) {
  auto m = ReadText("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "off");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->num_faces(), 1u);
}

// A PLY with awkward extras: a leading unknown element, vertex properties of mixed
// types around x/y/z, a list property on the vertex, a face element whose index list
// is not first, and an unknown trailing element with a list.
std::vector<uint8_t> AwkwardPly(const std::string& format) {
  const bool ascii = format == "ascii";
  const bool be = format == "binary_big_endian";
  std::string header = "ply\nformat " + format + " 1.0\ncomment awkward\nobj_info test\n";
  header += "element camera 1\nproperty float32 view_px\nproperty uint8 flags\n";
  header += "element vertex 4\nproperty uchar red\nproperty double x\nproperty list uint8 int32 tags\n";
  header += "property float y\nproperty short z\nproperty float nx\n";
  header += "element face 2\nproperty int flags\nproperty list uchar uint vertex_indices\nproperty float q\n";
  header += "element extra 1\nproperty list ushort char junk\nend_header\n";
  std::vector<uint8_t> out(header.begin(), header.end());
  const double xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 3}};
  if (ascii) {
    std::string body = "0.5 7\n";
    for (auto& p : xyz) {
      body += "200 " + std::to_string(p[0]) + " 2 5 6 " + std::to_string(p[1]) + " " +
              std::to_string(static_cast<int>(p[2])) + " 0.25\n";
    }
    body += "9 4 0 1 2 3 0.5\n9 3 2 1 3 0.5\n3 -1 -2 -3\n";
    out.insert(out.end(), body.begin(), body.end());
    return out;
  }
  using testing::AppendScalar;
  AppendScalar<float>(&out, 0.5f, be);
  AppendScalar<uint8_t>(&out, 7, be);
  for (auto& p : xyz) {
    AppendScalar<uint8_t>(&out, 200, be);
    AppendScalar<double>(&out, p[0], be);
    AppendScalar<uint8_t>(&out, 2, be);
    AppendScalar<int32_t>(&out, 5, be);
    AppendScalar<int32_t>(&out, 6, be);
    AppendScalar<float>(&out, static_cast<float>(p[1]), be);
    AppendScalar<int16_t>(&out, static_cast<int16_t>(p[2]), be);
    AppendScalar<float>(&out, 0.25f, be);
  }
  const std::vector<std::vector<uint32_t>> faces = {{0, 1, 2, 3}, {2, 1, 3}};
  for (const auto& f : faces) {
    AppendScalar<int32_t>(&out, 9, be);
    AppendScalar<uint8_t>(&out, static_cast<uint8_t>(f.size()), be);
    for (uint32_t i : f) AppendScalar<uint32_t>(&out, i, be);
    AppendScalar<float>(&out, 0.5f, be);
  }
  AppendScalar<uint16_t>(&out, 3, be);
  for (int j : {-1, -2, -3}) AppendScalar<int8_t>(&out, static_cast<int8_t>(j), be);
  return out;
}

class PlyEncodings : public ::testing::TestWithParam<std::string> {};

TEST_P(PlyEncodings, ReadsOnlyPositionsAndFaces) {
  ReadReport report;
  auto m = ReadMeshFromBytes(AwkwardPly(GetParam()), "ply", "awkward.ply", &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(report.format, "ply");
  ASSERT_EQ(m->num_vertices(), 4u);
  EXPECT_EQ(m->positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(m->positions[3], Vec3(0, 1, 3));
  EXPECT_EQ(report.polygons_triangulated, 1u);
  ExpectFaces(*m, {{0, 1, 2}, {0, 2, 3}, {2, 1, 3}});
}

TEST_P(PlyEncodings, TruncationIsAnErrorAtEveryLength) {
  const std::vector<uint8_t> full = AwkwardPly(GetParam());
  const std::string header_end = "end_header\n";
  const auto it = std::search(full.begin(), full.end(), header_end.begin(), header_end.end());
  const size_t body = static_cast<size_t>(it - full.begin()) + header_end.size();
  // Every cut inside the vertex and face data must fail; ascii may end a token early
  // and still parse as a shorter number, so only the binary encodings check each byte.
  const bool ascii = GetParam() == "ascii";
  for (size_t cut = 0; cut + 1 < full.size(); ++cut) {
    if (ascii && cut >= body) continue;
    std::vector<uint8_t> part(full.begin(), full.begin() + static_cast<ptrdiff_t>(cut));
    auto m = ReadMeshFromBytes(part, "ply", "cut.ply");
    EXPECT_FALSE(m.ok()) << "cut at " << cut << " of " << full.size();
    if (!m.ok()) {
      EXPECT_NE(m.status().message().find("cut.ply"), std::string::npos);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllThree, PlyEncodings,
                         ::testing::Values("ascii", "binary_little_endian", "binary_big_endian"));

TEST(ReadPly, TriStripsAlternateWindingAndSkipDegenerates) {
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 9\nproperty float x\nproperty float y\nproperty float z\n"
      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
  for (int i = 0; i < 9; ++i) ply += std::to_string(i) + " " + std::to_string(i * i) + " 0\n";
  ply += "12 0 1 2 3 3 4 -1 6 7 8 -1 5\n";
  auto m = ReadText(ply, "ply");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  // Strip A = 0 1 2 3 3 4: k=0 (0,1,2); k=1 (2,1,3); k=2 (2,3,3) degenerate;
  // k=3 (3,3,4) degenerate. Strip B = 6 7 8: (6,7,8). Strip C = 5: nothing.
  // Vertices 4 and 5 end up unused, so 6 7 8 become 4 5 6.
  ExpectFaces(*m, {{0, 1, 2}, {2, 1, 3}, {4, 5, 6}});
}

TEST(ReadPly, FaceListNamedVertexIndexAndSizedTypeNames) {
  const std::string ply =
      "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float32 x\r\nproperty float32 y\r\n"
      "property float32 z\r\nelement face 1\r\nproperty list uint8 int32 vertex_index\r\nend_header\r\n"
      "0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n";
  auto m = ReadText(ply, "ply");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  ExpectFaces(*m, {{0, 1, 2}});
}

TEST(ReadMeshFromBytes, ContentWinsOverAWrongFormat) {
  ReadReport report;
  auto m = ReadMeshFromBytes(AwkwardPly("binary_little_endian"), "obj", "misnamed.obj", &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(report.format, "ply");
  EXPECT_EQ(m->num_faces(), 3u);
  auto off = ReadText("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "", &report);
  ASSERT_TRUE(off.ok()) << off.status().ToString();
  EXPECT_EQ(report.format, "off");
}

TEST(ReadMesh, GzipByMagicAndExtension) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string path = testing::TempPath("tri.obj.gz");
  testing::WriteFile(path, testing::Gzip(ToBytes(obj)));
  ReadReport report;
  auto m = ReadMesh(path, &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(report.format, "obj");
  EXPECT_EQ(m->num_faces(), 1u);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace eqmesh
