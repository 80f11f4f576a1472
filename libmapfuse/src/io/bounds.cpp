#include "mapfuse/io/bounds.hpp"

#include <cstdio>

namespace mapfuse::io::bounds {

std::string numberText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

std::string rangeText(double lo, double hi) {
  return "[" + numberText(lo) + ", " + numberText(hi) + "]";
}

}  // namespace mapfuse::io::bounds
