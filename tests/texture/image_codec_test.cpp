// The texture image codec: lossless PNG and bounded-error JPEG round trips, the
// JPEG quality estimate against the quality encoded, deterministic output, and the
// decoders on files from independent writers (hand-made PNGs of every colour type,
// bit depth and interlacing; libjpeg's progressive and CMYK output) and on
// truncated, bit-flipped, random and size-lying input: an error or an image of the
// size its header declares, never a crash (these tests also run under ASan/UBSan).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>  // before jpeglib.h
#include <cstdlib>
#include <cstring>
#include <new>
#include <random>
#include <string>
#include <vector>

#include <jpeglib.h>
#include <zlib.h>

#include "texture/image_codec.h"

// The largest single operator new request since the last reset: shows that a
// refused header allocated no pixels (the codec's pixel buffers are std::vectors).
// Not inlined: gcc would see malloc and free meet operator delete and new, and warn.
static std::atomic<size_t> g_largest_allocation{0};

[[gnu::noinline]] void* operator new(size_t size) {
  size_t seen = g_largest_allocation.load(std::memory_order_relaxed);
  while (size > seen && !g_largest_allocation.compare_exchange_weak(seen, size)) {
  }
  void* p = std::malloc(size == 0 ? 1 : size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, size_t) noexcept { std::free(p); }

namespace eqmesh::texture {
namespace {

// ----- Synthetic images ------------------------------------------------------

// A smooth gradient per channel, different for each channel.
Image Gradient(int width, int height, int channels) {
  Image image;
  image.width = width;
  image.height = height;
  image.channels = channels;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) {
        const double v = 128 + 90 * std::sin(0.07 * (c + 1) * x + 0.05 * (3 - c) * y + c);
        image.pixels.push_back(static_cast<uint8_t>(std::lround(v)));
      }
    }
  }
  return image;
}

double Psnr(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = static_cast<double>(a.pixels[i]) - static_cast<double>(b.pixels[i]);
    sum += d * d;
  }
  const double mse = sum / static_cast<double>(a.pixels.size());
  return mse == 0 ? 1e9 : 10 * std::log10(255.0 * 255.0 / mse);
}

std::vector<uint8_t> MustEncodePng(const Image& image) {
  auto bytes = EncodePng(image);
  EXPECT_TRUE(bytes.ok()) << bytes.status().ToString();
  return bytes.ok() ? *bytes : std::vector<uint8_t>();
}

std::vector<uint8_t> MustEncodeJpeg(const Image& image, int quality) {
  auto bytes = EncodeJpeg(image, quality);
  EXPECT_TRUE(bytes.ok()) << bytes.status().ToString();
  return bytes.ok() ? *bytes : std::vector<uint8_t>();
}

Image MustDecode(const std::vector<uint8_t>& bytes) {
  auto image = DecodeImage(bytes.data(), bytes.size());
  EXPECT_TRUE(image.ok()) << image.status().ToString();
  return image.ok() ? *image : Image();
}

// ----- JPEG files from libjpeg directly ---------------------------------------

// A JPEG of `image` written by libjpeg with `configure` applied after the defaults
// (libjpeg's default error handler exits: these inputs are valid).
std::vector<uint8_t> LibjpegWrite(const Image& image, J_COLOR_SPACE space,
                                  void (*configure)(jpeg_compress_struct*)) {
  jpeg_compress_struct cinfo{};
  jpeg_error_mgr err{};
  cinfo.err = jpeg_std_error(&err);
  jpeg_create_compress(&cinfo);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&cinfo, &buffer, &size);
  cinfo.image_width = static_cast<JDIMENSION>(image.width);
  cinfo.image_height = static_cast<JDIMENSION>(image.height);
  cinfo.input_components = image.channels;
  cinfo.in_color_space = space;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, 90, TRUE);
  configure(&cinfo);
  jpeg_start_compress(&cinfo, TRUE);
  while (cinfo.next_scanline < cinfo.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(image.pixels.data() + cinfo.next_scanline * image.width * image.channels);
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  std::vector<uint8_t> bytes(buffer, buffer + size);
  jpeg_destroy_compress(&cinfo);
  std::free(buffer);
  return bytes;
}

