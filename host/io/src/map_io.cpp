#include "intgrid/io/map_io.hpp"

#include <png.h>
#include <yaml-cpp/yaml.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::io {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxPixelValue = 255;
constexpr long long kMaxPixels = 1LL << 31;

// How pixels become P(occupied); see read_ros_map in the header.
enum class MapMode {
  linear,  // no mode key: P itself, thresholds left to the user of the map
  trinary,
  scale,
  raw,
};

// ---- YAML ----

std::size_t line_of(const YAML::Mark& mark) {
  return mark.is_null() ? 0 : static_cast<std::size_t>(mark.line) + 1;
}

// The map's YAML document; every accessor reports problems at the line of the offending value.
class MapYaml {
 public:
  explicit MapYaml(fs::path file) : file_(std::move(file)) {
    const std::string text = read_input_file(file_);
    try {
      root_ = YAML::Load(text);
    } catch (const YAML::Exception& error) {
      throw InputError(file_, line_of(error.mark), "yaml", error.msg);
    }
    if (!root_.IsMap()) throw InputError(file_, 1, "yaml", "expected a mapping of keys to values");
  }

  const fs::path& file() const { return file_; }

  [[noreturn]] void fail(const YAML::Node& node, const std::string& field,
                         const std::string& message) const {
    throw InputError(file_, line_of(node.Mark()), field, message);
  }

  // Absent keys have no line to point at, hence line 0.
  YAML::Node required(const std::string& key) const {
    YAML::Node node = root_[key];
    if (!node) throw InputError(file_, 0, key, "missing key");
    return node;
  }

  YAML::Node optional(const std::string& key) const { return root_[key]; }

  std::string text(const YAML::Node& node, const std::string& field) const {
    if (!node.IsScalar()) fail(node, field, "expected a single value");
    return node.Scalar();
  }

  double number(const YAML::Node& node, const std::string& field) const {
    const double value =
        parse_number<double>(text(node, field), file_, line_of(node.Mark()), {field});
    if (!std::isfinite(value)) fail(node, field, "must be a finite number");
    return value;
  }

  double number(const std::string& key) const { return number(required(key), key); }

 private:
  fs::path file_;
  YAML::Node root_;
};

struct MapDescription {
  fs::path image;
  std::optional<std::uint32_t> image_crc32;  // the image's CRC-32, as intgrid writes it
  int image_crc32_line = 0;
  double resolution = 0.0;
  double origin_x = 0.0;
  double origin_y = 0.0;
  bool negate = false;
  double occupied_thresh = 0.0;
  double free_thresh = 0.0;
  MapMode mode = MapMode::linear;
};

// The field at fault and why, or nullopt if the thresholds are usable.
std::optional<std::pair<std::string, std::string>> threshold_problem(double occupied, double free) {
  const auto outside_unit_range = [](double p) { return !(p >= 0.0 && p <= 1.0); };
  if (outside_unit_range(occupied)) return {{"occupied_thresh", "must lie in [0, 1]"}};
  if (outside_unit_range(free)) return {{"free_thresh", "must lie in [0, 1]"}};
  if (free >= occupied) {
    return {{"free_thresh", "must be below occupied_thresh (" + format_number(free) +
                                " >= " + format_number(occupied) + ")"}};
  }
  return std::nullopt;
}

fs::path read_image_path(const MapYaml& yaml) {
  const YAML::Node node = yaml.required("image");
  const fs::path image = yaml.text(node, "image");
  if (image.empty()) yaml.fail(node, "image", "must name the image file (PGM or PNG)");
  // A file name with a control character (a NUL would cut every message naming the file short)
  // is no file a map was written with.
  const std::string name = image.string();
  if (std::any_of(name.begin(), name.end(),
                  [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; }))
    yaml.fail(node, "image", "holds a control character: " + quote_input(name));
  return image.is_absolute() ? image : yaml.file().parent_path() / image;
}

void read_origin(const MapYaml& yaml, MapDescription& map) {
  const YAML::Node origin = yaml.required("origin");
  if (!origin.IsSequence() || origin.size() != 3) {
    yaml.fail(origin, "origin", "must be [x, y, yaw]");
  }
  map.origin_x = yaml.number(origin[0], "origin");
  map.origin_y = yaml.number(origin[1], "origin");
  if (yaml.number(origin[2], "origin") != 0.0) {
    yaml.fail(origin[2], "origin", "rotated maps are not supported (yaw must be 0)");
  }
}

