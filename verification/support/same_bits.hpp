#pragma once
// Bitwise equality of doubles and of arrays of plain values (signed zeros and NaN
// payloads included), for the tests of code that must reproduce another's bits.
#include <cstring>
#include <vector>

namespace pdmpm::test {

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace pdmpm::test
