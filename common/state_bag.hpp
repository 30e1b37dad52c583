#pragma once
// What a run needs to go on from a frame as if it had never stopped (`duet run --resume`): named
// arrays of doubles, written into the frame's file under /state (common/h5_writer.hpp). The
// driver puts its own counters and the particles' internal variables there, a solver what it
// carries from one step to the next. Integers and flags are stored as doubles (exact below 2^53).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/tensor.hpp"

namespace duet {

using StateBag = std::map<std::string, std::vector<double>>;

void put(StateBag& bag, const std::string& key, double value);
void put(StateBag& bag, const std::string& key, const std::vector<double>& values);
void put(StateBag& bag, const std::string& key, const std::vector<Vec2>& values);
template <typename Integer>
void put_integers(StateBag& bag, const std::string& key, const std::vector<Integer>& values) {
  bag[key].assign(values.begin(), values.end());
}

/// Fixed-size Eigen matrices (Mat2, Mat3), each flattened in Eigen's storage order.
template <typename Matrix>
void put_matrices(StateBag& bag, const std::string& key, const std::vector<Matrix>& values) {
  constexpr int size = Matrix::SizeAtCompileTime;
  std::vector<double>& v = bag[key];
  v.resize(size * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int k = 0; k < size; ++k) v[size * i + k] = values[i](k);
  }
}

/// The entry `key`; throws std::runtime_error naming it when the bag lacks it (a frame written by
/// another version, or by a method that keeps other state).
const std::vector<double>& entry(const StateBag& bag, const std::string& key);
[[noreturn]] void throw_bad_entry(const std::string& key, const std::string& what);
double scalar(const StateBag& bag, const std::string& key);
void get(const StateBag& bag, const std::string& key, std::vector<double>& out);
void get(const StateBag& bag, const std::string& key, std::vector<Vec2>& out);
template <typename Integer>
void get_integers(const StateBag& bag, const std::string& key, std::vector<Integer>& out) {
  const std::vector<double>& v = entry(bag, key);
  out.resize(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = static_cast<Integer>(v[i]);
}

/// 64-bit masks (contact and attachment bits), each as two exact 32-bit halves (low, high).
void put_bits(StateBag& bag, const std::string& key, const std::vector<std::uint64_t>& masks);
void get_bits(const StateBag& bag, const std::string& key, std::vector<std::uint64_t>& masks);

template <typename Matrix>
void get_matrices(const StateBag& bag, const std::string& key, std::vector<Matrix>& out) {
  constexpr int size = Matrix::SizeAtCompileTime;
  const std::vector<double>& v = entry(bag, key);
  if (v.size() % size != 0) throw_bad_entry(key, "is not a list of matrices");
  out.resize(v.size() / size);
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (int k = 0; k < size; ++k) out[i](k) = v[size * i + k];
  }
}

/// Lists of lists (Newton's residual history): lengths, then the values.
void put_lists(StateBag& bag, const std::string& key,
               const std::vector<std::vector<double>>& lists);
void get_lists(const StateBag& bag, const std::string& key,
               std::vector<std::vector<double>>& lists);

}  // namespace duet