// As map_server, the names are case-sensitive.
MapMode read_mode(const MapYaml& yaml) {
  const YAML::Node mode = yaml.optional("mode");
  if (!mode) return MapMode::linear;
  const std::string name = yaml.text(mode, "mode");
  if (name == "trinary") return MapMode::trinary;
  if (name == "scale") return MapMode::scale;
  if (name == "raw") return MapMode::raw;
  yaml.fail(mode, "mode", "unknown mode " + quote_input(name) + " (trinary, scale or raw)");
}

// `image_crc32: 1a2b3c4d`, which intgrid writes beside `image` (map_server reads no such key):
// the CRC-32 of the image's bytes, so that an image that does not belong to the YAML (a run
// killed between writing the two, or a file replaced since) is refused instead of read as a
// wrong map.
void read_image_crc32(const MapYaml& yaml, MapDescription& map) {
  const YAML::Node node = yaml.optional("image_crc32");
  if (!node) return;
  const std::string text = yaml.text(node, "image_crc32");
  std::uint32_t crc = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), crc, 16);
  if (text.size() != 8 || error != std::errc() || end != text.data() + text.size())
    yaml.fail(node, "image_crc32", "must be 8 hexadecimal digits, got " + quote_input(text));
  map.image_crc32 = crc;
  map.image_crc32_line = static_cast<int>(node.Mark().line) + 1;
}

std::uint32_t crc32_of(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t n = std::min<std::size_t>(bytes.size() - at, 1u << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), static_cast<uInt>(n));
    at += n;
  }
  return static_cast<std::uint32_t>(crc);
}

std::string crc32_text(std::uint32_t crc) {
  char text[9];
  std::snprintf(text, sizeof text, "%08x", crc);
  return text;
}

MapDescription read_map_description(const fs::path& file) {
  const MapYaml yaml(file);
  MapDescription map;
  map.image = read_image_path(yaml);

  map.resolution = yaml.number("resolution");
  // A tenth of a millimetre to a hundred metres a cell: past either end no robot's map, and
  // grid coordinates (metres / resolution) would lose their meaning.
  if (!(map.resolution >= 1e-4 && map.resolution <= 100.0)) {
    yaml.fail(yaml.required("resolution"), "resolution",
              "must lie in [0.0001, 100] (metres per cell)");
  }
  read_origin(yaml, map);

  const double negate = yaml.number("negate");
  if (negate != 0.0 && negate != 1.0) {
    yaml.fail(yaml.required("negate"), "negate", "must be 0 or 1");
  }
  map.negate = negate == 1.0;

  map.occupied_thresh = yaml.number("occupied_thresh");
  map.free_thresh = yaml.number("free_thresh");
  if (const auto problem = threshold_problem(map.occupied_thresh, map.free_thresh)) {
    yaml.fail(yaml.required(problem->first), problem->first, problem->second);
  }
  map.mode = read_mode(yaml);
  read_image_crc32(yaml, map);
  return map;
}

