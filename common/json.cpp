#include "common/json.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
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

}  // namespace duet
