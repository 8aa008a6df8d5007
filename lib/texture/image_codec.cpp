// Texture image codec over the system libraries: libjpeg-turbo through the libjpeg
// API (jpeg_read_header / jpeg_start_decompress / jpeg_read_scanlines to decode,
// jpeg_set_quality / jpeg_write_scanlines to encode) and libpng through its
// png_read_* / png_write_* API. The JPEG quality estimate inverts libjpeg's
// jpeg_set_quality: the ITU-T T.81 Annex K luminance table scaled by the IJG rule.
//
// Both libraries report a fatal error by calling a handler that must not return.
// Ours longjmp back to the setjmp at the top of a "guarded step" (the functions named
// ...Guarded): a function that owns no object with a destructor, between which and
// the handler lie only C frames and our callbacks, which own none either, so the jump
// skips no destructor ([csetjmp.syn]). Everything a step works on lives in a plain
// struct owned by its C++ caller, which frees the library state in a guard once the
// step has returned, normally or by the jump. Pixel buffers and row tables are
// allocated by the caller between steps, after the header has been checked.
//
// Departures from the libraries' defaults: no message goes to stderr (errors come
// back as Status); a JPEG warning that means lost pixels is fatal (libjpeg would fill
// the rest with gray); a JPEG with more than kMaxJpegScans scans is refused, since
// every progressive scan revisits the whole image.
#include "texture/image_codec.h"

#include <csetjmp>
#include <cstdio>  // before jpeglib.h, which uses FILE and size_t
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

#include <jerror.h>
#include <jpeglib.h>
#include <png.h>