std::string map_yaml_text(const std::string& image_name, std::uint32_t image_crc32,
                          const RosMap& map) {
  const core::GridGeometry& geometry = map.grid.geometry;
  YAML::Emitter out;
  // Numbers go in as shortest round-trip text: the emitter's own double output loses digits.
  out << YAML::BeginMap;
  out << YAML::Key << "image" << YAML::Value << image_name;
  out << YAML::Key << "image_crc32" << YAML::Value << crc32_text(image_crc32);
  out << YAML::Key << "resolution" << YAML::Value << format_number(geometry.resolution);
  out << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << format_number(geometry.origin_x) << format_number(geometry.origin_y) << "0"
      << YAML::EndSeq;
  out << YAML::Key << "negate" << YAML::Value << (map.negate ? "1" : "0");
  out << YAML::Key << "occupied_thresh" << YAML::Value << format_number(map.occupied_thresh);
  out << YAML::Key << "free_thresh" << YAML::Value << format_number(map.free_thresh);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

// ---- Images ----

// A decoded map image, row 0 at the top. Each pixel is `channels` samples of 8 or 16 bits (16-bit
// ones big-endian, as PNG stores them): grey or red, green, blue, then alpha if there is one.
struct MapImage {
  int width = 0;
  int height = 0;
  int channels = 1;  // 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
  int bit_depth = 8;
  std::size_t row_bytes = 0;
  std::vector<std::uint8_t> samples;
};

// ---- PGM ----

bool is_pgm_space(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

// Reads a PGM header (and the values of an ASCII one) token by token, passing over blanks and
// '#' comments and counting lines for the error messages.
class PgmTokens {
 public:
  PgmTokens(const fs::path& file, std::string_view data) : file_(file), data_(data) {}

  std::size_t line() const { return line_; }
  std::size_t offset() const { return offset_; }

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw InputError(file_, line_, field, message);
  }

  std::optional<std::string_view> next() {
    skip_blanks_and_comments();
    if (offset_ == data_.size()) return std::nullopt;
    const std::size_t begin = offset_;
    while (offset_ < data_.size() && !is_pgm_space(data_[offset_]) && data_[offset_] != '#') {
      ++offset_;
    }
    return data_.substr(begin, offset_ - begin);
  }

  long long next_integer(const std::string& field) {
    const std::optional<std::string_view> token = next();
    if (!token) fail(field, "missing: the file ends in the header");
    return parse_number<long long>(*token, file_, line_, {field});
  }

 private:
  void skip_blanks_and_comments() {
    while (offset_ < data_.size()) {
      const char c = data_[offset_];
      if (c == '#') {
        while (offset_ < data_.size() && data_[offset_] != '\n') ++offset_;
      } else if (is_pgm_space(c)) {
        if (c == '\n') ++line_;
        ++offset_;
      } else {
        return;
      }
    }
  }

  const fs::path& file_;
  std::string_view data_;
  std::size_t offset_ = 0;
  std::size_t line_ = 1;
};

int read_dimension(PgmTokens& tokens, const std::string& field) {
  const long long value = tokens.next_integer(field);
  if (value <= 0 || value > kMaxPixels) {
    tokens.fail(field,
                "must be a positive integer no larger than 2^31, got " + std::to_string(value));
  }
  return static_cast<int>(value);
}

// Reported at the header line that declared the size the data disagrees with.
InputError pixel_count_mismatch(const fs::path& file, std::size_t size_line, std::size_t expected,
                                std::size_t actual, const char* unit) {
  return InputError(file, size_line, "pixels",
                    "the header promises width * height = " + std::to_string(expected) + " " +
                        unit + " of pixel data, found " + std::to_string(actual));
}

// P5: a single whitespace byte after maxval, then exactly width * height bytes. The size is
// checked before allocating, so a lying header cannot ask for gigabytes.
std::vector<std::uint8_t> read_binary_pixels(const fs::path& file, std::string_view data,
                                             std::size_t header_end, std::size_t size_line,
                                             std::size_t expected) {
  const std::string_view pixels = data.substr(std::min(header_end + 1, data.size()));
  if (pixels.size() != expected) {
    throw pixel_count_mismatch(file, size_line, expected, pixels.size(), "bytes");
  }
  return std::vector<std::uint8_t>(pixels.begin(), pixels.end());
}

// P2: exactly width * height decimal values, each at most maxval.
std::vector<std::uint8_t> read_ascii_pixels(const fs::path& file, PgmTokens& tokens,
                                            std::size_t size_line, std::size_t expected) {
  std::vector<std::uint8_t> pixels;
  std::size_t count = 0;
  while (const std::optional<std::string_view> token = tokens.next()) {
    ++count;
    if (count > expected) continue;  // only counted, for the error below
    const long long value = parse_number<long long>(*token, file, tokens.line(), {"pixels"});
    if (value < 0 || value > kMaxPixelValue) {
      tokens.fail("pixels", "value " + std::to_string(value) + " is outside 0..255");
    }
    pixels.push_back(static_cast<std::uint8_t>(value));
  }
  if (count != expected) throw pixel_count_mismatch(file, size_line, expected, count, "values");
  return pixels;
}

MapImage read_pgm(const fs::path& file, std::string_view data) {
  PgmTokens tokens(file, data);
  const std::string_view magic = tokens.next().value_or("");
  if (magic != "P5" && magic != "P2") {
    tokens.fail("magic", "expected P5 (binary PGM), P2 (ASCII PGM) or a PNG signature, found " +
                             quote_input(magic, 8));
  }
  MapImage image;
  image.width = read_dimension(tokens, "width");
  image.height = read_dimension(tokens, "height");
  const std::size_t size_line = tokens.line();
  const long long pixel_count = static_cast<long long>(image.width) * image.height;
  if (pixel_count > kMaxPixels) {
    tokens.fail("height", "width * height = " + std::to_string(pixel_count) + " exceeds 2^31");
  }
  const long long maxval = tokens.next_integer("maxval");
  if (maxval != kMaxPixelValue) {
    tokens.fail("maxval",
                "only 8-bit PGMs (maxval 255) are supported, got " + std::to_string(maxval));
  }
  const auto expected = static_cast<std::size_t>(pixel_count);
  image.row_bytes = static_cast<std::size_t>(image.width);
  image.samples = magic == "P5"
                      ? read_binary_pixels(file, data, tokens.offset(), size_line, expected)
                      : read_ascii_pixels(file, tokens, size_line, expected);
  return image;
}

// ---- PNG ----

bool has_png_signature(std::string_view data) {
  constexpr std::size_t kSignatureBytes = 8;
  return data.size() >= kSignatureBytes &&
         png_sig_cmp(reinterpret_cast<png_const_bytep>(data.data()), 0, kSignatureBytes) == 0;
}

// libpng reports errors by longjmp to the setjmp in decode_png_header or decode_png_pixels.
// Everything a jump can cross is plain data: the libpng frames, the callbacks below and those
// two functions, none of which holds an object with a destructor.
struct PngReadState {
  const png_byte* data = nullptr;
  std::size_t size = 0;
  std::size_t offset = 0;
  bool truncated = false;
  char message[256] = {};
};

void png_read_from_memory(png_structp png, png_bytep out, png_size_t length) {
  auto* state = static_cast<PngReadState*>(png_get_io_ptr(png));
  if (length > state->size - state->offset) {
    state->truncated = true;
    png_error(png, "the file ends early");
  }
  std::memcpy(out, state->data + state->offset, length);
  state->offset += length;
}

[[noreturn]] void png_on_error(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngReadState*>(png_get_error_ptr(png));
  std::strncpy(state->message, message != nullptr ? message : "unknown error",
               sizeof state->message - 1);
  png_longjmp(png, 1);
}

// Warnings (an odd colour profile, a damaged ancillary chunk that libpng skips) leave the
// pixels intact.
void png_on_warning(png_structp, png_const_charp) {}

// Owns libpng's read and info structures.
class PngReader {
 public:
  explicit PngReader(PngReadState& state)
      : png_(png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, png_on_error, png_on_warning)) {
    if (png_ != nullptr) info_ = png_create_info_struct(png_);
    if (info_ == nullptr) {
      png_destroy_read_struct(&png_, nullptr, nullptr);
      throw std::bad_alloc();
    }
    png_set_read_fn(png_, &state, png_read_from_memory);
  }
  ~PngReader() { png_destroy_read_struct(&png_, &info_, nullptr); }
  PngReader(const PngReader&) = delete;
  PngReader& operator=(const PngReader&) = delete;

  png_structp png() const { return png_; }
  png_infop info() const { return info_; }

 private:
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
};