void Progressive(jpeg_compress_struct* cinfo) { jpeg_simple_progression(cinfo); }
void ArithmeticCoded(jpeg_compress_struct* cinfo) { cinfo->arith_code = TRUE; }
void NoChange(jpeg_compress_struct*) {}

// A grayscale script of 316 valid scans: DC, then each AC coefficient alone, sent
// from bit 4 and refined one bit per scan.
void ManyScans(jpeg_compress_struct* cinfo) {
  static std::vector<jpeg_scan_info> scans;
  scans.clear();
  scans.push_back({1, {0}, 0, 0, 0, 0});
  for (int k = 1; k < DCTSIZE2; ++k) {
    scans.push_back({1, {0}, k, k, 0, 4});
    for (int al = 3; al >= 0; --al) scans.push_back({1, {0}, k, k, al + 1, al});
  }
  cinfo->scan_info = scans.data();
  cinfo->num_scans = static_cast<int>(scans.size());
}

// Offset of the frame header (SOF0..SOF2 marker), found by walking the segments.
size_t FindSof(const std::vector<uint8_t>& jpeg) {
  size_t i = 2;
  while (i + 4 <= jpeg.size() && jpeg[i] == 0xff) {
    const uint8_t marker = jpeg[i + 1];
    if (marker >= 0xc0 && marker <= 0xc2) return i;
    i += 2 + (size_t{jpeg[i + 2]} << 8 | jpeg[i + 3]);
  }
  ADD_FAILURE() << "no SOF marker";
  return 0;
}

// ----- PNG files written by hand (zlib for IDAT, CRC-32) ----------------------

struct PngSpec {
  std::string name;
  uint32_t width, height;
  int bit_depth;
  int color_type;  // 0 gray, 2 RGB, 3 palette, 4 gray + alpha, 6 RGBA
  bool interlaced;
  std::vector<uint8_t> plte;
  std::vector<uint8_t> trns;
};

int SamplesPerPixel(int color_type) {
  switch (color_type) {
    case 2: return 3;
    case 4: return 2;
    case 6: return 4;
    default: return 1;
  }
}

void PutBigEndian32(std::vector<uint8_t>* out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out->push_back(static_cast<uint8_t>(v >> shift));
}

void AppendChunk(std::vector<uint8_t>* png, const char* type, const std::vector<uint8_t>& data) {
  PutBigEndian32(png, static_cast<uint32_t>(data.size()));
  std::vector<uint8_t> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  png->insert(png->end(), body.begin(), body.end());
  PutBigEndian32(png, static_cast<uint32_t>(crc32(0, body.data(), static_cast<uInt>(body.size()))));
}

// The sample of channel c at (x, y): a pattern covering the full range of the depth.
uint16_t SampleAt(const PngSpec& spec, uint32_t x, uint32_t y, int c) {
  const uint32_t range = spec.color_type == 3 ? static_cast<uint32_t>(spec.plte.size() / 3)
                                              : (1u << spec.bit_depth);
  return static_cast<uint16_t>((x * 2654435761u + y * 40503u + static_cast<uint32_t>(c) * 977u) % range);
}

// One filter-0 scanline of the pixels x0, x0 + dx, ... of row y, packed MSB first.
void AppendScanline(const PngSpec& spec, uint32_t y, uint32_t x0, uint32_t dx, std::vector<uint8_t>* raw) {
  raw->push_back(0);
  uint32_t bits = 0, filled = 0;
  for (uint32_t x = x0; x < spec.width; x += dx) {
    for (int c = 0; c < SamplesPerPixel(spec.color_type); ++c) {
      const uint16_t v = SampleAt(spec, x, y, c);
      if (spec.bit_depth == 16) {
        raw->push_back(static_cast<uint8_t>(v >> 8));
        raw->push_back(static_cast<uint8_t>(v));
        continue;
      }
      bits = bits << spec.bit_depth | v;
      filled += static_cast<uint32_t>(spec.bit_depth);
      if (filled == 8) {
        raw->push_back(static_cast<uint8_t>(bits));
        bits = 0;
        filled = 0;
      }
    }
  }
  if (filled > 0) raw->push_back(static_cast<uint8_t>(bits << (8 - filled)));
}

