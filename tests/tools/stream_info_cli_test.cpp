// `eqmesh info` on streams: the report agrees with the decoder (every level's
// vertex and face count, the chunk ranges), says when a file is a prefix, and
// refuses what is not a stream with one clear line and a non-zero exit.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "codec/codec_fixtures.h"
#include "coding/decoder.h"
#include "coding/encoder.h"
#include "tools/tool_runner.h"

namespace eqmesh::testing {
namespace {

void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes, size_t size) {
  WriteText(path, std::string(reinterpret_cast<const char*>(bytes.data()), size));
}

nlohmann::json InfoJson(const std::string& path) {
  const ToolRun r = RunTool("info " + path + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return nlohmann::json::parse(r.output, nullptr, false);
}

TEST(StreamInfoCli, ReportAgreesWithTheDecoder) {
  const ScratchDir dir("stream_info");
  auto stream = Encode(MakeBumpySphereWithKept(2), GoldenOptions());
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  const std::string path = dir.Path("sphere.eqm");
  WriteBytes(path, *stream, stream->size());
  const nlohmann::json j = InfoJson(path);
  ASSERT_FALSE(j.is_discarded());
  EXPECT_EQ(j["version"], "1.5");  // the kept tetrahedron travels in a compact chunk
  EXPECT_TRUE(j["compact_kept"].get<bool>());
  EXPECT_EQ(j["coder"], "eq");
  EXPECT_TRUE(j["tangential_context"].get<bool>());
  EXPECT_TRUE(j["kept_exactly"].get<bool>());
  EXPECT_FALSE(j["truncated"].get<bool>());
  EXPECT_EQ(j["bytes"].get<size_t>(), stream->size());
  EXPECT_EQ(j["stream_bytes"].get<size_t>(), stream->size());
  const int levels = j["levels"].get<int>();
  ASSERT_EQ(j["level_meshes"].size(), static_cast<size_t>(levels) + 1);
  for (int k = 0; k <= levels; ++k) {
    DecodeOptions options;
    options.max_level = k;
    auto mesh = Decode(stream->data(), stream->size(), options);
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    const nlohmann::json& level = j["level_meshes"][static_cast<size_t>(k)];
    EXPECT_EQ(level["vertices"].get<size_t>(), mesh->positions.size()) << "level " << k;
    EXPECT_EQ(level["faces"].get<size_t>(), mesh->faces.size()) << "level " << k;
    EXPECT_EQ(level["prefix_bytes"], j["prefix_sizes"][static_cast<size_t>(k)]);
  }
  // The plain table says the same in words.
  const ToolRun table = RunTool("info " + path);
  EXPECT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("eqm stream 1.5"), std::string::npos) << table.output;
}

TEST(StreamInfoCli, PrefixesAreReportedAndNonStreamsRefused) {
  const ScratchDir dir("stream_info_bad");
  auto stream = Encode(MakeBumpySphereWithKept(2), GoldenOptions());
  ASSERT_TRUE(stream.ok());
  auto info = ReadStreamInfo(stream->data(), stream->size());
  ASSERT_TRUE(info.ok());
  // A prefix that holds the base: counts, and "truncated".
  const std::string prefix = dir.Path("prefix.eqm");
  WriteBytes(prefix, *stream, static_cast<size_t>(info->prefix_size[0]) + 1);
  const nlohmann::json j = InfoJson(prefix);
  ASSERT_FALSE(j.is_discarded());
  EXPECT_TRUE(j["truncated"].get<bool>());
  EXPECT_EQ(j["level_meshes"].size(), static_cast<size_t>(info->levels) + 1);
  // Header only: the header is reported, no level counts.
  const std::string header = dir.Path("header.eqm");
  WriteBytes(header, *stream, static_cast<size_t>(info->header_size));
  const nlohmann::json h = InfoJson(header);
  ASSERT_FALSE(h.is_discarded());
  EXPECT_TRUE(h["level_meshes"].empty());
  // Less than a header, and not a stream at all: one error line, exit 1.
  const std::string cut = dir.Path("cut.eqm");
  WriteBytes(cut, *stream, 9);
  const ToolRun r = RunTool("info " + cut);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("eqmesh info: error: " + cut), std::string::npos) << r.output;
  const std::string junk = dir.Path("junk.eqm");
  WriteText(junk, "solid not a stream at all\n");
  const ToolRun k = RunTool("info " + junk);
  EXPECT_EQ(k.exit_code, 1) << k.output;
  EXPECT_NE(k.output.find("not an eqmesh stream"), std::string::npos) << k.output;
}

}  // namespace
}  // namespace eqmesh::testing