struct PngLayout {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int channels = 0;
  int bit_depth = 0;
  std::size_t row_bytes = 0;
};

// Reads the chunks before the image data and sets up the transforms that leave 8- or 16-bit
// grey, grey + alpha, RGB or RGBA: palettes become RGB, 1/2/4-bit grey 8-bit, a tRNS chunk an
// alpha channel. No gamma or colour-profile conversion: the samples are read as stored, as
// map_server reads them. False, with the message in the read state, if libpng fails.
bool decode_png_header(png_structp png, png_infop info, PngLayout& layout) {
  if (setjmp(png_jmpbuf(png))) return false;
  // The size is bounded below, as for PGMs; libpng's own default limit is 10^6 a side.
  png_set_user_limits(png, PNG_UINT_31_MAX, PNG_UINT_31_MAX);
  png_read_info(png, info);
  const png_byte color_type = png_get_color_type(png, info);
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color_type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) {
    png_set_expand_gray_1_2_4_to_8(png);
  }
  if (png_get_valid(png, info, PNG_INFO_tRNS) != 0) png_set_tRNS_to_alpha(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  layout.width = png_get_image_width(png, info);
  layout.height = png_get_image_height(png, info);
  layout.channels = png_get_channels(png, info);
  layout.bit_depth = png_get_bit_depth(png, info);
  layout.row_bytes = png_get_rowbytes(png, info);
  return true;
}