// The filtered image data, Adam7 passes in order when interlaced (empty passes have
// no scanlines).
std::vector<uint8_t> RawImageData(const PngSpec& spec) {
  static const uint32_t kAdam7[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                        {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
  static const uint32_t kWhole[1][4] = {{0, 0, 1, 1}};
  const auto* passes = spec.interlaced ? kAdam7 : kWhole;
  std::vector<uint8_t> raw;
  for (int p = 0; p < (spec.interlaced ? 7 : 1); ++p) {
    const uint32_t x0 = passes[p][0], y0 = passes[p][1], dx = passes[p][2], dy = passes[p][3];
    if (x0 >= spec.width) continue;
    for (uint32_t y = y0; y < spec.height; y += dy) AppendScanline(spec, y, x0, dx, &raw);
  }
  return raw;
}

std::vector<uint8_t> Deflate(const std::vector<uint8_t>& raw) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<uint8_t> out(size);
  EXPECT_EQ(compress2(out.data(), &size, raw.data(), static_cast<uLong>(raw.size()), 9), Z_OK);
  out.resize(size);
  return out;
}

std::vector<uint8_t> PngHeader(uint32_t width, uint32_t height, int bit_depth, int color_type, bool interlaced) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  std::vector<uint8_t> ihdr;
  PutBigEndian32(&ihdr, width);
  PutBigEndian32(&ihdr, height);
  ihdr.insert(ihdr.end(), {static_cast<uint8_t>(bit_depth), static_cast<uint8_t>(color_type), 0, 0,
                           static_cast<uint8_t>(interlaced ? 1 : 0)});
  AppendChunk(&png, "IHDR", ihdr);
  return png;
}

std::vector<uint8_t> HandMadePng(const PngSpec& spec) {
  std::vector<uint8_t> png = PngHeader(spec.width, spec.height, spec.bit_depth, spec.color_type, spec.interlaced);
  if (!spec.plte.empty()) AppendChunk(&png, "PLTE", spec.plte);
  if (!spec.trns.empty()) AppendChunk(&png, "tRNS", spec.trns);
  AppendChunk(&png, "IDAT", Deflate(RawImageData(spec)));
  AppendChunk(&png, "IEND", {});
  return png;
}

// A sample of `depth` bits as 8 bits: bit replication below 8, rounding from 16.
uint8_t To8Bits(uint32_t v, int depth) {
  if (depth == 16) return static_cast<uint8_t>((v * 255 + 32767) / 65535);
  return static_cast<uint8_t>(v * 255 / ((1u << depth) - 1));
}

uint32_t TrnsKey(const PngSpec& spec, int c) { return uint32_t{spec.trns[2 * c]} << 8 | spec.trns[2 * c + 1]; }

// What the decoder must return for `spec`, per the PNG spec and glTF (no gamma).
Image ExpectedDecode(const PngSpec& spec) {
  const int samples = SamplesPerPixel(spec.color_type);
  const bool palette = spec.color_type == 3;
  const bool alpha_from_trns = !spec.trns.empty();
  Image image;
  image.width = static_cast<int>(spec.width);
  image.height = static_cast<int>(spec.height);
  image.channels = (palette ? 3 : samples) + (alpha_from_trns ? 1 : 0);
  for (uint32_t y = 0; y < spec.height; ++y) {
    for (uint32_t x = 0; x < spec.width; ++x) {
      if (palette) {
        const uint32_t i = SampleAt(spec, x, y, 0);
        for (int c = 0; c < 3; ++c) image.pixels.push_back(spec.plte[3 * i + c]);
        if (alpha_from_trns) image.pixels.push_back(i < spec.trns.size() ? spec.trns[i] : 255);
        continue;
      }
      bool matches_key = alpha_from_trns;
      for (int c = 0; c < samples; ++c) {
        const uint32_t v = SampleAt(spec, x, y, c);
        image.pixels.push_back(To8Bits(v, spec.bit_depth));
        if (alpha_from_trns) matches_key = matches_key && v == TrnsKey(spec, c);
      }
      if (alpha_from_trns) image.pixels.push_back(matches_key ? 0 : 255);
    }
  }
  return image;
}

