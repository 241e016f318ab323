// The PLY reader: a header parser, a value reader for the three encodings, and the element loop.
#include "ply_reader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "file_checks.h"
#include "float_conversion.h"
#include "sao/scenes/mesh_file.h"

namespace sao::scenes::detail {

namespace {

struct Type {
  std::string_view name, alias;
  int size;
  bool integer;
  double min, max;
};

constexpr Type kTypes[] = {
    {"char", "int8", 1, true, -128.0, 127.0},
    {"uchar", "uint8", 1, true, 0.0, 255.0},
    {"short", "int16", 2, true, -32768.0, 32767.0},
    {"ushort", "uint16", 2, true, 0.0, 65535.0},
    {"int", "int32", 4, true, -2147483648.0, 2147483647.0},
    {"uint", "uint32", 4, true, 0.0, 4294967295.0},
    {"float", "float32", 4, false, -INFINITY, INFINITY},
    {"double", "float64", 8, false, -INFINITY, INFINITY},
};

const Type* findType(std::string_view name) {
  for (const Type& t : kTypes)
    if (name == t.name || name == t.alias) return &t;
  return nullptr;
}

struct Property {
  std::string name;
  const Type* type = nullptr;
  const Type* countType = nullptr;  // set for a list
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Format { Ascii, LittleEndian, BigEndian };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t dataStart = 0;
};

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The text of a header word for a message: printable, at most 40 characters.
std::string shown(std::string_view word) {
  std::string s = "'";
  for (char c : word.substr(0, 40)) s += (c >= 32 && c < 127) ? c : '?';
  return s + (word.size() > 40 ? "...'" : "'");
}

class Parser {
 public:
  Parser(std::string_view bytes, std::string_view name) : bytes_(bytes), name_(name) {}

  Status error(const std::string& problem) const {
    std::string where;
    if (element_) where = "element '" + element_->name + "'";
    if (element_ && property_) where += " row " + std::to_string(row_) + ", property '" + property_->name + "'";
    return fileError(StatusCode::IoError, name_, "PLY: " + (where.empty() ? "" : where + ": ") + problem);
  }

  // Where the values being read belong, for messages ("element 'vertex' row 3, property 'x': ").
  void at(const Element* element, std::uint64_t row = 0, const Property* property = nullptr) {
    element_ = element;
    row_ = row;
    property_ = property;
  }

  Status header(Header& h) {
    std::string_view line;
    // Refused, not skipped: a PLY file is binary-capable and its magic is the bytes "ply"; an
    // editor that added the mark may also have changed the line ends or the encoding.
    if (bytes_.starts_with(kUtf8ByteOrderMark))
      return error("starts with a UTF-8 byte-order mark before 'ply'; save it without the mark (as plain ASCII)");
    if (!nextLine(line) || line != "ply") return error("not a PLY file (the first line is not 'ply')");
    bool haveFormat = false;
    while (true) {
      if (!nextLine(line)) return error("the header has no end_header line");
      const auto w = words(line);
      auto lineError = [&](const std::string& problem) { return error("header line " + std::to_string(line_) + ": " + problem); };
      if (w.empty()) continue;
      if (w[0] == "end_header") break;
      if (w[0] == "comment" || w[0] == "obj_info") continue;
      if (w[0] == "format") {
        if (haveFormat) return lineError("a second format line");
        if (w.size() != 3 || w[2] != "1.0") return lineError("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
        if (w[1] == "ascii") h.format = Format::Ascii;
        else if (w[1] == "binary_little_endian") h.format = Format::LittleEndian;
        else if (w[1] == "binary_big_endian") h.format = Format::BigEndian;
        else return lineError("unknown format " + shown(w[1]));
        haveFormat = true;
      } else if (w[0] == "element") {
        std::uint64_t count = 0;
        if (w.size() != 3) return lineError("expected 'element NAME COUNT'");
        const auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), count);
        if (ec != std::errc() || p != w[2].data() + w[2].size()) return lineError("element count " + shown(w[2]) + " is not a number");
        h.elements.push_back({std::string(w[1]), count, {}});
      } else if (w[0] == "property") {
        if (h.elements.empty()) return lineError("a property before any element");
        Property prop;
        if (w.size() >= 2 && w[1] == "list") {
          if (w.size() != 5) return lineError("expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
          prop.countType = findType(w[2]);
          prop.type = findType(w[3]);
          if (!prop.countType || !prop.countType->integer) return lineError("list count type " + shown(w[2]) + " is not an integer type");
          if (!prop.type) return lineError("unknown type " + shown(w[3]));
          prop.name = w[4];
        } else {
          if (w.size() != 3) return lineError("expected 'property TYPE NAME'");
          prop.type = findType(w[1]);
          if (!prop.type) return lineError("unknown type " + shown(w[1]));
          prop.name = w[2];
        }
        h.elements.back().properties.push_back(std::move(prop));
      }
      // Other lines are ignored, as other readers do (Blender 2.47 wrote a bare "Created by ..." line).
    }
    if (!haveFormat) return error("the header has no format line");
    h.dataStart = pos_;
    return Status::success();
  }

