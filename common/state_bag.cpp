#include "common/state_bag.hpp"

#include <stdexcept>

namespace duet {

void put(StateBag& bag, const std::string& key, double value) {
  bag[key] = {value};
}

void put(StateBag& bag, const std::string& key, const std::vector<double>& values) {
  bag[key] = values;
}

void put(StateBag& bag, const std::string& key, const std::vector<Vec2>& values) {
  std::vector<double>& v = bag[key];
  v.resize(2 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    v[2 * i] = values[i].x();
    v[2 * i + 1] = values[i].y();
  }
}

const std::vector<double>& entry(const StateBag& bag, const std::string& key) {
  const auto it = bag.find(key);
  if (it == bag.end()) throw std::runtime_error("the saved state has no '" + key + "'");
  return it->second;
}

void throw_bad_entry(const std::string& key, const std::string& what) {
  throw std::runtime_error("the saved state's '" + key + "' " + what);
}

double scalar(const StateBag& bag, const std::string& key) {
  const std::vector<double>& v = entry(bag, key);
  if (v.size() != 1) throw std::runtime_error("the saved state's '" + key + "' is not one number");
  return v[0];
}

void get(const StateBag& bag, const std::string& key, std::vector<double>& out) {
  out = entry(bag, key);
}

void get(const StateBag& bag, const std::string& key, std::vector<Vec2>& out) {
  const std::vector<double>& v = entry(bag, key);
  if (v.size() % 2 != 0) throw std::runtime_error("the saved state's '" + key + "' is not pairs");
  out.resize(v.size() / 2);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec2(v[2 * i], v[2 * i + 1]);
}

void put_bits(StateBag& bag, const std::string& key, const std::vector<std::uint64_t>& masks) {
  std::vector<double>& v = bag[key];
  v.resize(2 * masks.size());
  for (std::size_t i = 0; i < masks.size(); ++i) {
    v[2 * i] = static_cast<double>(masks[i] & 0xffffffffu);
    v[2 * i + 1] = static_cast<double>(masks[i] >> 32);
  }
}

void get_bits(const StateBag& bag, const std::string& key, std::vector<std::uint64_t>& masks) {
  const std::vector<double>& v = entry(bag, key);
  if (v.size() % 2 != 0) throw std::runtime_error("the saved state's '" + key + "' is not pairs");
  masks.resize(v.size() / 2);
  for (std::size_t i = 0; i < masks.size(); ++i) {
    masks[i] =
        static_cast<std::uint64_t>(v[2 * i + 1]) << 32 | static_cast<std::uint64_t>(v[2 * i]);
  }
}

void put_lists(StateBag& bag, const std::string& key,
               const std::vector<std::vector<double>>& lists) {
  std::vector<double> lengths, values;
  for (const std::vector<double>& list : lists) {
    lengths.push_back(static_cast<double>(list.size()));
    values.insert(values.end(), list.begin(), list.end());
  }
  bag[key + ".lengths"] = lengths;
  bag[key + ".values"] = values;
}

void get_lists(const StateBag& bag, const std::string& key,
               std::vector<std::vector<double>>& lists) {
  const std::vector<double>& lengths = entry(bag, key + ".lengths");
  const std::vector<double>& values = entry(bag, key + ".values");
  lists.clear();
  std::size_t at = 0;
  for (const double length : lengths) {
    const std::size_t n = static_cast<std::size_t>(length);
    if (at + n > values.size()) throw std::runtime_error("the saved state's '" + key + "' is cut");
    lists.emplace_back(values.begin() + static_cast<long>(at),
                       values.begin() + static_cast<long>(at + n));
    at += n;
  }
}

}  // namespace duet