std::vector<uint8_t> Palette(int entries) {
  std::vector<uint8_t> plte;
  for (int i = 0; i < entries; ++i) {
    plte.insert(plte.end(), {static_cast<uint8_t>(i * 37), static_cast<uint8_t>(255 - i * 11),
                             static_cast<uint8_t>(i * i)});
  }
  return plte;
}

std::vector<PngSpec> PngVariants() {
  return {
      {"gray1", 13, 7, 1, 0, false, {}, {}},
      {"gray2", 13, 7, 2, 0, false, {}, {}},
      {"gray4", 13, 7, 4, 0, false, {}, {}},
      {"gray8_trns", 13, 7, 8, 0, false, {}, {0, 0}},  // the key is the sample at (0, 0)
      {"gray16", 13, 7, 16, 0, false, {}, {}},
      {"gray_alpha8", 13, 7, 8, 4, false, {}, {}},
      {"gray_alpha16", 13, 7, 16, 4, false, {}, {}},
      {"rgb8_trns", 13, 7, 8, 2, false, {}, {0, 0, 0, 209, 0, 162}},  // the pixel at (0, 0)
      {"rgb16", 13, 7, 16, 2, false, {}, {}},
      {"rgba16", 13, 7, 16, 6, false, {}, {}},
      {"palette8", 13, 7, 8, 3, false, Palette(200), {}},
      {"palette4_trns", 13, 7, 4, 3, false, Palette(16), {0, 64, 128, 200, 255}},
      {"palette1", 13, 7, 1, 3, false, Palette(2), {}},
      {"interlaced_rgb8", 13, 11, 8, 2, true, {}, {}},
      {"interlaced_palette2_trns", 13, 11, 2, 3, true, Palette(4), {10, 20}},
      {"interlaced_gray16", 13, 11, 16, 0, true, {}, {}},
      {"interlaced_1x1_rgba8", 1, 1, 8, 6, true, {}, {}},
      {"interlaced_3x2_gray1", 3, 2, 1, 0, true, {}, {}},
  };
}

// Rewrites every chunk's CRC, so that corruption reaches the decoder behind it.
void FixPngCrcs(std::vector<uint8_t>* png) {
  size_t i = 8;
  while (i + 12 <= png->size()) {
    const uint32_t length = uint32_t{(*png)[i]} << 24 | uint32_t{(*png)[i + 1]} << 16 |
                            uint32_t{(*png)[i + 2]} << 8 | (*png)[i + 3];
    if (length > png->size() - i - 12) return;
    const uint32_t crc = static_cast<uint32_t>(crc32(0, png->data() + i + 4, length + 4));
    for (int k = 0; k < 4; ++k) (*png)[i + 8 + length + k] = static_cast<uint8_t>(crc >> (24 - 8 * k));
    i += 12 + length;
  }
}

// ----- Decode-safety checks --------------------------------------------------

// A decoded image must be consistent and inside the limits whatever the input.
void ExpectErrorOrConsistentImage(const std::vector<uint8_t>& bytes, const std::string& what) {
  const auto image = DecodeImage(bytes.data(), bytes.size());
  if (!image.ok()) {
    EXPECT_FALSE(image.status().message().empty()) << what;
    return;
  }
  EXPECT_GT(image->width, 0) << what;
  EXPECT_GT(image->height, 0) << what;
  EXPECT_LE(image->width, kMaxImageSide) << what;
  EXPECT_LE(image->height, kMaxImageSide) << what;
  EXPECT_GE(image->channels, 1) << what;
  EXPECT_LE(image->channels, 4) << what;
  EXPECT_EQ(image->pixels.size(), size_t(image->width) * image->height * image->channels) << what;
}