namespace eqmesh::texture {
namespace {

// zlib level 8. Measured on the decoded 512^2 and 1024^2 textures of
// ../shared/meshes/textured (duck, horse), as is and with a third of them blanked
// like atlas gutters: level 8 is 0.5-2.5 % smaller than 6 for 1.3-2.7x its time;
// level 9 gains a further 0.2-2 % for another 1.7-2.3x (0.57 s a megapixel here),
// too much time for too little.
constexpr int kPngZlibLevel = 8;
// Deflate inflates at most about 1032:1 (a 258-byte match in 2 bits), so a PNG whose
// file could not hold its image data that compressed lies about its size (the rule
// of mesh/file_bytes.cpp): refused before its pixels are allocated.
constexpr uint64_t kMaxDeflateRatio = 1032;
constexpr size_t kFirstOutputBytes = size_t{64} << 10;
constexpr size_t kMessageBytes = 200;

// ----- Shared helpers --------------------------------------------------------

bool IsPng(const uint8_t* data, size_t size) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  return size >= sizeof(kSignature) && std::memcmp(data, kSignature, sizeof(kSignature)) == 0;
}

// SOI followed by the first marker's 0xFF.
bool IsJpeg(const uint8_t* data, size_t size) {
  return size >= 3 && data[0] == 0xff && data[1] == 0xd8 && data[2] == 0xff;
}

std::string SizeText(uint64_t width, uint64_t height) {
  return std::to_string(width) + " x " + std::to_string(height);
}

// The limits every decoded or encoded image obeys; checked from headers, before the
// pixels are allocated.
Status CheckImageSize(const char* format, uint64_t width, uint64_t height, uint64_t channels) {
  if (width == 0 || height == 0) {
    return ParseError(std::string("corrupt ") + format + ": the header declares a " +
                      SizeText(width, height) + " image");
  }
  if (width > kMaxImageSide || height > kMaxImageSide) {
    return ResourceLimit(std::string(format) + " image of " + SizeText(width, height) +
                         " exceeds the " + SizeText(kMaxImageSide, kMaxImageSide) + " limit");
  }
  if (width * height * channels > kMaxImageBytes) {
    return ResourceLimit(std::string(format) + " image of " + SizeText(width, height) + " x " +
                         std::to_string(channels) + " samples exceeds the limit of 2^30 samples");
  }
  return Status::Ok();
}

Image AllocateImage(int width, int height, int channels) {
  Image image;
  image.width = width;
  image.height = height;
  image.channels = channels;
  image.pixels.resize(static_cast<size_t>(width) * height * channels);
  return image;
}

size_t RowBytes(const Image& image) { return static_cast<size_t>(image.width) * image.channels; }

Status CheckImageForEncoding(const Image& image) {
  if (image.channels < 1 || image.channels > 4) {
    return InvalidArgument("image has " + std::to_string(image.channels) + " channels; 1 to 4 expected");
  }
  if (image.width <= 0 || image.height <= 0) {
    return InvalidArgument("image is " + std::to_string(image.width) + " x " +
                           std::to_string(image.height) + " pixels");
  }
  EQMESH_RETURN_IF_ERROR(CheckImageSize("encoded", static_cast<uint64_t>(image.width),
                                        static_cast<uint64_t>(image.height),
                                        static_cast<uint64_t>(image.channels)));
  if (image.pixels.size() != RowBytes(image) * image.height) {
    return InvalidArgument("image of " + SizeText(image.width, image.height) + " x " +
                           std::to_string(image.channels) + " holds " +
                           std::to_string(image.pixels.size()) + " bytes");
  }
  return Status::Ok();
}

// Encoder output in malloc'd memory: the library callbacks that grow it run between a
// setjmp and a possible longjmp, where a std::vector could neither throw nor be freed.
struct OutputBuffer {
  uint8_t* data;
  size_t size;
  size_t capacity;
};

bool ReserveOutput(OutputBuffer* out, size_t min_capacity) {
  if (out->capacity >= min_capacity) return true;
  size_t capacity = out->capacity < kFirstOutputBytes ? kFirstOutputBytes : out->capacity;
  while (capacity < min_capacity) {
    if (capacity > std::numeric_limits<size_t>::max() / 2) return false;
    capacity *= 2;
  }
  void* grown = std::realloc(out->data, capacity);
  if (grown == nullptr) return false;
  out->data = static_cast<uint8_t*>(grown);
  out->capacity = capacity;
  return true;
}

bool AppendOutput(OutputBuffer* out, const uint8_t* bytes, size_t count) {
  if (count > std::numeric_limits<size_t>::max() - out->size) return false;
  if (!ReserveOutput(out, out->size + count)) return false;
  std::memcpy(out->data + out->size, bytes, count);
  out->size += count;
  return true;
}

std::vector<uint8_t> CopyOutput(const OutputBuffer& out) {
  return std::vector<uint8_t>(out.data, out.data + out.size);
}

// ----- JPEG: error trap ------------------------------------------------------

// cinfo->err points at `pub`, the first member, so the handlers recover the trap
// from it (the standard-layout first-member rule libjpeg's own examples rely on).
struct JpegTrap {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
  StatusCode code;
};
static_assert(std::is_standard_layout_v<JpegTrap>);

JpegTrap* TrapOf(j_common_ptr cinfo) { return reinterpret_cast<JpegTrap*>(cinfo->err); }

[[noreturn]] void JpegFailWith(j_common_ptr cinfo, StatusCode code, const char* message) {
  JpegTrap* trap = TrapOf(cinfo);
  std::snprintf(trap->message, sizeof(trap->message), "%s", message);
  trap->code = code;
  std::longjmp(trap->jump, 1);
}

StatusCode JpegErrorCode(int msg_code) {
  switch (msg_code) {
    case JERR_OUT_OF_MEMORY:
    case JERR_NO_BACKING_STORE:
      return StatusCode::kResourceLimit;
    case JERR_BAD_PRECISION:
    case JERR_NOT_COMPILED:
    case JERR_SOF_UNSUPPORTED:
    case JERR_CONVERSION_NOTIMPL:
      return StatusCode::kUnsupportedFeature;
    default:
      return StatusCode::kParseError;
  }
}

// libjpeg's error_exit.
[[noreturn]] void OnJpegError(j_common_ptr cinfo) {
  char message[JMSG_LENGTH_MAX];
  cinfo->err->format_message(cinfo, message);
  JpegFailWith(cinfo, JpegErrorCode(cinfo->err->msg_code), message);
}

// Warnings about framing and metadata, which libjpeg works around with every pixel
// intact; any other warning (data ended, bad Huffman code, lost restart sync) means
// the rest of the image would be made up.
bool JpegWarningKeepsPixels(int msg_code) {
  return msg_code == JWRN_EXTRANEOUS_DATA || msg_code == JWRN_JFIF_MAJOR ||
         msg_code == JWRN_ADOBE_XFORM || msg_code == JWRN_BOGUS_ICC;
}

// libjpeg's emit_message: level -1 is a warning, 0 and up are trace messages.
void OnJpegMessage(j_common_ptr cinfo, int msg_level) {
  if (msg_level >= 0) return;
  if (!JpegWarningKeepsPixels(cinfo->err->msg_code)) OnJpegError(cinfo);
  cinfo->err->num_warnings++;
}

void IgnoreJpegOutput(j_common_ptr) {}

// Makes `trap` the error manager that `err` (a cinfo's err field) points to.
void InstallJpegTrap(JpegTrap* trap, jpeg_error_mgr** err) {
  *err = jpeg_std_error(&trap->pub);
  trap->pub.error_exit = OnJpegError;
  trap->pub.emit_message = OnJpegMessage;
  trap->pub.output_message = IgnoreJpegOutput;
  trap->code = StatusCode::kParseError;
}

Status JpegDecodeFailure(const JpegTrap& trap) {
  switch (trap.code) {
    case StatusCode::kUnsupportedFeature: return UnsupportedFeature(std::string("unsupported JPEG: ") + trap.message);
    case StatusCode::kResourceLimit: return ResourceLimit(std::string("JPEG over the decoder's limits: ") + trap.message);
    case StatusCode::kInternal: return InternalError(std::string("JPEG decoder: ") + trap.message);
    default: return ParseError(std::string("corrupt JPEG: ") + trap.message);
  }
}

// ----- JPEG: decoding --------------------------------------------------------

struct JpegReader {
  jpeg_decompress_struct cinfo;
  JpegTrap trap;
  jpeg_progress_mgr progress;
};

struct JpegReaderGuard {
  JpegReader* reader;
  ~JpegReaderGuard() { jpeg_destroy_decompress(&reader->cinfo); }
};

// libjpeg's progress_monitor, called while a multi-scan file is read.
void LimitJpegScans(j_common_ptr cinfo) {
  if (!cinfo->is_decompressor) return;
  if (reinterpret_cast<j_decompress_ptr>(cinfo)->input_scan_number > kMaxJpegScans) {
    // A char array, not a std::string: the jump below would skip its destructor.
    char message[64];
    std::snprintf(message, sizeof(message), "more than %d scans", kMaxJpegScans);
    JpegFailWith(cinfo, StatusCode::kResourceLimit, message);
  }
}

bool OpenJpegGuarded(JpegReader* reader, const uint8_t* data, size_t size) {
  if (setjmp(reader->trap.jump) != 0) return false;
  jpeg_create_decompress(&reader->cinfo);
  reader->progress.progress_monitor = LimitJpegScans;
  reader->cinfo.progress = &reader->progress;
  jpeg_mem_src(&reader->cinfo, data, static_cast<unsigned long>(size));
  jpeg_read_header(&reader->cinfo, TRUE);
  return true;
}

// Sets the output colour space: gray stays gray, YCbCr and RGB become RGB.
StatusOr<int> ChooseJpegOutput(jpeg_decompress_struct* cinfo) {
  switch (cinfo->jpeg_color_space) {
    case JCS_GRAYSCALE:
      cinfo->out_color_space = JCS_GRAYSCALE;
      return 1;
    case JCS_YCbCr:
    case JCS_RGB:
      cinfo->out_color_space = JCS_RGB;
      return 3;
    case JCS_CMYK:
    case JCS_YCCK:
      return UnsupportedFeature("unsupported JPEG: CMYK colour (a texture must be gray or RGB)");
    default:
      return UnsupportedFeature("unsupported JPEG: " + std::to_string(cinfo->num_components) +
                                " colour components of unknown meaning");
  }
}

bool DecompressJpegGuarded(JpegReader* reader, Image* image) {
  if (setjmp(reader->trap.jump) != 0) return false;
  jpeg_decompress_struct* cinfo = &reader->cinfo;
  jpeg_start_decompress(cinfo);
  if (cinfo->output_width != static_cast<JDIMENSION>(image->width) ||
      cinfo->output_height != static_cast<JDIMENSION>(image->height) ||
      cinfo->output_components != image->channels) {
    JpegFailWith(reinterpret_cast<j_common_ptr>(cinfo), StatusCode::kInternal,
                 "output layout differs from the header's");
  }
  while (cinfo->output_scanline < cinfo->output_height) {
    JSAMPROW row = image->pixels.data() + cinfo->output_scanline * RowBytes(*image);
    jpeg_read_scanlines(cinfo, &row, 1);
  }
  // No jpeg_finish_decompress: the pixels are complete once the last row is out, and
  // the markers it would read on to (EOI, trailing metadata) cannot change them.
  return true;
}

StatusOr<Image> DecodeJpeg(const uint8_t* data, size_t size) {
  JpegReader reader{};
  InstallJpegTrap(&reader.trap, &reader.cinfo.err);
  JpegReaderGuard guard{&reader};
  if (!OpenJpegGuarded(&reader, data, size)) return JpegDecodeFailure(reader.trap);
  EQMESH_ASSIGN_OR_RETURN(const int channels, ChooseJpegOutput(&reader.cinfo));
  EQMESH_RETURN_IF_ERROR(CheckImageSize("JPEG", reader.cinfo.image_width, reader.cinfo.image_height,
                                        static_cast<uint64_t>(channels)));
  Image image = AllocateImage(static_cast<int>(reader.cinfo.image_width),
                              static_cast<int>(reader.cinfo.image_height), channels);
  if (!DecompressJpegGuarded(&reader, &image)) return JpegDecodeFailure(reader.trap);
  return image;
}

// ----- JPEG: quality estimate ------------------------------------------------

// ITU-T T.81 Annex K, Table K.1, in natural (row-major) order as libjpeg stores it.
constexpr int kAnnexKLuminance[DCTSIZE2] = {
    16, 11, 10, 16, 24,  40,  51,  61,  12, 12, 14, 19, 26,  58,  60,  55,
    14, 13, 16, 24, 40,  57,  69,  56,  14, 17, 22, 29, 51,  87,  80,  62,
    18, 22, 37, 56, 68,  109, 103, 77,  24, 35, 55, 64, 81,  104, 113, 92,
    49, 64, 78, 87, 103, 121, 120, 101, 72, 92, 95, 98, 112, 100, 103, 99};

// The IJG rule (jpeg_quality_scaling): a percentage applied to the Annex K tables.
int IjgScalePercent(int quality) { return quality < 50 ? 5000 / quality : 200 - 2 * quality; }

// jpeg_add_quant_table's rounding and clamping; baseline tables stop at 255.
int ScaledQuantizer(int base, int scale_percent, bool baseline) {
  const int value = (base * scale_percent + 50) / 100;
  const int ceiling = baseline ? 255 : 32767;
  return value < 1 ? 1 : (value > ceiling ? ceiling : value);
}

int ClosestIjgQuality(const UINT16* table) {
  bool baseline = true;
  for (int k = 0; k < DCTSIZE2; ++k) baseline = baseline && table[k] <= 255;
  int best_quality = -1;
  long best_distance = std::numeric_limits<long>::max();
  for (int quality = 1; quality <= 100; ++quality) {
    const int scale = IjgScalePercent(quality);
    long distance = 0;
    for (int k = 0; k < DCTSIZE2; ++k) {
      distance += std::labs(ScaledQuantizer(kAnnexKLuminance[k], scale, baseline) - long{table[k]});
    }
    if (distance < best_distance) {
      best_distance = distance;
      best_quality = quality;
    }
  }
  return best_quality;
}

// ----- JPEG: encoding --------------------------------------------------------

// cinfo->dest points at `pub`, the first member (as for JpegTrap).
struct JpegDestination {
  jpeg_destination_mgr pub;
  OutputBuffer out;
};
static_assert(std::is_standard_layout_v<JpegDestination>);

struct JpegWriter {
  jpeg_compress_struct cinfo;
  JpegTrap trap;
  JpegDestination destination;
};

struct JpegWriterGuard {
  JpegWriter* writer;
  ~JpegWriterGuard() {
    jpeg_destroy_compress(&writer->cinfo);
    std::free(writer->destination.out.data);
  }
};

// Hands libjpeg the free space after the first `used` bytes, growing the buffer.
void ProvideJpegSpace(j_compress_ptr cinfo, size_t used) {
  JpegDestination* destination = reinterpret_cast<JpegDestination*>(cinfo->dest);
  destination->out.size = used;
  if (!ReserveOutput(&destination->out, used + 1)) {
    JpegFailWith(reinterpret_cast<j_common_ptr>(cinfo), StatusCode::kResourceLimit, "out of memory");
  }
  destination->pub.next_output_byte = destination->out.data + used;
  destination->pub.free_in_buffer = destination->out.capacity - used;
}

void StartJpegOutput(j_compress_ptr cinfo) { ProvideJpegSpace(cinfo, 0); }

// Called when the buffer is full, so everything in it is used.
boolean GrowJpegOutput(j_compress_ptr cinfo) {
  ProvideJpegSpace(cinfo, reinterpret_cast<JpegDestination*>(cinfo->dest)->out.capacity);
  return TRUE;
}

void FinishJpegOutput(j_compress_ptr cinfo) {
  JpegDestination* destination = reinterpret_cast<JpegDestination*>(cinfo->dest);
  destination->out.size = destination->out.capacity - destination->pub.free_in_buffer;
}

void ConfigureJpegEncoder(jpeg_compress_struct* cinfo, const Image& image, int quality) {
  const bool gray = image.channels <= 2;
  cinfo->image_width = static_cast<JDIMENSION>(image.width);
  cinfo->image_height = static_cast<JDIMENSION>(image.height);
  cinfo->input_components = gray ? 1 : 3;
  cinfo->in_color_space = gray ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(cinfo);
  jpeg_set_quality(cinfo, quality, TRUE);
  cinfo->optimize_coding = TRUE;
  // The integer DCT gives the same bytes on every CPU (the float one need not).
  cinfo->dct_method = JDCT_ISLOW;
  if (!gray && quality >= 90) {
    cinfo->comp_info[0].h_samp_factor = 1;
    cinfo->comp_info[0].v_samp_factor = 1;
  }
}

// Row `y` as libjpeg takes it: the image's own row, or its colour samples copied to
// `scratch` when there is an alpha channel to drop. libjpeg only reads input rows.
JSAMPROW JpegInputRow(const Image& image, size_t y, uint8_t* scratch) {
  const uint8_t* row = image.pixels.data() + y * RowBytes(image);
  if (image.channels == 1 || image.channels == 3) return const_cast<JSAMPROW>(row);
  const int colour = image.channels - 1;
  for (size_t x = 0; x < static_cast<size_t>(image.width); ++x) {
    std::memcpy(scratch + x * colour, row + x * image.channels, static_cast<size_t>(colour));
  }
  return scratch;
}

bool CompressJpegGuarded(JpegWriter* writer, const Image& image, int quality, uint8_t* scratch) {
  if (setjmp(writer->trap.jump) != 0) return false;
  jpeg_compress_struct* cinfo = &writer->cinfo;
  jpeg_create_compress(cinfo);
  writer->destination.pub.init_destination = StartJpegOutput;
  writer->destination.pub.empty_output_buffer = GrowJpegOutput;
  writer->destination.pub.term_destination = FinishJpegOutput;
  cinfo->dest = &writer->destination.pub;
  ConfigureJpegEncoder(cinfo, image, quality);
  jpeg_start_compress(cinfo, TRUE);
  while (cinfo->next_scanline < cinfo->image_height) {
    JSAMPROW row = JpegInputRow(image, cinfo->next_scanline, scratch);
    jpeg_write_scanlines(cinfo, &row, 1);
  }
  jpeg_finish_compress(cinfo);
  return true;
}

// ----- PNG: error trap and memory I/O ----------------------------------------

struct PngTrap {
  std::jmp_buf jump;
  char message[kMessageBytes];
  StatusCode code;
};

// libpng's error_fn.
[[noreturn]] void OnPngError(png_structp png, png_const_charp message) {
  PngTrap* trap = static_cast<PngTrap*>(png_get_error_ptr(png));
  std::snprintf(trap->message, sizeof(trap->message), "%s", message);
  std::longjmp(trap->jump, 1);
}

void IgnorePngWarning(png_structp, png_const_charp) {}

// Ends a guarded step with an error of our own.
bool FailPngStep(PngTrap* trap, StatusCode code, const char* message) {
  std::snprintf(trap->message, sizeof(trap->message), "%s", message);
  trap->code = code;
  return false;
}

struct PngSource {
  const uint8_t* data;
  size_t size;
  size_t offset;
};

// libpng's read_data_fn.
void ReadPngBytes(png_structp png, png_bytep out, size_t count) {
  PngSource* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (count > source->size - source->offset) png_error(png, "the data ends early");
  std::memcpy(out, source->data + source->offset, count);
  source->offset += count;
}

// libpng's write_data_fn.
void WritePngBytes(png_structp png, png_bytep bytes, size_t count) {
  if (!AppendOutput(static_cast<OutputBuffer*>(png_get_io_ptr(png)), bytes, count)) {
    png_error(png, "out of memory");
  }
}

void FlushNothing(png_structp) {}

// ----- PNG: decoding ---------------------------------------------------------

uint32_t BigEndian32(const uint8_t* bytes) {
  return uint32_t{bytes[0]} << 24 | uint32_t{bytes[1]} << 16 | uint32_t{bytes[2]} << 8 | bytes[3];
}

// Channels after expansion, before a tRNS chunk adds alpha.
int PngChannelsBeforeTrns(int color_type) {
  switch (color_type) {
    case PNG_COLOR_TYPE_GRAY_ALPHA: return 2;
    case PNG_COLOR_TYPE_RGB:
    case PNG_COLOR_TYPE_PALETTE: return 3;
    case PNG_COLOR_TYPE_RGB_ALPHA: return 4;
    default: return 1;
  }
}

// Samples per pixel as stored (a palette index is one).
uint64_t PngStoredSamples(int color_type) {
  return color_type == PNG_COLOR_TYPE_PALETTE ? 1 : static_cast<uint64_t>(PngChannelsBeforeTrns(color_type));
}

// IHDR is the first chunk by rule (PNG spec 5.6), so a size the decoder would refuse,
// or one the file is too short to hold, is refused from it alone, before libpng
// reads on through the chunks that follow.
Status CheckPngHeader(const uint8_t* data, size_t size) {
  if (size < 26 || std::memcmp(data + 12, "IHDR", 4) != 0) return Status::Ok();  // libpng says why
  const uint64_t width = BigEndian32(data + 16), height = BigEndian32(data + 20);
  const int bit_depth = data[24], color_type = data[25];
  EQMESH_RETURN_IF_ERROR(
      CheckImageSize("PNG", width, height, static_cast<uint64_t>(PngChannelsBeforeTrns(color_type))));
  // The filtered rows of a non-interlaced image; Adam7 only adds to them.
  const uint64_t row_bytes = (width * PngStoredSamples(color_type) * static_cast<uint64_t>(bit_depth) + 7) / 8;
  const uint64_t image_data_bytes = height * (1 + row_bytes);
  if (image_data_bytes > kMaxDeflateRatio * size) {
    return ParseError("corrupt PNG: a " + SizeText(width, height) + " image cannot fit in " +
                      std::to_string(size) + " bytes");
  }
  return Status::Ok();
}

struct PngReader {
  PngTrap trap;
  PngSource source;
  png_structp png;
  png_infop info;
};

struct PngReaderGuard {
  PngReader* reader;
  ~PngReaderGuard() {
    if (reader->png != nullptr) png_destroy_read_struct(&reader->png, &reader->info, nullptr);
  }
};

bool OpenPngGuarded(PngReader* reader) {
  if (setjmp(reader->trap.jump) != 0) return false;
  reader->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &reader->trap, OnPngError, IgnorePngWarning);
  if (reader->png == nullptr) return FailPngStep(&reader->trap, StatusCode::kInternal, "cannot create a reader");
  reader->info = png_create_info_struct(reader->png);
  if (reader->info == nullptr) return FailPngStep(&reader->trap, StatusCode::kInternal, "cannot create a reader");
  png_set_read_fn(reader->png, &reader->source, ReadPngBytes);
  png_read_info(reader->png, reader->info);
  return true;
}

