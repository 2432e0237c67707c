// A flat JSON object written by hand: the CLI's --json output is one small
// object, not worth a dependency.
#pragma once
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace cmaps {

class JsonObject {
 public:
  JsonObject& add(const std::string& key, const std::string& value) { return raw(key, quote(value)); }
  JsonObject& add(const std::string& key, const char* value) { return add(key, std::string(value)); }
  JsonObject& add(const std::string& key, bool value) { return raw(key, value ? "true" : "false"); }
  JsonObject& add(const std::string& key, int value) { return raw(key, std::to_string(value)); }
  JsonObject& add(const std::string& key, unsigned long long value) { return raw(key, std::to_string(value)); }
  JsonObject& add(const std::string& key, double value) { return raw(key, number(value)); }
  // An array of numbers, e.g. a point [x, y, z].
  JsonObject& add(const std::string& key, const std::vector<double>& values) { return raw(key, array(values)); }
  // A nested object.
  JsonObject& add(const std::string& key, const JsonObject& value) { return raw(key, value.str()); }
  template <class T>
  JsonObject& add(const std::string& key, const std::optional<T>& value) {
    return value ? add(key, *value) : null(key);
  }
  JsonObject& null(const std::string& key) { return raw(key, "null"); }
  // JSON text built by the caller (e.g. with array() below); null when absent.
  JsonObject& add_json(const std::string& key, const std::optional<std::string>& json) {
    return json ? raw(key, *json) : null(key);
  }

  // JSON arrays of numbers or strings.
  static std::string array(const std::vector<int>& values) {
    std::string out = "[";
    for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + std::to_string(values[i]);
    return out + "]";
  }
  static std::string array(const std::vector<double>& values) {
    std::string out = "[";
    for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + number(values[i]);
    return out + "]";
  }
  static std::string array(const std::vector<std::string>& values) {
    std::string out = "[";
    for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + quote(values[i]);
    return out + "]";
  }

  std::string str() const { return "{" + body_ + "}"; }

  // Shortest exact form; JSON has no NaN or infinity, so they become null.
  static std::string number(double value) {
    if (!std::isfinite(value)) return "null";
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, value).ptr;
    return std::string(text, end);
  }

  static std::string quote(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
      switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        default:
          if (c < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
            out += escaped;
          } else {
            out += char(c);  // UTF-8 passes through unchanged
          }
      }
    }
    return out + "\"";
  }

 private:
  JsonObject& raw(const std::string& key, const std::string& value) {
    if (!body_.empty()) body_ += ", ";
    body_ += quote(key) + ": " + value;
    return *this;
  }

  std::string body_;
};

}  // namespace cmaps