struct Sample {
  std::string name;
  std::vector<uint8_t> bytes;
};

std::vector<Sample> DecodeSafetySamples() {
  return {
      {"jpeg_baseline_420", MustEncodeJpeg(Gradient(40, 24, 3), 75)},
      {"jpeg_baseline_444", MustEncodeJpeg(Gradient(40, 24, 3), 95)},
      {"jpeg_gray", MustEncodeJpeg(Gradient(40, 24, 1), 80)},
      {"jpeg_progressive", LibjpegWrite(Gradient(40, 24, 3), JCS_RGB, Progressive)},
      {"png_rgba", MustEncodePng(Gradient(24, 16, 4))},
      {"png_interlaced_palette", HandMadePng({"", 19, 13, 4, 3, true, Palette(16), {0, 99}})},
  };
}

// ----- Tests -----------------------------------------------------------------

TEST(SniffImageFormat, RecognisesMagicBytes) {
  const std::vector<uint8_t> png = MustEncodePng(Gradient(2, 2, 3));
  const std::vector<uint8_t> jpeg = MustEncodeJpeg(Gradient(2, 2, 3), 90);
  EXPECT_EQ(*SniffImageFormat(png.data(), png.size()), ImageFormat::kPng);
  EXPECT_EQ(*SniffImageFormat(jpeg.data(), jpeg.size()), ImageFormat::kJpeg);
  const std::vector<uint8_t> webp = {'R', 'I', 'F', 'F', 0, 0, 0, 0, 'W', 'E', 'B', 'P'};
  const auto status = SniffImageFormat(webp.data(), webp.size()).status();
  EXPECT_EQ(status.code(), StatusCode::kParseError);
  EXPECT_EQ(status.message(), "image is neither PNG nor JPEG");
  EXPECT_FALSE(SniffImageFormat(png.data(), 7).ok());  // a cut signature
  EXPECT_FALSE(SniffImageFormat(nullptr, 0).ok());
}

TEST(PngCodec, RoundTripIsBitExactForEveryChannelCount) {
  for (int channels = 1; channels <= 4; ++channels) {
    for (const auto& [w, h] : {std::pair{1, 1}, std::pair{37, 23}, std::pair{300, 2}}) {
      const Image image = Gradient(w, h, channels);
      const Image decoded = MustDecode(MustEncodePng(image));
      EXPECT_EQ(decoded.width, w);
      EXPECT_EQ(decoded.height, h);
      EXPECT_EQ(decoded.channels, channels);
      EXPECT_EQ(decoded.pixels, image.pixels) << channels << " channels, " << w << " x " << h;
    }
  }
}

TEST(PngCodec, EncodingIsDeterministic) {
  const Image image = Gradient(50, 30, 4);
  EXPECT_EQ(MustEncodePng(image), MustEncodePng(image));
}

TEST(PngCodec, DecodesEveryColourTypeBitDepthAndInterlacing) {
  for (const PngSpec& spec : PngVariants()) {
    const Image expected = ExpectedDecode(spec);
    const Image decoded = MustDecode(HandMadePng(spec));
    EXPECT_EQ(decoded.width, expected.width) << spec.name;
    EXPECT_EQ(decoded.height, expected.height) << spec.name;
    EXPECT_EQ(decoded.channels, expected.channels) << spec.name;
    EXPECT_EQ(decoded.pixels, expected.pixels) << spec.name;
  }
}

TEST(PngCodec, HugeDeclaredSizeIsRefusedBeforeAllocating) {
  // IHDR alone, and IHDR followed by real image data.
  std::vector<uint8_t> header_only = PngHeader(100000, 100000, 8, 2, false);
  std::vector<uint8_t> with_data = header_only;
  AppendChunk(&with_data, "IDAT", Deflate(std::vector<uint8_t>(64, 0)));
  AppendChunk(&with_data, "IEND", {});
  for (const auto* bytes : {&header_only, &with_data}) {
    g_largest_allocation = 0;
    const auto image = DecodeImage(bytes->data(), bytes->size());
    EXPECT_LT(g_largest_allocation.load(), size_t{1} << 20);
    ASSERT_FALSE(image.ok());
    EXPECT_EQ(image.status().code(), StatusCode::kResourceLimit) << image.status().ToString();
  }
  // One side past the limit is enough.
  const std::vector<uint8_t> tall = PngHeader(16384, 16385, 8, 6, false);
  EXPECT_EQ(DecodeImage(tall.data(), tall.size()).status().code(), StatusCode::kResourceLimit);
}

