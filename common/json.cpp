#include "common/json.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace duet {

Json Json::array(const std::vector<double>& values) {
  Json j = Json::array();
  auto& a = std::get<Array>(j.value_);
  a.reserve(values.size());
  for (double v : values) a.emplace_back(v);
  return j;
}

Json& Json::operator[](std::string_view key) {
  if (is_null()) value_ = Object{};
  auto& members = std::get<Object>(value_);
  for (auto& [k, v] : members) {
    if (k == key) return v;
  }
  members.emplace_back(std::string(key), Json());
  return members.back().second;
}

const Json* Json::find(std::string_view key) const {
  if (!is_object()) return nullptr;
  for (const auto& [k, v] : members()) {
    if (k == key) return &v;
  }
  return nullptr;
}

void Json::push_back(Json value) {
  if (is_null()) value_ = Array{};
  std::get<Array>(value_).push_back(std::move(value));
}

std::string json_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 2);
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
          out += buffer;
        } else {
          out += c;
        }
    }
  }
  return out;
}

namespace {

void newline(std::string& out, int indent, int level) {
  if (indent <= 0) return;
  out += '\n';
  out.append(static_cast<std::size_t>(indent * level), ' ');
}

void write_number(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  if (v == std::floor(v) && std::abs(v) < 1e15) {
    out += std::to_string(static_cast<long long>(v));
    return;
  }
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);  // shortest round trip
  out.append(buffer, result.ptr);
}

}  // namespace

void Json::dump_to(std::string& out, int indent, int level) const {
  if (std::holds_alternative<std::monostate>(value_)) {
    out += "null";
  } else if (const bool* b = std::get_if<bool>(&value_)) {
    out += *b ? "true" : "false";
  } else if (const double* d = std::get_if<double>(&value_)) {
    write_number(out, *d);
  } else if (const std::string* s = std::get_if<std::string>(&value_)) {
    out += '"';
    out += json_escape(*s);
    out += '"';
  } else if (const Object* o = std::get_if<Object>(&value_)) {
    if (o->empty()) {
      out += "{}";
      return;
    }
    out += '{';
    for (std::size_t i = 0; i < o->size(); ++i) {
      if (i) out += ',';
      newline(out, indent, level + 1);
      out += '"';
      out += json_escape((*o)[i].first);
      out += indent > 0 ? "\": " : "\":";
      (*o)[i].second.dump_to(out, indent, level + 1);
    }
    newline(out, indent, level);
    out += '}';
  } else {
    const Array& a = std::get<Array>(value_);
    if (a.empty()) {
      out += "[]";
      return;
    }
    // Arrays of numbers stay on one line (time series).
    bool flat = true;
    for (const auto& e : a) flat = flat && (e.is_number() || e.is_null());
    out += '[';
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (i) out += flat ? ", " : ",";
      if (!flat) newline(out, indent, level + 1);
      a[i].dump_to(out, indent, level + 1);
    }
    if (!flat) newline(out, indent, level);
    out += ']';
  }
}

std::string Json::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  out += '\n';
  return out;
}

void write_json(const std::string& path, const Json& value) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  file << value.dump();
  if (!file) throw std::runtime_error("error writing " + path);
}

namespace {

class Parser {
 public:
  explicit Parser(std::string_view text) : text_(text) {}

  Json document() {
    Json value = parse_value(0);
    skip_space();
    if (at_ < text_.size()) fail("the end of the text");
    return value;
  }

 private:
  static constexpr int kMaxDepth = 256;

  [[noreturn]] void fail(const std::string& expected) const {
    throw std::runtime_error("JSON at offset " + std::to_string(at_) + ": expected " + expected);
  }

  void skip_space() {
    while (at_ < text_.size() &&
           (text_[at_] == ' ' || text_[at_] == '\n' || text_[at_] == '\r' || text_[at_] == '\t'))
      ++at_;
  }

  bool take(std::string_view word) {
    if (text_.substr(at_, word.size()) != word) return false;
    at_ += word.size();
    return true;
  }

  Json parse_value(int depth) {
    if (depth > kMaxDepth) fail("less nesting");
    skip_space();
    if (at_ >= text_.size()) fail("a value");
    const char c = text_[at_];
    if (c == '{') return parse_object(depth);
    if (c == '[') return parse_array(depth);
    if (c == '"') return Json(parse_string());
    if (take("true")) return Json(true);
    if (take("false")) return Json(false);
    if (take("null")) return Json();
    return Json(parse_number());
  }

  Json parse_object(int depth) {
    ++at_;  // {
    Json object = Json::object();
    skip_space();
    if (take("}")) return object;
    while (true) {
      skip_space();
      if (at_ >= text_.size() || text_[at_] != '"') fail("a member name in quotes");
      const std::string key = parse_string();
      skip_space();
      if (!take(":")) fail("':'");
      object[key] = parse_value(depth + 1);
      skip_space();
      if (take("}")) return object;
      if (!take(",")) fail("',' or '}'");
    }
  }

  Json parse_array(int depth) {
    ++at_;  // [
    Json array = Json::array();
    skip_space();
    if (take("]")) return array;
    while (true) {
      array.push_back(parse_value(depth + 1));
      skip_space();
      if (take("]")) return array;
      if (!take(",")) fail("',' or ']'");
    }
  }

  double parse_number() {
    const std::size_t start = at_;
    while (at_ < text_.size() && std::strchr("+-0123456789.eE", text_[at_]) && text_[at_] != '\0')
      ++at_;
    const std::string word(text_.substr(start, at_ - start));
    char* end = nullptr;
    const double value = word.empty() ? 0.0 : std::strtod(word.c_str(), &end);
    if (word.empty() || end != word.c_str() + word.size()) {
      at_ = start;
      fail("a value (object, array, string, number, true, false or null)");
    }
    return value;
  }

  static void append_utf8(std::string& out, unsigned code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  unsigned parse_hex4() {
    if (at_ + 4 > text_.size()) fail("four hex digits");
    unsigned code = 0;
    for (int k = 0; k < 4; ++k) {
      const char h = text_[at_++];
      code <<= 4;
      if (h >= '0' && h <= '9') {
        code |= static_cast<unsigned>(h - '0');
      } else if (h >= 'a' && h <= 'f') {
        code |= static_cast<unsigned>(h - 'a' + 10);
      } else if (h >= 'A' && h <= 'F') {
        code |= static_cast<unsigned>(h - 'A' + 10);
      } else {
        fail("a hex digit");
      }
    }
    return code;
  }

  std::string parse_string() {
    ++at_;  // opening quote
    std::string out;
    while (true) {
      if (at_ >= text_.size()) fail("a closing '\"'");
      const char c = text_[at_++];
      if (c == '"') return out;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (at_ >= text_.size()) fail("an escape");
      switch (const char e = text_[at_++]) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          unsigned code = parse_hex4();
          if (code >= 0xD800 && code < 0xDC00 && take("\\u")) {  // a surrogate pair
            const unsigned low = parse_hex4();
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          append_utf8(out, code);
          break;
        }
        default:
          --at_;
          fail("an escape (\\\" \\\\ / b f n r t u)");
      }
    }
  }

  std::string_view text_;
  std::size_t at_ = 0;
};

}  // namespace

Json parse_json(std::string_view text) {
  return Parser(text).document();
}

Json read_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return parse_json(text.str());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace duet
