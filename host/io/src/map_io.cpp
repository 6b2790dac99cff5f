#include "intgrid/io/map_io.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
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
  double resolution = 0.0;
  double origin_x = 0.0;
  double origin_y = 0.0;
  bool negate = false;
  double occupied_thresh = 0.0;
  double free_thresh = 0.0;
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
  if (image.empty()) yaml.fail(node, "image", "must name the PGM file");
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

void check_mode(const MapYaml& yaml) {
  const YAML::Node mode = yaml.optional("mode");
  if (!mode) return;
  const std::string name = yaml.text(mode, "mode");
  if (name != "trinary" && name != "scale") {
    yaml.fail(mode, "mode", "unsupported mode \"" + name + "\" (trinary or scale)");
  }
}

MapDescription read_map_description(const fs::path& file) {
  const MapYaml yaml(file);
  MapDescription map;
  map.image = read_image_path(yaml);

  map.resolution = yaml.number("resolution");
  if (!(map.resolution > 0.0)) {
    yaml.fail(yaml.required("resolution"), "resolution", "must be positive (metres per cell)");
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
  check_mode(yaml);
  return map;
}

std::string map_yaml_text(const std::string& image_name, const RosMap& map) {
  const core::GridGeometry& geometry = map.grid.geometry;
  YAML::Emitter out;
  // Numbers go in as shortest round-trip text: the emitter's own double output loses digits.
  out << YAML::BeginMap;
  out << YAML::Key << "image" << YAML::Value << image_name;
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

// ---- PGM ----

// An 8-bit grey image, row 0 at the top.
struct PgmImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;
};

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

std::string printable(std::string_view bytes) {
  std::string text(bytes);
  for (char& c : text) {
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  }
  return text;
}

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

PgmImage read_pgm(const fs::path& file) {
  const std::string data = read_input_file(file);
  PgmTokens tokens(file, data);
  const std::string_view magic = tokens.next().value_or("");
  if (magic != "P5" && magic != "P2") {
    tokens.fail("magic", "expected P5 (binary PGM) or P2 (ASCII PGM), found \"" +
                             printable(magic.substr(0, 8)) + "\"");
  }
  PgmImage image;
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
  image.pixels = magic == "P5"
                     ? read_binary_pixels(file, data, tokens.offset(), size_line, expected)
                     : read_ascii_pixels(file, tokens, size_line, expected);
  return image;
}

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

double pixel_to_probability(std::uint8_t pixel, bool negate) {
  const double level = pixel / 255.0;
  return negate ? level : 1.0 - level;
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
  const PgmImage image = read_pgm(description.image);
  const core::GridGeometry geometry{image.width, image.height, description.resolution,
                                    description.origin_x, description.origin_y};
  RosMap map;
  map.grid = core::ProbabilityGrid(geometry, 0.0);
  map.occupied_thresh = description.occupied_thresh;
  map.free_thresh = description.free_thresh;
  map.negate = description.negate;
  // PGM row 0 is the top of the map, grid row 0 the bottom.
  for (int row = 0; row < image.height; ++row) {
    const std::size_t row_start = static_cast<std::size_t>(row) * image.width;
    for (int ix = 0; ix < image.width; ++ix) {
      map.grid.at(ix, image.height - 1 - row) =
          pixel_to_probability(image.pixels[row_start + ix], map.negate);
    }
  }
  return map;
}

void write_ros_map(const fs::path& yaml, const RosMap& map) {
  check_writable(yaml, map);
  fs::path image = yaml;
  image.replace_extension(".pgm");
  write_file_atomically(image, pgm_bytes(map.grid, map.negate));
  write_file_atomically(yaml, map_yaml_text(image.filename().string(), map));
}

}  // namespace intgrid::io