TEST(PngCodec, SizeTheDataCannotHoldIsRefusedBeforeAllocating) {
  // Within the limits (exactly 2^30 samples), but 64 zero rows' worth of data.
  std::vector<uint8_t> png = PngHeader(16384, 16384, 8, 6, false);
  AppendChunk(&png, "IDAT", Deflate(std::vector<uint8_t>(64 * (1 + 4 * 16384), 0)));
  AppendChunk(&png, "IEND", {});
  g_largest_allocation = 0;
  const auto image = DecodeImage(png.data(), png.size());
  EXPECT_LT(g_largest_allocation.load(), size_t{1} << 20);
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kParseError) << image.status().ToString();
}

TEST(PngCodec, MalformedInputGivesClearErrors) {
  std::vector<uint8_t> png = MustEncodePng(Gradient(8, 8, 3));
  png[png.size() / 2] ^= 0x40;  // inside IDAT: the CRC no longer matches
  const auto image = DecodeImage(png.data(), png.size());
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kParseError);
  EXPECT_EQ(image.status().message().rfind("corrupt PNG: ", 0), 0u) << image.status().message();
  const std::vector<uint8_t> zero_width = PngHeader(0, 5, 8, 0, false);
  EXPECT_EQ(DecodeImage(zero_width.data(), zero_width.size()).status().code(), StatusCode::kParseError);
}

TEST(JpegCodec, SmoothRgbAtQuality90KeepsPsnrAbove35Db) {
  const Image image = Gradient(64, 48, 3);
  const Image decoded = MustDecode(MustEncodeJpeg(image, 90));
  ASSERT_EQ(decoded.width, 64);
  ASSERT_EQ(decoded.height, 48);
  ASSERT_EQ(decoded.channels, 3);
  EXPECT_GE(Psnr(image, decoded), 35.0);
}

TEST(JpegCodec, GrayStaysOneChannel) {
  const Image image = Gradient(33, 17, 1);
  const Image decoded = MustDecode(MustEncodeJpeg(image, 85));
  ASSERT_EQ(decoded.channels, 1);
  EXPECT_GE(Psnr(image, decoded), 35.0);
}

TEST(JpegCodec, EstimatedQualityIsTheQualityEncoded) {
  for (const int quality : {50, 75, 90, 95}) {
    for (const int channels : {1, 3}) {
      const std::vector<uint8_t> jpeg = MustEncodeJpeg(Gradient(16, 16, channels), quality);
      EXPECT_NEAR(EstimateJpegQuality(jpeg.data(), jpeg.size()), quality, 1) << channels << " channels";
    }
  }
  // Beyond the baseline range of 8-bit tables, and at the ends of the scale.
  for (const int quality : {1, 10, 30, 99, 100}) {
    const std::vector<uint8_t> jpeg = MustEncodeJpeg(Gradient(16, 16, 3), quality);
    EXPECT_NEAR(EstimateJpegQuality(jpeg.data(), jpeg.size()), quality, 1);
  }
}

TEST(JpegCodec, EstimatedQualityIsMinusOneForNonJpeg) {
  const std::vector<uint8_t> png = MustEncodePng(Gradient(4, 4, 3));
  EXPECT_EQ(EstimateJpegQuality(png.data(), png.size()), -1);
  EXPECT_EQ(EstimateJpegQuality(nullptr, 0), -1);
  const std::vector<uint8_t> soi_only = {0xff, 0xd8, 0xff};
  EXPECT_EQ(EstimateJpegQuality(soi_only.data(), soi_only.size()), -1);
}

