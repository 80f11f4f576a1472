#pragma once
/// @file π and the degree, declared once for the library (std::numbers is C++20).

namespace mapfuse {

inline constexpr double kPi = 3.14159265358979323846;
/// rad per degree
inline constexpr double kDegree = kPi / 180.0;

}  // namespace mapfuse