int PngOutputChannels(const PngReader& reader) {
  const int color_type = png_get_color_type(reader.png, reader.info);
  const bool has_alpha = (color_type & PNG_COLOR_MASK_ALPHA) != 0;
  const bool has_trns = png_get_valid(reader.png, reader.info, PNG_INFO_tRNS) != 0;
  return PngChannelsBeforeTrns(color_type) + (has_trns && !has_alpha ? 1 : 0);
}

bool ReadPngPixelsGuarded(PngReader* reader, Image* image, png_bytepp rows) {
  if (setjmp(reader->trap.jump) != 0) return false;
  png_set_expand(reader->png);  // palette -> RGB, gray below 8 bits -> 8, tRNS -> alpha
  png_set_scale_16(reader->png);
  png_set_interlace_handling(reader->png);
  png_read_update_info(reader->png, reader->info);
  if (png_get_channels(reader->png, reader->info) != image->channels ||
      png_get_bit_depth(reader->png, reader->info) != 8 ||
      png_get_rowbytes(reader->png, reader->info) != RowBytes(*image)) {
    return FailPngStep(&reader->trap, StatusCode::kInternal, "output layout differs from the header's");
  }
  png_read_image(reader->png, rows);
  // No png_read_end: the pixels are complete, and chunks after the image data
  // (IEND included) only matter to a validator.
  return true;
}