TEST(JpegCodec, EncodingIsDeterministic) {
  const Image image = Gradient(70, 45, 3);
  for (const int quality : {60, 92}) EXPECT_EQ(MustEncodeJpeg(image, quality), MustEncodeJpeg(image, quality));
}

TEST(JpegCodec, ChromaIsSubsampledBelowQuality90Only) {
  const Image image = Gradient(32, 32, 3);
  for (const auto& [quality, luma_sampling] : {std::pair{50, 0x22}, std::pair{89, 0x22}, std::pair{90, 0x11},
                                              std::pair{100, 0x11}}) {
    const std::vector<uint8_t> jpeg = MustEncodeJpeg(image, quality);
    const size_t sof = FindSof(jpeg);
    ASSERT_EQ(jpeg[sof + 9], 3);  // components
    EXPECT_EQ(jpeg[sof + 11], luma_sampling) << "quality " << quality;
    EXPECT_EQ(jpeg[sof + 14], 0x11);
  }
}

TEST(JpegCodec, AlphaIsDropped) {
  const Image rgba = Gradient(20, 10, 4);
  Image rgb = rgba;
  rgb.channels = 3;
  rgb.pixels.clear();
  Image gray_alpha = Gradient(20, 10, 2);
  Image gray = gray_alpha;
  gray.channels = 1;
  gray.pixels.clear();
  for (size_t i = 0; i < rgba.pixels.size(); ++i) {
    if (i % 4 != 3) rgb.pixels.push_back(rgba.pixels[i]);
  }
  for (size_t i = 0; i < gray_alpha.pixels.size(); i += 2) gray.pixels.push_back(gray_alpha.pixels[i]);
  EXPECT_EQ(MustEncodeJpeg(rgba, 80), MustEncodeJpeg(rgb, 80));
  EXPECT_EQ(MustEncodeJpeg(gray_alpha, 80), MustEncodeJpeg(gray, 80));
}

TEST(JpegCodec, DecodesProgressiveAndArithmeticCoded) {
  const Image image = Gradient(48, 40, 3);
  for (auto* configure : {Progressive, ArithmeticCoded}) {
    const Image decoded = MustDecode(LibjpegWrite(image, JCS_RGB, configure));
    ASSERT_EQ(decoded.channels, 3);
    ASSERT_EQ(decoded.pixels.size(), image.pixels.size());
    EXPECT_GE(Psnr(image, decoded), 35.0);
  }
}

TEST(JpegCodec, RefusesFilesWithTooManyScans) {
  const std::vector<uint8_t> jpeg = LibjpegWrite(Gradient(16, 16, 1), JCS_GRAYSCALE, ManyScans);
  const auto image = DecodeImage(jpeg.data(), jpeg.size());
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kResourceLimit) << image.status().ToString();
}

TEST(JpegCodec, RefusesCmyk) {
  const std::vector<uint8_t> jpeg = LibjpegWrite(Gradient(16, 16, 4), JCS_CMYK, NoChange);
  const auto image = DecodeImage(jpeg.data(), jpeg.size());
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kUnsupportedFeature);
  EXPECT_NE(image.status().message().find("CMYK"), std::string::npos) << image.status().message();
}

TEST(JpegCodec, HugeDeclaredSizeIsRefusedBeforeAllocating) {
  std::vector<uint8_t> jpeg = MustEncodeJpeg(Gradient(16, 16, 3), 75);
  const size_t sof = FindSof(jpeg);
  for (const size_t at : {sof + 5, sof + 7}) {  // height, width
    jpeg[at] = 20000 >> 8;
    jpeg[at + 1] = 20000 & 0xff;
  }
  g_largest_allocation = 0;
  const auto image = DecodeImage(jpeg.data(), jpeg.size());
  EXPECT_LT(g_largest_allocation.load(), size_t{1} << 20);
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kResourceLimit) << image.status().ToString();
}

