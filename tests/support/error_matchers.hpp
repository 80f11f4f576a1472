#pragma once
/// @file Catch matchers for mapfuse errors, so that a test states where a reader must fail:
///   CHECK_THROWS_MATCHES(io::readPly(p), ParseError, test::ParseErrorAt("vertex"));
#include <catch2/catch.hpp>
#include <string>

#include "mapfuse/core/error.hpp"

namespace mapfuse::test {

/// A ParseError naming `field`, and, when given, `file` and a problem containing `problem`.
class ParseErrorAt : public Catch::MatcherBase<ParseError> {
 public:
  explicit ParseErrorAt(std::string field, std::string file = "", std::string problem = "")
      : field_(std::move(field)), file_(std::move(file)), problem_(std::move(problem)) {}

  bool match(const ParseError& e) const override {
    return e.field() == field_ && (file_.empty() || e.file() == file_) &&
           e.problem().find(problem_) != std::string::npos;
  }
  std::string describe() const override {
    return "is a ParseError of field '" + field_ + "'" + (file_.empty() ? "" : " in " + file_) +
           (problem_.empty() ? "" : " whose problem contains \"" + problem_ + "\"");
  }

 private:
  std::string field_, file_, problem_;
};

}  // namespace mapfuse::test