  // The next value of type t (ascii: the next word; binary: the next t.size bytes).
  Status value(Format format, const Type& t, double& v) {
    if (format == Format::Ascii) {
      while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
      std::size_t end = pos_;
      while (end < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[end]))) ++end;
      if (end == pos_) return error("the data ends early (after " + std::to_string(values_) + " values)");
      const std::string_view word = bytes_.substr(pos_, end - pos_);
      pos_ = end;
      if (!parseNumber(word, v)) return error("value " + shown(word) + " is not a valid " + std::string(t.name));
    } else {
      if (bytes_.size() - pos_ < std::size_t(t.size))
        return error("the data ends early (after " + std::to_string(values_) + " values)");
      unsigned char b[8];
      std::memcpy(b, bytes_.data() + pos_, std::size_t(t.size));
      pos_ += std::size_t(t.size);
      if (format == Format::BigEndian) std::reverse(b, b + t.size);
      v = decode(t, b);
    }
    if (t.integer && !(v == std::floor(v) && v >= t.min && v <= t.max))
      return error("value " + number(v) + " is not a valid " + std::string(t.name));
    ++values_;
    return Status::success();
  }

  // Skips `rows` rows of fixed-size binary data.
  Status skip(std::uint64_t rows, std::uint64_t rowBytes) {
    if (rowBytes != 0 && rows > (bytes_.size() - pos_) / rowBytes) return error("the data ends early");
    pos_ += std::size_t(rows * rowBytes);
    return Status::success();
  }

  std::size_t remaining() const { return bytes_.size() - pos_; }
  void seek(std::size_t pos) { pos_ = pos; }

 private:
  bool nextLine(std::string_view& line) {
    if (pos_ >= bytes_.size()) return false;
    std::size_t end = bytes_.find('\n', pos_);
    if (end == std::string_view::npos) end = bytes_.size();
    line = bytes_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = std::min(end + 1, bytes_.size());
    ++line_;
    return true;
  }

  static double decode(const Type& t, const unsigned char* b) {
    switch (t.size) {
      case 1: return t.min < 0 ? double(std::int8_t(b[0])) : double(b[0]);
      case 2: {
        std::uint16_t u;
        std::memcpy(&u, b, 2);
        return t.min < 0 ? double(std::int16_t(u)) : double(u);
      }
      case 4: {
        std::uint32_t u;
        std::memcpy(&u, b, 4);
        if (!t.integer) {
          float f;
          std::memcpy(&f, &u, 4);
          return f;
        }
        return t.min < 0 ? double(std::int32_t(u)) : double(u);
      }
      default: {
        double d;
        std::memcpy(&d, b, 8);
        return d;
      }
    }
  }

  std::string_view bytes_, name_;
  const Element* element_ = nullptr;
  const Property* property_ = nullptr;
  std::uint64_t row_ = 0;
  std::size_t pos_ = 0;
  std::uint64_t values_ = 0;
  int line_ = 0;
};

int findProperty(const Element& e, std::string_view name, bool list) {
  for (std::size_t i = 0; i < e.properties.size(); ++i)
    if (e.properties[i].name == name && (e.properties[i].countType != nullptr) == list) return int(i);
  return -1;
}

}  // namespace