std::vector<png_bytep> RowPointers(uint8_t* pixels, size_t row_bytes, int height) {
  std::vector<png_bytep> rows(static_cast<size_t>(height));
  for (size_t y = 0; y < rows.size(); ++y) rows[y] = pixels + y * row_bytes;
  return rows;
}

Status PngDecodeFailure(const PngTrap& trap) {
  if (trap.code == StatusCode::kInternal) return InternalError(std::string("PNG decoder: ") + trap.message);
  return ParseError(std::string("corrupt PNG: ") + trap.message);
}

StatusOr<Image> DecodePng(const uint8_t* data, size_t size) {
  EQMESH_RETURN_IF_ERROR(CheckPngHeader(data, size));
  PngReader reader{};
  reader.trap.code = StatusCode::kParseError;
  reader.source = PngSource{data, size, 0};
  PngReaderGuard guard{&reader};
  if (!OpenPngGuarded(&reader)) return PngDecodeFailure(reader.trap);
  const uint32_t width = png_get_image_width(reader.png, reader.info);
  const uint32_t height = png_get_image_height(reader.png, reader.info);
  const int channels = PngOutputChannels(reader);
  EQMESH_RETURN_IF_ERROR(CheckImageSize("PNG", width, height, static_cast<uint64_t>(channels)));
  Image image = AllocateImage(static_cast<int>(width), static_cast<int>(height), channels);
  std::vector<png_bytep> rows = RowPointers(image.pixels.data(), RowBytes(image), image.height);
  if (!ReadPngPixelsGuarded(&reader, &image, rows.data())) return PngDecodeFailure(reader.trap);
  return image;
}