// Decodes the image into rows, then reads on to the end chunk, so that a file cut short after
// its image data is an error too. False, with the message in the read state, if libpng fails.
bool decode_png_pixels(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

InputError png_decode_error(const fs::path& file, const PngReadState& state,
                            const std::string& field) {
  if (state.truncated) {
    return InputError(file, 0, field,
                      "truncated PNG: the file ends after " + std::to_string(state.size) +
                          " bytes, inside the " + (field == "header" ? "header" : "image data"));
  }
  return InputError(file, 0, field, std::string("corrupt PNG: ") + state.message);
}

MapImage read_png(const fs::path& file, std::string_view data) {
  PngReadState state;
  state.data = reinterpret_cast<const png_byte*>(data.data());
  state.size = data.size();
  const PngReader reader(state);
  PngLayout layout;
  if (!decode_png_header(reader.png(), reader.info(), layout)) {
    throw png_decode_error(file, state, "header");
  }
  // libpng has checked that both sizes are positive and below 2^31.
  const long long pixel_count = static_cast<long long>(layout.width) * layout.height;
  if (pixel_count > kMaxPixels) {
    throw InputError(file, 0, "height",
                     "width * height = " + std::to_string(pixel_count) + " exceeds 2^31");
  }
  MapImage image;
  image.width = static_cast<int>(layout.width);
  image.height = static_cast<int>(layout.height);
  image.channels = layout.channels;
  image.bit_depth = layout.bit_depth;
  image.row_bytes = layout.row_bytes;
  image.samples.resize(image.row_bytes * layout.height);
  std::vector<png_bytep> rows(layout.height);
  for (std::size_t row = 0; row < rows.size(); ++row) {
    rows[row] = image.samples.data() + row * image.row_bytes;
  }
  if (!decode_png_pixels(reader.png(), rows.data())) {
    throw png_decode_error(file, state, "pixels");
  }
  return image;
}

// A PNG by its signature, whatever the file's name; anything else must be a PGM.
MapImage read_map_image(const fs::path& file, const fs::path& yaml_file,
                        const MapDescription& map) {
  const std::string data = read_input_file(file);
  if (map.image_crc32) {
    const std::uint32_t crc = crc32_of(data);
    if (crc != *map.image_crc32)
      throw InputError(yaml_file, map.image_crc32_line, "image_crc32",
                       crc32_text(*map.image_crc32) + " is not the CRC-32 of " + file.string() +
                           " (" + crc32_text(crc) +
                           "): the image is not the one written with this YAML (a run stopped "
                           "between writing the two, or the image replaced since)");
  }
  return has_png_signature(data) ? read_png(file, data) : read_pgm(file, data);
}

// ---- Pixels to P(occupied) ----

// Turns one pixel into the P(occupied) of its cell, following the map's mode.
class PixelReading {
 public:
  PixelReading(const MapDescription& map, const MapImage& image)
      : map_(map),
        sample_bytes_(image.bit_depth == 16 ? 2 : 1),
        colour_channels_(image.channels >= 3 ? 3 : 1),
        has_alpha_(image.channels == 2 || image.channels == 4),
        max_value_(image.bit_depth == 16 ? 65535.0 : 255.0) {}

  std::size_t pixel_bytes() const {
    return static_cast<std::size_t>((colour_channels_ + (has_alpha_ ? 1 : 0)) * sample_bytes_);
  }

  double operator()(const std::uint8_t* pixel) const {
    double sum = 0.0;
    for (int channel = 0; channel < colour_channels_; ++channel) sum += sample(pixel, channel);
    const double mean = sum / colour_channels_;
    const bool opaque = !has_alpha_ || sample(pixel, colour_channels_) == max_value_;
    return probability(mean, opaque);
  }

 private:
  double sample(const std::uint8_t* pixel, int channel) const {
    const std::uint8_t* p = pixel + channel * sample_bytes_;
    return sample_bytes_ == 2 ? (p[0] << 8) | p[1] : p[0];
  }

  double probability(double mean, bool opaque) const {
    constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
    switch (map_.mode) {
      case MapMode::linear: {
        if (!opaque) return kUnknown;
        // The arithmetic of the PGM-only reader, bit for bit.
        const double level = mean / max_value_;
        return map_.negate ? level : 1.0 - level;
      }
      case MapMode::raw: {
        // The value as an 8-bit sample, whatever negate and alpha say, as map_server.
        const double percent = std::round(mean * 255.0 / max_value_);
        return percent <= 100.0 ? percent / 100.0 : kUnknown;
      }
      case MapMode::trinary:
      case MapMode::scale: {
        if (!opaque) return kUnknown;
        // map_server's p = (255 - v) / 255, or v / 255 if negate.
        const double p = map_.negate ? mean / max_value_ : (max_value_ - mean) / max_value_;
        if (p > map_.occupied_thresh) return 1.0;
        if (p < map_.free_thresh) return 0.0;
        return map_.mode == MapMode::scale ? p : kUnknown;
      }
    }
    return kUnknown;
  }

  const MapDescription& map_;
  int sample_bytes_;
  int colour_channels_;
  bool has_alpha_;
  double max_value_;
};

std::string pgm_bytes(const core::ProbabilityGrid& grid, bool negate) {
  const core::GridGeometry& geometry = grid.geometry;
  std::string out =
      "P5\n" + std::to_string(geometry.width) + " " + std::to_string(geometry.height) + "\n255\n";
  out.reserve(out.size() + geometry.size());
  for (int iy = geometry.height - 1; iy >= 0; --iy) {
    for (int ix = 0; ix < geometry.width; ++ix) {
      out += static_cast<char>(probability_to_pixel(grid.at(ix, iy), negate));
    }
  }
  return out;
}

void check_writable(const fs::path& yaml, const RosMap& map) {
  const core::GridGeometry& geometry = map.grid.geometry;
  core::check_geometry(geometry);
  if (map.grid.cells.size() != geometry.size()) {
    throw std::invalid_argument("map grid holds " + std::to_string(map.grid.cells.size()) +
                                " cells but its geometry has " + std::to_string(geometry.size()));
  }
  if (geometry.size() > static_cast<std::size_t>(kMaxPixels)) {
    throw std::invalid_argument("map grid has more than 2^31 cells, too many for a PGM map");
  }
  if (const auto problem = threshold_problem(map.occupied_thresh, map.free_thresh)) {
    throw std::invalid_argument(problem->first + ": " + problem->second);
  }
  if (yaml.extension() == ".pgm") {
    throw std::invalid_argument("map YAML path " + yaml.string() +
                                " ends in .pgm, the name of the image written beside it");
  }
}

}  // namespace