Status readPly(std::string_view bytes, std::string_view name, Mesh& out) {
  Parser parser(bytes, name);
  Header h;
  if (Status s = parser.header(h); !s) return s;

  const auto vertexElement = std::find_if(h.elements.begin(), h.elements.end(), [](const Element& e) { return e.name == "vertex"; });
  if (vertexElement == h.elements.end()) return parser.error("no vertex element");
  const std::uint64_t vertexCount = vertexElement->count;
  if (vertexCount > std::numeric_limits<std::uint32_t>::max())
    return parser.error("the header declares " + std::to_string(vertexCount) + " vertices, more than 2^32 - 1");
  const int px = findProperty(*vertexElement, "x", false), py = findProperty(*vertexElement, "y", false),
            pz = findProperty(*vertexElement, "z", false);
  if (px < 0 || py < 0 || pz < 0) return parser.error("the vertex element has no x, y and z properties");

  Mesh mesh;
  for (const Element& e : h.elements) {
    const bool isVertex = &e == &*vertexElement, isFace = e.name == "face";
    int indicesProperty = isFace ? findProperty(e, "vertex_indices", true) : -1;
    if (isFace && indicesProperty < 0) indicesProperty = findProperty(e, "vertex_index", true);
    const bool hasLists = std::any_of(e.properties.begin(), e.properties.end(), [](const Property& p) { return p.countType; });
    if (e.properties.empty()) continue;  // rows without properties take no bytes

    std::uint64_t rowBytes = 0;
    for (const Property& p : e.properties) rowBytes += std::uint64_t(p.type->size);
    if (h.format != Format::Ascii && !hasLists && !isVertex) {
      parser.at(&e);
      if (Status s = parser.skip(e.count, rowBytes); !s) return s;
      continue;
    }
    // Each row takes at least a byte a value (two in ascii): reserve no more than the data holds.
    const std::uint64_t fits = parser.remaining() / (h.format == Format::Ascii ? 2 * e.properties.size() : rowBytes);
    if (isVertex) mesh.positions.reserve(std::size_t(std::min(e.count, fits)));

    std::vector<std::uint32_t> polygon;
    for (std::uint64_t row = 0; row < e.count; ++row) {
      double xyz[3] = {0, 0, 0};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        parser.at(&e, row, &p);
        double v = 0;
        if (!p.countType) {
          if (Status s = parser.value(h.format, *p.type, v); !s) return s;
          if (isVertex && int(k) == px) xyz[0] = v;
          if (isVertex && int(k) == py) xyz[1] = v;
          if (isVertex && int(k) == pz) xyz[2] = v;
          continue;
        }
        double n = 0;
        if (Status s = parser.value(h.format, *p.countType, n); !s) return s;
        if (n < 0) return parser.error("the list count " + number(n) + " is negative");
        const bool wanted = int(k) == indicesProperty;
        polygon.clear();
        for (std::uint64_t i = 0; i < std::uint64_t(n); ++i) {
          if (Status s = parser.value(h.format, *p.type, v); !s) return s;
          if (!wanted) continue;
          if (!(v >= 0 && v < double(vertexCount) && v == std::floor(v)))
            return fileError(StatusCode::InvalidInput, name,
                             "PLY: face " + std::to_string(row) + " refers to vertex " + number(v) +
                                 ", but there are only " + std::to_string(vertexCount) + " vertices");
          polygon.push_back(std::uint32_t(v));
        }
        if (!wanted || polygon.size() < 3) continue;
        if (mesh.triangleCount() + polygon.size() - 2 > kMaxMeshTriangles)
          return fileError(StatusCode::InvalidInput, name,
                           "has more than the limit of " + std::to_string(kMaxMeshTriangles) + " triangles");
        for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
          mesh.indices.insert(mesh.indices.end(), {polygon[0], polygon[i], polygon[i + 1]});
      }
      if (isVertex) mesh.positions.emplace_back(toFloat(xyz[0]), toFloat(xyz[1]), toFloat(xyz[2]));
    }
  }
  out = std::move(mesh);
  return Status::success();
}

}  // namespace sao::scenes::detail