// ----- PNG: encoding ---------------------------------------------------------

struct PngWriter {
  PngTrap trap;
  OutputBuffer out;
  png_structp png;
  png_infop info;
};

struct PngWriterGuard {
  PngWriter* writer;
  ~PngWriterGuard() {
    if (writer->png != nullptr) png_destroy_write_struct(&writer->png, &writer->info);
    std::free(writer->out.data);
  }
};

int PngColorType(int channels) {
  switch (channels) {
    case 1: return PNG_COLOR_TYPE_GRAY;
    case 2: return PNG_COLOR_TYPE_GRAY_ALPHA;
    case 3: return PNG_COLOR_TYPE_RGB;
    default: return PNG_COLOR_TYPE_RGB_ALPHA;
  }
}

bool WritePngGuarded(PngWriter* writer, const Image& image, png_bytepp rows) {
  if (setjmp(writer->trap.jump) != 0) return false;
  writer->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &writer->trap, OnPngError, IgnorePngWarning);
  if (writer->png == nullptr) return FailPngStep(&writer->trap, StatusCode::kInternal, "cannot create a writer");
  writer->info = png_create_info_struct(writer->png);
  if (writer->info == nullptr) return FailPngStep(&writer->trap, StatusCode::kInternal, "cannot create a writer");
  png_set_write_fn(writer->png, &writer->out, WritePngBytes, FlushNothing);
  png_set_compression_level(writer->png, kPngZlibLevel);
  png_set_filter(writer->png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
  png_set_IHDR(writer->png, writer->info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PngColorType(image.channels), PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  png_write_info(writer->png, writer->info);
  png_write_image(writer->png, rows);
  png_write_end(writer->png, nullptr);
  return true;
}

}  // namespace

