// A small, strict JSON reader for the CLI's input files (feature vertices,
// per set member or of one mesh, and target directions): parses any JSON document into a tree, then the two
// readers below check the shapes they need. Every error names the file, the
// line and column, and what is wrong. Beyond RFC 8259 it accepts only the
// literals NaN, Infinity and -Infinity (Python's json.dump writes them), so
// a non-finite target is reported as such rather than as a syntax error.
#pragma once
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh.h"

namespace cmaps {

struct JsonValue {
  enum class Kind { Null, Boolean, Number, String, Array, Object };
  Kind kind = Kind::Null;
  bool boolean = false;
  double number = 0;
  std::string text;  // a string's value, or a number's source text
  std::vector<JsonValue> items;
  std::vector<std::pair<std::string, JsonValue>> members;  // in file order, keys unique
  int line = 1, column = 1;                                // where the value starts

  static const char* kind_name(Kind kind) {
    switch (kind) {
      case Kind::Null: return "null";
      case Kind::Boolean: return "a boolean";
      case Kind::Number: return "a number";
      case Kind::String: return "a string";
      case Kind::Array: return "an array";
      case Kind::Object: return "an object";
    }
    return "a value";
  }
};

class JsonParser {
 public:
  // `source` names the text in error messages (usually the file name).
  JsonParser(std::string text, std::string source) : text_(std::move(text)), source_(std::move(source)) {}

  JsonValue parse() {
    skip_space();
    if (at_end()) fail("file is empty (expected a JSON object)");
    JsonValue value = parse_value(0);
    skip_space();
    if (!at_end()) fail("unexpected '" + std::string(1, text_[pos_]) + "' after the JSON value");
    return value;
  }

  static JsonValue parse_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot read '" + path + "': no such file or not readable");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) throw IoError("cannot read '" + path + "'");
    return JsonParser(buffer.str(), path).parse();
  }

 private:
  static constexpr int kMaxDepth = 64;