std::uint8_t probability_to_pixel(double p, bool negate) {
  const double occupied = std::isnan(p) ? 0.5 : std::clamp(p, 0.0, 1.0);
  const double level = negate ? occupied : 1.0 - occupied;
  return static_cast<std::uint8_t>(std::lround(255.0 * level));
}

RosMap read_ros_map(const fs::path& yaml) {
  const MapDescription description = read_map_description(yaml);
  const MapImage image = read_map_image(description.image, yaml, description);
  const core::GridGeometry geometry{image.width, image.height, description.resolution,
                                    description.origin_x, description.origin_y};
  RosMap map;
  map.grid = core::ProbabilityGrid(geometry, 0.0);
  map.occupied_thresh = description.occupied_thresh;
  map.free_thresh = description.free_thresh;
  map.negate = description.negate;
  const PixelReading reading(description, image);
  const std::size_t pixel_bytes = reading.pixel_bytes();
  // Image row 0 is the top of the map, grid row 0 the bottom.
  for (int row = 0; row < image.height; ++row) {
    const std::uint8_t* pixel =
        image.samples.data() + static_cast<std::size_t>(row) * image.row_bytes;
    for (int ix = 0; ix < image.width; ++ix, pixel += pixel_bytes) {
      map.grid.at(ix, image.height - 1 - row) = reading(pixel);
    }
  }
  return map;
}

void write_ros_map(const fs::path& yaml, const RosMap& map) {
  check_writable(yaml, map);
  fs::path image = yaml;
  image.replace_extension(".pgm");
  // The image first, then the YAML naming it with its CRC-32: a run stopped between the two
  // leaves the old YAML beside a new image, which read_ros_map then refuses.
  const std::string pgm = pgm_bytes(map.grid, map.negate);
  write_file_atomically(image, pgm);
  write_file_atomically(yaml, map_yaml_text(image.filename().string(), crc32_of(pgm), map));
}

}  // namespace intgrid::io