StatusOr<ImageFormat> SniffImageFormat(const uint8_t* data, size_t size) {
  if (data == nullptr || size == 0) return ParseError("image is empty");
  if (IsPng(data, size)) return ImageFormat::kPng;
  if (IsJpeg(data, size)) return ImageFormat::kJpeg;
  return ParseError("image is neither PNG nor JPEG");
}

StatusOr<Image> DecodeImage(const uint8_t* data, size_t size) {
  EQMESH_ASSIGN_OR_RETURN(const ImageFormat format, SniffImageFormat(data, size));
  return format == ImageFormat::kJpeg ? DecodeJpeg(data, size) : DecodePng(data, size);
}

int EstimateJpegQuality(const uint8_t* data, size_t size) {
  if (data == nullptr || !IsJpeg(data, size)) return -1;
  JpegReader reader{};
  InstallJpegTrap(&reader.trap, &reader.cinfo.err);
  JpegReaderGuard guard{&reader};
  if (!OpenJpegGuarded(&reader, data, size) || reader.cinfo.num_components < 1) return -1;
  const int table_index = reader.cinfo.comp_info[0].quant_tbl_no;
  if (table_index < 0 || table_index >= NUM_QUANT_TBLS) return -1;
  const JQUANT_TBL* table = reader.cinfo.quant_tbl_ptrs[table_index];
  return table == nullptr ? -1 : ClosestIjgQuality(table->quantval);
}