  [[noreturn]] void fail(const std::string& what) const {
    throw InvalidInput(source_ + ":" + std::to_string(line_) + ":" + std::to_string(column_) + ": invalid JSON: " +
                       what);
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  char next() {
    const char c = text_[pos_++];
    if (c == '\n') ++line_, column_ = 1;
    else ++column_;
    return c;
  }
  void skip_space() {
    while (!at_end() && (peek() == ' ' || peek() == '\t' || peek() == '\n' || peek() == '\r')) next();
  }
  bool consume(const char* word) {
    const std::string w(word);
    if (text_.compare(pos_, w.size(), w) != 0) return false;
    for (std::size_t i = 0; i < w.size(); ++i) next();
    return true;
  }
  void expect(char c, const char* what) {
    skip_space();
    if (at_end()) fail(std::string("unexpected end of file, expected ") + what);
    if (peek() != c) fail("unexpected '" + std::string(1, peek()) + "', expected " + what);
    next();
  }

  JsonValue parse_value(int depth) {
    if (depth > kMaxDepth) fail("nested too deeply");
    skip_space();
    if (at_end()) fail("unexpected end of file, expected a value");
    JsonValue value;
    value.line = line_, value.column = column_;
    const char c = peek();
    if (c == '{') {
      value.kind = JsonValue::Kind::Object;
      next();
      skip_space();
      if (peek() == '}') return next(), value;
      for (;;) {
        skip_space();
        if (peek() != '"') {
          if (at_end()) fail("unexpected end of file, expected a quoted key");
          fail("unexpected '" + std::string(1, peek()) + "', expected a quoted key");
        }
        const int key_line = line_, key_column = column_;
        std::string key = parse_string();
        for (const auto& member : value.members)
          if (member.first == key) {
            line_ = key_line, column_ = key_column;
            fail("key \"" + key + "\" appears twice");
          }
        expect(':', "':'");
        JsonValue item = parse_value(depth + 1);
        value.members.emplace_back(std::move(key), std::move(item));
        skip_space();
        if (at_end()) fail("unexpected end of file, expected ',' or '}'");
        if (peek() == '}') return next(), value;
        expect(',', "',' or '}'");
      }
    }
    if (c == '[') {
      value.kind = JsonValue::Kind::Array;
      next();
      skip_space();
      if (peek() == ']') return next(), value;
      for (;;) {
        value.items.push_back(parse_value(depth + 1));
        skip_space();
        if (at_end()) fail("unexpected end of file, expected ',' or ']'");
        if (peek() == ']') return next(), value;
        expect(',', "',' or ']'");
      }
    }
    if (c == '"') {
      value.kind = JsonValue::Kind::String;
      value.text = parse_string();
      return value;
    }
    if (consume("true")) return value.kind = JsonValue::Kind::Boolean, value.boolean = true, value;
    if (consume("false")) return value.kind = JsonValue::Kind::Boolean, value;
    if (consume("null")) return value;
    value.kind = JsonValue::Kind::Number;
    if (consume("NaN")) return value.text = "NaN", value.number = std::numeric_limits<double>::quiet_NaN(), value;
    if (consume("Infinity")) return value.text = "Infinity", value.number = HUGE_VAL, value;
    if (consume("-Infinity")) return value.text = "-Infinity", value.number = -HUGE_VAL, value;
    if (c == '-' || (c >= '0' && c <= '9')) return parse_number(value);
    fail("unexpected '" + std::string(1, c) + "', expected a value");
  }

  static bool digit(char c) { return c >= '0' && c <= '9'; }

  // RFC 8259 number grammar; the value is converted with strtod (overflow
  // gives +-infinity, which the readers report as non-finite).
  JsonValue& parse_number(JsonValue& value) {
    const std::size_t start = pos_;
    if (peek() == '-') next();
    if (!digit(peek())) fail("invalid number (a digit must follow '-')");
    if (peek() == '0') {
      next();
      if (digit(peek())) fail("invalid number (leading zero)");
    } else {
      while (digit(peek())) next();
    }
    if (peek() == '.') {
      next();
      if (!digit(peek())) fail("invalid number (a digit must follow '.')");
      while (digit(peek())) next();
    }
    if (peek() == 'e' || peek() == 'E') {
      next();
      if (peek() == '+' || peek() == '-') next();
      if (!digit(peek())) fail("invalid number (a digit must follow the exponent)");
      while (digit(peek())) next();
    }
    value.text = text_.substr(start, pos_ - start);
    value.number = std::strtod(value.text.c_str(), nullptr);  // "C" locale: the CLI never calls setlocale
    return value;
  }

  static void append_utf8(std::string& out, unsigned code) {
    if (code < 0x80) {
      out += char(code);
    } else if (code < 0x800) {
      out += char(0xC0 | (code >> 6));
      out += char(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += char(0xE0 | (code >> 12));
      out += char(0x80 | ((code >> 6) & 0x3F));
      out += char(0x80 | (code & 0x3F));
    } else {
      out += char(0xF0 | (code >> 18));
      out += char(0x80 | ((code >> 12) & 0x3F));
      out += char(0x80 | ((code >> 6) & 0x3F));
      out += char(0x80 | (code & 0x3F));
    }
  }

  unsigned parse_hex4() {
    unsigned code = 0;
    for (int i = 0; i < 4; ++i) {
      if (at_end()) fail("unexpected end of file in a \\u escape");
      const char h = next();
      code <<= 4;
      if (h >= '0' && h <= '9') code |= unsigned(h - '0');
      else if (h >= 'a' && h <= 'f') code |= unsigned(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F') code |= unsigned(h - 'A' + 10);
      else fail("invalid \\u escape (expected 4 hex digits)");
    }
    return code;
  }

  std::string parse_string() {
    next();  // the opening quote
    std::string out;
    for (;;) {
      if (at_end()) fail("unexpected end of file in a string (missing closing '\"')");
      const int at_line = line_, at_column = column_;  // escape errors point at the backslash
      const char c = next();
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string (use \\n, \\t, ...)");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (at_end()) fail("unexpected end of file in a string escape");
      const char e = next();
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned code = parse_hex4();
          if (code >= 0xD800 && code < 0xDC00 && consume("\\u")) {  // a surrogate pair
            const unsigned low = parse_hex4();
            if (low >= 0xDC00 && low < 0xE000) code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
            else fail("invalid \\u escape (unpaired surrogate)");
          }
          if (code >= 0xD800 && code < 0xE000) fail("invalid \\u escape (unpaired surrogate)");
          append_utf8(out, code);
          break;
        }
        default:
          line_ = at_line, column_ = at_column;
          fail("invalid escape '\\" + std::string(1, e) + "' in a string");
      }
    }
  }

  std::string text_, source_;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1;
};

namespace json_detail {

[[noreturn]] inline void fail(const std::string& path, const JsonValue& at, const std::string& what) {
  throw InvalidInput(path + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": " + what);
}

inline const JsonValue& object_root(const std::string& path, const JsonValue& root, const char* what) {
  if (root.kind != JsonValue::Kind::Object)
    fail(path, root, std::string("expected a JSON object ") + what + ", got " + JsonValue::kind_name(root.kind));
  return root;
}

// A vertex index: a non-negative integer (1e2 and 100.0 count as integers).
// `what` names it in messages, e.g. "feature \"nose\"".
inline int vertex_index(const std::string& path, const JsonValue& value, const std::string& what) {
  if (value.kind != JsonValue::Kind::Number)
    fail(path, value, what + " must be a vertex index, got " + JsonValue::kind_name(value.kind));
  const double x = value.number;
  if (!std::isfinite(x) || x != std::floor(x))
    fail(path, value, what + " must be an integer vertex index, got " + value.text);
  if (x < 0) fail(path, value, what + " has a negative vertex index " + value.text);
  if (x > std::numeric_limits<int>::max())
    fail(path, value, what + " has vertex index " + value.text + ", which is too large");
  return static_cast<int>(x);
}

}  // namespace json_detail

// {"name": vertex_index, ...}: names with their vertex indices, in file order.
// Indices must be non-negative integers (1e2 and 100.0 count as integers);
// the range against a mesh is checked by the caller.
inline std::vector<std::pair<std::string, int>> read_feature_file(const std::string& path) {
  const JsonValue root = JsonParser::parse_file(path);
  json_detail::object_root(path, root, "{\"name\": vertex_index, ...}");
  std::vector<std::pair<std::string, int>> features;
  for (const auto& [name, value] : root.members)
    features.emplace_back(name, json_detail::vertex_index(path, value, "feature \"" + name + "\""));
  return features;
}

// {"name": [index_in_mesh_0, index_in_mesh_1, ...], ...} for a set of
// `meshes` meshes: one vertex index or null (the mesh lacks the feature) per
// mesh, in input order. Returns the names with their lists (null as -1), in
// file order; the ranges against the meshes are checked by the caller.
inline std::vector<std::pair<std::string, std::vector<int>>> read_set_feature_file(const std::string& path,
                                                                                   int meshes) {
  const JsonValue root = JsonParser::parse_file(path);
  json_detail::object_root(path, root, "{\"name\": [vertex_index or null per mesh], ...}");
  std::vector<std::pair<std::string, std::vector<int>>> features;
  for (const auto& [name, value] : root.members) {
    const std::string what = "feature \"" + name + "\"";
    if (value.kind != JsonValue::Kind::Array)
      json_detail::fail(path, value,
                        what + " must be a list of one vertex index (or null) per mesh, got " +
                            JsonValue::kind_name(value.kind));
    if (static_cast<int>(value.items.size()) != meshes)
      json_detail::fail(path, value,
                        what + " lists " + std::to_string(value.items.size()) + " vertices for " +
                            std::to_string(meshes) + " meshes (one per mesh, null where a mesh lacks it)");
    std::vector<int> vertices;
    for (std::size_t i = 0; i < value.items.size(); ++i) {
      const JsonValue& item = value.items[i];
      vertices.push_back(item.kind == JsonValue::Kind::Null
                             ? -1
                             : json_detail::vertex_index(path, item, what + " in mesh " + std::to_string(i)));
    }
    features.emplace_back(name, std::move(vertices));
  }
  return features;
}

// {"name": [x, y, z], ...}: names with their target directions, in file
// order. Values are returned as written (neither normalized nor checked for
// finiteness: the caller reports those with the feature's name).
inline std::vector<std::pair<std::string, Vec3>> read_target_file(const std::string& path) {
  const JsonValue root = JsonParser::parse_file(path);
  json_detail::object_root(path, root, "{\"name\": [x, y, z], ...}");
  std::vector<std::pair<std::string, Vec3>> targets;
  for (const auto& [name, value] : root.members) {
    if (value.kind != JsonValue::Kind::Array || value.items.size() != 3)
      json_detail::fail(path, value,
                        "target \"" + name + "\" must be an array of 3 numbers [x, y, z], got " +
                            (value.kind == JsonValue::Kind::Array
                                 ? "an array of " + std::to_string(value.items.size())
                                 : std::string(JsonValue::kind_name(value.kind))));
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      const JsonValue& c = value.items[k];
      if (c.kind != JsonValue::Kind::Number)
        json_detail::fail(path, c,
                          "target \"" + name + "\" must be an array of 3 numbers [x, y, z], got " +
                              JsonValue::kind_name(c.kind) + " at position " + std::to_string(k));
      p[k] = c.number;
    }
    targets.emplace_back(name, p);
  }
  return targets;
}

}  // namespace cmaps