TEST(JpegCodec, MissingDataIsAnErrorNotGrayPixels) {
  const std::vector<uint8_t> jpeg = MustEncodeJpeg(Gradient(64, 64, 3), 90);
  const std::vector<uint8_t> half(jpeg.begin(), jpeg.begin() + static_cast<long>(jpeg.size() / 2));
  const auto image = DecodeImage(half.data(), half.size());
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().code(), StatusCode::kParseError);
  EXPECT_EQ(image.status().message().rfind("corrupt JPEG: ", 0), 0u) << image.status().message();
}

TEST(ImageEncoders, RejectMalformedImagesAndQualities) {
  Image image = Gradient(4, 4, 3);
  EXPECT_EQ(EncodeJpeg(image, 0).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(EncodeJpeg(image, 101).status().code(), StatusCode::kInvalidArgument);
  image.pixels.pop_back();
  EXPECT_EQ(EncodePng(image).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(EncodeJpeg(image, 80).status().code(), StatusCode::kInvalidArgument);
  Image five = Gradient(4, 4, 5);
  EXPECT_EQ(EncodePng(five).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(EncodePng(Image()).status().code(), StatusCode::kInvalidArgument);
}

TEST(ImageDecodeSafety, TruncatedPrefixesFailOrGiveTheWholeImage) {
  for (const Sample& sample : DecodeSafetySamples()) {
    const Image full = MustDecode(sample.bytes);
    for (size_t length = 0; length < sample.bytes.size(); length += 7) {
      const std::vector<uint8_t> prefix(sample.bytes.begin(), sample.bytes.begin() + static_cast<long>(length));
      const auto image = DecodeImage(prefix.data(), prefix.size());
      if (!image.ok()) continue;
      // No made-up pixels: a prefix decodes only when it holds them all.
      EXPECT_EQ(image->width, full.width) << sample.name << " prefix " << length;
      EXPECT_EQ(image->height, full.height) << sample.name << " prefix " << length;
      EXPECT_EQ(image->pixels, full.pixels) << sample.name << " prefix " << length;
    }
  }
}

TEST(ImageDecodeSafety, BitFlipsFailOrGiveAConsistentImage) {
  for (const Sample& sample : DecodeSafetySamples()) {
    const bool png = sample.name.rfind("png", 0) == 0;
    for (size_t i = 0; i < sample.bytes.size(); ++i) {
      std::vector<uint8_t> flipped = sample.bytes;
      flipped[i] ^= static_cast<uint8_t>(1u << (i % 8));
      if (png) FixPngCrcs(&flipped);
      ExpectErrorOrConsistentImage(flipped, sample.name + " flip at " + std::to_string(i));
    }
  }
}

TEST(ImageDecodeSafety, RandomDamageFailsOrGivesAConsistentImage) {
  std::mt19937 rng(20261207);
  for (const Sample& sample : DecodeSafetySamples()) {
    const bool png = sample.name.rfind("png", 0) == 0;
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<uint8_t> damaged = sample.bytes;
      for (int k = 0; k < 1 + trial % 8; ++k) damaged[rng() % damaged.size()] = static_cast<uint8_t>(rng());
      if (png) FixPngCrcs(&damaged);
      ExpectErrorOrConsistentImage(damaged, sample.name + " trial " + std::to_string(trial));
    }
  }
}

TEST(ImageDecodeSafety, EmptyAndRandomBytesAreErrors) {
  EXPECT_FALSE(DecodeImage(nullptr, 0).ok());
  const std::vector<uint8_t> empty;
  EXPECT_FALSE(DecodeImage(empty.data(), 0).ok());
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<uint8_t> bytes(1 + rng() % 2000);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
    // Plain noise, and noise behind each format's magic bytes.
    const std::vector<uint8_t> magic = trial % 3 == 0   ? std::vector<uint8_t>{}
                                       : trial % 3 == 1 ? std::vector<uint8_t>{0xff, 0xd8, 0xff}
                                                        : std::vector<uint8_t>{0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
    bytes.insert(bytes.begin(), magic.begin(), magic.end());
    const auto image = DecodeImage(bytes.data(), bytes.size());
    EXPECT_FALSE(image.ok()) << "trial " << trial;
  }
}

}  // namespace
}  // namespace eqmesh::texture