StatusOr<std::vector<uint8_t>> EncodeJpeg(const Image& image, int quality) {
  EQMESH_RETURN_IF_ERROR(CheckImageForEncoding(image));
  if (quality < 1 || quality > 100) {
    return InvalidArgument("JPEG quality " + std::to_string(quality) + " is outside 1..100");
  }
  JpegWriter writer{};
  InstallJpegTrap(&writer.trap, &writer.cinfo.err);
  JpegWriterGuard guard{&writer};
  std::vector<uint8_t> scratch(RowBytes(image));
  if (!CompressJpegGuarded(&writer, image, quality, scratch.data())) {
    return InternalError(std::string("JPEG encoder: ") + writer.trap.message);
  }
  return CopyOutput(writer.destination.out);
}

StatusOr<std::vector<uint8_t>> EncodePng(const Image& image) {
  EQMESH_RETURN_IF_ERROR(CheckImageForEncoding(image));
  PngWriter writer{};
  PngWriterGuard guard{&writer};
  // libpng only reads the rows it is given to write.
  std::vector<png_bytep> rows =
      RowPointers(const_cast<uint8_t*>(image.pixels.data()), RowBytes(image), image.height);
  if (!WritePngGuarded(&writer, image, rows.data())) {
    return InternalError(std::string("PNG encoder: ") + writer.trap.message);
  }
  return CopyOutput(writer.out);
}

}  // namespace eqmesh::texture
